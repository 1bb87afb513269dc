"""The resolved render tree: the contract between the parser and the renderer.

The parser (:mod:`raster.parser`) turns an SVG document into a :class:`Tree`;
the renderer (:mod:`raster.renderer`) draws one.  Neither knows the other:
everything either needs is here, fully resolved and typed.

Guarantees of a tree built by the parser:

* **Nothing to parse.** Colours are straight-alpha RGBA float tuples in
  [0, 1], lengths are user units, transforms are :class:`~raster.geometry.
  transform.Affine`, closed sets are enums (:class:`BlendMode`,
  :class:`MaskType`, :class:`SpreadMethod`, :class:`PaintItem`, the filter
  enums), geometry is an immutable :class:`~raster.geometry.path.Path`.
* **Nothing relative.** CSS, inheritance, ``use``/``symbol``/nested ``svg``,
  ``switch``, ``display``/``visibility``, percentages, ``em``, viewBoxes,
  ``currentColor`` and every ``objectBoundingBox`` unit (gradients,
  patterns, clip paths, masks, filters) are resolved: paints and effects
  are in the user space of the node that uses them.
* **Coordinates.** A :class:`Group`'s ``transform`` maps its children's
  coordinates to its parent's; the root group maps the document's user
  space to *document pixels* (the natural size ``width x height`` in CSS
  px).  A :class:`PathNode`'s path, paints, clip path and mask are in its
  parent group's coordinates.
* Groups that change nothing are dropped; a group with only a transform
  costs the renderer nothing.

Modules: :mod:`.nodes` (Tree, Group, PathNode, ImageNode), :mod:`.paint`
(SolidPaint, Fill, Stroke), :mod:`.servers` (gradients, patterns),
:mod:`.effects` (ClipPath, Mask, BlendMode), :mod:`.filter` (one class per
filter primitive kind).  Two of them load on first use: :mod:`.servers`
with the first document that has a paint server (or the first use of one
of its names here), :mod:`.filter` with the first filter.
"""

from .paint import (RGBA, SERVER_NAMES, SolidPaint, Fill, FillRule, Stroke, PaintItem,
                    DEFAULT_PAINT_ORDER)
from .effects import BlendMode, MaskType, ClipPath, Mask
from .nodes import Node, Group, PathNode, ImageNode, Tree, walk

__all__ = ['RGBA', 'SolidPaint', 'GradientStop', 'LinearGradient', 'RadialGradient', 'Pattern',
           'SweepGradient', 'MeshGradient', 'MeshInterpolation', 'Paint', 'SpreadMethod', 'Fill', 'FillRule', 'Stroke', 'PaintItem', 'DEFAULT_PAINT_ORDER',
           'BlendMode', 'MaskType', 'ClipPath', 'Mask', 'Node', 'Group', 'PathNode',
           'ImageNode', 'Tree', 'walk', 'filter']


def __getattr__(name):
    # the paint servers and the filter classes (modules of dataclasses,
    # which cost a plain document's start-up to create) load with the first
    # document that needs them, or the first use of their names here
    if name in SERVER_NAMES:
        from . import paint
        return getattr(paint, name)
    if name == 'filter':
        import importlib
        return importlib.import_module(__name__ + '.filter')
    raise AttributeError('module %r has no attribute %r' % (__name__, name))
