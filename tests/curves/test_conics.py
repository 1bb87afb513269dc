"""Exact conics: circle and ellipse arcs as rational quadratics agree with
the circle and ellipse equations to 1e-12, the angle <-> parameter map is
exact, parabolas and hyperbolas satisfy their equations."""

import math

import numpy as np
import pytest

from raster.curves import (CurveError, NURBS, circle, circle_arc, conic, conic_kind, ellipse,
                           ellipse_arc)

T = np.linspace(0, 1, 2001)


@pytest.mark.parametrize('center,r,start,sweep', [
    ([0, 0], 1.0, 0.0, 2 * math.pi), ([3, -2], 7.5, 0.3, 1.2), ([1e3, 2e3], 250.0, -2.0, -4.5),
    ([0, 0], 1e-3, 1.0, math.pi / 2), ([-5, 5], 2.0, 0.0, math.pi)])
def test_circle_arcs_lie_on_the_circle(center, r, start, sweep):
    arc = circle_arc(center, r, start, sweep)
    p = arc.eval(T) - center
    # |p| = r to 1e-12 relative, at 2001 parameters over the whole arc
    np.testing.assert_allclose(np.hypot(p[:, 0], p[:, 1]) / r, 1.0, rtol=0, atol=1e-12)
    # end points at the given angles, tangents perpendicular to the radius
    ends = arc.eval([0.0, 1.0]) - center
    np.testing.assert_allclose(ends / r, [[math.cos(start), math.sin(start)],
                                          [math.cos(start + sweep), math.sin(start + sweep)]],
                               atol=1e-12)
    v = arc.tangent(T)
    cosang = (p * v).sum(1) / (np.linalg.norm(p, axis=1) * np.linalg.norm(v, axis=1))
    assert np.abs(cosang).max() < 1e-12
    assert len(arc) == max(1, math.ceil(abs(sweep) / (math.pi / 2) - 1e-9))


def test_points_at_angles_are_exact():
    arc = circle_arc([2, 1], 3.0, 0.25, 5.0)
    ang = np.linspace(0.25, 5.25, 37)
    want = np.stack([2 + 3 * np.cos(ang), 1 + 3 * np.sin(ang)], 1)
    np.testing.assert_allclose(arc.point_at_angle(ang), want, atol=1e-12 * 3)
    np.testing.assert_allclose(arc.angle_at_param(arc.param_at_angle(ang)), ang, atol=1e-13)
    with pytest.raises(CurveError, match='outside the arc'):
        arc.param_at_angle(6.0)


@pytest.mark.parametrize('rx,ry,rot,start,sweep', [
    (3.0, 1.0, 0.0, 0.0, 2 * math.pi), (5.0, 2.0, 0.7, 0.4, 3.0), (0.5, 4.0, -1.2, 2.0, -5.5)])
def test_ellipse_arcs_lie_on_the_ellipse(rx, ry, rot, start, sweep):
    c = np.array([1.5, -0.5])
    arc = ellipse_arc(c, rx, ry, rot, start, sweep)
    p = arc.eval(T) - c
    # into the ellipse's own axes: (x / rx)^2 + (y / ry)^2 = 1
    x = p[:, 0] * math.cos(rot) + p[:, 1] * math.sin(rot)
    y = -p[:, 0] * math.sin(rot) + p[:, 1] * math.cos(rot)
    np.testing.assert_allclose((x / rx) ** 2 + (y / ry) ** 2, 1.0, rtol=0, atol=1e-12)
    # parametric angles: x = rx cos a, y = ry sin a exactly
    a = np.linspace(start, start + sweep, 25)
    q = arc.point_at_angle(a) - c
    xa = q[:, 0] * math.cos(rot) + q[:, 1] * math.sin(rot)
    ya = -q[:, 0] * math.sin(rot) + q[:, 1] * math.cos(rot)
    np.testing.assert_allclose(np.stack([xa / rx, ya / ry], 1),
                               np.stack([np.cos(a), np.sin(a)], 1), atol=1e-12)


def test_full_circle_is_closed_and_curvature_continuous():
    c = circle([0, 0], 2.0)
    assert c.closed and len(c) == 4
    js = c.continuity()
    assert len(js) == 4 and all(j.G == 2 and j.C == 1 for j in js)
    lo, hi = c.bounding_box()
    np.testing.assert_allclose(lo, [-2, -2], atol=1e-12)
    np.testing.assert_allclose(hi, [2, 2], atol=1e-12)
    e = ellipse([0, 0], 3, 1, math.pi / 2)                 # x semi-axis along y
    lo, hi = e.bounding_box()
    np.testing.assert_allclose([lo, hi], [[-1, -3], [1, 3]], atol=1e-12)
    # the standard 9-point NURBS circle
    n = NURBS.from_rational(c)
    assert len(n.points) == 9
    np.testing.assert_allclose(n.knots, [0, 0, 0, .25, .25, .5, .5, .75, .75, 1, 1, 1])
    p = n.eval(T)
    np.testing.assert_allclose(np.hypot(p[:, 0], p[:, 1]), 2.0, rtol=0, atol=2e-12)


def test_parabola_and_hyperbola():
    # w = 1: (-1, 1), (0, -1), (1, 1) is the parabola y = x^2
    par = conic([-1, 1], [0, -1], [1, 1], 1.0)
    p = par.eval(T)
    np.testing.assert_allclose(p[:, 1], p[:, 0] ** 2, atol=1e-14)
    assert conic_kind(1.0) == 'parabola' and conic_kind(par) == 'parabola'
    # the hyperbola x y = 1 from (1/2, 2) to (2, 1/2): tangents meet at
    # (0.8, 0.8); the middle point (1, 1) gives w = 1.25 > 1
    hyp = conic([0.5, 2], [0.8, 0.8], [2, 0.5], 1.25)
    p = hyp.eval(T)
    np.testing.assert_allclose(p[:, 0] * p[:, 1], 1.0, atol=1e-14)
    assert conic_kind(hyp) == 'hyperbola' and conic_kind(0.5) == 'ellipse'


def test_bad_arcs():
    for args, needle in (((([0, 0]), 0.0), 'positive'), ((([0, 0]), 1.0, 0.0, 0.0), 'sweep'),
                         ((([0, 0]), 1.0, 0.0, 7.0), 'out of range'),
                         ((([0, 0, 0]), 1.0), 'dimensional')):
        with pytest.raises(CurveError, match=needle):
            circle_arc(*args)
    with pytest.raises(CurveError, match='positive'):
        conic([0, 0], [1, 1], [2, 0], -1)
