"""Tests of raster.geometry.bezier: evaluation against the Bernstein sum,
split and subsegment reproduce the curve, derivatives against finite
differences, power basis, elevation, extrema and exact bounds, for segments
of any degree and batches of them."""

from math import comb

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.errors import PathError
from raster.geometry import bezier as bz

DEGREES = [1, 2, 3, 4, 5, 8, 9, 12, 20]


def bernstein_sum(ctrl, t):
    """B(t) = sum_i C(n, i) t^i (1 - t)^(n - i) P_i, written out: (M, D)."""
    ctrl = np.asarray(ctrl, float)
    n = len(ctrl) - 1
    t = np.asarray(t, float)[:, None]
    return sum(comb(n, i) * t ** i * (1 - t) ** (n - i) * ctrl[i] for i in range(n + 1))


def random_ctrl(rng, n, batch=(), D=2):
    return rng.uniform(-100, 100, batch + (n + 1, D))


# -- bases ----------------------------------------------------------------------------------
@pytest.mark.parametrize('n', [0, 1, 2, 3, 7, 30])
def test_bernstein_basis_is_the_product_formula_and_a_partition_of_unity(n):
    t = np.linspace(0, 1, 101)
    B = bz.bernstein(n, t)
    want = np.array([[comb(n, i) * x ** i * (1 - x) ** (n - i) for i in range(n + 1)] for x in t])
    assert B.shape == (101, n + 1)
    assert np.allclose(B, want, rtol=1e-13, atol=1e-300)
    assert np.allclose(B.sum(axis=1), 1.0, rtol=1e-13)
    assert bz.bernstein(n, 0.3).shape == (n + 1,)


@pytest.mark.parametrize('n', [0, 1, 2, 5, 11])
def test_bernstein_matrix_gives_power_coefficients(n):
    M = bz.bernstein_matrix(n)
    t = np.linspace(0, 1, 17)
    powers = t[:, None] ** np.arange(n + 1)
    assert np.allclose(powers @ M, bz.bernstein(n, t), atol=1e-12)
    M[0, 0] = 99.0                                    # a fresh copy every time
    assert bz.bernstein_matrix(n)[0, 0] == 1.0


def test_bad_degrees_are_refused():
    for bad in (-1, 1.5, True, '3'):
        with pytest.raises(PathError):
            bz.bernstein(bad, 0.5)
    with pytest.raises(PathError):
        bz.evaluate(np.zeros((0, 2)), 0.5)


# -- evaluation -----------------------------------------------------------------------------
@pytest.mark.parametrize('n', DEGREES)
def test_evaluate_equals_the_bernstein_sum(n):
    rng = np.random.default_rng(n)
    ctrl = random_ctrl(rng, n)
    t = rng.uniform(0, 1, 50)
    assert np.allclose(bz.evaluate(ctrl, t), bernstein_sum(ctrl, t), rtol=0, atol=1e-9)
    # exact end points
    ends = bz.evaluate(ctrl, [0.0, 1.0])
    assert np.array_equal(ends, ctrl[[0, -1]])


def test_evaluate_broadcasts_batches_and_parameters():
    rng = np.random.default_rng(1)
    ctrl = random_ctrl(rng, 3, (4, 5), D=3)
    t = rng.uniform(0, 1, (4, 5))
    out = bz.evaluate(ctrl, t)
    assert out.shape == (4, 5, 3)
    assert np.allclose(out[2, 3], bernstein_sum(ctrl[2, 3], [t[2, 3]])[0], atol=1e-10)
    # one segment, many parameters; degree 0 (a constant) too
    assert bz.evaluate(ctrl[0, 0], np.linspace(0, 1, 7)).shape == (7, 3)
    assert bz.evaluate([[2.0, 3.0]], np.linspace(0, 1, 4)).tolist() == [[2.0, 3.0]] * 4


# -- subdivision ----------------------------------------------------------------------------
@pytest.mark.parametrize('n', DEGREES)
def test_split_halves_reproduce_the_curve(n):
    rng = np.random.default_rng(10 + n)
    ctrl = random_ctrl(rng, n, (6,))
    t = rng.uniform(0.05, 0.95, 6)
    left, right = bz.split(ctrl, t)
    s = np.linspace(0, 1, 21)
    for k in range(6):
        whole_l = bernstein_sum(ctrl[k], t[k] * s)
        whole_r = bernstein_sum(ctrl[k], t[k] + (1 - t[k]) * s)
        assert np.allclose(bernstein_sum(left[k], s), whole_l, atol=1e-8)
        assert np.allclose(bernstein_sum(right[k], s), whole_r, atol=1e-8)
    assert np.array_equal(left[:, 0], ctrl[:, 0]) and np.array_equal(right[:, -1], ctrl[:, -1])
    assert np.array_equal(left[:, -1], right[:, 0])


@settings(max_examples=80, deadline=None)
@given(st.sampled_from(DEGREES), st.floats(0, 1), st.floats(0, 1), st.integers(0, 2 ** 32 - 1))
def test_subsegment_reproduces_the_curve(n, t0, t1, seed):
    """The piece [t0, t1] (reversed for t0 > t1) traces B(t0 + (t1 - t0) s)."""
    ctrl = random_ctrl(np.random.default_rng(seed), n)
    piece = bz.subsegment(ctrl, t0, t1)
    s = np.linspace(0, 1, 17)
    assert np.allclose(bernstein_sum(piece, s), bernstein_sum(ctrl, t0 + (t1 - t0) * s),
                       rtol=0, atol=1e-8)


@pytest.mark.parametrize('n', [1, 2, 3, 5, 8, 9, 15])
def test_blossom_pieces_for_few_and_many_pieces_agree(n):
    """The index-table blossom (up to 256 pieces), the term-by-term one (more
    pieces) and, above degree 8, the two-split one give the same pieces,
    with exact end points at t = 0 and t = 1."""
    rng = np.random.default_rng(n)
    m = 50
    P = rng.normal(0, 100, (n + 1, 2, m))
    a = rng.uniform(0, 1, m)
    b = np.where(np.arange(m) % 3 == 0, 1.0, a + rng.uniform(0, 1, m) * (1 - a))
    a[::5] = 0.0
    b[7] = 0.2                                      # one reversed piece
    few = bz.blossom_pieces(P, a, b)
    many = bz.blossom_pieces(np.tile(P, 6), np.tile(a, 6), np.tile(b, 6))[:, :, :m]
    assert np.abs(few - many).max() <= 1e-12 * np.abs(P).max()
    # against de Casteljau subsegments of the (S, n+1, D) layout
    s = np.linspace(0, 1, 9)
    for k in (0, 7, 11):
        ref = bernstein_sum(P[:, :, k], a[k] + (b[k] - a[k]) * s)
        assert np.allclose(bernstein_sum(few[:, :, k], s), ref, atol=1e-8)
    one, zero = b == 1.0, a == 0.0
    assert np.array_equal(few[n][:, one], P[n][:, one])
    assert np.array_equal(few[0][:, zero], P[0][:, zero])


# -- derivatives, power basis, elevation ------------------------------------------------------
@pytest.mark.parametrize('n', DEGREES)
def test_derivative_against_finite_differences(n):
    rng = np.random.default_rng(20 + n)
    ctrl = random_ctrl(rng, n)
    d = bz.derivative(ctrl)
    assert d.shape == (n, 2)
    t = rng.uniform(0.1, 0.9, 20)
    h = 1e-6
    fd = (bernstein_sum(ctrl, t + h) - bernstein_sum(ctrl, t - h)) / (2 * h)
    scale = np.abs(ctrl).max() * n * n
    assert np.allclose(bz.evaluate(d, t), fd, rtol=0, atol=1e-6 * scale)
    # the point-major layout: derivative along axis 0
    assert np.array_equal(bz.derivative(ctrl.reshape(n + 1, 2, 1), axis=0)[:, :, 0], d)
    assert bz.derivative([[1.0, 2.0]]).tolist() == [[0.0, 0.0]]       # of a constant


@pytest.mark.parametrize('n', [0, 1, 2, 3, 6])
def test_power_coefficients_evaluate_to_the_curve(n):
    rng = np.random.default_rng(30 + n)
    ctrl = random_ctrl(rng, n, (3,))
    coef = bz.power_coeffs(ctrl)                         # (3, n+1, 2), lowest order first
    t = np.linspace(0, 1, 11)
    for k in range(3):
        v = (t[:, None, None] ** np.arange(n + 1)[None, :, None] * coef[k][None]).sum(1)
        assert np.allclose(v, bernstein_sum(ctrl[k], t), atol=1e-9)


@pytest.mark.parametrize('n, times', [(1, 1), (2, 1), (3, 4), (7, 2)])
def test_elevation_keeps_the_curve(n, times):
    rng = np.random.default_rng(40 + n)
    ctrl = random_ctrl(rng, n, (2,))
    up = bz.elevate(ctrl, times)
    assert up.shape == (2, n + 1 + times, 2)
    t = np.linspace(0, 1, 13)
    assert np.allclose(bz.evaluate(up, t[:, None]), bz.evaluate(ctrl, t[:, None]), atol=1e-10)


# -- extrema and bounds ---------------------------------------------------------------------
def test_bernstein_range_of_known_cubics():
    # (0, 1, 1, 0): 3 t (1 - t), maximum 3/4 at t = 1/2
    # (0, -1, 1, 0): 3 t (1 - t) (1 - 2 t), extrema -+sqrt(3)/6 at t = 1/2 -+ sqrt(3)/6
    c = np.array([[0.0, 0.0], [1.0, -1.0], [1.0, 1.0], [0.0, 0.0]])
    lo, hi = bz.bernstein_range(c)
    assert lo[0] == 0.0 and abs(hi[0] - 0.75) < 1e-15
    assert abs(lo[1] + np.sqrt(3) / 6) < 1e-15 and abs(hi[1] - np.sqrt(3) / 6) < 1e-15
    # the same without normalisation, bit for bit
    lo2, hi2 = bz.bernstein_range(c, normalize=False)
    assert np.array_equal(lo, lo2) and np.array_equal(hi, hi2)


@pytest.mark.parametrize('n', DEGREES)
def test_bounds_against_dense_sampling(n):
    rng = np.random.default_rng(50 + n)
    ctrl = random_ctrl(rng, n, (8,))
    lo, hi = bz.bounds(ctrl)
    t = np.linspace(0, 1, 20001)
    for k in range(8):
        p = bernstein_sum(ctrl[k], t)
        slo, shi = p.min(0), p.max(0)
        eps = 1e-7 * 200
        assert np.all(slo >= lo[k] - 1e-9) and np.all(shi <= hi[k] + 1e-9)
        assert np.all(slo - lo[k] <= eps) and np.all(hi[k] - shi <= eps)


@pytest.mark.parametrize('n', [2, 3, 4, 5, 7])
def test_extrema_are_stationary_points(n):
    rng = np.random.default_rng(60 + n)
    ctrl = random_ctrl(rng, n, (30,))
    t = bz.extrema(ctrl)
    assert t.shape == (30, 2, n - 1)
    ok = ~np.isnan(t)
    assert np.all((t[ok] > 0) & (t[ok] < 1)) and ok.sum() > 10
    s, ax, _ = np.nonzero(ok)
    d = bz.evaluate(bz.derivative(ctrl[s]), t[ok])[np.arange(len(s)), ax]
    assert np.all(np.abs(d) <= 1e-7 * np.abs(ctrl).max() * n)
    # NaN padding comes last, parameters ascend
    filled = np.where(ok, t, 2.0)
    assert np.all(np.diff(filled, axis=-1) >= 0)


def test_extrema_of_named_curves():
    # the parabola (0,0) (1,2) (2,0): y extremal at t = 1/2, x monotone
    t = bz.extrema([[0, 0], [1, 2], [2, 0]])
    assert t.shape == (2, 1) and np.isnan(t[0, 0]) and t[1, 0] == 0.5
    # the cubic (0,0) (0,1) (1,1) (1,0): y extremal at t = 1/2
    t = bz.extrema([[0, 0], [0, 1], [1, 1], [1, 0]])
    assert np.all(np.isnan(t[0])) and t[1].tolist()[0] == 0.5
    # lines have none
    assert bz.extrema([[0, 0], [3, 4]]).shape == (2, 0)


@pytest.mark.parametrize('scale', [1e-200, 1e-20, 1e20, 1e200])
def test_bounds_are_scale_invariant(scale):
    rng = np.random.default_rng(70)
    ctrl = random_ctrl(rng, 3, (20,))
    lo, hi = bz.bounds(ctrl)
    lo2, hi2 = bz.bounds(ctrl * scale)
    assert np.allclose(lo2 / scale, lo, rtol=1e-12) and np.allclose(hi2 / scale, hi, rtol=1e-12)


def test_segment_bounds_equal_per_degree_bounds():
    rng = np.random.default_rng(80)
    S = 300
    ctrl = rng.uniform(0, 100, (S, 4, 2))
    deg = rng.integers(1, 4, S)
    for k in (1, 2):
        ctrl[deg == k, k + 1:] = ctrl[deg == k, k:k + 1]
    lo, hi = bz.segment_bounds(ctrl, deg)
    t = bz.segment_extrema(ctrl, deg)
    assert t.shape == (S, 2, 2) and np.all(np.isnan(t[deg == 1]))
    for s in range(0, S, 7):
        l1, h1 = bz.bounds(ctrl[s, :deg[s] + 1])
        assert np.array_equal(lo[s], l1) and np.array_equal(hi[s], h1)
