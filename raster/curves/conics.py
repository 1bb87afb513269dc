r"""Exact conic sections as rational quadratic Bezier curves.

A rational quadratic with control points ``P0, P1, P2`` and weights
``1, w, 1`` (``w > 0``) is an arc of a conic: an ellipse for ``w < 1``, a
parabola for ``w = 1``, a hyperbola for ``w > 1`` (:func:`conic_kind`).

A circular arc of angle ``theta <= 180`` degrees has its end points on the
circle, ``P1`` at the intersection of the end tangents and ``w =
cos(theta / 2)``; the point at parameter ``t`` lies at angle ``psi`` from
the arc's middle with ``tan(psi / 2) = tan(theta / 4) (2 t - 1)`` (so the
curve is the circle exactly, only not at constant speed).  Longer arcs are
split into equal segments of at most 90 degrees.  An ellipse is the affine
image of the unit circle (``x = c + R(rotation) diag(rx, ry) (cos a, sin
a)``, ``a`` the parametric angle as in SVG arcs); affine maps keep the
weights, so ellipse arcs are exact too.

Angles are in radians, measured from the +x axis towards +y.

>>> arc = circle_arc([0, 0], 2.0, 0.0, np.pi)          # half circle, 2 segments
>>> len(arc), np.round(arc.point_at_angle(np.pi / 3), 12).tolist()
(2, [1.0, 1.732050807569])
>>> conic_kind(1.0), conic_kind(0.5), conic_kind(2.0)
('parabola', 'ellipse', 'hyperbola')
"""

import math
from typing import Union

import numpy as np
from numpy.typing import ArrayLike

from .checks import CurveError, as_points, as_scalar
from .rational import PiecewiseRational, RationalBezier

__all__ = ['ConicArc', 'conic', 'conic_kind', 'circle_arc', 'ellipse_arc', 'circle', 'ellipse']

TWO_PI = 2.0 * math.pi


def conic(p0: ArrayLike, p1: ArrayLike, p2: ArrayLike, w: float = 1.0) -> RationalBezier:
    """The rational quadratic ``P0, P1, P2`` with weights ``1, w, 1``.

    >>> conic([0, 0], [1, 2], [2, 0]).eval(0.5).tolist()      # w = 1: a parabola
    [1.0, 1.0]
    """
    w = as_scalar(w, 'w')
    if w <= 0:
        raise CurveError('the conic weight must be positive, got %g' % w)
    return RationalBezier(as_points([np.ravel(p0), np.ravel(p1), np.ravel(p2)], 3, dims=None),
                          [1.0, w, 1.0])


def conic_kind(w: Union[float, RationalBezier]) -> str:
    """``'ellipse'``, ``'parabola'`` or ``'hyperbola'`` for the middle weight
    ``w`` of a rational quadratic in standard form (end weights 1), or for a
    degree-2 :class:`RationalBezier` (its shape factor ``w1^2 / (w0 w2)``)."""
    if isinstance(w, RationalBezier):
        if w.degree != 2:
            raise CurveError('conic_kind needs a rational quadratic')
        a, b, c = w.weights
        k = b * b / (a * c)
    else:
        k = as_scalar(w, 'w') ** 2
    if abs(k - 1.0) <= 1e-12:
        return 'parabola'
    return 'ellipse' if k < 1.0 else 'hyperbola'


class ConicArc(PiecewiseRational):
    """An arc of a circle or ellipse as a chain of rational quadratics,
    parameter ``t`` in [0, 1] with the joints at equal steps.

    Built by :func:`circle_arc` and :func:`ellipse_arc`.

    Attributes
    ----------
    center : (2,) float64
    rx, ry : float
        Semi-axes (equal for a circle).
    rotation : float
        Angle of the x semi-axis, radians.
    start, sweep : float
        Parametric start angle and signed sweep, radians.
    """

    def __init__(self, center, rx, ry, rotation, start, sweep):
        c = np.array(as_points([np.ravel(center)], 1, 'center', dims=(2,))[0])
        rx = as_scalar(rx, 'rx')
        ry = as_scalar(ry, 'ry')
        if rx <= 0 or ry <= 0:
            raise CurveError('radii must be positive, got %g, %g' % (rx, ry))
        rot = as_scalar(rotation, 'rotation')
        a0 = as_scalar(start, 'start angle')
        sw = as_scalar(sweep, 'sweep', -TWO_PI * (1 + 1e-12), TWO_PI * (1 + 1e-12))
        if sw == 0:
            raise CurveError('the sweep angle must not be 0')
        sw = float(np.clip(sw, -TWO_PI, TWO_PI))
        k = max(1, int(math.ceil(abs(sw) / (math.pi / 2) - 1e-9)))
        theta = sw / k
        half = theta / 2.0
        mids = a0 + theta * (np.arange(k) + 0.5)
        ang = np.stack([mids - half, mids, mids + half], axis=1)           # (k, 3)
        rad = np.stack([np.ones(k), np.full(k, 1.0 / math.cos(half)), np.ones(k)], axis=1)
        unit = np.stack([rad * np.cos(ang), rad * np.sin(ang)], axis=2)   # (k, 3, 2)
        # the joints are exact evaluations of the same angle on both sides
        unit[1:, 0] = unit[:-1, 2]
        closed = abs(sw) >= TWO_PI
        if closed:
            unit[-1, 2] = unit[0, 0]
        M = np.array([[math.cos(rot), -math.sin(rot)], [math.sin(rot), math.cos(rot)]]) \
            @ np.diag([rx, ry])
        ctrl = unit @ M.T + c
        w = np.tile([1.0, math.cos(half), 1.0], (k, 1))
        super().__init__(ctrl, w, np.linspace(0.0, 1.0, k + 1), closed=closed)
        self.center, self.rx, self.ry = c, rx, ry
        self.rotation, self.start, self.sweep = rot, a0, sw
        self._theta = theta

    def __repr__(self):
        kind = 'circle' if self.rx == self.ry else 'ellipse'
        return 'ConicArc(%s, %d segments, sweep %.6g deg)' % (kind, len(self),
                                                              math.degrees(self.sweep))

    def param_at_angle(self, angle):
        """Curve parameter(s) ``t`` of parametric angle(s) on the arc (exact
        inverse of the stereographic speed): float or (M,) float64.

        Raises
        ------
        CurveError
            An angle outside the arc.
        """
        a = np.asarray(angle, dtype=np.float64)
        scalar = a.ndim == 0
        a = a.reshape(-1)
        rel = (a - self.start) / self.sweep                       # 0..1 along the arc
        if np.any(rel < -1e-12) or np.any(rel > 1 + 1e-12):
            raise CurveError('angle outside the arc')
        k = len(self)
        pos = np.clip(rel, 0.0, 1.0) * k
        s = np.clip(np.floor(pos), 0, k - 1)
        psi = (pos - s - 0.5) * self._theta
        t = (s + 0.5 * (1.0 + np.tan(psi / 2) / math.tan(self._theta / 4))) / k
        t = np.clip(t, 0.0, 1.0)
        return float(t[0]) if scalar else t

    def angle_at_param(self, t):
        """Parametric angle(s) of curve parameter(s) ``t``."""
        ta = np.asarray(t, dtype=np.float64)
        scalar = ta.ndim == 0
        ta = np.clip(ta.reshape(-1), 0.0, 1.0)
        k = len(self)
        s = np.clip(np.floor(ta * k), 0, k - 1)
        u = ta * k - s
        psi = 2 * np.arctan(math.tan(self._theta / 4) * (2 * u - 1))
        a = self.start + (s + 0.5) * self._theta + psi
        return float(a[0]) if scalar else a

    def point_at_angle(self, angle):
        """Point(s) of the arc at parametric angle(s): (2,) or (M, 2)."""
        return self.eval(self.param_at_angle(angle))


def circle_arc(center: ArrayLike, radius: float, start: float = 0.0,
               sweep: float = TWO_PI) -> 'ConicArc':
    """Arc of the circle ``|x - center| = radius`` from angle ``start``
    through the signed angle ``sweep`` (radians, ``0 < |sweep| <= 2 pi``):
    a :class:`ConicArc`."""
    return ConicArc(center, radius, radius, 0.0, start, sweep)


def ellipse_arc(center: ArrayLike, rx: float, ry: float, rotation: float = 0.0,
                start: float = 0.0, sweep: float = TWO_PI) -> 'ConicArc':
    """Arc of an ellipse with semi-axes ``rx, ry`` rotated by ``rotation``,
    between parametric angles ``start`` and ``start + sweep``: a
    :class:`ConicArc`."""
    return ConicArc(center, rx, ry, rotation, start, sweep)


def circle(center: ArrayLike, radius: float) -> 'ConicArc':
    """The full circle (4 quarter arcs, closed)."""
    return circle_arc(center, radius, 0.0, TWO_PI)


def ellipse(center: ArrayLike, rx: float, ry: float, rotation: float = 0.0) -> 'ConicArc':
    """The full ellipse (4 quarter arcs, closed)."""
    return ellipse_arc(center, rx, ry, rotation, 0.0, TWO_PI)
