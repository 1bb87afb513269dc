r"""Rational Bezier curves of any degree, and chains of them.

A rational Bezier curve of degree ``n`` with control points ``P_i`` and
positive weights ``w_i`` is

.. math:: R(t) = \frac{\sum_i w_i B_{n,i}(t) P_i}{\sum_i w_i B_{n,i}(t)}
          = \frac{A(t)}{w(t)}, \qquad t \in [0, 1],

the central projection of the polynomial Bezier curve with homogeneous
control points ``(w_i P_i, w_i)`` in one dimension more.  Everything here
works on that homogeneous form: evaluation, splitting and knot insertion are
the polynomial algorithms applied to ``(A, w)``; derivatives follow from
``A = w R`` by Leibniz's rule,

.. math:: R^{(k)} = \Big(A^{(k)} - \sum_{i=1}^{k} \binom{k}{i} w^{(i)} R^{(k-i)}\Big) / w ;

the derivative curve is again rational, ``R' = (A' w - A w') / w^2`` (degree
``2n``); coordinate extrema are the roots of the numerators
``A'_d w - A_d w'`` (degree ``2n - 1``), found exactly in Bernstein form.

Equal weights give the polynomial Bezier curve with the same control points
(:meth:`RationalBezier.to_bezier`, exact); otherwise
:meth:`PiecewiseRational.to_beziers` approximates by cubics with the same end
points and end tangents, split until a rigorous error bound holds: with
``B`` the cubic, ``R - B = (A - w B) / w``, and ``A - w B`` is a polynomial of
degree ``n + 3`` whose Bernstein coefficients bound it, while ``w`` is at
least its smallest Bernstein coefficient.

Conic sections are the rational quadratics (:mod:`raster.curves.conics`).

>>> q = RationalBezier([[1, 0], [1, 1], [0, 1]], [1, 2 ** -0.5, 1])   # quarter circle
>>> p = q.eval(0.5)
>>> bool(abs(p @ p - 1) < 1e-15)
True
"""

import math
from typing import Sequence, Tuple

import numpy as np
from numpy.typing import ArrayLike

from .base import CurveMixin
from .checks import CurveError, as_params, as_points, as_scalar, shape_out
from .bezier import Bezier, PiecewiseBezier

__all__ = ['RationalBezier', 'PiecewiseRational', 'bernstein_product', 'check_weights',
           'rational_derivatives']

#: Largest ratio between the weights of one segment (keeps the homogeneous
#: arithmetic well conditioned).
MAX_WEIGHT_RATIO = 1e12

#: Most pieces a cubic approximation may produce.
MAX_APPROX_PIECES = 1 << 20


def check_weights(w: ArrayLike, shape: Tuple[int, ...], name: str = 'weights') -> np.ndarray:
    """Validate positive weights: a scalar or an array of ``shape``; returns
    a float64 array of ``shape``.

    Raises
    ------
    CurveError
        Not finite and positive, the wrong shape, or weights of one row
        (last axis) spanning more than :data:`MAX_WEIGHT_RATIO`.
    """
    try:
        a = np.array(w, dtype=np.float64)
    except (TypeError, ValueError):
        raise CurveError('%s must be numbers' % name) from None
    if a.ndim == 0:
        a = np.full(shape, float(a))
    if a.shape != shape:
        raise CurveError('need %s %s, got shape %s'
                         % ('x'.join(map(str, shape)), name, a.shape))
    if not np.all(np.isfinite(a)) or np.any(a <= 0):
        raise CurveError('%s must be finite and positive' % name)
    lo, hi = a.min(axis=-1), a.max(axis=-1)
    if np.any(hi > MAX_WEIGHT_RATIO * lo):
        raise CurveError('weights of one segment differ by more than a factor %g'
                         % MAX_WEIGHT_RATIO)
    return a


def bernstein_product(f: ArrayLike, g: ArrayLike) -> np.ndarray:
    """Product of polynomials given by Bernstein coefficients, in Bernstein
    form: ``c_k = sum_{i+j=k} C(a,i) C(b,j) / C(a+b,k) f_i g_j``.

    Parameters
    ----------
    f : (S, a+1, D) array_like of float
    g : (S, b+1, D) or (S, b+1, 1) array_like of float
        Broadcast against ``f`` in the last axis.

    Returns
    -------
    (S, a+b+1, D) float64 ndarray

    >>> bernstein_product([[[1.0], [0.0]]], [[[1.0], [0.0]]]).ravel().tolist()  # (1-t)^2
    [1.0, 0.0, 0.0]
    """
    f = np.asarray(f, dtype=np.float64)
    g = np.asarray(g, dtype=np.float64)
    a, b = f.shape[1] - 1, g.shape[1] - 1
    D = max(f.shape[2], g.shape[2])
    out = np.zeros((f.shape[0], a + b + 1, D))
    for i in range(a + 1):
        ci = math.comb(a, i)
        for j in range(b + 1):
            out[:, i + j] += (ci * math.comb(b, j) / math.comb(a + b, i + j)) * f[:, i] * g[:, j]
    return out


def _elevate(c, times):
    """Degree elevation of Bernstein coefficients (S, n+1, D) by ``times``."""
    for _ in range(times):
        n = c.shape[1] - 1
        k = np.arange(1, n + 1)[None, :, None] / (n + 1)
        mid = k * c[:, :-1] + (1 - k) * c[:, 1:]
        c = np.concatenate([c[:, :1], mid, c[:, -1:]], axis=1)
    return c


def _split_at(h, t):
    """de Casteljau split of homogeneous segments h (S, n+1, K) at per-segment
    t (S,): (left, right)."""
    n1 = h.shape[1]
    tt = t[:, None, None]
    left = np.empty_like(h)
    right = np.empty_like(h)
    pts = h
    left[:, 0], right[:, -1] = h[:, 0], h[:, -1]
    for r in range(1, n1):
        pts = (1.0 - tt) * pts[:, :-1] + tt * pts[:, 1:]
        left[:, r] = pts[:, 0]
        right[:, n1 - 1 - r] = pts[:, -1]
    return left, right


def _pieces(h, u0, u1):
    """Homogeneous control points of the parts [u0, u1] (per row)."""
    _, right = _split_at(h, u0)
    frac = np.where(u0 < 1, (u1 - u0) / np.where(u0 < 1, 1 - u0, 1.0), 1.0)
    left, _ = _split_at(right, np.clip(frac, 0.0, 1.0))
    return left


def rational_derivatives(hd: Sequence[np.ndarray], D: int) -> np.ndarray:
    """Derivatives of a rational curve (or of a surface along one
    direction) from those of its homogeneous form, by Leibniz's rule.

    Parameters
    ----------
    hd : sequence of (M, D+1) float64 arrays
        The homogeneous point ``(A, w)`` and its derivatives of orders
        ``0 .. k``.
    D : int
        Dimension of the rational points.

    Returns
    -------
    (M, k+1, D) float64 ndarray
        ``R, R', ..., R^(k)``.
    """
    w = [x[:, D] for x in hd]
    out = []
    for k in range(len(hd)):
        acc = hd[k][:, :D].copy()
        for i in range(1, k + 1):
            acc -= math.comb(k, i) * w[i][:, None] * out[k - i]
        out.append(acc / w[0][:, None])
    return np.stack(out, axis=1)


class PiecewiseRational(CurveMixin):
    """A chain of ``S`` rational Bezier segments of one degree ``n``;
    segment ``s`` covers the global parameters ``[breaks[s], breaks[s+1]]``.

    Parameters
    ----------
    ctrl : (S, n+1, D) array_like of float
        Control points of every segment (finite).
    weights : (S, n+1) array_like of float
        Positive weights (a scalar gives equal weights).
    breaks : (S+1,) array_like of float, optional
        Strictly increasing joint parameters; default ``0, 1, ..., S``.
    closed : bool
        The chain is a closed loop: :meth:`continuity` also checks the
        joint from the last segment back to the first.

    Iterating yields :class:`RationalBezier` objects.

    >>> pr = PiecewiseRational([[[0, 0], [1, 1], [2, 0]]], [[1, 1, 1]])
    >>> pr.eval(0.5).tolist(), pr.is_polynomial()
    ([1.0, 0.5], True)
    """

    def __init__(self, ctrl, weights, breaks=None, closed=False):
        try:
            c = np.array(ctrl, dtype=np.float64)
        except (TypeError, ValueError):
            raise CurveError('control points must be numbers') from None
        if c.ndim != 3 or min(c.shape) < 1:
            raise CurveError('rational control points must be (S, n+1, D), got %s' % (c.shape,))
        as_points(c.reshape(-1, c.shape[2]), 1, dims=None)          # finiteness, limits
        w = check_weights(weights, c.shape[:2])
        hom = np.concatenate([c * w[..., None], w[..., None]], axis=2)
        self._h = PiecewiseBezier(hom, breaks)
        self.ctrl = c
        self.weights = w
        self.breaks = self._h.breaks
        self.closed = bool(closed)

    @classmethod
    def from_homogeneous(cls, pb, closed=False):
        """The chain whose homogeneous form is the :class:`PiecewiseBezier`
        ``pb`` (last coordinate the weight, which must stay positive)."""
        h = pb.ctrl
        w = h[..., -1]
        if np.any(w <= 0):
            raise CurveError('homogeneous weights must be positive')
        return cls(h[..., :-1] / w[..., None], w, pb.breaks, closed)

    def __repr__(self):
        return 'PiecewiseRational(%d segments, degree %d, D=%d)' % (len(self), self.degree,
                                                                   self.dim)

    # -- container -----------------------------------------------------------
    def __len__(self):
        return self.ctrl.shape[0]

    def __getitem__(self, i):
        return RationalBezier(self.ctrl[i], self.weights[i])

    def __iter__(self):
        return (RationalBezier(c, w) for c, w in zip(self.ctrl, self.weights))

    @property
    def degree(self):
        return self.ctrl.shape[1] - 1

    @property
    def dim(self):
        return self.ctrl.shape[2]

    @property
    def domain(self):
        return self._h.domain

    @property
    def points(self):
        """All control points, (S * (n+1), D) float64."""
        return self.ctrl.reshape(-1, self.dim)

    def control_points(self):
        """(S * (n+1), D) float64 copy of the control points."""
        return self.points.copy()

    def homogeneous(self):
        """The homogeneous form ``(w P, w)`` as a :class:`PiecewiseBezier` of
        dimension ``D + 1``."""
        return self._h

    def is_polynomial(self, tolerance=0.0):
        """True when every segment has equal weights (relative
        ``tolerance``): the chain is then a polynomial Bezier chain."""
        w = self.weights
        return bool(np.all(w.max(1) - w.min(1) <= tolerance * w.max(1)))

    def segments(self):
        """The chain itself: its own exact methods carry the vocabulary."""
        return self

    # -- evaluation ----------------------------------------------------------
    def eval(self, t):
        """Point(s) at global ``t``: (D,) or (M, D) float64 (the later segment
        at a joint)."""
        ta, scalar = as_params(t, *self.domain)
        h = np.atleast_2d(self._h.eval(ta))
        D = self.dim
        return shape_out(h[:, :D] / h[:, D:], scalar)

    __call__ = eval

    def derivatives(self, t, order=1):
        """The point and its derivatives up to ``order`` at ``t``.

        Returns
        -------
        (order+1, D) or (M, order+1, D) float64 ndarray
            Row ``k`` is ``R^(k)(t)`` (with respect to the global parameter).
        """
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            raise CurveError('derivative order must be a non-negative integer')
        ta, scalar = as_params(t, *self.domain)
        hd = [np.atleast_2d(self._h.deriv(k).eval(ta)) for k in range(int(order) + 1)]
        return shape_out(rational_derivatives(hd, self.dim), scalar)

    def tangent(self, t):
        """First derivative ``R'(t)``: (D,) or (M, D) float64."""
        d = self.derivatives(t, 1)
        return d[..., 1, :]

    def deriv(self, order=1):
        """The derivative curve, exactly: ``R' = (A' w - A w') / w^2``, a
        chain of degree ``2n`` (with respect to the global parameter)."""
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            raise CurveError('derivative order must be a non-negative integer')
        cur = self
        for _ in range(int(order)):
            cur = cur._deriv1()
        return cur

    def _deriv1(self):
        n, D = self.degree, self.dim
        h = self._h.ctrl
        A, w = h[..., :D], h[..., D:]
        hk = np.diff(self.breaks)[:, None, None]
        if n == 0:
            return PiecewiseRational(np.zeros_like(self.ctrl), np.ones_like(self.weights),
                                     self.breaks)
        dA, dw = n * np.diff(A, axis=1), n * np.diff(w, axis=1)
        num = bernstein_product(dA, w) - bernstein_product(A, dw)       # degree 2n - 1
        num = _elevate(num, 1) / hk
        den = bernstein_product(w, w)                                   # degree 2n
        return PiecewiseRational(num / den, den[..., 0], self.breaks)

    # -- pieces --------------------------------------------------------------
    def subsegment(self, t0, t1):
        """The part with ``t0 <= t <= t1``, keeping the global parameter."""
        return PiecewiseRational.from_homogeneous(self._h.subsegment(t0, t1))

    def reverse(self):
        """The chain traversed backwards on the same parameter range."""
        return PiecewiseRational.from_homogeneous(self._h.reverse(), self.closed)

    def transform(self, matrix, offset=None):
        """Apply ``p -> matrix @ p + offset`` to the control points (rational
        curves are affine invariant with unchanged weights)."""
        m = np.asarray(matrix, dtype=np.float64)
        c = self.ctrl @ m.T
        if offset is not None:
            c = c + np.asarray(offset, dtype=np.float64)
        return PiecewiseRational(c, self.weights, self.breaks, self.closed)

    # -- geometry ------------------------------------------------------------
    def _numerators(self):
        """Local Bernstein coefficients (S, 2n, D) of ``A'_d w - A_d w'``."""
        n, D = self.degree, self.dim
        h = self._h.ctrl
        A, w = h[..., :D], h[..., D:]
        return (bernstein_product(n * np.diff(A, axis=1), w)
                - bernstein_product(A, n * np.diff(w, axis=1)))

    def extrema(self):
        """Sorted global parameters inside segments where some coordinate has
        a zero derivative: (K,) float64."""
        if self.degree < 1:
            return np.zeros(0)
        num = self._numerators()                                      # (S, 2n, D)
        m1 = num.shape[1]                                             # 2n
        # an antiderivative of degree 2n whose hodograph is num: its
        # coordinate extrema are the roots of num
        q = np.concatenate([np.zeros_like(num[:, :1]), np.cumsum(num, axis=1) / m1], axis=1)
        return PiecewiseBezier(q, self.breaks).extrema()

    def bounding_box(self):
        """Exact bounding box ``(lo, hi)``: two (D,) float64 arrays."""
        t = np.concatenate([self.breaks, self.extrema()])
        p = np.concatenate([self.ctrl[:, 0], self.ctrl[-1:, -1], np.atleast_2d(self.eval(t))])
        return p.min(axis=0), p.max(axis=0)

    # -- conversion ----------------------------------------------------------
    def to_beziers(self, tolerance=None):
        """A :class:`~raster.curves.bezier.PiecewiseBezier` of this chain.

        Parameters
        ----------
        tolerance : float, optional
            Without it the chain must be polynomial (equal weights in every
            segment) and the conversion is exact.  With it, segments with
            unequal weights become cubics within ``tolerance`` (a rigorous
            bound, see the module notes) and the result is a cubic chain on
            the same global parameter.

        Raises
        ------
        CurveError
            Unequal weights and no tolerance, or a non-positive tolerance.
        LimitError
            More than :data:`MAX_APPROX_PIECES` pieces would be needed.
        """
        if tolerance is None:
            if not self.is_polynomial():
                raise CurveError('a rational curve with unequal weights has no exact '
                                 'polynomial form; give a tolerance')
            return PiecewiseBezier(self.ctrl, self.breaks)
        tol = as_scalar(tolerance, 'tolerance', 0.0)
        if tol <= 0:
            raise CurveError('tolerance must be positive')
        return self._cubics(tol)

    def _cubics(self, tol):
        from ..errors import LimitError
        h = self._h.ctrl
        n, D = self.degree, self.dim
        S = len(self)
        seg = np.arange(S)
        u0, u1 = np.zeros(S), np.ones(S)
        done = []
        for level in range(60):
            piece = _pieces(h[seg], u0, u1)                          # (K, n+1, D+1)
            w = piece[..., D]
            P = piece[..., :D] / w[..., None]
            cub = np.empty((len(seg), 4, D))
            cub[:, 0], cub[:, 3] = P[:, 0], P[:, -1]
            if n >= 1:
                d0 = n * (w[:, 1] / w[:, 0])[:, None] * (P[:, 1] - P[:, 0])
                d1 = n * (w[:, -2] / w[:, -1])[:, None] * (P[:, -1] - P[:, -2])
            else:
                d0 = d1 = np.zeros((len(seg), D))
            cub[:, 1] = cub[:, 0] + d0 / 3.0
            cub[:, 2] = cub[:, 3] - d1 / 3.0
            # error numerator A - w B in degree max(n, 3) + ... = n + 3
            E = _elevate(piece[..., :D], 3) - bernstein_product(cub, w[..., None])
            err = np.linalg.norm(E, axis=2).max(axis=1) / w.min(axis=1)
            ok = err <= tol
            if level == 59:
                ok[:] = True
            done.append((seg[ok], u0[ok], u1[ok], cub[ok]))
            bad = ~ok
            if not bad.any():
                break
            if 2 * int(bad.sum()) + sum(len(d[0]) for d in done) > MAX_APPROX_PIECES:
                raise LimitError('cubic approximation needs more than %d pieces; use a larger '
                                 'tolerance' % MAX_APPROX_PIECES)
            m = 0.5 * (u0[bad] + u1[bad])
            seg = np.concatenate([seg[bad], seg[bad]])
            u0, u1 = np.concatenate([u0[bad], m]), np.concatenate([m, u1[bad]])
        s = np.concatenate([d[0] for d in done])
        a = np.concatenate([d[1] for d in done])
        b = np.concatenate([d[2] for d in done])
        c = np.concatenate([d[3] for d in done])
        order = np.lexsort((a, s))
        s, a, b, c = s[order], a[order], b[order], c[order]
        br = self.breaks
        hs = br[s + 1] - br[s]
        brk = np.concatenate([br[s] + a * hs, [br[-1]]])
        # each cubic is in its piece's local parameter; the breaks map the
        # global parameter onto it linearly, as in the rational chain
        return PiecewiseBezier(c, brk)

    # -- drawing -------------------------------------------------------------
    def flatten(self, tolerance=0.25):
        """Polyline within ``tolerance`` of the curve: (K, D) float64 (half
        the tolerance for the cubic approximation, half for flattening)."""
        tol = as_scalar(tolerance, 'tolerance', 0.0)
        if tol <= 0:
            raise CurveError('tolerance must be positive')
        if self.is_polynomial():
            return self.to_beziers().flatten(tol)
        return self.to_beziers(tol / 2).flatten(tol / 2)

    def to_path(self, tolerance=0.25):
        """A :class:`raster.geometry.path.Path` of the (x, y) projection; rational
        segments as cubics within ``tolerance``."""
        return (self.to_beziers() if self.is_polynomial()
                else self.to_beziers(tolerance)).to_path(tolerance)

    def draw(self, pen, tolerance=0.25):
        """Send the (x, y) projection to a pen (fontTools protocol)."""
        (self.to_beziers() if self.is_polynomial()
         else self.to_beziers(tolerance)).draw(pen, tolerance)

    def end_derivatives(self):
        """Position, first and second derivative (global parameter) at both
        ends of every segment.

        Returns
        -------
        (starts, ends) : two (S, 3, D) float64 ndarrays
            ``starts[s, k]`` is ``R^(k)`` at the start of segment ``s`` (the
            right limit), ``ends[s, k]`` at its end (the left limit).
        """
        n, D = self.degree, self.dim
        h = self._h.ctrl
        hk = np.diff(self.breaks)

        def at(e, sgn):
            z = np.zeros_like(h[:, 0])
            d1 = n * sgn * (h[:, e + sgn] - h[:, e]) if n >= 1 else z
            d2 = n * (n - 1) * (h[:, e + 2 * sgn] - 2 * h[:, e + sgn] + h[:, e]) if n >= 2 else z
            loc = rational_derivatives([h[:, e], d1, d2], D)                       # local parameter
            return loc / (hk[:, None, None] ** np.arange(3)[None, :, None])

        return at(0, 1), at(n, -1)

    def continuity(self, tolerance=1e-9):
        """Continuity at each joint (:class:`~raster.curves.continuity.Joint`
        list), from the exact end derivatives of the segments."""
        from .continuity import continuity
        if len(self) < 2 and not self.closed:
            return []
        st, en = self.end_derivatives()
        hk = np.diff(self.breaks)[:, None]
        # quintic Hermite segments with the same end derivatives: the joint
        # analysis only looks at the ends
        q = np.empty((len(self), 6, self.dim))
        a0, a1, a2 = st[:, 0], st[:, 1] * hk, st[:, 2] * hk ** 2
        b0, b1, b2 = en[:, 0], en[:, 1] * hk, en[:, 2] * hk ** 2
        q[:, 0], q[:, 1], q[:, 2] = a0, a0 + a1 / 5, a0 + 2 * a1 / 5 + a2 / 20
        q[:, 5], q[:, 4], q[:, 3] = b0, b0 - b1 / 5, b0 - 2 * b1 / 5 + b2 / 20
        return continuity(PiecewiseBezier(q, self.breaks), tolerance, closed=self.closed)


class RationalBezier(CurveMixin):
    """A rational Bezier curve of degree ``n`` on ``t in [0, 1]``.

    Parameters
    ----------
    points : (n+1, D) array_like of float
        Control points.
    weights : (n+1,) array_like of float, optional
        Positive weights; default all 1 (the polynomial Bezier curve).

    >>> r = RationalBezier([[0, 0], [1, 1], [2, 0]], [1, 3, 1])
    >>> r.eval(0.5).tolist()                 # (0.25*0 + 0.5*3*1 + 0.25*2) / 2
    [1.0, 0.75]
    >>> r.blending(0.5).tolist()
    [0.125, 0.75, 0.125]
    """

    domain = (0.0, 1.0)

    def __init__(self, points, weights=None):
        p = as_points(points, 1, dims=None)
        w = check_weights(1.0 if weights is None else weights, (len(p),))
        self.points = p
        self.weights = w
        self._chain = PiecewiseRational(p[None], w[None])

    @classmethod
    def from_bezier(cls, bezier, weights=None):
        """The rational form of a :class:`~raster.curves.bezier.Bezier`
        (equal weights unless given)."""
        b = bezier if isinstance(bezier, Bezier) else Bezier(bezier)
        return cls(b.ctrl, weights)

    def __repr__(self):
        return 'RationalBezier(degree %d, D=%d, weights=%s)' % (
            self.degree, self.dim, np.array2string(self.weights, separator=', '))

    @property
    def degree(self):
        return len(self.points) - 1

    @property
    def dim(self):
        return self.points.shape[1]

    def control_points(self):
        """(n+1, D) float64 copy of the control points."""
        return self.points.copy()

    def to_chain(self):
        """This curve as a one-segment :class:`PiecewiseRational`."""
        return self._chain

    def is_polynomial(self, tolerance=0.0):
        return self._chain.is_polynomial(tolerance)

    def numerator(self):
        """``A(t) = sum w_i B_i(t) P_i`` as a :class:`Bezier` (points
        ``w_i P_i``)."""
        return Bezier(self.points * self.weights[:, None])

    def denominator(self):
        """``w(t) = sum w_i B_i(t)`` as a one-dimensional :class:`Bezier`."""
        return Bezier(self.weights[:, None])

    def segments(self):
        """The rational chain of this one segment (the vocabulary's source)."""
        return self._chain

    # -- evaluation ----------------------------------------------------------
    def eval(self, t):
        """Point(s): (D,) or (M, D) float64."""
        return self._chain.eval(t)

    __call__ = eval

    def derivatives(self, t, order=1):
        """Point and derivatives up to ``order``: (order+1, D) or
        (M, order+1, D)."""
        return self._chain.derivatives(t, order)

    def blending(self, t):
        """Rational basis functions ``R_i(t) = w_i B_i(t) / sum_j w_j
        B_j(t)``: (n+1,) or (M, n+1), non-negative, rows sum to 1."""
        from .bezier import bernstein
        ta, scalar = as_params(t, 0.0, 1.0)
        b = bernstein(self.degree, ta) * self.weights
        return shape_out(b / b.sum(axis=1, keepdims=True), scalar)

    def deriv(self, order=1):
        """The derivative curve (exact, degree ``2n`` per order): a
        :class:`RationalBezier`."""
        d = self._chain.deriv(order)
        return RationalBezier(d.ctrl[0], d.weights[0])

    # -- pieces --------------------------------------------------------------
    def split(self, t=0.5):
        """The halves ``[0, t]`` and ``[t, 1]``, each on [0, 1]."""
        t = as_scalar(t, 't', 0.0, 1.0)
        h = self._chain.homogeneous().ctrl
        left, right = _split_at(h, np.array([t]))
        D = self.dim
        return (RationalBezier(left[0, :, :D] / left[0, :, D:], left[0, :, D]),
                RationalBezier(right[0, :, :D] / right[0, :, D:], right[0, :, D]))

    def subsegment(self, t0, t1):
        """The piece from ``t0`` to ``t1`` (``t0 < t1``) on [0, 1]."""
        t0 = as_scalar(t0, 't0', 0.0, 1.0)
        t1 = as_scalar(t1, 't1', 0.0, 1.0)
        if not t0 < t1:
            raise CurveError('subsegment needs t0 < t1')
        p = _pieces(self._chain.homogeneous().ctrl, np.array([t0]), np.array([t1]))[0]
        D = self.dim
        return RationalBezier(p[:, :D] / p[:, D:], p[:, D])

    def reverse(self):
        return RationalBezier(self.points[::-1], self.weights[::-1])

    def elevate(self, times=1):
        """The same curve with degree ``n + times`` (homogeneous elevation)."""
        h = Bezier(self._chain.homogeneous().ctrl[0]).elevate(times).ctrl
        D = self.dim
        return RationalBezier(h[:, :D] / h[:, D:], h[:, D])

    def reweight(self, factor):
        """Weights ``w_i * factor**i`` (a Moebius reparameterization: the same
        point set, traced at another speed)."""
        f = as_scalar(factor, 'factor')
        if f <= 0:
            raise CurveError('factor must be positive')
        return RationalBezier(self.points, self.weights * f ** np.arange(len(self.points)))

    def transform(self, matrix, offset=None):
        c = self._chain.transform(matrix, offset)
        return RationalBezier(c.ctrl[0], self.weights)

    # -- geometry and conversion ----------------------------------------------
    def to_bezier(self):
        """The polynomial :class:`Bezier` with these control points, exact;
        only for equal weights.

        Raises
        ------
        CurveError
            The weights differ.
        """
        if not self.is_polynomial():
            raise CurveError('the weights differ: no exact polynomial Bezier form; use '
                             'to_beziers(tolerance)')
        return Bezier(self.points)

    def to_beziers(self, tolerance=None):
        return self._chain.to_beziers(tolerance)

    def continuity(self, tolerance=1e-9):
        """A single segment has no joints: ``[]``."""
        return []
