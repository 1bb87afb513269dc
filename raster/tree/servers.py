"""Paint servers of the render tree: gradients and patterns.

Every paint here is in the user space of the node it paints (the parser
has applied ``objectBoundingBox`` units, ``gradientTransform`` and
``patternTransform``): the renderer maps it to device pixels with the
node's CTM alone.  This module loads with the first document that has a
paint server (``raster.tree`` and :mod:`raster.tree.paint` export its
names on first use), so plain documents do not create its classes.
"""

from dataclasses import dataclass
from typing import Tuple

from ..geometry.rules import StrChoice
from ..geometry.transform import IDENTITY, Affine

__all__ = ['SpreadMethod', 'GradientStop', 'LinearGradient', 'RadialGradient', 'SweepGradient',
           'Pattern', 'MeshInterpolation', 'MeshGradient']


class SpreadMethod(StrChoice):
    """How a gradient continues outside [0, 1] (``spreadMethod``)."""
    PAD = 'pad'
    REFLECT = 'reflect'
    REPEAT = 'repeat'


@dataclass(slots=True, frozen=True)
class GradientStop:
    """A gradient stop: ``offset`` in [0, 1] (non-decreasing along a
    gradient's stops), ``color`` with ``stop-opacity`` folded into alpha."""
    offset: float
    color: Tuple[float, float, float, float]     # raster.tree.paint.RGBA


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

