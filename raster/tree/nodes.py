"""Nodes of the render tree: :class:`Tree`, :class:`Group`,
:class:`PathNode`, :class:`ImageNode` (text arrives as glyph-outline
PathNodes)."""

from dataclasses import dataclass, field
from typing import Iterator, List, Optional, Tuple

import numpy as np

from ..geometry.path import Path
from ..geometry.transform import IDENTITY, Affine
from .effects import BlendMode, ClipPath, Mask
from .paint import DEFAULT_PAINT_ORDER, Fill, PaintItem, Stroke

__all__ = ['Node', 'Group', 'PathNode', 'ImageNode', 'Tree', 'walk']


@dataclass(slots=True, eq=False)
class Node:
    """Base of the node kinds; ``id`` is the element's id ('' if none)."""
    id: str = ''


@dataclass(slots=True, eq=False)
class Group(Node):
    """Children drawn with a transform and group effects.

    ``transform`` maps the children's coordinates to the parent's.  In
    drawing order the effects are: ``filters`` (each a
    :class:`raster.tree.filter.Filter`) on the rendered children, then
    ``clip_path`` and ``mask`` (in the group's parent coordinates composed
    with ``transform``: the group's own user space), then ``opacity`` and
    ``blend_mode`` when compositing onto the backdrop.  ``isolate`` asks for
    an isolated group (CSS ``isolation``)."""
    transform: Affine = IDENTITY
    opacity: float = 1.0
    clip_path: Optional[ClipPath] = None
    mask: Optional[Mask] = None
    filters: tuple = ()
    blend_mode: BlendMode = BlendMode.NORMAL
    isolate: bool = False
    children: list = field(default_factory=list)

    @property
    def needs_layer(self) -> bool:
        """True when the group must be rendered into its own layer."""
        return (self.opacity < 1.0 or self.clip_path is not None or self.mask is not None
                or bool(self.filters) or self.blend_mode != BlendMode.NORMAL
                or self.isolate)


@dataclass(slots=True, eq=False)
class PathNode(Node):
    """A path drawn in its parent group's coordinates: ``fill`` and
    ``stroke`` (None when not painted) and ``markers`` (a Group of marker
    instances in the same coordinates, or None) in ``paint_order``.
    ``antialias`` is False for ``shape-rendering`` crispEdges /
    optimizeSpeed."""
    path: Path = None
    fill: Optional[Fill] = None
    stroke: Optional[Stroke] = None
    paint_order: Tuple[PaintItem, ...] = DEFAULT_PAINT_ORDER
    antialias: bool = True
    markers: Optional[Group] = None


@dataclass(slots=True, eq=False)
class ImageNode(Node):
    """An image in the rectangle ``view_rect`` (x, y, w, h) of the parent's
    coordinates.  ``transform`` maps image pixels (a raster image) or the
    image document's px (an SVG image) to parent coordinates
    (preserveAspectRatio applied); ``clip`` (x, y, w, h) is the viewport to
    clip to, or None.  ``pixels`` is an (H, W, 4) uint8 straight RGBA array;
    an SVG image is a :class:`Tree` in ``tree`` instead.  ``smooth``:
    bilinear resampling (else nearest)."""
    view_rect: Tuple[float, float, float, float] = (0, 0, 0, 0)
    transform: Affine = IDENTITY
    clip: Optional[Tuple[float, float, float, float]] = None
    pixels: Optional[np.ndarray] = None
    tree: Optional['Tree'] = None
    smooth: bool = True
    opacity: float = 1.0


@dataclass(slots=True, eq=False)
class Tree:
    """A resolved document: its natural size in px and the root group;
    ``ids`` maps an element id to the first node built for it."""
    width: float
    height: float
    root: Group
    ids: dict = field(default_factory=dict)


def walk(node, transform: Affine = IDENTITY) -> Iterator[Tuple[object, Affine]]:
    """Yield ``(node, transform)`` for ``node`` and every node below it in
    document order (groups and their children; not markers, clip paths,
    masks or pattern content).  The transform maps the node's own
    coordinates (a Group's children's, a PathNode's path) to the
    coordinates ``transform`` maps ``node``'s parent to."""
    stack = [(node, transform)]
    while stack:
        n, t = stack.pop()
        if isinstance(n, Group):
            t2 = t @ n.transform
            yield n, t2
            stack.extend((c, t2) for c in reversed(n.children))
        else:
            yield n, t
