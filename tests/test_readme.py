"""The README's examples run: every ```python block, and the rasterize
command lines of "Output formats", in a scratch directory holding a copy of
examples/ (so they write nowhere else)."""

import os
import re
import shutil
import subprocess
import sysconfig

import pytest
from PIL import Image

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
README = open(os.path.join(REPO, 'README.md'), encoding='utf-8').read()
BLOCKS = re.findall(r'```python\n(.*?)```', README, re.S)


def section(title):
    m = re.search(r'^#+ %s\n(.*?)(?=^#)' % re.escape(title), README, re.S | re.M)
    assert m, 'README has no section %r' % title
    return m.group(1)


@pytest.fixture
def scratch(tmp_path, monkeypatch):
    shutil.copytree(os.path.join(REPO, 'examples'), tmp_path / 'examples')
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_there_are_python_examples():
    assert len(BLOCKS) >= 4


@pytest.mark.parametrize('index', range(len(BLOCKS)))
def test_python_block_runs(scratch, pillow_registry, index):
    exec(compile(BLOCKS[index], 'README.md block %d' % index, 'exec'), {})


def test_output_format_commands_run(scratch):
    lines = [ln.strip() for ln in section('Output formats').splitlines()
             if ln.startswith('    rasterize ')]
    assert len(lines) >= 5
    env = dict(os.environ, PATH=sysconfig.get_path('scripts') + os.pathsep + os.environ['PATH'])
    for ln in lines:
        p = subprocess.run(['bash', '-c', ln], cwd=scratch, env=env, capture_output=True,
                           text=True, timeout=120)
        assert p.returncode == 0, (ln, p.stderr)
    formats = {}
    for name in os.listdir(scratch):
        if name.startswith('badge'):
            formats[name] = Image.open(scratch / name).format
    assert set(formats.values()) == {'PNG', 'JPEG', 'WEBP', 'TIFF', 'BMP'}


def test_limit_commands_run(scratch):
    """The command lines of "Limits" run (the budget options exist)."""
    lines = [ln.strip() for ln in section('Limits').splitlines()
             if ln.startswith(('    rasterize ', '    svg-bbox '))]
    assert len(lines) >= 3
    env = dict(os.environ, PATH=sysconfig.get_path('scripts') + os.pathsep + os.environ['PATH'])
    for ln in lines:
        p = subprocess.run(['bash', '-c', ln], cwd=scratch, env=env, capture_output=True,
                           text=True, timeout=120)
        assert p.returncode == 0 and p.stderr == '', (ln, p.stderr)


def test_limits_table_matches_the_library():
    from raster.limits import DEFAULT, Limits
    table = section('Limits')
    for name in Limits.names():
        assert '| `%s` |' % name in table, name
    assert len(re.findall(r'^\| `max_', table, re.M)) == len(Limits.names())
    assert DEFAULT.max_elements == 100_000 and '| `max_elements` | 100,000 |' in table
