r"""Surfaces: tensor-product Bezier patches, B-spline and NURBS surfaces of
any degree, bicubic Hermite patches and Coons patches.

A tensor-product surface maps ``(u, v)`` to

.. math:: S(u, v) = \frac{\sum_i \sum_j F_i(u) G_j(v) w_{ij} P_{ij}}
                         {\sum_i \sum_j F_i(u) G_j(v) w_{ij}}

with a control net ``P[i, j]`` (``i`` along ``u``, ``j`` along ``v``),
weights ``w`` (all 1 unless rational) and blending functions ``F, G``:
Bernstein polynomials for Bezier patches, B-spline basis functions for
B-spline and NURBS surfaces.  Bezier patches are evaluated by
:mod:`raster.geometry.patches` (the one patch code path, shared with mesh
gradients); spline surfaces by their basis functions.  Rational surfaces use
the homogeneous net ``(w P, w)`` and Leibniz's rule for derivatives.

Every surface has ``eval(u, v)``, ``partial(u, v, du, dv)``,
``derivatives(u, v, order)``, ``normal(u, v)``, ``eval_grid(us, vs)``,
``isocurve(u=... | v=...)``, ``transform(matrix, offset)``,
``control_net()`` and ``domain`` (``((u0, u1), (v0, v1))``); spline
surfaces add ``insert_knot`` and ``to_bezier_patches``.

Parameters ``u, v`` are scalars (one point, shape ``(D,)``) or equal-length
arrays (``(M, D)``).  Nets are ``(Nu, Nv, D)`` float64 arrays; surfaces are
usually 3-D (normals need ``D = 3``).

>>> s = BezierSurface([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]])   # bilinear
>>> s.eval(0.5, 0.5).tolist()
[0.5, 0.5, 0.25]
>>> np.round(s.normal(0, 0), 12).tolist()
[0.0, 0.0, 1.0]
"""

import math
from typing import Optional

import numpy as np
from numpy.typing import ArrayLike

from ..geometry import patches
from .checks import MAX_CURVE_POINTS, CurveError, as_points, as_scalar
from .bezier import Bezier
from .bspline import BSpline, basis_functions, knot_spans
from .nurbs import NURBS
from .rational import RationalBezier, check_weights

__all__ = ['BezierSurface', 'RationalBezierSurface', 'BSplineSurface', 'NURBSSurface',
           'HermitePatch', 'CoonsPatch', 'basis_derivatives', 'as_net']


def as_net(net: ArrayLike, min_u: int = 1, min_v: int = 1,
           name: str = 'control net') -> np.ndarray:
    """Validate a control net: (Nu, Nv, D) float64 copy, finite, D >= 1."""
    try:
        a = np.array(net, dtype=np.float64)
    except (TypeError, ValueError):
        raise CurveError('%s must be numbers (rows of points of equal length)' % name) from None
    if a.ndim != 3 or a.shape[2] < 1:
        raise CurveError('%s must have shape (Nu, Nv, D), got %s' % (name, a.shape))
    if a.shape[0] < min_u or a.shape[1] < min_v:
        raise CurveError('%s needs at least %d x %d points, got %d x %d'
                         % (name, min_u, min_v, a.shape[0], a.shape[1]))
    as_points(a.reshape(-1, a.shape[2]), 1, name, dims=None)
    return a


def _uv(u, v):
    try:
        ua = np.asarray(u, dtype=np.float64)
        va = np.asarray(v, dtype=np.float64)
    except (TypeError, ValueError):
        raise CurveError('u and v must be numbers') from None
    scalar = ua.ndim == 0 and va.ndim == 0
    try:
        ua, va = np.broadcast_arrays(ua.reshape(-1), va.reshape(-1))
    except ValueError:
        raise CurveError('u and v must have the same length') from None
    if ua.size > MAX_CURVE_POINTS:
        raise CurveError('too many (u, v) values (%d)' % ua.size)
    if not (np.all(np.isfinite(ua)) and np.all(np.isfinite(va))):
        raise CurveError('u and v must be finite')
    return ua.astype(np.float64), va.astype(np.float64), scalar


def _clip(a, lo, hi, name):
    eps = 1e-12 * max(1.0, abs(lo), abs(hi))
    if a.size and (a.min() < lo - eps or a.max() > hi + eps):
        bad = a[(a < lo - eps) | (a > hi + eps)][0]
        raise CurveError('%s=%g is outside the domain [%g, %g]' % (name, bad, lo, hi))
    return np.clip(a, lo, hi)


def _pair(value, name):
    if isinstance(value, (list, tuple)) and len(value) == 2:
        return value[0], value[1]
    return value, value


def basis_derivatives(knots: ArrayLike, degree: int, t: ArrayLike, order: int = 0,
                      span: Optional[np.ndarray] = None) -> np.ndarray:
    """Derivatives of the B-spline basis functions.

    ``N'_{i,p} = p / (u_{i+p} - u_i) N_{i,p-1} - p / (u_{i+p+1} - u_{i+1})
    N_{i+1,p-1}`` (terms with an empty denominator dropped), applied
    ``order`` times.

    Parameters
    ----------
    knots : (K,) array_like of float
    degree : int
    t : (M,) array_like of float
        Inside the domain ``[knots[p], knots[K-p-1]]``.
    order : int
        Derivative order (0: the functions themselves).
    span : (M,) int ndarray, optional
        Knot spans of ``t`` (as :meth:`BSpline.span`); computed if omitted.

    Returns
    -------
    (M, K - degree - 1) float64 ndarray

    >>> basis_derivatives([0, 0, 0, 1, 1, 1], 2, [0.5], 1).tolist()    # B'_{2,i}(0.5)
    [[-1.0, 0.0, 1.0]]
    """
    u = np.asarray(knots, dtype=np.float64)
    p = int(degree)
    ta = np.asarray(t, dtype=np.float64).reshape(-1)
    N = len(u) - p - 1
    if span is None:
        span = knot_spans(u, p, ta)
    k = int(order)
    if k == 0:
        return basis_functions(u, p, ta, span)
    if k > p:
        return np.zeros((len(ta), N))
    lower = basis_derivatives(u, p - 1, ta, k - 1, span)          # (M, N + 1)
    i = np.arange(N)
    d1 = u[i + p] - u[i]
    d2 = u[i + p + 1] - u[i + 1]
    with np.errstate(divide='ignore', invalid='ignore'):
        a = np.where(d1 > 0, p / d1, 0.0)
        b = np.where(d2 > 0, p / d2, 0.0)
    return a * lower[:, :N] - b * lower[:, 1:N + 1]


class _Surface:
    """Shared surface vocabulary over ``_hom`` (homogeneous partials at
    points) and ``_hom_grid`` (on a grid)."""

    rational = False

    @property
    def dim(self):
        return self.net.shape[2]

    def control_net(self):
        """(Nu, Nv, D) float64 copy of the control points."""
        return self.net.copy()

    def _check(self, u, v):
        ua, va, scalar = _uv(u, v)
        (u0, u1), (v0, v1) = self.domain
        return _clip(ua, u0, u1, 'u'), _clip(va, v0, v1, 'v'), scalar

    def derivatives(self, u, v, order=1):
        """All partial derivatives up to total order ``order``.

        Returns
        -------
        (order+1, order+1, D) or (M, order+1, order+1, D) float64 ndarray
            ``out[..., k, l, :] = d^(k+l) S / du^k dv^l`` (entries with
            ``k + l > order`` are also filled).
        """
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            raise CurveError('derivative order must be a non-negative integer')
        ua, va, scalar = self._check(u, v)
        K = int(order) + 1
        D = self.dim
        H = [[self._hom(ua, va, k, l) for l in range(K)] for k in range(K)]
        out = np.empty((len(ua), K, K, D))
        for k in range(K):
            for l in range(K):
                acc = H[k][l][:, :D].copy()
                for i in range(k + 1):
                    for j in range(l + 1):
                        if i == 0 and j == 0:
                            continue
                        acc -= (math.comb(k, i) * math.comb(l, j)
                                * H[i][j][:, D][:, None] * out[:, k - i, l - j])
                out[:, k, l] = acc / H[0][0][:, D][:, None]
        return out[0] if scalar else out

    def eval(self, u, v):
        """Point(s): (D,) or (M, D) float64."""
        ua, va, scalar = self._check(u, v)
        h = self._hom(ua, va, 0, 0)
        D = self.dim
        out = h[:, :D] / h[:, D:]
        return out[0] if scalar else out

    __call__ = eval

    def partial(self, u, v, du=1, dv=0):
        """The partial derivative ``d^(du+dv) S / du^du dv^dv``: (D,) or
        (M, D)."""
        for x in (du, dv):
            if isinstance(x, bool) or not isinstance(x, (int, np.integer)) or x < 0:
                raise CurveError('derivative orders must be non-negative integers')
        if not self.rational:
            ua, va, scalar = self._check(u, v)
            out = self._hom(ua, va, int(du), int(dv))[:, :self.dim]
            return out[0] if scalar else out
        d = self.derivatives(u, v, max(int(du), int(dv)))
        return d[..., int(du), int(dv), :]

    def normal(self, u, v):
        """Unit normal(s) ``S_u x S_v / |S_u x S_v|``: (3,) or (M, 3).

        Where ``S_u x S_v`` vanishes (a collapsed edge, a pole) the normal is
        the direction of its first non-zero derivative along the line towards
        the middle of the domain (the limit of the normal from inside); if
        that vanishes too the result is ``nan``.

        Raises
        ------
        CurveError
            The surface is not 3-D.
        """
        if self.dim != 3:
            raise CurveError('normals need a 3-D surface, got D=%d' % self.dim)
        ua, va, scalar = self._check(u, v)
        d = self.derivatives(ua, va, 2)
        su, sv = d[:, 1, 0], d[:, 0, 1]
        n = np.cross(su, sv)
        size = np.linalg.norm(n, axis=1)
        scale = np.maximum(np.linalg.norm(su, axis=1) * np.linalg.norm(sv, axis=1), 1e-300)
        bad = size <= 1e-10 * np.maximum(scale, np.abs(self.net).max() ** 2)
        if bad.any():
            (u0, u1), (v0, v1) = self.domain
            a = (0.5 * (u0 + u1) - ua[bad]) / (u1 - u0)
            b = (0.5 * (v0 + v1) - va[bad]) / (v1 - v0)
            still = (a == 0) & (b == 0)
            a[still], b[still] = 1.0, 1.0
            suu, suv, svv = d[bad, 2, 0], d[bad, 1, 1], d[bad, 0, 2]
            dsu = a[:, None] * suu + b[:, None] * suv
            dsv = a[:, None] * suv + b[:, None] * svv
            n[bad] = np.cross(dsu, sv[bad]) + np.cross(su[bad], dsv)
            size[bad] = np.linalg.norm(n[bad], axis=1)
        with np.errstate(invalid='ignore', divide='ignore'):
            out = n / size[:, None]
        return out[0] if scalar else out

    def eval_grid(self, us, vs):
        """Points on the grid ``us x vs``: (A, B, D) float64."""
        (u0, u1), (v0, v1) = self.domain
        ua = _clip(np.asarray(us, dtype=np.float64).reshape(-1), u0, u1, 'u')
        va = _clip(np.asarray(vs, dtype=np.float64).reshape(-1), v0, v1, 'v')
        if len(ua) * len(va) > MAX_CURVE_POINTS:
            raise CurveError('grid of %d points is too large' % (len(ua) * len(va)))
        h = self._hom_grid(ua, va)
        D = self.dim
        return h[..., :D] / h[..., D:]

    def grid(self, nu=17, nv=17):
        """``(us, vs, points)``: uniform parameters over the domain and the
        (nu, nv, D) points."""
        (u0, u1), (v0, v1) = self.domain
        us, vs = np.linspace(u0, u1, int(nu)), np.linspace(v0, v1, int(nv))
        return us, vs, self.eval_grid(us, vs)

    def corners(self):
        """``S(u0, v0), S(u1, v0), S(u0, v1), S(u1, v1)``: (4, D)."""
        (u0, u1), (v0, v1) = self.domain
        return self.eval([u0, u1, u0, u1], [v0, v0, v1, v1])


class BezierSurface(_Surface):
    """Tensor-product Bezier patch of degree ``(m, n)`` on ``[0, 1]^2``.

    Parameters
    ----------
    net : (m+1, n+1, D) array_like of float
        Control net, ``net[i, j]`` weighted by ``B_{m,i}(u) B_{n,j}(v)``.
    """

    domain = ((0.0, 1.0), (0.0, 1.0))

    def __init__(self, net):
        c = as_net(net)
        patches.as_nets(c)          # degree limits
        self.net = c
        self._hnet = np.concatenate([c, np.ones(c.shape[:2] + (1,))], axis=2)

    def __repr__(self):
        return 'BezierSurface(degree %d x %d, D=%d)' % (self.degree + (self.dim,))

    @property
    def degree(self):
        """``(m, n)``."""
        return (self.net.shape[0] - 1, self.net.shape[1] - 1)

    def _hom(self, ua, va, k, l):
        return patches.tensor_eval(self._hnet, ua, va, k, l)[0]

    def _hom_grid(self, ua, va):
        return patches.tensor_grid(self._hnet, ua, va)[0]

    def blending(self, u, v):
        """``(Bu, Bv)``: (M, m+1) and (M, n+1) Bernstein values; the weight
        of ``P[i, j]`` is ``Bu[:, i] * Bv[:, j]``."""
        ua, va, _ = self._check(u, v)
        m, n = self.degree
        return patches.bernstein_basis(m, ua), patches.bernstein_basis(n, va)

    def isocurve(self, u=None, v=None):
        """The curve ``S(u, .)`` (give ``u``) or ``S(., v)`` (give ``v``): a
        :class:`~raster.curves.bezier.Bezier` of degree ``n`` or ``m``."""
        if (u is None) == (v is None):
            raise CurveError('give exactly one of u and v')
        m, n = self.degree
        if u is not None:
            b = patches.bernstein_basis(m, [as_scalar(u, 'u', 0.0, 1.0)])[0]
            return Bezier(np.einsum('i,ijd->jd', b, self.net))
        b = patches.bernstein_basis(n, [as_scalar(v, 'v', 0.0, 1.0)])[0]
        return Bezier(np.einsum('j,ijd->id', b, self.net))

    def boundary(self):
        """The four boundary curves ``(S(., 0), S(1, .), S(., 1), S(0, .))``
        as Beziers (each running with its parameter)."""
        c = self.net
        return Bezier(c[:, 0]), Bezier(c[-1, :]), Bezier(c[:, -1]), Bezier(c[0, :])

    def split(self, t=0.5, direction='u'):
        """The two halves at ``t`` along ``direction`` (exact), each a
        BezierSurface on [0, 1]^2."""
        a, b = patches.split_patches(self.net, as_scalar(t, 't', 0.0, 1.0), direction)
        return BezierSurface(a[0]), BezierSurface(b[0])

    def subpatch(self, u0, u1, v0, v1):
        """The part over ``[u0, u1] x [v0, v1]`` reparameterized to [0, 1]^2."""
        return BezierSurface(patches.subpatches(self.net, [u0], [u1], [v0], [v1])[0])

    def transform(self, matrix, offset=None):
        """Apply ``p -> matrix @ p + offset`` to the net (affine invariance)."""
        c = self.net @ np.asarray(matrix, dtype=np.float64).T
        if offset is not None:
            c = c + np.asarray(offset, dtype=np.float64)
        return BezierSurface(c)

    def to_bezier_patches(self):
        """``[[self]]`` (the spline vocabulary)."""
        return [[self]]


class RationalBezierSurface(_Surface):
    """Rational tensor-product Bezier patch (a NURBS surface's piece).

    Parameters
    ----------
    net : (m+1, n+1, D) array_like of float
    weights : (m+1, n+1) array_like of float
        Positive.
    domain : ((u0, u1), (v0, v1)), optional
        Parameter ranges (default the unit square); the patch is the Bezier
        patch of the affinely mapped parameters.
    """

    rational = True

    def __init__(self, net, weights, domain=((0.0, 1.0), (0.0, 1.0))):
        c = as_net(net)
        patches.as_nets(c)
        w = check_weights(weights, c.shape[:2])
        self.net, self.weights = c, w
        self._hnet = np.concatenate([c * w[..., None], w[..., None]], axis=2)
        (a, b), (e, f) = domain
        if not (b > a and f > e):
            raise CurveError('empty patch domain')
        self.domain = ((float(a), float(b)), (float(e), float(f)))

    def __repr__(self):
        m, n = self.degree
        return 'RationalBezierSurface(degree %d x %d, D=%d)' % (m, n, self.dim)

    @property
    def degree(self):
        return (self.net.shape[0] - 1, self.net.shape[1] - 1)

    def _local(self, ua, va):
        (a, b), (e, f) = self.domain
        return (ua - a) / (b - a), (va - e) / (f - e), 1.0 / (b - a), 1.0 / (f - e)

    def _hom(self, ua, va, k, l):
        s, t, fu, fv = self._local(ua, va)
        return patches.tensor_eval(self._hnet, np.clip(s, 0, 1), np.clip(t, 0, 1), k, l)[0] \
            * (fu ** k * fv ** l)

    def _hom_grid(self, ua, va):
        s, t, _, _ = self._local(ua, va)
        return patches.tensor_grid(self._hnet, np.clip(s, 0, 1), np.clip(t, 0, 1))[0]

    def isocurve(self, u=None, v=None):
        """``S(u, .)`` or ``S(., v)`` as a :class:`RationalBezier`."""
        if (u is None) == (v is None):
            raise CurveError('give exactly one of u and v')
        m, n = self.degree
        (a, b), (e, f) = self.domain
        if u is not None:
            s = (as_scalar(u, 'u', a, b) - a) / (b - a)
            h = np.einsum('i,ijd->jd', patches.bernstein_basis(m, [s])[0], self._hnet)
        else:
            s = (as_scalar(v, 'v', e, f) - e) / (f - e)
            h = np.einsum('j,ijd->id', patches.bernstein_basis(n, [s])[0], self._hnet)
        D = self.dim
        return RationalBezier(h[:, :D] / h[:, D:], h[:, D])

    def transform(self, matrix, offset=None):
        c = self.net @ np.asarray(matrix, dtype=np.float64).T
        if offset is not None:
            c = c + np.asarray(offset, dtype=np.float64)
        return RationalBezierSurface(c, self.weights, self.domain)


class NURBSSurface(_Surface):
    """A NURBS surface: rational B-spline blending in both directions.

    Parameters
    ----------
    net : (Nu, Nv, D) array_like of float
        Control net.
    degree : int or (int, int)
        ``(p, q)``: degrees in ``u`` and ``v``; default 3 (cubic both ways).
    knots : pair of (array_like or None), optional
        Knot vectors in ``u`` (``Nu + p + 1`` values) and ``v`` (``Nv + q +
        1``); ``None`` gives the clamped uniform vector on [0, 1].
    weights : (Nu, Nv) array_like of float, optional
        Positive weights; default all 1 (a B-spline surface).

    Raises
    ------
    CurveError
        Too few points for a degree, bad knots or weights.
    """

    def __init__(self, net, degree=3, knots=(None, None), weights=None):
        c = as_net(net)
        Nu, Nv, D = c.shape
        p, q = _pair(degree, 'degree')
        if knots is None:
            knots = (None, None)
        if not isinstance(knots, (list, tuple)) or len(knots) != 2:
            raise CurveError('knots must be a pair (u knots, v knots)')
        w = check_weights(1.0 if weights is None else weights, (Nu, Nv))
        # validate degrees and knots as the curve class does, direction by direction
        bu = BSpline(np.zeros((Nu, 1)), p, knots[0])
        bv = BSpline(np.zeros((Nv, 1)), q, knots[1])
        self._set(c, w, bu.degree, bv.degree, bu.knots, bv.knots)
        self.rational = weights is not None and bool(w.max() - w.min() > 0)

    def _set(self, c, w, p, q, ku, kv):
        self.net, self.weights = c, w
        self.degree = (p, q)
        self.knots = (ku, kv)
        self._hnet = np.concatenate([c * w[..., None], w[..., None]], axis=2)
        self.domain = ((float(ku[p]), float(ku[c.shape[0]])), (float(kv[q]), float(kv[c.shape[1]])))

    @classmethod
    def _raw(cls, hnet, p, q, ku, kv, rational):
        obj = cls.__new__(cls)
        w = hnet[..., -1]
        if np.any(w <= 0):
            raise CurveError('homogeneous weights must be positive')
        obj._set(hnet[..., :-1] / w[..., None], w, p, q, ku, kv)
        obj.rational = rational
        return obj

    def __repr__(self):
        return '%s(%d x %d points, degree %d x %d)' % (
            type(self).__name__, self.net.shape[0], self.net.shape[1], *self.degree)

    def _spans(self, t, direction):
        return knot_spans(self.knots[direction], self.degree[direction], t)

    def basis(self, direction, t, order=0):
        """B-spline basis functions (or derivatives) in ``direction`` (0: u,
        1: v) at ``t``: (M, N_direction) float64."""
        ta = np.asarray(t, dtype=np.float64).reshape(-1)
        return basis_derivatives(self.knots[direction], self.degree[direction], ta, order,
                                 self._spans(ta, direction))

    def _hom(self, ua, va, k, l):
        return np.einsum('mi,mj,ijd->md', self.basis(0, ua, k), self.basis(1, va, l), self._hnet)

    def _hom_grid(self, ua, va):
        return np.einsum('ai,bj,ijd->abd', self.basis(0, ua), self.basis(1, va), self._hnet)

    def _flat_spline(self, direction):
        """The homogeneous net as a B-spline curve in ``direction`` whose
        control points are whole rows (or columns) of the net."""
        h = np.moveaxis(self._hnet, direction, 0)
        return BSpline(h.reshape(h.shape[0], -1), self.degree[direction],
                       self.knots[direction]), h.shape

    def isocurve(self, u=None, v=None):
        """``S(u, .)`` (give ``u``) or ``S(., v)`` (give ``v``): a
        :class:`~raster.curves.nurbs.NURBS` (a :class:`BSpline` when the
        surface is not rational), exact."""
        if (u is None) == (v is None):
            raise CurveError('give exactly one of u and v')
        (u0, u1), (v0, v1) = self.domain
        if u is not None:
            b = self.basis(0, [as_scalar(u, 'u', u0, u1)])[0]
            h = np.einsum('i,ijd->jd', b, self._hnet)
            deg, kn = self.degree[1], self.knots[1]
        else:
            b = self.basis(1, [as_scalar(v, 'v', v0, v1)])[0]
            h = np.einsum('j,ijd->id', b, self._hnet)
            deg, kn = self.degree[0], self.knots[0]
        D = self.dim
        pts, w = h[:, :D] / h[:, D:], h[:, D]
        if not self.rational:
            return BSpline(pts, deg, kn)
        return NURBS(pts, w, deg, kn)

    def insert_knot(self, direction, t, times=1):
        """The same surface with knot ``t`` inserted ``times`` times in
        ``direction`` (``'u'``/0 or ``'v'``/1): Boehm's algorithm applied to
        every row (column) of the homogeneous net at once."""
        d = {'u': 0, 'v': 1, 0: 0, 1: 1}.get(direction)
        if d is None:
            raise CurveError("direction must be 'u' or 'v', got %r" % (direction,))
        spl, shape = self._flat_spline(d)
        new = spl.insert_knot(t, times)
        h = np.moveaxis(new.control_points().reshape((-1,) + shape[1:]), 0, d)
        ku, kv = self.knots
        if d == 0:
            ku = new.knots
        else:
            kv = new.knots
        return type(self)._raw(h, self.degree[0], self.degree[1], ku, kv, self.rational)

    def to_bezier_patches(self):
        """Exact Bezier patches, one per pair of non-empty knot spans.

        Returns
        -------
        list of lists
            ``patches[a][b]`` covers the ``a``-th u span and ``b``-th v span:
            a :class:`BezierSurface` (on the unit square; see
            :meth:`patch_domains`) for a non-rational surface, else a
            :class:`RationalBezierSurface` carrying its domain.
        """
        p, q = self.degree
        su, shape = self._flat_spline(0)
        pu = su.to_beziers()                                 # (Su, p+1, Nv*(D+1))
        Su = len(pu)
        h = pu.ctrl.reshape(Su, p + 1, shape[1], shape[2])  # (Su, p+1, Nv, D+1)
        hv = np.moveaxis(h, 2, 0).reshape(shape[1], -1)     # (Nv, Su*(p+1)*(D+1))
        pv = BSpline(hv, q, self.knots[1]).to_beziers()      # (Sv, q+1, ...)
        Sv = len(pv)
        c = pv.ctrl.reshape(Sv, q + 1, Su, p + 1, shape[2])
        c = np.transpose(c, (2, 0, 3, 1, 4))                 # (Su, Sv, p+1, q+1, D+1)
        D = self.dim
        out = []
        for a in range(Su):
            row = []
            for b in range(Sv):
                hn = c[a, b]
                dom = ((pu.breaks[a], pu.breaks[a + 1]), (pv.breaks[b], pv.breaks[b + 1]))
                if self.rational:
                    row.append(RationalBezierSurface(hn[..., :D] / hn[..., D:], hn[..., D], dom))
                else:
                    row.append(BezierSurface(hn[..., :D] / hn[..., D:]))
            out.append(row)
        return out

    def patch_domains(self):
        """``(u_breaks, v_breaks)``: the distinct knots bounding the Bezier
        patches of :meth:`to_bezier_patches`."""
        bu = self._flat_spline(0)[0].to_beziers().breaks
        bv = BSpline(np.zeros((self.net.shape[1], 1)), self.degree[1],
                     self.knots[1]).to_beziers().breaks
        return bu.copy(), bv.copy()

    def transform(self, matrix, offset=None):
        """Apply ``p -> matrix @ p + offset`` to the net (weights kept)."""
        c = self.net @ np.asarray(matrix, dtype=np.float64).T
        if offset is not None:
            c = c + np.asarray(offset, dtype=np.float64)
        h = np.concatenate([c * self.weights[..., None], self.weights[..., None]], axis=2)
        return type(self)._raw(h, self.degree[0], self.degree[1], self.knots[0], self.knots[1],
                               self.rational)


class BSplineSurface(NURBSSurface):
    """A (non-rational) B-spline surface: :class:`NURBSSurface` with unit
    weights.

    Parameters
    ----------
    net : (Nu, Nv, D) array_like of float
    degree : int or (int, int)
    knots : pair of (array_like or None)
    """

    def __init__(self, net, degree=3, knots=(None, None)):
        super().__init__(net, degree, knots, None)


class HermitePatch(BezierSurface):
    r"""Bicubic Hermite patch from corner points, corner partials and twists.

    ``S(u, v) = U M_H G M_H^T V^T`` with ``U = [u^3, u^2, u, 1]``, the
    Hermite matrix ``M_H`` and the geometry matrix ``G = [[P, P_v], [P_u,
    P_uv]]`` of the corner data.  Exactly the bicubic Bezier patch with
    ``b_10 = P_00 + P_u/3``, ``b_01 = P_00 + P_v/3``, ``b_11 = P_00 + (P_u +
    P_v)/3 + P_uv/9`` and the mirrored formulas at the other corners.

    Parameters
    ----------
    points : (2, 2, D) array_like of float
        ``points[a][b] = S(a, b)`` (a: u, b: v).
    du, dv : (2, 2, D) array_like of float
        ``S_u`` and ``S_v`` at the corners.
    twist : (2, 2, D) array_like of float, optional
        ``S_uv`` at the corners; default zero (a Ferguson patch).
    """

    def __init__(self, points, du, dv, twist=None):
        P = as_net(points, 2, 2, 'corner points')
        if P.shape[:2] != (2, 2):
            raise CurveError('corner points must have shape (2, 2, D), got %s' % (P.shape,))
        Pu = as_net(du, 2, 2, 'u derivatives')
        Pv = as_net(dv, 2, 2, 'v derivatives')
        T = np.zeros_like(P) if twist is None else as_net(twist, 2, 2, 'twists')
        if not (Pu.shape == Pv.shape == T.shape == P.shape):
            raise CurveError('corner points, derivatives and twists must all be (2, 2, D)')
        net = patches.hermite_net(P[None], Pu[None], Pv[None], T[None])[0]
        super().__init__(net)
        self.corner_points, self.corner_du, self.corner_dv, self.corner_twist = P, Pu, Pv, T


class CoonsPatch(BezierSurface):
    """Bilinearly blended Coons patch of four Bezier boundary curves, exactly
    as a tensor-product Bezier patch (:func:`raster.geometry.patches.coons_net`).

    Parameters
    ----------
    top, bottom : Bezier or (n+1, D) array_like
        ``S(u, 0)`` and ``S(u, 1)``, running with ``u``.
    left, right : Bezier or (n+1, D) array_like
        ``S(0, v)`` and ``S(1, v)``, running with ``v``.

    Curves of lower degree are elevated to the highest one.

    Raises
    ------
    CurveError
        The curves do not meet at the four corners.
    """

    def __init__(self, top, bottom, left, right):
        curves = [c if isinstance(c, Bezier) else Bezier(c) for c in (top, bottom, left, right)]
        n = max(max(c.degree for c in curves), 1)
        ctrl = [c.elevate(n - c.degree).ctrl for c in curves]
        if len({c.shape[1] for c in ctrl}) != 1:
            raise CurveError('boundary curves must have the same dimension')
        try:
            net = patches.coons_net(*ctrl)[0]
        except patches.PatchError as e:
            raise CurveError(str(e)) from None
        super().__init__(net)
        self.boundary_curves = tuple(curves)

