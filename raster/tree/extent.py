"""What a node of the tree covers: the exact box of what it draws.

:func:`drawn_box` is the box of everything a node paints, in the
coordinates a given transform maps it to: exact boxes of fills and of
stroke outlines (joins, caps and dashes included, within ``tolerance``),
markers, images (their clipped viewport), then the group effects: a
filter's region replaces the content's box (filters draw outside it), a
clip path's geometry and a mask's rectangle cut it down.  This is what
``rasterize --id`` crops to (resvg's "layer bounding box").
"""

import math
from typing import Optional, Tuple

import numpy as np

from ..errors import RasterError
from ..geometry.bounds import bbox
from ..geometry.transform import IDENTITY, Affine
from .nodes import Group, ImageNode, PathNode, walk

__all__ = ['drawn_box']

Box = Tuple[float, float, float, float]


def _union(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return (min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3]))


def _intersect(a, b):
    if a is None or b is None:
        return None
    box = (max(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), min(a[3], b[3]))
    return box if box[2] > box[0] and box[3] > box[1] else None


def _rect_box(rect, t):
    x, y, w, h = rect
    p = t.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]], float))
    lo, hi = p.min(0), p.max(0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _path_box(n, t, tolerance):
    box = None
    try:
        if n.fill is not None:
            box = bbox(n.path, t)
        if n.stroke is not None and n.stroke.opacity > 0 and n.stroke.style.width > 0:
            box = _union(box, bbox(n.path, t, stroke=n.stroke.style, tolerance=tolerance))
    except RasterError:
        return None
    return box


def _clip_box(clip, t, tolerance):
    """Box of a clip path's geometry (its own clip path applied)."""
    ct = t @ clip.transform
    box = None
    for n, m in walk(clip.root, ct):
        if isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
            try:
                box = _union(box, bbox(n.path, m))
            except RasterError:
                continue
    if clip.clip_path is not None:
        box = _intersect(box, _clip_box(clip.clip_path, t, tolerance))
    return box


def drawn_box(node, transform: Affine = IDENTITY, tolerance: float = 0.1) -> Optional[Box]:
    """The exact box ``(x0, y0, x1, y1)`` of what ``node`` draws, in the
    coordinates ``transform`` maps the node's parent coordinates to; None
    when it draws nothing.

    Parameters
    ----------
    node : Group, PathNode or ImageNode
    transform : Affine
        The node's parent coordinates to the output coordinates.
    tolerance : float
        Of the stroke outlines, in output units.
    """
    t = transform
    if isinstance(node, PathNode):
        if node.path is None or len(node.path.verbs) == 0:
            return None
        box = _path_box(node, t, tolerance)
        if node.markers is not None:
            box = _union(box, drawn_box(node.markers, t, tolerance))
        return box
    if isinstance(node, ImageNode):
        return _rect_box(node.clip if node.clip is not None else node.view_rect, t)
    if not isinstance(node, Group):
        return None
    if node.opacity <= 0:
        return None
    ct = t @ node.transform
    if node.filters:
        box = None
        for f in node.filters:
            if f.region is None:            # a filter function: the content's box grown
                inner = _children_box(node, ct, tolerance)
                box = _union(box, _grown(inner, f, ct))
            else:
                box = _union(box, _rect_box(f.region, ct))
    else:
        box = _children_box(node, ct, tolerance)
    if box is not None and node.clip_path is not None:
        box = _intersect(box, _clip_box(node.clip_path, ct, tolerance))
    if box is not None and node.mask is not None:
        box = _intersect(box, _rect_box(node.mask.rect, ct))
    return box


def _children_box(g, ct, tolerance):
    box = None
    for c in g.children:
        box = _union(box, drawn_box(c, ct, tolerance))
    return box


def _grown(box, f, ct):
    """A filter function's reach around the content (blur: 3 deviations;
    drop shadow: its offset too)."""
    if box is None:
        return None
    s = ct.max_scale()
    grow_x = grow_y = 0.0
    shift = (0.0, 0.0)
    for p in f.primitives:
        sd = getattr(p, 'std_dev', None)
        if sd is not None:
            grow_x = max(grow_x, 3 * sd[0] * s)
            grow_y = max(grow_y, 3 * sd[1] * s)
        if hasattr(p, 'dx'):
            shift = (p.dx * s, p.dy * s)
    x0, y0, x1, y1 = box
    out = (x0 - grow_x, y0 - grow_y, x1 + grow_x, y1 + grow_y)
    moved = (out[0] + shift[0], out[1] + shift[1], out[2] + shift[0], out[3] + shift[1])
    res = _union(out, moved)
    return res if all(math.isfinite(v) for v in res) else None
