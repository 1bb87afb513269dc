"""Paints: ``fill``/``stroke`` values to tree paints.

Colours become shared :class:`~raster.tree.SolidPaint` objects here; a
``url()`` that references a paint server loads
:mod:`raster.parser.servers` (gradients, patterns, mesh gradients) with
the first such reference, so a document without one never creates those
classes.
"""

from ..tree import SolidPaint
from .style import local_name
from .values import parse_paint

__all__ = ['paint', 'PAINT_SERVERS']

#: Local names of the elements a ``url()`` paint can use.
PAINT_SERVERS = frozenset(['linearGradient', 'radialGradient', 'pattern', 'meshgradient'])


def paint(value, inh, ctx, state, cache, path=None, box=None):
    """The paint of a ``fill``/``stroke`` value for a node with geometry
    ``path`` (its box, or ``box`` (x0, y0, x1, y1) when given, resolves
    objectBoundingBox units); None when nothing is painted.  Without
    ``path`` a server needing a box is returned as is (a context paint,
    placed later by :func:`raster.parser.servers.in_space`)."""
    p = parse_paint(value)
    if p is None:
        return None
    kind = p.kind
    if kind == 'color':
        solid = cache.table('solid')
        c = solid.get(p.color)        # shared: paints are never modified
        if c is None:
            c = solid[p.color] = SolidPaint(p.color)
        return c
    if kind == 'current':
        return SolidPaint(inh['_color'])
    if kind == 'url':
        tgt = cache.by_id.get(p.url)
        name = local_name(tgt) if tgt is not None else None
        if name in PAINT_SERVERS:
            from .servers import UNSUPPORTED, url_paint      # loaded by the first server
            r = url_paint(tgt, name, ctx, cache, path, box)
            if r is not UNSUPPORTED:
                return r
        fb = p.fallback
        if fb is None:
            return None
        if fb.kind == 'color':
            return SolidPaint(fb.color)
        if fb.kind == 'current':
            return SolidPaint(inh['_color'])
        return None
    if kind in ('context-fill', 'context-stroke') and state is not None and state.context:
        return state.context[0 if kind == 'context-fill' else 1]
    return None     # none, or context-fill / context-stroke without a context
