r"""B-spline curves of any degree with uniform or non-uniform knot vectors,
open (clamped or not) or periodic (closed).

A B-spline of degree ``p`` with control points ``P_0 .. P_{N-1}`` and a
non-decreasing knot vector ``u_0 .. u_{N+p}`` is

.. math:: C(t) = \sum_i N_{i,p}(t) P_i, \qquad t \in [u_p, u_N]

with the Cox-de Boor basis functions

.. math::

    N_{i,0}(t) = [u_i \le t < u_{i+1}], \quad
    N_{i,d}(t) = \frac{t - u_i}{u_{i+d} - u_i} N_{i,d-1}(t)
               + \frac{u_{i+d+1} - t}{u_{i+d+1} - u_{i+1}} N_{i+1,d-1}(t)

(``0/0 = 0``; at ``t = u_N`` the last non-empty span is used).  Evaluation
uses de Boor's algorithm, vectorized over all parameters; conversion to
Bezier form evaluates the blossom ``b(a^{p-i}, b^i)`` on every span at once.

The default knot vector is the clamped uniform one on [0, 1]: ``p + 1``
zeros, uniform interior knots, ``p + 1`` ones; the curve then starts at
``P_0`` and ends at ``P_{N-1}``.

>>> s = BSpline([[0, 0], [1, 2], [3, 2], [4, 0]], degree=3)
>>> s.knots.tolist()
[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
>>> s.eval(0.5).tolist()     # one span: the cubic Bezier with these points
[2.0, 1.5]
"""

import numpy as np

from .base import CurveMixin
from .bezier import PiecewiseBezier
from .checks import MAX_CURVE_COORD, CurveError, as_degree, as_params, as_points, shape_out


def clamped_uniform_knots(n_points, degree, lo=0.0, hi=1.0):
    """Clamped uniform knot vector for ``n_points`` control points:
    (n_points + degree + 1,) float64 on ``[lo, hi]``.

    >>> clamped_uniform_knots(5, 2).tolist()
    [0.0, 0.0, 0.0, 0.3333333333333333, 0.6666666666666666, 1.0, 1.0, 1.0]
    """
    inner = np.linspace(lo, hi, n_points - degree + 1)
    return np.concatenate([np.full(degree, lo), inner, np.full(degree, hi)])


def _deboor(knots, ctrl, p, span, args):
    """Blossom of a B-spline on given spans, vectorized.

    knots : (K,); ctrl : (N, D); span : (M,) int with ``u_k < u_{k+1}``;
    args : (M, p) blossom arguments.  Returns (M, D).
    """
    M = len(span)
    off = span[:, None] - p + np.arange(p + 1)[None, :]           # (M, p+1)
    d = ctrl[off]                                                  # (M, p+1, D)
    for r in range(1, p + 1):
        ll = np.arange(r, p + 1)
        i = span[:, None] - p + ll[None, :]                        # (M, p+1-r)
        lo = knots[i]
        hi = knots[span[:, None] + ll[None, :] + 1 - r]
        a = ((args[:, r - 1][:, None] - lo) / (hi - lo))[:, :, None]
        d[:, r:] = (1.0 - a) * d[:, r - 1:p] + a * d[:, r:]
    return d[np.arange(M), p] if M else np.zeros((0, ctrl.shape[1]))


class BSpline(CurveMixin):
    """A B-spline curve.

    Parameters
    ----------
    points : (N, D) array_like of float
        Control points (N >= degree + 1).
    degree : int
        ``p >= 0``; default 3.
    knots : (N + p + 1,) array_like of float, optional
        Non-decreasing, with no value repeated more than ``p + 1`` times and
        ``u_p < u_N``.  Default: clamped uniform on [0, 1].  Not allowed with
        ``closed=True``.
    closed : bool
        Periodic B-spline: the first ``p`` control points are repeated at the
        end and the knots are uniform, so the curve is a closed loop with
        ``C^(p-1)`` continuity everywhere; domain [0, 1].

    Raises
    ------
    CurveError
        Too few points for the degree, a bad knot vector.
    """

    def __init__(self, points, degree=3, knots=None, closed=False):
        p = as_degree(degree)
        pts = as_points(points, 1, dims=None)
        N = len(pts)
        if N < p + 1:
            raise CurveError('a degree-%d B-spline needs at least %d control points, got %d'
                             % (p, p + 1, N))
        self.points = pts
        self.closed = bool(closed)
        if closed:
            if knots is not None:
                raise CurveError('a closed B-spline uses uniform knots; do not pass knots')
            ctrl = np.concatenate([pts, pts[:p]])
            kn = (np.arange(N + 2 * p + 1, dtype=np.float64) - p) / N
        else:
            ctrl = pts
            if knots is None:
                kn = clamped_uniform_knots(N, p)
            else:
                try:
                    kn = np.array(knots, dtype=np.float64).reshape(-1)
                except (TypeError, ValueError):
                    raise CurveError('knots must be numbers') from None
                _check_knots(kn, N, p)
        self._set(ctrl, p, kn)

    def _set(self, ctrl, p, kn):
        self.ctrl = ctrl
        self.degree = p
        self.knots = kn
        N = len(ctrl)
        nonempty = np.nonzero(kn[p:N] < kn[p + 1:N + 1])[0] + p
        self._kmax = int(nonempty[-1])

    @classmethod
    def _raw(cls, ctrl, p, kn, closed=False):
        obj = cls.__new__(cls)
        obj.points = ctrl
        obj.closed = closed
        obj._set(ctrl, p, kn)
        return obj

    def __repr__(self):
        return 'BSpline(%d points, degree %d%s)' % (len(self.ctrl), self.degree,
                                                  ', closed' if self.closed else '')

    @property
    def domain(self):
        return (float(self.knots[self.degree]), float(self.knots[len(self.ctrl)]))

    @property
    def dim(self):
        return self.ctrl.shape[1]

    def control_points(self):
        """(N, D) float64 copy of the control points actually used (for a
        closed spline, with the first ``p`` repeated at the end)."""
        return self.ctrl.copy()

    def span(self, t):
        """Knot span index ``k`` (``u_k <= t < u_{k+1}``, non-empty) of each
        ``t``: (M,) int64."""
        ta, _ = as_params(t, *self.domain)
        return self._span(ta)

    def _span(self, ta):
        k = np.searchsorted(self.knots, ta, side='right') - 1
        return np.clip(k, self.degree, self._kmax)

    # -- evaluation ----------------------------------------------------------
    def eval(self, t):
        """Point(s) by de Boor's algorithm: (D,) or (M, D) float64."""
        ta, scalar = as_params(t, *self.domain)
        args = np.repeat(ta[:, None], self.degree, axis=1)
        return shape_out(_deboor(self.knots, self.ctrl, self.degree, self._span(ta), args),
                         scalar)

    __call__ = eval

    def basis(self, t):
        """Cox-de Boor basis function values ``N_{i,p}(t)``.

        Returns
        -------
        (N,) or (M, N) float64 ndarray
            Non-negative, rows sum to 1 inside the domain.
        """
        ta, scalar = as_params(t, *self.domain)
        return shape_out(basis_functions(self.knots, self.degree, ta, self._span(ta)), scalar)

    blending = basis

    def deriv(self, order=1):
        """Derivative B-spline (degree ``p - order``) with respect to ``t``:
        ``Q_i = p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1})`` on the knots
        without their first and last entries."""
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            raise CurveError('derivative order must be a non-negative integer')
        s = self
        for _ in range(int(order)):
            p, c, u = s.degree, s.ctrl, s.knots
            if p == 0:
                s = BSpline._raw(np.zeros_like(c), 0, u)
                continue
            den = u[p + 1:len(c) + p] - u[1:len(c)]
            with np.errstate(divide='ignore', invalid='ignore'):
                q = p * np.diff(c, axis=0) / den[:, None]
            q[den == 0] = 0.0
            s = BSpline._raw(q, p - 1, u[1:-1])
        return s

    # -- knot insertion --------------------------------------------------------
    def insert_knot(self, t, times=1):
        """The same curve with knot ``t`` inserted ``times`` times (Boehm's
        algorithm).  The multiplicity of ``t`` may not exceed ``p``."""
        lo, hi = self.domain
        ta, _ = as_params(t, lo, hi)
        if ta.size != 1:
            raise CurveError('insert one knot value at a time')
        t = float(ta[0])
        if isinstance(times, bool) or not isinstance(times, (int, np.integer)) or times < 0:
            raise CurveError('times must be a non-negative integer')
        p = self.degree
        mult = int(np.sum(self.knots == t))
        if mult + times > p:
            raise CurveError('knot %g would get multiplicity %d > degree %d' % (t, mult + times, p))
        c, u = self.ctrl, self.knots
        for _ in range(int(times)):
            k = int(np.clip(np.searchsorted(u, t, side='right') - 1, p, len(c) - 1))
            if u[k] == t and t == hi:
                k = int(np.nonzero(u < t)[0][-1])
            i = np.arange(k - p + 1, k + 1)
            a = ((t - u[i]) / (u[i + p] - u[i]))[:, None]
            mid = (1.0 - a) * c[i - 1] + a * c[i]
            c = np.concatenate([c[:k - p + 1], mid, c[k:]])
            u = np.concatenate([u[:k + 1], [t], u[k + 1:]])
        return BSpline._raw(c, p, u, self.closed)

    # -- conversion ----------------------------------------------------------
    def to_beziers(self):
        """Exact piecewise Bezier form: one degree-``p`` segment per
        non-empty knot span of the domain, breaks at the distinct knots."""
        p, u = self.degree, self.knots
        N = len(self.ctrl)
        k = np.nonzero(u[p:N] < u[p + 1:N + 1])[0] + p                # (S,) spans
        a, b = u[k], u[k + 1]
        S = len(k)
        ctrl = np.empty((S, p + 1, self.dim))
        if p == 0:
            ctrl[:, 0] = self.ctrl[k]
        for i in range(p + 1):
            args = np.empty((S, p))
            args[:, :p - i] = a[:, None]
            args[:, p - i:] = b[:, None]
            ctrl[:, i] = _deboor(u, self.ctrl, p, k, args) if p else ctrl[:, i]
        return PiecewiseBezier(ctrl, np.concatenate([a, b[-1:]]))


def _check_knots(kn, N, p):
    if kn.shape != (N + p + 1,):
        raise CurveError('a degree-%d B-spline with %d control points needs %d knots, got %d'
                         % (p, N, N + p + 1, kn.size))
    if not np.all(np.isfinite(kn)) or np.abs(kn).max() > MAX_CURVE_COORD:
        raise CurveError('knots must be finite and at most %g in magnitude' % MAX_CURVE_COORD)
    if np.any(np.diff(kn) < 0):
        i = int(np.nonzero(np.diff(kn) < 0)[0][0])
        raise CurveError('knots must be non-decreasing (knot %d = %g > knot %d = %g)'
                         % (i, kn[i], i + 1, kn[i + 1]))
    _, counts = np.unique(kn, return_counts=True)
    if counts.max() > p + 1:
        raise CurveError('a knot is repeated %d times; at most degree + 1 = %d allowed'
                         % (counts.max(), p + 1))
    if not kn[p] < kn[N]:
        raise CurveError('empty domain: knot %d equals knot %d' % (p, N))


def knot_spans(knots, degree, t):
    """Index ``i`` of the knot span ``[u_i, u_{i+1})`` holding each
    parameter (clamped to the non-empty spans of the domain, so the domain's
    end belongs to the last one): (M,) int64."""
    u = np.asarray(knots, dtype=np.float64)
    p = int(degree)
    ta = np.asarray(t, dtype=np.float64).reshape(-1)
    N = len(u) - p - 1
    nonempty = np.nonzero(u[p:N] < u[p + 1:N + 1])[0] + p
    return np.clip(np.searchsorted(u, ta, side='right') - 1, p, nonempty[-1])


def basis_functions(knots, degree, t, span=None):
    """Cox-de Boor basis functions for many ``t`` at once.

    Parameters
    ----------
    knots : (K,) array_like of float
        Non-decreasing knot vector.
    degree : int
    t : (M,) array_like of float
        Parameters inside ``[knots[degree], knots[K - degree - 1]]``.
    span : (M,) int ndarray, optional
        Precomputed spans (used at the domain's right end).

    Returns
    -------
    (M, K - degree - 1) float64 ndarray

    >>> basis_functions([0, 0, 0, 1, 1, 1], 2, [0.5]).tolist()
    [[0.25, 0.5, 0.25]]
    """
    u = np.asarray(knots, dtype=np.float64)
    p = int(degree)
    ta = np.asarray(t, dtype=np.float64).reshape(-1)
    N = len(u) - p - 1
    if span is None:
        span = knot_spans(u, p, ta)
    M = len(ta)
    B = np.zeros((M, len(u) - 1))
    B[np.arange(M), span] = 1.0
    tt = ta[:, None]
    for d in range(1, p + 1):
        m = len(u) - 1 - d
        i = np.arange(m)
        den1 = u[i + d] - u[i]
        den2 = u[i + d + 1] - u[i + 1]
        with np.errstate(divide='ignore', invalid='ignore'):
            w1 = np.where(den1 > 0, (tt - u[i]) / den1, 0.0)
            w2 = np.where(den2 > 0, (u[i + d + 1] - tt) / den2, 0.0)
        B = w1 * B[:, :m] + w2 * B[:, 1:m + 1]
    return B[:, :N]
