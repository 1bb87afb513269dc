"""Tests of raster.geometry.bounds (raster.bbox) and of the segment bounds
of raster.geometry.bezier: exact boxes against dense sampling, analytic
shapes, the convex-hull property, transforms, degenerate cases, BoundsPen.
The root solvers have their own tests (test_roots.py)."""

import math
from math import comb

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import raster
from raster.errors import PathError
from raster.geometry.bezier import segment_bounds, segment_extrema
from raster.geometry.bounds import bbox, bezier_bbox
from raster.geometry.path import Path
from raster.geometry.pens import BoundsPen, PathBuilder, RecordingPen
from raster.geometry.transform import Affine


def bez_eval(ctrl, t):
    ctrl = np.asarray(ctrl, float)
    n = len(ctrl) - 1
    t = np.asarray(t, float)[:, None]
    return sum(comb(n, i) * (1 - t) ** (n - i) * t ** i * ctrl[i] for i in range(n + 1))


def sampled_box(ctrl, T=200001):
    p = bez_eval(ctrl, np.linspace(0, 1, T))
    return p.min(0), p.max(0)


def assert_tight(lo, hi, slo, shi, rel=1e-9):
    """The sampled box is inside the exact box and touches it."""
    size = max(float(np.max(hi - lo)), 1.0)
    eps = rel * size
    assert np.all(slo >= lo - eps) and np.all(shi <= hi + eps)
    assert np.all(slo - lo <= eps) and np.all(hi - shi <= eps), (lo, hi, slo, shi)


def path_of(ctrl):
    b = PathBuilder()
    b.moveTo(ctrl[0])
    if len(ctrl) == 2:
        b.lineTo(ctrl[1])
    elif len(ctrl) == 3:
        b.qCurveTo(ctrl[1], ctrl[2])
    else:
        b.curveTo(ctrl[1], ctrl[2], ctrl[3])
    return b.path()


# -- exact boxes against sampling ------------------------------------------------------
@pytest.mark.parametrize('deg', [2, 3])
def test_random_segments_against_sampling(deg):
    rng = np.random.default_rng(deg)
    for _ in range(20):
        ctrl = rng.uniform(-1000, 1000, (deg + 1, 2))
        lo, hi = bezier_bbox(ctrl)
        slo, shi = sampled_box(ctrl)
        assert_tight(lo, hi, slo, shi)
        b = bbox(path_of(ctrl))
        assert b == (lo[0], lo[1], hi[0], hi[1])


def test_vectorized_segment_bounds_match_single():
    rng = np.random.default_rng(11)
    S = 200
    ctrl = rng.uniform(0, 100, (S, 4, 2))
    deg = rng.integers(1, 4, S)
    for k in (1, 2):
        ctrl[deg == k, k + 1:] = ctrl[deg == k, k:k + 1]
    lo, hi = segment_bounds(ctrl, deg)
    for s in range(0, S, 13):
        l1, h1 = bezier_bbox(ctrl[s, :deg[s] + 1])
        assert np.array_equal(lo[s], l1) and np.array_equal(hi[s], h1)


def test_extrema_parameters_are_stationary():
    rng = np.random.default_rng(12)
    ctrl = rng.uniform(0, 100, (100, 4, 2))
    t = segment_extrema(ctrl, np.full(100, 3))
    assert t.shape == (100, 2, 2)
    ok = ~np.isnan(t)
    assert np.all((t[ok] > 0) & (t[ok] < 1)) and ok.sum() > 50
    # derivative of the cubic at t along that axis is ~0
    s, ax, j = np.nonzero(ok)
    tt = t[s, ax, j]
    p = ctrl[s, :, ax]
    d = 3 * ((1 - tt) ** 2 * (p[:, 1] - p[:, 0]) + 2 * tt * (1 - tt) * (p[:, 2] - p[:, 1])
             + tt ** 2 * (p[:, 3] - p[:, 2]))
    assert np.all(np.abs(d) <= 1e-9 * np.abs(p).max(1) * 10)


@pytest.mark.parametrize('d', [
    'M 10 20 A 30 15 20 1 1 50 60',
    'M 0 0 A 100 100 0 0 1 100 100 A 50 80 -30 1 0 -20 40 Z',
    'M 5 5 Q 40 -30 80 5 T 120 40 C 150 80 60 90 100 120 S 0 0 5 5',
])
def test_arcs_and_mixed_paths_against_sampling(d):
    p = raster.parse_path(d)
    seg = p.segments()
    pts = []
    for c, k in zip(seg.ctrl, seg.degree):
        pts.append(bez_eval(c[:k + 1], np.linspace(0, 1, 40001)))
    pts = np.concatenate(pts)
    lo = np.array(bbox(p)[:2])
    hi = np.array(bbox(p)[2:])
    assert_tight(lo, hi, pts.min(0), pts.max(0))


# -- convex hull property and invariances -------------------------------------------------
coord = st.floats(-1e4, 1e4, allow_nan=False)
pt = st.tuples(coord, coord)


@settings(max_examples=200, deadline=None)
@given(st.lists(pt, min_size=2, max_size=4))
def test_box_inside_control_box_and_contains_ends(ctrl):
    ctrl = np.array(ctrl)
    lo, hi = bezier_bbox(ctrl)
    eps = 1e-12 * (1 + np.abs(ctrl).max())
    assert np.all(lo >= ctrl.min(0) - eps) and np.all(hi <= ctrl.max(0) + eps)
    for end in (ctrl[0], ctrl[-1]):
        assert np.all(lo <= end) and np.all(end <= hi)
    # sampled points lie inside
    s = bez_eval(ctrl, np.linspace(0, 1, 257))
    assert np.all(s >= lo - eps) and np.all(s <= hi + eps)


@settings(max_examples=100, deadline=None)
@given(st.lists(pt, min_size=4, max_size=4))
def test_reversal_and_translation_invariance(ctrl):
    ctrl = np.array(ctrl)
    lo, hi = bezier_bbox(ctrl)
    lo2, hi2 = bezier_bbox(ctrl[::-1])
    tol = 1e-9 * (1 + np.abs(ctrl).max())
    assert np.allclose(lo, lo2, rtol=0, atol=tol) and np.allclose(hi, hi2, rtol=0, atol=tol)
    lo3, hi3 = bezier_bbox(ctrl + [128.0, -64.0])
    assert np.allclose(lo3, lo + [128, -64], rtol=0, atol=tol)
    assert np.allclose(hi3, hi + [128, -64], rtol=0, atol=tol)


# -- analytic shapes -------------------------------------------------------------------
def test_rotated_ellipse():
    # ellipse rx=2, ry=1 rotated by 45 degrees: x(t) = 2 cos t cos45 - sin t sin45,
    # half-width sqrt(rx^2 cos^2 + ry^2 sin^2) = sqrt((4 + 1) / 2)
    p = raster.parse_path('M 2 0 A 2 1 0 1 1 -2 0 A 2 1 0 1 1 2 0 Z', tolerance=1e-12)
    hw = math.sqrt(2.5)
    b = bbox(p, transform=Affine.rotate(45))
    assert b == pytest.approx((-hw, -hw, hw, hw), abs=1e-9)
    # the transformed box is not the box of the transformed box
    naive = bbox(p)
    assert naive == pytest.approx((-2, -1, 2, 1), abs=1e-9)
    assert b[2] < math.hypot(2, 1) * 0.99


def test_transform_applies_to_control_points():
    rng = np.random.default_rng(13)
    ctrl = rng.uniform(0, 50, (4, 2))
    p = path_of(ctrl)
    t = Affine.rotate(33) @ Affine.scale(2, 0.5) @ Affine.skew_x(10)
    assert bbox(p, transform=t) == bbox(p.transform(t))


def test_circle_box():
    p = raster.parse_path('M 110 50 A 60 60 0 1 1 -10 50 A 60 60 0 1 1 110 50', tolerance=1e-12)
    assert bbox(p) == pytest.approx((-10, -10, 110, 110), abs=1e-9)


def test_cubic_arch_is_analytic():
    # B(t) = (0,0)(0,4)(4,4)(4,0): y(t) = 12 t (1 - t), max 3 at t = 1/2
    assert bbox(path_of(np.array([[0, 0], [0, 4], [4, 4], [4, 0]], float))) == (0, 0, 4, 3)


# -- degenerate cases -------------------------------------------------------------------
def test_quadratic_derivative_a_zero():
    # cubic whose derivative's t^2 coefficient vanishes: -p0 + 3p1 - 3p2 + p3 = 0
    # in y (p = 0, 1, 2, 3 -> a = 0) and x has a ~ 1e-16 tiny leading term
    ctrl = np.array([[0, 0], [10, 1], [10 + 1e-15, 2], [0, 3]], float)
    lo, hi = bezier_bbox(ctrl)
    slo, shi = sampled_box(ctrl)
    assert_tight(lo, hi, slo, shi)
    assert hi[0] == pytest.approx(7.5)   # x(t) = 30 t (1 - t), max 7.5


def test_straight_line_cubics():
    # collinear cubic overshooting its end points: x(t) on a line
    ctrl = np.array([[0, 0], [30, 30], [-40, -40], [10, 10]], float)
    lo, hi = bezier_bbox(ctrl)
    slo, shi = sampled_box(ctrl)
    assert_tight(lo, hi, slo, shi)
    assert lo[0] < -8 and hi[0] == 10      # overshoots backwards only
    # evenly spaced straight cubic: box = end points
    lo, hi = bezier_bbox([[0, 0], [1, 2], [2, 4], [3, 6]])
    assert lo.tolist() == [0, 0] and hi.tolist() == [3, 6]


@pytest.mark.parametrize('scale', [1e-200, 1e-9, 1e9, 1e200])
def test_scale_invariance_at_extreme_magnitudes(scale):
    # cubic arch (0,0) (0,4) (4,4) (4,0): box (0, 0, 4, 3), scaled
    ctrl = np.array([[0, 0], [0, 4], [4, 4], [4, 0]], float) * scale
    lo, hi = bezier_bbox(ctrl)
    assert lo.tolist() == [0, 0]
    assert hi == pytest.approx([4 * scale, 3 * scale], rel=1e-12)
    lo, hi = bezier_bbox(ctrl[:3])                    # quadratic (0,0)(0,4)(4,4)
    assert hi == pytest.approx([4 * scale, 4 * scale], rel=1e-12)


def test_coincident_points_and_lone_points():
    assert bbox(path_of(np.array([[5, 5]] * 4, float))) == (5, 5, 5, 5)
    b = PathBuilder(); b.moveTo((7, 8)); b.closePath(); b.moveTo((100, 100))
    b.moveTo((0, 1)); b.lineTo((2, 3))
    assert bbox(b.path()) == (0, 1, 7, 8)     # M Z counts, lone M does not


def test_empty_path_raises():
    with pytest.raises(PathError):
        bbox(Path.empty())
    b = PathBuilder(); b.moveTo((1, 1))
    with pytest.raises(PathError):
        bbox(b.path())


def test_high_degree_bezier():
    rng = np.random.default_rng(14)
    for n in (4, 5, 7):
        for _ in range(5):
            ctrl = rng.uniform(-100, 100, (n + 1, 2))
            lo, hi = bezier_bbox(ctrl)
            slo, shi = sampled_box(ctrl)
            assert_tight(lo, hi, slo, shi, rel=1e-8)
    lo, hi = bezier_bbox(rng.uniform(0, 1, (6, 3)))
    assert lo.shape == (3,)
    assert [x.tolist() for x in bezier_bbox([[1, 2]])] == [[1, 2], [1, 2]]


@pytest.mark.parametrize('bad', [[[0, np.nan], [1, 1]], [], [[['x']]], 'abc'])
def test_bezier_bbox_bad_input(bad):
    with pytest.raises(PathError):
        bezier_bbox(bad)


def test_non_finite_after_transform():
    with np.errstate(over='ignore'), pytest.raises(PathError):
        bbox(Path.polygon([[0, 0], [1e300, 1]]), transform=Affine.scale(1e300))


# -- stroke-aware box -------------------------------------------------------------------
def test_stroke_box():
    sq = Path.polygon([(0, 0), (10, 0), (10, 10), (0, 10)])
    b = bbox(sq, stroke={'width': 2}, tolerance=0.01)
    assert b == pytest.approx((-1, -1, 11, 11), abs=0.01)
    # round cap on an open line: extends by the half-width beyond the ends
    ln = Path.polygon([(0, 0), (10, 0)], closed=False)
    b = bbox(ln, stroke={'width': 4, 'cap': 'round'}, tolerance=0.01)
    assert b == pytest.approx((-2, -2, 12, 2), abs=0.01)
    # device space: the stroke box follows the transform
    b = bbox(ln, transform=Affine.scale(3), stroke={'width': 4, 'cap': 'butt'}, tolerance=0.01)
    assert b == pytest.approx((0, -6, 30, 6), abs=0.01)
    # zero width draws nothing: the fill box
    assert bbox(ln, stroke={'width': 0}) == (0, 0, 10, 0)
    # a style object works as well as a dict
    from raster.geometry.stroking import StrokeStyle
    b = bbox(ln, stroke=StrokeStyle(width=4, cap='square'), tolerance=0.01)
    assert b == pytest.approx((-2, -2, 12, 2), abs=0.01)


# -- BoundsPen ----------------------------------------------------------------------------
def test_bounds_pen_matches_bbox_and_forwards():
    p = raster.parse_path('M 5 5 Q 40 -30 80 5 T 120 40 C 150 80 60 90 100 120 Z M 200 200 Z')
    rec = RecordingPen()
    pen = BoundsPen(rec)
    p.draw(pen)
    assert pen.bounds == bbox(p)
    assert [name for name, _ in rec.value][:3] == ['moveTo', 'qCurveTo', 'qCurveTo']


def test_bounds_pen_truetype_quadratics():
    pen = BoundsPen()
    assert pen.bounds is None
    pen.moveTo((0, 0))
    assert pen.bounds is None            # a move alone draws nothing
    pen.qCurveTo((0, 10), (10, 10), (10, 0))   # implied on-curve (5, 10)
    ref = PathBuilder(); ref.moveTo((0, 0)); ref.qCurveTo((0, 10), (10, 10), (10, 0))
    assert pen.bounds == bbox(ref.path())
    with pytest.raises(PathError):
        BoundsPen().lineTo((1, 1))
    with pytest.raises(PathError):
        pen.curveTo()
    # curveTo with two points is a quadratic (fontTools' pen protocol)
    a, b = BoundsPen(), BoundsPen()
    for q, call in ((a, 'curveTo'), (b, 'qCurveTo')):
        q.moveTo((0, 0))
        getattr(q, call)((5, -8), (10, 0))
    assert a.bounds == b.bounds == (0.0, -4.0, 10.0, 0.0)


def test_public_name():
    """raster.bbox is the function; no module of that name shadows it
    (the function lives in raster.geometry.bounds)."""
    import importlib.util
    assert raster.bbox is bbox
    assert importlib.util.find_spec('raster.bbox') is None
    import subprocess
    import sys
    code = ('import raster.geometry.bounds; from raster.geometry.bounds import bbox; '
            'import raster; assert raster.bbox is bbox')
    subprocess.run([sys.executable, '-c', code], check=True)


def test_bbox_rejects_non_paths():
    with pytest.raises(PathError):
        bbox('M 0 0 L 1 1')


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(1, 3), st.lists(pt, min_size=3, max_size=3)),
                min_size=1, max_size=6),
       st.sampled_from([0.05, 0.5]))
def test_consistent_with_flattening(segs, tol):
    # flattened vertices are curve points: inside the exact box; the
    # polyline is within tol of the curve: its box is within tol of the
    # exact box
    from raster.geometry.flattening import flatten
    b = PathBuilder()
    b.moveTo((0, 0))
    for deg, pts in segs:
        if deg == 1:
            b.lineTo(pts[0])
        elif deg == 2:
            b.qCurveTo(pts[0], pts[1])
        else:
            b.curveTo(*pts)
    p = b.path()
    box = np.array(bbox(p))
    fp = flatten(p, tol).points
    fbox = np.r_[fp.min(0), fp.max(0)]
    eps = 1e-9 * (1 + np.abs(box).max())
    assert np.all(fbox[:2] >= box[:2] - eps) and np.all(fbox[2:] <= box[2:] + eps)
    assert np.all(fbox[:2] <= box[:2] + tol + eps) and np.all(fbox[2:] >= box[2:] - tol - eps)
