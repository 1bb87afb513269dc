"""Exact bounding boxes of paths and Bezier curves.

The box of a Bezier curve is spanned by its end points and by the curve
points where a coordinate's derivative vanishes.  For quadratics and cubics
that derivative is a polynomial of degree 1 or 2 per axis, solved in closed
form (:func:`quadratic_roots`) for all segments at once.

Coordinates are float64 user units (x right, y down); a ``transform`` is
applied to the control points *before* the box is taken (the box of a
transformed curve, not the transformed box).
"""

import numpy as np

from ..errors import PathError

__all__ = ['bbox', 'bezier_bbox', 'segment_bounds', 'segment_extrema',
           'quadratic_roots', 'BoundsPen']


def quadratic_roots(a, b, c):
    """Real roots of ``a t**2 + b t + c = 0``, elementwise.

    Uses the cancellation-free form ``q = -(b + sign(b) sqrt(b**2 - 4ac)) / 2``,
    roots ``q / a`` and ``c / q``.  A zero (or tiny) ``a`` degrades
    gracefully to the linear root ``-c / b``; ``q / a`` is then infinite or
    huge.

    Parameters
    ----------
    a, b, c : array_like of float, broadcastable to one shape ``(...)``

    Returns
    -------
    (..., 2) float64 ndarray
        The two roots; NaN where there is no real root (negative
        discriminant, or ``a = b = 0``).  A double root appears twice.

    Examples
    --------
    >>> quadratic_roots(1.0, -3.0, 2.0).tolist()
    [2.0, 1.0]
    >>> quadratic_roots(0.0, 2.0, -1.0).tolist()
    [nan, 0.5]
    """
    a, b, c = np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in (a, b, c)))
    with np.errstate(all='ignore'):
        disc = b * b - 4.0 * a * c
        sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
        q = -0.5 * (b + np.where(b >= 0, sq, -sq))
        r1 = np.where(a != 0, q / a, np.nan)
        r2 = np.where(q != 0, c / q, np.where(a != 0, 0.0, np.nan))
    r1 = np.where(np.isfinite(r1), r1, np.nan)
    r2 = np.where(np.isfinite(r2), r2, np.nan)
    return np.stack([r1, r2], axis=-1)


def _bern2(p0, p1, p2, t):
    s = 1.0 - t
    return s * s * p0 + 2.0 * s * t * p1 + t * t * p2


def _bern3(p0, p1, p2, p3, t):
    s = 1.0 - t
    return s * s * s * p0 + 3.0 * s * t * (s * p1 + t * p2) + t * t * t * p3


def segment_extrema(ctrl, degree):
    """Parameters where a coordinate of a segment has an interior extremum.

    Parameters
    ----------
    ctrl : (S, 4, D) float64 ndarray
        Control points as in :class:`raster.geometry.path.Segments` (a segment of
        degree ``k`` uses ``ctrl[:, :k+1]``).
    degree : (S,) int ndarray
        1, 2 or 3.

    Returns
    -------
    (S, D, 2) float64 ndarray
        For each segment and axis, up to two parameters ``t`` in the open
        interval (0, 1) where that coordinate's derivative vanishes; NaN
        where there is none (always NaN for lines).

    Examples
    --------
    >>> c = np.array([[[0, 0], [1, 2], [2, 0], [2, 0]]], float)
    >>> segment_extrema(c, np.array([2]))[0].tolist()
    [[nan, nan], [nan, 0.5]]
    """
    ctrl = np.asarray(ctrl, dtype=np.float64)
    degree = np.asarray(degree)
    S, _, D = ctrl.shape
    p0, p1, p2, p3 = ctrl[:, 0], ctrl[:, 1], ctrl[:, 2], ctrl[:, 3]
    # derivative / degree, as a t**2 + b t + c per axis
    cub = degree[:, None] == 3
    quad = degree[:, None] == 2
    a = np.where(cub, -p0 + 3.0 * (p1 - p2) + p3, 0.0)
    b = np.where(cub, 2.0 * (p0 - 2.0 * p1 + p2), np.where(quad, p0 - 2.0 * p1 + p2, 0.0))
    c = np.where(cub | quad, p1 - p0, 0.0)
    # roots do not change under scaling: normalise so that squares can
    # neither overflow nor underflow for huge or tiny coordinates
    m = np.maximum(np.maximum(np.abs(a), np.abs(b)), np.abs(c))
    m = np.where(m > 0, m, 1.0)
    r = quadratic_roots(a / m, b / m, c / m)          # (S, D, 2)
    return np.where((r > 0.0) & (r < 1.0), r, np.nan)


def segment_bounds(ctrl, degree):
    """Exact bounding box of every segment.

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

    Examples
    --------
    >>> c = np.array([[[0, 0], [0, 4], [4, 4], [4, 0]]], float)   # a cubic arch
    >>> lo, hi = segment_bounds(c, np.array([3]))
    >>> lo.tolist(), hi.tolist()
    ([[0.0, 0.0]], [[4.0, 3.0]])
    """
    ctrl = np.asarray(ctrl, dtype=np.float64)
    degree = np.asarray(degree)
    t = segment_extrema(ctrl, degree)                 # (S, D, 2)
    tt = np.where(np.isnan(t), 0.0, t)
    p = [ctrl[:, k, :, None] for k in range(4)]       # (S, D, 1)
    v3 = _bern3(p[0], p[1], p[2], p[3], tt)
    v2 = _bern2(p[0], p[1], p[2], tt)
    v = np.where((degree == 3)[:, None, None], v3, v2)
    end = np.where((degree == 1)[:, None], ctrl[:, 1], ctrl[:, 3])
    ends = np.minimum(ctrl[:, 0], end), np.maximum(ctrl[:, 0], end)
    ok = ~np.isnan(t)
    lo = np.minimum(ends[0], np.where(ok, v, np.inf).min(axis=2))
    hi = np.maximum(ends[1], np.where(ok, v, -np.inf).max(axis=2))
    return lo, hi


def bezier_bbox(ctrl):
    """Exact bounding box of one Bezier curve of any degree.

    Parameters
    ----------
    ctrl : (n+1, D) array_like of float
        Control points, ``n >= 0``.

    Returns
    -------
    lo, hi : (D,) float64 ndarray

    Notes
    -----
    Degrees up to 3 are solved in closed form; higher degrees find the roots
    of each axis' derivative (the hodograph) with :func:`numpy.roots` and
    keep the real ones in (0, 1).

    Examples
    --------
    >>> lo, hi = bezier_bbox([[0, 0], [1, 2], [2, 0]])
    >>> lo.tolist(), hi.tolist()
    ([0.0, 0.0], [2.0, 1.0])
    """
    try:
        P = np.asarray(ctrl, dtype=np.float64)
    except (TypeError, ValueError):
        raise PathError('control points must be an (n+1, D) array of numbers') from None
    if P.ndim != 2 or len(P) < 1:
        raise PathError('control points must have shape (n+1, D), got %r' % (P.shape,))
    if not np.all(np.isfinite(P)):
        raise PathError('control points must be finite (NaN or infinity found)')
    n = len(P) - 1
    if n == 0:
        return P[0].copy(), P[0].copy()
    if n <= 3:
        C = np.empty((1, 4, P.shape[1]))
        C[0, :n + 1] = P
        C[0, n + 1:] = P[-1]
        lo, hi = segment_bounds(C, np.array([n]))
        return lo[0], hi[0]
    from math import comb
    lo = np.minimum(P[0], P[-1])
    hi = np.maximum(P[0], P[-1])
    # power-basis coefficients of each axis: x(t) = sum_k a_k t**k
    k = np.arange(n + 1)
    M = np.zeros((n + 1, n + 1))                      # M[k, i]: t**k coeff of B_i
    for i in range(n + 1):
        for j in range(n - i + 1):
            M[i + j, i] = comb(n, i) * comb(n - i, j) * (-1) ** j
    coef = M @ P                                      # (n+1, D), low order first
    dcoef = (coef[1:] * k[1:, None])                  # derivative, low order first
    for ax in range(P.shape[1]):
        poly = np.trim_zeros(dcoef[::-1, ax], 'f')
        if len(poly) < 2:
            continue
        r = np.roots(poly)
        r = r.real[(np.abs(r.imag) <= 1e-9 * np.maximum(1.0, np.abs(r.real)))
                   & (r.real > 0) & (r.real < 1)]
        if len(r):
            v = _decasteljau(P[:, ax], r)
            lo[ax] = min(lo[ax], v.min())
            hi[ax] = max(hi[ax], v.max())
    return lo, hi


def _decasteljau(c, t):
    """Values of the Bernstein polynomial with coefficients ``c`` ((n+1,))
    at ``t`` ((T,))."""
    W = np.broadcast_to(c, (len(t), len(c)))
    tt = t[:, None]
    while W.shape[1] > 1:
        W = (1.0 - tt) * W[:, :-1] + tt * W[:, 1:]
    return W[:, 0]


def bbox(path, transform=None, stroke=None, tolerance=0.25):
    """Exact bounding box of a path.

    Parameters
    ----------
    path : raster.geometry.path.Path
    transform : raster.geometry.transform.Affine or None, optional
        Applied to the control points first: the result is the exact box of
        the transformed path (not the transformed box).
    stroke : StrokeStyle, dict or None, optional
        When given, the box of the *stroke* instead of the fill: the path is
        stroked with :func:`raster.geometry.stroking.stroke` (a dict is passed as
        keyword arguments, anything else as the style) in device space and
        the exact box of that outline is returned.  The outline itself is
        within ``tolerance`` of the true stroke, so this box is too.  A
        stroke that draws nothing (zero width) gives the fill box.
    tolerance : float, optional
        Device-pixel tolerance of the stroke outline (only with ``stroke``).

    Returns
    -------
    (xmin, ymin, xmax, ymax) : tuple of float

    Raises
    ------
    PathError
        Not a path, or coordinates non-finite after the transform, or the
        path draws nothing: no segment and no closed lone point
        (``M x y Z`` counts as its point; a lone ``M x y`` is ignored, as in
        :func:`raster.flatten`).

    Examples
    --------
    >>> from raster.geometry.path import PathBuilder
    >>> b = PathBuilder(); b.moveTo((0, 0)); b.curveTo((0, 4), (4, 4), (4, 0))
    >>> bbox(b.path())
    (0.0, 0.0, 4.0, 3.0)
    """
    from .transform import as_affine
    if stroke is not None:
        from .stroking import stroke as _stroke
        if isinstance(stroke, dict):
            outline = _stroke(path, transform=transform, tolerance=tolerance, **stroke)
        else:
            outline = _stroke(path, stroke, transform=transform, tolerance=tolerance)
        if not outline.is_empty:
            return bbox(outline)
    if not callable(getattr(path, 'segments', None)):
        raise PathError('bbox needs a raster.Path, got %s' % type(path).__name__)
    seg = path.segments()
    t = as_affine(transform)
    ctrl = seg.ctrl
    lone = seg.contour_start[(seg.contour_nseg == 0) & seg.contour_closed]
    if not t.is_identity:
        ctrl = t.apply(ctrl)
        lone = t.apply(lone)
        if not (np.all(np.isfinite(ctrl)) and np.all(np.isfinite(lone))):
            raise PathError('transformed path has non-finite coordinates')
    if len(ctrl) == 0 and len(lone) == 0:
        raise PathError('path draws nothing: it has no bounding box')
    los, his = [lone], [lone]
    if len(ctrl):
        lo, hi = segment_bounds(ctrl, seg.degree)
        los.append(lo)
        his.append(hi)
    lo = np.concatenate(los).min(axis=0)
    hi = np.concatenate(his).max(axis=0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


class BoundsPen:
    """A pen that accumulates the exact bounds of what is drawn into it.

    Parameters
    ----------
    out : pen or None, optional
        Every call is forwarded to this pen as well.

    Attributes
    ----------
    bounds : (xmin, ymin, xmax, ymax) tuple of float, or None
        None until something is drawn.  A ``moveTo`` point counts once a
        segment or a ``closePath`` follows it (as in :func:`bbox`).

    Examples
    --------
    >>> pen = BoundsPen()
    >>> pen.moveTo((0, 0)); pen.qCurveTo((1, 2), (2, 0)); pen.closePath()
    >>> pen.bounds
    (0.0, 0.0, 2.0, 1.0)
    """

    def __init__(self, out=None):
        self.out = out
        self.bounds = None
        self._cur = None
        self._start = None
        self._pending = False      # the move point is not counted yet

    def _add(self, lo, hi):
        if self.bounds is None:
            self.bounds = (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
        else:
            b = self.bounds
            self.bounds = (min(b[0], float(lo[0])), min(b[1], float(lo[1])),
                           max(b[2], float(hi[0])), max(b[3], float(hi[1])))

    def _need(self):
        if self._cur is None:
            raise PathError('drawing command with no current point (missing move)')
        if self._pending:
            p = np.asarray(self._cur)
            self._add(p, p)
            self._pending = False

    def moveTo(self, pt):
        p = _point(pt)
        self._cur = self._start = p
        self._pending = True
        if self.out is not None:
            self.out.moveTo(pt)

    def lineTo(self, pt):
        self._need()
        p = _point(pt)
        self._add(np.minimum(self._cur, p), np.maximum(self._cur, p))
        self._cur = p
        if self.out is not None:
            self.out.lineTo(pt)

    def qCurveTo(self, *pts):
        """Quadratic(s); implied on-curve midpoints between consecutive
        off-curve points (TrueType rule)."""
        if not pts or pts[-1] is None:
            raise PathError('qCurveTo needs an on-curve end point')
        self._need()
        P = [_point(p) for p in pts]
        offs, end = P[:-1], P[-1]
        cur = self._cur
        for i, c in enumerate(offs):
            on = (c + offs[i + 1]) * 0.5 if i + 1 < len(offs) else end
            lo, hi = bezier_bbox(np.array([cur, c, on]))
            self._add(lo, hi)
            cur = on
        if not offs:
            self._add(np.minimum(cur, end), np.maximum(cur, end))
        self._cur = end
        if self.out is not None:
            self.out.qCurveTo(*pts)

    def curveTo(self, *pts):
        if not pts or len(pts) % 3:
            raise PathError('curveTo takes a multiple of 3 points, got %d' % len(pts))
        self._need()
        P = [_point(p) for p in pts]
        cur = self._cur
        for i in range(0, len(P), 3):
            lo, hi = bezier_bbox(np.array([cur, P[i], P[i + 1], P[i + 2]]))
            self._add(lo, hi)
            cur = P[i + 2]
        self._cur = cur
        if self.out is not None:
            self.out.curveTo(*pts)

    def closePath(self):
        if self._cur is not None:
            self._need()
            self._cur = self._start
        if self.out is not None:
            self.out.closePath()

    def endPath(self):
        self._cur = None
        self._pending = False
        if self.out is not None:
            self.out.endPath()


def _point(p):
    try:
        q = np.array([float(p[0]), float(p[1])])
    except (TypeError, ValueError, IndexError):
        raise PathError('point must be two numbers, got %r' % (p,)) from None
    if not np.all(np.isfinite(q)):
        raise PathError('non-finite coordinate %r' % (p,))
    return q
