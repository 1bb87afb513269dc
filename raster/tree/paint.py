"""Paints of the render tree: solid colours, gradients, patterns, and how a
path uses them (:class:`Fill`, :class:`Stroke`).

Every paint is in the user space of the node it paints (the parser has
applied ``objectBoundingBox`` units, ``gradientTransform`` and
``patternTransform``): the renderer maps it to device pixels with the
node's CTM alone.
"""

from ..geometry.rules import StrChoice
from dataclasses import dataclass
from typing import Optional, Tuple, Union

from ..geometry.stroking import StrokeStyle
from ..geometry.rules import FillRule
from ..geometry.transform import IDENTITY, Affine

__all__ = ['RGBA', 'SolidPaint', 'GradientStop', 'LinearGradient', 'RadialGradient',
           'SweepGradient', 'Pattern',
           'MeshGradient', 'MeshInterpolation', 'Paint', 'SpreadMethod', 'Fill', 'Stroke',
           'PaintItem', 'DEFAULT_PAINT_ORDER', 'FillRule']

#: Straight-alpha colour, four floats in [0, 1].
RGBA = Tuple[float, float, float, float]


class SpreadMethod(StrChoice):
    """How a gradient continues outside [0, 1] (``spreadMethod``)."""
    PAD = 'pad'
    REFLECT = 'reflect'
    REPEAT = 'repeat'


class PaintItem(StrChoice):
    """One item of ``paint-order``."""
    FILL = 'fill'
    STROKE = 'stroke'
    MARKERS = 'markers'


#: The default ``paint-order``: fill, then stroke, then markers.
DEFAULT_PAINT_ORDER = (PaintItem.FILL, PaintItem.STROKE, PaintItem.MARKERS)


@dataclass(slots=True, frozen=True)
class SolidPaint:
    """A solid colour."""
    color: RGBA


@dataclass(slots=True, frozen=True)
class GradientStop:
    """A gradient stop: ``offset`` in [0, 1] (non-decreasing along a
    gradient's stops), ``color`` with ``stop-opacity`` folded into alpha."""
    offset: float
    color: RGBA


@dataclass(slots=True, frozen=True)
class LinearGradient:
    """A linear gradient from (x1, y1) at offset 0 to (x2, y2) at offset 1,
    in the gradient space that ``transform`` maps to the painted node's
    user space.  At least two stops."""
    x1: float
    y1: float
    x2: float
    y2: float
    stops: Tuple[GradientStop, ...]
    transform: Affine = IDENTITY
    spread: SpreadMethod = SpreadMethod.PAD
    id: str = ''


@dataclass(slots=True, frozen=True)
class RadialGradient:
    """A two-point conical gradient: the focal circle (fx, fy, fr) at offset
    0 to the end circle (cx, cy, r) at offset 1, in the gradient space that
    ``transform`` maps to the painted node's user space."""
    cx: float
    cy: float
    r: float
    fx: float
    fy: float
    stops: Tuple[GradientStop, ...]
    fr: float = 0.0
    transform: Affine = IDENTITY
    spread: SpreadMethod = SpreadMethod.PAD
    id: str = ''


@dataclass(slots=True, frozen=True)
class SweepGradient:
    """A sweep (conic) gradient about (cx, cy): the colour at a point is
    that of offset ``(angle - start_angle) / (end_angle - start_angle)``,
    where ``angle`` is the point's direction from the centre in degrees in
    [0, 360), measured from the gradient space's x axis towards its y axis
    (``atan2(y - cy, x - cx)``; the angles of a COLRv1 font's sweep
    gradients in its y-up glyph space).  ``spread`` continues it outside
    [0, 1]; ``transform`` maps gradient space to the painted node's user
    space.  At least two stops."""
    cx: float
    cy: float
    start_angle: float
    end_angle: float
    stops: Tuple[GradientStop, ...]
    transform: Affine = IDENTITY
    spread: SpreadMethod = SpreadMethod.PAD
    id: str = ''


@dataclass(slots=True, frozen=True)
class Pattern:
    """A pattern tile: the rectangle ``rect`` (x, y, w, h) of the tile space
    that ``transform`` maps to the painted node's user space, repeated
    without gaps; ``root`` is the tile's content and ``content_transform``
    maps it to tile space (viewBox and ``patternContentUnits`` applied)."""
    rect: Tuple[float, float, float, float]
    root: 'object'          # a raster.tree.nodes.Group
    transform: Affine = IDENTITY
    content_transform: Affine = IDENTITY
    id: str = ''


class MeshInterpolation(StrChoice):
    """``meshgradient/@type``: how colours are interpolated in a patch."""
    BILINEAR = 'bilinear'
    BICUBIC = 'bicubic'


@dataclass(slots=True, frozen=True, eq=False)
class MeshGradient:
    """An SVG 2 mesh gradient: ``rows x cols`` Coons patches in the gradient
    space that ``transform`` maps to the painted node's user space.

    ``patches`` is a (P, 12, 2) float64 array (P = rows * cols, row-major):
    each patch's boundary as four cubic edges, point 0 the top-left corner,
    0-3 the top edge, 3-6 the right, 6-9 the bottom (right to left), 9, 10,
    11, 0 the left (bottom to top); ``colors`` is (P, 4, 4) straight RGBA at
    the corners top-left, top-right, bottom-right, bottom-left
    (:func:`raster.pixels.mesh.mesh_gradient` paints them).  Outside the
    patches the gradient is transparent."""
    patches: object
    colors: object
    shape: Tuple[int, int]
    interpolation: MeshInterpolation = MeshInterpolation.BILINEAR
    transform: Affine = IDENTITY
    id: str = ''


Paint = Union[SolidPaint, LinearGradient, RadialGradient, SweepGradient, Pattern, MeshGradient]


@dataclass(slots=True)
class Fill:
    """How a path is filled: ``paint`` with ``opacity`` (fill-opacity) and
    the fill ``rule``."""
    paint: Paint
    opacity: float = 1.0
    rule: FillRule = FillRule.NONZERO


@dataclass(slots=True)
class Stroke:
    """How a path is stroked: ``paint`` with ``opacity`` (stroke-opacity)
    along the outline of ``style`` (the geometry kernel's stroke style:
    width, join, cap, miter limit, dashes, all in the path's user units).

    >>> Stroke.of(SolidPaint((0, 0, 0, 1)), width=2, cap='round').style.cap == 'round'
    True
    """
    paint: Paint
    style: StrokeStyle = StrokeStyle()
    opacity: float = 1.0

    @classmethod
    def of(cls, paint, opacity=1.0, **style):
        """A Stroke of ``paint`` whose style is ``StrokeStyle(**style)``."""
        return cls(paint, StrokeStyle(**style), opacity)

    @property
    def width(self) -> float:
        """The stroke width (``style.width``)."""
        return self.style.width
