"""Tests of raster.pixels.scan: exact-area coverage masks."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import raster.pixels.scan as scan
from raster.errors import CanvasError, LimitError, PathError, RasterError
from raster.pixels.scan import Mask, coverage, path_coverage
from _geometry import kappa_circle as circle_path


# -- helpers ------------------------------------------------------------------

def poly_edges(*polys):
    """Closed polygons ((N, 2) vertex arrays) -> (E, 2, 2) edges."""
    out = []
    for p in polys:
        p = np.asarray(p, float)
        out.append(np.stack([p, np.roll(p, -1, 0)], 1))
    return np.concatenate(out)


def shoelace(p):
    p = np.asarray(p, float)
    x, y = p[:, 0], p[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def reference(edges, w, h, rule, n=64):
    """Point sampling on an n x n grid per pixel (sample centres), winding by
    signed crossings of each sample row (half-open in y, crossing counts for
    samples strictly right of it)."""
    s = (np.arange(n) + 0.5) / n
    ys = (np.arange(h)[:, None] + s[None, :]).ravel()
    xs = (np.arange(w)[:, None] + s[None, :]).ravel()
    e = np.asarray(edges, float)
    x0, y0, x1, y1 = e[:, 0, 0], e[:, 0, 1], e[:, 1, 0], e[:, 1, 1]
    hit = ((np.minimum(y0, y1)[:, None] <= ys[None, :])
           & (ys[None, :] < np.maximum(y0, y1)[:, None]))
    ei, ri = np.nonzero(hit)
    xc = x0[ei] + (ys[ri] - y0[ei]) * (x1[ei] - x0[ei]) / (y1[ei] - y0[ei])
    col = np.searchsorted(xs, xc, side='right')
    sign = np.where(y1[ei] > y0[ei], 1, -1)
    acc = np.bincount(ri * (len(xs) + 1) + col, weights=sign,
                      minlength=len(ys) * (len(xs) + 1)).reshape(len(ys), -1)
    wind = np.rint(np.cumsum(acc, axis=1)[:, :len(xs)]).astype(int)
    f = (wind != 0) if rule == 'nonzero' else (wind & 1).astype(bool)
    return f.reshape(h, n, w, n).mean((1, 3))


def full(edges, w, h, **kw):
    m = coverage(edges, w, h, **kw)
    return np.zeros((h, w), np.float32) if m is None else m.full(w, h)


def pentagram(cx, cy, r):
    a = np.pi / 2 + np.arange(5) * 4 * np.pi / 5
    return np.c_[cx + r * np.cos(a), cy - r * np.sin(a)]


def circle(cx, cy, r, n=256):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[cx + r * np.cos(a), cy + r * np.sin(a)]


def random_convex_polygon(rng, n, cx, cy, r):
    """Convex polygon: points on a circle at sorted random angles."""
    a = np.sort(rng.uniform(0, 2 * np.pi, n))
    return np.c_[cx + r * np.cos(a), cy + r * np.sin(a)]


def random_star_polygon(rng, n, cx, cy, rmin, rmax):
    """Simple polygon, star-shaped around (cx, cy): one vertex at a random
    angle in each of n equal sectors (n >= 4), so consecutive angles differ
    by less than pi."""
    a = 2 * np.pi * (np.arange(n) + rng.uniform(0, 1, n)) / n
    r = rng.uniform(rmin, rmax, n)
    return np.c_[cx + r * np.cos(a), cy + r * np.sin(a)]


STAR = poly_edges(pentagram(20.3, 21.1, 17.7))
CIRCLES = poly_edges(circle(15.2, 20.1, 10.3), circle(24.7, 19.6, 9.1))


# -- exact answers ------------------------------------------------------------

def test_pixel_aligned_rectangle_is_exactly_binary():
    rect = poly_edges([[3, 2], [9, 2], [9, 7], [3, 7]])
    m = coverage(rect, 12, 10)
    assert m.box == (3, 2, 9, 7)
    assert m.data.dtype == np.float32
    assert np.array_equal(m.data, np.ones((5, 6), np.float32))
    f = m.full(12, 10)
    assert f.sum() == 30.0 and set(np.unique(f)) == {0.0, 1.0}


def test_vertical_edge_at_half_pixel_gives_half_coverage():
    rect = poly_edges([[10.5, 0], [30, 0], [30, 20], [10.5, 20]])
    f = full(rect, 20, 20)
    assert np.all(f[:, 10] == 0.5)
    assert np.all(f[:, 11:] == 1.0) and np.all(f[:, :10] == 0.0)


def test_unit_square_offset_by_half_splits_into_quarters():
    sq = poly_edges([[1.5, 1.5], [2.5, 1.5], [2.5, 2.5], [1.5, 2.5]])
    m = coverage(sq, 4, 4)
    assert m.box == (1, 1, 3, 3)
    assert np.array_equal(m.data, np.full((2, 2), 0.25, np.float32))


def test_right_triangle_diagonal_pixels_are_half():
    # triangle (0,0) (6,0) (0,6): the hypotenuse x + y = 6 halves the
    # pixels it passes through (diagonals of those pixels)
    tri = poly_edges([[0, 0], [6, 0], [0, 6]])
    f = full(tri, 8, 8)
    i, j = np.indices((8, 8))
    expect = np.where(i + j < 5, 1.0, np.where(i + j == 5, 0.5, 0.0))
    assert np.allclose(f, expect, atol=1e-6)


@pytest.mark.parametrize('seed', range(6))
def test_total_coverage_equals_shoelace_area(seed):
    rng = np.random.default_rng(seed)
    p = random_star_polygon(rng, 40, 32.3, 30.7, 3.0, 28.0)
    m = coverage(poly_edges(p), 64, 64)
    assert abs(float(m.data.astype(np.float64).sum()) - shoelace(p)) < 1e-4 * shoelace(p)


def test_circle_area_converges_to_pi_r_squared():
    # a regular 4096-gon of radius 20 has area (n/2) r^2 sin(2 pi / n)
    n, r = 4096, 20.0
    m = coverage(poly_edges(circle(25.25, 24.75, r, n)), 50, 50)
    expect = 0.5 * n * r * r * np.sin(2 * np.pi / n)
    assert abs(float(m.data.sum(dtype=np.float64)) - expect) < 1e-3


# -- crossings and overlaps against a supersampled reference ------------------

@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
@pytest.mark.parametrize('name', ['pentagram', 'two_circles'])
def test_self_intersecting_and_overlapping_match_supersampling(name, rule):
    edges = STAR if name == 'pentagram' else CIRCLES
    got = full(edges, 40, 40, fill_rule=rule)
    ref = reference(edges, 40, 40, rule)
    assert np.abs(got - ref).max() <= 0.02
    assert got.min() >= 0 and got.max() <= 1


def test_fill_rules_as_enum_or_keyword():
    from raster.geometry.rules import FillRule
    for rule in FillRule:
        a = coverage(STAR, 40, 40, fill_rule=rule)
        b = coverage(STAR, 40, 40, fill_rule=rule.value)
        assert a.box == b.box and np.array_equal(a.data, b.data)
    m = scan.coverage_many([STAR, STAR], 40, 40, fill_rules=[FillRule.EVENODD, 'nonzero'])
    assert np.array_equal(m[0].data, coverage(STAR, 40, 40, fill_rule='evenodd').data)
    with pytest.raises(PathError, match="fill_rule must be 'nonzero' or 'evenodd'"):
        coverage(STAR, 40, 40, fill_rule='odd')
    with pytest.raises(PathError):
        coverage(STAR, 40, 40, fill_rule=['nonzero'])


def test_pentagram_area_is_exact():
    # the {5/2} star's outline is a 10-gon alternating between the
    # circumradius r and the inner radius ri: area 5 r ri sin(36 deg)
    r = 17.7
    ri = r * np.cos(np.radians(72)) / np.cos(np.radians(36))
    nz = full(STAR, 40, 40).sum(dtype=np.float64)
    assert abs(nz - 5 * r * ri * np.sin(np.radians(36))) < 1e-4


def rect_overlap(a, b):
    """Area of the intersection of axis-aligned boxes (x0, y0, x1, y1),
    broadcasting."""
    w = np.clip(np.minimum(a[2], b[2]) - np.maximum(a[0], b[0]), 0, None)
    h = np.clip(np.minimum(a[3], b[3]) - np.maximum(a[1], b[1]), 0, None)
    return w * h


def rect_poly(r):
    x0, y0, x1, y1 = r
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def exact_two_rects(r1, r2, w, h):
    """Per-pixel union (nonzero) and symmetric difference (evenodd) areas."""
    j, i = np.meshgrid(np.arange(w), np.arange(h))
    pix = (j, i, j + 1, i + 1)
    inter = (max(r1[0], r2[0]), max(r1[1], r2[1]), min(r1[2], r2[2]), min(r1[3], r2[3]))
    a, b = rect_overlap(r1, pix), rect_overlap(r2, pix)
    both = rect_overlap(inter, pix) if inter[0] < inter[2] and inter[1] < inter[3] else 0 * a
    return a + b - both, a + b - 2 * both


@settings(max_examples=100, deadline=None)
@given(st.lists(st.floats(0, 20), min_size=8, max_size=8), st.booleans())
def test_property_overlapping_rectangles_exact(v, reverse):
    r1 = (min(v[0], v[1]), min(v[2], v[3]), max(v[0], v[1]), max(v[2], v[3]))
    r2 = (min(v[4], v[5]), min(v[6], v[7]), max(v[4], v[5]), max(v[6], v[7]))
    p2 = rect_poly(r2)[::-1] if reverse else rect_poly(r2)
    e = poly_edges(rect_poly(r1), p2)
    union, xor = exact_two_rects(r1, r2, 21, 21)
    if not reverse:       # same orientation: nonzero is the union
        assert np.abs(full(e, 21, 21) - union).max() < 1e-5
    assert np.abs(full(e, 21, 21, fill_rule='evenodd') - xor).max() < 1e-5


def test_pentagram_areas_differ_by_the_inner_pentagon():
    # the evenodd hole is the inner pentagon; its circumradius is
    # r * cos(72 deg) / cos(36 deg) for a pentagram of circumradius r
    r = 17.7
    nz = full(STAR, 40, 40).sum(dtype=np.float64)
    eo = full(STAR, 40, 40, fill_rule='evenodd').sum(dtype=np.float64)
    ri = r * np.cos(np.radians(72)) / np.cos(np.radians(36))
    inner = 2.5 * ri * ri * np.sin(np.radians(72))
    assert abs((nz - eo) - inner) < 0.01 * inner


def test_recompute_is_needed_for_overlaps(monkeypatch):
    # without the recompute of flagged cells the accumulated area is wrong
    # by far more than the tolerance: this checks the test above can fail
    edges = CIRCLES
    none = np.zeros(0, np.int64)
    monkeypatch.setattr(scan, '_flag', lambda *a, **k: (none, none, none, (none, np.zeros(0))))
    bad = full(edges, 40, 40)
    assert np.abs(bad - reference(edges, 40, 40, 'nonzero')).max() > 0.1


def test_coincident_squares():
    sq = [[2.3, 2.6], [7.7, 2.6], [7.7, 8.2], [2.3, 8.2]]
    one = full(poly_edges(sq), 10, 10)
    two = full(poly_edges(sq, sq), 10, 10)
    assert np.abs(one - two).max() < 1e-6
    assert coverage(poly_edges(sq, sq), 10, 10, fill_rule='evenodd') is None
    # opposite orientation cancels under both rules
    assert coverage(poly_edges(sq, sq[::-1]), 10, 10) is None


def test_nested_squares_evenodd_hole():
    outer = [[1, 1], [9, 1], [9, 9], [1, 9]]
    inner = [[3.5, 3.5], [6.5, 3.5], [6.5, 6.5], [3.5, 6.5]]
    eo = full(poly_edges(outer, inner), 10, 10, fill_rule='evenodd')
    nz = full(poly_edges(outer, inner), 10, 10)
    assert abs(eo.sum() - (64 - 9)) < 1e-4 and abs(nz.sum() - 64) < 1e-4
    assert eo[5, 5] == 0 and eo[3, 3] == 0.75 and nz[3, 3] == 1


# -- invariances --------------------------------------------------------------

@pytest.mark.parametrize('seed', range(3))
def test_transpose_invariance(seed):
    rng = np.random.default_rng(seed)
    e = poly_edges(random_convex_polygon(rng, 30, 20.4, 17.9, 15.3))
    a = full(e, 40, 36)
    b = full(e[:, :, ::-1], 36, 40)
    assert np.abs(a - b.T).max() < 1e-5
    # with crossings: the recomputed cells are exact too
    s = full(STAR, 40, 40)
    t = full(STAR[:, :, ::-1], 40, 40)
    assert np.abs(s - t.T).max() < 1e-5


@pytest.mark.parametrize('seed', range(3))
def test_rotation_180_invariance(seed):
    rng = np.random.default_rng(seed + 10)
    e = poly_edges(random_convex_polygon(rng, 30, 20.4, 17.9, 15.3))
    a = full(e, 40, 36)
    b = full(np.array([40.0, 36.0]) - e, 40, 36)
    assert np.abs(a - b[::-1, ::-1]).max() < 1e-5
    s = full(STAR, 40, 40, fill_rule='evenodd')
    t = full(np.array([40.0, 40.0]) - STAR, 40, 40, fill_rule='evenodd')
    assert np.abs(s - t[::-1, ::-1]).max() < 1e-5


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_orientation_does_not_matter(rule):
    rng = np.random.default_rng(5)
    p = random_star_polygon(rng, 25, 15, 15, 2, 13)
    cw = full(poly_edges(p), 30, 30, fill_rule=rule)
    ccw = full(poly_edges(p[::-1]), 30, 30, fill_rule=rule)
    assert np.abs(cw - ccw).max() < 1e-6
    s1 = full(STAR, 40, 40, fill_rule=rule)
    s2 = full(poly_edges(pentagram(20.3, 21.1, 17.7)[::-1]), 40, 40, fill_rule=rule)
    assert np.abs(s1 - s2).max() < 1e-6


def test_translation_by_whole_pixels():
    rng = np.random.default_rng(3)
    e = poly_edges(random_star_polygon(rng, 30, 12.2, 11.9, 1, 10))
    a = coverage(e, 50, 50)
    b = coverage(e + [17, 9], 50, 50)
    assert b.box == (a.x0 + 17, a.y0 + 9, a.box[2] + 17, a.box[3] + 9)
    assert np.abs(a.data - b.data).max() < 1e-5


# -- clipping and edges outside the canvas ------------------------------------

def test_edges_far_left_still_count():
    rect = poly_edges([[-1e6, -1e6], [10.5, -1e6], [10.5, 1e6], [-1e6, 1e6]])
    m = coverage(rect, 20, 20)
    assert m.box == (0, 0, 11, 20)
    assert np.all(m.data[:, :10] == 1) and np.all(m.data[:, 10] == 0.5)


def test_polygon_clipped_on_all_sides_equals_window():
    # a big triangle; the canvas window must equal the same window of a
    # large canvas that contains everything
    tri = poly_edges([[-37.3, -20.1], [80.2, 10.7], [5.5, 95.3]])
    big = coverage(tri + 100, 300, 300).full(300, 300)
    small = full(tri, 40, 30)
    assert np.abs(big[100:130, 100:140] - small).max() < 1e-5


def test_polygon_entirely_left_or_outside_is_none():
    tri = poly_edges([[-50, 2], [-10, 5], [-30, 9]])
    assert coverage(tri, 20, 20) is None
    assert coverage(tri + [0, 100], 20, 20) is None
    assert coverage(tri + [100, 0], 20, 20) is None


def test_clip_rectangle_equals_slice():
    got = coverage(CIRCLES, 40, 40, clip=(10.2, 5, 30, 33.5))
    ref = full(CIRCLES, 40, 40)
    # the circles span rows 9..30: the box is the intersection
    assert got.box == (10, 9, 30, 31)
    assert np.abs(got.data - ref[9:31, 10:30]).max() < 1e-6
    assert coverage(CIRCLES, 40, 40, clip=(35, 35, 36, 36)) is None


def test_huge_but_allowed_coordinates():
    # a thin wedge from far away: only the part on the canvas matters
    tri = poly_edges([[-9e8, 5.0], [10.0, 5.0], [10.0, 6.0]])
    m = coverage(tri, 20, 20)
    assert m is not None and 0.4 < m.data.sum() < 10.1


def test_chunked_processing_matches(monkeypatch):
    a = full(CIRCLES, 40, 40, fill_rule='evenodd')
    s = full(STAR, 40, 40)
    monkeypatch.setattr(scan, '_CHUNK_PIECES', 97)
    monkeypatch.setattr(scan, '_CHUNK_WORK', 50)
    assert len(scan._bands(CIRCLES, 40, 40)) > 3
    b = full(CIRCLES, 40, 40, fill_rule='evenodd')
    t = full(STAR, 40, 40)
    # chains cut at band boundaries flag more cells; those are exact too
    assert np.abs(a - b).max() < 1e-5 and np.abs(s - t).max() < 1e-5


def test_crowded_cells_with_stacked_copies_stay_exact():
    # 40 copies of one square: pixels on its sides hold 40 pieces, more than
    # _EXACT_PIECES; equal pieces are merged, so they stay exact
    sq = [[2.3, 2.6], [7.7, 2.6], [7.7, 8.2], [2.3, 8.2]]
    assert 40 > scan._EXACT_PIECES
    one = full(poly_edges(sq), 10, 10)
    many = full(poly_edges(*[sq] * 40), 10, 10)
    assert np.abs(one - many).max() < 1e-6
    # with some copies reversed (they cancel) and a shifted one
    mixed = poly_edges(*([sq] * 25 + [sq[::-1]] * 12 + [np.add(sq, 0.013)]))
    a = full(mixed, 10, 10, fill_rule='evenodd')
    b = full(poly_edges(*([sq] * 13 + [np.add(sq, 0.013)])), 10, 10, fill_rule='evenodd')
    assert np.abs(a - b).max() < 1e-6


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_crowded_cells_are_refined_exactly(monkeypatch, rule):
    # cells with more than _EXACT_PIECES distinct pieces are scan converted
    # again on a finer grid (recursively): the same coverage
    a = full(CIRCLES, 40, 40, fill_rule=rule)
    s = full(STAR, 40, 40, fill_rule=rule)
    calls = []
    real = scan._refine
    monkeypatch.setattr(scan, '_refine', lambda *a: calls.append(len(a[4])) or real(*a))
    monkeypatch.setattr(scan, '_EXACT_PIECES', 1)
    monkeypatch.setattr(scan, '_FACES_RUNS', 1)      # no cell left to _faces
    b = full(CIRCLES, 40, 40, fill_rule=rule)
    t = full(STAR, 40, 40, fill_rule=rule)
    assert calls
    assert np.abs(a - b).max() < 1e-5 and np.abs(s - t).max() < 1e-5


def test_refinement_work_is_bounded(monkeypatch):
    # 300 lines through one point: refinement never parts them there, so
    # cells are refined only while their distinct pieces times 4 ** level
    # stay within _REFINE_WORK (levels 0 to 3 here); the busier ones are
    # sampled on evenly spaced lines, within 1/255 of refining deeper
    # (cells away from the point, whose lines cross nowhere, are decided
    # by their faces at some level)
    rng = np.random.default_rng(2)
    ang = rng.uniform(0, np.pi, 300)
    c = np.array([5.37, 5.61])
    polys = [np.array([c - 6 * u, c + 6 * u, c + 6 * u + 0.2 * np.r_[-u[1], u[0]]])
             for u in np.c_[np.cos(ang), np.sin(ang)]]
    e = poly_edges(*polys)
    depth, sampled = [], []
    real_refine, real_sampled = scan._refine, scan._sampled
    monkeypatch.setattr(scan, '_refine', lambda *a: depth.append(a[-1]) or real_refine(*a))
    monkeypatch.setattr(scan, '_sampled', lambda *a: sampled.append(len(a[1])) or real_sampled(*a))
    for rule in ('nonzero', 'evenodd'):
        depth.clear()
        sampled.clear()
        got = full(e, 11, 11, fill_rule=rule)
        assert max(depth) <= 3 and sum(sampled) > 0
        ref = reference(e, 11, 11, rule, n=64)
        assert np.abs(got - ref).max() < 0.02
        level = max(depth)
        depth.clear()
        with monkeypatch.context() as m:
            m.setattr(scan, '_REFINE_WORK', 12 * 4 ** 5)
            deep = full(e, 11, 11, fill_rule=rule)
        assert max(depth) > level
        assert np.abs(got - deep).max() < 1 / 255


@pytest.mark.parametrize('seed', range(4))
def test_sampled_cells_converge_to_the_exact_coverage(seed):
    # the midpoint rule on n evenly spaced lines against the exact rule on
    # all critical heights, for cells of 12 random pieces in the cell, some
    # starting or ending on its left side (both rules): the error shrinks
    # like 1/n
    rng = np.random.default_rng(seed)
    F, k = 50, 12
    ua, va, ub, vb = (rng.uniform(0.0, 1.0, (F, k)) for _ in range(4))
    ua[rng.random((F, k)) < 0.3] = 0.0
    ub[rng.random((F, k)) < 0.3] = 0.0
    m = rng.choice([-1.0, 1.0, 2.0], (F, k))
    C = rng.integers(-2, 3, F).astype(float)
    eo = rng.random(F) < 0.5
    exact = scan._exact_small(ua, va, ub, vb, m, C, eo)
    pf, pk = np.arange(F) * k, np.full(F, k)
    arrays = tuple(a.ravel() for a in (ua, va, ub, vb, m))
    err = [np.abs(scan._sampled(scan._pad(arrays), pf, pk, C, eo, lines=n) - exact).max()
           for n in (16, 256, 4096)]
    assert err[0] < 0.1 and err[1] < err[0] / 8 and err[2] < err[1] / 8


# -- errors -------------------------------------------------------------------

@pytest.mark.parametrize('w, h', [(0, 10), (10, -1), (2.5, 3), ('a', 3), (10**6, 10**6), (None, 4)])
def test_bad_canvas(w, h):
    with pytest.raises(CanvasError):
        coverage(STAR, w, h)


def test_bad_edges():
    bad = STAR.copy()
    bad[3, 1, 0] = np.nan
    with pytest.raises(PathError):
        coverage(bad, 10, 10)
    bad[3, 1, 0] = np.inf
    with pytest.raises(PathError):
        coverage(bad, 10, 10)
    with pytest.raises(LimitError):
        coverage(STAR * 1e9, 10, 10)
    with pytest.raises(PathError):
        coverage(np.zeros((3, 3)), 10, 10)
    with pytest.raises(PathError):
        coverage([['a', 'b']], 10, 10)
    with pytest.raises(PathError):
        coverage(STAR, 10, 10, fill_rule='winding')
    with pytest.raises(CanvasError):
        coverage(STAR, 10, 10, clip=(0, 0, 1))
    assert issubclass(CanvasError, RasterError)


def test_empty_and_degenerate():
    assert coverage(np.zeros((0, 2, 2)), 10, 10) is None
    assert coverage([], 10, 10) is None
    # zero-area polygon (a line traced back and forth)
    assert coverage(poly_edges([[1, 1], [8, 7]]), 10, 10) is None


def test_mask_helpers():
    m = Mask(np.ones((2, 2), np.float32), -1, 3)
    assert m.box == (-1, 3, 1, 5)
    f = m.full(4, 4)          # only pixel (3, 0) is on the canvas
    assert f.sum() == 1 and f[3, 0] == 1


# -- aliased (pixel centre) mode ----------------------------------------------

def test_crisp_centres_on_edges_follow_skia():
    """A centre on a shape's left or top edge is outside, one on its right
    or bottom edge inside (Skia's and resvg's aliased sampling: edge ends
    rounded to the nearest scanline and column).  Checked for a rectangle
    with every edge through centres and for its mirror images (a flip maps
    the rule onto itself shifted by one pixel)."""
    rect = poly_edges([[2.5, 3.5], [10.5, 3.5], [10.5, 12.5], [2.5, 12.5]])
    f = full(rect, 16, 16, antialias=False)
    expect = np.zeros((16, 16))
    expect[4:13, 3:11] = 1
    assert np.array_equal(f, expect)
    # the same rectangle traced backwards: the rule does not depend on direction
    back = poly_edges([[2.5, 3.5], [2.5, 12.5], [10.5, 12.5], [10.5, 3.5]])
    assert np.array_equal(full(back, 16, 16, antialias=False), expect)
    # mirrored about x = 8: edges 5.5 and 13.5, columns 6..13
    mir = poly_edges([[5.5, 3.5], [13.5, 3.5], [13.5, 12.5], [5.5, 12.5]])
    assert np.array_equal(full(mir, 16, 16, antialias=False)[:, 6:14], expect[:, 3:11])


def test_crisp_rectangle_centres():
    rect = poly_edges([[2.4, 1.6], [7.6, 1.6], [7.6, 4.4], [2.4, 4.4]])
    f = full(rect, 10, 6, antialias=False)
    expect = np.zeros((6, 10))
    expect[2:4, 2:8] = 1
    assert np.array_equal(f, expect)


def test_crisp_far_outside_and_clip():
    rect = poly_edges([[-1e6, -1e6], [10.5, -1e6], [10.5, 1e6], [-1e6, 1e6]])
    m = coverage(rect, 20, 20, antialias=False)
    # a centre exactly on the right edge (x = 10.5) is inside: min < c <= max
    assert m.box == (0, 0, 11, 20) and np.all(m.data == 1)
    c = coverage(CIRCLES, 40, 40, antialias=False, clip=(10, 12, 30, 25))
    ref = full(CIRCLES, 40, 40, antialias=False)
    assert np.array_equal(c.data, ref[c.y0:c.box[3], c.x0:c.box[2]])
    assert c.box[0] >= 10 and c.box[1] >= 12 and c.box[2] <= 30 and c.box[3] <= 25


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_crisp_matches_centre_sampling(rule):
    for edges in (STAR, CIRCLES):
        got = full(edges, 40, 40, antialias=False, fill_rule=rule)
        ref = reference(edges, 40, 40, rule, n=1)
        assert np.array_equal(got, ref)


# -- properties ---------------------------------------------------------------

polygons = st.lists(st.tuples(st.floats(-5, 35), st.floats(-5, 35)), min_size=3, max_size=12)


@settings(max_examples=80, deadline=None)
@given(polygons, st.sampled_from(['nonzero', 'evenodd']))
def test_property_coverage_in_unit_interval_and_close_to_sampling(pts, rule):
    e = poly_edges(np.array(pts))
    got = full(e, 30, 30, fill_rule=rule)
    assert got.min() >= 0 and got.max() <= 1
    ref = reference(e, 30, 30, rule, n=16)
    # 16x16 sampling is itself off by up to ~1/32 per edge in a pixel
    assert np.abs(got - ref).mean() < 0.01


@settings(max_examples=120, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(4, 32),
       st.floats(0.5, 25), st.floats(5.0, 25.0), st.floats(5.0, 25.0))
def test_property_area_conservation_simple_polygons(seed, n, rmax, cx, cy):
    # n <= _PAIR_LIMIT edges: no pixel holds more pieces than that (a line
    # meets a pixel in one piece), so every pixel is exact
    rng = np.random.default_rng(seed)
    p = random_star_polygon(rng, n, cx, cy, 0.0, min(rmax, cx, cy, 30 - cx, 30 - cy))
    m = coverage(poly_edges(p), 30, 30)
    total = 0.0 if m is None else float(m.data.sum(dtype=np.float64))
    assert abs(total - shoelace(p)) < 1e-4 * max(1.0, shoelace(p))
    if m is not None:
        assert m.data.min() >= 0 and m.data.max() <= 1


# -- paths with curves ----------------------------------------------------------


@pytest.mark.parametrize('tol', [1.0, 0.25, 0.02])
def test_path_coverage_honours_tolerance(tol):
    # chords of a flattened circle stay within tol of it, so the covered
    # area is within perimeter * tol (+ the cubic's own radial error)
    r = 20.0
    m = path_coverage(circle_path(25.3, 24.6, r), 50, 50, tolerance=tol)
    err = abs(float(m.data.sum(dtype=np.float64)) - np.pi * r * r)
    assert err <= 2 * np.pi * r * (tol + 2.8e-4 * r)
    # a transform scales the device-space tolerance, not the user one
    m2 = path_coverage(circle_path(2.53, 2.46, 2.0), 50, 50, tolerance=tol,
                       transform=(10, 0, 0, 10, 0, 0))
    err2 = abs(float(m2.data.sum(dtype=np.float64)) - np.pi * r * r)
    assert err2 <= 2 * np.pi * r * (tol + 2.8e-4 * r)


def test_path_coverage_error_shrinks_with_tolerance():
    r = 20.0
    errs = [abs(float(path_coverage(circle_path(25.3, 24.6, r), 50, 50,
                                    tolerance=t).data.sum(dtype=np.float64)) - np.pi * r * r)
            for t in (1.0, 0.1, 0.01)]
    assert errs[0] > errs[1] > errs[2]


# -- exactness properties on arbitrary (self-intersecting, overlapping) input ---

two_polygons = st.tuples(polygons, polygons)


@settings(max_examples=100, deadline=None)
@given(two_polygons, st.sampled_from(['nonzero', 'evenodd']))
def test_property_transpose_exact_with_crossings(polys, rule):
    # rows and columns are treated differently by the algorithm; the exact
    # answer is symmetric, so this checks the recomputed cells too
    e = poly_edges(np.array(polys[0]), np.array(polys[1]))
    a = full(e, 30, 30, fill_rule=rule)
    b = full(e[:, :, ::-1], 30, 30, fill_rule=rule)
    assert np.abs(a - b.T).max() < 2e-5


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_run_starting_a_hair_outside_its_cell_is_recomputed(rule):
    # a vertex at y = -5e-324 (the smallest denormal): the run starting
    # there lies a hair above its cell, so the cell's boundary walk would
    # miss its start (and take the windings' bound for linear); the cell
    # must be recomputed.  Found by the transpose property above.
    p1 = np.array([(0.0, 0.0), (-5e-324, 1.5), (1.0, 0.0)])
    p2 = np.array([(0.5, 2.0), (1.0, 0.0), (0.0, 0.0)])
    e = poly_edges(p1, p2)
    a = full(e, 4, 4, fill_rule=rule)
    b = full(e[:, :, ::-1], 4, 4, fill_rule=rule)
    assert np.abs(a - b.T).max() < 1e-6
    # the union of the two triangles in pixel (row 1, column 0): 1/12 + 1/4
    # less their overlap (nonzero) or less twice it (evenodd)
    y0 = 12 / 11
    lap = (y0 - 11 * y0 ** 2 / 24) - (1 - 11 / 24)
    want = 1 / 12 + 1 / 4 - (lap if rule == 'nonzero' else 2 * lap)
    assert abs(float(a[1, 0]) - want) < 1e-6


@settings(max_examples=100, deadline=None)
@given(two_polygons, st.sampled_from(['nonzero', 'evenodd']))
def test_property_refinement_exact_with_crossings(polys, rule):
    # scaling by 2 maps each pixel onto a 2x2 block: exact coverage of the
    # block sums to 4 times the pixel's coverage
    e = poly_edges(np.array(polys[0]), np.array(polys[1]))
    a = full(e, 30, 30, fill_rule=rule).astype(np.float64)
    b = full(2 * e, 60, 60, fill_rule=rule).astype(np.float64)
    blocks = b.reshape(30, 2, 30, 2).sum((1, 3))
    assert np.abs(blocks - 4 * a).max() < 1e-4


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(5, 30), st.floats(0.05, 0.9),
       st.sampled_from(['nonzero', 'evenodd']))
def test_property_wiggly_closed_walk_exact(seed, n, step, rule):
    # a closed random walk of short steps visits the same pixels again and
    # again and crosses itself: the pixels the chain revisits without being
    # monotone must be recomputed, or the refinement identity fails
    rng = np.random.default_rng(seed)
    ang = rng.uniform(0, 2 * np.pi, n)
    p = 6.3 + np.cumsum(np.c_[np.cos(ang), np.sin(ang)] * step, axis=0)
    e = poly_edges(p)
    a = full(e, 14, 14, fill_rule=rule).astype(np.float64)
    b = full(2 * e, 28, 28, fill_rule=rule).astype(np.float64)
    assert np.abs(b.reshape(14, 2, 14, 2).sum((1, 3)) - 4 * a).max() < 1e-4
    t = full(e[:, :, ::-1], 14, 14, fill_rule=rule)
    assert np.abs(a - t.T).max() < 2e-5


def test_wiggly_star_boundary_needs_no_recompute(monkeypatch):
    # a star-shaped polygon with sub-pixel zig-zag: its boundary pixels are
    # visited several times by one chain whose pieces all advance along the
    # tangent, so no pixel needs the exact recompute (and the area is exact)
    rng = np.random.default_rng(7)
    n = 4000
    th = 2 * np.pi * (np.arange(n) + rng.uniform(0, 1, n)) / n
    r = 40 + rng.uniform(-0.5, 0.5, n)
    p = np.c_[50 + r * np.cos(th), 50 + r * np.sin(th)]
    calls = []
    real = scan._exact
    monkeypatch.setattr(scan, '_exact', lambda *a: calls.append(len(a[7])) or real(*a))
    m = coverage(poly_edges(p), 100, 100)
    assert sum(calls) <= 2                  # at most the contour's start pixel(s)
    assert abs(float(m.data.sum(dtype=np.float64)) - shoelace(p)) < 1e-6 * shoelace(p)


# -- fast paths -----------------------------------------------------------------

def test_sparse_and_dense_accumulation_agree_bitwise(monkeypatch):
    # few pieces in a large box are summed over the touched cells only; the
    # sums are the same, in the same order, as the dense accumulators
    rng = np.random.default_rng(11)
    polys = [rng.uniform(3, 200, (9, 2)) for _ in range(3)]
    e = poly_edges(*polys)
    out = {}
    for ratio in (0, 10 ** 9):                 # never / always dense
        monkeypatch.setattr(scan, '_SPARSE_RATIO', ratio)
        for rule in ('nonzero', 'evenodd'):
            out[ratio, rule] = coverage(e, 210, 210, fill_rule=rule).data
    for rule in ('nonzero', 'evenodd'):
        assert np.array_equal(out[0, rule], out[10 ** 9, rule])


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(0, 59))
def test_property_closed_chain_start_cell_left_alone_is_exact(seed, start):
    # a smooth closed curve of tiny edges, started anywhere: the cell holding
    # its start (the chain's end and start, merged) is left to the running
    # sum when the chain is monotone there; the result still equals the
    # coverage with every touched cell recomputed exactly
    rng = np.random.default_rng(seed)
    th = np.sort(rng.uniform(0, 2 * np.pi, 60))
    r = 4.0 + 0.3 * np.cos(3 * th + rng.uniform(0, 6))
    p = np.c_[7.1 + r * np.cos(th), 6.9 + r * np.sin(th)]
    e = poly_edges(np.roll(p, -start, axis=0))
    a = full(e, 14, 14)
    scan._FLAG_EVERYTHING = True
    try:
        b = full(e, 14, 14)
    finally:
        scan._FLAG_EVERYTHING = False
    assert np.abs(a - b).max() < 1e-6
    assert abs(float(a.sum(dtype=np.float64)) - shoelace(p)) < 1e-6 * shoelace(p)


def test_merged_start_cell_needs_no_recompute(monkeypatch):
    # a wedge whose tip is rounded inside one pixel (radius 0.45, the
    # tangent turning from -20 to 110 degrees: neither x nor y monotone),
    # started in the middle of the rounding: the tip pixel holds one chain
    # (the contour's end and start, merged) whose directions fit in a
    # half-plane, so it needs no recompute
    phi = np.radians(np.linspace(-20.0, 110.0, 9))
    arc = np.c_[10.5 + 0.45 * np.sin(phi), 10.5 - 0.45 * np.cos(phi)]
    t_in = np.array([np.cos(phi[0]), np.sin(phi[0])])
    t_out = np.array([np.cos(phi[-1]), np.sin(phi[-1])])
    p = np.vstack([arc, arc[-1] + 8 * t_out, arc[0] - 8 * t_in])
    p = np.roll(p, -4, axis=0)                  # start mid-arc
    calls = []
    real = scan._exact
    monkeypatch.setattr(scan, '_exact', lambda *a: calls.append(len(a[7])) or real(*a))
    m = coverage(poly_edges(p), 24, 24)
    assert calls == []
    assert abs(float(m.data.sum(dtype=np.float64)) - shoelace(p)) < 1e-6 * shoelace(p)
    monkeypatch.setattr(scan, '_FLAG_EVERYTHING', True)
    assert np.abs(coverage(poly_edges(p), 24, 24).data - m.data).max() < 1e-6
    monkeypatch.setattr(scan, '_FLAG_EVERYTHING', False)
    # without the rounding's start there, the same tip is one run: also left alone
    calls.clear()
    coverage(poly_edges(np.roll(p, 4, axis=0)), 24, 24)
    assert calls == []


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans())
def test_property_split_pieces_chain_between_grid_lines(seed, per_segment_hi):
    """_split: pieces in travel order, consecutive ones sharing their split
    point bitwise, each between two consecutive integer lines of [0, hi]
    (or beyond them), split points exactly on the lines."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 40))
    ua, ub = rng.uniform(-3, 12, n), rng.uniform(-3, 12, n)
    ub[::5] = ua[::5]                                   # no extent in u
    ua[1::7] = np.round(ua[1::7])                       # ends on grid lines
    va, vb = rng.uniform(-5, 5, n), rng.uniform(-5, 5, n)
    hi = rng.integers(0, 10, n).astype(float) if per_segment_hi else 6
    tag = np.arange(n)
    UA, VA, UB, VB, T = scan._split(ua, va, ub, vb, hi, tag=tag)
    h = np.broadcast_to(hi, (n,))
    for i in range(n):
        s = np.flatnonzero(T == i)
        assert (np.diff(s) == 1).all() and len(s)
        assert UA[s[0]] == ua[i] and VA[s[0]] == va[i] and UB[s[-1]] == ub[i] and VB[s[-1]] == vb[i]
        assert (UB[s[:-1]] == UA[s[1:]]).all() and (VB[s[:-1]] == VA[s[1:]]).all()
        inner = UB[s[:-1]]
        assert (inner == np.round(inner)).all() and ((inner >= 0) & (inner <= h[i])).all()
        lines = np.arange(0, h[i] + 1)
        lo, hi_ = min(ua[i], ub[i]), max(ua[i], ub[i])
        assert len(inner) == int(((lines > lo) & (lines < hi_)).sum())
        if len(inner) > 1:
            assert (np.diff(inner) * np.sign(ub[i] - ua[i]) > 0).all()     # travel order
        # the split point lies on the segment
        t = (inner - ua[i]) / (ub[i] - ua[i])
        assert np.allclose(VB[s[:-1]], va[i] + t * (vb[i] - va[i]), atol=1e-12)
    # without a tag: the same pieces
    assert all(np.array_equal(a, b) for a, b in zip(scan._split(ua, va, ub, vb, hi), (UA, VA, UB, VB)))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(-2**40, 2**40), max_size=60), st.integers(1, 3))
def test_distinct_is_sorted_unique(values, cols):
    # np.unique without the masked-array import (the scan converter's and
    # the text layout's): same values, same order, same dtype, any shape
    from raster.geometry.rows import distinct_values
    a = np.array(values, np.int64)
    a = a[:len(a) // cols * cols].reshape(-1, cols)
    got = distinct_values(a)
    assert got.dtype == np.int64 and got.ndim == 1
    np.testing.assert_array_equal(got, np.unique(a))


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 60), st.integers(0, 3000), st.integers(0, 2**32 - 1))
def test_property_stable_order_is_a_stable_argsort(bits, n, seed):
    # cell keys of every width: one 16-bit radix pass, several, or (48 bits
    # and more) numpy's merge sort; many repeated keys, so the order of
    # equal keys is tested too
    rng = np.random.default_rng(seed)
    top = 1 << bits
    keys = rng.integers(0, top, n, dtype=np.int64)
    if n and rng.uniform() < 0.5:
        keys = rng.choice(keys[:max(1, n // 10)], n)
    assert np.array_equal(scan._stable_order(keys), np.argsort(keys, kind='stable'))
