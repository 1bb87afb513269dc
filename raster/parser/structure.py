"""Structure: ``g``, ``a``, ``switch``, nested ``svg``, ``use`` and
``symbol``, and the document root.

A nested ``svg`` or ``symbol`` instance is a viewport: its content is
mapped by its viewBox (``preserveAspectRatio``) and clipped to the
viewport unless ``overflow`` is ``visible``/``auto``.  ``use`` content
inherits from the ``use`` element, is its context element for
``context-fill``/``context-stroke`` (SVG 2), and is followed with cycle
detection and the use depth limit.
"""

import math

from ..errors import RasterError, SVGError
from ..geometry.pathdata import rect_path
from ..geometry.transform import IDENTITY, Affine
from ..tree import Fill, Group, PathNode, SolidPaint, Tree
from .boxes import content_box, layer_box, walk_all
from .context import State
from .convert import convert, convert_children
from .css import parse_declarations
from .effects import clip_rect, effects, wrap
from .paint import GradientServer, PatternServer, in_space, paint
from .refs import href_target, instance_size, is_recursive
from .style import (initial_inherited, is_displayed, length, length_context, local_name,
                    passes_conditions, style_of, transform_of)
from .values import (CURRENT_COLOR, LengthContext, parse_color, parse_length,
                     parse_preserve_aspect_ratio, parse_viewbox, viewbox_transform)

__all__ = ['convert_group', 'convert_switch', 'convert_svg', 'convert_use', 'convert_root']

_SHAPES = frozenset(['rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon', 'path'])
_CONTAINERS = frozenset(['g', 'a', 'svg', 'switch', 'use'])
# elements a <switch> may choose
_SWITCH_CHOICES = _SHAPES | _CONTAINERS | frozenset(['text', 'image', 'foreignObject'])


def _element(el, state, cache):
    """``(inh, own, ctx, t)`` of a container element, or None when its
    transform is singular."""
    inh, own = style_of(el, state.inh, state.own, cache)
    ctx = length_context(inh, state, cache)
    t = transform_of(el, own, ctx)
    if t is None:
        return None
    return inh, own, ctx, t


def convert_group(el, state, cache, parent):
    """``g`` and ``a``: the children, wrapped when the group does something."""
    e = _element(el, state, cache)
    if e is None:
        return
    inh, own, ctx, t = e
    kids = []
    convert_children(el, state.sub(inh, own, transform=t), cache, kids)
    parent.extend(wrap(el, own, t, kids, state, cache))


def convert_switch(el, state, cache, parent):
    """``switch``: the first direct child whose conditions pass."""
    e = _element(el, state, cache)
    if e is None:
        return
    inh, own, ctx, t = e
    kids = []
    sub = state.sub(inh, own, transform=t)
    for ch in el:
        cn = local_name(ch)
        if cn in _SWITCH_CHOICES and passes_conditions(ch, cache):
            convert(ch, sub, cache, kids)
            break
    parent.extend(wrap(el, own, t, kids, state, cache))


def convert_svg(el, state, cache, parent):
    """A nested ``svg`` element."""
    e = _element(el, state, cache)
    if e is None:
        return
    inh, own, ctx, t = e
    _nested_svg(el, inh, own, ctx, t, state, cache, parent)


def _nested_svg(el, inh, own, ctx, t, state, cache, parent, use_size=None):
    x = length(el, 'x', 'x', ctx)
    y = length(el, 'y', 'y', ctx)
    w, h = use_size if use_size is not None else (None, None)
    if w is None:
        w = length(el, 'width', 'x', ctx, None)
        if w is None:
            w = state.vw
    if h is None:
        h = length(el, 'height', 'y', ctx, None)
        if h is None:
            h = state.vh
    _viewport(el, inh, own, t, state, cache, parent, x, y, w, h, el)


def _viewport(el, inh, own, t, state, cache, parent, x, y, w, h, content_el):
    """Content of ``content_el`` in a viewport (x, y, w, h) with its
    viewBox: nested svg and symbol instances."""
    if not (w > 0 and h > 0):
        return
    vb_attr = content_el.get('viewBox')
    inner = Affine.translate(x, y)
    vw, vh = w, h
    if vb_attr is not None:
        vb = parse_viewbox(vb_attr)
        if vb is None:
            return
        par = parse_preserve_aspect_ratio(content_el.get('preserveAspectRatio', ''))
        inner = viewbox_transform(vb, par, w, h, x, y)
        vw, vh = vb[2], vb[3]
    ov = own.get('overflow', 'hidden').strip()
    clip = None if ov in ('visible', 'auto') else clip_rect(x, y, w, h)
    kids = []
    convert_children(content_el, state.sub(inh, own, transform=t @ inner, vw=vw, vh=vh),
                     cache, kids)
    if not kids:
        return
    if clip is None:
        parent.extend(wrap(el, own, t @ inner, kids, state, cache))
    else:
        if not inner.is_identity:
            kids = [Group(transform=inner, children=kids)]
        parent.extend(wrap(el, own, t, kids, state, cache, clip=clip))


def convert_use(el, state, cache, parent):
    """``use``: an instance of the referenced element (``symbol`` and
    ``svg`` targets are viewports sized by the ``use`` element)."""
    e = _element(el, state, cache)
    if e is None:
        return
    inh, own, ctx, t = e
    tgt = href_target(el, cache)
    if tgt is None:
        return
    if is_recursive(el, cache):
        cache.warn('use-cycle', 'recursive use reference ignored (or nested deeper than %d)'
                   % cache.options.max_use_depth)
        return
    max_depth = cache.options.max_use_depth
    if state.use_depth >= max_depth:
        cache.warn('use-depth', 'use nesting deeper than %d ignored' % max_depth)
        return
    # the cost model: a copy that cannot fit in the node or layer budgets
    # is left out before any of it is built (raster.limits max_elements,
    # max_layers)
    need, layers = instance_size(el, cache)        # the use itself included
    need -= 1                                      # (already counted)
    left = cache.options.max_elements - cache.count
    if need > left:
        cache.warn('limit', 'use element not rendered: its content needs about %d nodes, '
                   'more than the %d left of max_elements' % (need, max(left, 0)))
        return
    if layers and not cache.prepaid and not cache.spend('layers', layers, 'use element'):
        return
    cache.prepaid += bool(layers)
    try:
        _instantiate(el, tgt, state, cache, parent, inh, own, ctx, t)
    finally:
        cache.prepaid -= bool(layers)


def _instantiate(el, tgt, state, cache, parent, inh, own, ctx, t):
    """The rest of :func:`convert_use`: ``el``'s copy of ``tgt``."""
    x = length(el, 'x', 'x', ctx)
    y = length(el, 'y', 'y', ctx)
    name = local_name(tgt)
    if name is None:
        return
    # the use element is the context element of its content (SVG 2)
    cfill = paint(inh.get('fill', 'black'), inh, ctx, state, cache)
    sv = inh.get('stroke')
    cstroke = paint(sv, inh, ctx, state, cache) if sv is not None else None
    st2 = state.sub(inh, own, use_depth=state.use_depth + 1, context=(cfill, cstroke))
    kids = []
    if name == 'symbol':
        if not is_displayed(tgt, cache):
            return
        sinh, sown = style_of(tgt, inh, own, cache)
        w = length(el, 'width', 'x', ctx, None)
        h = length(el, 'height', 'y', ctx, None)
        if w is None:
            w = length(tgt, 'width', 'x', ctx, None)
        if h is None:
            h = length(tgt, 'height', 'y', ctx, None)
        w = state.vw if w is None else w
        h = state.vh if h is None else h
        _viewport(tgt, sinh, sown, IDENTITY, st2.sub(transform=t), cache, kids, x, y, w, h,
                  tgt)
        _rebase_context(kids, IDENTITY, inh, cfill, cstroke)
        parent.extend(wrap(el, own, t, kids, state, cache))
        return
    move = Affine.translate(x, y) if (x or y) else IDENTITY
    tt = t @ move
    if name == 'svg':
        w = length(el, 'width', 'x', ctx, None)
        h = length(el, 'height', 'y', ctx, None)
        if not is_displayed(tgt, cache):
            return
        if not cache.tick():
            return
        sinh, sown = style_of(tgt, inh, own, cache)
        sctx = length_context(sinh, st2, cache)
        stt = transform_of(tgt, sown, sctx)
        if stt is None:
            return
        _nested_svg(tgt, sinh, sown, sctx, stt, st2.sub(transform=tt), cache, kids,
                    use_size=(w, h))
    else:
        convert(tgt, st2.sub(transform=tt), cache, kids)
    _rebase_context(kids, move, inh, cfill, cstroke)
    parent.extend(wrap(el, own, tt, kids, state, cache))


def _rebase_context(kids, move, inh, cfill, cstroke):
    """Make the gradients and patterns that ``use`` content paints with
    ``context-fill``/``context-stroke`` act in the ``use`` element's user
    space, with its bounding box for ``objectBoundingBox`` units (as
    resvg does), whatever the transforms inside the content.

    ``kids`` are in content space, ``move`` maps it to the ``use``
    element's user space (its x/y).  Paints that the ``use`` itself took
    from an outer context are left to that outer ``use``."""
    todo = []
    for p, prop in ((cfill, 'fill'), (cstroke, 'stroke')):
        if p is None or isinstance(p, SolidPaint):
            continue
        v = inh.get(prop) or ''
        if 'context-' in v and not v.lstrip().startswith('url('):
            continue
        todo.append(p)
    if not todo or not kids:
        return
    box = None
    if any(isinstance(p, (GradientServer, PatternServer)) and p.needs_box() for p in todo):
        b = layer_box(kids, move)
        if b is not None:
            box = (b[0], b[1], b[2] - b[0], b[3] - b[1])
    memo = {}
    for n, m in walk_all(kids, move):
        if isinstance(n, Group):
            continue
        for attr in ('fill', 'stroke'):
            f = getattr(n, attr, None)
            if f is None or not any(f.paint is p for p in todo):
                continue
            key = (id(f.paint), m)
            if key not in memo:
                memo[key] = in_space(f.paint, m, box)
            f.paint = memo[key]


# -- the document root ------------------------------------------------------------

def convert_root(root, cache):
    """The :class:`~raster.tree.Tree` of the root ``svg`` element."""
    opts = cache.options
    inh0 = initial_inherited(opts.font_size)
    inh, own = style_of(root, inh0, {}, cache)
    vb_attr = root.get('viewBox')
    vb = parse_viewbox(vb_attr) if vb_attr is not None else None
    rw, rh = (vb[2], vb[3]) if vb is not None else (100.0, 100.0)
    ctx = LengthContext(font_size=inh['_fs'], width=rw, height=rh, dpi=opts.dpi)
    ws, hs = root.get('width'), root.get('height')
    auto = ws is None and hs is None and vb is None
    w = parse_length(ws, 'x', ctx) if ws is not None else None
    h = parse_length(hs, 'y', ctx) if hs is not None else None
    if ws is not None and w is None or hs is not None and h is None:
        raise SVGError('invalid document size: width=%r height=%r' % (ws, hs))
    if w is None:
        w = rw
    if h is None:
        h = rh
    if not (w > 0 and h > 0 and math.isfinite(w) and math.isfinite(h)):
        raise SVGError('invalid document size: width=%r height=%r' % (ws, hs))
    t_root = transform_of(root, own, ctx)
    vbt = IDENTITY
    if vb is not None:
        par = parse_preserve_aspect_ratio(root.get('preserveAspectRatio', ''))
        vbt = viewbox_transform(vb, par, w, h)
    kids = []
    rt = vbt if t_root is None else t_root @ vbt
    vw, vh = (vb[2], vb[3]) if vb is not None else (w, h)
    st = State(inh, own, vw, vh, rt)
    if t_root is not None and passes_conditions(root, cache):
        convert_children(root, st, cache, kids)
    e = effects(root, own, st, cache, kids)
    if not e.ok:
        kids = []
    bg = _root_background(root, rt, w, h) if not auto else None
    if bg is not None:
        kids = [bg] + kids
    group = e.group(root.get('id') or '', rt, kids)
    if auto and kids:
        box = content_box(group)
        if box is not None:
            x0, y0, x1, y1 = box
            w, h = x1 - x0, y1 - y0
            group.transform = Affine.translate(-x0, -y0) @ rt
    if group.id:
        cache.tree_ids.setdefault(group.id, group)
    return Tree(width=float(w), height=float(h), root=group, ids=cache.tree_ids)


def _root_background(root, rt, w, h):
    """A PathNode filling the whole viewport (0, 0, w, h) in document px
    with the root element's CSS ``background-color`` (from its ``style``
    attribute), in the root's user space (``rt`` maps it to document px);
    None when there is none or it is transparent.  resvg paints it under
    the content."""
    style = root.get('style')
    if not style or 'background-color' not in style.lower():
        return None
    value = None
    for d in parse_declarations(style):
        if d.name == 'background-color':
            value = d.value
    c = parse_color(value) if value is not None else None
    if c is None or c is CURRENT_COLOR or c[3] <= 0:
        return None
    try:
        inv = rt.inverse()
    except RasterError:
        return None
    pts = inv.apply([[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]])
    x0, y0 = pts.min(0)
    x1, y1 = pts.max(0)
    return PathNode(path=rect_path(float(x0), float(y0), float(x1 - x0), float(y1 - y0)),
                    fill=Fill(SolidPaint(tuple(float(v) for v in c))))
