"""Fuzzing: hypothesis properties over grammars of hostile input.

* the path parser (:func:`raster.parse_path`, then flattening and boxes):
  only :class:`raster.errors.RasterError` escapes, no warning at all;
* the CSS parser and cascade: stylesheets never raise, selectors raise
  only :class:`raster.parser.css.CSSError`;
* whole documents from a grammar that paints (a sample is checked to draw
  pixels), each rendered in a child process under a memory and time
  budget (:mod:`_fuzz_child`): only a one-line RasterError or one-line
  RasterWarnings escape.

The suite runs a few dozen examples of each; ``-m fuzz`` runs the long
versions (thousands of examples, and atheris on the renderer when it is
installed: ``pip install atheris``), a run for the length of a CI job.
Findings become cases of ``tests/hostile/``.
"""

import os
import random
import subprocess
import sys
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import _fuzz_grammar as grammar
from _fuzz_child import render_in_child

from raster.errors import RasterError, RasterWarning

HERE = os.path.dirname(os.path.abspath(__file__))

_QUICK = settings(max_examples=60, deadline=None, database=None,
                  suppress_health_check=[HealthCheck.too_slow])
_LONG = settings(max_examples=3000, deadline=None, database=None,
                 suppress_health_check=[HealthCheck.too_slow])


# -- path data ------------------------------------------------------------------------

def check_path_data(d):
    from raster import bbox, flatten, limits, parse_path
    with warnings.catch_warnings():
        warnings.simplefilter('error')          # no warning of any kind escapes
        for strict in (True, False):
            try:
                p = parse_path(d, strict=strict)
            except RasterError as e:
                assert '\n' not in str(e)
                continue
            assert np.all(np.isfinite(p.points))
            try:
                with limits.applied(max_flatten_points=200_000):
                    pl = flatten(p, 0.25)
                    box = bbox(p)
            except RasterError as e:
                assert '\n' not in str(e)
                continue
            if len(pl.points):
                assert np.all(np.isfinite(pl.points))
                slack = 1e-9 * np.abs(np.asarray(box)).max()
                assert np.all(pl.points.min(0) >= np.asarray(box[:2]) - slack)
                assert np.all(pl.points.max(0) <= np.asarray(box[2:]) + slack)


@_QUICK
@given(st.randoms(use_true_random=False))
def test_path_parser_property(r):
    check_path_data(grammar.path_data(r))


@_QUICK
@given(st.text(alphabet='MmLlHhVvCcSsQqTtAaZz0123456789.,-+eE \n', max_size=80))
def test_path_parser_on_raw_text(d):
    check_path_data(d)


@pytest.mark.fuzz
@_LONG
@given(st.randoms(use_true_random=False))
def test_path_parser_long(r):
    check_path_data(grammar.path_data(r, r.randint(0, 60)))


# -- CSS ------------------------------------------------------------------------------

def check_stylesheet(text):
    from lxml import etree
    from raster.parser.css import CSSError, declared_styles, parse_selector_list, \
        parse_stylesheet
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        warnings.simplefilter('always', RasterWarning)
        rules = parse_stylesheet(text)
        for rule in rules[:5]:
            assert isinstance(rule.declarations, (list, tuple))
        root = etree.fromstring(
            '<svg xmlns="http://www.w3.org/2000/svg"><g class="c1" id="a"><rect class="c0 c2"/>'
            '<circle id="b"/></g><path class="c3"/></svg>')
        style = etree.SubElement(root, '{http://www.w3.org/2000/svg}style')
        style.text = text
        styles = declared_styles(root)
        assert set(styles) == set(root.iter())
        for sel in text.split('{')[:3]:
            try:
                parse_selector_list(sel)
            except CSSError as e:
                assert '\n' not in str(e)


@_QUICK
@given(st.randoms(use_true_random=False))
def test_css_parser_property(r):
    check_stylesheet(grammar.stylesheet(r))


@_QUICK
@given(st.text(alphabet='{}:;.#>~+[]()*="\'/!@ abcdefgrtl-,\\\n', max_size=120))
def test_css_parser_on_raw_text(text):
    check_stylesheet(text)


@pytest.mark.fuzz
@_LONG
@given(st.randoms(use_true_random=False))
def test_css_parser_long(r):
    check_stylesheet(grammar.stylesheet(r))


# -- documents ------------------------------------------------------------------------

def check_document(text, width=None):
    status, detail = render_in_child(text.encode('utf-8'), width)
    assert status != 'bug', '%s\n--- document:\n%s' % (detail, text)
    return status, detail


def test_generated_documents_paint():
    """The grammar is worth fuzzing with: most documents of a seeded
    sample render and draw pixels (not only errors and blank canvases)."""
    drawn = 0
    for seed in range(24):
        status, detail = check_document(grammar.seeded(grammar.document, seed))
        drawn += status == 'ok' and detail
    assert drawn >= 12, drawn


@settings(max_examples=40, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.randoms(use_true_random=False))
def test_document_property(r):
    check_document(grammar.document(r))


@pytest.mark.fuzz
@_LONG
@given(st.randoms(use_true_random=False), st.sampled_from([None, 64, 300]))
def test_document_long(r, width):
    check_document(grammar.document(r), width)


@pytest.mark.fuzz
def test_atheris_renderer():
    """libFuzzer (atheris) mutating documents of the grammar and raw bytes
    for a while, each input under libFuzzer's own time and memory budget
    (``-timeout``, ``-rss_limit_mb``): see ``atheris_render.py``."""
    try:
        import atheris  # noqa: F401
    except ImportError:
        pytest.fail('the long fuzz run needs atheris: pip install atheris')
    seconds = int(os.environ.get('RASTER_FUZZ_SECONDS', '300'))
    p = subprocess.run([sys.executable, os.path.join(HERE, 'atheris_render.py'),
                        '-max_total_time=%d' % seconds, '-timeout=20', '-rss_limit_mb=1024',
                        '-print_final_stats=1'],
                       capture_output=True, text=True, timeout=seconds + 600)
    assert p.returncode == 0, p.stderr[-4000:]


def test_seeded_samples_are_reproducible():
    a = grammar.seeded(grammar.document, 7)
    assert a == grammar.seeded(grammar.document, 7)
    assert a != grammar.seeded(grammar.document, 8)
    assert grammar.document(random.Random(7)) == a
