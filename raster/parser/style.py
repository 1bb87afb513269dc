"""Computed style, lengths, transforms and conditions of elements.

The computed style of an element is a pair of dicts ``(inh, own)``: the
inherited properties (every inherited property present, with the font size
resolved to px under ``'_fs'`` and the colour to RGBA under ``'_color'``)
and the element's own non-inherited declarations.  Both are shared between
elements with the same declarations under the same parent style (``inh``
also between elements whose inherited declarations are the same), so they
must never be modified.  ``inherit`` takes the parent's computed value.
"""

from ..geometry.transform import IDENTITY, Affine
from .context import NO_OWN, SVG_NS
from .properties import INHERITED, PROPERTIES
from .values import (CURRENT_COLOR, LengthContext, parse_color, parse_length, parse_number,
                     parse_paint, parse_transform, parse_transform_origin)
from ..tree import DEFAULT_PAINT_ORDER, PaintItem

__all__ = ['local_name', 'style_of', 'doc_style', 'initial_inherited', 'length_context',
           'length', 'transform_of', 'passes_conditions', 'is_displayed', 'opacity',
           'number_or_percent', 'paint_order', 'stop_color', 'BLACK']

_P = '{%s}' % SVG_NS
_PLEN = len(_P)
BLACK = (0.0, 0.0, 0.0, 1.0)

# CSS 2's absolute size keywords (SVG 1.1 refers to CSS 2): a factor of
# 1.2 between adjacent sizes, ``medium`` the options' font size (as usvg);
# CSS Fonts 4 later gave a table (3/5 .. 2) that SVG 1.1 predates
_FONT_KEYWORDS = {'xx-small': 1.2 ** -3, 'x-small': 1.2 ** -2, 'small': 1.2 ** -1, 'medium': 1.0,
                  'large': 1.2, 'x-large': 1.2 ** 2, 'xx-large': 1.2 ** 3, 'xxx-large': 1.2 ** 4}


def local_name(el):
    """Local name of an SVG-namespace element, else None."""
    tag = el.tag
    if isinstance(tag, str) and tag.startswith(_P):
        return tag[_PLEN:]
    return None


def initial_inherited(font_size):
    """The inherited style of the root's parent: initial values, with the
    ``medium`` font size ``font_size`` px."""
    inh = {k: p.initial for k, p in PROPERTIES.items() if p.inherited}
    del inh['font-size']
    del inh['color']
    inh['_fs'] = float(font_size)
    inh['_color'] = BLACK
    return inh


def style_of(el, inh, own, cache):
    """``(inh, own)`` computed style of ``el`` given its rendering parent's
    ``inh``/``own`` (see the module docstring)."""
    decl = cache.styles.get(el)
    if not decl:
        return inh, NO_OWN
    return declared_style(decl, inh, own, cache)


def declared_style(decl, pinh, pown, cache):
    """:func:`style_of` of an element with declarations ``decl``
    (memoized: siblings with the same declarations share the result)."""
    memo = cache.table('style')
    key = (id(pinh), id(pown), tuple(decl.items()))
    hit = memo.get(key)
    if hit is not None:
        return hit[2], hit[3]
    inh, own = _compute(decl, pinh, pown, cache.options)
    if inh is not pinh:
        # elements that differ only in non-inherited declarations (their
        # clip paths, positions) share one inherited style too
        shared = cache.table('style_inh')
        ikey = (id(pinh), tuple(kv for kv in decl.items() if kv[0] in INHERITED))
        hit = shared.get(ikey)
        if hit is None:
            shared[ikey] = (pinh, inh)
        else:
            inh = hit[1]
    # the parents are kept alive with the result, so their ids stay unique
    memo[key] = (pinh, pown, inh, own)
    return inh, own


def _compute(decl, pinh, pown, options):
    inh = None
    own = {}
    for k, v in decl.items():
        if v == 'inherit':
            if k in INHERITED:
                continue
            pv = pown.get(k)
            if pv is not None:
                own[k] = pv
            continue
        if k in INHERITED:
            if k == 'font-size':
                fs = font_size_value(v, pinh['_fs'], options)
                if fs is None:
                    continue
                k, v = '_fs', fs
            elif k == 'color':
                c = parse_color(v)
                if c is None or c is CURRENT_COLOR:
                    continue
                k, v = '_color', c
            elif k == 'fill' or k == 'stroke':
                if parse_paint(v) is None:
                    continue
            if inh is None:
                inh = dict(pinh)
            inh[k] = v
        else:
            own[k] = v
    return (pinh if inh is None else inh), own


def font_size_value(v, parent, options):
    """A ``font-size`` value in px given the parent's (None: invalid)."""
    low = v.strip().lower()
    if low in _FONT_KEYWORDS:
        return options.font_size * _FONT_KEYWORDS[low]
    if low == 'larger':
        return parent * 1.2
    if low == 'smaller':
        return parent / 1.2
    fs = parse_length(v, 'other', LengthContext(font_size=parent, width=parent, height=parent,
                                                 dpi=options.dpi))
    if fs is None or fs < 0:
        return None
    return fs


def doc_style(el, cache):
    """``(inh, own)`` style of ``el`` along its *document* ancestors (for
    paint servers, stops, clip paths, masks, markers, filters).  Memoized."""
    memo = cache.table('doc_style')
    r = memo.get(el)
    if r is not None:
        return r
    chain = []
    e = el
    while e is not None and e not in memo:
        chain.append(e)
        e = e.getparent()
    if e is None:
        pinh, pown = initial_inherited(cache.options.font_size), {}
    else:
        pinh, pown = memo[e]
    for e in reversed(chain):
        pinh, pown = style_of(e, pinh, pown, cache)
        memo[e] = (pinh, pown)
    return memo[el]


def length_context(inh, state, cache):
    """The LengthContext of an element with computed style ``inh`` in
    ``state`` (font size, viewport, dpi); shared per distinct value."""
    memo = cache.table('length_context')
    key = (inh['_fs'], state.vw, state.vh)
    c = memo.get(key)
    if c is None:
        c = LengthContext(font_size=key[0], width=state.vw, height=state.vh,
                          dpi=cache.options.dpi)
        if len(memo) < 4096:
            memo[key] = c
    return c


def length(el, name, axis, ctx, default=0.0):
    """Attribute ``name`` of ``el`` as a length in user units along
    ``axis`` ('x', 'y', 'other'), or ``default`` when absent or invalid."""
    s = el.get(name)
    if s is None:
        return default
    v = parse_length(s, axis, ctx)
    return default if v is None else v


_OWN_BOXES = {'fill-box': 'fill', 'content-box': 'fill', 'stroke-box': 'stroke',
              'border-box': 'stroke'}


def origin_box(el, own):
    """``'fill'`` or ``'stroke'`` when the element's ``transform-origin``
    refers to its own bounding box (``transform-box`` ``fill-box`` or
    ``stroke-box``; ``content-box`` and ``border-box`` stand for them on
    SVG elements, CSS Transforms 1), it has a transform and an origin;
    else None (the reference box is the viewport, ``view-box``)."""
    kind = _OWN_BOXES.get(own.get('transform-box', 'view-box').strip().lower())
    if kind is None or own.get('transform-origin') is None:
        return None
    if own.get('transform') is None and el.get('transform') is None:
        return None
    return kind


def transform_of(el, own, ctx, box=None):
    """The element's transform (``transform-origin`` applied); None when it
    is singular.  An identity is always the object ``IDENTITY``.  ``box``
    ``(x, y, w, h)`` is the reference box of the origin when it is not the
    viewport (see :func:`origin_box`)."""
    s = own.get('transform')
    if s is None:
        s = el.get('transform')
    if s is None:
        return IDENTITY
    t = parse_transform(s)
    if t is None:
        return IDENTITY
    if t.determinant == 0:
        return None
    if t.is_identity:
        return IDENTITY
    o = own.get('transform-origin')
    if o is not None:
        p = parse_transform_origin(o, ctx, box)
        if p is not None and (p[0] or p[1]):
            t = Affine.translate(p[0], p[1]) @ t @ Affine.translate(-p[0], -p[1])
            if t.is_identity:
                return IDENTITY
    return t


def passes_conditions(el, cache):
    """False when ``requiredExtensions`` or ``systemLanguage`` exclude the
    element (for the user's languages, :attr:`Options.languages`)."""
    if el not in cache.conditional:
        return True
    attrib = el.attrib
    if 'requiredExtensions' in attrib:
        return False
    sl = attrib.get('systemLanguage')
    if sl is not None:
        primary = cache.table('languages').get('primary')
        if primary is None:
            primary = frozenset(str(x).strip().lower().split('-')[0]
                                for x in cache.options.languages)
            cache.table('languages')['primary'] = primary
        for tag in sl.split(','):
            tag = tag.strip().lower()
            if tag and tag.split('-')[0] in primary:
                return True
        return False
    return True


def is_displayed(el, cache):
    """False when the element's declared ``display`` is ``none`` (the one
    place that test is written)."""
    decl = cache.styles.get(el)
    if decl:
        v = decl.get('display')
        if v is not None and v.strip() == 'none':
            return False
    return True


def number_or_percent(s):
    """A number or a percentage (as a fraction), or None."""
    s = s.strip()
    if s.endswith('%'):
        v = parse_number(s[:-1])
        return None if v is None else v / 100.0
    return parse_number(s)


_OPACITY_CACHE = {}


def opacity(s, default=1.0):
    """An opacity value clamped to [0, 1]; ``default`` when absent or
    invalid."""
    if s is None:
        return default
    v = _OPACITY_CACHE.get(s)
    if v is None:
        v = number_or_percent(s)
        v = False if v is None else min(max(v, 0.0), 1.0)
        if len(_OPACITY_CACHE) < 4096:
            _OPACITY_CACHE[s] = v
    return default if v is False else v


def stop_color(stop, cache):
    """Straight RGBA of a gradient or mesh ``stop`` element: its computed
    ``stop-color`` (``currentColor`` its ``color``; invalid: black) with
    ``stop-opacity`` folded into alpha."""
    inh, own = doc_style(stop, cache)
    c = parse_color(own.get('stop-color', 'black'))
    if c is None:
        c = BLACK
    elif c is CURRENT_COLOR:
        c = inh['_color']
    return (c[0], c[1], c[2], c[3] * opacity(own.get('stop-opacity')))


_PAINT_ORDERS = {}


def paint_order(v):
    """A ``paint-order`` value as a tuple of the three :class:`PaintItem`
    in drawing order (invalid values: the default order)."""
    r = _PAINT_ORDERS.get(v)
    if r is None:
        r = _parse_paint_order(v)
        if len(_PAINT_ORDERS) < 256:
            _PAINT_ORDERS[v] = r
    return r


def _parse_paint_order(v):
    if v is None:
        return DEFAULT_PAINT_ORDER
    words = v.split()
    if not words or words == ['normal']:
        return DEFAULT_PAINT_ORDER
    seen = []
    for w in words:
        if w not in ('fill', 'stroke', 'markers') or w in seen:
            return DEFAULT_PAINT_ORDER
        seen.append(w)
    for w in ('fill', 'stroke', 'markers'):
        if w not in seen:
            seen.append(w)
    return tuple(PaintItem(w) for w in seen)
