"""Filter effects of the render tree: one class per primitive kind.

A :class:`Filter` is a resolved ``<filter>`` element (or a CSS filter
function such as ``blur(2px)``, which has no region): its region and the
primitives in order, every length in the filtered group's user units
(``filterUnits``/``primitiveUnits`` applied), every input resolved to
a :class:`Source` (the source graphic, its alpha, or the previous
primitive's result) or a :class:`Result` of an earlier primitive.  A primitive that is in error (a bad feConvolveMatrix,
a lighting primitive without a light, an unsupported kind) is a
:class:`Flood` of transparent black, which is what it draws.

The renderer dispatches on the primitive's class.
"""

from ..geometry.rules import StrChoice
from dataclasses import dataclass, field
from typing import Optional, Tuple, Union

import numpy as np

from .effects import BlendMode
from .paint import RGBA

__all__ = ['Source', 'PREVIOUS', 'Result', 'Input', 'Filter', 'Primitive', 'GaussianBlur', 'Offset',
           'Flood', 'Merge', 'CompositeOperator', 'Composite', 'Blend', 'ColorMatrix',
           'TableTransfer', 'DiscreteTransfer', 'LinearTransfer', 'GammaTransfer',
           'ComponentTransfer', 'MorphologyOperator', 'Morphology', 'Tile', 'Image',
           'EdgeMode', 'ConvolveMatrix', 'DistantLight', 'PointLight', 'SpotLight',
           'DiffuseLighting', 'SpecularLighting', 'Turbulence', 'DisplacementMap',
           'DropShadow', 'TRANSPARENT']

Rect = Tuple[Optional[float], Optional[float], Optional[float], Optional[float]]

#: Transparent black, the colour of a primitive in error.
TRANSPARENT = (0.0, 0.0, 0.0, 0.0)


class Source(StrChoice):
    """The filter's own inputs, and the previous primitive's result."""
    GRAPHIC = 'SourceGraphic'
    ALPHA = 'SourceAlpha'
    PREVIOUS = 'previous'


#: The result of the primitive just before (never the first primitive's
#: input: the parser gives that :data:`Source.GRAPHIC`).
PREVIOUS = Source.PREVIOUS


@dataclass(slots=True, frozen=True)
class Result:
    """The result of an earlier primitive of the same filter, by its
    ``result`` name (the parser guarantees it exists)."""
    name: str


Input = Union[Source, Result]


@dataclass(slots=True)
class Primitive:
    """What every primitive has: its ``inputs`` (:class:`Source` or
    :class:`Result`), its ``result`` name ('' if none), its ``subregion``
    (x, y, w, h) in user units with None for the parts that default to the
    filter region, and ``linear``: True when it works in linearRGB
    (``color-interpolation-filters``)."""
    inputs: Tuple[Input, ...] = ()
    result: str = ''
    subregion: Rect = (None, None, None, None)
    linear: bool = True


@dataclass(slots=True)
class GaussianBlur(Primitive):
    """feGaussianBlur: ``std_dev`` (x, y) in user units."""
    std_dev: Tuple[float, float] = (0.0, 0.0)


@dataclass(slots=True)
class Offset(Primitive):
    """feOffset by (dx, dy) user units."""
    dx: float = 0.0
    dy: float = 0.0


@dataclass(slots=True)
class Flood(Primitive):
    """feFlood with ``color`` (flood-opacity folded into alpha)."""
    color: RGBA = TRANSPARENT


@dataclass(slots=True)
class Merge(Primitive):
    """feMerge: the inputs composited in order (source-over)."""


class CompositeOperator(StrChoice):
    """feComposite ``operator``."""
    OVER = 'over'
    IN = 'in'
    OUT = 'out'
    ATOP = 'atop'
    XOR = 'xor'
    ARITHMETIC = 'arithmetic'


@dataclass(slots=True)
class Composite(Primitive):
    """feComposite of inputs[0] onto inputs[1]; ``k`` (k1..k4) for
    arithmetic."""
    operator: CompositeOperator = CompositeOperator.OVER
    k: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)


@dataclass(slots=True)
class Blend(Primitive):
    """feBlend of inputs[0] (source) onto inputs[1] (backdrop)."""
    mode: BlendMode = BlendMode.NORMAL


@dataclass(slots=True)
class ColorMatrix(Primitive):
    """feColorMatrix as a (4, 5) float64 matrix on straight RGBA (every
    ``type`` is reduced to its matrix)."""
    matrix: np.ndarray = field(default_factory=lambda: np.hstack([np.eye(4), np.zeros((4, 1))]))


@dataclass(slots=True, frozen=True)
class TableTransfer:
    """feFunc type="table": piecewise linear through ``values``."""
    values: Tuple[float, ...]


@dataclass(slots=True, frozen=True)
class DiscreteTransfer:
    """feFunc type="discrete": a step function of ``values``."""
    values: Tuple[float, ...]


@dataclass(slots=True, frozen=True)
class LinearTransfer:
    """feFunc type="linear": ``slope * c + intercept``."""
    slope: float = 1.0
    intercept: float = 0.0


@dataclass(slots=True, frozen=True)
class GammaTransfer:
    """feFunc type="gamma": ``amplitude * c ** exponent + offset``."""
    amplitude: float = 1.0
    exponent: float = 1.0
    offset: float = 0.0


@dataclass(slots=True)
class ComponentTransfer(Primitive):
    """feComponentTransfer: ``funcs`` maps a channel index (0..3 = R, G, B,
    A) to its transfer function; channels not listed are unchanged."""
    funcs: dict = field(default_factory=dict)


class MorphologyOperator(StrChoice):
    ERODE = 'erode'
    DILATE = 'dilate'


@dataclass(slots=True)
class Morphology(Primitive):
    """feMorphology with ``radius`` (x, y) in user units (a negative or
    all-zero radius passes the input through)."""
    operator: MorphologyOperator = MorphologyOperator.ERODE
    radius: Tuple[float, float] = (0.0, 0.0)


@dataclass(slots=True)
class Tile(Primitive):
    """feTile: the input's subregion repeated over this subregion."""


@dataclass(slots=True)
class Image(Primitive):
    """feImage: ``root`` (a Group in the filtered group's user space, for a
    referenced element or an external image already fitted into the
    subregion) drawn translated by ``shift``."""
    root: 'object' = None
    shift: Tuple[float, float] = (0.0, 0.0)


class EdgeMode(StrChoice):
    DUPLICATE = 'duplicate'
    WRAP = 'wrap'
    NONE = 'none'


@dataclass(slots=True)
class ConvolveMatrix(Primitive):
    """feConvolveMatrix with a valid (oy, ox) float64 ``kernel``."""
    kernel: np.ndarray = None
    divisor: float = 1.0
    bias: float = 0.0
    target: Tuple[int, int] = (0, 0)
    edge_mode: EdgeMode = EdgeMode.DUPLICATE
    preserve_alpha: bool = False


@dataclass(slots=True, frozen=True)
class DistantLight:
    """feDistantLight: direction angles in degrees."""
    azimuth: float = 0.0
    elevation: float = 0.0


@dataclass(slots=True, frozen=True)
class PointLight:
    """fePointLight at (x, y, z) user units."""
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0


@dataclass(slots=True, frozen=True)
class SpotLight:
    """feSpotLight at (x, y, z) pointing at ``points_at``; the cone's
    ``specular_exponent`` and ``limiting_cone_angle`` (degrees, None: no
    limit)."""
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    points_at: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    specular_exponent: float = 1.0
    limiting_cone_angle: Optional[float] = None


Light = Union[DistantLight, PointLight, SpotLight]


@dataclass(slots=True)
class DiffuseLighting(Primitive):
    """feDiffuseLighting of the input's alpha as a bump map."""
    light: Light = DistantLight()
    color: Tuple[float, float, float] = (1.0, 1.0, 1.0)
    surface_scale: float = 1.0
    diffuse_constant: float = 1.0


@dataclass(slots=True)
class SpecularLighting(Primitive):
    """feSpecularLighting (``specular_exponent`` in [1, 128])."""
    light: Light = DistantLight()
    color: Tuple[float, float, float] = (1.0, 1.0, 1.0)
    surface_scale: float = 1.0
    specular_constant: float = 1.0
    specular_exponent: float = 1.0


@dataclass(slots=True)
class Turbulence(Primitive):
    """feTurbulence (no inputs) in the filtered group's user space;
    ``stitch`` (``stitchTiles="stitch"``): the noise tiles its primitive
    subregion seamlessly."""
    base_frequency: Tuple[float, float] = (0.0, 0.0)
    num_octaves: int = 1
    seed: int = 0
    fractal: bool = False
    stitch: bool = False


@dataclass(slots=True)
class DisplacementMap(Primitive):
    """feDisplacementMap of inputs[0] by the channels (0..3 = R, G, B, A)
    of inputs[1]; ``scale`` in user units."""
    scale: float = 0.0
    x_channel: int = 3
    y_channel: int = 3


@dataclass(slots=True)
class DropShadow(Primitive):
    """feDropShadow: the input over its blurred, offset, flood-coloured
    alpha."""
    std_dev: Tuple[float, float] = (2.0, 2.0)
    dx: float = 2.0
    dy: float = 2.0
    color: RGBA = (0.0, 0.0, 0.0, 1.0)


@dataclass(slots=True)
class Filter:
    """A resolved filter: ``region`` (x, y, w, h) in the filtered group's
    user space, or None for a CSS filter function (no region: it covers
    the canvas), and its primitives in order."""
    region: Optional[Tuple[float, float, float, float]]
    primitives: list
    id: str = ''
