"""Paints of the render tree: solid colours, and how a path uses its
paints (:class:`Fill`, :class:`Stroke`).

Every paint is in the user space of the node it paints (the parser has
applied ``objectBoundingBox`` units, ``gradientTransform`` and
``patternTransform``): the renderer maps it to device pixels with the
node's CTM alone.  The gradients and patterns live in
:mod:`raster.tree.servers`, which loads with the first of them; their
names (and the :data:`Paint` union) are also found here, on first use.
"""

from dataclasses import dataclass
from typing import Tuple, Union

from ..geometry.rules import FillRule, StrChoice
from ..geometry.stroking import StrokeStyle

__all__ = ['RGBA', 'SolidPaint', 'GradientStop', 'LinearGradient', 'RadialGradient',
           'SweepGradient', 'Pattern',
           'MeshGradient', 'MeshInterpolation', 'Paint', 'SpreadMethod', 'Fill', 'Stroke',
           'PaintItem', 'DEFAULT_PAINT_ORDER', 'FillRule']

#: The names of :mod:`raster.tree.servers`, and the :data:`Paint` union of
#: all paints, exported here (and by :mod:`raster.tree`) on first use.
SERVER_NAMES = frozenset(['SpreadMethod', 'GradientStop', 'LinearGradient', 'RadialGradient',
                          'SweepGradient', 'Pattern', 'MeshInterpolation', 'MeshGradient',
                          'Paint'])


def __getattr__(name):
    if name not in SERVER_NAMES:
        raise AttributeError('module %r has no attribute %r' % (__name__, name))
    from . import servers
    if name != 'Paint':
        return getattr(servers, name)
    global Paint
    #: Any paint of the tree.
    Paint = Union[SolidPaint, servers.LinearGradient, servers.RadialGradient,
                  servers.SweepGradient, servers.Pattern, servers.MeshGradient]
    return Paint


#: Straight-alpha colour, four floats in [0, 1].
RGBA = Tuple[float, float, float, float]


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


@dataclass(slots=True)
class Fill:
    """How a path is filled: ``paint`` with ``opacity`` (fill-opacity) and
    the fill ``rule``."""
    paint: 'Paint'
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
    paint: 'Paint'
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
