"""Tests of raster.curves.bezier: closed forms worked by hand, hypothesis
properties of Bezier curves, and the shared vocabulary on PiecewiseBezier."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.spatial import ConvexHull

from raster.geometry.bounds import bezier_bbox
from raster.curves import (Bezier, PiecewiseBezier, bernstein, bernstein_matrix, CurveError,
                           convex_hull)
from raster.errors import RasterError
from raster.geometry.pens import RecordingPen

# The cubic used for the hand-worked answers:
#   P = (0,0), (1,2), (3,2), (4,0)
#   x(t) = 3t + 3t^2 - 2t^3,  y(t) = 6t - 6t^2
CUBIC = [[0, 0], [1, 2], [3, 2], [4, 0]]


def rng_points(seed, n, d=2):
    return np.random.default_rng(seed).normal(size=(n + 1, d)) * 10


curves = st.builds(rng_points, st.integers(0, 2**32 - 1), st.integers(1, 7),
                   st.sampled_from([2, 3]))
ts = st.floats(0.0, 1.0)


# -- closed forms ----------------------------------------------------------
def test_cubic_closed_form_points_and_polynomial():
    b = Bezier(CUBIC)
    t = np.linspace(0, 1, 11)
    expect = np.column_stack([3 * t + 3 * t**2 - 2 * t**3, 6 * t - 6 * t**2])
    np.testing.assert_allclose(b.eval(t), expect, atol=1e-14)
    np.testing.assert_allclose(b.eval_casteljau(t), expect, atol=1e-14)
    np.testing.assert_allclose(b.power_coeffs(), [[0, 0], [3, 6], [3, -6], [-2, 0]], atol=1e-14)


def test_cubic_tangent_slope_and_second_derivative():
    b = Bezier(CUBIC)
    # x' = 3 + 6t - 6t^2, y' = 6 - 12t; x'' = 6 - 12t, y'' = -12
    np.testing.assert_allclose(b.tangent(0.25), [3 + 1.5 - 0.375, 3.0])
    assert b.slope(0.0) == pytest.approx(2.0)
    assert b.slope(0.5) == pytest.approx(0.0)
    np.testing.assert_allclose(b.deriv(2).eval([0.0, 1.0]), [[6, -12], [-6, -12]])
    np.testing.assert_allclose(b.deriv(3).ctrl, [[-12, 0]])
    np.testing.assert_allclose(b.deriv(4).ctrl, [[0, 0]])


def test_cubic_bounding_box_and_extrema():
    b = Bezier(CUBIC)
    np.testing.assert_allclose(b.extrema(), [0.5])        # y' = 0 at t = 1/2
    lo, hi = b.bounding_box()
    np.testing.assert_allclose(lo, [0, 0])
    np.testing.assert_allclose(hi, [4, 1.5])


def test_bernstein_cubic_closed_form():
    t = np.linspace(0, 1, 7)
    expect = np.column_stack([(1 - t)**3, 3 * t * (1 - t)**2, 3 * t**2 * (1 - t), t**3])
    np.testing.assert_allclose(bernstein(3, t), expect, atol=1e-15)
    # matrix form: [1, t, t^2, t^3] @ M
    pw = np.vander(t, 4, increasing=True)
    np.testing.assert_allclose(pw @ bernstein_matrix(3), expect, atol=1e-14)


def test_parabola_arc_length():
    # quadratic (0,0),(1,2),(2,0): the parabola y = 2x - x^2 on [0, 2];
    # length = int_0^2 sqrt(1 + u^2) du = sqrt(5) + asinh(2) / 2
    exact = math.sqrt(5) + math.asinh(2) / 2
    assert Bezier([[0, 0], [1, 2], [2, 0]]).arc_length(1e-12) == pytest.approx(exact, abs=1e-11)


def test_line_arc_length_and_degenerate():
    assert Bezier([[0, 0], [3, 4]]).arc_length() == pytest.approx(5.0, abs=1e-12)
    # a cubic with all control points on a line, doubling back: x = 3t - 3t^2 ... length 2*max
    b = Bezier([[0, 0], [1, 0], [0, 0], [0, 0]])
    xs = b.eval(np.linspace(0, 1, 100001))[:, 0]
    assert b.arc_length(1e-9) == pytest.approx(2 * xs.max(), abs=1e-8)


@pytest.mark.parametrize('tol', [1e-2, 1e-5, 1e-9])
def test_arc_length_honours_tolerance(tol):
    b = Bezier(rng_points(3, 6))
    ref = b.arc_length(1e-13)
    assert abs(b.arc_length(tol) - ref) <= tol


def test_split_known_values():
    left, right = Bezier(CUBIC).split(0.5)
    np.testing.assert_allclose(left.ctrl, [[0, 0], [0.5, 1], [1.25, 1.5], [2, 1.5]])
    np.testing.assert_allclose(right.ctrl, [[2, 1.5], [2.75, 1.5], [3.5, 1], [4, 0]])


def test_elevate_quadratic_known():
    # quadratic -> cubic: Q1 = P0/3 + 2P1/3, Q2 = 2P1/3 + P2/3
    e = Bezier([[0, 0], [3, 3], [6, 0]]).elevate()
    np.testing.assert_allclose(e.ctrl, [[0, 0], [2, 2], [4, 2], [6, 0]])


def test_three_d_curve():
    b = Bezier([[0, 0, 0], [1, 0, 1], [1, 1, 2]])
    np.testing.assert_allclose(b.eval(0.5), [0.75, 0.25, 1.0])
    lo, hi = b.bounding_box()
    np.testing.assert_allclose(lo, [0, 0, 0])
    np.testing.assert_allclose(hi, [1, 1, 2])


# -- hypothesis properties -------------------------------------------------
@settings(max_examples=50, deadline=None)
@given(st.integers(0, 20), st.lists(ts, min_size=1, max_size=20))
def test_blending_nonnegative_partition_of_unity(n, t):
    B = bernstein(n, t)
    assert np.all(B >= 0)
    np.testing.assert_allclose(B.sum(axis=1), 1.0, atol=1e-13)


@settings(max_examples=50, deadline=None)
@given(curves, st.lists(ts, min_size=1, max_size=10))
def test_casteljau_matches_bernstein(P, t):
    b = Bezier(P)
    np.testing.assert_allclose(b.eval(t), b.eval_casteljau(t), atol=1e-10)


@settings(max_examples=50, deadline=None)
@given(curves)
def test_end_points_and_end_tangents(P):
    b = Bezier(P)
    n = len(P) - 1
    np.testing.assert_array_equal(b.eval(0.0), P[0])
    np.testing.assert_array_equal(b.eval(1.0), P[-1])
    np.testing.assert_allclose(b.tangent(0.0), n * (P[1] - P[0]), atol=1e-9)
    np.testing.assert_allclose(b.tangent(1.0), n * (P[-1] - P[-2]), atol=1e-9)


@settings(max_examples=50, deadline=None)
@given(curves, st.integers(0, 2**32 - 1))
def test_affine_invariance(P, seed):
    r = np.random.default_rng(seed)
    d = P.shape[1]
    A, off = r.normal(size=(d, d)), r.normal(size=d)
    t = r.uniform(0, 1, 9)
    b = Bezier(P)
    np.testing.assert_allclose(b.transform(A, off).eval(t), b.eval(t) @ A.T + off,
                               atol=1e-9 * (1 + np.abs(P).max()) * (1 + np.abs(A).max()))


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(3, 7), st.sampled_from([2, 3]))
def test_curve_inside_convex_hull_of_control_points(seed, n1, d):
    P = rng_points(seed, n1, d)          # gaussian points: hull not degenerate
    hull = ConvexHull(P)
    pts = Bezier(P).eval(np.linspace(0, 1, 200))
    # every facet inequality a.x + b <= 0 holds (within rounding)
    assert np.all(pts @ hull.equations[:, :-1].T + hull.equations[:, -1] <= 1e-9)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 9))
def test_curve_inside_raster_hull(seed, n):
    # the same property with raster's own monotone-chain hull (counter-clockwise,
    # y up): every curve point is left of (or on) every hull edge
    P = rng_points(seed, n)
    H = convex_hull(P)
    a, b = H, np.roll(H, -1, axis=0)
    pts = Bezier(P).eval(np.linspace(0, 1, 300))
    cross = ((b[None, :, 0] - a[None, :, 0]) * (pts[:, None, 1] - a[None, :, 1])
             - (b[None, :, 1] - a[None, :, 1]) * (pts[:, None, 0] - a[None, :, 0]))
    assert np.all(cross >= -1e-9 * (1 + np.abs(P).max()) ** 2)
    np.testing.assert_allclose(np.sort(Bezier(P).hull(), axis=0), np.sort(H, axis=0))


@settings(max_examples=60, deadline=None)
@given(curves)
def test_bounding_box_agrees_with_raster_bbox(P):
    lo, hi = Bezier(P).bounding_box()
    rlo, rhi = bezier_bbox(P)
    np.testing.assert_allclose(lo, rlo, atol=1e-9 * (1 + np.abs(P).max()))
    np.testing.assert_allclose(hi, rhi, atol=1e-9 * (1 + np.abs(P).max()))


@settings(max_examples=50, deadline=None)
@given(curves, st.lists(ts, min_size=1, max_size=10))
def test_reversal_symmetry(P, t):
    t = np.array(t)
    b = Bezier(P)
    np.testing.assert_allclose(b.reverse().eval(t), b.eval(1 - t), atol=1e-10)


@settings(max_examples=50, deadline=None)
@given(curves, st.floats(0.01, 0.99), st.lists(ts, min_size=1, max_size=10))
def test_split_halves_reproduce_curve(P, s, u):
    u = np.array(u)
    b = Bezier(P)
    left, right = b.split(s)
    np.testing.assert_allclose(left.eval(u), b.eval(s * u), atol=1e-9)
    np.testing.assert_allclose(right.eval(u), b.eval(s + (1 - s) * u), atol=1e-9)


@settings(max_examples=50, deadline=None)
@given(curves, ts, ts, st.lists(ts, min_size=1, max_size=10))
def test_subsegment_reproduces_curve(P, t0, t1, u):
    u = np.array(u)
    sub = Bezier(P).subsegment(t0, t1)
    np.testing.assert_allclose(sub.eval(u), Bezier(P).eval(t0 + (t1 - t0) * u), atol=1e-9)


@settings(max_examples=50, deadline=None)
@given(curves, st.integers(1, 4), st.lists(ts, min_size=1, max_size=10))
def test_degree_elevation_preserves_curve(P, k, t):
    b = Bezier(P)
    e = b.elevate(k)
    assert e.degree == b.degree + k
    np.testing.assert_allclose(e.eval(t), b.eval(t), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(curves)
def test_derivative_matches_power_form(P):
    b = Bezier(P)
    c = b.power_coeffs()
    t = np.linspace(0, 1, 7)
    k = np.arange(1, len(c))
    dpoly = (k[None, :, None] * c[None, 1:] * t[:, None, None] ** (k - 1)[None, :, None]).sum(1)
    np.testing.assert_allclose(b.tangent(t), dpoly, atol=1e-7 * (1 + np.abs(c).max()))


@settings(max_examples=60, deadline=None)
@given(curves)
def test_bounding_box_exact(P):
    b = Bezier(P)
    lo, hi = b.bounding_box()
    dense = b.eval(np.linspace(0, 1, 4001))
    assert np.all(dense >= lo - 1e-9) and np.all(dense <= hi + 1e-9)
    # tight: the dense maximum is close (sampling error only)
    span = hi - lo
    assert np.all(dense.min(0) - lo <= 1e-3 * (1 + span))
    assert np.all(hi - dense.max(0) <= 1e-3 * (1 + span))
    # extrema are roots of the hodograph coordinates
    for t in b.extrema():
        assert np.min(np.abs(b.tangent(t))) <= 1e-6 * (1 + np.abs(b.deriv().ctrl).max())


# -- piecewise -------------------------------------------------------------
def test_piecewise_eval_breaks_and_deriv_chain_rule():
    # two lines, the second on a parameter interval of length 2
    pb = PiecewiseBezier([[[0, 0], [1, 0]], [[1, 0], [1, 4]]], breaks=[0, 1, 3])
    np.testing.assert_allclose(pb.eval([0, 0.5, 1, 2, 3]),
                               [[0, 0], [0.5, 0], [1, 0], [1, 2], [1, 4]])
    np.testing.assert_allclose(pb.tangent([0.5, 2.0]), [[1, 0], [0, 2]])
    sub = pb.subsegment(0.5, 2.0)
    np.testing.assert_allclose(sub.eval([0.5, 1, 2]), [[0.5, 0], [1, 0], [1, 2]])
    rev = pb.reverse()
    np.testing.assert_allclose(rev.eval([0, 3]), [[1, 4], [0, 0]])
    assert pb.arc_length() == pytest.approx(5.0)


def test_concat_elevates_and_iterates():
    pb = PiecewiseBezier.concat([Bezier([[0, 0], [1, 0]]), Bezier([[1, 0], [2, 1], [3, 0]])])
    assert pb.degree == 2 and len(pb) == 2
    assert [b.degree for b in pb] == [2, 2]
    np.testing.assert_allclose(pb.eval(0.5), [0.5, 0])


def test_to_path_verbs_and_pen():
    p = Bezier(CUBIC).to_path()
    assert p.verbs.tolist() == [0, 3]
    assert Bezier(CUBIC).to_svg() == 'M 0 0 C 1 2 3 2 4 0'
    assert Bezier([[0, 0], [1, 1], [2, 0]]).to_path().verbs.tolist() == [0, 2]
    pen = RecordingPen()
    Bezier([[0, 0], [5, 5]]).draw(pen)
    assert pen.value == [('moveTo', ((0.0, 0.0),)), ('lineTo', ((5.0, 5.0),)), ('endPath', ())]


@pytest.mark.parametrize('tol', [1.0, 0.1, 0.001])
def test_high_degree_to_cubics_honours_tolerance(tol):
    P = rng_points(11, 6) * 5
    b = Bezier(P)
    cubics = b.to_beziers().to_cubics(tol)
    # the pieces tile the parameter range in order, each matching the curve
    # at the same parameter: recover each piece's range from its end points
    u = np.linspace(0, 1, 50)
    dense_t = np.linspace(0, 1, 40001)
    dense = b.eval(dense_t)
    ends = np.concatenate([cubics[:1, 0], cubics[:, -1]])
    idx = np.argmin(np.linalg.norm(dense[None, :] - ends[:, None], axis=2), axis=1)
    tk = dense_t[idx]
    assert np.all(np.diff(tk) > 0)
    for k, c in enumerate(cubics):
        ref = b.eval(tk[k] + (tk[k + 1] - tk[k]) * u)
        # each end parameter is recovered to half the grid step (and the
        # piece's interior shifts by no more): allow max speed times that
        slack = 2 * 0.5 / 40000 * np.linalg.norm(b.deriv().ctrl, axis=1).max()
        assert np.linalg.norm(Bezier(c).eval(u) - ref, axis=1).max() <= tol + slack
    assert np.array_equal(cubics[0, 0], P[0]) and np.array_equal(cubics[-1, -1], P[-1])
    p = b.to_path(tol)
    assert set(p.verbs.tolist()) == {0, 3}


@pytest.mark.parametrize('tol', [1.0, 0.25, 0.01])
def test_flatten_honours_tolerance(tol):
    b = Bezier(rng_points(5, 4) * 10)
    poly = b.flatten(tol)
    dense = b.eval(np.linspace(0, 1, 5001))
    a, c = poly[:-1], poly[1:]
    ab = c - a
    w = np.clip(np.einsum('mkd,kd->mk', dense[:, None] - a[None], ab)
                / np.einsum('kd,kd->k', ab, ab), 0, 1)
    dist = np.linalg.norm(dense[:, None] - (a[None] + w[..., None] * ab[None]), axis=2).min(1)
    assert dist.max() <= tol * (1 + 1e-9)
    np.testing.assert_array_equal(poly[0], b.ctrl[0])
    np.testing.assert_array_equal(poly[-1], b.ctrl[-1])


# -- errors ----------------------------------------------------------------
@pytest.mark.parametrize('bad', [[[0, np.nan], [1, 1]], [[0, 0], [1]], 'abc', [[]], [1, 2, 3]])
def test_bad_control_points(bad):
    with pytest.raises(CurveError):
        Bezier(bad)


def test_bad_parameters():
    b = Bezier(CUBIC)
    assert issubclass(CurveError, RasterError)
    for t in (1.5, -0.1, np.nan, 'x'):
        with pytest.raises(CurveError):
            b.eval(t)
    with pytest.raises(CurveError):
        b.split(2)
    with pytest.raises(CurveError):
        b.arc_length(0)
    with pytest.raises(CurveError):
        b.deriv(-1)
    with pytest.raises(CurveError):
        PiecewiseBezier([[[0, 0], [1, 0]]], breaks=[1, 0])


def test_bezier_and_piecewise_bezier_pickle_and_copy_as_immutable_curves():
    import copy
    import pickle
    b = Bezier([[0.0, 0.0], [1.0, 2.0], [3.0, 1.0], [4.0, 4.0]])
    pb = PiecewiseBezier([[[0, 0], [1, 2], [3, 1]], [[3, 1], [4, 0], [5, 1]]], [0.0, 0.5, 2.0])
    t = np.linspace(0.0, 1.0, 9)
    for curve, ts in ((b, t), (pb, 2.0 * t)):
        for q in (pickle.loads(pickle.dumps(curve)), copy.copy(curve), copy.deepcopy(curve)):
            assert type(q) is type(curve)
            assert np.array_equal(q.ctrl, curve.ctrl) and np.array_equal(q.eval(ts), curve.eval(ts))
            with pytest.raises(AttributeError):
                q.ctrl = None
    assert np.array_equal(pickle.loads(pickle.dumps(pb)).breaks, pb.breaks)
