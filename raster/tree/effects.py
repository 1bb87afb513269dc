"""Group effects of the render tree: clip paths, masks and blend modes."""

from ..geometry.rules import StrChoice
from dataclasses import dataclass
from typing import Optional, Tuple

from ..geometry.transform import IDENTITY, Affine

__all__ = ['BlendMode', 'MaskType', 'ClipPath', 'Mask']


class BlendMode(StrChoice):
    """``mix-blend-mode`` (and ``feBlend`` ``mode``): the 16 blend modes of
    Compositing and Blending Level 1."""
    NORMAL = 'normal'
    MULTIPLY = 'multiply'
    SCREEN = 'screen'
    OVERLAY = 'overlay'
    DARKEN = 'darken'
    LIGHTEN = 'lighten'
    COLOR_DODGE = 'color-dodge'
    COLOR_BURN = 'color-burn'
    HARD_LIGHT = 'hard-light'
    SOFT_LIGHT = 'soft-light'
    DIFFERENCE = 'difference'
    EXCLUSION = 'exclusion'
    HUE = 'hue'
    SATURATION = 'saturation'
    COLOR = 'color'
    LUMINOSITY = 'luminosity'


class MaskType(StrChoice):
    """``mask-type``: the mask value is the content's luminance times its
    alpha, or its alpha alone."""
    LUMINANCE = 'luminance'
    ALPHA = 'alpha'


@dataclass(slots=True, eq=False)
class ClipPath:
    """A clip path: the union of the geometry of ``root``'s paths (each
    with its fill rule, which carries ``clip-rule``), mapped to the clipped
    node's user space by ``transform`` (its own transform and any
    objectBoundingBox mapping), itself clipped by ``clip_path``."""
    root: 'object'                      # a raster.tree.nodes.Group
    transform: Affine = IDENTITY
    clip_path: Optional['ClipPath'] = None
    id: str = ''


@dataclass(slots=True, eq=False)
class Mask:
    """A mask: the content ``root`` (in the masked node's user space)
    rendered and reduced to one value per pixel by ``kind``, limited to
    ``rect`` (x, y, w, h) of that space, multiplied by ``mask``."""
    rect: Tuple[float, float, float, float]
    root: 'object'                      # a raster.tree.nodes.Group
    kind: MaskType = MaskType.LUMINANCE
    mask: Optional['Mask'] = None
    id: str = ''
