"""Tests of raster.geometry.roots: quadratics, cubics and polynomials of any
degree on (0, 1) -- analytic roots, double roots, degenerate leading
coefficients, no cancellation, and hypothesis properties against
numpy.roots."""

import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as st

from raster.geometry.roots import solve_cubic, solve_quadratic, unit_interval_roots

SETTINGS = settings(max_examples=200, deadline=None)


def real(r):
    """The non-NaN entries of a root vector."""
    r = np.asarray(r)
    return r[~np.isnan(r)]


# -- quadratics -----------------------------------------------------------------------------
def test_quadratic_cases():
    r = solve_quadratic([1, 0, 1, 1, 0, 1e-300], [-3, 2, 0, 2, 0, 1], [2, -1, 1, 1, 1, -0.5])
    assert r.shape == (2, 6)
    assert r[:, 0].tolist() == [1, 2]                       # (t - 1)(t - 2), ascending
    assert r[0, 1] == 0.5 and np.isnan(r[1, 1])             # linear 2t - 1
    assert np.all(np.isnan(r[:, 2]))                        # t^2 + 1: no real root
    assert r[:, 3].tolist() == [-1, -1]                     # (t + 1)^2: double root twice
    assert np.all(np.isnan(r[:, 4]))                        # the constant 1
    assert r[1, 5] == pytest.approx(0.5)                    # a ~ 0: the linear root kept
    assert r[0, 5] == pytest.approx(-1e300)                 # and the huge one
    assert solve_quadratic(1.0, 0.0, 0.0).tolist() == [0.0, 0.0]   # t^2


def test_quadratic_no_cancellation():
    # t^2 - 1e8 t + 1: the small root 1e-8 cancels in the textbook formula
    r = solve_quadratic(1.0, -1e8, 1.0)
    assert r[0] == pytest.approx(1e-8, rel=1e-15)
    assert r[1] == pytest.approx(1e8, rel=1e-15)


@pytest.mark.parametrize('scale', [1e-300, 1e-160, 1.0, 1e160, 1e300])
def test_quadratic_scale_invariance(scale):
    """Roots do not depend on the scale of the coefficients: the power-of-two
    normalisation keeps b^2 - 4ac from overflowing or underflowing, and
    changes no rounding (same bits as the unscaled solve)."""
    a, b, c = np.array([1.0, 3.0, -2.0]), np.array([-3.0, 1.0, 5.0]), np.array([2.0, -7.0, 1.0])
    ref = solve_quadratic(a, b, c)
    got = solve_quadratic(a * scale, b * scale, c * scale)
    assert np.allclose(got, ref, rtol=1e-14, equal_nan=True)
    if scale == 1.0:
        assert np.array_equal(solve_quadratic(a, b, c, normalize=False), ref, equal_nan=True)


@SETTINGS
@given(st.integers(-1000, 1000), st.integers(-1000, 1000), st.integers(-1000, 1000))
def test_quadratic_roots_are_roots(a, b, c):
    a, b, c = a / 7.0, b / 3.0, float(c)
    r = solve_quadratic(a, b, c)
    disc = b * b - 4 * a * c
    if a != 0:
        assert np.isnan(r).sum() == (2 if disc < 0 else 0)
    x = real(r)
    assert np.all(np.diff(x) >= 0)
    for v in x:
        scale = abs(a) * v * v + abs(b * v) + abs(c)
        assert abs(a * v * v + b * v + c) <= 1e-12 * max(scale, 1e-300)


@SETTINGS
@given(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.floats(0.01, 100))
def test_quadratic_against_numpy_roots(r1, r2, lead):
    """(t - r1)(t - r2) scaled: the roots numpy.roots finds, to relative
    precision (well separated roots only: a near double root is
    ill-conditioned in both)."""
    assume(abs(r1 - r2) > 1e-3 * max(1.0, abs(r1), abs(r2)))
    coef = lead * np.poly([r1, r2])
    want = np.sort(np.roots(coef).real)
    got = solve_quadratic(*coef)
    assert np.allclose(got, want, rtol=1e-9, atol=1e-9 * max(1.0, abs(r1), abs(r2)))


# -- cubics ---------------------------------------------------------------------------------
def test_cubic_analytic_roots():
    # (t - 1)(t - 2)(t - 3) = t^3 - 6t^2 + 11t - 6: exact integers
    assert solve_cubic(1.0, -6.0, 11.0, -6.0).tolist() == [1.0, 2.0, 3.0]
    # t^3 + t + 1: one real root, the real root of the depressed cubic
    r = solve_cubic(1.0, 0.0, 1.0, 1.0)
    x = real(r)
    assert len(x) == 1 and abs(x[0] ** 3 + x[0] + 1) < 1e-15
    # t^3 - 2: the cube root of 2, twice scaled
    assert real(solve_cubic(-4.0, 0.0, 0.0, 8.0)).tolist() == [pytest.approx(2 ** (1 / 3), rel=1e-15)]
    # t (t^2 + 1): the root 0 only
    assert real(solve_cubic(1.0, 0.0, 1.0, 0.0)).tolist() == [0.0]


@pytest.mark.parametrize('roots', [[1, 1, -2], [-3, 0.5, 0.5], [0, 0, 7], [2, 2, 2], [-1, -1, -1],
                                   [0.25, 0.25, -4]])
def test_cubic_double_and_triple_roots(roots):
    """Polynomials with a double (or triple) root and exact coefficients
    (dyadic roots): every root is reported with its multiplicity, within the
    sqrt(eps) (eps**(1/3) for a triple root) conditioning of a multiple
    root."""
    coef = np.poly(roots)
    got = solve_cubic(*coef)
    assert not np.any(np.isnan(got))
    tol = 1e-7 if len(set(roots)) == 2 else 1e-4
    assert np.allclose(got, np.sort(roots), atol=tol * max(1, np.abs(roots).max()))


@pytest.mark.parametrize('lead', [0.0, 1e-70, 1e-40, 1e-20, 1e-12, 1e-6])
def test_cubic_degenerate_leading_coefficient(lead):
    """(lead t + 1)(t - 0.3)(t - 0.7): the quadratic's roots stay accurate as
    the third root runs off to -1/lead; a leading coefficient below 1e-60 of
    the others is a quadratic."""
    coef = [lead, 1.0 - lead, 0.21 * lead - 1.0, 0.21]
    got = solve_cubic(*coef)
    x = real(got)
    small = x[np.abs(x) < 10]
    assert np.allclose(small, [0.3, 0.7], rtol=1e-13)
    if lead == 0 or lead < 1e-60:
        assert len(x) == 2
    else:
        assert len(x) == 3 and x[0] == pytest.approx(-1 / lead, rel=1e-12)


def test_cubic_all_zero_and_constant():
    assert np.all(np.isnan(solve_cubic(0.0, 0.0, 0.0, 0.0)))
    assert np.all(np.isnan(solve_cubic(0.0, 0.0, 0.0, 3.0)))
    assert real(solve_cubic(0.0, 0.0, 2.0, -1.0)).tolist() == [0.5]


def test_cubic_vectorized_shapes():
    a = np.ones((3, 4))
    r = solve_cubic(a, 0.0, -a, 0.0)                       # t^3 - t
    assert r.shape == (3, 3, 4)
    assert np.allclose(r[:, 1, 2], [-1, 0, 1])
    assert solve_cubic(1.0, -6.0, 11.0, -6.0).shape == (3,)


@pytest.mark.parametrize('scale', [1e-250, 1e-100, 1e100, 1e250])
def test_cubic_scale_invariance(scale):
    coef = np.poly([0.2, -3.0, 5.5])
    assert np.allclose(solve_cubic(*(coef * scale)), solve_cubic(*coef), rtol=1e-14)


@SETTINGS
@given(st.lists(st.floats(-100, 100), min_size=3, max_size=3), st.floats(0.01, 100),
       st.booleans())
def test_cubic_against_numpy_roots_three_real(rs, lead, negate):
    """Three well separated real roots: the same as numpy.roots (companion
    matrix eigenvalues) to relative precision."""
    rs = sorted(rs)
    span = max(1.0, max(abs(r) for r in rs))
    assume(min(rs[1] - rs[0], rs[2] - rs[1]) > 1e-2 * span)
    coef = (-lead if negate else lead) * np.poly(rs)
    want = np.sort(np.roots(coef).real)
    got = solve_cubic(*coef)
    assert np.allclose(got, want, rtol=0, atol=1e-8 * span)


@SETTINGS
@given(st.floats(-100, 100), st.floats(-100, 100), st.floats(0.1, 100), st.floats(0.01, 100))
def test_cubic_against_numpy_roots_one_real(r, re, im, lead):
    """One real root and a complex pair: the real root only."""
    coef = lead * np.real(np.poly([r, re + 1j * im, re - 1j * im]))
    ev = np.roots(coef)
    want = ev.real[np.abs(ev.imag) < 1e-9 * max(1.0, abs(r))]
    got = real(solve_cubic(*coef))
    assert len(want) == 1 and len(got) == 1
    span = max(1.0, abs(r), abs(re), im)
    assert abs(got[0] - want[0]) <= 1e-8 * span


_COEF = st.one_of(st.just(0.0), st.floats(1e-6, 10), st.floats(-10, -1e-6))


@SETTINGS
@given(st.lists(_COEF, min_size=4, max_size=4))
def test_cubic_roots_are_roots(coef):
    """Any coefficients (zero or within 1e-6 .. 10 in magnitude): every
    reported root has a residual at rounding level relative to the size of
    the terms."""
    a, b, c, d = coef
    assume(max(abs(v) for v in coef) > 0)
    for x in real(solve_cubic(a, b, c, d)):
        terms = abs(a * x ** 3) + abs(b * x * x) + abs(c * x) + abs(d)
        assert abs(((a * x + b) * x + c) * x + d) <= 1e-9 * terms


# -- polynomials on (0, 1) ------------------------------------------------------------------
def test_unit_interval_roots_analytic():
    # (u - 1/2)^2 (double root, reported twice), 1 + u (root -1: outside)
    r, k = unit_interval_roots([[0.25, -1.0, 1.0], [1.0, 1.0, 0.0]])
    assert r.tolist() == [0.5, 0.5] and k.tolist() == [0, 0]
    # a quartic with roots 0.2, 0.5, 0.7 and 3 (degree 4: companion matrix)
    coef = np.poly([0.2, 0.5, 0.7, 3.0])[::-1]
    r, k = unit_interval_roots(coef[None])
    assert np.allclose(np.sort(r), [0.2, 0.5, 0.7], atol=1e-12) and k.tolist() == [0, 0, 0]


@pytest.mark.parametrize('m', [1, 2, 3, 4, 6, 9])
def test_unit_interval_roots_every_degree(m):
    rng = np.random.default_rng(m)
    K = 40
    roots = rng.uniform(-0.5, 1.5, (K, m))
    coef = np.array([np.poly(r)[::-1] for r in roots]) * rng.uniform(0.5, 2, (K, 1))
    r, k = unit_interval_roots(coef)
    for row in range(K):
        want = np.sort(roots[row][(roots[row] > 1e-6) & (roots[row] < 1 - 1e-6)])
        got = np.sort(r[k == row])
        # rows whose roots are close to each other are ill-conditioned
        if len(want) > 1 and np.diff(want).min() < 1e-3:
            continue
        assert len(got) == len(want), (row, want, got)
        assert np.allclose(got, want, atol=1e-8)
    assert np.all(np.diff(k) >= 0)                     # rows in order


def test_unit_interval_roots_margin_and_zero_rows():
    # roots exactly at 0 and 1 are left out; an all-zero row has none
    coef = np.array([np.poly([0.0, 0.5, 1.0])[::-1], np.zeros(4)])
    r, k = unit_interval_roots(coef)
    assert r.tolist() == pytest.approx([0.5]) and k.tolist() == [0]
    r, k = unit_interval_roots(np.zeros((3, 1)))
    assert len(r) == len(k) == 0
