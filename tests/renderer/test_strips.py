"""Strips of a large output cut by estimated work (raster.renderer.tiles):
row_work puts a path's verbs and box pixels on the rows it covers;
balanced_spans covers every row once, within the row limit, in strips of
about equal work."""

import numpy as np
from hypothesis import given, settings, strategies as st

from raster.renderer import output_geometry
from raster.renderer.tiles import (BOX_PIXEL_WORK, PIXEL_WORK, balanced_spans, row_work,
                                   strip_rows, strip_spans)
from raster.svg import load_svg


def test_row_work_lies_where_the_paths_are():
    # a dense zigzag (200 line verbs) in rows 10-30 of a 100 x 100 output,
    # a square (5 verbs) in rows 60-80: the work of each is spread evenly
    # over its rows, on top of every pixel's share
    zig = 'M0 10 ' + ' '.join('L%d %d' % (i / 2, 10 + 20 * (i % 2)) for i in range(1, 200))
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
           '<path d="%s" fill="none" stroke="black"/>'
           '<rect x="20" y="60" width="20" height="20"/></svg>' % zig).encode()
    g = output_geometry(load_svg(doc))
    w = row_work(g.node, g.transform, g.width, g.height)
    base = PIXEL_WORK * 100
    assert w.shape == (100,)
    assert np.allclose(w[:10], base) and np.allclose(w[30:60], base) and np.allclose(w[80:], base)
    zig_box = 99 * 20                   # x from 0 to 99 ('%d' of i / 2)
    assert np.allclose(w[10:30], base + (200 + BOX_PIXEL_WORK * zig_box) / 20)
    assert np.allclose(w[60:80], w[60])
    assert w[10:30].sum() > 10 * (w[60:80].sum() - 20 * base)


def test_row_work_counts_groups_markers_and_nested_images():
    # a path under a translated group lies on the rows the group moves it
    # to; its markers' content and a nested SVG image add work on theirs
    base_doc = ('<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
                '<defs><marker id="m" markerWidth="6" markerHeight="6" refX="3" refY="3" '
                'markerUnits="userSpaceOnUse"><path d="M0 0 L6 0 L6 6 L0 6 Z M1 1 L5 1 L5 5 Z"/>'
                '</marker></defs><g transform="translate(0 40)">'
                '<path d="M10 4 L90 6" stroke="black" %s/></g>%s</svg>')
    image = ('<image x="0" y="80" width="100" height="10" href="data:image/svg+xml;utf8,'
             '%3Csvg xmlns=%22http://www.w3.org/2000/svg%22 width=%2210%22 height=%2210%22%3E'
             '%3Cpath d=%22M0 0 L10 0 L10 10 L0 10 Z%22/%3E%3C/svg%3E"/>')

    def work(markers, img):
        doc = base_doc % ('marker-start="url(#m)" marker-end="url(#m)"' if markers else '',
                          image if img else '')
        g = output_geometry(load_svg(doc.encode()))
        return row_work(g.node, g.transform, g.width, g.height)

    plain, marked, with_image = work(False, False), work(True, False), work(False, True)
    base = PIXEL_WORK * 100
    # the line spans y 44-46 once moved: rows 44 and 45
    assert np.allclose(plain[:44], base) and (plain[44:46] > base).all()
    assert np.allclose(plain[46:], base)
    # the markers' 6 px boxes about (10, 44) and (90, 46) reach rows 41-48
    assert (marked[41:49] > plain[41:49]).all()
    assert np.allclose(marked[:41], plain[:41]) and np.allclose(marked[49:], plain[49:])
    # the image's path covers rows 80-89
    assert (with_image[80:90] > plain[80:90]).all() and np.allclose(with_image[:80], plain[:80])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.0, 100.0), min_size=1, max_size=300), st.integers(1, 9),
       st.integers(1, 120))
def test_balanced_spans_cover_the_rows_within_the_limit(work, count, rows):
    w = np.asarray(work) + 0.01
    spans = balanced_spans(w, count, rows)
    assert spans[0][0] == 0 and spans[-1][1] == len(w)
    assert all(a < b for a, b in spans)
    assert all(b0 == a1 for (_, b0), (a1, _) in zip(spans, spans[1:]))
    assert all(b - a <= rows for a, b in spans)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.integers(2, 8))
def test_balanced_spans_share_the_work(seed, count):
    # each strip's work is within one row's work of the even share, or
    # the strip is a single row
    w = np.random.default_rng(seed).gamma(0.5, 10.0, 400) + 0.01
    spans = balanced_spans(w, count, 400)
    share = w.sum() / count
    for a, b in spans:
        assert w[a:b].sum() <= share + w[a:b].max() + 1e-9 or b - a == 1
    assert len(spans) <= count


def test_balanced_spans_of_even_work_are_strips_of_even_height():
    spans = balanced_spans(np.ones(1000), 4, 1000)
    assert spans == [(0, 250), (250, 500), (500, 750), (750, 1000)]
    # the limit cuts the strips further, into equal parts
    assert balanced_spans(np.ones(1000), 2, 300) == [(0, 250), (250, 500), (500, 750),
                                                     (750, 1000)]
    assert strip_spans(1000, strip_rows(1000, 24 * 1000 * 250)) == spans
