"""Device-space boxes of tree nodes, for sizing layers and batches, and the
detection of groups clipped by one device rectangle.

Boxes are ``(x0, y0, x1, y1)`` floats in device pixels (conservative: the
transformed control points of paths, padded by a stroke's reach), pixel
boxes integer ``(x0, y0, x1, y1)`` half-open windows of a target.
"""

import math

import numpy as np

from ..geometry.path import CLOSE, LINE, MOVE
from ..geometry.stroking import stroke_reach
from ..tree import Group, ImageNode, PathNode

__all__ = ['pixel_box', 'node_box', 'group_box', 'stroke_reach', 'device_box', 'device_area',
           'clip_rect']


def pixel_box(box, w, h, margin=1):
    """Float device box -> integer pixel box clipped to the ``w x h``
    target (grown by ``margin`` pixels), or None when empty."""
    x0, y0, x1, y1 = box
    if not all(math.isfinite(v) for v in box):
        return None
    px0 = max(0, int(math.floor(x0)) - margin)
    py0 = max(0, int(math.floor(y0)) - margin)
    px1 = min(w, int(math.ceil(x1)) + margin)
    py1 = min(h, int(math.ceil(y1)) + margin)
    if px1 <= px0 or py1 <= py0:
        return None
    return px0, py0, px1, py1


def _union(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return (min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3]))


def _points_box(pts):
    if len(pts) == 0:
        return None
    lo, hi = pts.min(0), pts.max(0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _rect_box(rect, t):
    x, y, w, h = rect
    return _points_box(t.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]],
                                        float)))


def node_box(n, t):
    """Conservative device bounding box of what ``n`` draws under the CTM
    ``t``, or None when it draws nothing.  A path's box is that of its
    transformed control points (a Bezier lies in their hull): an exact box
    would cost a root solve per segment to size a layer."""
    if isinstance(n, Group):
        ct = t @ n.transform
        if n.filters:
            from .filters import filter_box     # (loaded with the first filter)
            return filter_box(n.filters, ct, lambda: group_box(n, ct))
        box = group_box(n, ct)
        if box is not None and n.mask is not None:
            mb = _rect_box(n.mask.rect, ct)
            box = (max(box[0], mb[0]), max(box[1], mb[1]), min(box[2], mb[2]), min(box[3], mb[3]))
            if box[2] <= box[0] or box[3] <= box[1]:
                return None
        return box
    if isinstance(n, PathNode):
        if n.path is None or len(n.path.points) == 0:
            return None
        box = None
        if n.fill is not None or n.stroke is not None:
            box = _points_box(t.apply(n.path.points))
        if box is not None and n.stroke is not None:
            reach = stroke_reach(n.stroke.style) * max(t.max_scale(), 1e-12) + 1.0
            box = (box[0] - reach, box[1] - reach, box[2] + reach, box[3] + reach)
        if n.markers is not None:
            box = _union(box, node_box(n.markers, t))
        return box
    if isinstance(n, ImageNode):
        return _rect_box(n.clip if n.clip is not None else n.view_rect, t)
    return None


def group_box(g, ct):
    """Union of the :func:`node_box` of a group's children under the CTM
    ``ct`` of its children."""
    box = None
    for c in g.children:
        box = _union(box, node_box(c, ct))
    return box


def device_box(path, t):
    """(x0, y0, x1, y1): the box of ``path``'s control box under ``t`` (a
    bound of what the path covers, before any stroke)."""
    x0, y0, x1, y1 = path.control_box()
    a, b, c, d = t.a, t.b, t.c, t.d
    if b == 0.0 and c == 0.0:       # scale and translation: the corners' order is known
        if a < 0.0:
            x0, x1 = x1, x0
        if d < 0.0:
            y0, y1 = y1, y0
        return a * x0 + t.e, d * y0 + t.f, a * x1 + t.e, d * y1 + t.f
    xs = (a * x0 + c * y0, a * x1 + c * y0, a * x0 + c * y1, a * x1 + c * y1)
    ys = (b * x0 + d * y0, b * x1 + d * y0, b * x0 + d * y1, b * x1 + d * y1)
    return min(xs) + t.e, min(ys) + t.f, max(xs) + t.e, max(ys) + t.f


def device_area(path, t, size, reach=1.0, off=(0, 0)):
    """Pixels of the device box of ``path``'s control points under ``t``,
    grown by ``reach`` and clipped to the canvas ``size`` (w, h) lying at
    ``off`` (ox, oy) in the pixels ``t`` maps to: a bound of the mask
    area, for batch budgets."""
    x0, y0, x1, y1 = device_box(path, t)
    w = min(x1 - off[0] + reach, size[0]) - max(x0 - off[0] - reach, 0.0)
    h = min(y1 - off[1] + reach, size[1]) - max(y0 - off[1] - reach, 0.0)
    return max(w, 0.0) * max(h, 0.0)


def clip_rect(g, t):
    """The device box (x0, y0, x1, y1) of group ``g``'s clip path (CTM of
    the parent ``t``) when the clip path is all that needs a layer and it
    is one antialiased axis-aligned rectangle in device space; else None.

    Drawing the children through the rectangle's coverage instead of into
    a clipped layer gives the same pixels except where children overlap
    each other in a pixel the rectangle's edge crosses (there a layer
    clips the composite of the children, this clips each child)."""
    cp = g.clip_path
    if (cp is None or cp.clip_path is not None or g.mask is not None or g.filters
            or g.opacity < 1.0 or g.blend_mode != 'normal' or g.isolate):
        return None
    rect = _RECT_CLIPS.get(id(cp), _UNSEEN)
    if rect is _UNSEEN or rect[0] is not cp:
        rect = (cp, _clip_rectangle(cp))
        _RECT_CLIPS[id(cp)] = rect
        if len(_RECT_CLIPS) > 4096:
            _RECT_CLIPS.clear()
    r = rect[1]
    if r is None:
        return None
    m = t @ g.transform @ cp.transform @ cp.root.transform
    if m.b != 0.0 or m.c != 0.0:
        return None
    x0, y0, x1, y1 = r
    xa, xb = m.a * x0 + m.e, m.a * x1 + m.e
    ya, yb = m.d * y0 + m.f, m.d * y1 + m.f
    box = (min(xa, xb), min(ya, yb), max(xa, xb), max(ya, yb))
    if not all(math.isfinite(v) for v in box):
        return None
    return box


_UNSEEN = object()
# id(ClipPath) -> (ClipPath, (x0, y0, x1, y1) in the root's units or None)
_RECT_CLIPS = {}


def _clip_rectangle(cp):
    """(x0, y0, x1, y1) when clip path ``cp`` is one antialiased polygon
    ``M L L L Z`` (or with a fifth point back at the start) whose sides
    are axis-aligned, in its root group's coordinates; else None."""
    root = cp.root
    if not isinstance(root, Group) or len(root.children) != 1 or root.needs_layer:
        return None
    n = root.children[0]
    if not isinstance(n, PathNode) or n.path is None or not n.antialias:
        return None
    p = n.path
    v = p.verbs.tolist()
    q = p.points.tolist()
    if len(q) not in (4, 5) or len(v) != len(q) + 1:
        return None
    if v[0] != MOVE or v[-1] != CLOSE or any(x != LINE for x in v[1:-1]):
        return None
    if len(q) == 5:
        if q[4] != q[0]:
            return None
        q = q[:4]
    xs = [x for x, _ in q]
    ys = [y for _, y in q]
    # consecutive corners differ in exactly one coordinate, alternately
    steps = [(xs[(k + 1) % 4] != xs[k], ys[(k + 1) % 4] != ys[k]) for k in range(4)]
    if not all(dx != dy for dx, dy in steps):
        return None
    if not all(steps[k][0] != steps[k + 1][0] for k in range(3)):
        return None
    return (min(xs), min(ys), max(xs), max(ys))
