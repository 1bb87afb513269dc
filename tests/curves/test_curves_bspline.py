"""Tests of raster.curves.bspline, cross-checked against scipy.interpolate."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.interpolate import BSpline as SciBSpline
from scipy.spatial import ConvexHull

from raster.curves import BSpline, Bezier, basis_functions, clamped_uniform_knots, CurveError

seeds = st.integers(0, 2**32 - 1)


def random_spline(seed, degree, d=2, clamped=None):
    r = np.random.default_rng(seed)
    n = degree + 1 + int(r.integers(0, 6))
    P = r.normal(size=(n, d)) * 3
    inner = np.sort(r.uniform(0, 1, n - degree - 1))
    if degree >= 1 and r.random() < 0.3 and len(inner) > 1:   # a repeated interior knot
        inner[1] = inner[0]
    if clamped is None:
        clamped = r.random() < 0.5
    if clamped:
        kn = np.concatenate([np.zeros(degree + 1), inner, np.ones(degree + 1)])
    else:
        kn = np.sort(np.concatenate([r.uniform(-1, 0, degree + 1), inner,
                                     r.uniform(1, 2, degree + 1)]))
    return BSpline(P, degree, kn), P, kn


def test_uniform_cubic_closed_form():
    # unclamped uniform cubic, knots 0..7, 4 points: one span [3, 4];
    # C(3) = (P0 + 4 P1 + P2) / 6, C(4) = (P1 + 4 P2 + P3) / 6
    P = np.array([[0, 0], [6, 0], [6, 6], [0, 6]], float)
    s = BSpline(P, 3, np.arange(8.0))
    assert s.domain == (3.0, 4.0)
    np.testing.assert_allclose(s.eval(3.0), (P[0] + 4 * P[1] + P[2]) / 6)
    np.testing.assert_allclose(s.eval(4.0), (P[1] + 4 * P[2] + P[3]) / 6)
    # midpoint: blending (1, 23, 23, 1) / 48
    np.testing.assert_allclose(s.eval(3.5), (P[0] + 23 * P[1] + 23 * P[2] + P[3]) / 48)


def test_linear_bspline_is_the_polyline():
    P = np.array([[0, 0], [1, 2], [3, 1], [4, 4]], float)
    s = BSpline(P, 1)           # clamped uniform: knots 0,0,1/3,2/3,1,1
    np.testing.assert_allclose(s.eval([0, 1 / 3, 2 / 3, 1]), P, atol=1e-15)
    np.testing.assert_allclose(s.eval(1 / 6), (P[0] + P[1]) / 2)


def test_single_span_clamped_is_bezier():
    P = np.random.default_rng(1).normal(size=(6, 3))
    t = np.linspace(0, 1, 21)
    np.testing.assert_allclose(BSpline(P, 5).eval(t), Bezier(P).eval(t), atol=1e-12)


def test_quadratic_basis_closed_form():
    # knots 0,0,0,1,1,1: Bernstein quadratics
    t = np.linspace(0, 1, 5)
    np.testing.assert_allclose(basis_functions([0, 0, 0, 1, 1, 1], 2, t),
                               np.column_stack([(1 - t)**2, 2 * t * (1 - t), t**2]), atol=1e-15)


def test_default_knots():
    np.testing.assert_allclose(clamped_uniform_knots(6, 3), [0, 0, 0, 0, 1 / 3, 2 / 3, 1, 1, 1, 1])


@settings(max_examples=80, deadline=None)
@given(seeds, st.integers(0, 5))
def test_against_scipy(seed, p):
    s, P, kn = random_spline(seed, p)
    lo, hi = s.domain
    t = np.linspace(lo, hi, 57)[:-1]        # scipy uses the left-closed convention
    ref = SciBSpline(kn, P, p)
    np.testing.assert_allclose(s.eval(t), ref(t), atol=1e-9)
    # derivatives away from knots (where they may jump); scipy refuses to
    # differentiate through interior knots of multiplicity > p - order
    inner = kn[(kn > lo) & (kn < hi)]
    mult = np.unique(inner, return_counts=True)[1].max() if len(inner) else 0
    tt = t[np.min(np.abs(t[:, None] - kn[None, :]), axis=1) > 1e-6]
    if p >= 1 and mult <= p - 1:
        np.testing.assert_allclose(s.deriv().eval(tt), ref.derivative()(tt), atol=1e-7)
    if p >= 2 and mult <= p - 2:
        np.testing.assert_allclose(s.deriv(2).eval(tt), ref.derivative(2)(tt), atol=1e-6)
    B = s.basis(t)
    design = SciBSpline.design_matrix(t, kn, p).toarray()
    np.testing.assert_allclose(B, design, atol=1e-12)


@settings(max_examples=80, deadline=None)
@given(seeds, st.integers(0, 5))
def test_basis_nonnegative_partition_of_unity(seed, p):
    s, P, kn = random_spline(seed, p)
    B = s.basis(np.linspace(*s.domain, 41))
    assert np.all(B >= -1e-15)
    np.testing.assert_allclose(B.sum(1), 1.0, atol=1e-12)


@settings(max_examples=80, deadline=None)
@given(seeds, st.integers(1, 5))
def test_to_beziers_reproduces_curve(seed, p):
    s, P, kn = random_spline(seed, p)
    t = np.linspace(*s.domain, 101)
    pb = s.to_beziers()
    assert pb.degree == p
    np.testing.assert_allclose(pb.eval(t), s.eval(t), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(seeds, st.integers(1, 5), st.floats(0, 1))
def test_knot_insertion_preserves_curve(seed, p, where):
    s, P, kn = random_spline(seed, p)
    lo, hi = s.domain
    # (lo + 1.0 * (hi - lo) can land one ulp past hi; parameters are clamped
    # to the domain, so the test clamps too)
    u = min(max(lo + where * (hi - lo), lo), hi)
    mult = int(np.sum(kn == u))
    if mult >= p:
        with pytest.raises(CurveError):
            s.insert_knot(u, p - mult + 1)
        return
    s2 = s.insert_knot(u, p - mult)
    assert len(s2.ctrl) == len(s.ctrl) + p - mult
    t = np.linspace(lo, hi, 61)
    np.testing.assert_allclose(s2.eval(t), s.eval(t), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(seeds, st.integers(1, 4))
def test_local_control(seed, p):
    s, P, kn = random_spline(seed, p, clamped=True)
    r = np.random.default_rng(seed)
    j = int(r.integers(0, len(P)))
    P2 = P.copy()
    P2[j] += r.normal(size=2) * 10
    s2 = BSpline(P2, p, kn)
    t = np.linspace(*s.domain, 301)
    outside = (t < kn[j]) | (t > kn[j + p + 1])
    np.testing.assert_allclose(s2.eval(t[outside]), s.eval(t[outside]), atol=1e-12)
    inside = (t > kn[j]) & (t < kn[j + p + 1])
    assert not inside.any() or np.abs(s2.eval(t[inside]) - s.eval(t[inside])).max() > 0


@settings(max_examples=40, deadline=None)
@given(seeds, st.integers(2, 4))
def test_span_inside_hull_of_its_control_points(seed, p):
    s, P, kn = random_spline(seed, p)
    lo, hi = s.domain
    t = np.linspace(lo, hi, 400)
    k = s.span(t)
    for span in np.unique(k):
        hull = ConvexHull(P[span - p:span + 1])
        pts = s.eval(t[k == span])
        assert np.all(pts @ hull.equations[:, :-1].T + hull.equations[:, -1] <= 1e-9)


@settings(max_examples=40, deadline=None)
@given(seeds, st.integers(1, 5))
def test_closed_periodic_loop(seed, p):
    r = np.random.default_rng(seed)
    P = r.normal(size=(p + 1 + int(r.integers(0, 5)), 2))
    s = BSpline(P, p, closed=True)
    assert s.domain == (0.0, 1.0)
    for k in range(p):       # C^(p-1) across the seam
        d = s.deriv(k) if k else s
        np.testing.assert_allclose(d.eval(0.0), d.eval(1.0), atol=1e-9 * (1 + 10 ** k))
    joints = s.continuity()
    assert all(j.C >= min(p - 1, 2) for j in joints)
    assert len(joints) == len(s.to_beziers())       # the seam joint is included


def test_errors():
    P = [[0, 0], [1, 1], [2, 0], [3, 1]]
    with pytest.raises(CurveError, match='non-decreasing'):
        BSpline(P, 2, [0, 0, 0, 0.6, 0.5, 1, 1])
    with pytest.raises(CurveError, match='needs 7 knots'):
        BSpline(P, 2, [0, 0, 0, 1, 1, 1])
    with pytest.raises(CurveError, match='at least 4'):
        BSpline(P[:3], 3)
    with pytest.raises(CurveError):
        BSpline(P, 1, [0, 0, 0, 0, 1, 1])          # multiplicity 4 > 2
    with pytest.raises(CurveError):
        BSpline(P, -1)
    with pytest.raises(CurveError):
        BSpline(P, 2).eval(1.5)
    with pytest.raises(CurveError):
        BSpline(P, 2, closed=True, knots=[0] * 7)
    with pytest.raises(CurveError):
        BSpline(P, 2).insert_knot(0.0)             # already multiplicity 3
