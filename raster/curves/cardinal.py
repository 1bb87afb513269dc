r"""Cardinal splines and Catmull-Rom splines: interpolating piecewise cubic
Hermite curves whose tangent at key ``P_i`` is

.. math:: T_i = (1 - c) \frac{P_{i+1} - P_{i-1}}{2}

with tension ``c`` (``c = 0``: Catmull-Rom; ``c = 1``: zero tangents,
straight-line-like corners; ``c < 0`` loosens the curve).  Segment ``s``
runs from key ``s`` to key ``s+1`` on the parameter interval ``[s, s+1]``,
so ``eval(i)`` is key ``i``.

End handling (``ends``):

* ``'duplicate'`` (default): every point is a key; the missing neighbours of
  the first and last points are taken equal to those points;
* ``'interior'``: the first and last points only steer the end tangents; the
  curve runs from ``points[1]`` to ``points[-2]`` (needs 4 points);
* ``'closed'``: a closed loop through all points (neighbours wrap around).

>>> c = CatmullRom([[0, 0], [1, 1], [2, 0], [3, 1]], ends='interior')
>>> c.eval([0, 0.5, 1]).tolist()
[[1.0, 1.0], [1.5, 0.5], [2.0, 0.0]]
"""

import numpy as np

from .checks import CurveError, as_params, as_points, as_scalar, shape_out
from .hermite import HERMITE_MATRIX, HermiteSpline

ENDS = ('duplicate', 'interior', 'closed')


def neighbours(points, ends):
    """Keys and their neighbours for an interpolating spline.

    Returns ``(prev, key, next, index)``: three (K, D) arrays and the (K,)
    index of each key in ``points`` (the spline runs through the K keys in
    order; for ``'closed'`` the first key is repeated at the end).
    """
    if ends not in ENDS:
        raise CurveError('ends must be one of %s, got %r' % (', '.join(ENDS), ends))
    p = points
    N = len(p)
    if ends == 'interior':
        if N < 4:
            raise CurveError("ends='interior' needs at least 4 points, got %d" % N)
        idx = np.arange(1, N - 1)
        return p[idx - 1], p[idx], p[idx + 1], idx
    if ends == 'closed':
        if N < 3:
            raise CurveError("a closed spline needs at least 3 points, got %d" % N)
        idx = np.arange(N + 1) % N
        return p[(idx - 1) % N], p[idx], p[(idx + 1) % N], idx
    idx = np.arange(N)
    return p[np.maximum(idx - 1, 0)], p[idx], p[np.minimum(idx + 1, N - 1)], idx


def cardinal_matrix(tension=0.0):
    """4x4 cardinal basis matrix: rows multiply ``u^3, u^2, u, 1``, columns
    weight ``P_{i-1}, P_i, P_{i+1}, P_{i+2}`` for the segment from ``P_i`` to
    ``P_{i+1}`` (``s = (1 - tension) / 2``).

    >>> (cardinal_matrix(0.0) * 2).tolist()   # Catmull-Rom
    [[-1.0, 3.0, -3.0, 1.0], [2.0, -5.0, 4.0, -1.0], [-1.0, 0.0, 1.0, 0.0], [0.0, 2.0, 0.0, 0.0]]
    """
    s = (1.0 - as_scalar(tension, 'tension')) / 2.0
    # (P0, P1, T0, T1) in terms of (P_{i-1}, P_i, P_{i+1}, P_{i+2})
    w = np.array([[0, 1, 0, 0], [0, 0, 1, 0], [-s, 0, s, 0], [0, -s, 0, s]], dtype=np.float64)
    return HERMITE_MATRIX @ w


class CardinalSpline(HermiteSpline):
    """Cardinal spline through ``points`` with ``tension``.

    Parameters
    ----------
    points : (N, D) array_like of float
        N >= 2 (>= 4 for ``ends='interior'``, >= 3 for ``'closed'``).
    tension : float
        ``c``; tangents are ``(1 - c)(P_{i+1} - P_{i-1}) / 2``.
    ends : {'duplicate', 'interior', 'closed'}
    """

    def __init__(self, points, tension=0.0, ends='duplicate'):
        p = as_points(points, 2, dims=None)
        self.tension = as_scalar(tension, 'tension')
        self.ends = ends
        prev, key, nxt, _ = neighbours(p, ends)
        tan = (1.0 - self.tension) * 0.5 * (nxt - prev)
        super().__init__(key, tan[:-1], tan[1:])
        self.keys = key
        self.source_points = p

    def blending(self, t):
        """Weights of ``P_{i-1}, P_i, P_{i+1}, P_{i+2}`` (the four points
        around the segment containing ``t``): (4,) or (M, 4) float64."""
        ta, scalar = as_params(t, *self.domain)
        S = len(self.points) - 1
        u = ta - np.clip(np.floor(ta), 0, S - 1)
        pw = np.stack([u ** 3, u ** 2, u, np.ones_like(u)], axis=1)
        return shape_out(pw @ cardinal_matrix(self.tension), scalar)


class CatmullRom(CardinalSpline):
    """Catmull-Rom spline: the cardinal spline with tension 0 (uniform
    parameterization)."""

    def __init__(self, points, ends='duplicate'):
        super().__init__(points, 0.0, ends)
