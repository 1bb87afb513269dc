r"""Bezier curves of any degree ``n >= 1`` in any dimension (2-D and 3-D in
practice), and :class:`PiecewiseBezier`, the common form every other curve
family converts to.

A Bezier curve of degree ``n`` with control points ``P_0 .. P_n`` is

.. math:: B(t) = \sum_{i=0}^{n} B_{n,i}(t) P_i, \qquad
          B_{n,i}(t) = \binom{n}{i} t^i (1-t)^{n-i}, \quad t \in [0, 1].

Coordinates follow raster's conventions (x right, y down); control points are
``(n+1, D)`` float64 arrays.  Every method accepts a scalar ``t`` (returning
one point, shape ``(D,)``) or an array of ``M`` values (returning ``(M, D)``).

>>> b = Bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
>>> b.eval(0.5).tolist()
[2.0, 1.5]
>>> b.eval([0, 1]).tolist()
[[0.0, 0.0], [4.0, 0.0]]
>>> b.deriv().eval(0.0).tolist()    # end tangent n (P1 - P0)
[3.0, 6.0]
"""

import numpy as np

from ..errors import LimitError
from ..geometry import bezier as kb
from ..geometry.flattening import flatten_beziers
from ..geometry.hull import convex_hull
from ..geometry.pens import PathBuilder
from .base import CurveMixin
from .checks import MAX_DEGREE, CurveError, as_degree, as_params, as_points, as_scalar, shape_out
from .continuity import continuity as _continuity

__all__ = ['Bezier', 'PiecewiseBezier', 'bernstein', 'bernstein_matrix', 'MAX_DEGREE',
           'MAX_ARC_INTERVALS']

# Gauss-Legendre nodes and weights on [0, 1] (16 points) for arc lengths.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)
_GL_X = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W

#: Most parameter intervals an arc-length computation may keep active.
MAX_ARC_INTERVALS = 1 << 22


def bernstein(n, t):
    """Bernstein blending functions ``B(n, i)(t)`` for many ``t`` at once
    (:func:`raster.geometry.bezier.bernstein`, with the toolkit's degree
    limit).

    Parameters
    ----------
    n : int
        Degree, ``0 <= n <= MAX_DEGREE``.
    t : float or (M,) array_like of float

    Returns
    -------
    (n+1,) or (M, n+1) float64 ndarray
        Row ``m`` holds ``B(n, 0)(t_m) .. B(n, n)(t_m)``; rows sum to 1.

    >>> bernstein(2, 0.5).tolist()
    [0.25, 0.5, 0.25]
    >>> bernstein(3, [0.0, 1.0]).tolist()
    [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
    """
    return kb.bernstein(as_degree(n), t)


def bernstein_matrix(n):
    """The ``(n+1, n+1)`` matrix ``M`` with ``B(n, i)(t) = sum_k M[k, i] t^k``:
    power-basis coefficients of the Bernstein polynomials
    (:func:`raster.geometry.bezier.bernstein_matrix`).

    >>> bernstein_matrix(2).tolist()
    [[1.0, 0.0, 0.0], [-2.0, 2.0, 0.0], [1.0, -2.0, 1.0]]
    """
    return kb.bernstein_matrix(as_degree(n))


class Bezier(CurveMixin):
    """A Bezier curve of degree ``n`` (``n + 1`` control points) on
    ``t in [0, 1]``.

    Parameters
    ----------
    ctrl : (n+1, D) array_like of float
        Control points, finite; ``D >= 1`` (2 or 3 for drawing).  A single
        control point (degree 0, a constant) is allowed: it is the hodograph
        of a line.

    Raises
    ------
    CurveError
        For non-finite or badly shaped control points.
    """

    __slots__ = ('ctrl',)
    domain = (0.0, 1.0)

    def __init__(self, ctrl):
        c = as_points(ctrl, 1, dims=None)
        as_degree(len(c) - 1)
        c.flags.writeable = False
        object.__setattr__(self, 'ctrl', c)

    def __setattr__(self, name, value):
        raise AttributeError('Bezier is immutable')

    def __reduce__(self):
        # pickled and copied as its control points
        return (type(self), (self.ctrl,))

    def __repr__(self):
        return 'Bezier(%s)' % np.array2string(self.ctrl, separator=', ').replace('\n', '')

    def __eq__(self, other):
        return isinstance(other, Bezier) and np.array_equal(self.ctrl, other.ctrl)

    __hash__ = None

    @property
    def degree(self):
        """Degree n."""
        return len(self.ctrl) - 1

    @property
    def dim(self):
        """Dimension D."""
        return self.ctrl.shape[1]

    @property
    def points(self):
        return self.ctrl

    def control_points(self):
        """(n+1, D) float64 copy of the control points."""
        return self.ctrl.copy()

    # -- evaluation ----------------------------------------------------------
    def eval(self, t):
        """Point(s) by the Bernstein blending functions.

        Parameters
        ----------
        t : float or (M,) array_like of float in [0, 1]

        Returns
        -------
        (D,) or (M, D) float64 ndarray
        """
        ta, scalar = as_params(t, 0.0, 1.0)
        out = kb.bernstein(self.degree, ta) @ self.ctrl
        out[ta == 0.0] = self.ctrl[0]
        out[ta == 1.0] = self.ctrl[-1]
        return shape_out(out, scalar)

    __call__ = eval

    def eval_casteljau(self, t):
        """Point(s) by de Casteljau's algorithm (repeated linear
        interpolation); same shapes as :meth:`eval`.

        >>> Bezier([[0, 0], [2, 2], [4, 0]]).eval_casteljau(0.25).tolist()
        [1.0, 0.75]
        """
        ta, scalar = as_params(t, 0.0, 1.0)
        return shape_out(kb.evaluate(self.ctrl, ta), scalar)

    def blending(self, t):
        """Blending function values ``B(n, i)(t)``: (n+1,) or (M, n+1)."""
        ta, scalar = as_params(t, 0.0, 1.0)
        return shape_out(kb.bernstein(self.degree, ta), scalar)

    def power_coeffs(self):
        """Power-basis coefficients: (n+1, D) float64, row ``k`` multiplies
        ``t**k`` (so column ``d`` gives ``x(t)``, ``y(t)``, ...).

        >>> Bezier([[0, 0], [1, 2], [2, 0]]).power_coeffs().tolist()
        [[0.0, 0.0], [2.0, 4.0], [0.0, -4.0]]
        """
        return kb.power_coeffs(self.ctrl)

    # -- derivatives ---------------------------------------------------------
    def deriv(self, order=1):
        """The ``order``-th derivative curve (hodograph), a Bezier of degree
        ``max(n - order, 0)``; beyond the degree it is the zero constant."""
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            raise CurveError('derivative order must be a non-negative integer')
        c = self.ctrl
        for _ in range(int(order)):
            c = kb.derivative(c)
        return Bezier(c)

    def tangent(self, t):
        """First derivative B'(t): (D,) or (M, D) float64."""
        return self.deriv().eval(t)

    # -- subdivision ---------------------------------------------------------
    def split(self, t=0.5):
        """The two halves ``[0, t]`` and ``[t, 1]`` (de Casteljau)."""
        t = as_scalar(t, 't', 0.0, 1.0)
        left, right = kb.split(self.ctrl, t)
        return Bezier(left), Bezier(right)

    def subsegment(self, t0, t1):
        """The piece from ``t0`` to ``t1`` reparameterized to [0, 1]
        (``t0 > t1`` gives it reversed).

        >>> Bezier([[0, 0], [3, 3], [6, 0]]).subsegment(0, 0.5).ctrl.tolist()
        [[0.0, 0.0], [1.5, 1.5], [3.0, 1.5]]
        """
        t0 = as_scalar(t0, 't0', 0.0, 1.0)
        t1 = as_scalar(t1, 't1', 0.0, 1.0)
        return Bezier(kb.subsegment(self.ctrl, t0, t1))

    def reverse(self):
        """Same curve traversed backwards: ``r(t) = B(1 - t)``."""
        return Bezier(self.ctrl[::-1])

    def elevate(self, times=1):
        """Same curve as a Bezier of degree ``n + times`` (exact)."""
        if isinstance(times, bool) or not isinstance(times, (int, np.integer)) or times < 0:
            raise CurveError('elevation count must be a non-negative integer')
        as_degree(self.degree + int(times))
        return Bezier(kb.elevate(self.ctrl, int(times)))

    def transform(self, matrix, offset=None):
        """Apply ``p -> matrix @ p + offset`` to the control points (Bezier
        curves are affine invariant, so this transforms the curve)."""
        m = np.asarray(matrix, dtype=np.float64)
        c = self.ctrl @ m.T
        if offset is not None:
            c = c + np.asarray(offset, dtype=np.float64)
        return Bezier(c)

    # -- geometry ------------------------------------------------------------
    def hull(self):
        """Convex hull of the (x, y) control points, (H, 2) float64
        (:func:`raster.geometry.hull.convex_hull`)."""
        return convex_hull(self.ctrl[:, :2])

    def to_beziers(self):
        """This curve as a one-segment :class:`PiecewiseBezier`."""
        return PiecewiseBezier(self.ctrl[None])

    def arc_length(self, tolerance=1e-9):
        """Arc length, estimated to an absolute ``tolerance`` (adaptive
        16-point Gauss-Legendre; the estimate compares each interval with its
        two halves)."""
        return self.to_beziers().arc_length(tolerance)

    # flatten, to_path, to_svg, draw, extrema and bounding_box come from
    # CurveMixin, through to_beziers()

    def continuity(self, tolerance=1e-9):
        """A single segment has no joints: ``[]``."""
        return []


class PiecewiseBezier(CurveMixin):
    """A chain of ``S`` Bezier segments of one degree ``n``, segment ``s``
    covering the global parameter interval ``[breaks[s], breaks[s+1]]``.

    Parameters
    ----------
    ctrl : (S, n+1, D) array_like of float
        Control points of every segment.
    breaks : (S+1,) array_like of float, optional
        Strictly increasing parameter values of the joints; default
        ``0, 1, ..., S``.

    Iterating yields :class:`Bezier` objects, so a PiecewiseBezier is also
    "a list of Beziers".

    >>> pb = PiecewiseBezier([[[0, 0], [1, 1]], [[1, 1], [2, 0]]])
    >>> pb.eval(1.5).tolist(), len(pb), pb.domain
    ([1.5, 0.5], 2, (0.0, 2.0))
    """

    __slots__ = ('ctrl', 'breaks')

    def __init__(self, ctrl, breaks=None):
        try:
            c = np.array(ctrl, dtype=np.float64)
        except (TypeError, ValueError):
            raise CurveError('Bezier control points must be numbers') from None
        if c.ndim != 3 or c.shape[0] < 1 or c.shape[1] < 1 or c.shape[2] < 1:
            raise CurveError('piecewise Bezier control points must be (S, n+1, D), got %s'
                             % (c.shape,))
        if not np.all(np.isfinite(c)):
            raise CurveError('Bezier control points must be finite')
        as_degree(c.shape[1] - 1)
        if breaks is None:
            b = np.arange(c.shape[0] + 1, dtype=np.float64)
        else:
            b = np.array(breaks, dtype=np.float64).reshape(-1)
            if b.shape != (c.shape[0] + 1,):
                raise CurveError('need %d breaks, got %d' % (c.shape[0] + 1, b.size))
            if not np.all(np.isfinite(b)) or np.any(np.diff(b) <= 0):
                raise CurveError('breaks must be finite and strictly increasing')
        c.flags.writeable = False
        b.flags.writeable = False
        object.__setattr__(self, 'ctrl', c)
        object.__setattr__(self, 'breaks', b)

    def __setattr__(self, name, value):
        raise AttributeError('PiecewiseBezier is immutable')

    def __reduce__(self):
        # pickled and copied as its control points and breaks
        return (type(self), (self.ctrl, self.breaks))

    def __repr__(self):
        return 'PiecewiseBezier(%d segments, degree %d, D=%d)' % (len(self), self.degree, self.dim)

    @classmethod
    def concat(cls, beziers, breaks=None):
        """Join Beziers (or control arrays) into one chain; lower degrees are
        elevated to the highest one."""
        cs = [b.ctrl if isinstance(b, Bezier) else as_points(b, 1, dims=None) for b in beziers]
        if not cs:
            raise CurveError('need at least one Bezier segment')
        n = max(len(c) for c in cs) - 1
        out = [kb.elevate(c, n - (len(c) - 1)) for c in cs]
        return cls(np.stack(out), breaks)

    # -- container -----------------------------------------------------------
    def __len__(self):
        return self.ctrl.shape[0]

    def __getitem__(self, i):
        return Bezier(self.ctrl[i])

    def __iter__(self):
        return (Bezier(c) for c in self.ctrl)

    @property
    def degree(self):
        return self.ctrl.shape[1] - 1

    @property
    def dim(self):
        return self.ctrl.shape[2]

    @property
    def domain(self):
        return (float(self.breaks[0]), float(self.breaks[-1]))

    @property
    def points(self):
        """All control points, (S * (n+1), D)."""
        return self.ctrl.reshape(-1, self.dim)

    def to_beziers(self):
        return self

    def _locate(self, t):
        ta, scalar = as_params(t, *self.domain)
        idx = np.searchsorted(self.breaks, ta, side='right') - 1
        idx = np.clip(idx, 0, len(self) - 1)
        h = self.breaks[idx + 1] - self.breaks[idx]
        u = np.clip((ta - self.breaks[idx]) / h, 0.0, 1.0)
        return idx, u, scalar

    # -- evaluation ----------------------------------------------------------
    def eval(self, t):
        """Point(s) at global parameter(s) ``t``: (D,) or (M, D) float64.
        At a joint the later segment is used."""
        idx, u, scalar = self._locate(t)
        out = np.einsum('mi,mid->md', kb.bernstein(self.degree, u), self.ctrl[idx])
        return shape_out(out, scalar)

    __call__ = eval

    def deriv(self, order=1):
        """Derivative with respect to the global parameter (chain rule:
        segment hodographs divided by the interval length)."""
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            raise CurveError('derivative order must be a non-negative integer')
        c = self.ctrl
        h = np.diff(self.breaks)[:, None, None]
        for _ in range(int(order)):
            c = kb.derivative(c) / h if c.shape[1] > 1 else np.zeros_like(c)
        return PiecewiseBezier(c, self.breaks)

    def tangent(self, t):
        return self.deriv().eval(t)

    # -- pieces --------------------------------------------------------------
    def subsegment(self, t0, t1):
        """The part with ``t0 <= t <= t1`` (``t0 < t1``) keeping the global
        parameterization."""
        lo, hi = self.domain
        t0 = as_scalar(t0, 't0', lo, hi)
        t1 = as_scalar(t1, 't1', lo, hi)
        if not t0 < t1:
            raise CurveError('subsegment needs t0 < t1')
        b = self.breaks
        first = int(np.clip(np.searchsorted(b, t0, side='right') - 1, 0, len(self) - 1))
        last = int(np.clip(np.searchsorted(b, t1, side='left') - 1, 0, len(self) - 1))
        segs = np.arange(first, last + 1)
        h = b[segs + 1] - b[segs]
        u0 = np.clip((np.maximum(b[segs], t0) - b[segs]) / h, 0.0, 1.0)
        u1 = np.clip((np.minimum(b[segs + 1], t1) - b[segs]) / h, 0.0, 1.0)
        c = kb.subsegment(self.ctrl[segs], u0, u1)
        nb = np.concatenate([[t0], b[segs[1:]], [t1]])
        return PiecewiseBezier(c, nb)

    def reverse(self):
        """The chain traversed backwards, on the parameter range negated and
        shifted so that it is ``[lo, hi]`` again."""
        lo, hi = self.domain
        return PiecewiseBezier(self.ctrl[::-1, ::-1], (lo + hi) - self.breaks[::-1])

    def elevate(self, times=1):
        if isinstance(times, bool) or not isinstance(times, (int, np.integer)) or times < 0:
            raise CurveError('elevation count must be a non-negative integer')
        as_degree(self.degree + int(times))
        return PiecewiseBezier(kb.elevate(self.ctrl, int(times)), self.breaks)

    # -- geometry ------------------------------------------------------------
    def extrema(self):
        """Sorted global parameters inside segments where some coordinate of
        the curve has a zero derivative, (K,) float64
        (:func:`raster.geometry.bezier.extrema` of every segment)."""
        if self.degree < 2:
            return np.zeros(0)
        u = kb.extrema(self.ctrl)                               # (S, D, n-1)
        seg = np.broadcast_to(np.arange(len(self))[:, None, None], u.shape)
        ok = ~np.isnan(u)
        s, r = seg[ok], u[ok]
        t = self.breaks[s] + r * (self.breaks[s + 1] - self.breaks[s])
        return np.unique(t)

    def bounding_box(self):
        """Exact bounding box ``(lo, hi)``: (D,) float64 each
        (:func:`raster.geometry.bezier.bounds` of every segment)."""
        lo, hi = kb.bounds(self.ctrl)
        return lo.min(axis=0), hi.max(axis=0)

    def arc_length(self, tolerance=1e-9):
        """Total arc length to an absolute ``tolerance`` (adaptive
        Gauss-Legendre over all segments at once).

        An interval is accepted when its 16-point estimate and the sum of
        its halves' estimates differ by at most its share of ``tolerance``
        (or by rounding, ``4e-14`` relative), so the result is within
        ``tolerance`` plus rounding of the true length for smooth
        integrands (cusps converge more slowly but are subdivided until the
        criterion holds, at most 40 levels).  Tolerances below ``1e-14``
        times the length are raised to that floor.

        Raises
        ------
        CurveError
            Non-positive tolerance.
        LimitError
            More than :data:`MAX_ARC_INTERVALS` intervals would be needed."""
        tol = as_scalar(tolerance, 'tolerance', 0.0)
        if tol <= 0:
            raise CurveError('tolerance must be positive')
        if self.degree == 0:
            return 0.0
        dc = kb.derivative(self.ctrl)
        n1 = self.degree - 1
        pcoef = kb.power_coeffs(dc) if n1 <= 8 else None

        def gl(seg, a, b):
            u = a[:, None] + (b - a)[:, None] * _GL_X[None, :]         # (K, 16)
            if pcoef is not None:                                       # Horner
                c = pcoef[seg]
                v = np.repeat(c[:, n1][:, None, :], u.shape[1], axis=1)
                for k in range(n1 - 1, -1, -1):
                    v *= u[:, :, None]
                    v += c[:, k][:, None, :]
            else:
                B = kb.bernstein(n1, u.reshape(-1)).reshape(u.shape + (n1 + 1,))
                v = np.einsum('kgi,kid->kgd', B, dc[seg])
            speed = np.sqrt(np.einsum('kgd,kgd->kg', v, v))
            return (speed @ _GL_W) * (b - a)

        seg = np.arange(len(self))
        a = np.zeros(len(self))
        b = np.ones(len(self))
        whole = gl(seg, a, b)
        # tolerances below the float resolution of the length are raised to it
        tol = max(tol, 1e-14 * float(whole.sum()))
        total = 0.0
        for level in range(40):
            m = 0.5 * (a + b)
            left, right = gl(seg, a, m), gl(seg, m, b)
            halves = left + right
            # budget: tol shared by parameter length; floor: rounding of the sum
            ok = np.abs(halves - whole) <= np.maximum(tol * (b - a) / len(self) * 0.5,
                                                      4e-14 * np.abs(halves))
            if level == 39:
                ok[:] = True
            total += float(halves[ok].sum())
            bad = ~ok
            if not bad.any():
                break
            if 2 * int(bad.sum()) > MAX_ARC_INTERVALS:
                raise LimitError('arc length needs more than %d intervals; use a larger '
                                 'tolerance' % MAX_ARC_INTERVALS)
            seg = np.concatenate([seg[bad], seg[bad]])
            a, b = np.concatenate([a[bad], m[bad]]), np.concatenate([m[bad], b[bad]])
            whole = np.concatenate([left[bad], right[bad]])
        return total

    def to_cubics(self, tolerance=0.25):
        """(K, 4, D) cubic control points within ``tolerance`` of the curve.

        Degrees <= 3 are converted exactly (elevation).  Higher degrees are
        split adaptively; each piece is replaced by the cubic with the same
        end points and end derivatives, accepted when the exact error bound
        ``max_i |P_i - E_i|`` (``E``: the cubic elevated to degree n; the
        difference of two Bezier curves lies in the hull of the differences
        of their control points) is at most ``tolerance``.
        """
        tol = as_scalar(tolerance, 'tolerance', 0.0)
        if tol <= 0:
            raise CurveError('tolerance must be positive')
        n = self.degree
        if n <= 3:
            return kb.elevate(self.ctrl, 3 - n)
        seg = np.arange(len(self))
        u0, u1 = np.zeros(len(self)), np.ones(len(self))
        done_seg, done_u, done_c = [], [], []
        for level in range(48):
            piece = kb.subsegment(self.ctrl[seg], u0, u1)
            cub = np.empty(piece.shape[:1] + (4,) + piece.shape[2:])
            cub[:, 0], cub[:, 3] = piece[:, 0], piece[:, -1]
            cub[:, 1] = piece[:, 0] + (n / 3.0) * (piece[:, 1] - piece[:, 0])
            cub[:, 2] = piece[:, -1] - (n / 3.0) * (piece[:, -1] - piece[:, -2])
            err = np.linalg.norm(piece - kb.elevate(cub, n - 3), axis=2).max(axis=1)
            ok = err <= tol
            if level == 47:
                ok[:] = True
            done_seg.append(seg[ok]); done_u.append(u0[ok]); done_c.append(cub[ok])
            bad = ~ok
            if not bad.any():
                break
            m = 0.5 * (u0[bad] + u1[bad])
            seg = np.concatenate([seg[bad], seg[bad]])
            u0, u1 = np.concatenate([u0[bad], m]), np.concatenate([m, u1[bad]])
        s, u, c = np.concatenate(done_seg), np.concatenate(done_u), np.concatenate(done_c)
        order = np.lexsort((u, s))
        return c[order]

    def flatten(self, tolerance=0.25):
        """Polyline through the curve within ``tolerance`` (device units):
        (K, D) float64, first and last points exact (via
        :func:`raster.geometry.flattening.flatten_beziers`)."""
        tol = as_scalar(tolerance, 'tolerance', 0.0)
        if tol <= 0:
            raise CurveError('tolerance must be positive')
        if self.degree == 0:
            return self.ctrl[:, 0].copy()
        pts, counts = flatten_beziers(self.ctrl, tol)
        pts = np.asarray(pts)
        counts = np.asarray(counts)
        # drop each segment's first point except the very first (joints repeat)
        starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
        keep = np.ones(len(pts), bool)
        keep[starts[1:]] = False
        return pts[keep]

    def to_path(self, tolerance=0.25):
        """A :class:`raster.geometry.path.Path` of the (x, y) projection: one contour
        of lines, quadratics or cubics for degrees 1-3 (exact); higher
        degrees as cubics within ``tolerance`` (see :meth:`to_cubics`)."""
        b = PathBuilder()
        self.draw(b, tolerance)
        return b.path()

    def draw(self, pen, tolerance=0.25):
        """Replay the (x, y) projection into a pen as one open contour.
        Segment starts that do not meet the previous end begin a new
        contour."""
        if self.dim < 2:
            raise CurveError('drawing needs a curve of dimension >= 2')
        n = self.degree
        c = self.ctrl[:, :, :2] if n <= 3 else self.to_cubics(tolerance)[:, :, :2]
        if n > 3:
            n = 3
        pen.moveTo(tuple(c[0, 0].tolist()))
        cur = c[0, 0]
        for seg in c.tolist():
            if seg[0] != list(cur):
                pen.endPath()
                pen.moveTo(tuple(seg[0]))
            if n == 0:
                pass
            elif n == 1:
                pen.lineTo(tuple(seg[1]))
            elif n == 2:
                pen.qCurveTo(tuple(seg[1]), tuple(seg[2]))
            else:
                pen.curveTo(tuple(seg[1]), tuple(seg[2]), tuple(seg[3]))
            cur = np.array(seg[-1])
        pen.endPath()

    def continuity(self, tolerance=1e-9):
        """Continuity at each joint; see :func:`raster.curves.continuity.continuity`."""
        return _continuity(self, tolerance)
