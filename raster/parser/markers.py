"""SVG markers (``marker-start``, ``marker-mid``, ``marker-end``) resolved
into the render tree.

A marker is drawn at vertices of a shape's path: ``marker-start`` at the
first vertex, ``marker-end`` at the last, ``marker-mid`` at every vertex in
between.  Each instance is a :class:`~raster.tree.Group` whose transform
maps the marker's content coordinates to the path's user space::

    translate(vertex) @ rotate(angle) @ scale(sx, sy) @ translate(-refX, -refY)

where ``(sx, sy)`` is the stroke width (``markerUnits="strokeWidth"``, the
default) or 1 (``userSpaceOnUse``) times the viewBox scale, and the angle is
the ``orient`` angle or, for ``auto``/``auto-start-reverse``, the direction
of the path at the vertex.  Unless ``overflow`` is ``visible``/``auto`` the
content is clipped to the marker viewport (``0 0 markerWidth
markerHeight``, mapped into viewBox coordinates when there is a viewBox).
All instances of a path are the children of the Group stored in
:attr:`PathNode.markers <raster.tree.PathNode>`, in the path's user
space, and are drawn at the ``markers`` position of ``paint-order``.

Vertices and directions follow resvg (usvg's marker module), the reference
for the conformance suite, so that conformance images match:

* the path is seen as a list of segments ``M``, ``L``, ``C`` (quadratics are
  raised to cubics) and ``Z``; a ``Z`` has the vertex of its subpath start;
* start: segment 0; end: the last segment (none when it is a ``M``); mid:
  every segment in between except ``Z`` -- so the start of a later subpath
  gets a mid marker, the closing vertex of a closed subpath in the middle of
  the path gets none;
* elliptical arcs count as their cubic pieces of at most 90 degrees each (a
  half ellipse has a mid vertex), and the basic shapes (``rect``,
  ``circle``, ``ellipse``) are marked too (SVG 2);
* the ``auto`` angle at a vertex is the bisector of an incoming and an
  outgoing direction taken from the neighbouring vertices and control
  points, skipping a control point that coincides with the vertex.

Two savings that leave the picture unchanged: the viewport clip is dropped
when the content provably lies inside it (a clip costs the renderer a
layer per instance), and when every instance of one marker property draws
the same single opaque solid path (fill of one convex contour, or a stroke
without dashes) under a uniform scale, the instances become one PathNode
with one contour per vertex (the renderer's cost is per node: 2000 arrow
instances render about 10x faster).  Anti-aliased edges where instances
overlap then blend once instead of twice.

Coordinates are user units, x right, y down; angles are degrees clockwise
on screen (SVG's rotate).  Bad input to the functions here raises
:class:`~raster.errors.PathError`; nothing in a document raises: invalid
marker references, sizes or attributes just draw no marker (as resvg).

>>> from raster.geometry.pathdata import parse_path
>>> mv = marker_vertices(parse_path('M 0 0 L 10 0 L 10 10'))
>>> mv.points.tolist(), mv.angles.tolist()
([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]], [0.0, 45.0, 90.0])
>>> mv.start, mv.mid.tolist(), mv.end
(0, [1], 2)
"""

import dataclasses
import math
from typing import NamedTuple

import numpy as np

from ..errors import PathError, RasterError
from ..geometry.path import CLOSE, CUBIC, MOVE, QUAD, Path
from ..geometry.transform import Affine
from ..geometry.bounds import bbox as exact_bbox
from ..tree import FillRule, Group, PathNode, SolidPaint
from .convert import convert_children
from .boxes import walk_all
from .effects import clip_rect
from .style import doc_style, length, local_name
from .values import (ZERO_VIEWBOX, parse_angle, parse_length, parse_preserve_aspect_ratio,
                     parse_url, resolve_viewbox, viewbox_transform)

__all__ = ['MARKABLE', 'MarkerVertices', 'marker_vertices', 'vertex_angles', 'parse_orient',
           'marker_matrices', 'marker_transform', 'context_paint', 'build_markers']

#: Elements that take markers (SVG 2: every shape; resvg draws them too).
MARKABLE = frozenset(['path', 'line', 'polyline', 'polygon', 'rect', 'circle', 'ellipse'])

_M, _L, _C, _Z = 0, 1, 3, 4          # marker segment kinds (path verb values)
_NPTS = np.array([1, 1, 2, 3, 0], dtype=np.int64)
_TWO_PI = 2.0 * math.pi
# arcs are re-flattened for marker placement with a tolerance so large that
# only the "at most 90 degrees per piece" rule splits them (as resvg does)
_PLACEMENT_TOL = 1e9


class MarkerVertices(NamedTuple):
    """Marker vertices of a path.

    Attributes
    ----------
    points : (S, 2) float64 ndarray
        The vertex of every marker segment (see the module docstring): the
        end point of ``M``/``L``/``C``, the subpath start for ``Z``.
    angles : (S,) float64 ndarray
        The ``orient="auto"`` angle at each vertex, degrees in [0, 360).
    kinds : (S,) uint8 ndarray
        Segment kinds: 0 ``M``, 1 ``L``, 3 ``C``, 4 ``Z``.
    start : int
        Index of the start vertex, -1 when there is none.
    mid : (K,) int64 ndarray
        Indices of the mid vertices.
    end : int
        Index of the end vertex, -1 when there is none.
    """
    points: np.ndarray
    angles: np.ndarray
    kinds: np.ndarray
    start: int
    mid: np.ndarray
    end: int


def _segments(path):
    """Marker segments of a path: kinds (S,), vertices (S, 2), first and
    second control points (S, 2) (meaningful for cubics) and the start of
    the latest subpath strictly before each segment (S, 2)."""
    verbs = np.asarray(path.verbs)
    pts = np.asarray(path.points, dtype=np.float64).reshape(-1, 2)
    n = len(verbs)
    if n == 0:
        z = np.zeros((0, 2))
        return np.zeros(0, np.uint8), z, z, z, z
    npts = _NPTS[verbs]
    off = np.cumsum(npts) - npts
    # a move directly followed by a move is replaced by it (as tiny-skia does)
    nxt = np.append(verbs[1:], CLOSE)
    keep = ~((verbs == MOVE) & (nxt == MOVE))
    is_move = verbs == MOVE
    move_idx = np.where(is_move, np.arange(n), -1)
    np.maximum.accumulate(move_idx, out=move_idx)       # latest move at or before
    sub_start = pts[off[np.maximum(move_idx, 0)]]
    last = np.clip(off + npts - 1, 0, len(pts) - 1)
    vert = np.where((verbs == CLOSE)[:, None], sub_start, pts[last])
    prev = pts[np.maximum(off - 1, 0)]                  # start point of a drawing verb
    c1 = pts[np.minimum(off, len(pts) - 1)].copy()
    c2 = pts[np.minimum(off + 1, len(pts) - 1)].copy()
    q = verbs == QUAD
    if q.any():                                         # degree elevation
        qc = pts[off[q]]
        c1[q] = (prev[q] + 2.0 * qc) / 3.0
        c2[q] = (vert[q] + 2.0 * qc) / 3.0
    kinds = np.where(q, CUBIC, verbs).astype(np.uint8)
    kinds, vert, c1, c2 = kinds[keep], vert[keep], c1[keep], c2[keep]
    # start of the latest subpath strictly before each kept segment
    km = kinds == MOVE
    S = len(kinds)
    before = np.where(km, np.arange(S), -1)
    before = np.concatenate([[-1], before[:-1]])
    np.maximum.accumulate(before, out=before)
    sp = np.where((before >= 0)[:, None], vert[np.maximum(before, 0)], 0.0)
    return kinds, vert, c1, c2, sp


def _near(a, b):
    """Rows of ``a`` and ``b`` ((N, 2)) equal to within a few float32 ulps
    (resvg compares single-precision coordinates)."""
    tol = 4.0 * np.finfo(np.float32).eps * np.maximum(np.abs(a), np.abs(b))
    return np.all(np.abs(a - b) <= tol, axis=-1)


def _bisector(vin, vout):
    """resvg's vertex angle (degrees in [0, 360)) from incoming and outgoing
    direction vectors ((N, 2) each): the mean of the two angles, turned by
    180 degrees when they are more than 180 degrees apart.  A zero vector
    has angle 0."""
    a_in = np.mod(np.arctan2(vin[:, 1], vin[:, 0]), _TWO_PI)
    a_out = np.mod(np.arctan2(vout[:, 1], vout[:, 0]), _TWO_PI)
    d = (a_out - a_in) * 0.5
    ang = a_in + d - np.where(np.abs(d) > math.pi / 2, math.pi, 0.0)
    return np.degrees(np.mod(ang, _TWO_PI)) % 360.0


def _curves(prev, c1, x, c2, nxt):
    """Incoming/outgoing directions at vertex ``x`` between a control point
    ``c1`` before it and ``c2`` after it; a control point on the vertex is
    replaced by the neighbouring vertex (``prev`` or ``nxt``)."""
    e1 = _near(c1, x)[:, None]
    e2 = _near(x, c2)[:, None]
    vin = np.where(e1, x - prev, x - c1)
    vout = np.where(e1, c2 - x, np.where(e2, nxt - x, c2 - x))
    return vin, vout


def vertex_angles(kinds, vert, c1, c2, sp):
    """``orient="auto"`` angles (degrees, (S,)) of marker segments as made
    by :func:`_segments`; vectorized over all vertices."""
    S = len(kinds)
    vin = np.zeros((S, 2))
    vout = np.zeros((S, 2))
    if S < 2:
        return np.zeros(S)
    # -- first vertex: the direction into the first segment
    k1 = kinds[1]
    if k1 == _L:
        vin[0] = vout[0] = vert[1] - vert[0]
    elif k1 == _C:
        d = vert[1] - vert[0] if _near(vert[0:1], c1[1:2])[0] else c1[1] - vert[0]
        vin[0] = vout[0] = d
    # -- last vertex
    j = S - 1
    k, kp = kinds[j], kinds[j - 1]
    if k == _L:
        vin[j] = vout[j] = vert[j] - vert[j - 1]
    elif k == _C:
        d = vert[j] - c1[j] if _near(c2[j:j + 1], vert[j:j + 1])[0] else vert[j] - c2[j]
        vin[j] = vout[j] = d
    elif k == _Z and kp == _L:
        vin[j] = vout[j] = sp[j] - vert[j - 1]
    elif k == _Z and kp == _C:
        p = vert[j - 1:j]
        a, b = _curves(p, c2[j - 1:j], p, sp[j:j + 1], sp[j:j + 1])
        vin[j], vout[j] = a[0], b[0]
    # -- middle vertices: each (this kind, next kind) case over its subset
    if S > 2:
        cur, nk = kinds[1:-1], kinds[2:]

        def case(sel, fn):
            j = np.flatnonzero(sel) + 1                     # vertex indices
            if len(j):
                vin[j], vout[j] = fn(j)

        def line(d):
            return d, d
        case((cur == _M) & (nk == _L), lambda j: line(vert[j + 1] - vert[j]))
        case((cur == _M) & (nk == _C), lambda j: line(c1[j + 1] - vert[j]))
        case((cur == _L) & (nk == _L), lambda j: (vert[j] - vert[j - 1], vert[j + 1] - vert[j]))
        case((cur == _C) & (nk == _C),
             lambda j: _curves(vert[j - 1], c2[j], vert[j], c1[j + 1], vert[j + 1]))
        case((cur == _L) & (nk == _C),
             lambda j: _curves(vert[j - 1], vert[j - 1], vert[j], c1[j + 1], vert[j + 1]))
        case((cur == _C) & (nk == _L),
             lambda j: _curves(vert[j - 1], c2[j], vert[j], vert[j + 1], vert[j + 1]))
        case((cur == _L) & (nk == _M), lambda j: line(vert[j] - vert[j - 1]))
        case((cur == _C) & (nk == _M),
             lambda j: line(np.where(_near(vert[j], c2[j])[:, None], vert[j] - vert[j - 1],
                                     vert[j] - c2[j])))
        case((cur == _L) & (nk == _Z), lambda j: (vert[j] - vert[j - 1], sp[j] - vert[j]))
        case(((cur == _M) | (cur == _C)) & (nk == _Z), lambda j: line(sp[j] - vert[j - 1]))
    return _bisector(vin, vout)


def marker_vertices(path):
    """Marker vertices, ``auto`` angles and start/mid/end indices of a path.

    Parameters
    ----------
    path : raster.Path
        In user units (elliptical arcs already converted to cubics; see the
        module docstring for how arcs should be split).

    Returns
    -------
    MarkerVertices
        Empty arrays and ``start == end == -1`` for a path of fewer than
        two segments.

    Raises
    ------
    raster.errors.PathError
        When ``path`` is not a :class:`raster.Path`.

    Examples
    --------
    A closed triangle: the closing vertex is the end, and the last corner's
    angle bisects its edge and the closing edge.

    >>> from raster.geometry.pathdata import parse_path
    >>> mv = marker_vertices(parse_path('M 0 0 L 10 0 L 10 10 Z'))
    >>> mv.points[mv.end].tolist(), mv.mid.tolist(), round(float(mv.angles[2]), 6)
    ([0.0, 0.0], [1, 2], 157.5)
    """
    if not isinstance(path, Path):
        raise PathError('marker_vertices needs a raster.Path, got %s' % type(path).__name__)
    kinds, vert, c1, c2, sp = _segments(path)
    S = len(kinds)
    if S < 2:
        e = np.zeros(0, np.int64)
        return MarkerVertices(np.zeros((0, 2)), np.zeros(0), kinds, -1, e, -1)
    angles = vertex_angles(kinds, vert, c1, c2, sp)
    start = 0 if kinds[0] == _M else -1
    mid = np.flatnonzero(kinds[1:S - 1] != _Z) + 1
    end = S - 1 if kinds[S - 1] != _M else -1
    return MarkerVertices(vert, angles, kinds, start, mid.astype(np.int64), end)


def parse_orient(s):
    """``orient`` attribute: ``'auto'``, ``'auto-start-reverse'`` or an angle
    in degrees (``deg``/``rad``/``grad``/``turn`` units accepted); missing or
    invalid is 0.

    >>> parse_orient('auto'), parse_orient('0.25turn'), parse_orient('x')
    ('auto', 90.0, 0.0)
    """
    if s is None:
        return 0.0
    s = s.strip()
    if s in ('auto', 'auto-start-reverse'):
        return s
    try:
        a = parse_angle(s)
    except RasterError:
        a = None
    return 0.0 if a is None else float(a)


def marker_matrices(points, angles, sx, sy, ref):
    """Instance transforms of one marker at many vertices, vectorized.

    Parameters
    ----------
    points : (K, 2) array_like of float
        Vertices.
    angles : (K,) array_like of float
        Marker angles in degrees.
    sx, sy : float
        Scale of the content (stroke width times viewBox scale).
    ref : (2,) floats
        The reference point in content coordinates.

    Returns
    -------
    (K, 6) float64 ndarray
        Rows ``(a, b, c, d, e, f)`` of ``translate(point) @ rotate(angle) @
        scale(sx, sy) @ translate(-ref)``; sines and cosines below 1e-15 are
        snapped to 0 so quarter turns are exact.
    """
    p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    r = np.radians(np.mod(np.asarray(angles, dtype=np.float64).reshape(-1), 360.0))
    co, si = np.cos(r), np.sin(r)
    co[np.abs(co) < 1e-15] = 0.0
    si[np.abs(si) < 1e-15] = 0.0
    with np.errstate(all='ignore'):       # huge scales: non-finite rows, dropped by callers
        rx, ry = -sx * float(ref[0]), -sy * float(ref[1])
        return np.stack([co * sx, si * sx, -si * sy, co * sy,
                         p[:, 0] + co * rx - si * ry, p[:, 1] + si * rx + co * ry], axis=1)


def marker_transform(point, angle, sx, sy, ref):
    """Affine mapping marker content to the path's user space:
    ``translate(point) @ rotate(angle) @ scale(sx, sy) @ translate(-ref)``.

    Raises :class:`~raster.errors.TransformError` when the result is not
    finite.

    >>> marker_transform((10, 20), 90, 2, 2, (1, 0)).apply([[1.0, 0.0], [2.0, 0.0]]).tolist()
    [[10.0, 20.0], [10.0, 22.0]]
    """
    return Affine(*marker_matrices([point], [angle], sx, sy, ref)[0])


def context_paint(paint, to_context, box=None):
    """A context element's paint, re-expressed for content whose coordinates
    map to the context element's user space by ``to_context``.

    Gradients and patterns keep painting in the context element's space
    (SVG 2 context-fill/context-stroke): their transform is prefixed by the
    inverse of ``to_context``, and object-bounding-box units are resolved
    against ``box`` (x0, y0, x1, y1), the context element's bounding box.
    Returns None when the paint cannot be used (singular transform, empty
    box).  Solid colours and None are returned unchanged.
    """
    if paint is None or isinstance(paint, SolidPaint):
        return paint
    from .servers import in_space       # loaded with the first paint server
    if box is not None:
        box = (box[0], box[1], box[2] - box[0], box[3] - box[1])
    return in_space(paint, to_context, box)


# -- tree building ----------------------------------------------------------------


def _marker_ref(value, cache):
    if value is None:
        return None
    v = value.strip()
    if not v or v == 'none':
        return None
    u = parse_url(v)
    if u is None:
        return None
    el = cache.by_id.get(u[0])
    if el is None or local_name(el) != 'marker':
        return None
    return el


def _stroke_width(inh, ctx):
    s = inh.get('stroke-width')
    if s is None:
        return 1.0
    v = parse_length(s, 'other', ctx)
    if v is None or v < 0:
        return 1.0
    return v


def _ref(mk, name, axis, ctx, lo, size):
    s = mk.get(name)
    if s is None:
        return 0.0
    k = s.strip()
    if k in ('left', 'top'):
        return lo
    if k == 'center':
        return lo + size * 0.5
    if k in ('right', 'bottom'):
        return lo + size
    v = parse_length(s, axis, ctx)
    return 0.0 if v is None else v


class _Marker:
    """Everything about one marker element that does not depend on the
    vertex."""
    __slots__ = ('el', 'inh', 'own', 'scale', 'ref', 'clip', 'clip_rect', 'orient', 'vw',
                 'vh')


def _resolve_marker(mk, ctx, sw, cache):
    """The vertex-independent part of a marker, or None when it draws
    nothing (zero or negative size, zero stroke scale, bad viewBox)."""
    inh, own = doc_style(mk, cache)
    mw = length(mk, 'markerWidth', 'x', ctx, 3.0)
    mh = length(mk, 'markerHeight', 'y', ctx, 3.0)
    if not (mw > 0 and mh > 0):
        return None
    units = 1.0 if mk.get('markerUnits', '').strip() == 'userSpaceOnUse' else sw
    if not (units > 0 and math.isfinite(units)):
        return None
    m = _Marker()
    m.el, m.inh, m.own = mk, inh, own
    # an invalid viewBox is ignored, a zero-sized one disables the marker
    vb = resolve_viewbox(mk.get('viewBox'))
    if vb is ZERO_VIEWBOX:
        return None
    if vb is None:
        sx = sy = units
        lox, loy, vw, vh = 0.0, 0.0, mw, mh
        vp_rect = (0.0, 0.0, mw, mh)
    else:
        try:
            par = parse_preserve_aspect_ratio(mk.get('preserveAspectRatio', ''))
            vbt = viewbox_transform(vb, par, mw, mh)
        except RasterError:
            return None
        sx, sy = vbt.a * units, vbt.d * units
        lox, loy, vw, vh = vb
        # the viewport (0 0 mw mh) in viewBox coordinates
        vp_rect = (-vbt.e / vbt.a, -vbt.f / vbt.d, mw / vbt.a, mh / vbt.d)
    m.scale = (sx, sy)
    m.vw, m.vh = vw, vh
    m.ref = (_ref(mk, 'refX', 'x', ctx, lox, vw), _ref(mk, 'refY', 'y', ctx, loy, vh))
    # markers default to overflow: hidden (user agent style sheet); `inherit`
    # takes the parent's value, whose initial value is visible
    decl = cache.styles.get(mk) or {}
    inherit = decl.get('overflow', '').strip() == 'inherit'
    ov = own.get('overflow', 'visible' if inherit else 'hidden').strip()
    m.clip = None if ov in ('visible', 'auto') else clip_rect(*vp_rect)
    m.clip_rect = vp_rect
    m.orient = parse_orient(mk.get('orient'))
    return m


def _content_box(nodes):
    """Conservative (x0, y0, x1, y1) bounds of marker content in its own
    coordinates (control points, strokes padded by their reach), or None
    when unknown (images, text, filters) or empty."""
    lo = np.array([np.inf, np.inf])
    hi = -lo
    stack = [(n, None) for n in nodes]
    while stack:
        n, t = stack.pop()
        if isinstance(n, Group):
            if n.filters:
                return None
            ct = n.transform if t is None else t @ n.transform
            stack.extend((c, ct) for c in n.children)
        elif isinstance(n, PathNode):
            if n.path is None or len(n.path.points) == 0:
                continue
            pts = n.path.points if t is None else t.apply(n.path.points)
            pad = 0.0
            if n.stroke is not None:
                s = n.stroke
                st = s.style
                k = max(1.0, st.miterlimit) if st.join in ('miter', 'miter-clip', 'arcs') \
                    else 1.0
                if st.cap == 'square':
                    k = max(k, math.sqrt(2.0))
                pad = 0.5 * s.width * k * (1.0 if t is None else t.max_scale())
            lo = np.minimum(lo, pts.min(0) - pad)
            hi = np.maximum(hi, pts.max(0) + pad)
            if n.markers is not None:
                stack.append((n.markers, t))
        else:
            return None
    if not np.all(hi >= lo):
        return None
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def _needs_clip(nodes, rect):
    """False when the content provably lies inside the clip rectangle
    (x, y, w, h): the clip changes nothing and costs a layer."""
    b = _content_box(nodes)
    if b is None:
        return True
    x, y, w, h = rect
    return not (b[0] >= x and b[1] >= y and b[2] <= x + w and b[3] <= y + h)


def _convex_single_contour(path):
    """True for one contour whose control polygon turns one way once
    around (then every instance winds the same way and a union by the
    nonzero rule is exact)."""
    v = path.verbs
    if np.count_nonzero(v == MOVE) != 1:
        return False
    p = path.points
    d = np.diff(np.vstack([p, p[:1]]), axis=0)
    d = d[np.any(d != 0, axis=1)]
    if len(d) < 3:
        return False
    e = np.vstack([d[1:], d[:1]])
    cross = d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0]
    dot = np.sum(d * e, axis=1)
    if not (np.all(cross >= 0) or np.all(cross <= 0)):
        return False
    turn = np.sum(np.arctan2(cross, dot))
    return abs(abs(turn) - _TWO_PI) < 1e-6


def _merged(nodes, mats, scale):
    """One PathNode drawing a single-path marker content at every instance
    transform (rows of ``mats``, (K, 6)) at once (the renderer's cost is per node), or None when that
    could change the picture: more than one node, both fill and stroke,
    translucent or non-solid paint, evenodd, dashes, nested markers, a
    non-uniform scale, or a fill that is not one convex contour."""
    if len(nodes) != 1 or not isinstance(nodes[0], PathNode) or scale[0] != scale[1]:
        return None
    n = nodes[0]
    if n.markers is not None or n.path is None or len(n.path.verbs) == 0:
        return None
    f, s = n.fill, n.stroke
    if (f is None) == (s is None):
        return None
    use = f if f is not None else s
    if (not isinstance(use.paint, SolidPaint) or use.paint.color[3] < 1.0
            or use.opacity < 1.0):
        return None
    if f is not None and (f.rule != FillRule.NONZERO or not _convex_single_contour(n.path)):
        return None
    if s is not None and s.style.dash is not None:
        return None
    m = np.asarray(mats, dtype=np.float64)                     # (K, 6): a b c d e f
    x, y = n.path.points[:, 0], n.path.points[:, 1]
    px = m[:, 0:1] * x + m[:, 2:3] * y + m[:, 4:5]
    py = m[:, 1:2] * x + m[:, 3:4] * y + m[:, 5:6]
    pts = np.stack([px, py], axis=-1)                          # (K, N, 2)
    if not np.all(np.isfinite(pts)):
        return None
    path = Path(np.tile(n.path.verbs, len(m)), pts.reshape(-1, 2))
    if s is not None:
        s = dataclasses.replace(s, style=dataclasses.replace(
            s.style, width=s.style.width * abs(scale[0])))
    return PathNode(path=path, fill=f, stroke=s, antialias=n.antialias)


def _content(m, state, T, context, cache):
    """Marker content nodes built for the instance transform ``T``."""
    sub = state.sub(m.inh, m.own, transform=T, vw=m.vw, vh=m.vh, context=context)
    ids = set(cache.tree_ids)
    nodes = []
    with cache.referencing(m.el):
        convert_children(m.el, sub, cache, nodes)
    # marker content is not a document node: keep `ids` for real elements
    for k in [k for k in cache.tree_ids if k not in ids]:
        del cache.tree_ids[k]
    return nodes


def build_markers(el, name, path, placement, inh, ctx, state, cache, fill=None, stroke=None):
    """Marker instances of a shape, as one Group in the shape's user space.

    Parameters
    ----------
    el : lxml element
        The shape element; ``name`` its local name.
    path : raster.Path
        The shape's geometry in its user space.
    placement : raster.Path
        The path whose vertices carry the markers (``path`` with arcs
        split into pieces of at most 90 degrees, as resvg places them).
    inh : dict
        The shape's computed inherited properties.
    ctx : raster.parser.values.LengthContext
        Length context of the shape.
    state : raster.parser.context.State
        State whose CTM includes the shape's transform.
    cache : raster.parser.context.Cache
    fill, stroke : raster.tree.Fill, raster.tree.Stroke or None
        The shape's resolved paints: the context for ``context-fill`` /
        ``context-stroke`` in the marker content.

    Returns
    -------
    raster.tree.Group or None
        None when no marker draws anything.
    """
    if name not in MARKABLE or state.clip:
        return None
    refs = [_marker_ref(inh.get(p), cache) for p in ('marker-start', 'marker-mid', 'marker-end')]
    if all(r is None for r in refs):
        return None
    sw = _stroke_width(inh, ctx)
    if not sw > 0:
        return None
    mv = marker_vertices(placement)
    if len(mv.points) == 0:
        return None
    cfill = fill.paint if fill is not None else None
    cstroke = stroke.paint if stroke is not None else None
    simple = all(p is None or isinstance(p, SolidPaint) for p in (cfill, cstroke))
    box = None
    if not simple:
        try:
            box = exact_bbox(path)
        except RasterError:
            box = None
    resolved = {}
    out = []
    for kind, mk in enumerate(refs):
        if mk is None:
            continue
        if kind == 0:
            idx = [mv.start] if mv.start >= 0 else []
        elif kind == 1:
            idx = mv.mid.tolist()
        else:
            idx = [mv.end] if mv.end >= 0 else []
        if not idx:
            continue
        if mk in cache.active:
            cache.warn('marker-recursive', 'recursive marker reference ignored')
            continue
        m = resolved.get(mk)
        if m is None:
            m = resolved[mk] = _resolve_marker(mk, ctx, sw, cache)
        if m is None:
            continue
        o = m.orient
        if o == 'auto':
            ang = mv.angles[idx]
        elif o == 'auto-start-reverse':
            ang = mv.angles[idx] + (180.0 if kind == 0 else 0.0)
        else:
            ang = np.full(len(idx), o)
        mats = marker_matrices(mv.points[idx], ang, m.scale[0], m.scale[1], m.ref)
        if not np.all(np.isfinite(mats)):
            continue
        if simple:
            T0 = Affine(*mats[0])
            shared = _content(m, state, T0, (cfill, cstroke), cache)
            if not shared:
                continue
            clip = m.clip
            if clip is not None and not _needs_clip(shared, m.clip_rect):
                clip = None
            if clip is None and len(idx) > 2:
                g = _merged(shared, mats, m.scale)
                if g is not None:
                    out.append(g)
                    continue
            # every instance draws the shared content again: it counts as
            # many nodes, and markers that cannot all fit in what is left of
            # the budget are left out before any is built (raster.limits
            # max_elements)
            size = 1 + sum(1 for _ in walk_all(shared))
            left = cache.options.max_elements - cache.count
            if size * len(mats) > left:
                cache.warn('limit', 'markers not rendered: %d instances of %d nodes, more than '
                           'the %d left of max_elements' % (len(mats), size, max(left, 0)))
                continue
            for row in mats:
                if not cache.tick(size):
                    break
                out.append(Group(transform=Affine(*row), clip_path=clip, children=list(shared)))
            continue
        for row in mats:
            T = Affine(*row)
            nodes = _content(m, state, T, (context_paint(cfill, T, box),
                                           context_paint(cstroke, T, box)), cache)
            clip = m.clip
            if clip is not None and not _needs_clip(nodes, m.clip_rect):
                clip = None
            if nodes:
                out.append(Group(transform=T, clip_path=clip, children=nodes))
            if cache.stopped:
                break
    if not out:
        return None
    return Group(children=out)
