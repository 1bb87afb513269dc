r"""SVG 2 mesh gradients: the colours of a mesh of Coons patches at pixel
centres.

This is the pixel half of ``<meshgradient>``; the SVG half (``meshrow``/
``meshpatch``/``stop`` path data into patch boundaries and corner colours)
is :mod:`raster.parser.mesh`, and the renderer maps the patches to device
space and clips them to the painted shape (:func:`raster.renderer.paint.mesh_colors`).  The entry point is
:func:`mesh_gradient`.

Input, all in device space:

* ``patches`` -- ``(P, 12, 2)`` float64: the closed boundary of every patch
  as four cubic Bezier edges in ``meshpatch`` order: point 0 the top-left
  corner; points 0-3 the top edge (left to right), 3-6 the right edge (top
  to bottom), 6-9 the bottom edge (right to left), 9, 10, 11, 0 the left
  edge (bottom to top).  A line edge ``l``/``L`` is the cubic with its
  control points at 1/3 and 2/3.  Patches come in row-major mesh order.
* ``colors`` -- ``(P, 4, 4)`` float: straight RGBA in [0, 1] at the corners
  0, 3, 6, 9 (the corner where each ``stop``'s edge starts: top-left,
  top-right, bottom-right, bottom-left).

Painting (SVG 2, "Painting a mesh patch"): the corner colours are placed on
the unit square and interpolated there -- ``'bilinear'``, or ``'bicubic'``
with the monotone derivatives of the specification (below) -- and the unit
square is mapped onto the patch by the Coons formula ``S = S_C + S_D -
S_B`` (:mod:`raster.geometry.patches`).  A pixel gets the colour of the
patch point on its centre; later patches paint over earlier ones; where a
patch folds over itself the part with the larger ``v``, then the larger
``u``, is on top (the rule of PDF Coons-patch shadings).  Colours are
interpolated as straight RGBA and premultiplied afterwards, as the
renderer's other gradients do.

Accuracy (``tolerance``, device pixels): every patch is cut into a uniform
grid of cells whose two triangles lie within ``tolerance / 2`` of the patch
(:func:`raster.geometry.patches.grid_counts`, a rigorous bound from the
control net); a pixel centre inside a triangle, or within ``tolerance / 2``
of one (which closes the cracks between patches cut differently), takes
the colour of the patch at the parameters the triangle interpolates there.
So each painted pixel shows the exact colour of a patch point within
``tolerance`` of its centre, and every centre deeper than ``tolerance``
inside the mesh is painted.

Work is bounded: patches needing more than :data:`MAX_PIECE_CELLS` cells are
split in four (exactly, de Casteljau) and the parts whose control nets miss
the window are dropped, so a zoomed-in mesh costs about what its visible
part does; at most :data:`MAX_MESH_CELLS` cells in all (else
:class:`raster.errors.LimitError`).  Everything runs as array operations
over all cells and candidate pixels at once (in bounded chunks).

Bicubic interpolation (SVG 2): along every row and every column of mesh
corners ``p_0 .. p_n`` with colour values ``c_k`` (each channel alone) the
secants are ``Delta_k = (c_{k+1} - c_k) / |p_{k+1} - p_k|`` (0 where the
points coincide); the derivative at an inner corner is ``delta_k =
(Delta_{k-1} + Delta_k) / 2``, set to 0 where the secants differ in sign,
and limited to ``3 |Delta_{k-1}|`` and ``3 |Delta_k|`` (a monotone cubic);
at the ends ``delta_0 = 2 Delta_0 - delta_1`` and ``delta_n = 2
Delta_{n-1} - delta_{n-1}`` when the row has inner corners (the
specification's text says "n > 2"; we read it as "there is a delta_1",
which its formulas need), else ``delta_0 = delta_1 = Delta_0``.  In a patch
the colour is the bicubic Hermite interpolant of the corner colours with
``dc/du = delta_x * |top (or bottom) edge chord|``, ``dc/dv = delta_y *
|left (or right) edge chord|`` and zero cross derivatives.

>>> sq = np.array([[[0, 0], [1, 0], [2, 0], [3, 0], [3, 1], [3, 2], [3, 3],
...                 [2, 3], [1, 3], [0, 3], [0, 2], [0, 1]]], float)
>>> red_blue = np.array([[[1, 0, 0, 1], [0, 0, 1, 1], [0, 0, 1, 1], [1, 0, 0, 1]]], float)
>>> px = mesh_gradient(sq, red_blue, (0, 0, 3, 1))
>>> np.round(px[0, :, [0, 2]].astype(float), 4).tolist()    # red, blue across u = x / 3
[[0.8333, 0.5, 0.1667], [0.1667, 0.5, 0.8333]]
"""

import math
from typing import Optional, Tuple

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LimitError, RasterError
from ..geometry import patches as P
from .. import limits

__all__ = ['MeshError', 'MAX_MESH_CELLS', 'MAX_PIECE_CELLS', 'INTERPOLATIONS', 'mesh_gradient',
           'color_nets', 'corner_grid', 'bicubic_slopes', 'mesh_cells']

#: Interpolation types of ``meshgradient/@type``.
INTERPOLATIONS = ('bilinear', 'bicubic')

#: Most cells of one patch piece before it is split (for culling).
MAX_PIECE_CELLS = 64 * 64

#: Most cells of a whole mesh gradient call.
MAX_MESH_CELLS = 1 << 23

#: Most candidate (pixel, triangle) pairs examined at once.
_CHUNK = 1 << 21

#: Largest window side.
MAX_WINDOW_SIDE = 100_000


class MeshError(RasterError, ValueError):
    """Malformed mesh-gradient input: patches or colours of the wrong shape
    or not finite, an unknown interpolation, a bad window, shape or
    tolerance."""


def _patches(patches, colors):
    try:
        b = np.array(patches, dtype=np.float64)
        c = np.array(colors, dtype=np.float64)
    except (TypeError, ValueError):
        raise MeshError('mesh patches and colours must be numbers') from None
    if b.ndim != 3 or b.shape[1:] != (12, 2):
        raise MeshError('mesh patches must have shape (P, 12, 2), got %s' % (b.shape,))
    if c.shape != (b.shape[0], 4, 4):
        raise MeshError('mesh colours must have shape (%d, 4, 4), got %s'
                        % (b.shape[0], c.shape))
    if not (np.all(np.isfinite(b)) and np.all(np.isfinite(c))):
        raise MeshError('mesh patches and colours must be finite')
    return b, np.clip(c, 0.0, 1.0)


def _shape(shape, n):
    try:
        rows, cols = (int(x) for x in shape)
    except (TypeError, ValueError):
        raise MeshError('shape must be (rows, columns)') from None
    if rows < 1 or cols < 1 or rows * cols != n:
        raise MeshError('shape %s does not hold %d patches' % ((rows, cols), n))
    return rows, cols


def corner_grid(patches: ArrayLike, colors: ArrayLike,
                shape: Tuple[int, int]) -> Tuple[np.ndarray, np.ndarray]:
    """The mesh corners and their colours as grids.

    Parameters
    ----------
    patches : (P, 12, 2) array_like of float
    colors : (P, 4, 4) array_like of float
    shape : (rows, cols)
        ``rows * cols == P``; patch ``r * cols + c`` is in row ``r``,
        column ``c``.

    Returns
    -------
    points : (rows+1, cols+1, 2) float64 ndarray
    colours : (rows+1, cols+1, 4) float64 ndarray
        Corner ``[r, c]`` is the top-left corner of patch ``(r, c)`` (the
        last row and column from the bottom and right corners).
    """
    b, c = _patches(patches, colors)
    rows, cols = _shape(shape, len(b))
    b = b.reshape(rows, cols, 12, 2)
    c = c.reshape(rows, cols, 4, 4)
    pts = np.empty((rows + 1, cols + 1, 2))
    col = np.empty((rows + 1, cols + 1, 4))
    pts[:-1, :-1], col[:-1, :-1] = b[:, :, 0], c[:, :, 0]
    pts[:-1, -1], col[:-1, -1] = b[:, -1, 3], c[:, -1, 1]
    pts[-1, :-1], col[-1, :-1] = b[-1, :, 9], c[-1, :, 3]
    pts[-1, -1], col[-1, -1] = b[-1, -1, 6], c[-1, -1, 2]
    return pts, col


def bicubic_slopes(points: ArrayLike, values: ArrayLike) -> np.ndarray:
    """Monotone colour derivatives along lines of mesh corners (SVG 2).

    Parameters
    ----------
    points : (L, n+1, 2) array_like of float
        ``L`` lines of ``n + 1`` corner points each.
    values : (L, n+1, K) array_like of float
        Colour channels at the points.

    Returns
    -------
    (L, n+1, K) float64 ndarray
        ``delta_k``: derivative of each channel per unit length along the
        line (see the module notes).

    >>> bicubic_slopes([[[0, 0], [1, 0], [2, 0]]], [[[0.0], [0.5], [1.0]]]).ravel().tolist()
    [0.5, 0.5, 0.5]
    """
    p = np.asarray(points, dtype=np.float64)
    c = np.asarray(values, dtype=np.float64)
    n = p.shape[1] - 1
    if n < 1:
        raise MeshError('a line of corners needs at least two points')
    dist = np.linalg.norm(np.diff(p, axis=1), axis=2)[..., None]            # (L, n, 1)
    with np.errstate(divide='ignore', invalid='ignore'):
        sec = np.where(dist > 0, np.diff(c, axis=1) / dist, 0.0)            # (L, n, K)
    d = np.empty_like(c)
    if n == 1:
        d[:, 0] = d[:, 1] = sec[:, 0]
        return d
    a, b = sec[:, :-1], sec[:, 1:]
    inner = 0.5 * (a + b)
    inner = np.where(a * b < 0, 0.0, inner)
    inner = np.where(np.abs(inner) > np.abs(3 * a), 3 * a, inner)
    inner = np.where(np.abs(inner) > np.abs(3 * b), 3 * b, inner)
    d[:, 1:-1] = inner
    d[:, 0] = 2 * sec[:, 0] - d[:, 1]
    d[:, -1] = 2 * sec[:, -1] - d[:, -2]
    return d


def color_nets(patches: ArrayLike, colors: ArrayLike, interpolation: str = 'bilinear',
               shape: Optional[Tuple[int, int]] = None) -> np.ndarray:
    """Colour patches in the unit square as tensor-product Bezier nets in
    RGBA space.

    Parameters
    ----------
    patches : (P, 12, 2) array_like of float
    colors : (P, 4, 4) array_like of float
    interpolation : {'bilinear', 'bicubic'}
    shape : (rows, cols), optional
        Needed for ``'bicubic'`` (derivatives come from neighbouring
        patches).

    Returns
    -------
    (P, 2, 2, 4) or (P, 4, 4, 4) float64 ndarray
        Evaluate with :func:`raster.geometry.patches.tensor_eval` at the
        patch parameters ``(u, v)`` for the straight RGBA colour.
    """
    b, c = _patches(patches, colors)
    if interpolation not in INTERPOLATIONS:
        raise MeshError('mesh interpolation must be bilinear or bicubic, got %r'
                        % (interpolation,))
    if interpolation == 'bilinear':
        return P.bilinear_net(c[:, [0, 1, 3, 2]])
    if shape is None:
        raise MeshError('bicubic mesh interpolation needs the mesh shape (rows, cols)')
    rows, cols = _shape(shape, len(b))
    g, gc = corner_grid(b, c, (rows, cols))
    dx = bicubic_slopes(g, gc)                                                  # along rows
    dy = np.swapaxes(bicubic_slopes(np.swapaxes(g, 0, 1), np.swapaxes(gc, 0, 1)), 0, 1)
    lu = np.linalg.norm(np.diff(g, axis=1), axis=2)[..., None]     # (rows+1, cols, 1)
    lv = np.linalg.norm(np.diff(g, axis=0), axis=2)[..., None]     # (rows, cols+1, 1)
    r, k = np.divmod(np.arange(len(b)), cols)
    val = np.empty((len(b), 2, 2, 4))
    du = np.empty_like(val)
    dv = np.empty_like(val)
    for a in (0, 1):              # corner u = a, v = e: grid point (r + e, k + a)
        for e in (0, 1):
            val[:, a, e] = gc[r + e, k + a]
            du[:, a, e] = dx[r + e, k + a] * lu[r + e, k]
            dv[:, a, e] = dy[r + e, k + a] * lv[r, k + a]
    return P.hermite_net(val, du, dv)


def _window(window):
    try:
        x0, y0, w, h = (int(v) for v in window)
        if [x0, y0, w, h] != [float(v) for v in window]:
            raise ValueError
    except (TypeError, ValueError):
        raise MeshError('window must be four integers (x0, y0, width, height)') from None
    if w < 1 or h < 1 or w > MAX_WINDOW_SIDE or h > MAX_WINDOW_SIDE:
        raise MeshError('window size %d x %d is out of range' % (w, h))
    if w * h > limits.current().max_pixels:
        raise LimitError('mesh gradient window of %d pixels exceeds max_pixels %d'
                         % (w * h, limits.current().max_pixels))
    return x0, y0, w, h


def mesh_cells(nets: ArrayLike, tolerance: float, window: Tuple[int, int, int, int]):
    """Cut patches into pieces small enough to grid, dropping pieces outside
    the window.

    Parameters
    ----------
    nets : (P, m+1, n+1, 2) float64 ndarray
        Patch nets in device space.
    tolerance : float
        Distance bound of the triangulation (device pixels).
    window : (x0, y0, w, h)

    Returns
    -------
    piece_patch : (Q,) int64
        The patch of each piece.
    box : (Q, 4) float64
        Parameter rectangles ``(u0, u1, v0, v1)`` of the pieces.
    piece_nets : (Q, m+1, n+1, 2) float64
    nu, nv : (Q,) int64
        Grid counts meeting ``tolerance``.
    """
    x0, y0, w, h = window
    nets = np.asarray(nets, dtype=np.float64)
    pid = np.arange(len(nets))
    box = np.tile([0.0, 1.0, 0.0, 1.0], (len(nets), 1))
    done = []
    total = 0
    for level in range(24):
        lo, hi = P.net_bounds(nets)
        inside = ((hi[:, 0] >= x0 - tolerance) & (lo[:, 0] <= x0 + w + tolerance)
                  & (hi[:, 1] >= y0 - tolerance) & (lo[:, 1] <= y0 + h + tolerance))
        nets, pid, box = nets[inside], pid[inside], box[inside]
        lo, hi = lo[inside], hi[inside]
        if not len(nets):
            break
        if len(nets) > MAX_MESH_CELLS // 16:
            raise LimitError('mesh gradient needs more than %d pieces at tolerance %g'
                             % (MAX_MESH_CELLS // 16, tolerance))
        nu, nv = P.grid_counts(nets, tolerance, max_count=1 << 30)
        small = (nu * nv <= MAX_PIECE_CELLS) | (level == 23)
        # a piece wholly inside the window gains nothing from splitting
        within = ((lo[:, 0] >= x0) & (hi[:, 0] <= x0 + w) & (lo[:, 1] >= y0)
                  & (hi[:, 1] <= y0 + h))
        keep = small | (within & (nu * nv <= MAX_MESH_CELLS))
        total += int((nu[keep] * nv[keep]).sum())
        if total > MAX_MESH_CELLS:
            raise LimitError('mesh gradient needs more than %d cells at tolerance %g'
                             % (MAX_MESH_CELLS, tolerance))
        done.append((pid[keep], box[keep], nets[keep], nu[keep], nv[keep]))
        split = ~keep
        if not split.any():
            break
        nets, pid, box = nets[split], pid[split], box[split]
        a, b = P.split_patches(nets, 0.5, 'u')
        aa, ab = P.split_patches(a, 0.5, 'v')
        ba, bb = P.split_patches(b, 0.5, 'v')
        u0, u1, v0, v1 = box.T
        um, vm = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
        nets = np.concatenate([aa, ab, ba, bb])
        pid = np.tile(pid, 4)
        box = np.concatenate([np.stack(q, 1) for q in ((u0, um, v0, vm), (u0, um, vm, v1),
                                                       (um, u1, v0, vm), (um, u1, vm, v1))])
    if not done:
        z = np.zeros(0, np.int64)
        return z, np.zeros((0, 4)), np.zeros((0,) + nets.shape[1:]), z, z
    return tuple(np.concatenate([d[k] for d in done]) for k in range(5))


def _grid_points(piece_nets, nu, nv):
    """Vertices of every piece's uniform grid: local (s, t), the piece of
    each vertex and the offset of each piece's first vertex."""
    cnt = (nu + 1) * (nv + 1)
    first = np.concatenate([[0], np.cumsum(cnt)[:-1]])
    owner = np.repeat(np.arange(len(nu)), cnt)
    k = np.arange(int(cnt.sum())) - first[owner]
    i, j = np.divmod(k, nv[owner] + 1)
    s = i / nu[owner]
    t = j / nv[owner]
    return s, t, owner, first


def _triangles(nu, nv, first):
    """Vertex indices (T, 3) of the two triangles of every grid cell."""
    cells = nu * nv
    owner = np.repeat(np.arange(len(nu)), cells)
    k = np.arange(int(cells.sum())) - np.repeat(np.concatenate([[0], np.cumsum(cells)[:-1]]),
                                                cells)
    i, j = np.divmod(k, nv[owner])
    stride = nv[owner] + 1
    v00 = first[owner] + i * stride + j
    v10 = v00 + stride
    v01 = v00 + 1
    v11 = v10 + 1
    return np.concatenate([np.stack([v00, v10, v11], 1), np.stack([v00, v11, v01], 1)])


def _seg_closest(px, py, ax, ay, bx, by):
    """Squared distance from points to segments and the segment parameter."""
    dx, dy = bx - ax, by - ay
    ll = dx * dx + dy * dy
    with np.errstate(divide='ignore', invalid='ignore'):
        s = np.where(ll > 0, ((px - ax) * dx + (py - ay) * dy) / ll, 0.0)
    s = np.clip(s, 0.0, 1.0)
    ex, ey = ax + s * dx - px, ay + s * dy - py
    return ex * ex + ey * ey, s


def mesh_gradient(patches: ArrayLike, colors: ArrayLike, window: Tuple[int, int, int, int],
                  interpolation: str = 'bilinear', shape: Optional[Tuple[int, int]] = None,
                  tolerance: float = 0.1) -> np.ndarray:
    """Paint a mesh gradient: premultiplied colours at the pixel centres of a
    window.

    Parameters
    ----------
    patches : (P, 12, 2) array_like of float
        Patch boundaries in device space, row-major mesh order (module
        notes for the point order).
    colors : (P, 4, 4) array_like of float
        Straight RGBA in [0, 1] at the corners 0, 3, 6, 9 of each patch
        (values outside are clamped).
    window : (x0, y0, width, height) ints
        Output pixel ``[i, j]`` has its centre at ``(x0 + j + 0.5, y0 + i +
        0.5)``.
    interpolation : {'bilinear', 'bicubic'}
        ``meshgradient/@type``.
    shape : (rows, cols), optional
        Mesh shape, ``rows * cols == P``; required for ``'bicubic'``.
    tolerance : float
        Device pixels, > 0: each painted pixel has the colour of a patch
        point within ``tolerance`` of its centre (module notes).

    Returns
    -------
    (height, width, 4) float32 ndarray
        Premultiplied RGBA; transparent where no patch covers the centre.

    Raises
    ------
    MeshError
        Malformed input.
    LimitError
        The mesh needs more than :data:`MAX_MESH_CELLS` cells.
    """
    b, c = _patches(patches, colors)
    x0, y0, w, h = _window(window)
    try:
        tol = float(tolerance)
    except (TypeError, ValueError):
        raise MeshError('tolerance must be a number') from None
    if not (tol > 0 and math.isfinite(tol)):
        raise MeshError('tolerance must be positive and finite')
    if np.abs(b).max(initial=0.0) > 1e9:
        raise MeshError('mesh coordinates exceed 1e9 device pixels')
    cnets = color_nets(b, c, interpolation, shape)
    out = np.zeros((h, w, 4), np.float32)
    if len(b) == 0:
        return out
    nets = P.mesh_patch_nets(b)
    half = tol / 2
    pid, box, pnets, nu, nv = mesh_cells(nets, half, (x0, y0, w, h))
    if len(pid) == 0:
        return out
    s, t, owner, first = _grid_points(pnets, nu, nv)
    xy = P.tensor_points(pnets, owner, s, t)                                  # (V, 2)
    U = box[owner, 0] + s * (box[owner, 1] - box[owner, 0])
    V = box[owner, 2] + t * (box[owner, 3] - box[owner, 2])
    vpatch = pid[owner]
    tri = _triangles(nu, nv, first)
    best = np.full(h * w, -1, np.int64)
    bu = np.zeros(h * w)
    bv = np.zeros(h * w)
    bp = np.zeros(h * w, np.int64)
    X, Y = xy[:, 0], xy[:, 1]
    tx, ty = X[tri], Y[tri]                                                   # (T, 3)
    area = ((tx[:, 1] - tx[:, 0]) * (ty[:, 2] - ty[:, 0])
            - (ty[:, 1] - ty[:, 0]) * (tx[:, 2] - tx[:, 0]))
    # columns / rows of the centres within `half` of each triangle's box
    c0 = np.maximum(np.ceil(tx.min(1) - half - 0.5 - x0), 0)
    c1 = np.minimum(np.floor(tx.max(1) + half - 0.5 - x0), w - 1)
    r0 = np.maximum(np.ceil(ty.min(1) - half - 0.5 - y0), 0)
    r1 = np.minimum(np.floor(ty.max(1) + half - 0.5 - y0), h - 1)
    nx = np.maximum(c1 - c0 + 1, 0).astype(np.int64)
    ny = np.maximum(r1 - r0 + 1, 0).astype(np.int64)
    live = np.flatnonzero((nx * ny > 0) & (area != 0))
    counts = (nx * ny)[live]
    ends = np.cumsum(counts)
    start = 0
    while start < len(live):
        base = ends[start - 1] if start else 0
        stop = max(int(np.searchsorted(ends, base + _CHUNK, side='right')), start + 1)
        sel = live[start:stop]
        _paint_chunk(sel, counts[start:stop], tri, tx, ty, area, c0, r0, nx, x0, y0, w, half,
                     U, V, vpatch, best, bu, bv, bp)
        start = stop
    hit = np.flatnonzero(best >= 0)
    if len(hit):
        col = P.tensor_points(cnets, bp[hit], bu[hit], bv[hit])
        col = np.clip(col, 0.0, 1.0)
        col[:, :3] *= col[:, 3:]
        out.reshape(-1, 4)[hit] = col.astype(np.float32)
    return out


def _paint_chunk(sel, counts, tri, tx, ty, area, c0, r0, nx, x0, y0, w, half, U, V, vpatch,
                 best, bu, bv, bp):
    """Candidate centres of the triangles ``sel``; keeps the winner per
    pixel in ``best`` (key), ``bu``, ``bv``, ``bp``."""
    k = np.repeat(np.arange(len(sel)), counts)
    local = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
    T = sel[k]
    col = c0[T].astype(np.int64) + local % nx[T]
    row = r0[T].astype(np.int64) + local // nx[T]
    px = x0 + col + 0.5
    py = y0 + row + 0.5
    ax, bx, cx = tx[T, 0], tx[T, 1], tx[T, 2]
    ay, by, cy = ty[T, 0], ty[T, 1], ty[T, 2]
    A = area[T]
    # barycentric coordinates (exact inside test)
    l1 = ((px - ax) * (cy - ay) - (py - ay) * (cx - ax)) / A
    l2 = ((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / A
    l0 = 1.0 - l1 - l2
    inside = (l0 >= 0) & (l1 >= 0) & (l2 >= 0)
    # outside: within `half` of the triangle's boundary, parameters of the
    # closest boundary point
    out_i = np.flatnonzero(~inside)
    if len(out_i):
        qx, qy = px[out_i], py[out_i]
        verts = [(ax[out_i], ay[out_i]), (bx[out_i], by[out_i]), (cx[out_i], cy[out_i])]
        best_d = np.full(len(out_i), np.inf)
        bl = np.zeros((len(out_i), 3))
        for e, (i, j) in enumerate(((0, 1), (1, 2), (2, 0))):
            d2, s = _seg_closest(qx, qy, *verts[i], *verts[j])
            better = d2 < best_d
            best_d = np.where(better, d2, best_d)
            lam = np.zeros((len(out_i), 3))
            lam[:, i] = 1 - s
            lam[:, j] = s
            bl[better] = lam[better]
        near = best_d <= half * half
        l0[out_i], l1[out_i], l2[out_i] = bl[:, 0], bl[:, 1], bl[:, 2]
        inside[out_i[near]] = True
    ok = np.flatnonzero(inside)
    if not len(ok):
        return
    T, l0, l1, l2 = T[ok], l0[ok], l1[ok], l2[ok]
    vi = tri[T]
    uu = l0 * U[vi[:, 0]] + l1 * U[vi[:, 1]] + l2 * U[vi[:, 2]]
    vv = l0 * V[vi[:, 0]] + l1 * V[vi[:, 1]] + l2 * V[vi[:, 2]]
    pp = vpatch[vi[:, 0]]
    uu, vv = np.clip(uu, 0.0, 1.0), np.clip(vv, 0.0, 1.0)
    pix = row[ok] * w + col[ok]
    key = ((pp.astype(np.int64) << 40) | (np.round(vv * 0xFFFFF).astype(np.int64) << 20)
           | np.round(uu * 0xFFFFF).astype(np.int64))
    np.maximum.at(best, pix, key)
    win = key == best[pix]
    bu[pix[win]] = uu[win]
    bv[pix[win]] = vv[win]
    bp[pix[win]] = pp[win]
