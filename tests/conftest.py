"""Test-suite setup.

* The helper modules of tests/ (``_shared``, ``_geometry``) are importable
  from test files in any sub-folder (the suite mirrors the package layout:
  tests/geometry, tests/parser, ...).
* The ``conformance`` marker names the full resvg-suite run (slow; it
  starts its own worker processes).  Under pytest-xdist (``-n``) it is
  moved to the front of the run, so that the longest test overlaps the
  others instead of finishing alone at the end; serially it stays last.
* The ``fuzz`` marker names the long fuzz runs of tests/fuzz; they are
  deselected unless ``-m`` names them (``pytest -m fuzz tests/fuzz``).
* ``pillow_registry``: a fixture restoring Pillow's plugin tables.
* The persistent font-scan cache lives in a temporary folder for the whole
  run (``RASTER_CACHE_DIR``, set before anything scans fonts), never in
  the user's cache folder; worker processes inherit it.
"""

import atexit
import os
import shutil
import sys
import tempfile

import pytest

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

if not os.environ.get('RASTER_TEST_CACHE_SET'):
    _CACHE = tempfile.mkdtemp(prefix='raster-test-cache-')
    os.environ['RASTER_CACHE_DIR'] = _CACHE
    os.environ['RASTER_TEST_CACHE_SET'] = '1'
    atexit.register(shutil.rmtree, _CACHE, True)


def pytest_configure(config):
    config.addinivalue_line(
        'markers', 'conformance: the full resvg-suite conformance ratchet (slow, starts its own '
        'worker processes; deselect with -m "not conformance")')
    config.addinivalue_line(
        'markers', 'fuzz: the long fuzz runs (tests/fuzz), run only when selected: -m fuzz')


def pytest_collection_modifyitems(config, items):
    # the long fuzz runs are opt-in: left out unless -m names them
    if 'fuzz' not in (config.option.markexpr or ''):
        keep = [it for it in items if it.get_closest_marker('fuzz') is None]
        if len(keep) != len(items):
            config.hook.pytest_deselected(items=[it for it in items if it not in keep])
            items[:] = keep
    if getattr(config.option, 'numprocesses', None):
        # a stable sort: every xdist worker must see the same order
        items.sort(key=lambda item: item.get_closest_marker('conformance') is None)


@pytest.fixture
def pillow_registry():
    """Pillow's plugin tables (every plugin loaded first) restored after the
    test, so that a test registering raster's SVG plugin leaves no trace."""
    from PIL import Image
    Image.init()
    saved = (dict(Image.OPEN), list(Image.ID), dict(Image.SAVE), dict(Image.EXTENSION),
             dict(Image.MIME))
    yield
    for table, old in zip((Image.OPEN, Image.ID, Image.SAVE, Image.EXTENSION, Image.MIME), saved):
        if isinstance(table, list):
            table[:] = old
        else:
            table.clear()
            table.update(old)
