"""NURBS curves and surfaces against independent implementations: geomdl
(NURBS evaluation, derivatives, normals, knot insertion, Bezier
decomposition) and scipy (the homogeneous B-spline, projected by hand).
Agreement to 1e-9 relative to the size of the control points."""

import numpy as np
import pytest
from geomdl import NURBS as GN, operations
from scipy.interpolate import BSpline as SciBSpline

from raster.curves import BSpline, BSplineSurface, NURBS, NURBSSurface, CurveError

TOL = 1e-9


def random_knots(rng, n, p):
    """A clamped non-uniform knot vector with a repeated interior knot."""
    inner = np.sort(rng.uniform(0.05, 0.95, n - p - 1))
    if len(inner) >= 2:
        inner[1] = inner[0]                      # multiplicity 2 somewhere
    return np.concatenate([np.zeros(p + 1), inner, np.ones(p + 1)])


def geomdl_curve(P, w, p, kv):
    c = GN.Curve()
    c.degree = p
    c.ctrlpts = P.tolist()
    c.weights = w.tolist()
    c.knotvector = kv.tolist()
    return c


CASES = [(seed, p, n, d) for seed, (p, n, d) in enumerate(
    [(1, 4, 2), (2, 5, 2), (3, 7, 3), (4, 9, 2), (5, 8, 3), (3, 12, 2)])]


@pytest.mark.parametrize('seed,p,n,d', CASES)
def test_curve_points_and_derivatives_match_geomdl(seed, p, n, d):
    rng = np.random.default_rng(seed)
    P = rng.uniform(-10, 10, (n, d))
    w = rng.uniform(0.3, 3.0, n)
    kv = random_knots(rng, n, p)
    ours = NURBS(P, w, p, kv)
    ref = geomdl_curve(P, w, p, kv)
    t = np.concatenate([rng.uniform(0, 1, 40), [0.0, 1.0], kv[p + 1:-p - 1]])
    scale = np.abs(P).max()
    np.testing.assert_allclose(ours.eval(t), np.array(ref.evaluate_list(t.tolist())),
                               rtol=0, atol=TOL * scale)
    order = min(2, p)
    got = ours.derivatives(t, order)
    want = np.array([ref.derivatives(float(x), order) for x in t])
    # derivatives grow with the knot spacing: compare relative to their size
    for k in range(order + 1):
        s = max(1.0, np.abs(want[:, k]).max())
        np.testing.assert_allclose(got[:, k], want[:, k], rtol=0, atol=TOL * s)


@pytest.mark.parametrize('seed,p,n,d', CASES[:4])
def test_curve_matches_scipy_homogeneous_bspline(seed, p, n, d):
    rng = np.random.default_rng(100 + seed)
    P = rng.uniform(-5, 5, (n, d))
    w = rng.uniform(0.5, 2.0, n)
    kv = random_knots(rng, n, p)
    hb = SciBSpline(kv, np.column_stack([P * w[:, None], w]), p)
    t = np.linspace(0, 1, 57)
    h = hb(t)
    np.testing.assert_allclose(NURBS(P, w, p, kv).eval(t), h[:, :d] / h[:, d:], atol=TOL * 5)


def test_knot_insertion_and_bezier_decomposition_match_geomdl():
    rng = np.random.default_rng(7)
    P = rng.uniform(-3, 3, (7, 2))
    w = rng.uniform(0.5, 2, 7)
    kv = random_knots(rng, 7, 3)
    ours = NURBS(P, w, 3, kv)
    ref = geomdl_curve(P, w, 3, kv)
    ins = ours.insert_knot(0.37, 2)
    operations.insert_knot(ref, [0.37], [2])
    np.testing.assert_allclose(ins.knots, ref.knotvector, atol=1e-15)
    np.testing.assert_allclose(ins.points, ref.ctrlpts, atol=TOL)
    np.testing.assert_allclose(ins.weights, ref.weights, atol=TOL)
    # exact Bezier segments: the same control points and weights per span
    segs = geomdl_curve(P, w, 3, kv)
    parts = operations.decompose_curve(segs)
    chain = ours.to_rational_beziers()
    assert len(parts) == len(chain)
    for seg, part in zip(chain, parts):
        np.testing.assert_allclose(seg.points, part.ctrlpts, atol=TOL)
        np.testing.assert_allclose(seg.weights / seg.weights[0],
                                   np.array(part.weights) / part.weights[0], atol=TOL)


def test_equal_weights_are_the_bspline_exactly():
    rng = np.random.default_rng(8)
    P = rng.normal(size=(6, 3))
    kv = random_knots(rng, 6, 2)
    b = BSpline(P, 2, kv)
    n = NURBS.from_bspline(b, None)
    t = np.linspace(0, 1, 33)
    np.testing.assert_allclose(n.eval(t), b.eval(t), atol=1e-14)
    np.testing.assert_allclose(n.to_bspline().eval(t), b.eval(t), atol=1e-14)
    np.testing.assert_array_equal(n.to_beziers().ctrl, b.to_beziers().ctrl)
    with pytest.raises(CurveError, match='weights differ'):
        NURBS(P, [1, 2, 1, 1, 1, 1], 2, kv).to_bspline()


def geomdl_surface(net, w, p, q, ku, kv):
    s = GN.Surface()
    s.degree_u, s.degree_v = p, q
    s.ctrlpts_size_u, s.ctrlpts_size_v = net.shape[:2]
    s.ctrlpts = net.reshape(-1, 3).tolist()
    s.weights = w.reshape(-1).tolist()
    s.knotvector_u, s.knotvector_v = ku.tolist(), kv.tolist()
    return s


@pytest.mark.parametrize('seed,p,q,nu,nv', [(1, 2, 2, 4, 5), (2, 3, 2, 6, 4), (3, 3, 3, 7, 6),
                                            (4, 1, 4, 3, 7)])
def test_surface_points_derivatives_normals_match_geomdl(seed, p, q, nu, nv):
    rng = np.random.default_rng(seed)
    net = rng.uniform(-4, 4, (nu, nv, 3))
    w = rng.uniform(0.4, 2.5, (nu, nv))
    ku, kv = random_knots(rng, nu, p), random_knots(rng, nv, q)
    ours = NURBSSurface(net, (p, q), (ku, kv), w)
    ref = geomdl_surface(net, w, p, q, ku, kv)
    uv = np.vstack([rng.uniform(0, 1, (30, 2)), [[0, 0], [1, 1], [0, 1], [1, 0]]])
    scale = np.abs(net).max()
    np.testing.assert_allclose(ours.eval(uv[:, 0], uv[:, 1]),
                               np.array(ref.evaluate_list(uv.tolist())), atol=TOL * scale)
    order = min(2, p, q)
    got = ours.derivatives(uv[:, 0], uv[:, 1], order)
    want = np.array([ref.derivatives(float(a), float(b), order) for a, b in uv])
    for k in range(order + 1):
        for l in range(order + 1 - k):
            s = max(1.0, np.abs(want[:, k, l]).max())
            np.testing.assert_allclose(got[:, k, l], want[:, k, l], atol=TOL * s)
    inner = uv[:30]
    nr = np.array([operations.normal(ref, [float(a), float(b)])[1] for a, b in inner])
    np.testing.assert_allclose(ours.normal(inner[:, 0], inner[:, 1]), nr, atol=TOL)


def test_surface_knot_insertion_matches_geomdl():
    rng = np.random.default_rng(12)
    net = rng.uniform(-2, 2, (5, 4, 3))
    w = rng.uniform(0.5, 2, (5, 4))
    ku, kv = random_knots(rng, 5, 2), random_knots(rng, 4, 2)
    ours = NURBSSurface(net, 2, (ku, kv), w).insert_knot('u', 0.41, 1).insert_knot('v', 0.6, 2)
    ref = geomdl_surface(net, w, 2, 2, ku, kv)
    operations.insert_knot(ref, [0.41, 0.6], [1, 2])
    np.testing.assert_allclose(ours.knots[0], ref.knotvector_u, atol=1e-15)
    np.testing.assert_allclose(ours.knots[1], ref.knotvector_v, atol=1e-15)
    np.testing.assert_allclose(ours.net.reshape(-1, 3), ref.ctrlpts, atol=TOL)
    np.testing.assert_allclose(ours.weights.reshape(-1), ref.weights, atol=TOL)


def test_surface_bezier_patches_isocurves_and_bspline_case():
    rng = np.random.default_rng(13)
    net = rng.uniform(-2, 2, (6, 5, 3))
    w = rng.uniform(0.5, 2, (6, 5))
    ku, kv = random_knots(rng, 6, 3), random_knots(rng, 5, 2)
    s = NURBSSurface(net, (3, 2), (ku, kv), w)
    patches = s.to_bezier_patches()
    bu, bv = s.patch_domains()
    assert (len(patches), len(patches[0])) == (len(bu) - 1, len(bv) - 1)
    for a in range(len(bu) - 1):
        for b in range(len(bv) - 1):
            pt = patches[a][b]
            uu = np.linspace(bu[a], bu[a + 1], 5)
            vv = np.linspace(bv[b], bv[b + 1], 5)
            U, V = (x.ravel() for x in np.meshgrid(uu, vv))
            np.testing.assert_allclose(pt.eval(U, V), s.eval(U, V), atol=TOL)
    c = s.isocurve(v=0.3)
    t = np.linspace(0, 1, 11)
    np.testing.assert_allclose(c.eval(t), s.eval(t, np.full(11, 0.3)), atol=TOL)
    assert isinstance(c, NURBS)
    # unit weights: a B-spline surface whose isocurves are B-splines
    bs = BSplineSurface(net, (3, 2), (ku, kv))
    assert isinstance(bs.isocurve(u=0.5), BSpline)
    ref = geomdl_surface(net, np.ones((6, 5)), 3, 2, ku, kv)
    uv = rng.uniform(0, 1, (20, 2))
    np.testing.assert_allclose(bs.eval(uv[:, 0], uv[:, 1]), ref.evaluate_list(uv.tolist()),
                               atol=TOL)
