"""Packaging: the distribution name, one version source, the licences kept
and shipped, every package of raster/ listed, the console scripts wired
with --version."""

import importlib.metadata
import os
import subprocess
import sys
import sysconfig

import pytest

import raster

tomllib = pytest.importorskip('tomllib', reason='tomllib is in the standard library from 3.11')

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIST = 'raster-svg'


@pytest.fixture(scope='module')
def pyproject():
    with open(os.path.join(REPO, 'pyproject.toml'), 'rb') as f:
        return tomllib.load(f)


def test_distribution_name_and_one_version_source(pyproject):
    proj = pyproject['project']
    assert proj['name'] == DIST
    assert 'version' not in proj and 'version' in proj['dynamic']
    assert pyproject['tool']['setuptools']['dynamic']['version'] == {'attr': 'raster.__version__'}
    # the installed metadata was generated from raster.__version__
    assert importlib.metadata.version(DIST) == raster.__version__


def test_licences_are_kept_and_listed(pyproject):
    text = open(os.path.join(REPO, 'LICENSE')).read()
    assert text.startswith('MIT License') and 'the raster developers' in text
    ofl = 'raster/fonts/NotoSans-LICENSE-OFL.txt'
    assert set(pyproject['project']['license-files']) == {'LICENSE', ofl}
    body = open(os.path.join(REPO, ofl)).read()
    assert 'SIL OPEN FONT LICENSE Version 1.1' in body
    # the font's own copyright statement (name ID 0) is carried with the licence
    from fontTools.ttLib import TTFont
    font = TTFont(os.path.join(REPO, 'raster/fonts/NotoSans-Regular-ASCII.ttf'))
    assert font['name'].getDebugName(0) in body
    # fonts and licence texts are package data (shipped in the wheel)
    assert {'*.ttf', '*.txt'} <= set(pyproject['tool']['setuptools']['package-data']['raster.fonts'])


def test_every_package_is_listed(pyproject):
    listed = set(pyproject['tool']['setuptools']['packages'])
    found = set()
    for d, dirs, files in os.walk(os.path.join(REPO, 'raster')):
        dirs[:] = [x for x in dirs if x != '__pycache__']
        if '__init__.py' in files:
            found.add(os.path.relpath(d, REPO).replace(os.sep, '.'))
    assert found <= listed, 'packages missing from pyproject.toml: %s' % sorted(found - listed)


def test_console_scripts_print_the_version(pyproject):
    scripts = pyproject['project']['scripts']
    assert set(scripts) == {'rasterize', 'svg-flatten', 'svg-bbox', 'curve'}
    bindir = sysconfig.get_path('scripts')
    for name in scripts:
        p = subprocess.run([os.path.join(bindir, name), '--version'], capture_output=True,
                           text=True, timeout=60)
        assert p.returncode == 0 and p.stdout.strip() == '%s %s' % (name, raster.__version__)
    p = subprocess.run([sys.executable, '-m', 'raster_cli.conformance', '--version'],
                       capture_output=True, text=True, timeout=60)
    assert p.returncode == 0 and p.stdout.strip().endswith(' ' + raster.__version__)
