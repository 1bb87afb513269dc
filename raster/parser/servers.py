"""Paint servers: the ``linearGradient``, ``radialGradient``, ``pattern``
(and, through :mod:`raster.parser.mesh`, ``meshgradient``) elements that
``url()`` paints reference, to tree paints.  Loaded by the first of them
(:func:`raster.parser.paint.paint`).

A paint server element is resolved once per length context into a
*server* (:class:`GradientServer`, :class:`PatternServer`): the tree paint
in the server's own units plus whether those are ``objectBoundingBox``
units.  :func:`in_space` turns a server into a tree paint in the user
space of the node it paints, given that node's bounding box: the tree
never holds objectBoundingBox units.  Context paints (``context-fill``,
``context-stroke`` in ``use`` content and markers) stay servers until the
context element's box is known (see :func:`in_space`).

Mesh gradients (SVG 2 ``meshgradient``) are read by :mod:`raster.parser.mesh`
and resolved like gradients.  Gradients: ``href`` inheritance with cycles cut, stop offsets clamped and
made monotonic, ``stop-color``/``stop-opacity`` with ``currentColor``,
``transform-origin``; a gradient with one stop is that stop's solid
colour; one without stops paints the fallback colour (else nothing).
Patterns: ``href`` inheritance, ``patternUnits``, ``patternContentUnits``,
``viewBox`` with ``preserveAspectRatio``, ``patternTransform``; a
recursive pattern, or one whose content draws nothing, paints nothing
(a transparent pattern).  A paint server that cannot paint paints
the fallback colour of the ``url()`` (``fill="url(#p) lime"``; none given:
nothing): a gradient without stops, a pattern without content (no
element children, itself or through ``href``), with a tile of zero (or
negative) size or a viewBox of zero size, and a server with objectBoundingBox units (``gradientUnits``,
``patternUnits`` or ``patternContentUnits``) on a shape whose bounding box
has no width or no height (a horizontal line).
"""

import dataclasses
from dataclasses import dataclass
from typing import Optional, Tuple

from ..geometry.bounds import bbox as exact_bbox
from ..errors import RasterError
from ..geometry.transform import IDENTITY, Affine
from ..tree import Group, SolidPaint
from ..tree.servers import GradientStop, LinearGradient, Pattern, RadialGradient, SpreadMethod
from .context import SVG_NS, State
from .convert import convert_children
from .document import chain_attr
from .refs import href_chain
from .style import doc_style, number_or_percent, stop_color
from .values import (LengthContext, parse_length, parse_preserve_aspect_ratio, parse_transform,
                     parse_transform_origin, resolve_viewbox, viewbox_transform, ZERO_VIEWBOX)

__all__ = ['url_paint', 'server_of', 'in_space', 'GradientServer', 'PatternServer',
           'UNSUPPORTED']

_P = '{%s}' % SVG_NS
_SPREADS = {m.value: m for m in SpreadMethod}

#: A paint server that cannot paint (no stops, empty box): use the fallback.
UNSUPPORTED = object()


@dataclass(frozen=True, eq=False)
class GradientServer:
    """A resolved gradient element: ``paint`` with its coordinates and
    ``transform`` (gradientTransform) in the gradient's units, which are
    fractions of the painted node's box when ``obb``."""
    paint: object
    obb: bool

    def needs_box(self):
        return self.obb


@dataclass(frozen=True, eq=False)
class PatternServer:
    """A resolved pattern element: the tile ``rect`` in pattern units
    (fractions of the box when ``obb``), the content ``root`` in content
    units (fractions of the box when ``content_obb`` and there is no
    viewBox), ``transform`` (patternTransform), and either the viewBox
    (``view_box``, ``par``) or ``content_transform``."""
    rect: Tuple[float, float, float, float]
    root: Group
    obb: bool
    content_obb: bool
    transform: Affine
    content_transform: Affine
    view_box: Optional[Tuple[float, float, float, float]]
    par: Optional[tuple]
    id: str

    def needs_box(self):
        return self.obb or (self.content_obb and self.view_box is None)


def in_space(p, to_space=IDENTITY, box=None):
    """Paint ``p`` (a tree paint or a server) as a tree paint of a node
    whose coordinates ``to_space`` maps into the space ``p`` paints in,
    where that node (or the context element) has bounding box ``box``
    (x, y, w, h).  Gradients and patterns keep painting in that space
    (their transform is prefixed by the inverse of ``to_space``).  None
    when it cannot paint (singular ``to_space``, a box needed but empty).
    Solid colours and None are returned unchanged."""
    if p is None or isinstance(p, SolidPaint):
        return p
    if to_space.is_identity:
        inv = None
    else:
        try:
            inv = to_space.inverse()
        except RasterError:
            return None
    if isinstance(p, (GradientServer, PatternServer)) and p.needs_box():
        if box is None or not (box[2] > 0 and box[3] > 0):
            return None
    if isinstance(p, GradientServer):
        g = p.paint
        t = g.transform
        if p.obb:
            t = Affine(box[2], 0, 0, box[3], box[0], box[1]) @ t
        if inv is not None:
            t = inv @ t
        return dataclasses.replace(g, transform=t)
    if isinstance(p, PatternServer):
        x, y, w, h = p.rect
        if p.obb:
            x, y, w, h = box[0] + x * box[2], box[1] + y * box[3], w * box[2], h * box[3]
        if p.view_box is not None:
            if p.obb:       # the viewBox maps onto the tile, sized by the box
                try:
                    content = viewbox_transform(p.view_box, p.par, w, h)
                except RasterError:
                    return None
            else:
                content = p.content_transform
        elif p.content_obb:
            content = p.content_transform @ Affine.scale(box[2], box[3])
        else:
            content = p.content_transform
        t = p.transform if inv is None else inv @ p.transform
        return Pattern(rect=(x, y, w, h), root=p.root, transform=t, content_transform=content,
                       id=p.id)
    # an already resolved tree paint
    if inv is None:
        return p
    return dataclasses.replace(p, transform=inv @ p.transform)


def url_paint(el, name, ctx, cache, path=None, box=None):
    """The paint of paint server element ``el`` (local name ``name``, one
    of :data:`raster.parser.paint.PAINT_SERVERS`) for a node with geometry
    ``path`` (its box, or ``box`` (x0, y0, x1, y1) when given, resolves
    objectBoundingBox units): a tree paint, None (paints nothing) or
    :data:`UNSUPPORTED` (the ``url()``'s fallback paints).  Without ``path``
    and ``box`` a server needing a box is returned as is (a context paint,
    placed later by :func:`in_space`)."""
    server = server_of(el, name, ctx, cache)
    if not isinstance(server, (GradientServer, PatternServer)):
        return server
    if not server.needs_box():
        return _user_space(server, cache)
    if path is None and box is None:
        return server
    try:
        x0, y0, x1, y1 = box if box is not None else exact_bbox(path)
    except RasterError:
        x0 = x1 = 0.0
    # a bounding box of zero width or height cannot be used
    if x1 > x0 and y1 > y0:
        r = in_space(server, IDENTITY, (x0, y0, x1 - x0, y1 - y0))
        if r is not None:
            return r
    return UNSUPPORTED


def _user_space(server, cache):
    """The tree paint of a server in user space units (one per server)."""
    memo = cache.table('user_space_paint')
    r = memo.get(id(server))
    if r is None or r[0] is not server:
        r = memo[id(server)] = (server, in_space(server))
    return r[1]


def server_of(el, name, ctx, cache):
    """A paint server element to a server, a SolidPaint (a gradient with
    one stop), None (paints nothing) or :data:`UNSUPPORTED` (use the
    fallback).  Memoized per element and length context."""
    memo = cache.table('servers')
    key = (el, ctx)
    if key in memo:
        return memo[key]
    if name == 'pattern':
        r = _pattern(el, ctx, cache)
    elif name == 'meshgradient':
        from .mesh import mesh_gradient      # loaded by the first mesh gradient
        m = mesh_gradient(el, ctx, cache)
        r = UNSUPPORTED if m is None else GradientServer(*m)
    else:
        r = _gradient(el, name, ctx, cache)
    memo[key] = r
    return r


def _with_origin(el, t, lctx, cache):
    """``t`` about the element's ``transform-origin`` (lengths in the
    paint server's units)."""
    o = doc_style(el, cache)[1].get('transform-origin')
    if o is None or t.is_identity:
        return t
    p = parse_transform_origin(o, lctx)
    if p is None or not (p[0] or p[1]):
        return t
    return Affine.translate(p[0], p[1]) @ t @ Affine.translate(-p[0], -p[1])


def _pattern(el, ctx, cache):
    if el in cache.active:
        cache.warn('pattern-recursive', 'recursive pattern reference ignored')
        return None
    chain = href_chain(el, ('pattern',), cache)

    def attr(n):
        return chain_attr(chain, n)
    content_el = None
    for e in chain:
        if any(isinstance(c.tag, str) and c.tag.startswith(_P) for c in e):
            content_el = e
            break
    # a pattern that cannot paint -- no content, an empty tile, a viewBox
    # of zero size -- paints the fallback (content that draws nothing is a
    # transparent pattern)
    if content_el is None:
        return UNSUPPORTED
    obb = attr('patternUnits') != 'userSpaceOnUse'
    cobb = attr('patternContentUnits') == 'objectBoundingBox'
    if obb:
        lctx = LengthContext(font_size=ctx.font_size, width=1.0, height=1.0, dpi=ctx.dpi)
    else:
        lctx = ctx
    vals = []
    for n, axis in (('x', 'x'), ('y', 'y'), ('width', 'x'), ('height', 'y')):
        v = attr(n)
        r = parse_length(v, axis, lctx) if v is not None else None
        vals.append(0.0 if r is None else r)
    x, y, w, h = vals
    if not (w > 0 and h > 0):
        return UNSUPPORTED
    tf = IDENTITY
    ts = attr('patternTransform')
    if ts is not None:
        t = parse_transform(ts)
        if t is not None and t.determinant != 0:
            # patternTransform acts in user space whatever the units
            tf = _with_origin(el, t, ctx, cache)
    vb = par = None
    content_t = IDENTITY
    vb = resolve_viewbox(attr('viewBox'))
    if vb is ZERO_VIEWBOX:
        return UNSUPPORTED
    if vb is not None:
        par = parse_preserve_aspect_ratio(attr('preserveAspectRatio') or '')
        if not obb:
            content_t = viewbox_transform(vb, par, w, h)
    with cache.referencing(el):
        inh, own = doc_style(content_el, cache)
        scale = 1000.0 if (cobb or obb) else 1.0
        st = State(inh, own, ctx.width, ctx.height, tf @ Affine.scale(scale))
        nodes = []
        convert_children(content_el, st, cache, nodes)
    if not nodes:
        return None
    return PatternServer(rect=(x, y, w, h), root=Group(children=nodes), obb=obb,
                         content_obb=cobb, transform=tf, content_transform=content_t,
                         view_box=vb, par=par, id=el.get('id') or '')


def _gradient(el, name, ctx, cache):
    chain = href_chain(el, ('linearGradient', 'radialGradient'), cache)

    def attr(n, same_kind=False):
        return chain_attr(chain, n, el.tag if same_kind else None)
    stops_el = None
    for e in chain:
        ss = [c for c in e if isinstance(c.tag, str) and c.tag == _P + 'stop']
        if ss:
            stops_el = ss
            break
    if stops_el is None:
        return UNSUPPORTED     # no stops: the fallback colour, else nothing
    stops = []
    last = 0.0
    for stop in stops_el:
        off = number_or_percent(stop.get('offset', '0'))
        off = 0.0 if off is None else min(max(off, 0.0), 1.0)
        off = max(off, last)
        last = off
        stops.append(GradientStop(off, stop_color(stop, cache)))
    if len(stops) == 1:
        return SolidPaint(stops[0].color)
    obb = attr('gradientUnits') != 'userSpaceOnUse'
    if obb:
        lctx = LengthContext(font_size=ctx.font_size, width=1.0, height=1.0, dpi=ctx.dpi)
    else:
        lctx = ctx

    def length(n, axis, default):
        v = attr(n, True)    # geometry comes only from gradients of the same kind
        if v is None:
            return default
        r = parse_length(v, axis, lctx)
        return default if r is None else r
    tf = IDENTITY
    ts = attr('gradientTransform')
    if ts is not None:
        t = parse_transform(ts)
        if t is not None and t.determinant != 0:    # singular: ignored (resvg)
            tf = _with_origin(el, t, lctx, cache)
    spread = _SPREADS.get(attr('spreadMethod'), SpreadMethod.PAD)
    gid = el.get('id') or ''
    stops = tuple(stops)
    if name == 'linearGradient':
        x1 = length('x1', 'x', 0.0)
        y1 = length('y1', 'y', 0.0)
        x2 = length('x2', 'x', 1.0 if obb else lctx.width)
        y2 = length('y2', 'y', 0.0)
        return GradientServer(LinearGradient(x1, y1, x2, y2, stops, transform=tf,
                                             spread=spread, id=gid), obb)
    half_w = 0.5 if obb else 0.5 * lctx.width
    half_h = 0.5 if obb else 0.5 * lctx.height
    cx = length('cx', 'x', half_w)
    cy = length('cy', 'y', half_h)
    r = length('r', 'other', parse_length('50%', 'other', lctx))
    fx = length('fx', 'x', cx)
    fy = length('fy', 'y', cy)
    fr = length('fr', 'other', 0.0)
    if r < 0:       # invalid: resvg paints the last stop, as for r = 0
        r = 0.0
    if fr < 0:
        fr = 0.0
    return GradientServer(RadialGradient(cx, cy, r, fx, fy, stops, fr=fr, transform=tf,
                                         spread=spread, id=gid), obb)
