r"""Bezier segments of any degree: the one copy of the Bernstein maths that
flattening, bounds, stroking and the curve toolkit share.

A Bezier segment of degree ``n`` with control points ``P_0 .. P_n`` is

.. math:: B(t) = \sum_{i=0}^{n} B_{n,i}(t) P_i, \qquad
          B_{n,i}(t) = \binom{n}{i} t^i (1-t)^{n-i}, \quad t \in [0, 1].

Layouts
-------
Control points are float64 arrays ``(..., n+1, D)``: any leading batch
shape, then the control points, then the coordinates (usually ``D = 2``).
Functions that take parameters broadcast them against the batch shape.
Two functions use other layouts, because their callers are hot loops:

* :func:`blossom_pieces` works on the *point-major* layout
  ``(n+1, D, m)`` that :mod:`raster.geometry.flattening` keeps its pieces
  in (every row contiguous);
* :func:`bernstein_range` takes one coordinate only, coefficients first:
  ``(n+1, ...)``;
* :func:`segment_extrema` and :func:`segment_bounds` take the mixed-degree
  segment arrays of :class:`raster.geometry.path.Segments` (``(S, 4, D)``
  plus a degree per segment).

Arithmetic
----------
De Casteljau steps are ``a + t (b - a)``; the end points of evaluations and
pieces at ``t = 0`` and ``t = 1`` are the control points exactly.  Roots of
derivatives come from :mod:`raster.geometry.roots`.

>>> c = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])
>>> evaluate(c, 0.5).tolist()
[2.0, 1.5]
>>> lo, hi = bounds(c)
>>> lo.tolist(), hi.tolist()
([0.0, 0.0], [4.0, 1.5])
"""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING, Tuple

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

from ..errors import PathError
from .roots import solve_quadratic, unit_interval_roots

__all__ = ['bernstein', 'bernstein_matrix', 'evaluate', 'split', 'subsegment', 'blossom_pieces',
           'derivative', 'power_coeffs', 'elevate', 'bernstein_range', 'extrema', 'bounds',
           'segment_extrema', 'segment_bounds']


def _degree(n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise PathError('Bezier degree must be a non-negative integer, got %r' % (n,))
    return int(n)


@functools.lru_cache(maxsize=None)
def _binomials(n):
    b = np.array([math.comb(n, k) for k in range(n + 1)], dtype=np.float64)
    b.flags.writeable = False
    return b


@functools.lru_cache(maxsize=None)
def _power_matrix(n):
    m = np.zeros((n + 1, n + 1))
    for k in range(n + 1):
        for i in range(k + 1):
            m[k, i] = math.comb(n, k) * math.comb(k, i) * (-1) ** (k - i)
    m.flags.writeable = False
    return m


# ---------------------------------------------------------------------------
# bases
# ---------------------------------------------------------------------------

def bernstein(n: int, t: ArrayLike) -> np.ndarray:
    """Bernstein basis polynomials ``B(n, i)(t)`` for many ``t`` at once.

    Evaluated as the product ``C(n, i) * t**i * (1 - t)**(n - i)``: every
    factor is non-negative on [0, 1], so there is no cancellation and the
    relative error is a few ulps times ``n``.

    Parameters
    ----------
    n : int
        Degree, ``>= 0``.
    t : float or (M,) array_like of float

    Returns
    -------
    (n+1,) or (M, n+1) float64 ndarray
        Row ``m`` holds ``B(n, 0)(t_m) .. B(n, n)(t_m)``; rows sum to 1.

    >>> bernstein(2, 0.5).tolist()
    [0.25, 0.5, 0.25]
    """
    n = _degree(n)
    ta = np.asarray(t, dtype=np.float64)
    scalar = ta.ndim == 0
    ta = ta.reshape(-1, 1)
    i = np.arange(n + 1)
    out = _binomials(n) * np.power(ta, i) * np.power(1.0 - ta, n - i)
    return out[0] if scalar else out


def bernstein_matrix(n: int) -> np.ndarray:
    """The ``(n+1, n+1)`` float64 matrix ``M`` with
    ``B(n, i)(t) = sum_k M[k, i] t**k``: power-basis coefficients of the
    Bernstein polynomials (a fresh array).

    >>> bernstein_matrix(2).tolist()
    [[1.0, 0.0, 0.0], [-2.0, 2.0, 0.0], [1.0, -2.0, 1.0]]
    """
    return _power_matrix(_degree(n)).copy()


# ---------------------------------------------------------------------------
# evaluation and subdivision
# ---------------------------------------------------------------------------

def _points(ctrl):
    c = np.asarray(ctrl, dtype=np.float64)
    if c.ndim < 2 or c.shape[-2] < 1:
        raise PathError('control points must be an (..., n+1, D) array, got shape %r'
                        % (c.shape,))
    return c


def evaluate(ctrl: ArrayLike, t: ArrayLike) -> np.ndarray:
    """Points of Bezier segments by de Casteljau's algorithm.

    Parameters
    ----------
    ctrl : (..., n+1, D) array_like of float
    t : float or array_like of float, broadcastable to the batch shape
        ``(...)``

    Returns
    -------
    (..., D) float64 ndarray
        ``B(t)`` of every segment (batch shape broadcast with ``t``); the
        end points exactly at ``t = 0`` and ``t = 1``.

    >>> evaluate([[0, 0], [2, 2], [4, 0]], [0.25, 1.0]).tolist()
    [[1.0, 0.75], [4.0, 0.0]]
    """
    q = _points(ctrl)
    ta = np.asarray(t, dtype=np.float64)
    u = ta[..., None, None]
    end = q[..., -1, :]
    if q.shape[-2] == 1:
        shape = np.broadcast_shapes(q.shape[:-2], ta.shape) + q.shape[-1:]
        return np.broadcast_to(end, shape).copy()
    while q.shape[-2] > 1:
        q = q[..., :-1, :] + u * (q[..., 1:, :] - q[..., :-1, :])
    out = q[..., 0, :]
    one = ta == 1.0
    if np.any(one):
        out = np.where(one[..., None], end, out)
    return out


def split(ctrl: ArrayLike, t: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
    """Split Bezier segments at ``t`` (de Casteljau).

    Parameters
    ----------
    ctrl : (..., n+1, D) array_like of float
    t : float or array_like of float, broadcastable to the batch shape

    Returns
    -------
    left, right : (..., n+1, D) float64 ndarray
        Control points of the pieces ``[0, t]`` and ``[t, 1]``, each
        reparameterized to [0, 1]; ``left[..., n, :] == right[..., 0, :]``
        is the point at ``t``.

    >>> l, r = split([[0, 0], [2, 2], [4, 0]], 0.5)
    >>> l.tolist(), r.tolist()
    ([[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]], [[2.0, 1.0], [3.0, 1.0], [4.0, 0.0]])
    """
    q = _points(ctrl)
    u = np.asarray(t, dtype=np.float64)[..., None]
    shape = np.broadcast_shapes(q.shape, u.shape[:-1] + (1, 1))
    q = np.broadcast_to(q, shape)
    n = shape[-2] - 1
    left = np.empty(shape)
    right = np.empty(shape)
    left[..., 0, :] = q[..., 0, :]
    right[..., n, :] = q[..., n, :]
    for k in range(1, n + 1):
        q = q[..., :-1, :] + u[..., None] * (q[..., 1:, :] - q[..., :-1, :])
        left[..., k, :] = q[..., 0, :]
        right[..., n - k, :] = q[..., -1, :]
    return left, right


# Highest degree, and most pieces, for which blossom weights are computed
# from index tables (fewer numpy calls); up to _LOOP_DEGREE term by term
# (faster for many pieces); beyond, by two de Casteljau splits.
_TABLE_DEGREE = 8
_TABLE_PIECES = 256
_LOOP_DEGREE = 8


def blossom_pieces(P: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Control points of the pieces ``[a, b]`` of Bezier segments, in the
    point-major layout.

    Parameters
    ----------
    P : (n+1, D, m) float64 ndarray
        Control points of the segment each piece belongs to, control point
        index first, then coordinate, then piece.
    a, b : (m,) float64 ndarray
        Parameter interval of each piece (``a > b`` gives it reversed).

    Returns
    -------
    (n+1, D, m) float64 ndarray
        ``Q_i`` is the blossom ``P(a, .., a, b, .., b)`` with ``n - i``
        arguments ``a``: the piece reparameterized to [0, 1].
        ``Q_0 = P(a)``, ``Q_n = P(b)``; exactly ``P_0`` (``P_n``) where
        ``a`` (``b``) is 0 (1).

    Notes
    -----
    For degrees up to 8 the blossom is a convex combination of the ``P_j``
    whose weights are the convolution of the Bernstein weights of degree
    ``n - i`` at ``a`` and of degree ``i`` at ``b``: exact at 0 and 1, no
    accumulated error.  Higher degrees split at ``max(a, b)`` and then at
    ``min / max`` (O(n) de Casteljau steps instead of O(n**3) weights).

    >>> P = np.array([[0.0, 3.0, 6.0], [0.0, 3.0, 0.0]]).T[:, :, None]
    >>> blossom_pieces(P, np.array([0.0]), np.array([0.5]))[:, :, 0].tolist()
    [[0.0, 0.0], [1.5, 1.5], [3.0, 1.5]]
    """
    n1, D, m = P.shape
    n = n1 - 1
    if n == 0:
        return P.copy()
    if n > _LOOP_DEGREE:
        return _pieces_by_splits(P, a, b)
    if m > _TABLE_PIECES:
        return _blossom_loops(P, a, b)
    ii, jj, rr, kk, coef, S = _blossom_table(n)
    X = np.empty((n1, 4, m))
    X[0] = 1.0
    X[1:, 0] = a
    X[1:, 1] = 1.0 - a
    X[1:, 2] = b
    X[1:, 3] = 1.0 - b
    pw = np.cumprod(X, axis=0)                # pw[p, :] = a**p, (1-a)**p, b**p, (1-b)**p
    T = pw[rr, 0] * pw[n - ii - rr, 1]
    T *= pw[kk, 2]
    T *= pw[ii - kk, 3]
    T *= coef[:, None]
    W = (S @ T).reshape(n1, n1, 1, m)         # W[i, j]: weight of P_j in Q_i
    return (W * P[None]).sum(axis=1)


def _blossom_loops(P, a, b):
    """:func:`blossom_pieces` for many pieces, term by term (the tables of
    :func:`_blossom_table` grow like n**5 and their matrix product like the
    piece count)."""
    if P.shape[0] == 4:
        return _blossom_cubic(P, a, b)
    return _blossom_terms(P, a, b)


def _blossom_terms(P, a, b):
    """:func:`_blossom_loops` of any degree, term by term (the reference
    of :func:`_blossom_cubic`)."""
    n1, D, m = P.shape
    n = n1 - 1
    one = np.ones(m)
    pa, qa, pb, qb = [one], [one], [one], [one]      # powers of a, 1-a, b, 1-b
    for _ in range(n):
        pa.append(pa[-1] * a)
        qa.append(qa[-1] * (1.0 - a))
        pb.append(pb[-1] * b)
        qb.append(qb[-1] * (1.0 - b))
    W = np.zeros((n1, n1, m))                         # W[i, j]: weight of P_j in Q_i
    for i in range(n1):
        ci = _binomials(i)
        wb = [ci[k] * pb[k] * qb[i - k] for k in range(i + 1)]
        cr = _binomials(n - i)
        for r in range(n - i + 1):
            wa = cr[r] * pa[r] * qa[n - i - r]
            for k in range(i + 1):
                W[i, r + k] += wa * wb[k]
    Q = np.empty((n1, D, m))
    for i in range(n1):
        Q[i] = W[i, 0] * P[0]
        for j in range(1, n1):
            Q[i] += W[i, j] * P[j]
    return Q


def _blossom_cubic(P, a, b):
    """:func:`_blossom_loops` for cubics, with the same floating-point
    operations in the same order (hence the same result bit for bit) but
    without those that cannot change a value: products with the constant
    1, additions to the zeros the weights start from (every weight is a
    sum of products of numbers in [0, 1], so non-negative), and the powers
    of ``1 - a`` and ``1 - b`` computed once."""
    sa, sb = 1.0 - a, 1.0 - b
    pa = (None, a, a * a, a * a * a)                  # powers of a, 1-a, b, 1-b
    qa = (None, sa, sa * sa, sa * sa * sa)
    pb = (None, b, b * b, b * b * b)
    qb = (None, sb, sb * sb, sb * sb * sb)

    def term(c, p, q, i, k):
        # (c p[k]) q[i - k] as _blossom_loops computes it (c a binomial;
        # None: the constant 1)
        if k == 0:
            if i == 0:
                return None
            return q[i] if c == 1 else c * q[i]       # (c * 1) * q = c * q
        x = p[k] if c == 1 else c * p[k]
        return x if i == k else x * q[i - k]

    Q = np.empty(P.shape)
    for i in range(4):
        ci = _binomials(i)
        wb = [term(ci[k], pb, qb, i, k) for k in range(i + 1)]
        cr = _binomials(3 - i)
        W = [None] * 4
        for r in range(4 - i):
            wa = term(cr[r], pa, qa, 3 - i, r)
            for k in range(i + 1):
                # (never both the constant 1 for a cubic)
                t = wa if wb[k] is None else wb[k] if wa is None else wa * wb[k]
                W[r + k] = t if W[r + k] is None else W[r + k] + t
        q = Q[i]
        np.multiply(W[0], P[0], out=q)
        for j in range(1, 4):
            q += W[j] * P[j]
    return Q


_BLOSSOM_TABLES = {}


def _blossom_table(n):
    """Index tables of the blossom weights of degree ``n``: one term per
    (i, r, k) with weight C(n-i, r) C(i, k) a**r (1-a)**(n-i-r) b**k
    (1-b)**(i-k) added to W[i, r + k]; ``S`` sums the terms into W."""
    tab = _BLOSSOM_TABLES.get(n)
    if tab is None:
        terms = [(i, r + k, r, k, math.comb(n - i, r) * math.comb(i, k))
                 for i in range(n + 1) for r in range(n - i + 1) for k in range(i + 1)]
        ii, jj, rr, kk, coef = (np.array(v) for v in zip(*terms))
        S = np.zeros(((n + 1) ** 2, len(terms)))
        S[ii * (n + 1) + jj, np.arange(len(terms))] = 1.0
        tab = (ii, jj, rr, kk, coef.astype(np.float64), S)
        _BLOSSOM_TABLES[n] = tab
    return tab


def _pieces_by_splits(P, a, b):
    """:func:`blossom_pieces` for high degrees: the piece ``[lo, hi]`` is the
    right part, split at ``lo / hi``, of the left part split at ``hi``."""
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    C = np.moveaxis(P, 2, 0)                          # (m, n+1, D)
    left, _ = split(C, hi)
    with np.errstate(invalid='ignore', divide='ignore'):
        ratio = np.where(hi > 0, lo / hi, 0.0)
    _, piece = split(left, ratio)
    rev = a > b
    if np.any(rev):
        piece[rev] = piece[rev, ::-1]
    out = np.moveaxis(piece, 0, 2).copy()             # (n+1, D, m)
    z, o = a == 0.0, b == 1.0
    out[0][:, z] = P[0][:, z]
    out[-1][:, o] = P[-1][:, o]
    return out


def subsegment(ctrl: ArrayLike, t0: ArrayLike, t1: ArrayLike) -> np.ndarray:
    """The pieces ``[t0, t1]`` of Bezier segments, reparameterized to [0, 1].

    Parameters
    ----------
    ctrl : (..., n+1, D) array_like of float
    t0, t1 : float or array_like of float, broadcastable to the batch shape
        ``t0 > t1`` gives the piece reversed.

    Returns
    -------
    (..., n+1, D) float64 ndarray
        By blossoming (:func:`blossom_pieces`).

    >>> subsegment([[0, 0], [3, 3], [6, 0]], 0, 0.5).tolist()
    [[0.0, 0.0], [1.5, 1.5], [3.0, 1.5]]
    """
    c = _points(ctrl)
    t0 = np.asarray(t0, dtype=np.float64)
    t1 = np.asarray(t1, dtype=np.float64)
    batch = np.broadcast_shapes(c.shape[:-2], t0.shape, t1.shape)
    n1, D = c.shape[-2:]
    C = np.broadcast_to(c, batch + (n1, D)).reshape(-1, n1, D)
    a = np.broadcast_to(t0, batch).reshape(-1)
    b = np.broadcast_to(t1, batch).reshape(-1)
    Q = blossom_pieces(np.moveaxis(C, 0, 2), a, b)
    return np.moveaxis(Q, 2, 0).reshape(batch + (n1, D))


def derivative(ctrl: ArrayLike, axis: int = -2) -> np.ndarray:
    """Control points of the derivative (hodograph): ``n (P_{i+1} - P_i)``.

    Parameters
    ----------
    ctrl : array_like of float
        Control points along ``axis`` (default: ``(..., n+1, D)``).
    axis : int, optional
        The control point axis (0 for the point-major layout).

    Returns
    -------
    float64 ndarray
        ``n`` points along ``axis`` (a segment of degree ``n - 1``); for
        ``n = 0`` one zero point (the derivative of a constant).

    >>> derivative([[0, 0], [1, 2], [3, 2], [4, 0]]).tolist()
    [[3.0, 6.0], [6.0, 0.0], [3.0, -6.0]]
    """
    c = np.asarray(ctrl, dtype=np.float64)
    n = c.shape[axis] - 1
    if n == 0:
        return np.zeros_like(c)
    return n * np.diff(c, axis=axis)


def power_coeffs(ctrl: ArrayLike) -> np.ndarray:
    """Power-basis coefficients: ``B(t) = sum_k coef[..., k, :] t**k``.

    Parameters
    ----------
    ctrl : (..., n+1, D) array_like of float

    Returns
    -------
    (..., n+1, D) float64 ndarray, lowest order first

    >>> power_coeffs([[0, 0], [1, 2], [2, 0]]).tolist()
    [[0.0, 0.0], [2.0, 4.0], [0.0, -4.0]]
    """
    c = _points(ctrl)
    return _power_matrix(c.shape[-2] - 1) @ c


def elevate(ctrl: ArrayLike, times: int = 1) -> np.ndarray:
    """Degree elevation (exact): the same curves with ``times`` more
    control points.

    Parameters
    ----------
    ctrl : (..., n+1, D) array_like of float
    times : int, optional

    Returns
    -------
    (..., n+1+times, D) float64 ndarray

    >>> elevate([[0, 0], [3, 3]]).tolist()
    [[0.0, 0.0], [1.5, 1.5], [3.0, 3.0]]
    """
    c = _points(ctrl)
    for _ in range(_degree(times)):
        n1 = c.shape[-2]
        n = n1 - 1
        out = np.empty(c.shape[:-2] + (n1 + 1, c.shape[-1]))
        out[..., 0, :] = c[..., 0, :]
        out[..., -1, :] = c[..., -1, :]
        i = np.arange(1, n1)[:, None]
        w = i / (n + 1.0)
        out[..., 1:n1, :] = w * c[..., :-1, :] + (1.0 - w) * c[..., 1:, :]
        c = out
    return c


# ---------------------------------------------------------------------------
# extrema and bounds
# ---------------------------------------------------------------------------

def _cubic_derivative(c0, c1, c2, c3):
    """Derivative / 3 of the cubic Bernstein polynomial as ``a t**2 + b t
    + c``."""
    return c3 - c0 + 3.0 * (c1 - c2), 2.0 * (c0 - 2.0 * c1 + c2), c1 - c0


def bernstein_range(c: ArrayLike, normalize: bool = True) -> Tuple[np.ndarray, np.ndarray]:
    """Exact minimum and maximum over ``t`` in [0, 1] of Bernstein
    polynomials (one coordinate of Bezier segments).

    Parameters
    ----------
    c : (n+1, ...) array_like of float
        Bernstein coefficients, coefficient axis first (one polynomial per
        index of the remaining axes).
    normalize : bool, optional
        Passed to :func:`~raster.geometry.roots.solve_quadratic` for cubics:
        without it the result is the same bit for bit for coefficients
        within about ``1e-150 .. 1e150``.

    Returns
    -------
    lo, hi : (...) float64 ndarray

    Notes
    -----
    The extrema are at the ends or where the derivative vanishes: for
    degree 2 one linear root, for degree 3 the roots of a quadratic, for
    higher degrees :func:`~raster.geometry.roots.unit_interval_roots`.
    Candidates outside (0, 1) are replaced by ``t = 0`` (an end point, a
    candidate anyway), so the work per polynomial is fixed.

    ``12 t (1 - t) (1 - 2 t)`` reaches ``+-2 / sqrt(3)``:

    >>> lo, hi = bernstein_range(np.array([[0.0], [4.0], [-4.0], [0.0]]))
    >>> bool(np.allclose([lo[0], hi[0]], [-2 / np.sqrt(3), 2 / np.sqrt(3)], rtol=1e-15))
    True
    """
    c = np.asarray(c, dtype=np.float64)
    n = len(c) - 1
    if n < 0:
        raise PathError('a Bernstein polynomial needs at least one coefficient')
    c0, cn = c[0], c[n]
    lo = np.minimum(c0, cn)
    hi = np.maximum(c0, cn)
    if n <= 1:
        return lo, hi
    if n == 2:
        c1, c2 = c[1], c[2]
        # derivative / 2 = (c1 - c0) + t (c0 - 2 c1 + c2): one root
        den = c0 - 2.0 * c1 + c2
        with np.errstate(all='ignore'):
            t = np.where(den != 0, (c0 - c1) / den, 0.0)
        t = np.where((t > 0.0) & (t < 1.0), t, 0.0)
        s = 1.0 - t
        v = s * s * c0 + 2.0 * s * t * c1 + t * t * c2
        return np.minimum(lo, v), np.maximum(hi, v)
    if n == 3:
        c1, c2, c3 = c[1], c[2], c[3]
        t = solve_quadratic(*_cubic_derivative(c0, c1, c2, c3), normalize=normalize)
        t[~((t > 0.0) & (t < 1.0))] = 0.0
        s = 1.0 - t
        v = s * s * s * c0 + 3.0 * s * t * (s * c1 + t * c2) + t * t * t * c3
        return np.minimum(lo, v.min(axis=0)), np.maximum(hi, v.max(axis=0))
    shape = c.shape[1:]
    flat = c.reshape(n + 1, -1).T                         # (K, n+1)
    dcoef = power_coeffs(derivative(flat[:, :, None]))[:, :, 0]     # (K, n)
    r, owner = unit_interval_roots(dcoef)
    lo, hi = lo.reshape(-1).copy(), hi.reshape(-1).copy()
    if len(r):
        v = evaluate(flat[owner][:, :, None], r)[:, 0]
        np.minimum.at(lo, owner, v)
        np.maximum.at(hi, owner, v)
    return lo.reshape(shape), hi.reshape(shape)


def extrema(ctrl: ArrayLike) -> np.ndarray:
    """Parameters where a coordinate of a Bezier segment has an interior
    extremum (its derivative vanishes).

    Parameters
    ----------
    ctrl : (..., n+1, D) array_like of float

    Returns
    -------
    (..., D, max(n-1, 0)) float64 ndarray
        For each segment and axis the parameters in the open interval
        (0, 1), ascending, NaN-padded.  Degrees up to 3 are solved in
        closed form; higher degrees leave out roots within ``1e-12`` of
        the ends (see :func:`~raster.geometry.roots.unit_interval_roots`).

    >>> extrema([[0, 0], [1, 2], [2, 0]]).tolist()
    [[nan], [0.5]]
    """
    c = _points(ctrl)
    n = c.shape[-2] - 1
    cf = np.moveaxis(c, -2, 0)                        # (n+1, ..., D)
    if n <= 1:
        return np.zeros(c.shape[:-2] + (c.shape[-1], 0))
    if n == 2:
        c0, c1, c2 = cf
        den = c0 - 2.0 * c1 + c2
        with np.errstate(all='ignore'):
            t = np.where(den != 0, (c0 - c1) / den, np.nan)
        return np.where((t > 0.0) & (t < 1.0), t, np.nan)[..., None]
    if n == 3:
        t = solve_quadratic(*_cubic_derivative(*cf))        # (2, ..., D), ascending
        t = np.where((t > 0.0) & (t < 1.0), t, np.nan)
        t = np.sort(t, axis=0)                              # NaN last
        return np.moveaxis(t, 0, -1)
    batch, D = c.shape[:-2], c.shape[-1]
    flat = c.reshape(-1, n + 1, D)
    K = len(flat) * D
    dcoef = np.moveaxis(power_coeffs(derivative(flat)), 1, 2).reshape(K, n)
    r, owner = unit_interval_roots(dcoef)
    out = np.full((K, n - 1), np.nan)
    if len(r):
        order = np.lexsort((r, owner))
        r, owner = r[order], owner[order]
        first = np.searchsorted(owner, owner)
        out[owner, np.arange(len(r)) - first] = r
    return out.reshape(batch + (D, n - 1))


def bounds(ctrl: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
    """Exact bounding boxes of Bezier segments of one degree.

    Parameters
    ----------
    ctrl : (..., n+1, D) array_like of float

    Returns
    -------
    lo, hi : (..., D) float64 ndarray
        Minimum and maximum of each coordinate over ``t`` in [0, 1]
        (:func:`bernstein_range` of each coordinate).

    >>> lo, hi = bounds([[0, 0], [0, 4], [4, 4], [4, 0]])     # a cubic arch
    >>> lo.tolist(), hi.tolist()
    ([0.0, 0.0], [4.0, 3.0])
    """
    c = _points(ctrl)
    return bernstein_range(np.moveaxis(c, -2, 0))


def segment_extrema(ctrl: ArrayLike, degree: ArrayLike) -> np.ndarray:
    """:func:`extrema` of mixed-degree path segments.

    Parameters
    ----------
    ctrl : (S, 4, D) float64 ndarray
        Control points as in :class:`raster.geometry.path.Segments` (a
        segment of degree ``k`` uses ``ctrl[:, :k+1]``).
    degree : (S,) int ndarray
        1, 2 or 3.

    Returns
    -------
    (S, D, 2) float64 ndarray
        For each segment and axis up to two parameters in (0, 1),
        ascending, NaN-padded (always NaN for lines).

    >>> c = np.array([[[0, 0], [1, 2], [2, 0], [2, 0]]], float)
    >>> segment_extrema(c, np.array([2]))[0].tolist()
    [[nan, nan], [0.5, nan]]
    """
    ctrl = np.asarray(ctrl, dtype=np.float64)
    degree = np.asarray(degree)
    S, _, D = ctrl.shape
    out = np.full((S, D, 2), np.nan)
    for k in (2, 3):
        sel = degree == k
        if np.any(sel):
            out[sel, :, :k - 1] = extrema(ctrl[sel, :k + 1])
    return out


def segment_bounds(ctrl: ArrayLike, degree: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
    """Exact bounding box of every mixed-degree path segment.

    Parameters
    ----------
    ctrl : (S, 4, D) float64 ndarray
        As in :class:`raster.geometry.path.Segments`.
    degree : (S,) int ndarray
        1, 2 or 3.

    Returns
    -------
    lo, hi : (S, D) float64 ndarray
        Per-segment minimum and maximum of each coordinate over t in [0, 1].

    >>> c = np.array([[[0, 0], [0, 4], [4, 4], [4, 0]]], float)   # a cubic arch
    >>> lo, hi = segment_bounds(c, np.array([3]))
    >>> lo.tolist(), hi.tolist()
    ([[0.0, 0.0]], [[4.0, 3.0]])
    """
    ctrl = np.asarray(ctrl, dtype=np.float64)
    degree = np.asarray(degree)
    end = np.where((degree == 1)[:, None], ctrl[:, 1], ctrl[:, 3])
    lo = np.minimum(ctrl[:, 0], end)
    hi = np.maximum(ctrl[:, 0], end)
    for k in (2, 3):
        sel = np.flatnonzero(degree == k)
        if len(sel):
            lo[sel], hi[sel] = bounds(ctrl[sel, :k + 1])
    return lo, hi
