"""Surfaces: Bezier, B-spline and NURBS surfaces, Hermite and Coons
patches.  Analytic checks (a NURBS sphere octant, bilinear and Hermite
patches), and hypothesis properties: convex hull, affine invariance,
end-point (corner and boundary) interpolation."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.curves import (Bezier, BezierSurface, BSplineSurface, CoonsPatch, CurveError,
                           HermitePatch, NURBS, NURBSSurface)

R2 = 2 ** -0.5


def sphere_octant():
    """The unit sphere's octant x, y, z >= 0 as a biquadratic NURBS: the
    quarter circle from the pole to the equator revolved by a quarter
    circle (net = profile x revolution, weights multiplied)."""
    prof = [(0, 1), (1, 1), (1, 0)]            # (radius, z)
    pw = [1, R2, 1]
    rev = [(1, 0), (1, 1), (0, 1)]
    rw = [1, R2, 1]
    net = np.array([[[r * c, r * s, z] for (c, s) in rev] for (r, z) in prof], float)
    w = np.outer(pw, rw)
    return NURBSSurface(net, 2, (None, None), w)


def test_sphere_octant_points_and_normals_are_exact():
    s = sphere_octant()
    g = np.linspace(0, 1, 41)
    U, V = (x.ravel() for x in np.meshgrid(g, g))
    p = s.eval(U, V)
    np.testing.assert_allclose(np.linalg.norm(p, axis=1), 1.0, rtol=0, atol=1e-12)
    n = s.normal(U, V)
    # normals are radial and point outwards (S_u x S_v with u from the pole
    # down, v around); at the pole (u = 0, a collapsed edge, S_v = 0) the
    # limit normal from inside is used
    np.testing.assert_allclose(n[U > 0], p[U > 0], atol=1e-12)
    np.testing.assert_allclose(n[U == 0], np.tile([0, 0, 1.0], ((U == 0).sum(), 1)), atol=1e-9)
    assert np.all(np.isfinite(n))


def test_bezier_surface_is_the_double_sum():
    rng = np.random.default_rng(1)
    net = rng.normal(size=(4, 3, 3))
    s = BezierSurface(net)
    u, v = 0.3, 0.8
    want = sum(math.comb(3, i) * u ** i * (1 - u) ** (3 - i) * math.comb(2, j) * v ** j
               * (1 - v) ** (2 - j) * net[i, j] for i in range(4) for j in range(3))
    np.testing.assert_allclose(s.eval(u, v), want, atol=1e-13)
    Bu, Bv = s.blending(u, v)
    np.testing.assert_allclose(np.einsum('i,j,ijd->d', Bu[0], Bv[0], net), want, atol=1e-13)
    # partials by finite differences
    h = 1e-6
    np.testing.assert_allclose(s.partial(u, v, 1, 0), (s.eval(u + h, v) - s.eval(u - h, v)) / (2 * h),
                               atol=1e-7)
    np.testing.assert_allclose(s.partial(u, v, 0, 1), (s.eval(u, v + h) - s.eval(u, v - h)) / (2 * h),
                               atol=1e-7)
    # isocurves and splitting
    np.testing.assert_allclose(s.isocurve(u=u).eval(v), want, atol=1e-13)
    np.testing.assert_allclose(s.isocurve(v=v).eval(u), want, atol=1e-13)
    a, b = s.split(0.4, 'u')
    np.testing.assert_allclose(a.eval(u / 0.4, v), want, atol=1e-13)
    np.testing.assert_allclose(s.subpatch(0.2, 0.6, 0.5, 1.0).eval(0.25, 0.6), want, atol=1e-13)


def test_bilinear_patch_normal():
    # the hyperbolic paraboloid z = x y over the unit square
    s = BezierSurface([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]])
    x, y = 0.3, 0.7
    n = s.normal(x, y)
    want = np.array([-y, -x, 1.0]) / math.sqrt(x * x + y * y + 1)
    np.testing.assert_allclose(n, want, atol=1e-14)
    with pytest.raises(CurveError, match='3-D'):
        BezierSurface([[[0, 0], [0, 1]], [[1, 0], [1, 1]]]).normal(0.5, 0.5)


def test_hermite_patch_reproduces_its_corner_data():
    rng = np.random.default_rng(2)
    P, Pu, Pv, T = (rng.normal(size=(2, 2, 3)) for _ in range(4))
    s = HermitePatch(P, Pu, Pv, T)
    for a in (0, 1):
        for b in (0, 1):
            np.testing.assert_allclose(s.eval(a, b), P[a, b], atol=1e-13)
            np.testing.assert_allclose(s.partial(a, b, 1, 0), Pu[a, b], atol=1e-12)
            np.testing.assert_allclose(s.partial(a, b, 0, 1), Pv[a, b], atol=1e-12)
            np.testing.assert_allclose(s.partial(a, b, 1, 1), T[a, b], atol=1e-12)
    # the Hermite form S = U M G M^T V^T for one coordinate
    M = np.array([[2, -2, 1, 1], [-3, 3, -2, -1], [0, 0, 1, 0], [1, 0, 0, 0]], float)
    G = np.block([[P[..., 0], Pv[..., 0]], [Pu[..., 0], T[..., 0]]])
    u, v = 0.35, 0.6
    Uv, Vv = np.array([u ** 3, u ** 2, u, 1]), np.array([v ** 3, v ** 2, v, 1])
    assert s.eval(u, v)[0] == pytest.approx(Uv @ M @ G @ M.T @ Vv, abs=1e-13)


def test_coons_patch_interpolates_its_boundary():
    top = Bezier([[0, 0, 0], [1, 0, 1], [2, 0, 1], [3, 0, 0]])
    bottom = Bezier([[0, 3, 0], [1, 3, -1], [3, 3, 0]])               # degree 2: elevated
    left = Bezier([[0, 0, 0], [0, 1.5, 2], [0, 3, 0]])
    right = Bezier([[3, 0, 0], [3.5, 1, 0], [3.5, 2, 0], [3, 3, 0]])
    s = CoonsPatch(top, bottom, left, right)
    t = np.linspace(0, 1, 11)
    np.testing.assert_allclose(s.eval(t, 0 * t), top.eval(t), atol=1e-13)
    np.testing.assert_allclose(s.eval(t, 0 * t + 1), bottom.eval(t), atol=1e-13)
    np.testing.assert_allclose(s.eval(0 * t, t), left.eval(t), atol=1e-13)
    np.testing.assert_allclose(s.eval(0 * t + 1, t), right.eval(t), atol=1e-13)
    u, v = 0.3, 0.55
    sc = (1 - v) * top.eval(u) + v * bottom.eval(u)
    sd = (1 - u) * left.eval(v) + u * right.eval(v)
    sb = ((1 - u) * (1 - v) * top.eval(0) + u * (1 - v) * top.eval(1) + (1 - u) * v * bottom.eval(0)
          + u * v * bottom.eval(1))
    np.testing.assert_allclose(s.eval(u, v), sc + sd - sb, atol=1e-13)
    with pytest.raises(CurveError, match='corner'):
        CoonsPatch(top, bottom, left, Bezier([[3, 1, 0], [3, 3, 0]]))


def clamped(rng, n, p):
    inner = np.sort(rng.uniform(0.1, 0.9, n - p - 1))
    return np.concatenate([np.zeros(p + 1), inner, np.ones(p + 1)])


def support_ok(points, net):
    """Every surface point inside the control net's convex hull: support
    functions in many directions."""
    rng = np.random.default_rng(0)
    d = rng.normal(size=(64, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    flat = net.reshape(-1, 3)
    scale = 1e-9 * max(1.0, np.abs(flat).max())
    return bool(np.all((points @ d.T).max(0) <= (flat @ d.T).max(0) + scale)
                and np.all((points @ d.T).min(0) >= (flat @ d.T).min(0) - scale))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 31), st.integers(1, 4), st.integers(1, 4))
def test_bezier_surface_properties(seed, m, n):
    rng = np.random.default_rng(seed)
    net = rng.uniform(-10, 10, (m + 1, n + 1, 3))
    s = BezierSurface(net)
    g = np.linspace(0, 1, 9)
    U, V = (x.ravel() for x in np.meshgrid(g, g))
    X = s.eval(U, V)
    assert support_ok(X, net)
    np.testing.assert_allclose(s.corners(), net[[0, -1, 0, -1], [0, 0, -1, -1]], atol=1e-12)
    np.testing.assert_allclose(s.eval(g, 0 * g), Bezier(net[:, 0]).eval(g), atol=1e-12)
    A, o = rng.normal(size=(3, 3)), rng.normal(size=3)
    np.testing.assert_allclose(s.transform(A, o).eval(U, V), X @ A.T + o, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 31), st.integers(1, 3), st.integers(1, 3), st.booleans())
def test_nurbs_surface_properties(seed, p, q, rational):
    rng = np.random.default_rng(seed)
    nu, nv = p + 1 + int(rng.integers(0, 3)), q + 1 + int(rng.integers(0, 3))
    net = rng.uniform(-10, 10, (nu, nv, 3))
    w = rng.uniform(0.2, 5, (nu, nv)) if rational else None
    ku, kv = clamped(rng, nu, p), clamped(rng, nv, q)
    s = NURBSSurface(net, (p, q), (ku, kv), w) if rational else BSplineSurface(net, (p, q),
                                                                                 (ku, kv))
    g = np.linspace(0, 1, 9)
    U, V = (x.ravel() for x in np.meshgrid(g, g))
    X = s.eval(U, V)
    assert support_ok(X, net)
    # clamped knots: the corners are the corner control points, the
    # boundary is the boundary curve of the net
    np.testing.assert_allclose(s.corners(), net[[0, -1, 0, -1], [0, 0, -1, -1]], atol=1e-12)
    ww = np.ones((nu, nv)) if w is None else w
    edge = NURBS(net[:, 0], ww[:, 0], p, ku)
    np.testing.assert_allclose(s.eval(g, 0 * g), edge.eval(g), atol=1e-12)
    A, o = rng.normal(size=(3, 3)), rng.normal(size=3)
    np.testing.assert_allclose(s.transform(A, o).eval(U, V), X @ A.T + o, atol=1e-9)
    # knot insertion changes the net, not the surface
    np.testing.assert_allclose(s.insert_knot('v', 0.5).eval(U, V), X, atol=1e-10)


def test_errors():
    with pytest.raises(CurveError, match='shape'):
        BezierSurface([[0, 0, 0], [1, 1, 1]])
    with pytest.raises(CurveError, match='at least'):
        NURBSSurface(np.zeros((2, 3, 3)), 2)
    with pytest.raises(CurveError, match='outside the domain'):
        BezierSurface(np.zeros((2, 2, 3))).eval(1.5, 0)
    with pytest.raises(CurveError, match='exactly one'):
        BezierSurface(np.zeros((2, 2, 3))).isocurve()
    with pytest.raises(CurveError, match='non-decreasing'):
        NURBSSurface(np.zeros((3, 3, 3)), 1, ([0, 0, 1, 0.5, 1], None))
    with pytest.raises(CurveError, match='positive'):
        NURBSSurface(np.zeros((3, 3, 3)), 1, None, -np.ones((3, 3)))
