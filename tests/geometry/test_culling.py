"""Tests of raster.geometry.culling: a path cut down to what reaches a box
fills and strokes exactly the same pixels inside the box."""

import math

import numpy as np
import pytest
from hypothesis import example, given, settings, strategies as st

from raster.geometry.culling import cull_fill, cull_stroke
from raster.geometry.flattening import flatten
from raster.geometry.path import CLOSE, CUBIC, LINE, MOVE, QUAD, Path
from raster.geometry.pathdata import parse_path
from raster.geometry.pens import PathBuilder
from raster.geometry.stroking import StrokeStyle, stroke
from raster.geometry.transform import Affine
from raster.pixels.scan import coverage

W = H = 96


def random_path(rng, contours=4, spread=(-40, 140)):
    """Contours of random lines, quadratics and cubics over and around a
    96 x 96 frame (some closed, some lone moves or dots)."""
    b = PathBuilder()
    lo, hi = spread
    for _ in range(int(rng.integers(1, contours + 1))):
        b.moveTo(rng.uniform(lo, hi, 2))
        r = rng.random()
        if r < 0.05:
            continue                                     # a lone move
        if r < 0.1:
            b.closePath()                                # a dot
            continue
        for _ in range(int(rng.integers(1, 12))):
            v = int(rng.integers(1, 4))
            if v == 1:
                b.lineTo(rng.uniform(lo, hi, 2))
            elif v == 2:
                b.qCurveTo(rng.uniform(lo, hi, 2), rng.uniform(lo, hi, 2))
            else:
                b.curveTo(rng.uniform(lo, hi, 2), rng.uniform(lo, hi, 2),
                          rng.uniform(lo, hi, 2))
        if rng.random() < 0.5:
            b.closePath()
    return b.path()


def random_transform(rng):
    a = rng.uniform(0, 2 * math.pi)
    s = rng.uniform(0.6, 1.4)
    return (Affine.translate(48, 48) @ Affine.rotate(math.degrees(a)) @ Affine.scale(s)
            @ Affine.translate(-50, -50))


def random_box(rng):
    x0, x1 = sorted(rng.integers(0, W + 1, 2).tolist())
    y0, y1 = sorted(rng.integers(0, H + 1, 2).tolist())
    if rng.random() < 0.5:
        x0, x1 = 0, W                       # a strip
    return x0, y0, max(x1, x0 + 1), max(y1, y0 + 1)


def window(edges, box, rule):
    """The coverage of ``box`` (its own pixels) from frame edges."""
    x0, y0, x1, y1 = box
    e = edges - np.array((x0, y0), np.float64)
    m = coverage(e, x1 - x0, y1 - y0, rule) if len(e) else None
    return np.zeros((y1 - y0, x1 - x0), np.float32) if m is None else m.full(x1 - x0, y1 - y0)


def fill_window(path, t, box, rule):
    return window(flatten(path, 0.1, transform=t, straddle=True).edges(close_all=True), box, rule)


def stroke_window(path, style, t, box):
    out = stroke(path, style, transform=t, tolerance=0.1, straddle=True)
    return window(flatten(out, 0.1).edges(close_all=True), box, 'nonzero')


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from(['nonzero', 'evenodd']))
def test_a_culled_fill_covers_the_box_as_the_whole_path(seed, rule):
    rng = np.random.default_rng(seed)
    p, t, box = random_path(rng), random_transform(rng), random_box(rng)
    c = cull_fill(p, t, box, margin=1.0)
    np.testing.assert_allclose(fill_window(c, t, box, rule), fill_window(p, t, box, rule),
                               rtol=0, atol=1e-6)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from(['butt', 'round', 'square']),
       st.sampled_from(['miter', 'round', 'bevel']))
def test_a_culled_stroke_covers_the_box_as_the_whole_path(seed, cap, join):
    rng = np.random.default_rng(seed)
    p, t, box = random_path(rng), random_transform(rng), random_box(rng)
    style = StrokeStyle(width=float(rng.uniform(0.5, 8)), cap=cap, join=join, miterlimit=4)
    k = max(style.miterlimit if join == 'miter' else 1.0, math.sqrt(2) if cap == 'square' else 1)
    reach = style.width / 2 * k * t.max_scale() + 1.0
    c = cull_stroke(p, t, box, reach=reach)
    np.testing.assert_allclose(stroke_window(c, style, t, box), stroke_window(p, style, t, box),
                               rtol=0, atol=1e-6)


def test_many_segments_far_from_a_strip_are_left_out():
    # a circle of radius 40 drawn in a strip of 8 rows through its top
    rng = np.random.default_rng(3)
    a = np.sort(rng.uniform(0, 2 * np.pi, 400))
    p = Path.polygon(np.c_[48 + 40 * np.cos(a), 48 + 40 * np.sin(a)])
    box = (0, 8, W, 16)
    f = cull_fill(p, None, box, margin=1.0)
    s = cull_stroke(p, None, box, reach=3.0)
    assert len(f.verbs) < len(p.verbs) // 3 and len(s.verbs) < len(p.verbs) // 3
    np.testing.assert_allclose(fill_window(f, None, box, 'nonzero'),
                               fill_window(p, None, box, 'nonzero'), atol=1e-6)
    style = StrokeStyle(width=4.0)
    np.testing.assert_allclose(stroke_window(s, style, None, box),
                               stroke_window(p, style, None, box), atol=1e-6)
    # the fill's far runs became lines, one per side
    assert set(f.verbs.tolist()) <= {MOVE, LINE, CLOSE}


def test_the_kept_segments_are_the_paths_own():
    p = parse_path('M 0 0 C 20 -10 40 10 60 0 Q 80 -10 90 50 L 90 100 L 90 150 '
                   'C 95 180 60 220 10 200 L 5 150 L 0 100 Z')
    box = (0, -20, 100, 20)
    f = cull_fill(p, None, box, margin=0.5)
    s = cull_stroke(p, None, box, reach=0.5)
    # a fill keeps two segments each side of the kept ones (the straddled
    # flattening reads its neighbours): only the far cubic becomes a line
    assert f.to_svg() == ('M 0 0 C 20 -10 40 10 60 0 Q 80 -10 90 50 L 90 100 L 90 150 '
                          'L 10 200 L 5 150 L 0 100 Z')
    # the closing line reaches the box: it leads the piece across the start
    assert s.to_svg() == 'M 0 100 L 0 0 C 20 -10 40 10 60 0 Q 80 -10 90 50'


def test_a_path_near_the_box_is_returned_as_it_is():
    p = parse_path('M 10 10 Q 50 -5 90 10 L 90 90 Z')
    assert cull_fill(p, None, (0, 0, 100, 100)) is p
    assert cull_stroke(p, None, (0, 0, 100, 100)) is p
    # every segment meets the box: nothing changes
    assert cull_fill(p, None, (40, 40, 60, 60), margin=50) is p
    assert cull_stroke(p, None, (0, 0, 95, 50), reach=0) is p


def test_contours_without_segments_stay_and_far_ones_go():
    p = parse_path('M 5 5 Z M 500 500 L 600 600 M 7 7 M 8 8 L 9 9')
    s = cull_stroke(p, None, (0, 0, 20, 20), reach=2)
    assert s.to_svg() == 'M 5 5 Z M 7 7 M 8 8 L 9 9'
    far = parse_path('M 500 500 L 600 600 Q 700 500 800 800 Z')
    assert len(cull_stroke(far, None, (0, 0, 20, 20), reach=2).verbs) == 0
    f = cull_fill(far, None, (0, 0, 20, 20))
    assert f.to_svg() == 'M 500 500 L 800 800 Z'


def test_a_kept_whole_closed_contour_keeps_its_close():
    p = parse_path('M 0 0 L 10 0 L 10 10 Z M 200 0 L 300 0 L 300 10 Z')
    s = cull_stroke(p, None, (0, 0, 20, 20), reach=1)
    assert s.to_svg() == 'M 0 0 L 10 0 L 10 10 Z'


def test_infinite_sides_cut_only_above():
    # what a window drawn top to bottom keeps for the windows below it
    top = [(10 * i, -20 * min(i, 10 - i)) for i in range(11)]
    p = Path.polygon(top + [(100, 300), (0, 300)])
    s = cull_stroke(p, None, (-math.inf, 10, math.inf, math.inf), reach=1)
    assert s.to_svg() == 'M 100 0 L 100 300 L 0 300 L 0 0'
    f = cull_fill(p, None, (-math.inf, 10, math.inf, math.inf), margin=1)
    assert f.to_svg() == 'M 0 0 L 10 -20 L 20 -40 L 80 -40 L 90 -20 L 100 0 L 100 300 L 0 300 Z'


@pytest.mark.parametrize('verb', [LINE, QUAD, CUBIC])
def test_a_segment_is_kept_by_its_control_points(verb):
    # the curve's control points come near the box though its ends do not
    pts = {LINE: [[0, 0], [100, 0]], QUAD: [[0, 0], [50, 60], [100, 0]],
           CUBIC: [[0, 0], [30, 60], [70, 60], [100, 0]]}[verb]
    p = Path.from_arrays([MOVE, verb], pts)
    box = (0, 20, 100, 40)
    kept = verb != LINE
    assert (cull_stroke(p, None, box, reach=1) is p) == kept
    assert (len(cull_stroke(p, None, box, reach=1).verbs) == 0) == (not kept)


def test_an_open_contour_ending_at_its_start_stays_whole():
    # the stroker seals such a contour into a ring (no butt caps meeting at
    # the seam, whose end chords meet at an angle): cut into two open
    # pieces its stroke at the seam would differ, so it is never cut
    p = parse_path('M 0 0 C 0 -12 14 -12 20 -4 L 100 -4 L 100 100 L -20 100 L -20 10 '
                   'C -12 18 0 12 0 0')
    box = (-10, -10, 10, 10)
    assert cull_stroke(p, None, box, reach=1) is p
    style = StrokeStyle(width=6.0, cap='butt')
    two = parse_path('M 0 0 C 0 -12 14 -12 20 -4 M -20 10 C -12 18 0 12 0 0')
    assert np.abs(stroke_window(two, style, None, box)
                  - stroke_window(p, style, None, box)).max() > 0.005


# -- dashes cut by the stroker (stroke(..., window=)) --------------------------------

def dashed_window(path, style, t, box, window=None):
    out = stroke(path, style, transform=t, tolerance=0.1, straddle=True, window=window)
    return out, window_of(out, box)


def window_of(outline, box):
    return window(flatten(outline, 0.1).edges(close_all=True), box, 'nonzero')


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from(['butt', 'round', 'square']),
       st.sampled_from(['miter', 'round', 'bevel']))
@example(2122490, 'round', 'miter')        # a zero-length subpath by the window's edge
def test_dashes_far_from_the_window_are_left_out_and_the_window_is_unchanged(seed, cap, join):
    rng = np.random.default_rng(seed)
    p, t, box = random_path(rng, spread=(-200, 300)), random_transform(rng), random_box(rng)
    dash = rng.uniform(0.5, 12, int(rng.integers(1, 4)) * 2).tolist()
    style = StrokeStyle(width=float(rng.uniform(0.5, 8)), cap=cap, join=join, miterlimit=4,
                        dash=dash, dash_offset=float(rng.uniform(0, 10)))
    whole, a = dashed_window(p, style, t, box)
    cut, b = dashed_window(p, style, t, box, window=box)
    np.testing.assert_allclose(b, a, rtol=0, atol=1e-6)
    assert int((cut.verbs == MOVE).sum()) <= int((whole.verbs == MOVE).sum())


@pytest.mark.parametrize('cap', ['round', 'square'])
@pytest.mark.parametrize('offset', [0.0, 0.5, 6.5])
@pytest.mark.parametrize('d', ['M 10 -3 Z M -40 15 L 60 15',
                               'M -40 15 Q 10 25 60 15 Z M 10 -3 Z',
                               'M 10 -3 L 10 -3 M -40 15 L 60 15'])
def test_a_dashed_zero_length_subpath_draws_no_dot_cut_or_not(cap, offset, d):
    # "M x y Z" stroked with round or square caps draws a dot, but dashed
    # it has no length to dash and draws nothing (Skia's contour measure
    # skips it; resvg draws no dot), wherever it is in the path and
    # whatever the dash offset (a dash starting before 0 made a dot of it);
    # the window cut of the dashes agrees (the dot would reach 1 px into the box)
    p = parse_path(d)
    box = (0, 0, 20, 20)
    plain = window_of(stroke(p, StrokeStyle(width=8.0, cap=cap), tolerance=0.1), box)
    assert plain[0, 8:12].min() > 0.5
    style = StrokeStyle(width=8.0, cap=cap, dash=[5.0, 2.0], dash_offset=offset)
    whole, a = dashed_window(p, style, None, box)
    cut, b = dashed_window(p, style, None, box, window=box)
    assert not a[:2, 4:16].any() and a[12:18].any()     # no dot; the other dashes
    np.testing.assert_allclose(b, a, rtol=0, atol=1e-6)


def test_a_long_dashed_line_through_a_small_window_keeps_its_few_dashes():
    # a line 10^6 px long with dashes of 10 + gaps of 10, seen through
    # 64 x 48: about 50,000 dashes, of which the window's reach holds 5
    p = Path.polygon([(-5e5, 20.0), (5e5, 20.0)], closed=False)
    style = StrokeStyle(width=6.0, dash=[10.0, 10.0])
    box = (0, 0, 64, 48)
    whole, a = dashed_window(p, style, None, box)
    cut, b = dashed_window(p, style, None, box, window=box)
    assert int((whole.verbs == MOVE).sum()) == 50_000
    assert int((cut.verbs == MOVE).sum()) <= 5
    np.testing.assert_array_equal(a, b)
    assert a.max() == 1.0
    # infinite sides: everything below y = 40 (beyond the reach of a miter
    # join, 4 x 3 px, from y = 20), then everything below y = 30
    assert len(stroke(p, style, window=(-np.inf, 40.0, np.inf, np.inf)).verbs) == 0
    assert len(stroke(p, style, window=(-np.inf, 30.0, np.inf, np.inf)).verbs) == 250_000


def test_stroke_many_cuts_dashes_per_path_but_not_a_shared_outline():
    from raster.geometry.stroking import stroke_many
    line = Path.polygon([(0.0, 0.0), (1000.0, 0.0)], closed=False)
    other = Path.polygon([(0.0, 5.0), (1000.0, 5.0)], closed=False)
    style = StrokeStyle(width=2.0, dash=[4.0, 4.0])
    box = (0, 0, 50, 50)
    ts = [Affine.translate(0, 10), Affine.translate(0, 20), Affine.translate(0, 30)]
    # line twice (one shared outline, two transforms) and other once
    outs = stroke_many([line, line, other], style, transforms=ts, window=box)
    moves = [int((o.verbs == MOVE).sum()) for o in outs]
    assert moves[0] == moves[1] == 125           # shared: every dash
    assert moves[2] <= 8                         # alone: those within reach of x < 50
    for o, t, pth in zip(outs, ts, [line, line, other]):
        np.testing.assert_array_equal(window_of(o, box),
                                      window_of(stroke(pth, style, transform=t), box))


@pytest.mark.parametrize('bad', [(0, 0, 10), (0, 0, 10, float('nan')), (10, 0, 0, 10),
                                 (0, 10, 10, 0), 'abcd', 5, (0, 0, 'x', 1)])
def test_a_bad_window_is_a_stroke_error(bad):
    from raster.geometry.stroking import StrokeError, stroke_many
    p = Path.polygon([(0.0, 0.0), (10.0, 0.0)], closed=False)
    with pytest.raises(StrokeError, match='window'):
        stroke(p, StrokeStyle(width=1.0, dash=[1.0, 1.0]), window=bad)
    with pytest.raises(StrokeError, match='window'):
        stroke(Path.empty(), StrokeStyle(width=1.0), window=bad)
    with pytest.raises(StrokeError, match='window'):
        stroke_many([p], StrokeStyle(width=1.0), window=bad)


def test_dashes_beyond_the_budget_are_drawn_where_the_window_sees_them():
    # 100,000 dashes on a line 2e5 long: over a budget of 50,000 points the
    # whole stroke is refused, but a window makes only the periods near it
    from raster import limits
    from raster.errors import LimitError
    p = Path.polygon([(-1e5, 20.0), (1e5, 20.0)], closed=False)
    style = StrokeStyle(width=3.0, dash=[1.0, 1.0], dash_offset=0.25)
    box = (0, 0, 64, 48)
    with limits.applied(max_flatten_points=50_000):
        with pytest.raises(LimitError, match='dashes'):
            stroke(p, style)
        cut = stroke(p, style, window=box)
    assert 30 <= int((cut.verbs == MOVE).sum()) <= 40
    _, ref = dashed_window(p, style, None, box)
    np.testing.assert_array_equal(window_of(cut, box), ref)


@pytest.mark.parametrize('box', [(0, 0, 30, 30), (80, 80, 120, 120), (-10, 40, 20, 60)])
def test_a_closed_contour_keeps_its_dash_through_the_start(box):
    # a square of side 100 from (10, 10) with dashes of 30 and gaps of 7:
    # the last dash runs on through the start point into the first
    p = Path.polygon([(10.0, 10.0), (110.0, 10.0), (110.0, 110.0), (10.0, 110.0)])
    style = StrokeStyle(width=4.0, dash=[30.0, 7.0], dash_offset=11.0)
    _, ref = dashed_window(p, style, None, box)
    cut, got = dashed_window(p, style, None, box, window=box)
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-6)
    assert ref.max() > 0.5
