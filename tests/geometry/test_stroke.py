"""Tests of raster.stroke: outlines, joins, caps, dashes, hairlines.

Regions are checked with an independent nonzero winding-number sampler
(``winding`` below) and, where the union has no overlaps, with exact
shoelace areas of the emitted polygons.
"""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.spatial import cKDTree

from raster.errors import LimitError, RasterError
from raster.geometry.path import CLOSE, LINE, MOVE, Path
from raster.geometry.pens import PathBuilder
from raster.geometry.stroking import (DashedLines, LineCap, LineJoin, StrokeError, StrokeStyle,
                                     dash_pattern, dash_polylines, hairline_scale, stroke)
from raster.geometry.transform import Affine


# -- helpers -------------------------------------------------------------------

def polygons(path):
    """List of (k, 2) arrays, one per closed polygon of a stroke outline."""
    v = path.verbs
    assert set(v.tolist()) <= {MOVE, LINE, CLOSE}
    out, cur, i = [], None, 0
    for verb in v.tolist():
        if verb == MOVE:
            cur = [path.points[i]]; i += 1
        elif verb == LINE:
            cur.append(path.points[i]); i += 1
        else:
            out.append(np.array(cur)); cur = None
    assert cur is None, 'every outline contour must be closed'
    return out


def shoelace(poly):
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def edges(path):
    """(E, 2, 2) edges of the outline, closing edges included."""
    segs = path.segments()
    e = [np.stack([segs.ctrl[:, 0], segs.ctrl[:, 3]], axis=1)]
    cl = segs.contour_closed
    e.append(np.stack([segs.contour_end[cl], segs.contour_start[cl]], axis=1))
    return np.concatenate(e)


def winding(path, pts):
    """Nonzero winding number of each point (P, 2) with respect to the path."""
    E = edges(path)
    pts = np.asarray(pts, dtype=np.float64)
    out = np.zeros(len(pts), np.int64)
    a, b = E[:, 0], E[:, 1]
    for lo in range(0, len(pts), 2000):
        p = pts[lo:lo + 2000, None, :]
        cr = (b[:, 0] - a[:, 0]) * (p[..., 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (p[..., 0] - a[:, 0])
        up = (a[:, 1] <= p[..., 1]) & (p[..., 1] < b[:, 1]) & (cr > 0)
        dn = (b[:, 1] <= p[..., 1]) & (p[..., 1] < a[:, 1]) & (cr < 0)
        out[lo:lo + 2000] = up.sum(1) - dn.sum(1)
    return out


def inside(path, pts):
    return winding(path, pts) != 0


def grid(x0, y0, x1, y1, h):
    xs = np.arange(x0 + h / 2, x1, h)
    ys = np.arange(y0 + h / 2, y1, h)
    X, Y = np.meshgrid(xs, ys)
    return np.stack([X.ravel(), Y.ravel()], axis=1)


def sampled_area(path, box, h):
    g = grid(*box, h)
    return inside(path, g).sum() * h * h


def dist_to_polyline(pts, poly):
    """Distance of each point (P, 2) to the polyline (V, 2)."""
    a, b = poly[:-1], poly[1:]
    p = pts[:, None, :]
    ab = b - a
    L2 = np.maximum((ab ** 2).sum(1), 1e-300)
    t = np.clip(((p - a) * ab).sum(-1) / L2, 0, 1)
    q = a + t[..., None] * ab
    return np.sqrt(((p - q) ** 2).sum(-1)).min(1)


def line(*pts, closed=False):
    return Path.polygon(pts, closed=closed)


def parse(d):
    """Tiny parser for M/L/C/Q/Z absolute path data used in these tests."""
    toks = d.replace(',', ' ').split()
    b = PathBuilder()
    i = 0
    while i < len(toks):
        c = toks[i]; i += 1
        n = {'M': 1, 'L': 1, 'Q': 2, 'C': 3, 'Z': 0}[c]
        pts = [(float(toks[i + 2 * k]), float(toks[i + 2 * k + 1])) for k in range(n)]
        i += 2 * n
        {'M': lambda: b.moveTo(*pts), 'L': lambda: b.lineTo(*pts),
         'Q': lambda: b.qCurveTo(*pts), 'C': lambda: b.curveTo(*pts),
         'Z': b.closePath}[c]()
    return b.path()


# -- style validation -------------------------------------------------------------

@pytest.mark.parametrize('kw', [dict(width=-1), dict(width=float('nan')), dict(join='pointy'),
                                dict(cap='flat'), dict(miterlimit=0.99),
                                dict(miterlimit=float('inf')), dict(dash=[1, float('nan')]),
                                dict(dash='1 2'), dict(dash_offset=float('inf')),
                                dict(width='wide')])
def test_bad_style_raises_stroke_error(kw):
    with pytest.raises(StrokeError) as ei:
        StrokeStyle(**kw)
    assert isinstance(ei.value, RasterError)
    assert '\n' not in str(ei.value)


def test_bad_arguments_to_stroke():
    p = line((0, 0), (1, 0))
    with pytest.raises(StrokeError):
        stroke('M 0 0 L 1 0')
    with pytest.raises(StrokeError):
        stroke(p, tolerance=0)
    with pytest.raises(StrokeError):
        stroke(p, tolerance=float('nan'))
    with pytest.raises(StrokeError):
        stroke(p, width=-2)
    with pytest.raises(StrokeError):
        stroke(p, colour='red')
    with pytest.raises(StrokeError):
        stroke(p, {'width': 2})


def test_joins_and_caps_are_str_enums():
    """StrokeStyle stores LineJoin / LineCap members; the SVG keywords and
    the members are interchangeable, and a style is an immutable, hashable
    value (strokes are batched by style)."""
    assert LineJoin.values() == ('miter', 'miter-clip', 'round', 'bevel', 'arcs')
    assert LineCap.values() == ('butt', 'round', 'square')
    a = StrokeStyle(width=2, join='bevel', cap=LineCap.ROUND)
    b = StrokeStyle(width=2.0, join=LineJoin.BEVEL, cap='round')
    assert a.join is LineJoin.BEVEL and a.cap is LineCap.ROUND
    assert a.join == 'bevel' and '%s/%s' % (a.join, a.cap) == 'bevel/round'
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1
    assert StrokeStyle().join is LineJoin.MITER and StrokeStyle().cap is LineCap.BUTT
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.width = 3
    with pytest.raises(StrokeError, match="unknown line join 'pointy' .*miter-clip"):
        StrokeStyle(join='pointy')
    with pytest.raises(StrokeError, match='unknown line cap'):
        StrokeStyle(cap=['butt'])
    # the same outline either way
    p = line((0, 0), (10, 0), (10, 10))
    assert stroke(p, a) == stroke(p, width=2, join='bevel', cap='round')


def test_style_and_keyword_override():
    s = StrokeStyle(width=4, cap='square')
    a = stroke(line((0, 0), (10, 0)), s, width=2)
    b = stroke(line((0, 0), (10, 0)), width=2, cap='square')
    assert a == b
    assert s.width == 4


def test_zero_width_and_empty_path_draw_nothing():
    assert stroke(line((0, 0), (10, 0)), width=0, cap='round').is_empty
    assert len(stroke(Path.empty(), width=3)) == 0
    # a singular transform with no scale at all
    assert len(stroke(line((0, 0), (10, 0)), width=1, transform=Affine.scale(0))) == 0


# -- dash patterns -------------------------------------------------------------------

def test_dash_pattern_rules():
    assert dash_pattern(None) is None
    assert dash_pattern([]) is None
    assert dash_pattern([3, -1, 2]) is None          # negative -> solid
    assert dash_pattern([0, 0, 0]) is None           # zero sum -> solid
    assert dash_pattern([2]).tolist() == [2, 2]      # odd -> repeated
    assert dash_pattern([1, 2, 3]).tolist() == [1, 2, 3, 1, 2, 3]
    assert dash_pattern([0, 3]).tolist() == [0, 3]


# -- areas of single lines (no overlaps: shoelace sums are exact) -------------------

L, W = 20.0, 4.0


def test_butt_line_area_is_length_times_width():
    out = stroke(line((1, 2), (1 + L, 2)), width=W)
    assert sum(shoelace(p) for p in polygons(out)) == pytest.approx(L * W, rel=1e-12)
    assert out.control_box() == (1.0, 0.0, 21.0, 4.0)


def test_square_cap_line_area():
    out = stroke(line((1, 2), (1 + L, 2)), width=W, cap='square')
    assert sum(shoelace(p) for p in polygons(out)) == pytest.approx((L + W) * W, rel=1e-12)
    assert out.control_box() == (-1.0, 0.0, 23.0, 4.0)


@pytest.mark.parametrize('tol', [0.01, 0.1, 0.5])
def test_round_cap_line_area_within_tolerance(tol):
    out = stroke(line((1, 2), (1 + L, 2)), width=W, cap='round', tolerance=tol)
    area = sum(shoelace(p) for p in polygons(out))
    # arcs are polygonized at the area-preserving radius: the area is exact
    assert area == pytest.approx(L * W + math.pi * (W / 2) ** 2, rel=1e-12)
    # ... and the outline stays within the tolerance of the exact stroke
    poly = polygons(out)[0]
    centre = np.array([(1.0, 2.0), (1 + L, 2.0)])
    dv = dist_to_polyline(poly, centre)
    dm = dist_to_polyline((poly + np.roll(poly, -1, axis=0)) / 2, centre)
    assert np.all(np.abs(dv - W / 2) <= tol) and np.all(dm >= W / 2 - tol)
    assert dv.max() > W / 2 + tol / 10            # the vertices do lie outside


@pytest.mark.parametrize('r', [0.1, 1.5, 20.0, 1e4])
@pytest.mark.parametrize('tol', [1e-3, 0.05, 0.25, 1.0, 100.0])
@pytest.mark.parametrize('sweep', [0.3, -np.pi, 2 * np.pi])
def test_arc_polygonization_within_tolerance(r, tol, sweep):
    from raster.geometry.stroking import _arcs
    pts, cnt = _arcs(np.array([[3.0, 4.0]]), np.array([[0.6 * r, 0.8 * r]]), np.array([sweep]), tol)
    rad = np.hypot(*(pts - (3, 4)).T)
    mid = np.hypot(*((pts[1:] + pts[:-1]) / 2 - (3, 4)).T)
    assert np.all(np.abs(rad - r) <= tol) and np.all(mid >= r - tol)
    ang = np.unwrap(np.arctan2(*(pts - (3, 4))[:, ::-1].T))
    assert ang[-1] - ang[0] == pytest.approx(sweep)


def test_winding_counts_pieces_with_one_sign():
    # the nonzero union relies on every outline polygon adding to the winding
    # with the same sign: windings are >= 0 everywhere (<= 0 when mirrored)
    p = parse('M 0 0 C 30 0 -10 30 20 30 L 25 0 L 0 25 Z M 40 40 L 60 40 L 41 41 M 5 5 Z')
    rng = np.random.default_rng(2)
    g = rng.uniform(-10, 70, size=(8000, 2))
    for t in (None, Affine.scale(1, -1), Affine.rotate(30) @ Affine.skew_x(20)):
        for join in ('miter', 'round', 'bevel', 'miter-clip'):
            out = stroke(p, width=3, join=join, cap='round', transform=t)
            wn = winding(out, (t or Affine()).apply(g))
            sign = 1 if t is None or t.determinant > 0 else -1
            assert np.all(wn * sign >= 0) and np.any(wn * sign >= 2)


@pytest.mark.parametrize('w', [0.5, 3.0, 40.0])
@pytest.mark.parametrize('tol, t', [(0.01, None), (0.25, None), (0.1, Affine.scale(4)),
                                    (1.0, Affine.rotate(10) @ Affine.scale(0.3))])
def test_round_join_within_device_tolerance(w, tol, t):
    # a 120-degree turn at (10, 0) (round caps too, for the 40 wide pen whose
    # caps reach the join); t is a similarity, so the exact stroke in
    # device space is {p : dist(p, t(polyline)) <= s * w / 2}
    pts = np.array([(0, 0), (10, 0), (5, 8.660254037844386)])
    out = stroke(line(*pts), width=w, join='round', cap='round', tolerance=tol, transform=t)
    t = t or Affine()
    s = t.max_scale()
    dev = t.apply(pts)
    rng = np.random.default_rng(4)
    g = dev[1] + rng.uniform(-1, 1, size=(6000, 2)) * s * w
    d = dist_to_polyline(g, dev)
    got = inside(out, g)
    assert np.all(got[d < s * w / 2 - tol]) and not np.any(got[d > s * w / 2 + tol])
    assert np.any(np.abs(d - s * w / 2) < tol)     # the boundary band is sampled


def test_sampled_areas_match_analytic_values():
    # unions with overlaps: count samples with the nonzero rule
    h = 0.05
    box = (-5, -5, 28, 9)
    p = line((1, 2), (1 + L, 2))
    a = sampled_area(stroke(p, width=W, cap='round', tolerance=0.01), box, h)
    assert a == pytest.approx(L * W + math.pi * 4, abs=0.2)


# -- joins ---------------------------------------------------------------------------

def test_rectangle_with_miter_joins_is_outer_minus_inner():
    Wr, Hr, w = 30.0, 20.0, 4.0
    p = line((0, 0), (Wr, 0), (Wr, Hr), (0, Hr), closed=True)
    out = stroke(p, width=w)
    assert out.control_box() == (-2.0, -2.0, 32.0, 22.0)
    # the outline is exactly the two rectangles (inner offsets end where they
    # cross, miter tips replace the outer offset ends)
    loops = sorted(sorted(map(tuple, q.tolist())) for q in polygons(out))
    assert loops == [[(-2, -2), (-2, 22), (32, -2), (32, 22)], [(2, 2), (2, 18), (28, 2), (28, 18)]]
    h = 0.25                                       # edges fall between samples
    g = grid(-3, -3, 33, 23, h)
    got = inside(out, g)
    x, y = g[:, 0], g[:, 1]
    outer = (x > -2) & (x < 32) & (y > -2) & (y < 22)
    inner = (x > 2) & (x < 28) & (y > 2) & (y < 18)
    assert np.array_equal(got, outer & ~inner)
    assert got.sum() * h * h == pytest.approx((Wr + w) * (Hr + w) - (Wr - w) * (Hr - w))


@pytest.mark.parametrize('limit, tip_inside', [(1.4, False), (1.5, True), (math.sqrt(2), True)])
def test_miterlimit_switches_to_bevel_at_90_degrees(limit, tip_inside):
    # 90-degree corner: miter ratio 1/sin(45deg) = sqrt(2) = 1.41421...
    p = line((0, 0), (10, 0), (10, 10))
    out = stroke(p, width=2, miterlimit=limit)
    # the miter tip is (11, -1); the bevel edge is at distance sqrt(2)/2 from the
    # vertex (10, 0) along the outer bisector
    assert bool(inside(out, [(10.9, -0.9)])[0]) == tip_inside
    assert bool(inside(out, [(10.99, -0.99)])[0]) == tip_inside
    assert inside(out, [(10.3, -0.3)])[0]          # inside the bevel triangle


def test_miter_clip_clips_at_half_limit_times_width():
    p = line((0, 0), (10, 0), (10, 10))
    out = stroke(p, width=2, join='miter-clip', miterlimit=1.2)
    # along the outer bisector (1, -1)/sqrt(2) from the vertex (10, 0):
    b = np.array([1.0, -1.0]) / math.sqrt(2)
    v = np.array([10.0, 0.0])
    assert inside(out, [v + 1.15 * b])[0]          # beyond the bevel (0.707), before the clip
    assert not inside(out, [v + 1.25 * b])[0]      # past the clip line at 1.2
    # below the limit, miter-clip is an ordinary miter
    assert stroke(p, width=2, join='miter-clip', miterlimit=2) == stroke(p, width=2, miterlimit=2)


def test_arcs_join_falls_back_to_miter():
    p = line((0, 0), (10, 0), (4, 8))
    assert stroke(p, width=3, join='arcs') == stroke(p, width=3, join='miter')


def test_bevel_and_round_joins():
    p = line((0, 0), (10, 0), (10, 10))
    b = stroke(p, width=2, join='bevel')
    r = stroke(p, width=2, join='round', tolerance=0.01)
    v = np.array([10.0, 0.0])
    d = np.array([1.0, -1.0]) / math.sqrt(2)
    assert inside(b, [v + 0.65 * d])[0] and not inside(b, [v + 0.75 * d])[0]
    assert inside(r, [v + 0.98 * d])[0] and not inside(r, [v + 1.02 * d])[0]


def test_cusp_makes_no_spike_and_no_hole():
    p = line((0, 0), (10, 0), (0, 0.0))            # 180-degree turn
    for join in ('miter', 'miter-clip', 'bevel', 'round'):
        out = stroke(p, width=2, join=join, miterlimit=4)
        box = out.control_box()
        expect = {'miter': 10, 'bevel': 10, 'miter-clip': 14, 'round': 11}[join]
        # (the round join is polygonized within the default tolerance 0.25)
        assert box[2] == pytest.approx(expect, abs=0.25 if join == 'round' else 1e-9), join
        assert box[1] == pytest.approx(-1, abs=0.25) and box[3] == pytest.approx(1, abs=0.25)
        g = grid(0.1, -0.9, 9.9, 0.9, 0.1)
        assert inside(out, g).all(), join


def test_inner_join_region_filled():
    # sharp zig-zag with a fat pen: the inner side overlaps heavily
    p = line((0, 0), (10, 0), (0, 3), (10, 6))
    out = stroke(p, width=6, join='round', cap='round', tolerance=0.02)
    g = grid(-5, -5, 15, 11, 0.1)
    d = dist_to_polyline(g, np.array([(0, 0), (10, 0), (0, 3), (10, 6)], float))
    got = inside(out, g)
    assert np.all(got[d < 3 - 0.03]) and not np.any(got[d > 3 + 0.03])


# -- degenerate subpaths -----------------------------------------------------------

@pytest.mark.parametrize('d', ['M 10 10 Z', 'M 10 10 L 10 10', 'M 10 10 C 10 10 10 10 10 10',
                               'M 10 10 Q 10 10 10 10 Z', 'M 10 10 L 10 10 L 10 10 Z'])
def test_zero_length_subpath_caps(d):
    p = parse(d)
    assert len(stroke(p, width=4, cap='butt')) == 0
    sq = stroke(p, width=4, cap='square')
    assert sq.control_box() == (8.0, 8.0, 12.0, 12.0)
    assert sum(shoelace(q) for q in polygons(sq)) == pytest.approx(16.0)
    disc = stroke(p, width=4, cap='round', tolerance=0.01)
    a = sum(shoelace(q) for q in polygons(disc))
    assert a == pytest.approx(4 * math.pi, rel=1e-12)
    r = np.hypot(*(polygons(disc)[0] - 10).T)
    assert np.all(np.abs(r - 2) <= 0.01)


def test_lone_move_is_not_stroked():
    assert len(stroke(parse('M 10 10'), width=4, cap='round')) == 0
    assert len(stroke(parse('M 10 10 M 20 20'), width=4, cap='square')) == 0


def test_zero_length_square_cap_is_axis_aligned_in_user_space():
    t = Affine.rotate(30)
    out = stroke(parse('M 0 0 Z'), width=2, cap='square', transform=t)
    expect = t.apply(np.array([(1.0, 1), (-1, 1), (-1, -1), (1, -1)]))
    got = polygons(out)[0]
    assert len(got) == 4
    assert sorted(map(tuple, np.round(got, 12))) == sorted(map(tuple, np.round(expect, 12)))


def test_coincident_points_are_ignored():
    a = stroke(line((0, 0), (5, 0), (5, 0), (10, 0), (10, 5), (10, 5)), width=2, cap='square')
    b = stroke(line((0, 0), (5, 0), (10, 0), (10, 5)), width=2, cap='square')
    assert a == b


def test_short_segment_with_huge_width():
    p = line((0, 0), (0.001, 0), (0.001, 0.001), (1, 1))
    out = stroke(p, width=100, join='round', cap='round', tolerance=0.05)
    g = grid(-60, -60, 60, 60, 1.0)
    pts = np.array([(0, 0), (0.001, 0), (0.001, 0.001), (1, 1)])
    d = dist_to_polyline(g, pts)
    got = inside(out, g)
    assert np.all(got[d < 50 - 0.06]) and not np.any(got[d > 50 + 0.06])


# -- closed subpaths -------------------------------------------------------------------

def test_closed_subpath_has_no_caps_and_joins_at_start():
    p = line((0, 0), (10, 0), (10, 10), closed=True)
    out = stroke(p, width=2, cap='round', join='miter', miterlimit=10)
    open_ = stroke(line((0, 0), (10, 0), (10, 10), (0, 0)), width=2, cap='butt', miterlimit=10)
    g = grid(-6, -6, 16, 16, 0.1)
    a, b = inside(out, g), inside(open_, g)
    assert a.sum() > b.sum()                        # the join at (0, 0) adds a miter
    assert np.all(a >= b)
    assert out.control_box()[0] < -2.4              # the 45-degree miter tip reaches left


def test_explicit_closing_point_equals_implicit_close():
    a = stroke(line((0, 0), (10, 0), (10, 10), (0, 0), closed=True), width=2)
    b = stroke(line((0, 0), (10, 0), (10, 10), closed=True), width=2)
    assert a == b


# -- curves and tolerance ---------------------------------------------------------------

CURVE = 'M 0 0 C 40 -20 60 60 100 20 Q 130 0 110 -30'


def bezier_points(d, n=20000):
    """Dense points of the curve path CURVE (the exact stroke centre line)."""
    out = []
    segs = parse(d).segments()
    t = np.linspace(0, 1, n)[:, None]
    for c, k in zip(segs.ctrl, segs.degree):
        c = c[:k + 1]
        pts = sum(math.comb(k, i) * (1 - t) ** (k - i) * t ** i * c[i] for i in range(k + 1))
        out.append(pts)
    return np.concatenate(out)


@pytest.mark.parametrize('tol, t', [(0.25, None), (0.05, None), (0.1, Affine.rotate(20) @ Affine.scale(3)),
                                    (0.5, Affine.scale(0.5))])
def test_round_stroke_of_curve_within_tolerance(tol, t):
    # round joins and caps: the exact stroke is {p : dist(p, curve) <= w/2}
    p = parse(CURVE)
    w = 8.0
    out = stroke(p, width=w, join='round', cap='round', tolerance=tol, transform=t)
    t = t or Affine()
    s = t.max_scale()                               # a similarity: uniform scale s
    curve = t.apply(bezier_points(CURVE))
    rng = np.random.default_rng(1)
    lo, hi = curve.min(0) - w * s, curve.max(0) + w * s
    g = rng.uniform(lo, hi, size=(6000, 2))
    d = cKDTree(curve).query(g)[0]                 # distance to dense curve points
    got = inside(out, g)
    band = tol + 0.01 * s                          # dense-sampling reference error
    assert np.all(got[d < w / 2 * s - band])
    assert not np.any(got[d > w / 2 * s + band])


@pytest.mark.parametrize('w, tol', [(40, 0.25), (40, 0.05), (120, 0.25), (2, 0.25)])
def test_fat_butt_capped_arc_is_annular_sector(w, tol):
    # a quarter circle (one cubic, within 0.027 of the circle of radius 100)
    # stroked with butt caps: exactly the annular sector in the first quadrant.
    # The caps rest on the end chords of the flattening, which must leave the
    # curve along its tangent (within tol / (w/2) radians) for this to hold.
    k = 0.5522847498 * 100
    p = parse('M 100 0 C 100 %r %r 100 0 100' % (k, k))
    out = stroke(p, width=w, tolerance=tol)
    rng = np.random.default_rng(8)
    R, r = 100.0, w / 2
    g = rng.uniform(-r - 5, R + r + 5, size=(20000, 2))
    rho = np.hypot(*g.T)
    exact = (g[:, 0] > 0) & (g[:, 1] > 0) & (np.abs(rho - R) < r)
    margin = np.min([np.abs(g[:, 0]), np.abs(g[:, 1]), np.abs(np.abs(rho - R) - r)], axis=0)
    ok = margin > tol + 0.03
    assert np.array_equal(inside(out, g)[ok], exact[ok])


def test_circle_under_nonuniform_scale_has_right_extent():
    k = 0.5522847498 * 10
    circle = parse('M 10 0 C 10 %r %r 10 0 10 C %r 10 -10 %r -10 0 '
                   'C -10 %r %r -10 0 -10 C %r -10 10 %r 10 0 Z'
                   % (k, k, -k, k, -k, -k, k, -k))
    out = stroke(circle, width=2, transform=Affine.scale(1, 3), tolerance=0.05)
    x0, y0, x1, y1 = out.control_box()
    assert x1 == pytest.approx(11, abs=0.06) and x0 == pytest.approx(-11, abs=0.06)
    assert y1 == pytest.approx(33, abs=0.06) and y0 == pytest.approx(-33, abs=0.06)
    # the inner edge: the hole is the scaled circle of radius 9
    assert not inside(out, [(8.8, 0), (0, 26.5)]).any()
    assert inside(out, [(9.3, 0), (0, 27.9)]).all()


def test_skewed_square_cap_follows_transform():
    t = Affine.skew_x(30)
    p = line((0, 0), (10, 0))
    out = stroke(p, width=2, cap='square', transform=t)
    user = stroke(p, width=2, cap='square')
    assert np.allclose(out.points, t.apply(user.points))


# -- invariances -----------------------------------------------------------------------

def random_polyline(rng, n):
    return np.cumsum(rng.normal(0, 5, size=(n, 2)), axis=0)


@pytest.mark.parametrize('join', ['miter', 'bevel', 'round', 'miter-clip'])
@pytest.mark.parametrize('cap', ['butt', 'square', 'round'])
def test_rotation_180_invariance(join, cap):
    rng = np.random.default_rng(7)
    pts = random_polyline(rng, 8)
    p = line(*pts)
    r = Affine.rotate(180)
    a = stroke(p.transform(r), width=3, join=join, cap=cap, miterlimit=3)
    b = stroke(p, width=3, join=join, cap=cap, miterlimit=3).transform(r)
    g = rng.uniform(pts.min(0) - 20, pts.max(0) + 20, size=(8000, 2))
    assert np.array_equal(inside(a, g), inside(b, g))


@pytest.mark.parametrize('join', ['miter', 'bevel', 'round', 'miter-clip'])
@pytest.mark.parametrize('cap', ['butt', 'square', 'round'])
@pytest.mark.parametrize('closed', [False, True])
def test_reversal_invariance(join, cap, closed):
    rng = np.random.default_rng(11)
    pts = random_polyline(rng, 9)
    a = stroke(line(*pts, closed=closed), width=2.5, join=join, cap=cap, miterlimit=2.5)
    b = stroke(line(*pts[::-1], closed=closed), width=2.5, join=join, cap=cap, miterlimit=2.5)
    g = rng.uniform(pts.min(0) - 10, pts.max(0) + 10, size=(8000, 2))
    ia, ib = inside(a, g), inside(b, g)
    if join == 'round' or cap == 'round':
        # arcs are polygonized from their start: compare outside the tolerance band
        d = dist_to_polyline(g, np.concatenate([pts, pts[:1]]) if closed else pts)
        ok = (d < 1.25 - 0.25) | (d > 1.25 + 0.25)
        assert np.array_equal(ia[ok], ib[ok])
    else:
        assert np.array_equal(ia, ib)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.integers(2, 7), st.floats(0.5, 6), st.booleans())
def test_round_stroke_is_distance_region(seed, n, w, closed):
    # property: with round joins and caps, the filled outline is the set of points
    # within w/2 of the polyline, up to the tolerance
    rng = np.random.default_rng(seed)
    pts = random_polyline(rng, n)
    tol = 0.05
    out = stroke(line(*pts, closed=closed), width=w, join='round', cap='round', tolerance=tol)
    ref = np.concatenate([pts, pts[:1]]) if closed else pts
    g = rng.uniform(pts.min(0) - w, pts.max(0) + w, size=(3000, 2))
    d = dist_to_polyline(g, ref)
    got = inside(out, g)
    assert np.all(got[d < w / 2 - tol])
    assert not np.any(got[d > w / 2 + tol])


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.integers(3, 8), st.floats(0.5, 30),
       st.sampled_from(['miter', 'miter-clip', 'bevel', 'round']), st.floats(1, 6))
def test_stroke_is_union_of_its_two_segment_strokes(seed, n, w, join, limit):
    # property: with butt caps, the stroke of a polyline is the union of the
    # strokes of its consecutive segment pairs (each pair holds one join).  Fat
    # pens on short segments exercise the inner-join pivots.
    rng = np.random.default_rng(seed)
    pts = random_polyline(rng, n)
    kw = dict(width=w, join=join, miterlimit=limit, tolerance=0.05)
    whole = stroke(line(*pts), **kw)
    g = rng.uniform(pts.min(0) - limit * w, pts.max(0) + limit * w, size=(3000, 2))
    ref = np.zeros(len(g), bool)
    for i in range(n - 2):
        ref |= inside(stroke(line(*pts[i:i + 3]), **kw), g)
    got = inside(whole, g)
    if join == 'round':        # arcs are polygonized from different start angles
        d = np.min([np.abs(np.hypot(*(g - q).T) - w / 2) for q in pts], axis=0)
        ok = d > 0.06
        assert np.array_equal(got[ok], ref[ok])
    else:
        assert np.array_equal(got, ref)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.sampled_from(['miter', 'miter-clip', 'bevel', 'round']),
       st.sampled_from(['butt', 'square', 'round']), st.booleans(), st.booleans(),
       st.sampled_from([None, Affine.scale(1, -2), Affine.rotate(40) @ Affine.skew_x(30)]))
def test_random_paths_fill_with_one_sign(seed, join, cap, dashed, closed, t):
    # property: for any path (lines, quadratics, cubics, repeated points, zero
    # length pieces) the outline's winding never takes both signs, and points
    # on the path itself are inside
    rng = np.random.default_rng(seed)
    b = PathBuilder()
    b.moveTo(tuple(rng.uniform(0, 40, 2)))
    for _ in range(rng.integers(1, 6)):
        kind = rng.integers(0, 4)
        pts = [tuple(p) for p in rng.uniform(0, 40, (3, 2)).round(rng.integers(0, 3))]
        if kind == 0:
            b.lineTo(pts[0])
        elif kind == 1:
            b.qCurveTo(pts[0], pts[1])
        elif kind == 2:
            b.curveTo(*pts)
        else:
            b.lineTo(b.current_point)                     # zero-length segment
    if closed:
        b.closePath()
    p = b.path()
    w = float(rng.uniform(0.5, 15))
    kw = dict(width=w, join=join, cap=cap, miterlimit=float(rng.uniform(1, 5)))
    if dashed:
        kw.update(dash=list(rng.uniform(0, 8, rng.integers(1, 4))), dash_offset=float(rng.uniform(-20, 20)))
    out = stroke(p, transform=t, tolerance=0.1, **kw)
    t = t or Affine()
    g = t.apply(rng.uniform(-20, 60, size=(3000, 2)))
    wn = winding(out, g)
    assert np.all(wn >= 0) or np.all(wn <= 0)
    if not dashed:
        # points of the path, away from its two ends (on a butt cap's edge)
        on = bezier_points(p.to_svg(), n=50)
        seg = p.segments()
        ends = np.concatenate([seg.contour_start, seg.contour_end])
        far = np.min([np.hypot(*(on - e).T) for e in ends], axis=0) > 1.0
        assert inside(out, t.apply(on[far])).all()


# -- dashes -----------------------------------------------------------------------------

def dashes_of(pts, dash, offset=0.0, closed=False):
    pts = np.asarray(pts, float)
    pl = DashedLines(pts, np.array([0]), np.array([closed]), np.array([[1.0, 0]]))
    return list(dash_polylines(pl, dash, offset))


def spans_on_x_axis(pieces):
    return [(round(p[0, 0], 9), round(p[-1, 0], 9)) for p, c in pieces]


@pytest.mark.parametrize('offset, expect', [
    (0, [(0, 3), (4, 7), (8, 10)]),
    (1, [(0, 2), (3, 6), (7, 10)]),
    (5, [(0, 2), (3, 6), (7, 10)]),                 # offset wraps (5 = 1 mod 4)
    (-1, [(1, 4), (5, 8), (9, 10)]),                # negative offset wraps
    (-401, [(1, 4), (5, 8), (9, 10)]),
])
def test_dash_pieces_on_a_line(offset, expect):
    assert spans_on_x_axis(dashes_of([(0, 0), (10, 0)], [3, 1], offset)) == expect


def test_odd_dash_array_is_repeated():
    assert spans_on_x_axis(dashes_of([(0, 0), (10, 0)], [2])) == [(0, 2), (4, 6), (8, 10)]
    assert spans_on_x_axis(dashes_of([(0, 0), (14, 0)], [1, 2, 3])) == \
        [(0, 1), (3, 6), (7, 9), (12, 13)]


def test_dash_polylines_accepts_flatten_polylines():
    from raster.geometry.flattening import flatten
    pl = flatten(parse('M 0 0 L 10 0 L 10 10 Z M 20 0 L 30 0'))
    pieces = list(dash_polylines(pl, [5, 2]))
    assert [p.tolist() for p, c in pieces][:2] == [[[0, 0], [5, 0]], [[7, 0], [10, 0], [10, 2]]]
    assert [p.tolist() for p, c in pieces][-2:] == [[[20, 0], [25, 0]], [[27, 0], [30, 0]]]
    with pytest.raises(StrokeError):
        dash_polylines(object(), [1, 1])


def test_dash_runs_around_corners():
    pieces = dashes_of([(0, 0), (10, 0), (10, 10)], [15, 2])
    assert [p.tolist() for p, c in pieces] == [[[0, 0], [10, 0], [10, 5]], [[10, 7], [10, 10]]]


def test_closed_contour_dash_through_the_start_is_joined():
    # perimeter 40, dashes [0, 30] and [35, 40]: the second runs on through
    # the start point into the first, as one dash with a join at (0, 0)
    sq = [(0, 0), (10, 0), (10, 10), (0, 10)]
    pieces = dashes_of(sq, [30, 5], closed=True)
    assert [p.tolist() for p, c in pieces] == [[[0, 5], [0, 0], [10, 0], [10, 10], [0, 10]]]
    assert not any(c for p, c in pieces)
    # the corner at the start point gets its miter, not two butt ends
    out = stroke(line(*sq, closed=True), width=2, dash=[30, 5])
    assert inside(out, [(-0.9, -0.9)])[0]
    # a dash that does not reach the start point stays apart
    pieces = dashes_of(sq, [30, 5], offset=-1, closed=True)
    assert [p.tolist() for p, c in pieces] == [[[1, 0], [10, 0], [10, 10], [0, 10], [0, 9]],
                                               [[0, 4], [0, 0]]]


def test_closed_contour_covered_by_one_dash_stays_closed():
    sq = [(0, 0), (10, 0), (10, 10), (0, 10)]
    pieces = dashes_of(sq, [50, 5], closed=True)
    assert len(pieces) == 1 and pieces[0][1]
    a = stroke(line(*sq, closed=True), width=2, dash=[50, 5], cap='round')
    b = stroke(line(*sq, closed=True), width=2, cap='round')
    assert a == b


def test_solid_dash_arrays_give_the_solid_stroke():
    p = line((0, 0), (10, 0), (10, 10))
    solid = stroke(p, width=2)
    for dash in ([1, -1], [0, 0], []):
        assert stroke(p, width=2, dash=dash) == solid


def test_dashes_restart_for_every_subpath():
    p = parse('M 0 0 L 10 0 M 0 5 L 10 5')
    out = stroke(p, width=1, dash=[3, 1], dash_offset=1)
    polys = polygons(out)
    xs = sorted((round(q[:, 0].min(), 9), round(q[:, 0].max(), 9), round(q[:, 1].mean())) for q in polys)
    assert xs == [(0, 2, 0), (0, 2, 5), (3, 6, 0), (3, 6, 5), (7, 10, 0), (7, 10, 5)]


def test_zero_length_dashes_draw_oriented_dots():
    p = line((0, 0), (10, 10))
    step = 10 * math.sqrt(2) / 4
    out = stroke(p, width=2, dash=[0, step], cap='square')
    polys = polygons(out)
    assert len(polys) == 5                             # at s = 0, step, .., 4 step
    for q in polys:
        assert abs(shoelace(q)) == pytest.approx(4.0)
        e = q[1] - q[0]                                # sides along the 45-degree path
        assert abs(abs(e[0]) - abs(e[1])) < 1e-9
    assert len(stroke(p, width=2, dash=[0, step], cap='butt')) == 0
    dots = stroke(p, width=2, dash=[0, step], cap='round')
    assert len(polygons(dots)) == 5


def reference_dash_length(L, pattern, offset):
    """Measure of {s in [0, L] : (s + offset) mod P is in a dash}: interval sums."""
    pat = dash_pattern(pattern)
    P = pat.sum()
    cum = np.concatenate([[0], np.cumsum(pat)])
    total = 0.0
    k0 = math.floor(offset / P) - 1
    for k in range(k0, k0 + int(L / P) + 3):
        for i in range(0, len(pat), 2):
            a = k * P + cum[i] - offset
            b = k * P + cum[i + 1] - offset
            total += max(0.0, min(b, L) - max(a, 0.0))
    return total


def piece_length(p):
    return float(np.hypot(*np.diff(p, axis=0).T).sum())


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.integers(2, 12),
       st.lists(st.floats(0.0, 5.0), min_size=1, max_size=5).filter(lambda d: sum(d) > 0.1),
       st.floats(-50, 50))
def test_dash_lengths_property(seed, n, dash, offset):
    rng = np.random.default_rng(seed)
    pts = random_polyline(rng, n)
    L = float(np.hypot(*np.diff(pts, axis=0).T).sum())
    pieces = dashes_of(pts, dash, offset)
    got = sum(piece_length(p) for p, c in pieces)
    assert got == pytest.approx(reference_dash_length(L, dash, offset), abs=1e-7 * (1 + L))
    # every dash vertex lies on the polyline
    if pieces:
        allp = np.concatenate([p for p, c in pieces])
        assert dist_to_polyline(allp, pts).max() < 1e-7 * (1 + L)


def test_dashed_stroke_is_union_of_dash_strokes():
    p = line((0, 0), (20, 0), (20, 15))
    out = stroke(p, width=2, dash=[6, 3], cap='round', join='round', tolerance=0.02)
    pieces = dashes_of(p.points, [6, 3])
    g = grid(-3, -3, 23, 18, 0.1)
    d = np.min([dist_to_polyline(g, q) for q, c in pieces], axis=0)
    got = inside(out, g)
    assert np.all(got[d < 1 - 0.03]) and not np.any(got[d > 1 + 0.03])


def test_large_dashed_polyline_is_vectorized():
    rng = np.random.default_rng(3)
    pts = random_polyline(rng, 10001)                  # 10,000 segments
    L = float(np.hypot(*np.diff(pts, axis=0).T).sum())
    out = stroke(line(*pts), width=1, dash=[2, 1], cap='butt', join='bevel')
    assert len(out) > 10000
    pieces = dashes_of(pts, [2, 1])
    assert len(pieces) == pytest.approx(L / 3, abs=2)
    # 10,000 separate dashed contours
    b = PathBuilder()
    for i in range(10000):
        b.moveTo((0, i)); b.lineTo((10, i))
    out = stroke(b.path(), width=0.5, dash=[4, 2])
    assert len(polygons(out)) == 20000


def test_absurd_dash_count_raises_limit_error():
    with pytest.raises(LimitError):
        stroke(line((0, 0), (1e6, 0)), width=1, dash=[1e-9, 1e-9])


def test_absurd_round_join_resolution_raises_limit_error():
    rng = np.random.default_rng(5)
    p = line(*random_polyline(rng, 2000))
    with pytest.raises(LimitError):
        stroke(p, width=1e9, join='round', tolerance=1e-6)


# -- hairlines -----------------------------------------------------------------------

def test_hairline_scale():
    assert hairline_scale(StrokeStyle(width=0.5)) == 0.5
    assert hairline_scale(StrokeStyle(width=1.0)) is None
    assert hairline_scale(StrokeStyle(width=2.0), Affine.scale(0.25)) == 0.5
    # mean scale sqrt(|det|) = 0.5: device width exactly 1 px, no hairline
    assert hairline_scale(StrokeStyle(width=2.0), Affine.scale(1, 0.25)) is None
    assert hairline_scale(StrokeStyle(width=1.9), Affine.scale(1, 0.25)) == pytest.approx(0.95)
    assert hairline_scale(StrokeStyle(width=0.0)) is None
    assert hairline_scale(StrokeStyle(width=1.0), Affine.scale(0)) is None
    assert hairline_scale(StrokeStyle(width=0.3), Affine.scale(2, 0.5)) == pytest.approx(0.3)


# -- rasterized coverage (raster.pixels.scan) ------------------------------------------------

def rasterize(path, width, height):
    from raster.pixels.scan import coverage
    return coverage(edges(path), width, height, fill_rule='nonzero').full(width, height)


def test_rasterized_line_areas():
    p = line((5.3, 10.7), (25.3, 10.7))             # L = 20, off the pixel grid
    butt = rasterize(stroke(p, width=4), 40, 24).sum(dtype=np.float64)
    square = rasterize(stroke(p, width=4, cap='square'), 40, 24).sum(dtype=np.float64)
    rnd = rasterize(stroke(p, width=4, cap='round', tolerance=0.01), 40, 24).sum(dtype=np.float64)
    assert butt == pytest.approx(80, abs=1e-3)
    assert square == pytest.approx(96, abs=1e-3)
    assert rnd == pytest.approx(80 + 4 * math.pi, abs=1e-3)


def test_rasterized_rotated_line_area():
    p = line((5, 5), (25, 25))
    L = 20 * math.sqrt(2)
    a = rasterize(stroke(p, width=3), 32, 32).sum(dtype=np.float64)
    assert a == pytest.approx(3 * L, abs=1e-3)


def test_rasterized_self_overlapping_stroke_is_union():
    # one path crossing itself: the overlap square counts once
    p = parse('M 2 10 L 18 10 M 10 2 L 10 18')
    a = rasterize(stroke(p, width=2), 20, 20).sum(dtype=np.float64)
    assert a == pytest.approx(2 * 16 * 2 - 4, abs=1e-3)
    # a zig-zag whose inner joins overlap the neighbouring segments
    q = line((2, 2), (30, 3), (2, 6), (30, 9))
    cov = rasterize(stroke(q, width=5, join='miter', miterlimit=10), 40, 16)
    assert cov.max() <= 1.0 + 1e-6


def test_rasterized_rectangle_is_outer_minus_inner():
    p = line((4.5, 4.5), (34.5, 4.5), (34.5, 24.5), (4.5, 24.5), closed=True)
    a = rasterize(stroke(p, width=3), 40, 30).sum(dtype=np.float64)
    assert a == pytest.approx(33 * 23 - 27 * 17, abs=1e-3)


def reference_coverage(pts, hw, width, height, ss=8, closed=False):
    """Supersampled coverage of {p : dist(p, polyline) <= hw} (round joins/caps)."""
    o = (np.arange(ss) + 0.5) / ss
    X, Y = np.meshgrid(np.arange(width)[:, None] + o[None, :], np.arange(height)[:, None] + o[None, :])
    g = np.stack([X.ravel(), Y.ravel()], axis=1)
    ref = np.concatenate([pts, pts[:1]]) if closed else pts
    d = np.concatenate([dist_to_polyline(g[i:i + 20000], ref) for i in range(0, len(g), 20000)])
    inside_ = (d <= hw).reshape(height * ss, width * ss)
    return inside_.reshape(height, ss, width, ss).mean(axis=(1, 3))


@pytest.mark.parametrize('seed', [0, 1, 2])
def test_rasterized_round_stroke_matches_supersampled_reference(seed):
    rng = np.random.default_rng(seed)
    pts = rng.uniform(6, 42, size=(7, 2))
    w = rng.uniform(1, 6)
    closed = bool(seed % 2)
    cov = rasterize(stroke(line(*pts, closed=closed), width=w, join='round', cap='round'), 48, 48)
    ref = reference_coverage(pts, w / 2, 48, 48, closed=closed)
    err = np.abs(cov - ref)
    touched = (cov > 0) | (ref > 0)
    assert err[touched].mean() < 0.05              # measured 0.004 - 0.008
    assert err.max() < 0.25


def test_rasterized_dashed_curve_matches_reference():
    p = parse('M 4 30 C 20 -10 40 70 60 20')
    # dash ends drift along a curve by the arc-length error of the flattening
    # (about 0.27 px over this curve at tolerance 0.25), hence tolerance 0.1
    out = stroke(p, width=3, dash=[7, 4], dash_offset=2, cap='round', join='round', tolerance=0.1)
    cov = rasterize(out, 64, 48)
    # reference: the dash pieces of a fine flattening of the same curve
    curve = bezier_points('M 4 30 C 20 -10 40 70 60 20', n=3000)
    pieces = dashes_of(curve, [7, 4], 2)
    o = (np.arange(6) + 0.5) / 6
    X, Y = np.meshgrid(np.arange(64)[:, None] + o[None, :], np.arange(48)[:, None] + o[None, :])
    g = np.stack([X.ravel(), Y.ravel()], axis=1)
    d = np.min([cKDTree(np.concatenate([q, (q[:-1] + q[1:]) / 2])).query(g)[0]
                for q, c in pieces], axis=0)
    ref = (d <= 1.5).reshape(48 * 6, 64 * 6).reshape(48, 6, 64, 6).mean(axis=(1, 3))
    err = np.abs(cov - ref)
    touched = (cov > 0) | (ref > 0)
    assert err[touched].mean() < 0.05              # measured 0.027
    assert abs(cov.sum() - ref.sum()) < 0.01 * ref.sum()


# -- against resvg (the reference renderer) ----------------------------------------------

ZIGZAG = 'M 10 80 L 30 20 L 50 80 L 70 25 L 90 80'
SQUARE = 'M 10 10 L 90 10 L 90 90 L 10 90 Z'
RESVG_CASES = [
    (ZIGZAG, dict(width=8, join='miter', miterlimit=4), None),
    (ZIGZAG, dict(width=8, join='miter', miterlimit=2), None),
    (ZIGZAG, dict(width=8, join='miter-clip', miterlimit=2), None),
    (ZIGZAG, dict(width=8, join='round', cap='round'), None),
    (ZIGZAG, dict(width=8, join='bevel', cap='square'), None),
    (SQUARE, dict(width=10, dash=[40, 20], dash_offset=-300), None),     # dash through start
    (SQUARE, dict(width=6, dash=[7, 5, 2], dash_offset=3, cap='round'), None),
    ('M 90 50 C 90 72 72 90 50 90', dict(width=30), None),               # fat butt arc
    ('M 20 20 Z M 50 50 L 50 50 M 80 30 Z', dict(width=12, cap='round'), None),
    ('M 20 20 Z M 50 50 L 50 50 M 80 30 Z', dict(width=12, cap='square'), None),
    ('M 5 50 C 30 -20 60 120 95 40', dict(width=5, dash=[9, 4], cap='round', join='round'), None),
    ('M 30 0 C 30 16.57 16.57 30 0 30 C -16.57 30 -30 16.57 -30 0 C -30 -16.57 -16.57 -30 0 -30 '
     'C 16.57 -30 30 -16.57 30 0 Z', dict(width=4),
     Affine.translate(50, 50) @ Affine.scale(1.2, 0.5) @ Affine.rotate(30)),
    ('M 10 50 L 60 50 L 10 52', dict(width=10, miterlimit=10), None),     # sharp turn
    ('M 10 50 L 90 50 L 10 50', dict(width=10, join='round'), None),      # cusp
]


def resvg_alpha(d, kw, t, size=100):
    import io
    import resvg_py
    from PIL import Image
    attrs = 'stroke-width="%r" stroke-linejoin="%s" stroke-linecap="%s" stroke-miterlimit="%r"' % (
        kw.get('width', 1.0), kw.get('join', 'miter'), kw.get('cap', 'butt'), kw.get('miterlimit', 4.0))
    if 'dash' in kw:
        attrs += ' stroke-dasharray="%s" stroke-dashoffset="%r"' % (
            ' '.join(map(repr, kw['dash'])), kw.get('dash_offset', 0.0))
    tr = '' if t is None else ' transform="matrix(%r %r %r %r %r %r)"' % tuple(t)
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d"><path d="%s" '
           'fill="none" stroke="black" %s%s/></svg>' % (size, size, d, attrs, tr))
    png = resvg_py.svg_to_bytes(svg_string=svg)
    return np.asarray(Image.open(io.BytesIO(bytes(png))).convert('RGBA'))[..., 3] / 255.0


@pytest.mark.parametrize('d, kw, t', RESVG_CASES)
def test_matches_resvg(d, kw, t):
    ref = resvg_alpha(d, kw, t)
    cov = rasterize(stroke(parse(d), transform=t, **kw), 100, 100)
    err = np.abs(cov - ref)
    touched = (cov > 0) | (ref > 0)
    assert err[touched].mean() < 0.05                # measured <= 0.037
    assert err.max() < 0.4                           # measured <= 0.34
    assert cov.sum() == pytest.approx(ref.sum(), rel=0.025)   # measured <= 2.1 %


@pytest.mark.parametrize('join', ['miter', 'bevel', 'miter-clip'])
@pytest.mark.parametrize('w, tol, t', [(2, 0.25, None), (16, 0.05, None), (8, 0.1, Affine.scale(3)),
                                       (0.5, 0.01, Affine.rotate(33) @ Affine.scale(5))])
def test_circle_of_cubics_with_sharp_joins_is_annulus_within_tolerance(join, w, tol, t):
    # a circle of four cubics (the standard kappa approximation, radius 10)
    # meets itself with one tangent at the cubic ends, so the stroke with
    # any join is the annulus between radii 10 -+ w/2: every outline
    # vertex lies within tol (device px) of one of the two circles (up to
    # the kappa error of the cubics, 2.7e-4 of the radius)
    k = 10 * 0.5522847498
    circle = Path.from_arrays([MOVE, 3, 3, 3, 3, CLOSE], [
        (10, 0), (10, k), (k, 10), (0, 10), (-k, 10), (-10, k), (-10, 0),
        (-10, -k), (-k, -10), (0, -10), (k, -10), (10, -k), (10, 0)])
    t = t or Affine()
    out = stroke(circle, join=join, width=w, transform=t, tolerance=tol)
    q = t.inverse().apply(out.points)
    rad = np.hypot(q[:, 0], q[:, 1])
    s = t.min_scale()
    err = np.minimum(np.abs(rad - (10 + w / 2)), np.abs(rad - (10 - w / 2)))
    assert np.all(err * s <= tol + 2.7e-3 * s)
    assert np.any(rad > 10 + w / 2 - tol / s) and np.any(rad < 10 - w / 2 + tol / s)


# -- open contours ending where they started ------------------------------------

_RING = ('M 3 0 C 3 1.657 1.657 3 0 3 C -1.657 3 -3 1.657 -3 0 '
         'C -3 -1.657 -1.657 -3 0 -3 C 1.657 -3 3 -1.657 3 0')


@pytest.mark.parametrize('scale', [1.5, 6.0, 25.0])
def test_open_smooth_ring_with_butt_caps_is_the_closed_ring(scale):
    """Invariance: a curve that ends at its start with the tangent it
    started with (a circle drawn without Z, as vega writes its symbols),
    stroked with butt caps, is the stroke of the closed circle: same
    outline loops, and the annulus' area is met within the flattening
    (the open contour used to leave a notch at the seam)."""
    t = Affine(scale, 0, 0, scale, 0, 0)
    st_ = StrokeStyle(width=2.0, cap='butt')
    o_open = stroke(parse(_RING), st_, transform=t, tolerance=0.05)
    o_closed = stroke(parse(_RING + ' Z'), st_, transform=t, tolerance=0.05)
    assert o_open.verbs.tolist() == o_closed.verbs.tolist()
    assert np.allclose(o_open.points, o_closed.points, atol=1e-9)
    # the kappa circle's radius wobbles by 0.03 %: the annulus of radii
    # 3 -+ 1 (times the scale) within that and the tolerance
    area = sum(shoelace(p) for p in polygons(o_open))
    exact = math.pi * ((4 * scale) ** 2 - (2 * scale) ** 2)
    assert abs(abs(area) - exact) <= 2 * math.pi * 6 * scale * (0.05 + 3e-4 * scale) + 1e-9


@pytest.mark.parametrize('d,cap', [
    (_RING, 'square'),                                  # caps protrude: kept
    ('M 3 0 L 0 3 C -1.657 3 -3 1.657 -3 0 C -3 -1.657 -1.657 -3 0 -3 '
     'C 1.657 -3 3 -1.657 3 0', 'butt'),                # a corner at the seam: kept
])
def test_open_ring_stays_open_when_the_seam_shows(d, cap):
    """An open contour ending at its start keeps its caps when they show:
    square caps, or a corner at the seam (no join there)."""
    st_ = StrokeStyle(width=1.0, cap=cap)
    o_open = stroke(parse(d), st_, tolerance=0.05)
    o_closed = stroke(parse(d + ' Z'), st_, tolerance=0.05)
    assert len(polygons(o_open)) == 1
    assert len(polygons(o_closed)) == 2


# -- long outlines are built in parts ------------------------------------------

def _random_polylines(rng, n_contours, n_points, closed):
    b = PathBuilder()
    for _ in range(n_contours):
        pts = rng.uniform(4, 60, (n_points, 2))
        b.moveTo(pts[0])
        for i, p in enumerate(pts[1:]):
            if i % 3 == 2:
                b.qCurveTo(rng.uniform(4, 60, 2), p)
            else:
                b.lineTo(p)
        if closed:
            b.closePath()
        else:
            b.endPath()
    return b.path()


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.integers(2, 9), st.booleans(),
       st.sampled_from(['butt', 'round', 'square']),
       st.sampled_from(['miter', 'round', 'bevel', 'miter-clip', 'arcs']))
def test_outline_in_parts_covers_the_same_pixels(seed, block, closed, cap, join):
    # an outline longer than _OUTLINE_POINTS is built in parts (windows of
    # a long contour share a segment, rings are unrolled): the filled
    # stroke is the same, pixel for pixel within 1/255 of coverage
    from raster.geometry import stroking
    from raster.pixels.scan import path_coverage
    rng = np.random.default_rng(seed)
    path = _random_polylines(rng, int(rng.integers(1, 4)), int(rng.integers(2, 30)), closed)
    style = StrokeStyle(width=float(rng.uniform(0.5, 6.0)), cap=cap, join=join)
    whole = stroke(path, style)
    saved = stroking._OUTLINE_POINTS
    stroking._OUTLINE_POINTS = block
    try:
        parts = stroke(path, style)
    finally:
        stroking._OUTLINE_POINTS = saved
    a = path_coverage(whole, 64, 64).full(64, 64)
    b = path_coverage(parts, 64, 64).full(64, 64)
    assert np.abs(a - b).max() <= 1 / 255


def test_a_long_stroke_is_outlined_in_parts(monkeypatch):
    from raster.geometry import stroking
    from raster.pixels.scan import path_coverage
    rng = np.random.default_rng(3)
    path = _random_polylines(rng, 2, 400, True)
    style = StrokeStyle(width=2.0, cap='round', join='miter')
    whole = stroke(path, style)
    seen = []
    part = stroking._outline_part

    def counted(lines, *a):
        seen.append(len(lines.points))
        return part(lines, *a)
    monkeypatch.setattr(stroking, '_outline_part', counted)
    monkeypatch.setattr(stroking, '_OUTLINE_POINTS', 64)
    cut = stroke(path, style)
    assert len(seen) > 10 and max(seen) <= 66
    a, b = (path_coverage(p, 64, 64).full(64, 64) for p in (whole, cut))
    assert np.abs(a - b).max() <= 1 / 255
