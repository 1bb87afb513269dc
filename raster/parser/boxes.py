"""Bounding boxes of converted content, for ``objectBoundingBox`` units
and document sizes (exact boxes of the paths, :func:`raster.bbox`)."""

import math

from ..geometry.bounds import bbox as exact_bbox
from ..errors import RasterError
from ..geometry.transform import IDENTITY
from ..tree import Group, ImageNode, PathNode, walk

__all__ = ['nodes_box', 'object_box', 'layer_box', 'content_box', 'walk_all', 'Boxed']


class Boxed(list):
    """A list of nodes with a known object bounding box ``box`` ((x, y, w,
    h), or None): text, whose box comes from its font metrics, not from
    its glyph outlines (SVG 2, 11.11: the bounding box of text is the
    union of its glyph cells)."""

    def __init__(self, nodes, box):
        super().__init__(nodes)
        self.box = box


def walk_all(nodes, transform=IDENTITY):
    """:func:`raster.tree.walk` over a list of sibling nodes."""
    for node in nodes:
        yield from walk(node, transform)


def nodes_box(nodes, stroke_pad=False):
    """(x0, y0, x1, y1) exact fill box of the paths under ``nodes`` in
    their parent's coordinates (an image counts as its viewport rectangle),
    widened by half of each stroke's width when ``stroke_pad``; None when
    there is no geometry."""
    lo = [math.inf, math.inf]
    hi = [-math.inf, -math.inf]
    for n, t in walk_all(nodes):
        if isinstance(n, ImageNode):
            # an image's box is its viewport (x, y, width, height)
            x, y, w, h = n.view_rect
            c = t.apply([[x, y], [x + w, y], [x + w, y + h], [x, y + h]])
            lo = [min(lo[0], float(c[:, 0].min())), min(lo[1], float(c[:, 1].min()))]
            hi = [max(hi[0], float(c[:, 0].max())), max(hi[1], float(c[:, 1].max()))]
        elif isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
            try:
                x0, y0, x1, y1 = exact_bbox(n.path, t)
            except RasterError:
                continue
            pad = 0.0
            if stroke_pad and n.stroke is not None:
                pad = n.stroke.width * 0.5 * t.max_scale()
            lo = [min(lo[0], x0 - pad), min(lo[1], y0 - pad)]
            hi = [max(hi[0], x1 + pad), max(hi[1], y1 + pad)]
    if not math.isfinite(lo[0]):
        return None
    return lo[0], lo[1], hi[0], hi[1]


def object_box(nodes):
    """(x, y, w, h) object bounding box (fill box) of nodes in their
    parent's user space, or None when there is no geometry (a
    :class:`Boxed` list gives its own box)."""
    if isinstance(nodes, Boxed):
        return nodes.box
    b = nodes_box(nodes)
    return None if b is None else (b[0], b[1], b[2] - b[0], b[3] - b[1])


def content_box(group):
    """Visual bounds (exact fill boxes widened by half the stroke width) of
    a group's content in its parent's coordinates, or None when empty."""
    b = nodes_box([group], stroke_pad=True)
    if b is None or not (b[2] > b[0] and b[3] > b[1]):
        return None
    return b


def layer_box(nodes, t):
    """(x0, y0, x1, y1) bounding box of ``nodes`` mapped by ``t``, composed
    the way resvg composes the box of a ``use`` element: each group's box
    is the box of its children's boxes' corners under the group transform
    (not the exact box of the transformed geometry).  None when empty."""
    lo = [math.inf, math.inf]
    hi = [-math.inf, -math.inf]
    for n in nodes:
        if isinstance(n, Group):
            b = layer_box(n.children, IDENTITY)
        elif isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
            try:
                b = exact_bbox(n.path)
            except RasterError:
                b = None
        else:
            b = None
        if b is None:
            continue
        m = t @ n.transform if isinstance(n, Group) else t
        c = m.apply([[b[0], b[1]], [b[2], b[1]], [b[2], b[3]], [b[0], b[3]]])
        lo = [min(lo[0], c[:, 0].min()), min(lo[1], c[:, 1].min())]
        hi = [max(hi[0], c[:, 0].max()), max(hi[1], c[:, 1].max())]
    if not math.isfinite(lo[0]):
        return None
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
