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
from .boxes import content_box, layer_box, object_box, walk_all
from .context import State
from .convert import convert, convert_children
from .css import parse_declarations
from .effects import clip_rect, effects, wrap
from .paint import paint
from .refs import external_target, href_target, instance_size, is_recursive
from .style import (initial_inherited, is_displayed, length, length_context, local_name,
                    origin_box, passes_conditions, style_of, transform_of)
from .values import (CURRENT_COLOR, LengthContext, parse_color, parse_length,
                     parse_preserve_aspect_ratio, resolve_viewbox, viewbox_transform,
                     ZERO_VIEWBOX)

__all__ = ['convert_group', 'convert_switch', 'convert_svg', 'convert_use', 'convert_root',
           'document_size']

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
    kind = origin_box(el, own)
    if kind is not None:
        # transform-box fill-box / stroke-box: the origin in the group's
        # own box, its content's object (or visual) bounding box
        b = object_box(kids) if kind == 'fill' else content_box(Group(children=kids))
        if b is not None and kind == 'stroke':
            b = (b[0], b[1], b[2] - b[0], b[3] - b[1])
        if b is not None:
            t = transform_of(el, own, ctx, b)
            if t is None:
                return
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
    vb = resolve_viewbox(content_el.get('viewBox'))
    if vb is ZERO_VIEWBOX:
        return
    inner = Affine.translate(x, y)
    vw, vh = w, h
    if vb is not None:
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
    ``svg`` targets are viewports sized by the ``use`` element).  The
    element may be in another local SVG document (``lib.svg#id``; see
    :func:`raster.parser.refs.external_target`): it is then converted with
    that document's cache (its style sheets and ids)."""
    e = _element(el, state, cache)
    if e is None:
        return
    inh, own, ctx, t = e
    ext = external_target(el, cache)
    if ext is not None:
        tgt, tcache = ext
        key = (id(tcache), id(tgt))
        active = cache.table('external_active')
        if key in active:
            cache.warn('use-cycle', 'recursive use reference ignored (or nested deeper than %d)'
                       % cache.options.max_use_depth)
            return
    else:
        # (a reference to another document that cannot be followed warned)
        tgt, tcache = href_target(el, cache, warn=False), cache
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
    # max_layers; the content of another document is counted as it is built)
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
        _instantiate(el, tgt, ext, state, cache, parent, inh, own, ctx, t)
    finally:
        cache.prepaid -= bool(layers)


def _instantiate(el, tgt, ext, state, cache, parent, inh, own, ctx, t):
    """The rest of :func:`convert_use`: ``el``'s copy of ``tgt`` (of the
    document of ``ext``'s cache when not None)."""
    name = local_name(tgt)
    if name is None:
        return
    if ext is None:
        _instance(el, tgt, name, inh, own, ctx, t, state, cache, cache, parent)
        return
    # the element counts and limits of the whole rendering carry on in the
    # other document's cache
    tcache = ext[1]
    key = (id(tcache), id(tgt))
    active = cache.table('external_active')
    active[key] = True
    tcache.count, tcache.stopped = cache.count, cache.stopped
    tcache.spent, tcache.prepaid = cache.spent, cache.prepaid     # one set of budgets
    try:
        _instance(el, tgt, name, inh, own, ctx, t, state, cache, tcache, parent)
    finally:
        active.pop(key, None)
        cache.count, cache.stopped = tcache.count, tcache.stopped


def _instance(el, tgt, name, inh, own, ctx, t, state, cache, tcache, parent):
    """The content of ``use`` element ``el`` (of ``cache``'s document)
    instantiating ``tgt`` (of ``tcache``'s)."""
    x = length(el, 'x', 'x', ctx)
    y = length(el, 'y', 'y', ctx)
    # the use element is the context element of its content (SVG 2)
    cfill = paint(inh.get('fill', 'black'), inh, ctx, state, cache)
    sv = inh.get('stroke')
    cstroke = paint(sv, inh, ctx, state, cache) if sv is not None else None
    st2 = state.sub(inh, own, use_depth=state.use_depth + 1, context=(cfill, cstroke))
    kids = []
    if name == 'symbol':
        if not is_displayed(tgt, tcache):
            return
        sinh, sown = style_of(tgt, inh, own, tcache)
        w = length(el, 'width', 'x', ctx, None)
        h = length(el, 'height', 'y', ctx, None)
        if w is None:
            w = length(tgt, 'width', 'x', ctx, None)
        if h is None:
            h = length(tgt, 'height', 'y', ctx, None)
        w = state.vw if w is None else w
        h = state.vh if h is None else h
        _viewport(tgt, sinh, sown, IDENTITY, st2.sub(transform=t), tcache, kids, x, y, w, h,
                  tgt)
        _rebase_context(kids, IDENTITY, inh, cfill, cstroke)
        parent.extend(wrap(el, own, t, kids, state, cache))
        return
    move = Affine.translate(x, y) if (x or y) else IDENTITY
    tt = t @ move
    if name == 'svg':
        w = length(el, 'width', 'x', ctx, None)
        h = length(el, 'height', 'y', ctx, None)
        if not is_displayed(tgt, tcache):
            return
        if not tcache.tick():
            return
        sinh, sown = style_of(tgt, inh, own, tcache)
        sctx = length_context(sinh, st2, tcache)
        stt = transform_of(tgt, sown, sctx)
        if stt is None:
            return
        _nested_svg(tgt, sinh, sown, sctx, stt, st2.sub(transform=tt), tcache, kids,
                    use_size=(w, h))
    else:
        convert(tgt, st2.sub(transform=tt), tcache, kids)
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
    # the paints are servers or gradients: raster.parser.servers made them
    from .servers import GradientServer, PatternServer, in_space
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

def _size_attr(root, name, axis, ctx):
    """The root's ``width``/``height`` in px: None when absent or ``auto``
    (SVG 2), :class:`~raster.errors.SVGError` when invalid."""
    s = root.get(name)
    if s is None or s.strip() == 'auto':
        return None
    v = parse_length(s, axis, ctx)
    if v is None:
        raise SVGError('invalid document size: width=%r height=%r'
                       % (root.get('width'), root.get('height')))
    return v


def document_size(root, vb, ctx):
    """``(w, h)`` of the root ``svg`` element from its ``width``,
    ``height`` and viewBox ``vb`` (x, y, w, h or None); an axis is None
    when it follows the content (no viewBox and no length for it).

    A missing (or ``auto``) side takes the viewBox's aspect ratio from the
    other side (CSS sizing with an intrinsic ratio: ``width="80"
    viewBox="0 0 40 20"`` is 80 x 40); both missing: the viewBox size.
    Percentages resolve against the viewBox size (else 100 x 100)."""
    w = _size_attr(root, 'width', 'x', ctx)
    h = _size_attr(root, 'height', 'y', ctx)
    if vb is not None:
        if w is None and h is None:
            w, h = vb[2], vb[3]
        elif w is None:
            w = h * vb[2] / vb[3]
        elif h is None:
            h = w * vb[3] / vb[2]
    return w, h


def convert_root(root, cache):
    """The :class:`~raster.tree.Tree` of the root ``svg`` element.

    Its size is :func:`document_size`; a side that follows the content
    (no viewBox and no length) is the far edge of the content's visual
    bounds, from the user-space origin (the content is not moved; 100 when
    the content does not reach past 0).  ``display: none`` on the root, or
    a viewBox with a zero side, renders nothing at the document's size."""
    opts = cache.options
    inh0 = initial_inherited(opts.font_size)
    inh, own = style_of(root, inh0, {}, cache)
    vb = resolve_viewbox(root.get('viewBox'))
    disabled = vb is ZERO_VIEWBOX
    if disabled:
        vb = None
    rw, rh = (vb[2], vb[3]) if vb is not None else (100.0, 100.0)
    ctx = LengthContext(font_size=inh['_fs'], width=rw, height=rh, dpi=opts.dpi)
    ws, hs = root.get('width'), root.get('height')
    w, h = document_size(root, vb, ctx)
    fit_w, fit_h = w is None, h is None
    for v in (w, h):
        if v is not None and not (v > 0 and math.isfinite(v)):
            raise SVGError('invalid document size: width=%r height=%r' % (ws, hs))
    t_root = transform_of(root, own, ctx)
    vbt = IDENTITY
    if vb is not None:
        par = parse_preserve_aspect_ratio(root.get('preserveAspectRatio', ''))
        vbt = viewbox_transform(vb, par, w, h)
    kids = []
    rt = vbt if t_root is None else t_root @ vbt
    vw, vh = (vb[2], vb[3]) if vb is not None else (rw if fit_w else w, rh if fit_h else h)
    st = State(inh, own, vw, vh, rt)
    shown = is_displayed(root, cache) and not disabled
    if shown and t_root is not None and passes_conditions(root, cache):
        convert_children(root, st, cache, kids)
    e = effects(root, own, st, cache, kids)
    if not e.ok:
        kids = []
    if fit_w or fit_h:
        box = content_box(Group(transform=rt, children=kids)) if kids else None
        x1, y1 = (box[2], box[3]) if box is not None else (0.0, 0.0)
        if fit_w:
            w = x1 if x1 > 0 and math.isfinite(x1) else 100.0
        if fit_h:
            h = y1 if y1 > 0 and math.isfinite(y1) else 100.0
    bg = _root_background(root, rt, w, h) if shown else None
    if bg is not None:
        kids = [bg] + kids
    group = e.group(root.get('id') or '', rt, kids)
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
