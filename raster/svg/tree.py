"""The resolved render tree.

An SVG document is resolved into a few node kinds, after the usvg model:
:class:`Group`, :class:`PathNode` and :class:`ImageNode`; text is laid out
into glyph-outline PathNodes (raster.svg.text).  Everything is resolved when the
tree is built: CSS and inheritance, units, ``use``/``symbol``/nested ``svg``,
``switch``, ``display``/``visibility``, transforms and viewBoxes, colours and
``currentColor``.  The renderer never parses a string.

Coordinates: a :class:`Group`'s ``transform`` maps its children's coordinates
to its parent's.  The tree's root group maps the document's user space to
*document pixels*: the document's natural size ``(width, height)`` in CSS px.
Rendering at another size prepends a scale.

Groups that change nothing (identity transform, opacity 1, no clip, mask,
filter or blend mode) are dropped by the builder; a group with only a
transform costs the renderer nothing (no layer is allocated).
"""

from dataclasses import dataclass, field
from typing import Optional, Tuple, Union

import numpy as np

from ..geometry.path import Path
from ..geometry.transform import IDENTITY, Affine

RGBA = Tuple[float, float, float, float]


@dataclass(slots=True)
class SolidPaint:
    """A solid colour: straight-alpha RGBA floats in [0, 1]."""
    color: RGBA


@dataclass(slots=True)
class GradientStop:
    offset: float           # in [0, 1], non-decreasing along the list
    color: RGBA             # straight alpha, stop-opacity folded into alpha


@dataclass(slots=True)
class LinearGradient:
    """Resolved linear gradient. ``units`` is 'userSpaceOnUse' or
    'objectBoundingBox' (then x1..y2 are fractions of the painted element's
    bbox); ``transform`` is the gradientTransform."""
    x1: float
    y1: float
    x2: float
    y2: float
    stops: list
    units: str = 'objectBoundingBox'
    transform: Affine = IDENTITY
    spread: str = 'pad'      # 'pad' | 'reflect' | 'repeat'
    id: str = ''


@dataclass(slots=True)
class RadialGradient:
    cx: float
    cy: float
    r: float
    fx: float
    fy: float
    stops: list
    fr: float = 0.0
    units: str = 'objectBoundingBox'
    transform: Affine = IDENTITY
    spread: str = 'pad'
    id: str = ''


@dataclass(slots=True)
class Pattern:
    """Resolved pattern tile: ``rect`` (x, y, w, h) in pattern units,
    ``content_transform`` maps content to tile space (viewBox or
    patternContentUnits), ``root`` holds the tile content."""
    rect: Tuple[float, float, float, float]
    root: 'Group'
    units: str = 'objectBoundingBox'
    content_units: str = 'userSpaceOnUse'
    transform: Affine = IDENTITY
    content_transform: Affine = IDENTITY
    view_box: Optional[Tuple[float, float, float, float]] = None
    id: str = ''
    # (align, meet_or_slice) for a viewBox; None: 'xMidYMid meet'.  Needed
    # when patternUnits=objectBoundingBox, where the tile size (and so the
    # viewBox mapping) is only known when the painted element is.
    preserve_aspect_ratio: Optional[Tuple[str, str]] = None


Paint = Union[SolidPaint, LinearGradient, RadialGradient, Pattern]


@dataclass(slots=True)
class Fill:
    paint: Paint
    opacity: float = 1.0            # fill-opacity
    rule: str = 'nonzero'           # 'nonzero' | 'evenodd'
    context_element: bool = False   # paint came from context-fill/-stroke


@dataclass(slots=True)
class Stroke:
    """Resolved stroke: lengths in the element's user units."""
    paint: Paint
    width: float = 1.0
    opacity: float = 1.0
    join: str = 'miter'             # miter | miter-clip | round | bevel | arcs
    cap: str = 'butt'               # butt | round | square
    miterlimit: float = 4.0
    dash: Optional[Tuple[float, ...]] = None   # None: solid
    dash_offset: float = 0.0


@dataclass(slots=True)
class ClipPath:
    """A resolved clipPath: ``transform`` (its own transform, plus the
    object-bounding-box mapping when clipPathUnits=objectBoundingBox) maps
    the children to the clipped element's user space."""
    root: 'Group'
    transform: Affine = IDENTITY
    clip_path: Optional['ClipPath'] = None
    id: str = ''


@dataclass(slots=True)
class Mask:
    """A resolved mask: ``rect`` in the masked element's user space, ``kind``
    'luminance' or 'alpha'; ``root`` content in the masked element's user
    space (maskContentUnits already applied)."""
    rect: Tuple[float, float, float, float]
    root: 'Group'
    kind: str = 'luminance'
    mask: Optional['Mask'] = None
    id: str = ''


@dataclass(slots=True, eq=False)
class Node:
    id: str = ''


@dataclass(slots=True, eq=False)
class Group(Node):
    transform: Affine = IDENTITY
    opacity: float = 1.0
    clip_path: Optional[ClipPath] = None
    mask: Optional[Mask] = None
    filters: list = field(default_factory=list)
    blend_mode: str = 'normal'
    isolate: bool = False
    children: list = field(default_factory=list)

    @property
    def needs_layer(self):
        """True when the group must be rendered into its own layer."""
        return (self.opacity < 1.0 or self.clip_path is not None or self.mask is not None
                or bool(self.filters) or self.blend_mode != 'normal' or self.isolate)


@dataclass(slots=True, eq=False)
class PathNode(Node):
    """A path drawn in its parent group's coordinates.  ``path`` is in those
    coordinates; ``fill``/``stroke`` are None when not painted;
    ``paint_order`` lists 'fill', 'stroke', 'markers' in drawing order."""
    path: Path = None
    fill: Optional[Fill] = None
    stroke: Optional[Stroke] = None
    paint_order: Tuple[str, ...] = ('fill', 'stroke', 'markers')
    antialias: bool = True
    markers: Optional['Group'] = None      # resolved marker instances


@dataclass(slots=True, eq=False)
class ImageNode(Node):
    """A raster image placed in the rectangle ``view_rect`` (x, y, w, h) of
    the parent's coordinates (preserveAspectRatio already applied:
    ``transform`` maps image pixels to parent coordinates, ``clip`` is the
    viewport to clip to).  ``pixels`` is an (H, W, 4) uint8 straight RGBA
    array; an SVG image is a :class:`Tree` in ``tree`` instead."""
    view_rect: Tuple[float, float, float, float] = (0, 0, 0, 0)
    transform: Affine = IDENTITY
    clip: Optional[Tuple[float, float, float, float]] = None
    pixels: Optional[np.ndarray] = None
    tree: Optional['Tree'] = None
    smooth: bool = True
    opacity: float = 1.0


@dataclass(slots=True, eq=False)
class Tree:
    """A resolved document: natural size in px and the root group."""
    width: float
    height: float
    root: Group
    ids: dict = field(default_factory=dict)     # id -> Node, for --id


def walk(node, transform=IDENTITY):
    """Yield ``(node, absolute_transform)`` for every node in document order;
    the transform maps the node's coordinates to the tree's document px."""
    stack = [(node, transform)]
    while stack:
        n, t = stack.pop()
        if isinstance(n, Group):
            t2 = t @ n.transform
            yield n, t2
            stack.extend((c, t2) for c in reversed(n.children))
        else:
            yield n, t
