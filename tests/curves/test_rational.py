"""Rational Bezier curves and chains: evaluation, derivatives, the exact
derivative curve, bounds, splitting, the cubic approximation bound,
flattening and continuity; hypothesis properties (convex hull, affine
invariance, end points)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.curves import (Bezier, CurveError, NURBS, PiecewiseRational, RationalBezier,
                           circle_arc)
from raster.curves.rational import bernstein_product


def direct(P, w, t):
    """R(t) from the definition (independent)."""
    n = len(P) - 1
    B = np.array([[math.comb(n, i) * x ** i * (1 - x) ** (n - i) for i in range(n + 1)]
                  for x in np.atleast_1d(t)])
    num = (B * w) @ P
    return num / (B @ w)[:, None]


def test_definition_and_blending():
    rng = np.random.default_rng(1)
    for n in (1, 2, 3, 5, 8):
        P = rng.normal(size=(n + 1, 2))
        w = rng.uniform(0.2, 4, n + 1)
        r = RationalBezier(P, w)
        t = np.linspace(0, 1, 21)
        np.testing.assert_allclose(r.eval(t), direct(P, w, t), atol=1e-13)
        R = r.blending(t)
        np.testing.assert_allclose(R.sum(1), 1, atol=1e-14)
        np.testing.assert_allclose(R @ P, r.eval(t), atol=1e-13)


def test_equal_weights_is_the_polynomial_bezier():
    P = [[1, 1], [2, 3], [4, 3], [6, 4]]
    r = RationalBezier(P, [2.5] * 4)
    b = Bezier(P)
    t = np.linspace(0, 1, 11)
    np.testing.assert_allclose(r.eval(t), b.eval(t), atol=1e-14)
    assert r.to_bezier() == b
    np.testing.assert_allclose(r.tangent(t), b.tangent(t), atol=1e-13)
    assert RationalBezier.from_bezier(b).is_polynomial()
    with pytest.raises(CurveError, match='weights differ'):
        RationalBezier(P, [1, 2, 1, 1]).to_bezier()
    with pytest.raises(CurveError, match='tolerance'):
        RationalBezier(P, [1, 2, 1, 1]).to_beziers()


def test_derivatives_against_finite_differences_and_the_derivative_curve():
    rng = np.random.default_rng(2)
    P = rng.normal(size=(5, 3))
    w = rng.uniform(0.3, 3, 5)
    r = RationalBezier(P, w)
    t, h = 0.37, 1e-5
    d = r.derivatives(t, 3)
    fd1 = (r.eval(t + h) - r.eval(t - h)) / (2 * h)
    fd2 = (r.eval(t + h) - 2 * r.eval(t) + r.eval(t - h)) / h ** 2
    np.testing.assert_allclose(d[1], fd1, atol=1e-7)
    np.testing.assert_allclose(d[2], fd2, atol=1e-3)
    # the exact hodograph (degree 2n) equals the first derivative everywhere
    dr = r.deriv()
    assert dr.degree == 8
    ts = np.linspace(0, 1, 17)
    np.testing.assert_allclose(dr.eval(ts), r.tangent(ts), atol=1e-11)
    np.testing.assert_allclose(r.deriv(2).eval(ts), r.derivatives(ts, 2)[:, 2], atol=1e-8)


def test_quarter_circle_tangent_and_curvature():
    # x^2 + y^2 = 1: tangent perpendicular to the radius, curvature 1
    q = RationalBezier([[1, 0], [1, 1], [0, 1]], [1, 2 ** -0.5, 1])
    t = np.linspace(0, 1, 9)
    d = q.derivatives(t, 2)
    p, v, a = d[:, 0], d[:, 1], d[:, 2]
    np.testing.assert_allclose((p * v).sum(1), 0, atol=1e-14)
    k = np.abs(v[:, 0] * a[:, 1] - v[:, 1] * a[:, 0]) / np.linalg.norm(v, axis=1) ** 3
    np.testing.assert_allclose(k, 1.0, atol=1e-13)


def test_split_subsegment_elevate_reweight():
    rng = np.random.default_rng(3)
    P = rng.normal(size=(4, 2))
    r = RationalBezier(P, rng.uniform(0.5, 2, 4))
    a, b = r.split(0.3)
    s = np.linspace(0, 1, 11)
    np.testing.assert_allclose(a.eval(s), r.eval(0.3 * s), atol=1e-13)
    np.testing.assert_allclose(b.eval(s), r.eval(0.3 + 0.7 * s), atol=1e-13)
    np.testing.assert_allclose(r.subsegment(0.2, 0.9).eval(s), r.eval(0.2 + 0.7 * s), atol=1e-13)
    e = r.elevate(2)
    assert e.degree == 5
    np.testing.assert_allclose(e.eval(s), r.eval(s), atol=1e-13)
    # a Moebius reweighting traces the same point set: every point of the
    # reweighted curve is a point of the original one at some parameter
    m = r.reweight(2.0)
    dense = r.eval(np.linspace(0, 1, 20001))
    for p in m.eval(s):
        assert np.linalg.norm(dense - p, axis=1).min() < 1e-3
    np.testing.assert_allclose(m.eval([0, 1]), r.eval([0, 1]), atol=1e-14)


def test_exact_bounding_box_and_extrema():
    rng = np.random.default_rng(4)
    for _ in range(10):
        P = rng.normal(size=(5, 2))
        r = RationalBezier(P, rng.uniform(0.2, 5, 5))
        lo, hi = r.bounding_box()
        dense = r.eval(np.linspace(0, 1, 200001))
        np.testing.assert_allclose(lo, dense.min(0), atol=1e-9)
        np.testing.assert_allclose(hi, dense.max(0), atol=1e-9)
        for t in r.extrema():
            v = r.tangent(t)
            assert min(abs(v[0]), abs(v[1])) <= 1e-8 * max(1, np.abs(v).max())


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2 ** 31), st.floats(1e-4, 0.5), st.integers(1, 6))
def test_cubic_approximation_bound_holds(seed, tol, n):
    rng = np.random.default_rng(seed)
    P = rng.uniform(-20, 20, (n + 1, 2))
    r = RationalBezier(P, rng.uniform(0.2, 5, n + 1))
    pb = r.to_beziers(tol)
    t = np.linspace(0, 1, 4001)
    assert np.linalg.norm(pb.eval(t) - r.eval(t), axis=1).max() <= tol * (1 + 1e-9)


@settings(max_examples=20, deadline=None)
@given(st.integers(0, 2 ** 31), st.floats(0.01, 1.0))
def test_flatten_honours_the_tolerance(seed, tol):
    rng = np.random.default_rng(seed)
    P = rng.uniform(-50, 50, (4, 2))
    r = RationalBezier(P, rng.uniform(0.2, 5, 4))
    poly = r.flatten(tol)
    pts = r.eval(np.linspace(0, 1, 3001))
    a, b = poly[:-1], poly[1:]
    d = b - a
    s = np.clip(((pts[:, None] - a) * d).sum(2) / np.maximum((d * d).sum(1), 1e-300), 0, 1)
    dist = np.linalg.norm(pts[:, None] - (a + s[..., None] * d), axis=2).min(1)
    assert dist.max() <= tol * (1 + 1e-9)
    np.testing.assert_allclose(poly[[0, -1]], P[[0, -1]], atol=1e-12)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 31), st.integers(1, 7))
def test_properties_hull_affine_endpoints(seed, n):
    rng = np.random.default_rng(seed)
    P = rng.uniform(-10, 10, (n + 1, 2))
    w = rng.uniform(0.1, 10, n + 1)
    r = RationalBezier(P, w)
    t = np.linspace(0, 1, 101)
    X = r.eval(t)
    # convex hull (positive weights): support in every direction is bounded
    for ang in np.linspace(0, np.pi, 12, endpoint=False):
        d = np.array([math.cos(ang), math.sin(ang)])
        assert (X @ d).max() <= (P @ d).max() + 1e-9
        assert (X @ d).min() >= (P @ d).min() - 1e-9
    # end-point interpolation
    np.testing.assert_allclose(X[[0, -1]], P[[0, -1]], atol=1e-12)
    # affine invariance with the same weights
    A = rng.normal(size=(2, 2))
    o = rng.normal(size=2)
    np.testing.assert_allclose(r.transform(A, o).eval(t), X @ A.T + o, atol=1e-9)


def test_chains_continuity_and_nurbs_round_trip():
    arc = circle_arc([0, 0], 1.0, 0.0, 1.5 * np.pi)            # 3 quarter arcs
    js = arc.continuity()
    assert [(j.C, j.G) for j in js] == [(1, 2), (1, 2)]
    # a cusp: the quarter arc ending at (0, 1) going -x, then the quarter
    # arc of the circle about (0, 2) leaving (0, 1) going +x: G0 only
    q = RationalBezier([[1, 0], [1, 1], [0, 1]], [1, 2 ** -0.5, 1])
    r = circle_arc([0, 2], 1.0, -np.pi / 2, np.pi / 2)
    kink = PiecewiseRational([q.points, r.ctrl[0]], [q.weights, r.weights[0]])
    j, = kink.continuity()
    assert (j.C, j.G) == (0, 0) and j.gap < 1e-15
    n = NURBS.from_rational(arc)
    t = np.linspace(0, 1, 41)
    np.testing.assert_allclose(n.eval(t), arc.eval(t), atol=1e-14)
    back = n.to_rational_beziers()
    np.testing.assert_allclose(back.eval(t), arc.eval(t), atol=1e-14)
    with pytest.raises(CurveError, match='do not meet'):
        NURBS.from_rational(PiecewiseRational([q.points, q.points + 5],
                                              [q.weights, q.weights]))


def test_bernstein_product_is_the_polynomial_product():
    rng = np.random.default_rng(5)
    f, g = rng.normal(size=(1, 4, 1)), rng.normal(size=(1, 3, 1))
    t = np.linspace(0, 1, 9)
    ev = lambda c: Bezier(c[0]).eval(t)[:, 0]                         # noqa: E731
    np.testing.assert_allclose(ev(bernstein_product(f, g)), ev(f) * ev(g), atol=1e-13)


@pytest.mark.parametrize('args,needle', [
    (([[0, 0], [1, 1]], [1, -1]), 'positive'),
    (([[0, 0], [1, 1]], [1, 1, 1]), 'need'),
    (([[0, 0], [1, 1]], [1, np.inf]), 'finite'),
    (([[0, 0], [1, 1]], [1, 1e13]), 'differ'),
])
def test_bad_weights(args, needle):
    with pytest.raises(CurveError, match=needle):
        RationalBezier(*args)
