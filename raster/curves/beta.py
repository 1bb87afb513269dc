r"""Barsky's uniform cubic Beta-spline with shape parameters ``beta1`` (bias)
and ``beta2`` (tension).

Segment ``s`` (parameter ``u = t - s`` in [0, 1]) blends four consecutive
control points:

.. math:: Q_s(u) = \sum_{r=-2}^{1} b_r(\beta_1, \beta_2; u) V_{s+2+r}

The blending functions are the cubics fixed by Barsky's constraints at every
joint, for all control points: positions agree (G0), first derivatives
satisfy ``Q_s'(0) = beta1 Q_{s-1}'(1)`` (G1) and second derivatives satisfy
``Q_s''(0) = beta1^2 Q_{s-1}''(1) + beta2 Q_{s-1}'(1)`` (G2), normalized by
``sum_r b_r(0) = 1``.  Solving those 16 linear conditions gives, with
``delta = 2 beta1^3 + 4 beta1^2 + 4 beta1 + beta2 + 2``,

.. math::

    b_{-2} &= 2\beta_1^3 (1-u)^3 / \delta \\
    b_{-1} &= [2\beta_1^3 u(u^2-3u+3) + 2\beta_1^2 (u^3-3u^2+2)
              + 2\beta_1 (u^3-3u+2) + \beta_2 (2u^3-3u^2+1)] / \delta \\
    b_{0}  &= [2\beta_1^2 u^2(3-u) + 2\beta_1 u(3-u^2)
              + \beta_2 u^2(3-2u) + 2(1-u^3)] / \delta \\
    b_{1}  &= 2u^3 / \delta

(the test suite re-derives them by solving the constraint system).  With
``beta1 = 1, beta2 = 0`` this is the uniform cubic B-spline.  ``beta1 > 0``
and ``beta2 >= 0`` keep ``delta > 0`` and the functions non-negative.

>>> np.round(beta_basis_matrix(1, 0) * 6, 12).tolist()
[[-1.0, 3.0, -3.0, 1.0], [3.0, -6.0, 3.0, 0.0], [-3.0, 0.0, 3.0, 0.0], [1.0, 4.0, 1.0, 0.0]]
"""

import numpy as np

from .base import CurveMixin
from .checks import CurveError, as_params, as_points, as_scalar, shape_out
from .bezier import PiecewiseBezier, bernstein_matrix


def beta_basis_matrix(beta1=1.0, beta2=0.0):
    """The 4x4 Beta-spline basis matrix: rows multiply ``u^3, u^2, u, 1``,
    columns weight ``V_{s}, V_{s+1}, V_{s+2}, V_{s+3}`` (float64)."""
    b1 = as_scalar(beta1, 'beta1 (bias)')
    b2 = as_scalar(beta2, 'beta2 (tension)')
    if b1 <= 0 or b2 < 0:
        raise CurveError('Beta-spline needs beta1 > 0 and beta2 >= 0, got %g, %g' % (b1, b2))
    d = 2 * b1 ** 3 + 4 * b1 ** 2 + 4 * b1 + b2 + 2
    m = np.array([
        [-2 * b1 ** 3, 2 * b1 ** 3 + 2 * b1 ** 2 + 2 * b1 + 2 * b2,
         -2 * b1 ** 2 - 2 * b1 - 2 * b2 - 2, 2.0],
        [6 * b1 ** 3, -6 * b1 ** 3 - 6 * b1 ** 2 - 3 * b2, 6 * b1 ** 2 + 3 * b2, 0.0],
        [-6 * b1 ** 3, 6 * b1 ** 3 - 6 * b1, 6 * b1, 0.0],
        [2 * b1 ** 3, 4 * b1 ** 2 + 4 * b1 + b2, 2.0, 0.0]])
    return m / d


def beta_blend(t, beta1=1.0, beta2=0.0):
    """Blending functions ``b_{-2}, b_{-1}, b_0, b_1`` at local ``u``:
    (4,) or (M, 4) float64."""
    ta = np.asarray(t, dtype=np.float64)
    scalar = ta.ndim == 0
    ta = ta.reshape(-1)
    pw = np.stack([ta ** 3, ta ** 2, ta, np.ones_like(ta)], axis=1)
    out = pw @ beta_basis_matrix(beta1, beta2)
    return out[0] if scalar else out


class BetaSpline(CurveMixin):
    """Uniform cubic Beta-spline.

    Parameters
    ----------
    points : (N, D) array_like of float
        Control points, N >= 4 (N >= 3 when closed).
    beta1 : float
        Bias, > 0 (1: unbiased).
    beta2 : float
        Tension, >= 0 (0: none).
    closed : bool
        Wrap the first three points around: a closed loop of N segments.

    The parameter runs over ``[0, S]``; segment ``s`` is ``[s, s+1]``.
    """

    def __init__(self, points, beta1=1.0, beta2=0.0, closed=False):
        p = as_points(points, 3 if closed else 4, dims=None)
        self.points = p
        self.closed = bool(closed)
        self.matrix = beta_basis_matrix(beta1, beta2)
        self.beta1, self.beta2 = float(beta1), float(beta2)
        self.ctrl = np.concatenate([p, p[:3]]) if closed else p

    @property
    def domain(self):
        return (0.0, float(len(self.ctrl) - 3))

    def _windows(self, idx):
        return self.ctrl[idx[:, None] + np.arange(4)[None, :]]          # (M, 4, D)

    def eval(self, t):
        """Point(s) at global ``t``: (D,) or (M, D) float64."""
        ta, scalar = as_params(t, *self.domain)
        idx = np.clip(np.floor(ta).astype(np.int64), 0, len(self.ctrl) - 4)
        u = ta - idx
        w = beta_blend(u, self.beta1, self.beta2)
        return shape_out(np.einsum('mk,mkd->md', w, self._windows(idx)), scalar)

    __call__ = eval

    def blending(self, t):
        """Blending function values at the local parameter of ``t``."""
        ta, scalar = as_params(t, *self.domain)
        u = ta - np.clip(np.floor(ta), 0, len(self.ctrl) - 4)
        return shape_out(beta_blend(u, self.beta1, self.beta2), scalar)

    def to_beziers(self):
        """Exact cubic Bezier segments (basis change
        ``Bernstein^-1 @ power <- beta``)."""
        g = np.linalg.solve(bernstein_matrix(3), self.matrix[::-1])     # (4, 4)
        S = len(self.ctrl) - 3
        ctrl = np.einsum('ik,skd->sid', g, self._windows(np.arange(S)))
        return PiecewiseBezier(ctrl)
