r"""NURBS curves: non-uniform rational B-splines of any degree.

A NURBS curve of degree ``p`` with control points ``P_i``, positive weights
``w_i`` and a non-decreasing knot vector is

.. math:: C(t) = \frac{\sum_i N_{i,p}(t) w_i P_i}{\sum_i N_{i,p}(t) w_i}
          = \sum_i R_{i,p}(t) P_i ,

the projection of the B-spline with homogeneous control points
``(w_i P_i, w_i)``.  This module keeps exactly that B-spline
(:class:`~raster.curves.bspline.BSpline` in dimension ``D + 1``) and derives
everything from it: evaluation by de Boor's algorithm, knot insertion by
Boehm's, the exact split into rational Bezier segments
(:meth:`NURBS.to_rational_beziers`), and derivatives by Leibniz's rule (see
:mod:`raster.curves.rational`).

Equal weights give the B-spline with the same control points and knots
(:meth:`NURBS.to_bspline`, exact); :meth:`NURBS.from_bspline` goes the other
way.

>>> c = NURBS([[1, 0], [1, 1], [0, 1]], [1, 2 ** -0.5, 1], degree=2)   # quarter circle
>>> p = c.eval(0.3)
>>> bool(abs(p @ p - 1) < 1e-15)
True
"""

import numpy as np

from .base import CurveMixin
from .checks import CurveError, as_params, as_points, shape_out
from .bspline import BSpline
from .rational import PiecewiseRational, check_weights, rational_derivatives

__all__ = ['NURBS']


class NURBS(CurveMixin):
    """A NURBS curve.

    Parameters
    ----------
    points : (N, D) array_like of float
        Control points (N >= degree + 1).
    weights : (N,) array_like of float, optional
        Positive weights; default all 1.
    degree : int
        ``p >= 1``; default 3.
    knots : (N + p + 1,) array_like of float, optional
        Non-decreasing knot vector (any spacing); default clamped uniform on
        [0, 1] (the curve then starts at ``P_0`` and ends at ``P_{N-1}``).
    closed : bool
        Periodic curve with uniform knots (as :class:`BSpline`); the first
        ``p`` points and weights are repeated at the end.

    Raises
    ------
    CurveError
        Bad points, weights or knots (as :class:`BSpline`).
    """

    def __init__(self, points, weights=None, degree=3, knots=None, closed=False):
        pts = as_points(points, 1, dims=None)
        N = len(pts)
        w = check_weights(1.0 if weights is None else weights, (N,))
        hom = np.concatenate([pts * w[:, None], w[:, None]], axis=1)
        self._set(BSpline(hom, degree, knots, closed), pts, w)

    def _set(self, hb, pts, w):
        self._h = hb
        self.points = pts
        self.weights = w
        self.degree = hb.degree
        self.knots = hb.knots
        self.closed = hb.closed

    @classmethod
    def _from_homogeneous(cls, hb):
        c = hb.control_points()
        w = c[:, -1]
        if np.any(w <= 0):
            raise CurveError('homogeneous weights must be positive')
        obj = cls.__new__(cls)
        obj._set(hb, c[:, :-1] / w[:, None], w)
        return obj

    @classmethod
    def from_bspline(cls, bspline, weights=None):
        """The NURBS with a B-spline's control points and knots (weights 1
        unless given: then the same curve as the B-spline)."""
        if not isinstance(bspline, BSpline):
            raise CurveError('from_bspline needs a BSpline')
        pts = bspline.control_points()
        if bspline.closed:
            pts = pts[:len(pts) - bspline.degree]
            return cls(pts, weights, bspline.degree, closed=True)
        return cls(pts, weights, bspline.degree, bspline.knots)

    @classmethod
    def from_rational(cls, chain, tolerance=1e-9):
        """The NURBS of a :class:`~raster.curves.rational.PiecewiseRational`
        (or :class:`~raster.curves.rational.RationalBezier`), exactly:
        interior knots of multiplicity ``n`` at the breaks, each segment's
        weights scaled so that they agree at the joints.

        Raises
        ------
        CurveError
            Consecutive segments do not meet (relative ``tolerance``).
        """
        from .rational import RationalBezier
        if isinstance(chain, RationalBezier):
            chain = chain.to_chain()
        if not isinstance(chain, PiecewiseRational):
            raise CurveError('from_rational needs a PiecewiseRational or RationalBezier')
        n, S = chain.degree, len(chain)
        if n < 1:
            raise CurveError('a NURBS needs degree >= 1')
        ends, starts = chain.ctrl[:-1, -1], chain.ctrl[1:, 0]
        scale = max(1.0, float(np.abs(chain.ctrl).max()))
        if S > 1 and np.abs(ends - starts).max() > tolerance * scale:
            raise CurveError('segments do not meet at their joints; a NURBS is continuous')
        w = chain.weights.copy()
        for s in range(1, S):
            w[s] *= w[s - 1, -1] / w[s, 0]
        pts = [chain.ctrl[0]] + [chain.ctrl[s, 1:] for s in range(1, S)]
        wts = [w[0]] + [w[s, 1:] for s in range(1, S)]
        br = chain.breaks
        knots = np.concatenate([[br[0]] * (n + 1)] + [[b] * n for b in br[1:-1]]
                               + [[br[-1]] * (n + 1)])
        return cls(np.concatenate(pts), np.concatenate(wts), n, knots)

    def __repr__(self):
        return 'NURBS(%d points, degree %d%s)' % (len(self.points), self.degree,
                                                ', closed' if self.closed else '')

    @property
    def domain(self):
        return self._h.domain

    @property
    def dim(self):
        return self.points.shape[1]

    def control_points(self):
        """(N', D) float64: the control points used (closed: with the first
        ``p`` repeated)."""
        c = self._h.control_points()
        return c[:, :-1] / c[:, -1:]

    def control_weights(self):
        """(N',) float64: the weights used (closed: repeated like the
        points)."""
        return self._h.control_points()[:, -1].copy()

    def homogeneous(self):
        """The homogeneous :class:`BSpline` ``(w P, w)`` of dimension D+1."""
        return self._h

    def is_rational(self, tolerance=0.0):
        """False when all weights are equal (relative ``tolerance``)."""
        w = self.control_weights()
        return bool(w.max() - w.min() > tolerance * w.max())

    def segments(self):
        """The exact rational Bezier chain (:meth:`to_rational_beziers`)."""
        return self.to_rational_beziers()

    # -- evaluation ----------------------------------------------------------
    def eval(self, t):
        """Point(s): (D,) or (M, D) float64."""
        ta, scalar = as_params(t, *self.domain)
        h = np.atleast_2d(self._h.eval(ta))
        D = self.dim
        return shape_out(h[:, :D] / h[:, D:], scalar)

    __call__ = eval

    def derivatives(self, t, order=1):
        """Point and derivatives up to ``order``: (order+1, D) or
        (M, order+1, D) float64 (row ``k`` is ``C^(k)(t)``)."""
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            raise CurveError('derivative order must be a non-negative integer')
        ta, scalar = as_params(t, *self.domain)
        hd = [np.atleast_2d(self._h.deriv(k).eval(ta)) for k in range(int(order) + 1)]
        return shape_out(rational_derivatives(hd, self.dim), scalar)

    def tangent(self, t):
        """First derivative: (D,) or (M, D) float64."""
        return self.derivatives(t, 1)[..., 1, :]

    def basis(self, t):
        """Rational basis functions ``R_{i,p}(t) = w_i N_{i,p}(t) / sum_j w_j
        N_{j,p}(t)``: (N',) or (M, N') float64, rows sum to 1."""
        ta, scalar = as_params(t, *self.domain)
        b = np.atleast_2d(self._h.basis(ta)) * self.control_weights()
        return shape_out(b / b.sum(axis=1, keepdims=True), scalar)

    blending = basis

    def span(self, t):
        """Knot span index of each ``t``: (M,) int64."""
        return self._h.span(t)

    # -- modification ----------------------------------------------------------
    def insert_knot(self, t, times=1):
        """The same curve with knot ``t`` inserted ``times`` times (Boehm's
        algorithm on the homogeneous points)."""
        return NURBS._from_homogeneous(self._h.insert_knot(t, times))

    def transform(self, matrix, offset=None):
        """Apply ``p -> matrix @ p + offset`` to the control points (affine
        invariance; weights unchanged)."""
        if self.closed:
            raise CurveError('transform a closed NURBS by building it from transformed points')
        m = np.asarray(matrix, dtype=np.float64)
        c = self.points @ m.T
        if offset is not None:
            c = c + np.asarray(offset, dtype=np.float64)
        return NURBS(c, self.weights, self.degree, self.knots)

    # -- conversion ----------------------------------------------------------
    def to_rational_beziers(self):
        """Exact rational Bezier segments, one per non-empty knot span, as a
        :class:`~raster.curves.rational.PiecewiseRational` with breaks at the
        distinct knots."""
        return PiecewiseRational.from_homogeneous(self._h.to_beziers(), closed=self.closed)

    def to_bspline(self):
        """The polynomial :class:`BSpline` with these points and knots,
        exact; only for equal weights.

        Raises
        ------
        CurveError
            The weights differ.
        """
        if self.is_rational():
            raise CurveError('the weights differ: no exact B-spline form; use '
                             'to_beziers(tolerance)')
        if self.closed:
            return BSpline(self.points, self.degree, closed=True)
        return BSpline(self.points, self.degree, self.knots)

    def to_beziers(self, tolerance=None):
        """Polynomial Bezier chain: exact for equal weights, else cubics
        within ``tolerance`` (:meth:`PiecewiseRational.to_beziers`)."""
        return self.to_rational_beziers().to_beziers(tolerance)

    def subsegment(self, t0, t1):
        """The part with ``t0 <= t <= t1`` (a :class:`PiecewiseRational` on the
        global parameter)."""
        return PiecewiseRational.from_homogeneous(self._h.subsegment(t0, t1))

    def deriv(self, order=1):
        """The derivative curve, exactly, as a :class:`PiecewiseRational`."""
        return self.to_rational_beziers().deriv(order)

    def continuity(self, tolerance=1e-9):
        """Continuity at the distinct interior knots (and the closing joint
        of a closed curve)."""
        return self.to_rational_beziers().continuity(tolerance)
