"""Tests of raster.curves.natural, cross-checked against scipy.interpolate."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.interpolate import CubicSpline

from raster.curves import NaturalSpline, FunctionSpline, solve_tridiagonal, CurveError
from raster.curves.natural import parameterize

seeds = st.integers(0, 2**32 - 1)


def samples(seed, n):
    r = np.random.default_rng(seed)
    x = np.cumsum(r.uniform(0.05, 2, n)) - 3
    return x, r.normal(size=n) * 4


def test_three_point_hat_closed_form():
    # (0,0), (1,1), (2,0): 4 M1 = 6 (-1 - 1) -> M1 = -3;
    # on [0, 1]: y = -x^3/2 + 3x/2; symmetric on [1, 2]
    f = FunctionSpline([0, 1, 2], [0, 1, 0])
    np.testing.assert_allclose(f.second_derivatives(), [0, -3, 0])
    x = np.linspace(0, 1, 11)
    np.testing.assert_allclose(f.value(x), -x**3 / 2 + 1.5 * x, atol=1e-15)
    np.testing.assert_allclose(f.value(2 - x), -x**3 / 2 + 1.5 * x, atol=1e-15)
    np.testing.assert_allclose(f.value(x, order=1), -1.5 * x**2 + 1.5, atol=1e-14)


def test_clamped_reproduces_a_cubic():
    # clamped with the exact end slopes, the spline of y = x^3 - 2x + 1 is exact
    x = np.array([-1.0, -0.3, 0.2, 1.1, 2.0, 2.4])
    y = x**3 - 2 * x + 1
    f = FunctionSpline(x, y, end_slopes=(3 * x[0]**2 - 2, 3 * x[-1]**2 - 2))
    xs = np.linspace(-1, 2.4, 101)
    np.testing.assert_allclose(f.value(xs), xs**3 - 2 * xs + 1, atol=1e-12)
    np.testing.assert_allclose(f.value(xs, 2), 6 * xs, atol=1e-10)


def test_natural_reproduces_a_line():
    x = np.array([0.0, 0.5, 2.0, 2.1, 5.0])
    f = FunctionSpline(x, 3 * x - 1)
    xs = np.linspace(0, 5, 51)
    np.testing.assert_allclose(f.value(xs), 3 * xs - 1, atol=1e-12)
    np.testing.assert_allclose(f.eval(xs), np.column_stack([xs, 3 * xs - 1]), atol=1e-12)


@settings(max_examples=80, deadline=None)
@given(seeds, st.integers(2, 60), st.booleans())
def test_function_against_scipy(seed, n, clamped):
    x, y = samples(seed, n)
    ends = (0.7, -1.3) if clamped else None
    f = FunctionSpline(x, y, ends)
    ref = CubicSpline(x, y, bc_type=((1, 0.7), (1, -1.3)) if clamped else 'natural')
    xs = np.linspace(x[0], x[-1], 203)
    np.testing.assert_allclose(f.value(xs), ref(xs), atol=1e-9 * (1 + np.abs(y).max()))
    np.testing.assert_allclose(f.value(xs, 1), ref(xs, 1), atol=1e-7 * (1 + np.abs(y).max()))
    # exact Bezier form of the graph
    np.testing.assert_allclose(f.to_beziers().eval(xs), f.eval(xs), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(seeds, st.integers(2, 30), st.sampled_from(['uniform', 'chord', 'centripetal']),
       st.sampled_from([2, 3]))
def test_parametric_against_scipy(seed, n, kind, d):
    P = np.random.default_rng(seed).normal(size=(n, d)) * 3
    s = NaturalSpline(P, kind)
    np.testing.assert_allclose(s.eval(s.params), P, atol=1e-9)
    ref = CubicSpline(s.params, P, bc_type='natural')
    t = np.linspace(0, 1, 157)
    np.testing.assert_allclose(s.eval(t), ref(t), atol=1e-8)
    np.testing.assert_allclose(s.to_beziers().eval(t), s.eval(t), atol=1e-9)
    assert all(j.C == 2 for j in s.continuity(1e-7))


def test_parameterizations():
    P = np.array([[0, 0], [3, 4], [3, 5], [3, 14]], float)        # steps 5, 1, 9
    np.testing.assert_allclose(parameterize(P, 'uniform'), [0, 1 / 3, 2 / 3, 1])
    np.testing.assert_allclose(parameterize(P, 'chord'), [0, 5 / 15, 6 / 15, 1])
    c = np.sqrt([5, 1, 9])
    np.testing.assert_allclose(parameterize(P, 'centripetal'),
                               np.concatenate([[0], np.cumsum(c)]) / c.sum())


def test_parametric_clamped_end_tangents():
    P = np.array([[0, 0], [1, 1], [2, 0], [3, 1]], float)
    s = NaturalSpline(P, 'uniform', end_tangents=[[3, 0], [0, -3]])
    np.testing.assert_allclose(s.eval(0.0, order=1), [3, 0], atol=1e-12)
    np.testing.assert_allclose(s.eval(1.0, order=1), [0, -3], atol=1e-12)
    np.testing.assert_allclose(s.tangent(1.0), [0, -3], atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(seeds, st.integers(1, 70), st.integers(1, 3))
def test_tridiagonal_against_dense_solve(seed, n, k):
    r = np.random.default_rng(seed)
    a, c = r.uniform(-1, 1, n), r.uniform(-1, 1, n)
    b = (np.abs(a) + np.abs(c) + r.uniform(0.1, 2, n)) * r.choice([-1, 1], n)
    d = r.normal(size=(n, k))
    A = np.diag(b) + np.diag(a[1:], -1) + np.diag(c[:-1], 1)
    np.testing.assert_allclose(solve_tridiagonal(a, b, c, d), np.linalg.solve(A, d), atol=1e-9)
    np.testing.assert_allclose(solve_tridiagonal(a, b, c, d[:, 0]),
                               np.linalg.solve(A, d[:, 0]), atol=1e-9)


def test_errors():
    with pytest.raises(CurveError, match='increasing'):
        FunctionSpline([0, 2, 1], [0, 1, 2])
    with pytest.raises(CurveError):
        FunctionSpline([0, 1], [0, 1, 2])
    with pytest.raises(CurveError):
        FunctionSpline([0, 1, 2], [0, 1, 2]).value(3)
    with pytest.raises(CurveError, match='coincide'):
        NaturalSpline([[0, 0], [0, 0], [1, 1]])
    with pytest.raises(CurveError):
        NaturalSpline([[0, 0], [1, 1]], 'arc')
    with pytest.raises(CurveError):
        NaturalSpline([[0, 0]])
    with pytest.raises(CurveError):
        NaturalSpline([[0, 0], [1, 1]], end_tangents=[1, 2, 3])
