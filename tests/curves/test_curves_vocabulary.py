"""The shared vocabulary on every curve family: eval, deriv/tangent,
subsegment, extrema, bounding_box, to_beziers, flatten, to_path/to_svg, draw."""

import numpy as np
import pytest

from raster.curves import (Bezier, Hermite, CardinalSpline, CatmullRom, KochanekBartels,
                           BSpline, BetaSpline, NaturalSpline, FunctionSpline, PiecewiseBezier,
                           CurveError)
from raster.geometry.pens import RecordingPen
from raster.geometry.pathdata import parse_path

R = np.random.default_rng(20261122)
P5 = R.normal(size=(5, 2)) * 20
P6_3D = R.normal(size=(6, 3)) * 20

FAMILIES = {
    'bezier': lambda: Bezier(P5),
    'bezier3d': lambda: Bezier(P6_3D),
    'bezier-high': lambda: Bezier(R.normal(size=(8, 2)) * 20),
    'hermite': lambda: Hermite(P5[0], P5[1], P5[2], P5[3]),
    'cardinal': lambda: CardinalSpline(P5, 0.3),
    'catmull-rom-closed': lambda: CatmullRom(P5, ends='closed'),
    'kochanek-bartels': lambda: KochanekBartels(P5, 0.1, -0.4, 0.3),
    'bspline': lambda: BSpline(P5, 3),
    'bspline-quad-3d': lambda: BSpline(P6_3D, 2, [0, 0, 0, 0.1, 0.5, 0.7, 1, 1, 1]),
    'bspline-closed': lambda: BSpline(P5, 3, closed=True),
    'beta': lambda: BetaSpline(P5, 1.5, 4.0),
    'natural': lambda: NaturalSpline(P5, 'centripetal'),
    'natural-function': lambda: FunctionSpline(np.arange(5.0) * 10, P5[:, 1]),
}


@pytest.fixture(params=sorted(FAMILIES))
def curve(request):
    return FAMILIES[request.param]()


def dense(curve, n=20001):
    return curve.eval(np.linspace(*curve.domain, n))


def test_bezier_form_reproduces(curve):
    t = np.linspace(*curve.domain, 257)
    pb = curve.to_beziers()
    assert isinstance(pb, PiecewiseBezier) and pb.domain == pytest.approx(curve.domain)
    np.testing.assert_allclose(pb.eval(t), curve.eval(t), atol=1e-9)
    assert all(isinstance(b, Bezier) for b in pb)


def test_bounding_box_exact(curve):
    lo, hi = curve.bounding_box()
    pts = dense(curve)
    assert np.all(pts >= lo - 1e-9) and np.all(pts <= hi + 1e-9)
    np.testing.assert_allclose(pts.min(0), lo, atol=1e-4)
    np.testing.assert_allclose(pts.max(0), hi, atol=1e-4)


def test_extrema_are_stationary(curve):
    d = curve.deriv()
    scale = np.abs(d.to_beziers().ctrl).max()
    for t in curve.extrema():
        assert np.min(np.abs(d.eval(t))) <= 1e-7 * scale


def test_tangent_matches_finite_difference(curve):
    lo, hi = curve.domain
    t = np.linspace(lo, hi, 13)[1:-1] + 1e-3 * (hi - lo)      # away from joints
    h = 1e-6 * (hi - lo)
    fd = (curve.eval(t + h) - curve.eval(t - h)) / (2 * h)
    np.testing.assert_allclose(curve.tangent(t), fd, atol=1e-4 * (1 + np.abs(fd).max()))


def test_subsegment(curve):
    lo, hi = curve.domain
    t0, t1 = lo + 0.2 * (hi - lo), lo + 0.85 * (hi - lo)
    sub = curve.subsegment(t0, t1)
    t = np.linspace(t0, t1, 55)
    if isinstance(curve, Bezier):       # a Bezier piece is reparameterized to [0, 1]
        np.testing.assert_allclose(sub.eval((t - t0) / (t1 - t0)), curve.eval(t), atol=1e-9)
    else:                               # spline pieces keep the global parameter
        assert sub.domain == pytest.approx((t0, t1))
        np.testing.assert_allclose(sub.eval(t), curve.eval(t), atol=1e-9)
    with pytest.raises(CurveError):
        curve.subsegment(t1, t0) if not isinstance(curve, Bezier) else curve.subsegment(0, 2)


@pytest.mark.parametrize('tol', [2.0, 0.25, 0.01])
def test_flatten_within_tolerance(curve, tol):
    poly = curve.flatten(tol)
    pts = dense(curve, 4001)
    a, c = poly[:-1], poly[1:]
    ab = c - a
    L2 = np.maximum(np.einsum('kd,kd->k', ab, ab), 1e-300)
    w = np.clip(np.einsum('mkd,kd->mk', pts[:, None] - a[None], ab) / L2, 0, 1)
    dist = np.linalg.norm(pts[:, None] - (a[None] + w[..., None] * ab[None]), axis=2).min(1)
    assert dist.max() <= tol * (1 + 1e-9)


def test_svg_round_trip_and_pen(curve):
    path = curve.to_path(0.01)
    back = parse_path(curve.to_svg(0.01))
    np.testing.assert_allclose(back.points, path.points)
    assert back.verbs.tolist() == path.verbs.tolist()
    pen = RecordingPen()
    curve.draw(pen, 0.01)
    assert pen.value[0][0] == 'moveTo' and pen.value[-1][0] == 'endPath'
    first = curve.eval(curve.domain[0])[:2]
    np.testing.assert_allclose(pen.value[0][1][0], first, atol=1e-12)


# families built from a point array, for invariance checks
BUILDERS = {
    'bezier': lambda P: Bezier(P),
    'cardinal': lambda P: CardinalSpline(P, 0.3),
    'kochanek-bartels': lambda P: KochanekBartels(P, 0.2, 0.3, -0.1),
    'bspline': lambda P: BSpline(P, 3),
    'bspline-closed': lambda P: BSpline(P, 2, closed=True),
    'beta': lambda P: BetaSpline(P, 1.3, 2.0),
    'natural-uniform': lambda P: NaturalSpline(P, 'uniform'),
}


@pytest.mark.parametrize('name', sorted(BUILDERS))
@pytest.mark.parametrize('seed', [1, 2, 3])
def test_affine_invariance(name, seed):
    r = np.random.default_rng(seed)
    P = r.normal(size=(6, 3))
    A, off = r.normal(size=(3, 3)), r.normal(size=3)
    c, ca = BUILDERS[name](P), BUILDERS[name](P @ A.T + off)
    t = np.linspace(*c.domain, 31)
    np.testing.assert_allclose(ca.eval(t), c.eval(t) @ A.T + off, atol=1e-9)


@pytest.mark.parametrize('name', ['bezier', 'cardinal', 'bspline', 'natural-uniform'])
def test_reversal_symmetry(name):
    # symmetric constructions: reversed points trace the curve backwards
    P = np.random.default_rng(9).normal(size=(6, 2))
    c, r = BUILDERS[name](P), BUILDERS[name](P[::-1])
    lo, hi = c.domain
    t = np.linspace(lo, hi, 41)
    np.testing.assert_allclose(r.eval(lo + hi - t), c.eval(t), atol=1e-9)
