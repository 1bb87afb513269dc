"""Tests of raster.geometry.patches: tensor-product Bezier patches, Coons
and Hermite nets, subdivision and the linearization bound."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.errors import LimitError
from raster.geometry import patches as P


def direct_patch(net, u, v):
    """S(u, v) by the double Bernstein sum written out (independent)."""
    m, n = net.shape[0] - 1, net.shape[1] - 1
    out = np.zeros(net.shape[2])
    for i in range(m + 1):
        bi = math.comb(m, i) * u ** i * (1 - u) ** (m - i)
        for j in range(n + 1):
            out += bi * math.comb(n, j) * v ** j * (1 - v) ** (n - j) * net[i, j]
    return out


def bezier_point(ctrl, t):
    """A Bezier curve point by de Casteljau (independent of the module)."""
    pts = np.array(ctrl, float)
    while len(pts) > 1:
        pts = (1 - t) * pts[:-1] + t * pts[1:]
    return pts[0]


def test_bernstein_partition_of_unity_and_derivative():
    t = np.linspace(0, 1, 11)
    for n in range(0, 7):
        np.testing.assert_allclose(P.bernstein_basis(n, t).sum(1), 1.0, atol=1e-14)
        # derivatives of a sum that is identically 1 vanish
        np.testing.assert_allclose(P.bernstein_basis(n, t, 1).sum(1), 0.0, atol=1e-12)
    # B_{3,1}(t) = 3t(1-t)^2: B' = 3 - 12t + 9t^2, B'' = -12 + 18t
    tt = np.array([0.2, 0.7])
    np.testing.assert_allclose(P.bernstein_basis(3, tt, 1)[:, 1], 3 - 12 * tt + 9 * tt ** 2)
    np.testing.assert_allclose(P.bernstein_basis(3, tt, 2)[:, 1], -12 + 18 * tt)
    assert not P.bernstein_basis(2, tt, 3).any()


def test_tensor_eval_matches_the_double_sum():
    rng = np.random.default_rng(3)
    for m, n in ((1, 1), (2, 3), (4, 2), (5, 5)):
        net = rng.normal(size=(m + 1, n + 1, 3))
        uv = rng.uniform(size=(20, 2))
        got = P.tensor_eval(net, uv[:, 0], uv[:, 1])[0]
        ref = np.array([direct_patch(net, a, b) for a, b in uv])
        np.testing.assert_allclose(got, ref, atol=1e-12)
        # per-patch parameters and pointwise evaluation agree with it
        two = np.stack([net, 2 * net])
        pp = P.tensor_eval(two, np.stack([uv[:, 0]] * 2), np.stack([uv[:, 1]] * 2))
        np.testing.assert_allclose(pp[1], 2 * ref, atol=1e-12)
        pts = P.tensor_points(two, np.ones(20, int), uv[:, 0], uv[:, 1])
        np.testing.assert_allclose(pts, 2 * ref, atol=1e-12)


def test_partial_derivatives_against_finite_differences():
    rng = np.random.default_rng(4)
    net = rng.normal(size=(4, 3, 2))
    u, v, h = 0.37, 0.61, 1e-6
    S = lambda a, b: P.tensor_eval(net, [a], [b])[0, 0]                # noqa: E731
    su = P.tensor_eval(net, [u], [v], du=1)[0, 0]
    sv = P.tensor_eval(net, [u], [v], dv=1)[0, 0]
    suv = P.tensor_eval(net, [u], [v], du=1, dv=1)[0, 0]
    np.testing.assert_allclose(su, (S(u + h, v) - S(u - h, v)) / (2 * h), atol=1e-7)
    np.testing.assert_allclose(sv, (S(u, v + h) - S(u, v - h)) / (2 * h), atol=1e-7)
    fd = (S(u + h, v + h) - S(u + h, v - h) - S(u - h, v + h) + S(u - h, v - h)) / (4 * h * h)
    np.testing.assert_allclose(suv, fd, atol=1e-4)


def test_grid_is_the_tensor_product_of_the_parameters():
    rng = np.random.default_rng(5)
    net = rng.normal(size=(2, 4, 3, 3))
    us, vs = np.array([0, 0.3, 1.0]), np.array([0.1, 0.9])
    g = P.tensor_grid(net, us, vs)
    assert g.shape == (2, 3, 2, 3)
    np.testing.assert_allclose(g[1, 1, 0], direct_patch(net[1], 0.3, 0.1), atol=1e-12)


def coons_direct(top, bottom, left, right, u, v):
    """The Coons formula S_C + S_D - S_B of SVG 2 / PDF, evaluated from the
    boundary curves themselves."""
    c1, c2 = bezier_point(top, u), bezier_point(bottom, u)
    d1, d2 = bezier_point(left, v), bezier_point(right, v)
    sc = (1 - v) * c1 + v * c2
    sd = (1 - u) * d1 + u * d2
    sb = ((1 - v) * ((1 - u) * top[0] + u * top[-1]) + v * ((1 - u) * bottom[0] + u * bottom[-1]))
    return sc + sd - sb


@pytest.mark.parametrize('n', [1, 2, 3, 5])
def test_coons_net_is_the_coons_patch(n):
    rng = np.random.default_rng(10 + n)
    c = rng.normal(size=(4, 2))                 # corners 00, 10, 01, 11
    top = np.vstack([c[0], rng.normal(size=(n - 1, 2)), c[1]])
    bottom = np.vstack([c[2], rng.normal(size=(n - 1, 2)), c[3]])
    left = np.vstack([c[0], rng.normal(size=(n - 1, 2)), c[2]])
    right = np.vstack([c[1], rng.normal(size=(n - 1, 2)), c[3]])
    net = P.coons_net(top, bottom, left, right)
    uv = rng.uniform(size=(30, 2))
    got = P.tensor_eval(net, uv[:, 0], uv[:, 1])[0]
    ref = np.array([coons_direct(top, bottom, left, right, a, b) for a, b in uv])
    np.testing.assert_allclose(got, ref, atol=1e-12)
    # boundary rows are the curves
    np.testing.assert_array_equal(net[0, :, 0], top)
    np.testing.assert_array_equal(net[0, 0, :], left)


def test_cubic_coons_interior_point_is_the_pdf_formula():
    # PDF type-6 -> type-7: p11 = (-4 p00 + 6 (p01 + p10) - 2 (p03 + p30)
    #                             + 3 (p31 + p13) - p33) / 9
    rng = np.random.default_rng(7)
    b = rng.normal(size=(12, 2))
    net = P.mesh_patch_nets([b])[0]
    p = lambda i, j: net[j, i]                    # PDF p[row=v][col=u]  # noqa: E731
    want = (-4 * p(0, 0) + 6 * (p(0, 1) + p(1, 0)) - 2 * (p(0, 3) + p(3, 0))
            + 3 * (p(3, 1) + p(1, 3)) - p(3, 3)) / 9
    np.testing.assert_allclose(net[1, 1], want, atol=1e-13)
    # corners of the mesh patch: 0, 3, 6, 9 at S(0,0), S(1,0), S(1,1), S(0,1)
    np.testing.assert_array_equal([net[0, 0], net[3, 0], net[3, 3], net[0, 3]], b[[0, 3, 6, 9]])


def test_coons_corners_must_meet():
    line = np.linspace([0, 0], [1, 0], 4)
    with pytest.raises(P.PatchError, match='corner'):
        P.coons_net(line, line + [0, 1], line[:, ::-1] + [0.5, 0], line[:, ::-1] + [1, 0])


def test_hermite_net_reproduces_corner_data():
    rng = np.random.default_rng(8)
    pts, du, dv, tw = (rng.normal(size=(1, 2, 2, 3)) for _ in range(4))
    net = P.hermite_net(pts, du, dv, tw)
    for a in (0, 1):
        for b in (0, 1):
            np.testing.assert_allclose(P.tensor_eval(net, [a], [b])[0, 0], pts[0, a, b], atol=1e-12)
            np.testing.assert_allclose(P.tensor_eval(net, [a], [b], 1, 0)[0, 0], du[0, a, b],
                                       atol=1e-12)
            np.testing.assert_allclose(P.tensor_eval(net, [a], [b], 0, 1)[0, 0], dv[0, a, b],
                                       atol=1e-12)
            np.testing.assert_allclose(P.tensor_eval(net, [a], [b], 1, 1)[0, 0], tw[0, a, b],
                                       atol=1e-12)


def test_split_and_subpatch_are_exact():
    rng = np.random.default_rng(9)
    net = rng.normal(size=(3, 4, 3, 2))
    a, b = P.split_patches(net, 0.3, 'v')
    s = np.linspace(0, 1, 7)
    np.testing.assert_allclose(P.tensor_grid(a, s, s), P.tensor_grid(net, s, 0.3 * s), atol=1e-12)
    np.testing.assert_allclose(P.tensor_grid(b, s, s), P.tensor_grid(net, s, 0.3 + 0.7 * s),
                               atol=1e-12)
    q = P.subpatches(net, [0.1] * 3, [0.6] * 3, [0.2] * 3, [0.9] * 3)
    np.testing.assert_allclose(P.tensor_grid(q, s, s),
                               P.tensor_grid(net, 0.1 + 0.5 * s, 0.2 + 0.7 * s), atol=1e-12)


def test_derivative_bounds_hold():
    rng = np.random.default_rng(11)
    net = rng.normal(size=(6, 4, 5, 2))
    A, B, C = P.derivative_bounds(net)
    s = np.linspace(0, 1, 41)
    for k, (du, dv) in enumerate(((2, 0), (0, 2), (1, 1))):
        d = np.linalg.norm(P.tensor_grid(net, s, s, du, dv), axis=-1).reshape(6, -1).max(1)
        assert np.all(d <= (A, B, C)[k] * (1 + 1e-12))


def triangulation_error(net, nu, nv, k=9):
    """Largest distance between the grid's triangles and the patch at the
    same (linearly interpolated) parameters, sampled k x k per triangle."""
    us, vs = np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1)
    G = P.tensor_grid(net[None], us, vs)[0]
    a, b = np.meshgrid(np.linspace(0, 1, k), np.linspace(0, 1, k), indexing='ij')
    lo = a + b <= 1
    a, b = a[lo], b[lo]
    worst = 0.0
    for i in range(nu):
        for j in range(nv):
            # triangles (00, 10, 11) and (00, 11, 01)
            for (p1, q1), (p2, q2) in (((1, 0), (1, 1)), ((1, 1), (0, 1))):
                x = (G[i, j] + a[:, None] * (G[i + p1, j + q1] - G[i, j])
                     + b[:, None] * (G[i + p2, j + q2] - G[i, j]))
                u = us[i] + (a * p1 + b * p2) * (us[1] - us[0])
                v = vs[j] + (a * q1 + b * q2) * (vs[1] - vs[0])
                s = P.tensor_eval(net, u, v)[0]
                worst = max(worst, float(np.linalg.norm(x - s, axis=1).max()))
    return worst


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2 ** 31), st.floats(0.05, 2.0), st.integers(1, 4), st.integers(1, 4))
def test_grid_counts_honour_the_tolerance(seed, tol, m, n):
    rng = np.random.default_rng(seed)
    net = rng.normal(scale=20, size=(m + 1, n + 1, 2))
    nu, nv = P.grid_counts(net[None], tol)
    bound = P.linearization_error(net[None], nu, nv)[0]
    assert bound <= tol * (1 + 1e-12)
    if nu[0] * nv[0] <= 400:
        assert triangulation_error(net, int(nu[0]), int(nv[0])) <= bound * (1 + 1e-9) + 1e-12


def test_grid_counts_limit_and_bad_input():
    net = np.zeros((1, 4, 4, 2))
    net[0, 1, 1] = 1e6
    with pytest.raises(LimitError):
        P.grid_counts(net, 1e-6, max_count=100)
    with pytest.raises(P.PatchError):
        P.grid_counts(net, 0)
    with pytest.raises(P.PatchError):
        P.tensor_eval(np.zeros((3, 3)), [0], [0])
    with pytest.raises(P.PatchError):
        P.tensor_eval(np.zeros((2, 2, 2)), [1.5], [0])
    with pytest.raises(P.PatchError):
        P.mesh_patch_nets(np.zeros((1, 11, 2)))
