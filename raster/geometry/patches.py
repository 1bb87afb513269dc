r"""Tensor-product Bezier patches and Coons patches, vectorized over many
patches at once.

A tensor-product Bezier patch of degree ``(m, n)`` with control net
``P[i, j]`` (``i = 0..m`` along ``u``, ``j = 0..n`` along ``v``) is

.. math:: S(u, v) = \sum_{i=0}^{m} \sum_{j=0}^{n} B_{m,i}(u) B_{n,j}(v) P_{ij},
          \qquad (u, v) \in [0, 1]^2 .

Nets are float64 arrays of shape ``(P, m+1, n+1, D)`` -- ``P`` patches, any
dimension ``D`` (positions in 2-D or 3-D, or colours as points of RGBA
space).  The first axis after the batch runs along ``u``.

A bilinearly blended Coons patch interpolates four boundary curves: with
``C1(u)`` the top (``v = 0``), ``C2(u)`` the bottom (``v = 1``), ``D1(v)``
the left (``u = 0``) and ``D2(v)`` the right (``u = 1``) curve,

.. math:: S = S_C + S_D - S_B, \quad
          S_C = (1-v) C_1(u) + v C_2(u), \quad
          S_D = (1-u) D_1(v) + u D_2(v),

and ``S_B`` the bilinear interpolation of the four corners (SVG 2
``meshpatch``, PDF shading type 6).  When the four curves are Bezier curves
of degree ``n`` the Coons patch *is* a tensor-product patch of degree
``(n, n)``: every term above is, after degree elevation in the linear
direction.  :func:`coons_net` computes that net (for cubics its interior
points are the PDF type-6 to type-7 formulas), so every patch -- surfaces
of the curve toolkit, SVG mesh gradients -- is evaluated by one code path,
:func:`tensor_eval`.

Linearization: over a parameter rectangle of size ``hu x hv`` the patch
differs from the bilinear interpolation of the rectangle's corners by at
most ``hu^2/8 max|S_uu| + hv^2/8 max|S_vv|``, and the bilinear quad from its
two triangles (split along the diagonal) by at most ``hu hv max|S_uv| / 4``;
the second derivatives are bounded by the net's second differences (a
Bezier patch lies in the convex hull of its control net, and so do its
derivative patches).  :func:`linearization_error` and :func:`grid_counts`
turn this into a uniform grid whose triangles are within a tolerance of the
patch.

>>> net = bilinear_net([[0, 0], [2, 0], [0, 1], [2, 1]])   # a 2 x 1 rectangle, P = 1
>>> tensor_eval(net, [0.5], [0.5]).tolist()
[[[1.0, 0.5]]]
"""

import math
from typing import Optional, Tuple

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LimitError, RasterError
from .bezier import bernstein

__all__ = ['PatchError', 'MAX_PATCH_DEGREE', 'bernstein_basis', 'tensor_eval', 'tensor_grid',
           'tensor_points', 'coons_net', 'mesh_patch_nets', 'bilinear_net', 'hermite_net',
           'split_patches',
           'subpatches', 'derivative_bounds', 'linearization_error', 'grid_counts',
           'net_bounds']

#: Highest degree in either direction (Bernstein values are products of
#: binomials and powers; far below float64 trouble).
MAX_PATCH_DEGREE = 60

#: Most evaluation points one call may produce (patches x points).
MAX_PATCH_POINTS = 50_000_000


class PatchError(RasterError, ValueError):
    """Malformed patch input: a control net or boundary that is not a
    finite array of the documented shape, a degree beyond the limit, or
    parameters outside ``[0, 1]``."""


def _degree(n, name='degree'):
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise PatchError('%s must be a non-negative integer, got %r' % (name, n))
    if n > MAX_PATCH_DEGREE:
        raise PatchError('%s %d exceeds the limit %d' % (name, n, MAX_PATCH_DEGREE))
    return int(n)


def _params(t, name):
    try:
        a = np.asarray(t, dtype=np.float64)
    except (TypeError, ValueError):
        raise PatchError('%s must be numbers' % name) from None
    if a.size and not np.all(np.isfinite(a)):
        raise PatchError('%s must be finite' % name)
    if a.size and (a.min() < -1e-12 or a.max() > 1 + 1e-12):
        raise PatchError('%s must lie in [0, 1]' % name)
    return np.clip(a, 0.0, 1.0)


def as_nets(net: ArrayLike, name: str = 'control net') -> Tuple[np.ndarray, bool]:
    """Validate control nets: returns ``((P, m+1, n+1, D) float64, batched)``
    where ``batched`` tells whether the input had the batch axis."""
    try:
        a = np.array(net, dtype=np.float64)
    except (TypeError, ValueError):
        raise PatchError('%s must be numbers' % name) from None
    batched = a.ndim == 4
    if a.ndim == 3:
        a = a[None]
    if a.ndim != 4 or min(a.shape) < 1:
        raise PatchError('%s must have shape (P, m+1, n+1, D) or (m+1, n+1, D), got %s'
                         % (name, a.shape))
    _degree(a.shape[1] - 1, 'degree in u')
    _degree(a.shape[2] - 1, 'degree in v')
    if not np.all(np.isfinite(a)):
        raise PatchError('%s must be finite' % name)
    return a, batched


def bernstein_basis(n: int, t: ArrayLike, order: int = 0) -> np.ndarray:
    """Bernstein polynomials of degree ``n`` or their derivatives.

    ``d^k/dt^k B_{n,i}(t) = n!/(n-k)! sum_j (-1)^(k-j) C(k, j) B_{n-k, i-j}(t)``.

    Parameters
    ----------
    n : int
        Degree, ``0 <= n <= MAX_PATCH_DEGREE``.
    t : (M,) array_like of float
        Parameters (any real values; the patch functions keep them in [0, 1]).
    order : int
        Derivative order ``k >= 0``.

    Returns
    -------
    (M, n+1) float64 ndarray

    >>> bernstein_basis(2, [0.5]).tolist()
    [[0.25, 0.5, 0.25]]
    >>> bernstein_basis(2, [0.5], 1).tolist()      # 2 (B_{1,i-1} - B_{1,i})
    [[-1.0, 0.0, 1.0]]
    """
    n = _degree(n)
    k = _degree(order, 'derivative order')
    ta = np.asarray(t, dtype=np.float64).reshape(-1, 1)
    out = np.zeros((ta.shape[0], n + 1))
    if k > n:
        return out
    m = n - k
    b = bernstein(m, ta[:, 0]).reshape(ta.shape[0], m + 1)
    for j in range(k + 1):
        out[:, j:j + m + 1] += (-1.0) ** (k - j) * math.comb(k, j) * b
    return out * (math.factorial(n) / math.factorial(m))


def tensor_eval(net: ArrayLike, u: ArrayLike, v: ArrayLike, du: int = 0,
                dv: int = 0) -> np.ndarray:
    """Points (or partial derivatives) of tensor-product Bezier patches.

    Parameters
    ----------
    net : (P, m+1, n+1, D) array_like of float
        Control nets (a single ``(m+1, n+1, D)`` net is taken as ``P = 1``).
    u, v : (K,) or (P, K) array_like of float in [0, 1]
        Parameters: the same ``K`` points for every patch, or ``K`` points
        per patch.  ``u`` and ``v`` must have the same shape.
    du, dv : int
        Orders of the partial derivatives in ``u`` and ``v`` (0: the points).

    Returns
    -------
    (P, K, D) float64 ndarray
        ``d^(du+dv) S / du^du dv^dv`` at each parameter pair.

    Raises
    ------
    PatchError
        Malformed nets or parameters.

    >>> net = np.array([[[0, 0], [0, 3]], [[3, 0], [3, 3]]], float)   # u along x
    >>> tensor_eval(net, [0.5], [1 / 3]).tolist()
    [[[1.5, 1.0]]]
    >>> tensor_eval(net, [0.5], [0.5], du=1).tolist()
    [[[3.0, 0.0]]]
    """
    c, _ = as_nets(net)
    P, m1, n1, D = c.shape
    ua, va = _params(u, 'u'), _params(v, 'v')
    if ua.shape != va.shape or ua.ndim not in (1, 2) or (ua.ndim == 2 and ua.shape[0] != P):
        raise PatchError('u and v must both have shape (K,) or (P, K), got %s and %s'
                         % (ua.shape, va.shape))
    K = ua.shape[-1]
    if P * K > MAX_PATCH_POINTS:
        raise LimitError('patch evaluation of %d points exceeds the limit %d'
                         % (P * K, MAX_PATCH_POINTS))
    bu = bernstein_basis(m1 - 1, ua.reshape(-1), du)
    bv = bernstein_basis(n1 - 1, va.reshape(-1), dv)
    if ua.ndim == 1:
        return np.einsum('ki,kj,pijd->pkd', bu, bv, c)
    bu = bu.reshape(P, K, m1)
    bv = bv.reshape(P, K, n1)
    return np.einsum('pki,pkj,pijd->pkd', bu, bv, c)


def tensor_points(net: ArrayLike, idx: ArrayLike, u: ArrayLike, v: ArrayLike, du: int = 0,
                  dv: int = 0) -> np.ndarray:
    """Points of patch ``idx[k]`` at ``(u[k], v[k])``: one point per entry.

    Parameters
    ----------
    net : (P, m+1, n+1, D) array_like of float
    idx : (K,) array_like of int
        Patch of each point.
    u, v : (K,) array_like of float in [0, 1]
    du, dv : int
        Partial derivative orders.

    Returns
    -------
    (K, D) float64 ndarray

    >>> net = bilinear_net([[0, 0], [1, 0], [0, 1], [1, 1]])
    >>> tensor_points(np.concatenate([net, net + 5]), [1, 0], [0.5, 0.5], [0, 1]).tolist()
    [[5.5, 5.0], [0.5, 1.0]]
    """
    c, _ = as_nets(net)
    P, m1, n1, D = c.shape
    try:
        ix = np.asarray(idx, dtype=np.int64).reshape(-1)
    except (TypeError, ValueError):
        raise PatchError('patch indices must be integers') from None
    ua, va = _params(u, 'u').reshape(-1), _params(v, 'v').reshape(-1)
    if not len(ix) == len(ua) == len(va):
        raise PatchError('idx, u and v must have the same length')
    if len(ix) and (ix.min() < 0 or ix.max() >= P):
        raise PatchError('patch index out of range')
    bu = bernstein_basis(m1 - 1, ua, du)
    bv = bernstein_basis(n1 - 1, va, dv)
    # contract v first: (K, m+1, D), then u
    rows = np.einsum('kj,kijd->kid', bv, c[ix])
    return np.einsum('ki,kid->kd', bu, rows)


def tensor_grid(net: ArrayLike, us: ArrayLike, vs: ArrayLike, du: int = 0,
                dv: int = 0) -> np.ndarray:
    """Patches evaluated on the grid ``us x vs``.

    Parameters
    ----------
    net : (P, m+1, n+1, D) array_like of float
    us : (A,) array_like of float in [0, 1]
    vs : (B,) array_like of float in [0, 1]
    du, dv : int
        Partial derivative orders.

    Returns
    -------
    (P, A, B, D) float64 ndarray
        ``out[p, a, b] = d^(du+dv) S_p(us[a], vs[b])``.

    >>> tensor_grid(bilinear_net([[0, 0], [2, 0], [0, 2], [2, 2]]), [0, 1], [0.5]).tolist()
    [[[[0.0, 1.0]], [[2.0, 1.0]]]]
    """
    c, _ = as_nets(net)
    P, m1, n1, D = c.shape
    ua = _params(us, 'u').reshape(-1)
    va = _params(vs, 'v').reshape(-1)
    if P * len(ua) * len(va) > MAX_PATCH_POINTS:
        raise LimitError('patch grid of %d points exceeds the limit %d'
                         % (P * len(ua) * len(va), MAX_PATCH_POINTS))
    bu = bernstein_basis(m1 - 1, ua, du)
    bv = bernstein_basis(n1 - 1, va, dv)
    return np.einsum('ai,bj,pijd->pabd', bu, bv, c)


def bilinear_net(corners: ArrayLike) -> np.ndarray:
    """The degree-(1, 1) net of the bilinear patch through four corners.

    Parameters
    ----------
    corners : (4, D) or (P, 4, D) array_like of float
        Corners in the order ``S(0,0), S(1,0), S(0,1), S(1,1)``.

    Returns
    -------
    (P, 2, 2, D) float64 ndarray

    >>> bilinear_net([[0, 0], [1, 0], [0, 1], [1, 1]]).shape
    (1, 2, 2, 2)
    """
    c = np.array(corners, dtype=np.float64)
    if c.ndim == 2:
        c = c[None]
    if c.ndim != 3 or c.shape[1] != 4:
        raise PatchError('corners must have shape (4, D) or (P, 4, D), got %s' % (c.shape,))
    if not np.all(np.isfinite(c)):
        raise PatchError('corners must be finite')
    return np.stack([np.stack([c[:, 0], c[:, 2]], 1), np.stack([c[:, 1], c[:, 3]], 1)], 1)


def hermite_net(points: ArrayLike, du: ArrayLike, dv: ArrayLike,
                twist: Optional[ArrayLike] = None) -> np.ndarray:
    """The bicubic net of Hermite patches from corner values, first partials
    and twists.

    At a corner the Bezier net has ``S_u = 3 (b_10 - b_00)``, ``S_v = 3
    (b_01 - b_00)`` and ``S_uv = 9 (b_11 - b_10 - b_01 + b_00)``; solving
    these (and their mirror images at the other corners) for the points
    next to each corner gives the net.

    Parameters
    ----------
    points, du, dv : (P, 2, 2, D) array_like of float
        ``S``, ``S_u`` and ``S_v`` at the corners; ``[:, a, b]`` is the
        corner ``u = a, v = b``.
    twist : (P, 2, 2, D) array_like of float, optional
        ``S_uv`` at the corners (default 0).

    Returns
    -------
    (P, 4, 4, D) float64 ndarray

    >>> z = np.zeros((1, 2, 2, 1))
    >>> P = np.array([0.0, 0.0, 1.0, 1.0]).reshape(1, 2, 2, 1)     # S = u
    >>> hermite_net(P, z + 1, z)[0, :, 0, 0].tolist()
    [0.0, 0.3333333333333333, 0.6666666666666667, 1.0]
    """
    arrs = []
    for a, name in ((points, 'corner points'), (du, 'u derivatives'), (dv, 'v derivatives'),
                    (np.zeros_like(np.asarray(points, dtype=np.float64)) if twist is None
                     else twist, 'twists')):
        try:
            x = np.array(a, dtype=np.float64)
        except (TypeError, ValueError):
            raise PatchError('%s must be numbers' % name) from None
        if x.ndim != 4 or x.shape[1:3] != (2, 2):
            raise PatchError('%s must have shape (P, 2, 2, D), got %s' % (name, x.shape))
        if not np.all(np.isfinite(x)):
            raise PatchError('%s must be finite' % name)
        arrs.append(x)
    P, Pu, Pv, T = arrs
    if not (P.shape == Pu.shape == Pv.shape == T.shape):
        raise PatchError('corner points, derivatives and twists must have one shape')
    net = np.empty((P.shape[0], 4, 4, P.shape[3]))
    for a in (0, 1):
        for b in (0, 1):
            su, sv = 1 - 2 * a, 1 - 2 * b              # +1 at parameter 0, -1 at 1
            i, j = 3 * a, 3 * b
            p, pu, pv, t = P[:, a, b], Pu[:, a, b], Pv[:, a, b], T[:, a, b]
            net[:, i, j] = p
            net[:, i + su, j] = p + su * pu / 3
            net[:, i, j + sv] = p + sv * pv / 3
            net[:, i + su, j + sv] = p + su * pu / 3 + sv * pv / 3 + su * sv * t / 9
    return net


def _curves(a, name):
    try:
        c = np.array(a, dtype=np.float64)
    except (TypeError, ValueError):
        raise PatchError('%s must be numbers' % name) from None
    if c.ndim == 2:
        c = c[None]
    if c.ndim != 3 or c.shape[1] < 2 or c.shape[2] < 1:
        raise PatchError('%s must have shape (n+1, D) or (P, n+1, D) with n >= 1, got %s'
                         % (name, c.shape))
    if not np.all(np.isfinite(c)):
        raise PatchError('%s must be finite' % name)
    return c


def coons_net(top: ArrayLike, bottom: ArrayLike, left: ArrayLike, right: ArrayLike,
              tolerance: float = 1e-9) -> np.ndarray:
    """The tensor-product net of the bilinearly blended Coons patch of four
    Bezier boundary curves of one degree ``n``.

    ``net[i, j] = (1 - j/n) C1_i + (j/n) C2_i + (1 - i/n) D1_j + (i/n) D2_j
    - L_ij`` with ``L`` the bilinear interpolation of the corners at
    ``(i/n, j/n)``: the Coons formula with each term written as a degree
    ``(n, n)`` tensor patch (linear blends elevated).

    Parameters
    ----------
    top, bottom : (n+1, D) or (P, n+1, D) array_like of float
        ``C1(u)`` at ``v = 0`` and ``C2(u)`` at ``v = 1``, both running with
        ``u`` from 0 to 1.
    left, right : (n+1, D) or (P, n+1, D) array_like of float
        ``D1(v)`` at ``u = 0`` and ``D2(v)`` at ``u = 1``, both running with
        ``v`` from 0 to 1.
    tolerance : float
        Corners shared by two curves must agree within ``tolerance`` times
        the boundary's size (the curves' own corner points are used).

    Returns
    -------
    (P, n+1, n+1, D) float64 ndarray

    Raises
    ------
    PatchError
        Shapes that differ, or boundary curves that do not meet at the
        corners.

    >>> line = lambda a, b: np.linspace(a, b, 4)
    >>> net = coons_net(line([0, 0], [3, 0]), line([0, 3], [3, 3]),
    ...                 line([0, 0], [0, 3]), line([3, 0], [3, 3]))
    >>> net[0, 1, 2].tolist()                        # a square: the uniform grid
    [1.0, 2.0]
    """
    c1, c2 = _curves(top, 'top'), _curves(bottom, 'bottom')
    d1, d2 = _curves(left, 'left'), _curves(right, 'right')
    shapes = {c1.shape, c2.shape, d1.shape, d2.shape}
    if len(shapes) != 1:
        raise PatchError('boundary curves must have one shape, got %s' % sorted(shapes))
    P, n1, D = c1.shape
    _degree(n1 - 1)
    scale = max(1.0, float(np.abs(np.concatenate([c1, c2, d1, d2], 1)).max()))
    for a, b, what in ((c1[:, 0], d1[:, 0], 'top-left'), (c1[:, -1], d2[:, 0], 'top-right'),
                       (c2[:, 0], d1[:, -1], 'bottom-left'),
                       (c2[:, -1], d2[:, -1], 'bottom-right')):
        if np.abs(a - b).max() > tolerance * scale:
            raise PatchError('boundary curves do not meet at the %s corner' % what)
    n = n1 - 1
    s = np.arange(n1) / n
    S = s[:, None, None]            # i (u) as rows, broadcast over j and D
    T = s[None, :, None]            # j (v)
    c00, c10 = c1[:, 0][:, None, None], c1[:, -1][:, None, None]
    c01, c11 = c2[:, 0][:, None, None], c2[:, -1][:, None, None]
    net = ((1 - T) * c1[:, :, None] + T * c2[:, :, None]
           + (1 - S) * d1[:, None, :] + S * d2[:, None, :]
           - ((1 - S) * (1 - T) * c00 + S * (1 - T) * c10 + (1 - S) * T * c01 + S * T * c11))
    # the boundary rows are the curves themselves, exactly
    net[:, :, 0], net[:, :, -1] = c1, c2
    net[:, 0, :], net[:, -1, :] = d1, d2
    return net


def mesh_patch_nets(boundary: ArrayLike) -> np.ndarray:
    """Bicubic tensor nets of SVG 2 mesh patches given by their boundary.

    Parameters
    ----------
    boundary : (P, 12, D) array_like of float
        The closed boundary of each patch as four cubic Bezier edges in
        ``meshpatch`` order: ``b[0]`` the top-left corner, ``b[0..3]`` the
        top edge (left to right), ``b[3..6]`` the right edge (top to
        bottom), ``b[6..9]`` the bottom edge (right to left), ``b[9..11],
        b[0]`` the left edge (bottom to top).  Corners: ``S(0,0) = b[0]``,
        ``S(1,0) = b[3]``, ``S(1,1) = b[6]``, ``S(0,1) = b[9]``.

    Returns
    -------
    (P, 4, 4, D) float64 ndarray
        Nets of the Coons patches (:func:`coons_net`), ``u`` along the top
        edge and ``v`` down the left edge.

    >>> sq = [[0, 0], [1, 0], [2, 0], [3, 0], [3, 1], [3, 2], [3, 3],
    ...       [2, 3], [1, 3], [0, 3], [0, 2], [0, 1]]
    >>> mesh_patch_nets([sq])[0, 2, 1].tolist()
    [2.0, 1.0]
    """
    try:
        b = np.array(boundary, dtype=np.float64)
    except (TypeError, ValueError):
        raise PatchError('patch boundaries must be numbers') from None
    if b.ndim != 3 or b.shape[1] != 12 or b.shape[2] < 1:
        raise PatchError('patch boundaries must have shape (P, 12, D), got %s' % (b.shape,))
    if not np.all(np.isfinite(b)):
        raise PatchError('patch boundaries must be finite')
    top = b[:, 0:4]
    right = b[:, 3:7]
    bottom = b[:, [9, 8, 7, 6]]
    left = b[:, [0, 11, 10, 9]]
    return coons_net(top, bottom, left, right, tolerance=np.inf)


def _casteljau_split(c, t, axis):
    """Split nets (P, m+1, n+1, D) at per-patch t (P,) along axis 1 (u) or 2
    (v): returns (left, right)."""
    c = np.moveaxis(c, axis, 1)
    k = c.shape[1]
    tt = t.reshape((-1,) + (1,) * (c.ndim - 1))
    left = np.empty_like(c)
    right = np.empty_like(c)
    pts = c
    left[:, 0] = pts[:, 0]
    right[:, k - 1] = pts[:, k - 1]
    for r in range(1, k):
        pts = (1.0 - tt) * pts[:, :-1] + tt * pts[:, 1:]
        left[:, r] = pts[:, 0]
        right[:, k - 1 - r] = pts[:, -1]
    return np.moveaxis(left, 1, axis), np.moveaxis(right, 1, axis)


def split_patches(net: ArrayLike, t: ArrayLike = 0.5,
                  direction: str = 'u') -> Tuple[np.ndarray, np.ndarray]:
    """Split patches at a parameter value (de Casteljau), exactly.

    Parameters
    ----------
    net : (P, m+1, n+1, D) array_like of float
    t : float or (P,) array_like of float in [0, 1]
    direction : {'u', 'v'}

    Returns
    -------
    (left, right) : two (P, m+1, n+1, D) float64 ndarrays
        The parts with parameter in ``[0, t]`` and ``[t, 1]``, each again on
        ``[0, 1]``.

    >>> a, b = split_patches(bilinear_net([[0, 0], [4, 0], [0, 1], [4, 1]]), 0.25)
    >>> a[0, -1, 0].tolist(), b[0, 0, 1].tolist()
    ([1.0, 0.0], [1.0, 1.0])
    """
    c, _ = as_nets(net)
    if direction not in ('u', 'v'):
        raise PatchError("direction must be 'u' or 'v', got %r" % (direction,))
    ta = np.broadcast_to(_params(t, 't'), (c.shape[0],)).astype(np.float64)
    return _casteljau_split(c, ta, 1 if direction == 'u' else 2)


def subpatches(net: ArrayLike, u0: ArrayLike, u1: ArrayLike, v0: ArrayLike,
               v1: ArrayLike) -> np.ndarray:
    """The parts of patches over parameter rectangles, each reparameterized
    to ``[0, 1]^2`` (exact).

    Parameters
    ----------
    net : (P, m+1, n+1, D) array_like of float
    u0, u1, v0, v1 : (P,) array_like of float
        ``0 <= u0 < u1 <= 1`` and ``0 <= v0 < v1 <= 1`` per patch.

    Returns
    -------
    (P, m+1, n+1, D) float64 ndarray

    >>> q = subpatches(bilinear_net([[0, 0], [4, 0], [0, 4], [4, 4]]), [0.25], [0.5], [0], [1])
    >>> q[0, :, 0].tolist()
    [[1.0, 0.0], [2.0, 0.0]]
    """
    c, _ = as_nets(net)
    P = c.shape[0]
    lims = [np.broadcast_to(_params(x, name), (P,)).astype(np.float64)
            for x, name in ((u0, 'u0'), (u1, 'u1'), (v0, 'v0'), (v1, 'v1'))]
    a0, a1, b0, b1 = lims
    if np.any(a1 <= a0) or np.any(b1 <= b0):
        raise PatchError('sub-patch ranges need u0 < u1 and v0 < v1')
    for lo, hi, axis in ((a0, a1, 1), (b0, b1, 2)):
        _, c = _casteljau_split(c, lo, axis)                    # [lo, 1]
        frac = np.where(lo < 1, (hi - lo) / np.where(lo < 1, 1 - lo, 1.0), 1.0)
        c, _ = _casteljau_split(c, np.clip(frac, 0.0, 1.0), axis)
    return c


def derivative_bounds(net: ArrayLike) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bounds on the second partial derivatives of patches.

    Returns
    -------
    (A, B, C) : three (P,) float64 ndarrays
        ``|S_uu| <= A``, ``|S_vv| <= B`` and ``|S_uv| <= C`` everywhere on
        the patch (Euclidean norms): ``A = m(m-1) max |P_{i+2,j} - 2
        P_{i+1,j} + P_{ij}|``, ``B`` likewise along ``v``, ``C = m n max
        |P_{i+1,j+1} - P_{i+1,j} - P_{i,j+1} + P_{ij}|``.

    >>> A, B, C = derivative_bounds(bilinear_net([[0, 0], [1, 0], [0, 1], [1, 2]]))
    >>> A.tolist(), B.tolist(), C.tolist()
    ([0.0], [0.0], [1.0])
    """
    c, _ = as_nets(net)
    P, m1, n1, D = c.shape
    m, n = m1 - 1, n1 - 1
    zero = np.zeros(P)
    A = (m * (m - 1) * np.linalg.norm(np.diff(c, 2, axis=1), axis=-1).reshape(P, -1).max(1)
         if m >= 2 else zero)
    B = (n * (n - 1) * np.linalg.norm(np.diff(c, 2, axis=2), axis=-1).reshape(P, -1).max(1)
         if n >= 2 else zero)
    C = (m * n * np.linalg.norm(np.diff(np.diff(c, axis=1), axis=2), axis=-1)
         .reshape(P, -1).max(1) if m >= 1 and n >= 1 else zero)
    return A, B, C


def linearization_error(net: ArrayLike, nu: ArrayLike, nv: ArrayLike) -> np.ndarray:
    """Bound on the distance between patches and their triangulations on a
    uniform ``nu x nv`` grid (each grid cell split along the diagonal from
    its ``(u0, v0)`` corner to its ``(u1, v1)`` corner, the triangles
    interpolating the parameters linearly).

    Returns
    -------
    (P,) float64 ndarray
        ``A / (8 nu^2) + B / (8 nv^2) + C / (4 nu nv)`` with ``A, B, C`` from
        :func:`derivative_bounds`: every point of a triangle is within this
        distance of the patch point at the same (interpolated) parameters.

    >>> linearization_error(bilinear_net([[0, 0], [1, 0], [0, 1], [1, 2]]), 2, 2).tolist()
    [0.0625]
    """
    A, B, C = derivative_bounds(net)
    nu = np.asarray(nu, dtype=np.float64)
    nv = np.asarray(nv, dtype=np.float64)
    return A / (8 * nu * nu) + B / (8 * nv * nv) + C / (4 * nu * nv)


def grid_counts(net: ArrayLike, tolerance: float,
                max_count: int = 4096) -> Tuple[np.ndarray, np.ndarray]:
    """Grid sizes ``(nu, nv)`` per patch whose triangulation is within
    ``tolerance`` of the patch (:func:`linearization_error`).

    Each of the three terms of the bound gets a third of the tolerance.

    Parameters
    ----------
    net : (P, m+1, n+1, D) array_like of float
    tolerance : float
        Positive distance in the net's units.
    max_count : int
        Largest count per direction; patches needing more raise.

    Returns
    -------
    (nu, nv) : two (P,) int64 ndarrays, each >= 1

    Raises
    ------
    PatchError
        Non-positive tolerance.
    LimitError
        A patch needs more than ``max_count`` cells in one direction (split
        it first, e.g. with :func:`split_patches`).

    >>> grid_counts(bilinear_net([[0, 0], [1, 0], [0, 1], [1, 2]]), 0.01)
    (array([9]), array([9]))
    """
    try:
        tol = float(tolerance)
    except (TypeError, ValueError):
        raise PatchError('tolerance must be a number') from None
    if not tol > 0 or not math.isfinite(tol):
        raise PatchError('tolerance must be positive and finite')
    A, B, C = derivative_bounds(net)
    third = tol / 3.0
    nu = np.ceil(np.sqrt(A / (8 * third))).clip(1)
    nv = np.ceil(np.sqrt(B / (8 * third))).clip(1)
    # the twist term C / (4 nu nv) <= tol/3: grow both counts by one factor
    need = C / (4 * third)
    grow = np.sqrt(np.maximum(need / (nu * nv), 1.0))
    nu = np.ceil(nu * grow - 1e-9).clip(1)
    nv = np.ceil(nv * grow - 1e-9).clip(1)
    if len(nu) and max(nu.max(), nv.max()) > max_count:
        raise LimitError('a patch needs a %d x %d grid for tolerance %g (limit %d per side)'
                         % (nu.max(), nv.max(), tol, max_count))
    return nu.astype(np.int64), nv.astype(np.int64)


def net_bounds(net: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
    """Axis-aligned boxes of the control nets (which contain the patches).

    Returns
    -------
    (lo, hi) : two (P, D) float64 ndarrays

    >>> lo, hi = net_bounds(bilinear_net([[0, 0], [1, 0], [0, 1], [1, 2]]))
    >>> lo.tolist(), hi.tolist()
    ([[0.0, 0.0]], [[1.0, 2.0]])
    """
    c, _ = as_nets(net)
    flat = c.reshape(c.shape[0], -1, c.shape[-1])
    return flat.min(axis=1), flat.max(axis=1)
