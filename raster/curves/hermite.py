r"""Cubic Hermite curves: a cubic from its end points ``P0, P1`` and end
tangents ``T0, T1`` (derivatives with respect to ``t in [0, 1]``).

.. math:: H(t) = h_{00}(t) P_0 + h_{01}(t) P_1 + h_{10}(t) T_0 + h_{11}(t) T_1

with the blending functions ``h00 = 2t^3 - 3t^2 + 1``, ``h01 = -2t^3 + 3t^2``,
``h10 = t^3 - 2t^2 + t`` and ``h11 = t^3 - t^2``; in matrix form
``H(t) = [t^3, t^2, t, 1] M_H [P0, P1, T0, T1]^T``.  The exact cubic Bezier
form has control points ``P0, P0 + T0/3, P1 - T1/3, P1``.

:class:`HermiteSpline` chains such cubics (segment ``s`` on ``[s, s+1]``);
the cardinal, Catmull-Rom and Kochanek-Bartels splines are Hermite splines
with tangents computed from neighbouring points.

>>> h = Hermite([0, 0], [1, 0], [0, 3], [0, -3])
>>> h.eval(0.5).tolist()
[0.5, 0.75]
>>> h.to_bezier().ctrl.tolist()
[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]
"""

import numpy as np

from .base import CurveMixin
from .checks import CurveError, as_params, as_points, shape_out
from .bezier import Bezier, PiecewiseBezier

#: Hermite basis matrix; rows multiply t^3, t^2, t, 1, columns P0, P1, T0, T1.
HERMITE_MATRIX = np.array([[2.0, -2.0, 1.0, 1.0],
                           [-3.0, 3.0, -2.0, -1.0],
                           [0.0, 0.0, 1.0, 0.0],
                           [1.0, 0.0, 0.0, 0.0]])


def hermite_basis_matrix():
    """The 4x4 Hermite basis matrix ``M_H`` (a copy of
    :data:`HERMITE_MATRIX`): ``[t^3, t^2, t, 1] @ M_H`` gives the blending
    functions ``(h00, h01, h10, h11)``."""
    return HERMITE_MATRIX.copy()


def hermite_blend(t):
    """Hermite blending functions for many ``t``.

    Parameters
    ----------
    t : float or (M,) array_like of float

    Returns
    -------
    (4,) or (M, 4) float64 ndarray
        Columns ``h00, h01, h10, h11`` (weights of P0, P1, T0, T1).

    >>> hermite_blend(0.5).tolist()
    [0.5, 0.5, 0.125, -0.125]
    """
    ta = np.asarray(t, dtype=np.float64)
    scalar = ta.ndim == 0
    ta = ta.reshape(-1)
    powers = np.stack([ta ** 3, ta ** 2, ta, np.ones_like(ta)], axis=1)
    out = powers @ HERMITE_MATRIX
    return out[0] if scalar else out


class HermiteSpline(CurveMixin):
    """Piecewise cubic Hermite curve through ``points``; segment ``s`` runs
    from ``points[s]`` to ``points[s+1]`` on the parameter interval
    ``[s, s+1]``.

    Parameters
    ----------
    points : (S+1, D) array_like of float
    out_tangents : (S, D) array_like of float
        Tangent leaving ``points[s]`` (start of segment ``s``).
    in_tangents : (S, D) array_like of float
        Tangent arriving at ``points[s+1]`` (end of segment ``s``).
    """

    def __init__(self, points, out_tangents, in_tangents):
        p = as_points(points, 2, dims=None)
        S = len(p) - 1
        to = as_points(out_tangents, S, 'tangents', dims=None)
        ti = as_points(in_tangents, S, 'tangents', dims=None)
        if to.shape != (S, p.shape[1]) or ti.shape != (S, p.shape[1]):
            raise CurveError('need %d tangents of dimension %d' % (S, p.shape[1]))
        self.points, self.out_tangents, self.in_tangents = p, to, ti

    @property
    def domain(self):
        return (0.0, float(len(self.points) - 1))

    def eval(self, t):
        """Point(s) at global ``t`` in ``[0, S]``: (D,) or (M, D) float64."""
        ta, scalar = as_params(t, *self.domain)
        S = len(self.points) - 1
        idx = np.clip(np.floor(ta).astype(np.int64), 0, S - 1)
        u = ta - idx
        h = hermite_blend(u)
        out = (h[:, 0:1] * self.points[idx] + h[:, 1:2] * self.points[idx + 1]
               + h[:, 2:3] * self.out_tangents[idx] + h[:, 3:4] * self.in_tangents[idx])
        return shape_out(out, scalar)

    __call__ = eval

    def to_beziers(self):
        """Exact cubic Bezier segments: ``P_s, P_s + T^out_s / 3,
        P_{s+1} - T^in_s / 3, P_{s+1}``."""
        p = self.points
        c = np.stack([p[:-1], p[:-1] + self.out_tangents / 3.0,
                      p[1:] - self.in_tangents / 3.0, p[1:]], axis=1)
        return PiecewiseBezier(c)


class Hermite(HermiteSpline):
    """One cubic Hermite curve on ``t in [0, 1]``.

    Parameters
    ----------
    p0, p1 : (D,) array_like of float
        End points.
    t0, t1 : (D,) array_like of float
        End tangents ``H'(0)`` and ``H'(1)``.
    """

    def __init__(self, p0, p1, t0, t1):
        sizes = {np.size(p0), np.size(p1), np.size(t0), np.size(t1)}
        if len(sizes) != 1:
            raise CurveError('end points and tangents must all have the same dimension')
        pts = as_points([np.ravel(p0), np.ravel(p1)], 2, 'end points', dims=None)
        tans = as_points([np.ravel(t0), np.ravel(t1)], 2, 'tangents', dims=None)
        if tans.shape != pts.shape:
            raise CurveError('end points and tangents must have the same dimension')
        super().__init__(pts, tans[:1], tans[1:])

    @property
    def tangents(self):
        """(2, D) float64: ``T0, T1``."""
        return np.concatenate([self.out_tangents, self.in_tangents])

    def blending(self, t):
        """Blending function values: (4,) or (M, 4), see :func:`hermite_blend`."""
        ta, scalar = as_params(t, 0.0, 1.0)
        return shape_out(hermite_blend(ta), scalar)

    def power_coeffs(self):
        """(4, D) float64; row ``k`` multiplies ``t**k``."""
        g = np.concatenate([self.points, self.out_tangents, self.in_tangents])
        return (HERMITE_MATRIX @ g)[::-1]

    def to_bezier(self):
        """The exact cubic :class:`~raster.curves.bezier.Bezier`."""
        return Bezier(self.to_beziers().ctrl[0])
