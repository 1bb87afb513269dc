"""raster.errors.log_warnings: another library's log records become one-line
RasterWarnings while raster's code runs, with a handler attached for the
block only, and none (nor :mod:`logging`) before the library is loaded."""

import logging
import os
import subprocess
import sys
import textwrap
import types
import warnings

import pytest

from raster.errors import RasterWarning, library_loaded, log_warnings

from _shared import SUITE_FONTS


@pytest.fixture
def lib(monkeypatch):
    """A made-up library name, not loaded until the test loads it."""
    name = 'raster_test_lib'
    monkeypatch.delitem(sys.modules, name, raising=False)
    yield name
    logging.getLogger(name).handlers.clear()


def _load(name, monkeypatch):
    monkeypatch.setitem(sys.modules, name, types.ModuleType(name))


def test_records_become_one_line_warnings_for_the_block_only(lib, monkeypatch):
    _load(lib, monkeypatch)
    logger = logging.getLogger(lib + '.tables')
    propagate = logging.getLogger(lib).propagate
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always')
        with log_warnings(lib):
            logger.warning('bad  checksum\nin %s', 'head')
            logger.info('below the level')
            logging.getLogger('another').warning('not ours')
        assert logging.getLogger(lib).handlers == []
        logger.warning('after the block')
    ours = [str(w.message) for w in caught if w.category is RasterWarning]
    assert ours == ['%s: bad checksum in head' % lib]
    assert logging.getLogger(lib).propagate is propagate


def test_a_library_loaded_inside_the_block_is_captured_once_it_says_so(lib, monkeypatch):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always')
        with log_warnings(lib):
            with log_warnings(lib):                 # nested blocks share one handler
                assert logging.getLogger(lib).handlers == []
                _load(lib, monkeypatch)
                library_loaded(lib)
                assert len(logging.getLogger(lib).handlers) == 1
            logging.getLogger(lib).warning('read later')
            assert len(logging.getLogger(lib).handlers) == 1
        assert logging.getLogger(lib).handlers == []
        library_loaded(lib)                         # outside any block: nothing
        assert logging.getLogger(lib).handlers == []
    assert [str(w.message) for w in caught if w.category is RasterWarning] == [
        '%s: read later' % lib]


def test_plain_text_imports_no_logging_and_colour_fonts_attach_the_handler():
    # text drawn by HarfBuzz alone never loads fontTools, so never logging;
    # a colour font loads fontTools inside the text converter's blocks,
    # which attach their handler then and remove it when they end
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="60" height="20">'
           '<text x="1" y="15" font-family="%s" font-size="12">%s</text></svg>')
    code = textwrap.dedent('''
        import sys, warnings
        warnings.simplefilter('ignore')
        import raster
        raster.render(%r, font_dirs=[%r])          # (fills the font scan cache)
        plain = 'logging' in sys.modules
        import logging
        added = []
        real = logging.Logger.addHandler
        def spy(self, h):
            added.append((self.name, type(h).__name__))
            return real(self, h)
        logging.Logger.addHandler = spy
        raster.render(%r, font_dirs=[%r])
        print(plain, 'fontTools' in sys.modules, ('fontTools', '_ToWarnings') in added,
              logging.getLogger('fontTools').handlers)
    ''')
    plain_doc = (svg % ('Noto Sans', 'Hi')).encode()
    colour_doc = (svg % ('Noto Color Emoji', '\U0001F600')).encode()
    run = [sys.executable, '-c']
    # the first process may scan the fonts (quiet_fonttools imports logging)
    subprocess.run(run + [code % (plain_doc, SUITE_FONTS, plain_doc, SUITE_FONTS)], check=True,
                   capture_output=True, cwd=os.path.dirname(os.path.abspath(__file__)))
    out = subprocess.run(run + [code % (plain_doc, SUITE_FONTS, colour_doc, SUITE_FONTS)],
                         check=True, capture_output=True, text=True,
                         cwd=os.path.dirname(os.path.abspath(__file__)))
    assert out.stdout.split() == ['False', 'True', 'True', '[]'], out.stdout + out.stderr
