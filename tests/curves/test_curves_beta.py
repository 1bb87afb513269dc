"""Tests of raster.curves.beta: the basis matrix is re-derived here from
Barsky's G0/G1/G2 constraints by a linear solve and compared with the
closed form."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.spatial import ConvexHull

from raster.curves import BetaSpline, BSpline, beta_basis_matrix, beta_blend, CurveError

seeds = st.integers(0, 2**32 - 1)
beta1s = st.floats(0.05, 20)
beta2s = st.floats(0, 50)

BSPLINE_CUBIC = np.array([[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 0, 3, 0], [1, 4, 1, 0]]) / 6


def derive_basis(b1, b2):
    """Solve for the 16 coefficients: unknown x[4 r + k] is the coefficient
    of u^(3-k) in blending function b_{r-2}.  Constraints for every joint
    (value, first and second derivative rows at u = 0 and u = 1), and
    sum_r b_r(0) = 1."""
    def row(u, order):
        # derivative of [u^3, u^2, u, 1]
        return {0: [u**3, u**2, u, 1], 1: [3 * u**2, 2 * u, 1, 0], 2: [6 * u, 2, 0, 0]}[order]
    A, rhs = [], []

    def eq(terms):
        r = np.zeros(16)
        for fn, u, order, w in terms:        # fn in 0..3 (b_{-2}..b_1)
            r[4 * fn:4 * fn + 4] += w * np.array(row(u, order), float)
        A.append(r); rhs.append(0.0)
    # weight of V_{s+j} in Q_s(0) must equal its weight in Q_{s-1}(1):
    # b_j(0) (index j+2) vs b_{j+1}(1) (index j+3)
    for j in range(-3, 2):
        left = [(j + 2, 0.0, o, 1.0) for o in (0,)] if -2 <= j <= 1 else []
        right = [(j + 3, 1.0, 0, -1.0)] if -2 <= j + 1 <= 1 else []
        eq(left + right)
        l1 = [(j + 2, 0.0, 1, 1.0)] if -2 <= j <= 1 else []
        r1 = [(j + 3, 1.0, 1, -b1)] if -2 <= j + 1 <= 1 else []
        eq(l1 + r1)
        l2 = [(j + 2, 0.0, 2, 1.0)] if -2 <= j <= 1 else []
        r2 = ([(j + 3, 1.0, 2, -b1 * b1), (j + 3, 1.0, 1, -b2)] if -2 <= j + 1 <= 1 else [])
        eq(l2 + r2)
    norm = np.zeros(16)
    for fn in range(4):
        norm[4 * fn + 3] = 1.0
    A.append(norm); rhs.append(1.0)
    x = np.linalg.lstsq(np.array(A), np.array(rhs), rcond=None)[0]
    assert np.allclose(np.array(A) @ x, rhs, atol=1e-9)   # consistent, unique
    assert np.linalg.matrix_rank(np.array(A)) == 16
    return x.reshape(4, 4).T          # rows u^3..1, columns b_{-2}..b_1


def test_reduces_to_uniform_cubic_bspline():
    np.testing.assert_allclose(beta_basis_matrix(1, 0), BSPLINE_CUBIC, atol=1e-15)
    P = np.random.default_rng(2).normal(size=(7, 2))
    bs = BSpline(P, 3, np.arange(11.0))           # uniform unclamped: domain [3, 7]
    t = np.linspace(0, 4, 41)
    np.testing.assert_allclose(BetaSpline(P, 1, 0).eval(t), bs.eval(t + 3), atol=1e-12)


def test_derivation_at_bspline_values():
    np.testing.assert_allclose(derive_basis(1.0, 0.0), BSPLINE_CUBIC, atol=1e-12)


@settings(max_examples=100, deadline=None)
@given(beta1s, beta2s)
def test_closed_form_matches_constraint_solution(b1, b2):
    # the constraint system is ill-conditioned for small beta1 (~1e-9 error)
    np.testing.assert_allclose(beta_basis_matrix(b1, b2), derive_basis(b1, b2), atol=1e-7)


@settings(max_examples=100, deadline=None)
@given(beta1s, beta2s, st.lists(st.floats(0, 1), min_size=1, max_size=20))
def test_blending_nonnegative_partition_of_unity(b1, b2, u):
    w = beta_blend(u, b1, b2)
    assert np.all(w >= -1e-12)
    np.testing.assert_allclose(w.sum(1), 1.0, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(seeds, beta1s, beta2s, st.booleans())
def test_geometric_continuity_and_exact_bezier(seed, b1, b2, closed):
    P = np.random.default_rng(seed).normal(size=(7, 2))
    s = BetaSpline(P, b1, b2, closed=closed)
    pb = s.to_beziers()
    t = np.linspace(*s.domain, 91)
    np.testing.assert_allclose(pb.eval(t), s.eval(t), atol=1e-9)
    d1, d2 = pb.deriv(1).ctrl, pb.deriv(2).ctrl
    scale = 1 + np.abs(d2).max()
    # Q_s'(0) = b1 Q_{s-1}'(1);  Q_s''(0) = b1^2 Q_{s-1}''(1) + b2 Q_{s-1}'(1)
    np.testing.assert_allclose(d1[1:, 0], b1 * d1[:-1, -1], atol=1e-9 * scale)
    np.testing.assert_allclose(d2[1:, 0], b1**2 * d2[:-1, -1] + b2 * d1[:-1, -1],
                               atol=1e-8 * scale * (1 + b1**2 + b2))
    joints = s.continuity(1e-6)
    assert all(j.G == 2 for j in joints if not np.isnan(j.angle))
    if closed:
        np.testing.assert_allclose(s.eval(0.0), s.eval(s.domain[1]), atol=1e-12)


@settings(max_examples=40, deadline=None)
@given(seeds, beta1s, beta2s)
def test_segments_inside_hull_of_their_points(seed, b1, b2):
    P = np.random.default_rng(seed).normal(size=(6, 2))
    s = BetaSpline(P, b1, b2)
    for k in range(3):
        hull = ConvexHull(P[k:k + 4])
        pts = s.eval(np.linspace(k, k + 1, 50))
        assert np.all(pts @ hull.equations[:, :-1].T + hull.equations[:, -1] <= 1e-9)


def test_known_point_high_tension():
    # with tension beta2 -> large the curve is pulled to the control polygon:
    # Q(0) -> V_1 (the weight of V_1 at u = 0 is (4 b1^2 + 4 b1 + b2) / delta)
    P = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    w = beta_blend(0.0, 1.0, 1e6)
    assert w[1] == pytest.approx((8 + 1e6) / (12 + 1e6))
    np.testing.assert_allclose(BetaSpline(P, 1, 1e9).eval(0.0), P[1], atol=1e-8)


def test_errors():
    P = [[0, 0], [1, 1], [2, 0], [3, 1]]
    with pytest.raises(CurveError):
        BetaSpline(P, 0.0, 0.0)
    with pytest.raises(CurveError):
        BetaSpline(P, 1.0, -1.0)
    with pytest.raises(CurveError):
        BetaSpline(P[:3])
    with pytest.raises(CurveError):
        BetaSpline(P).eval(1.5)


@settings(max_examples=40, deadline=None)
@given(seeds, beta1s, beta2s)
def test_reversal_maps_bias_to_its_inverse(seed, b1, b2):
    # traversing the control points backwards gives the same curve with
    # beta1 -> 1 / beta1 and beta2 -> beta2 / beta1^3 (the G1/G2 conditions
    # read from the other side of each joint)
    P = np.random.default_rng(seed).normal(size=(7, 2))
    s = BetaSpline(P, b1, b2)
    r = BetaSpline(P[::-1], 1 / b1, b2 / b1**3)
    t = np.linspace(0, 4, 41)
    np.testing.assert_allclose(r.eval(4 - t), s.eval(t), atol=1e-9)
