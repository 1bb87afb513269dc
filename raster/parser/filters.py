"""The ``filter`` property and ``<filter>`` elements to
:class:`raster.tree.filter.Filter` lists.

A ``filter`` value naming ``<filter>`` elements (and CSS filter functions
such as ``blur(2px)``) becomes a list of filters in the filtered element's
*user space*: ``filterUnits``/``primitiveUnits`` applied, the filter
region and every primitive subregion resolved to ``(x, y, w, h)``,
lengths such as ``stdDeviation`` and ``dx`` in user units, every input
resolved (an ``in`` naming no earlier ``result`` is the previous result,
or ``SourceGraphic`` for the first primitive).

Semantics follow the specification and resvg where they differ:

* a reference to a missing element or to a non-``filter`` element, a
  filter without primitives, a region of zero size, or
  ``objectBoundingBox`` units on an element without a box make the
  reference unusable: it is left out of the list, and when nothing usable
  is left the element is **not rendered** (``url(#a) url(#missing)``
  applies ``#a``; ``url(#missing)`` alone hides the element); a syntax
  error (a comma between the functions, an invalid function) makes the
  whole value ignored;
* ``feImage`` referencing an element draws it in the filtered element's
  user space translated to the subregion's origin (as resvg); an image
  (data URI or file) is fitted into the subregion with
  ``preserveAspectRatio``; an element whose filter has an feImage
  referencing that element itself ignores its ``filter`` property (as
  resvg); other circular references are cut where they close;
* a primitive in error (a bad feConvolveMatrix, a lighting primitive
  without a light or with a specular exponent outside [1, 128], invalid
  feTurbulence parameters, an empty feImage) is transparent black;
* primitive subregions given in ``objectBoundingBox`` primitive units are
  fractions of the filter region, except for feImage and feFlood, whose
  subregion is in fractions of the bounding box, missing values 0, 0, 1,
  1 (resvg); light source positions stay user units.
"""

import math
import re

import numpy as np

from ..errors import RasterError
from ..tree import BlendMode, Group, ImageNode
from ..tree import filter as F
from .boxes import object_box
from .context import XLINK_HREF
from .convert import convert
from .document import chain_attr
from .imageload import ImageError, load_image
from .refs import href_chain
from .style import doc_style, initial_inherited, length_context, local_name
from .values import (LengthContext, parse_angle, parse_color, parse_length, parse_number,
                     parse_number_list, parse_preserve_aspect_ratio, parse_url,
                     viewbox_transform)

__all__ = ['resolve_filter_property']

_SUPPORTED = frozenset(['feGaussianBlur', 'feOffset', 'feFlood', 'feMerge', 'feComposite',
                        'feBlend', 'feColorMatrix', 'feComponentTransfer', 'feDropShadow',
                        'feMorphology', 'feTile', 'feImage', 'feConvolveMatrix',
                        'feDiffuseLighting', 'feSpecularLighting', 'feTurbulence',
                        'feDisplacementMap'])
_FUNCTION_RE = re.compile(r'([A-Za-z-]+)\(')
_BLEND = {m.value: m for m in BlendMode}
_COMPOSITE = {m.value: m for m in F.CompositeOperator}
_EDGE = {m.value: m for m in F.EdgeMode}
_IDENTITY_MATRIX = np.hstack([np.eye(4), np.zeros((4, 1))])


def _numbers(s):
    """Numbers of a list attribute (None if absent or malformed)."""
    if s is None:
        return None
    try:
        v = parse_number_list(s)
    except RasterError:
        return None
    if v is None:
        return None
    v = [float(x) for x in v]
    return v if all(math.isfinite(x) for x in v) else None


def _number(s, default):
    v = _numbers(s)
    return default if not v or len(v) != 1 else v[0]


def resolve_filter_property(el, value, kids, state, cache):
    """Resolve a ``filter`` property value for an element.

    Parameters
    ----------
    el : lxml element
        The filtered element.
    value : str
        The property value, e.g. ``'url(#f1)'`` (several ``url()`` and
        filter functions apply in order).
    kids : list of tree nodes
        The element's content in its user space (for objectBoundingBox).
    state, cache : the converter's state and cache.

    Returns
    -------
    list of Filter or None
        None when the element must not be rendered (invalid reference,
        empty filter, zero region); an empty list when the value is
        ignored (an invalid filter function list, a recursive reference;
        with a warning).
    """
    refs = _functions(value)
    out = []
    if not refs:
        cache.warn('filter-syntax', 'invalid filter value %r ignored' % (value,))
        return out
    if _draws_itself(el, refs, cache):
        cache.warn('filter-recursive', 'filter whose feImage draws the filtered element '
                   'ignored')
        return out
    invalid = False
    for name, args in refs:
        if name != 'url':
            f = _filter_function(el, name, args, state, cache)
            if f is None:
                cache.warn('filter-syntax', 'invalid filter value %r ignored' % (value,))
                return []
            out.append(f)
            continue
        u = parse_url('url(%s)' % args)
        if u is None:           # url() without a reference: a syntax error
            cache.warn('filter-syntax', 'invalid filter value %r ignored' % (value,))
            return []
        tgt = cache.by_id.get(u[0])
        if tgt is None or local_name(tgt) != 'filter':
            invalid = True
            continue
        if tgt in cache.active:
            # used inside its own feImage: the inner use is dropped (resvg)
            cache.warn('filter-recursive', 'recursive filter reference ignored')
            continue
        f = _resolve_filter(tgt, kids, state, cache)
        if f is None:
            invalid = True
            continue
        out.append(f)
    if invalid:
        # a reference that cannot be used is left out of the list; with
        # nothing usable left the element is not rendered (resvg)
        cache.warn('filter-reference', 'filter reference not usable in %r' % (value,))
        if not out:
            return None
    return out


def _draws_itself(el, refs, cache):
    """True when a filter of the list has an ``feImage`` that references
    the filtered element itself: the element then ignores its ``filter``
    property, wherever it is drawn (as resvg; drawing it through its own
    filter has no end).  Circular references through other elements are
    cut where they close (the inner reference draws nothing)."""
    i = el.get('id')
    if not i:
        return False
    for name, args in refs:
        if name != 'url':
            continue
        u = parse_url('url(%s)' % args)
        tgt = cache.by_id.get(u[0]) if u is not None else None
        if tgt is None or local_name(tgt) != 'filter':
            continue
        chain = href_chain(tgt, ('filter',), cache)
        src = next((e for e in chain if any(local_name(c) for c in e)), tgt)
        for c in src:
            if local_name(c) == 'feImage':
                h = (c.get('href') or c.get(XLINK_HREF) or '').strip()
                if h == '#' + i:
                    return True
    return False


def _functions(value):
    """``'url(#a) blur(2px)'`` -> ``[('url', '#a'), ('blur', '2px')]``
    (nested parentheses kept in the arguments); None when malformed (the
    list is separated by white space only: a comma or a keyword between
    the functions is a syntax error)."""
    out = []
    i, n = 0, len(value)
    while i < n:
        if value[i].isspace():
            i += 1
            continue
        m = _FUNCTION_RE.match(value, i)
        if m is None:
            return None
        depth, j = 1, m.end()
        while j < n and depth:
            depth += {'(': 1, ')': -1}.get(value[j], 0)
            j += 1
        if depth:
            return None
        out.append((m.group(1).lower(), value[m.end():j - 1].strip()))
        i = j
    return out


def _amount(args, default, clamp):
    """A filter function's number or percentage (None when invalid)."""
    a = args.strip()
    if not a:
        return default
    v = parse_number(a[:-1]) / 100.0 if a.endswith('%') and parse_number(a[:-1]) is not None \
        else parse_number(a)
    if v is None or not math.isfinite(v) or v < 0:
        return None
    return min(v, 1.0) if clamp else v


def _function_filter(primitive):
    """A filter function as a one-primitive Filter without a region."""
    primitive.inputs = (F.Source.GRAPHIC,)
    primitive.linear = False
    return F.Filter(region=None, primitives=[primitive])


def _filter_function(el, name, args, state, cache):
    """A CSS filter function as a Filter without a region (None: invalid)."""
    if name in ('grayscale', 'sepia', 'saturate', 'hue-rotate'):
        if name == 'hue-rotate':
            # CSS angles need a unit (only 0 may go without)
            a = 0.0 if not args or args.strip() == '0' else parse_angle(args.strip())
            if a is None or (args and args.strip() != '0' and args.strip()[-1].isdigit()):
                return None
            m = _color_matrix_of('hueRotate', repr(float(a)))
        else:
            v = _amount(args, 1.0, name != 'saturate')
            if v is None:
                return None
            if name == 'saturate':
                m = _saturate_matrix(v)
            else:
                r = 1.0 - v
                m = _IDENTITY_MATRIX.copy()
                if name == 'grayscale':
                    m[:3, :3] = [[0.2126 + 0.7874 * r, 0.7152 - 0.7152 * r, 0.0722 - 0.0722 * r],
                                 [0.2126 - 0.2126 * r, 0.7152 + 0.2848 * r, 0.0722 - 0.0722 * r],
                                 [0.2126 - 0.2126 * r, 0.7152 - 0.7152 * r, 0.0722 + 0.9278 * r]]
                else:
                    m[:3, :3] = [[0.393 + 0.607 * r, 0.769 - 0.769 * r, 0.189 - 0.189 * r],
                                 [0.349 - 0.349 * r, 0.686 + 0.314 * r, 0.168 - 0.168 * r],
                                 [0.272 - 0.272 * r, 0.534 - 0.534 * r, 0.131 + 0.869 * r]]
        return _function_filter(F.ColorMatrix(matrix=m))
    if name in ('invert', 'opacity', 'brightness', 'contrast'):
        v = _amount(args, 1.0, name in ('invert', 'opacity'))
        if v is None:
            return None
        if name == 'invert':
            funcs = {i: F.TableTransfer((v, 1.0 - v)) for i in range(3)}
        elif name == 'opacity':
            funcs = {3: F.TableTransfer((0.0, v))}
        elif name == 'brightness':
            funcs = {i: F.LinearTransfer(v, 0.0) for i in range(3)}
        else:
            funcs = {i: F.LinearTransfer(v, 0.5 - 0.5 * v) for i in range(3)}
        return _function_filter(F.ComponentTransfer(funcs=funcs))
    inh, _own = doc_style(el, cache)
    ctx = length_context(inh, state, cache)
    if name == 'blur':
        v = 0.0 if not args else parse_length(args, 'other', ctx)
        if v is None or v < 0 or args.strip().endswith('%'):
            return None
        return _function_filter(F.GaussianBlur(std_dev=(v, v)))
    if name == 'drop-shadow':
        toks = _tokens(args)

        def length(tok):
            return None if tok.endswith('%') else parse_length(tok, 'other', ctx)

        color = given = None
        if toks and length(toks[0]) is None:
            given = toks.pop(0)
        elif toks and length(toks[-1]) is None:
            given = toks.pop()
        if given is not None:
            color = parse_color(given)
            if color is None:
                return None
        lens = [length(tok) for tok in toks]
        if None in lens:
            return None
        if len(lens) not in (2, 3) or (len(lens) == 3 and lens[2] < 0):
            return None
        if color is None or not isinstance(color, tuple):
            color = inh.get('_color', (0.0, 0.0, 0.0, 1.0))
        std = lens[2] if len(lens) == 3 else 0.0
        return _function_filter(F.DropShadow(std_dev=(std, std), dx=lens[0], dy=lens[1],
                                             color=tuple(color)))
    return None


def _tokens(args):
    """Space-separated tokens, parentheses kept together."""
    out, depth, cur = [], 0, ''
    for ch in args:
        if ch.isspace() and depth == 0:
            if cur:
                out.append(cur)
            cur = ''
            continue
        depth += {'(': 1, ')': -1}.get(ch, 0)
        cur += ch
    if cur:
        out.append(cur)
    return out


def _saturate_matrix(s):
    m = _IDENTITY_MATRIX.copy()
    m[:3, :3] = [[0.213 + 0.787 * s, 0.715 - 0.715 * s, 0.072 - 0.072 * s],
                 [0.213 - 0.213 * s, 0.715 + 0.285 * s, 0.072 - 0.072 * s],
                 [0.213 - 0.213 * s, 0.715 - 0.715 * s, 0.072 + 0.928 * s]]
    return m


def _resolve_filter(fel, kids, state, cache):
    chain = href_chain(fel, ('filter',), cache)
    inh, _own = doc_style(fel, cache)
    units = chain_attr(chain, 'filterUnits')
    obb = units != 'userSpaceOnUse'
    pobb = chain_attr(chain, 'primitiveUnits') == 'objectBoundingBox'
    box = None
    if obb or pobb:
        box = object_box(kids)
        if box is None or box[2] <= 0 or box[3] <= 0:
            return None
    unit_ctx = LengthContext(font_size=inh['_fs'], width=1.0, height=1.0, dpi=cache.options.dpi)
    user_ctx = length_context(inh, state, cache)

    def rect(src, ctx, in_obb, default):
        vals = []
        for name, axis, d in zip(('x', 'y', 'width', 'height'), 'xyxy', default):
            s = chain_attr(src, name)
            v = parse_length(s, axis, ctx) if s is not None else None
            vals.append(v)
        if in_obb:
            out = [box[0] + vals[0] * box[2] if vals[0] is not None else None,
                   box[1] + vals[1] * box[3] if vals[1] is not None else None,
                   vals[2] * box[2] if vals[2] is not None else None,
                   vals[3] * box[3] if vals[3] is not None else None]
        else:
            out = vals
        return [d if v is None else v for v, d in zip(out, default)]

    if obb:
        dflt = (box[0] - 0.1 * box[2], box[1] - 0.1 * box[3], 1.2 * box[2], 1.2 * box[3])
    else:
        dflt = (parse_length('-10%', 'x', user_ctx), parse_length('-10%', 'y', user_ctx),
                parse_length('120%', 'x', user_ctx), parse_length('120%', 'y', user_ctx))
    region = rect(chain, unit_ctx if obb else user_ctx, obb, dflt)
    if not (region[2] > 0 and region[3] > 0):
        return None
    src = next((e for e in chain if any(local_name(c) for c in e)), fel)
    prims = []
    names = set()
    with cache.referencing(fel):
        for c in src:
            name = local_name(c)
            if name is None or not name.startswith('fe'):
                continue
            p = _resolve_primitive(c, name, region, box if pobb else None,
                                   unit_ctx if pobb else user_ctx, state, cache)
            if p is None:
                continue
            p.inputs = tuple(_input(v, names, not prims) for v in p.inputs)
            prims.append(p)
            if p.result:
                names.add(p.result)
    if not prims:
        return None
    return F.Filter(region=tuple(float(v) for v in region), primitives=prims,
                    id=fel.get('id') or '')


def _input(name, defined, first):
    """An ``in`` attribute value resolved against the result names defined
    so far: a Source, a Result, or the previous result (SourceGraphic for
    the first primitive)."""
    if name == 'SourceGraphic':
        return F.Source.GRAPHIC
    if name == 'SourceAlpha':
        return F.Source.ALPHA
    if name is not None and name in defined:
        return F.Result(name)
    return F.Source.GRAPHIC if first else F.PREVIOUS


def _transparent():
    """What a primitive in error draws."""
    return F.Flood(color=F.TRANSPARENT)


def _resolve_primitive(el, name, region, pbox, ctx, state, cache):
    inh, own = doc_style(el, cache)
    if name not in _SUPPORTED:
        cache.warn('filter-unknown', 'unknown filter primitive <%s> skipped' % name)
        return None         # unknown elements are skipped (resvg)
    sub = []
    for attr, axis, i in (('x', 'x', 0), ('y', 'y', 1), ('width', 'x', 2), ('height', 'y', 3)):
        s = el.get(attr)
        v = parse_length(s, axis, ctx) if s is not None else None
        if pbox is not None:
            # as resvg: fractions of the filter region, not of the bbox,
            # except for feImage and feFlood, whose missing values are
            # 0, 0, 100 %, 100 % of the bbox (not the filter region)
            if name in ('feImage', 'feFlood'):
                if v is None:
                    v = 0.0 if i < 2 else 1.0
                ref = pbox
            else:
                ref = region
            if v is not None:
                v = ref[i] + v * ref[i + 2] if i < 2 else v * ref[i]
        sub.append(v)
    subregion = tuple(None if v is None else float(v) for v in sub)
    linear = inh.get('color-interpolation-filters', 'linearRGB') == 'linearRGB'
    sx, sy = (pbox[2], pbox[3]) if pbox is not None else (1.0, 1.0)
    ins = (el.get('in'),)
    if name in ('feComposite', 'feBlend', 'feDisplacementMap'):
        ins = (el.get('in'), el.get('in2'))
    elif name == 'feMerge':
        ins = tuple(c.get('in') for c in el if local_name(c) == 'feMergeNode')
    elif name in ('feFlood', 'feTurbulence', 'feImage'):
        ins = ()

    def color(prop_c, prop_o):
        c = parse_color(own.get(prop_c, 'black')) if own.get(prop_c) else (0, 0, 0, 1)
        if c is None:
            c = (0, 0, 0, 1)
        elif not isinstance(c, tuple):          # currentColor
            c = inh.get('_color', (0, 0, 0, 1))
        o = _number(own.get(prop_o), 1.0) if prop_o in own else 1.0
        s = own.get(prop_o, '').strip()
        if s.endswith('%'):
            o = _number(s[:-1], 100.0) / 100.0
        return tuple(c[:3]) + (float(c[3]) * min(max(o, 0.0), 1.0),)

    def std_dev(default):
        v = _numbers(el.get('stdDeviation'))
        if v is None or len(v) not in (1, 2):
            v = [default, default]
        if len(v) == 1:
            v = [v[0], v[0]]
        return (v[0] * sx, v[1] * sy)

    if name == 'feGaussianBlur':
        p = F.GaussianBlur(std_dev=std_dev(0.0))
    elif name == 'feDropShadow':
        p = F.DropShadow(std_dev=std_dev(2.0), dx=_number(el.get('dx'), 2.0) * sx,
                         dy=_number(el.get('dy'), 2.0) * sy,
                         color=color('flood-color', 'flood-opacity'))
    elif name == 'feOffset':
        p = F.Offset(dx=_number(el.get('dx'), 0.0) * sx, dy=_number(el.get('dy'), 0.0) * sy)
    elif name == 'feFlood':
        p = F.Flood(color=color('flood-color', 'flood-opacity'))
    elif name == 'feComposite':
        p = F.Composite(operator=_COMPOSITE.get(el.get('operator', 'over'),
                                                F.CompositeOperator.OVER),
                        k=tuple(_number(el.get(k), 0.0) for k in ('k1', 'k2', 'k3', 'k4')))
    elif name == 'feBlend':
        p = F.Blend(mode=_BLEND.get(el.get('mode', 'normal').strip(), BlendMode.NORMAL))
    elif name == 'feColorMatrix':
        p = F.ColorMatrix(matrix=_color_matrix_of(el.get('type', 'matrix').strip(),
                                                  el.get('values')))
    elif name == 'feComponentTransfer':
        funcs = {}
        for c in el:
            n = local_name(c)
            if n in ('feFuncR', 'feFuncG', 'feFuncB', 'feFuncA'):
                fn = _transfer_of(c)
                if fn is not None:
                    funcs['RGBA'.index(n[-1])] = fn
        p = F.ComponentTransfer(funcs=funcs)
    elif name == 'feMorphology':
        v = _numbers(el.get('radius'))
        if v is None or len(v) not in (1, 2):
            v = [-1.0, -1.0]                    # invalid: the input unchanged
        if len(v) == 1:
            v = [v[0], v[0]]
        op = el.get('operator', 'erode')
        p = F.Morphology(operator=F.MorphologyOperator.DILATE if op == 'dilate'
                         else F.MorphologyOperator.ERODE, radius=(v[0] * sx, v[1] * sy))
    elif name == 'feTile':
        p = F.Tile()
    elif name == 'feMerge':
        p = F.Merge()
    elif name == 'feTurbulence':
        bf = _numbers(el.get('baseFrequency', '0'))
        if bf is None or len(bf) not in (1, 2) or min(bf) < 0:
            p = _transparent()
        else:
            if len(bf) == 1:
                bf = [bf[0], bf[0]]
            octaves = _number(el.get('numOctaves'), 1.0)
            p = F.Turbulence(base_frequency=tuple(bf), num_octaves=max(int(octaves), 0),
                             seed=int(_number(el.get('seed'), 0.0)),
                             fractal=el.get('type') == 'fractalNoise',
                             stitch=el.get('stitchTiles', '').strip() == 'stitch')
    elif name == 'feDisplacementMap':
        p = F.DisplacementMap(scale=_number(el.get('scale'), 0.0) * (sx + sy) / 2.0,
                              x_channel=_channel(el.get('xChannelSelector', 'A')),
                              y_channel=_channel(el.get('yChannelSelector', 'A')))
    elif name == 'feConvolveMatrix':
        p = _convolve(el)
    elif name in ('feDiffuseLighting', 'feSpecularLighting'):
        p = _lighting(el, name, inh, own)
    else:   # feImage
        rect = tuple(r if v is None else v for v, r in zip(sub, region))
        nodes, is_element = _image_nodes(el, state, rect, cache)
        if not nodes:
            p = _transparent()
        else:
            # as resvg: an element is placed at the subregion's origin
            p = F.Image(root=Group(children=nodes), shift=rect[:2] if is_element else (0.0, 0.0))
    if isinstance(p, F.Flood) and name != 'feFlood':
        ins = ()
    p.inputs = ins
    p.result = el.get('result') or ''
    p.subregion = subregion
    p.linear = linear
    return p


def _channel(v):
    return 'RGBA'.index(v) if v in ('R', 'G', 'B', 'A') else 3


def _lighting(el, name, inh, own):
    light = _light_of(el)
    if light is None:
        return _transparent()
    lc = own.get('lighting-color', 'white')
    c = parse_color(lc)
    if c is None:
        c = (1.0, 1.0, 1.0, 1.0)
    elif not isinstance(c, tuple):
        c = inh.get('_color', (0.0, 0.0, 0.0, 1.0))
    surface = _number(el.get('surfaceScale'), 1.0)
    if name == 'feDiffuseLighting':
        return F.DiffuseLighting(light=light, color=tuple(c[:3]), surface_scale=surface,
                                 diffuse_constant=_number(el.get('diffuseConstant'), 1.0))
    exp = _number(el.get('specularExponent'), 1.0)
    if not 1 <= exp <= 128:
        return _transparent()
    return F.SpecularLighting(light=light, color=tuple(c[:3]), surface_scale=surface,
                              specular_constant=_number(el.get('specularConstant'), 1.0),
                              specular_exponent=exp)


def _image_nodes(el, state, rect, cache):
    """``(nodes, is_element)``: tree nodes of an feImage.  A reference to
    an element gives that element's nodes (drawn in the filtered element's
    user space, like ``use``); an image (data URI or file) gives an
    ImageNode fitted into ``rect`` (x, y, w, h) with preserveAspectRatio."""
    href = el.get('href') or el.get(XLINK_HREF) or ''
    href = href.strip()
    if not href.startswith('#'):
        return _image_file_nodes(el, href, rect, cache), False
    tgt = cache.by_id.get(href[1:])
    if tgt is None or local_name(tgt) is None or tgt in cache.active:
        return [], True
    if state.use_depth >= cache.options.max_use_depth:
        return [], True
    parent = tgt.getparent()
    if parent is not None:
        pinh, pown = doc_style(parent, cache)
    else:
        pinh, pown = initial_inherited(cache.options.font_size), {}
    nodes = []
    with cache.referencing(tgt):
        convert(tgt, state.sub(pinh, pown, use_depth=state.use_depth + 1), cache, nodes)
    return nodes, True


def _image_file_nodes(el, href, rect, cache):
    x, y, w, h = rect
    if not href or not (w > 0 and h > 0):
        return []
    try:
        img = load_image(href, cache)
    except (ImageError, RasterError) as e:
        cache.warn(('image', str(e)), 'feImage not rendered: %s' % e)
        return []
    tree = None if isinstance(img, np.ndarray) else img
    iw, ih = (img.shape[1], img.shape[0]) if tree is None else (tree.width, tree.height)
    if not (iw > 0 and ih > 0):
        return []
    par = parse_preserve_aspect_ratio(el.get('preserveAspectRatio', ''))
    try:
        m = viewbox_transform((0.0, 0.0, float(iw), float(ih)), par, w, h, x, y)
    except RasterError:
        return []
    return [ImageNode(view_rect=(x, y, w, h), transform=m, clip=(x, y, w, h),
                      pixels=None if tree is not None else img, tree=tree)]


def _light_of(el):
    """The first light source child of a lighting primitive, or None."""
    for c in el:
        n = local_name(c)
        if n == 'feDistantLight':
            return F.DistantLight(_number(c.get('azimuth'), 0.0),
                                  _number(c.get('elevation'), 0.0))
        if n in ('fePointLight', 'feSpotLight'):
            # positions are user units even with objectBoundingBox
            # primitive units (what resvg's references show)
            def num(a):
                return _number(c.get(a), 0.0)
            if n == 'fePointLight':
                return F.PointLight(num('x'), num('y'), num('z'))
            cone = _number(c.get('limitingConeAngle'), None) \
                if c.get('limitingConeAngle') is not None else None
            # 0 is a flat cone (every direction inside it lit alike); a
            # negative exponent is invalid: the initial 1 (resvg too)
            sexp = _number(c.get('specularExponent'), 1.0)
            return F.SpotLight(num('x'), num('y'), num('z'),
                               (num('pointsAtX'), num('pointsAtY'), num('pointsAtZ')),
                               sexp if sexp >= 0 else 1.0, cone)
    return None


def _convolve(el):
    """An feConvolveMatrix, or transparent black when it is in error (bad
    order, kernel size, target, zero divisor)."""
    order = _numbers(el.get('order', '3'))
    if not order or len(order) > 2 or any(o != int(o) or o < 1 for o in order):
        return _transparent()
    ox = int(order[0])
    oy = int(order[-1])
    k = _numbers(el.get('kernelMatrix'))
    if not k or len(k) != ox * oy:
        return _transparent()
    kern = np.array(k, np.float64).reshape(oy, ox)
    if el.get('divisor') is not None:
        div = _number(el.get('divisor'), 0.0)
        if div == 0:
            return _transparent()
    else:
        div = float(kern.sum()) or 1.0
    tx = _number(el.get('targetX'), ox // 2)
    ty = _number(el.get('targetY'), oy // 2)
    if not (0 <= tx < ox and 0 <= ty < oy) or tx != int(tx) or ty != int(ty):
        return _transparent()
    return F.ConvolveMatrix(kernel=kern, divisor=div, bias=_number(el.get('bias'), 0.0),
                            target=(int(tx), int(ty)),
                            edge_mode=_EDGE.get(el.get('edgeMode', 'duplicate'),
                                                F.EdgeMode.DUPLICATE),
                            preserve_alpha=el.get('preserveAlpha') == 'true')


def _color_matrix_of(kind, values):
    """(4, 5) float64 matrix of an feColorMatrix (identity when invalid)."""
    v = _numbers(values)
    if kind == 'saturate':
        s = v[0] if v and len(v) == 1 else 1.0
        return _saturate_matrix(min(max(s, 0.0), 1.0))
    if kind == 'hueRotate':
        a = math.radians(v[0]) if v and len(v) == 1 else 0.0
        co, si = math.cos(a), math.sin(a)
        m = _IDENTITY_MATRIX.copy()
        m[:3, :3] = (np.array([[0.213, 0.715, 0.072]] * 3)
                     + co * np.array([[0.787, -0.715, -0.072], [-0.213, 0.285, -0.072],
                                      [-0.213, -0.715, 0.928]])
                     + si * np.array([[-0.213, -0.715, 0.928], [0.143, 0.140, -0.283],
                                      [-0.787, 0.715, 0.072]]))
        return m
    if kind == 'luminanceToAlpha':
        m = np.zeros((4, 5))
        m[3, :3] = (0.2125, 0.7154, 0.0721)
        return m
    if v is not None and len(v) == 20:          # 'matrix', and unknown types (resvg)
        return np.array(v, np.float64).reshape(4, 5)
    return _IDENTITY_MATRIX.copy()


def _transfer_of(el):
    kind = el.get('type', '')
    if kind == 'table' or kind == 'discrete':
        v = _numbers(el.get('tableValues'))
        if not v:
            return None
        return F.TableTransfer(tuple(v)) if kind == 'table' else F.DiscreteTransfer(tuple(v))
    if kind == 'linear':
        return F.LinearTransfer(_number(el.get('slope'), 1.0), _number(el.get('intercept'), 0.0))
    if kind == 'gamma':
        return F.GammaTransfer(_number(el.get('amplitude'), 1.0), _number(el.get('exponent'), 1.0),
                               _number(el.get('offset'), 0.0))
    return None
