"""SVG filter effects (Filter Effects Module Level 1): resolution and pixels.

Two halves:

* **Resolution** (:func:`resolve_filter_property`, called by the tree
  builder): a ``filter`` property value naming ``<filter>`` elements becomes a
  list of :class:`Filter` objects in the filtered element's *user space*:
  ``filterUnits``/``primitiveUnits`` applied, the filter region and every
  primitive subregion resolved to ``(x, y, w, h)`` rectangles, lengths such as
  ``stdDeviation`` and ``dx`` in user units, ``in``/``result`` names kept.
* **Pixels** (:func:`apply_filters`, called by the renderer on a finished
  layer, and the primitive operations :func:`gaussian_blur`,
  :func:`offset`, :func:`composite`, :func:`color_matrix`, ...): premultiplied
  float32 RGBA images of shape ``(H, W, 4)``, row 0 at the top; pixel
  ``(i, j)`` covers ``[j, j+1] x [i, i+1]`` of the layer.

Semantics follow the specification and resvg where they differ:

* a reference to a missing element or to a non-``filter`` element, a filter
  without primitives, a region of zero size, or ``objectBoundingBox`` units
  on an element without a box make the element **not rendered**;
* the filter region is transformed to device space and rounded outwards to
  whole pixels; everything outside it is transparent;
* an ``in`` naming no earlier ``result`` is taken as unspecified (the
  previous result, or ``SourceGraphic`` for the first primitive);
* ``feImage`` referencing an element draws it in the filtered element's user
  space translated to the subregion's origin (as resvg); an image (data URI
  or file) is fitted into the subregion with ``preserveAspectRatio``;
* an feConvolveMatrix in error (bad order, kernel size, target, zero
  divisor) gives transparent black;
* feTurbulence follows the specification's reference generator (no
  ``stitchTiles``); feDisplacementMap samples the nearest pixel.

Transforms: the filter works on device pixels.  An axis-aligned CTM
(scale + translate) is exact.  Under rotation or skew the region is the
device bounding box of the transformed user-space region; blur radii and
offsets are scaled by the lengths of the CTM matrix's rows (not rotated): an
approximation, the one resvg makes (its references show device-
aligned region edges and device-isotropic blurs under skew).

Colour: results carry their colour space; an input is converted to the
primitive's ``color-interpolation-filters`` space (``linearRGB`` by default)
on unpremultiplied values, and the final result back to sRGB.

>>> import numpy as np
>>> img = np.zeros((1, 5, 4), np.float32); img[0, 1] = (1, 0, 0, 1)
>>> offset(img, 2, 0)[0, :, 3].tolist()
[0.0, 0.0, 0.0, 1.0, 0.0]
"""

import math
import re
from dataclasses import dataclass, field
from typing import Optional, Tuple

import numpy as np

from ..errors import RasterError
from ..geometry.transform import Affine
from .document import chain_attr

__all__ = ['FilterError', 'Filter', 'Primitive', 'resolve_filter_property', 'filter_box',
           'filter_pixel_box', 'group_filters', 'apply_filters', 'gaussian_blur', 'box_blur',
           'box_sigma', 'offset', 'composite', 'blend', 'color_matrix', 'component_transfer',
           'morphology', 'convolve', 'lighting', 'turbulence', 'displace', 'srgb_to_linear',
           'linear_to_srgb', 'DEFAULT_TOLERANCE']

#: Default tolerance (device pixels) for explicit-accuracy blurs (see
#: :func:`gaussian_blur`; the renderer follows the specification's box
#: approximation instead, as resvg).
DEFAULT_TOLERANCE = 0.25


class FilterError(RasterError, ValueError):
    """Invalid input to a filter operation (bad image shape, non-finite
    parameter)."""


# ---------------------------------------------------------------------------
# Resolved filters
# ---------------------------------------------------------------------------

@dataclass(slots=True)
class Primitive:
    """One resolved filter primitive.

    Attributes
    ----------
    kind : str
        Element local name: ``'feGaussianBlur'``, ``'feOffset'``, ...
    inputs : tuple of str or None
        Input names (``'SourceGraphic'``, ``'SourceAlpha'``, a result name);
        ``None`` entries mean "previous result".
    result : str
        The ``result`` name ('' if none).
    subregion : (x, y, w, h) floats or None
        Subregion in the element's user space; None entries default to the
        filter region's.
    linear : bool
        True when ``color-interpolation-filters`` is ``linearRGB``.
    params : dict
        Kind-specific parameters, lengths in user units.
    """
    kind: str
    inputs: tuple = ()
    result: str = ''
    subregion: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    linear: bool = True
    params: dict = field(default_factory=dict)


@dataclass(slots=True)
class Filter:
    """A resolved ``<filter>``: ``region`` (x, y, w, h) in the filtered
    element's user space (None for a CSS filter function such as
    ``blur(2px)``, which has no region: it covers the canvas) and its
    primitives in order."""
    region: Optional[Tuple[float, float, float, float]]
    primitives: list
    id: str = ''


class FilterList(list):
    """A list of :class:`Filter` to apply in order (truthy when not empty)."""


_SUPPORTED = {'feGaussianBlur', 'feOffset', 'feFlood', 'feMerge', 'feComposite', 'feBlend',
              'feColorMatrix', 'feComponentTransfer', 'feDropShadow', 'feMorphology', 'feTile',
              'feImage', 'feConvolveMatrix', 'feDiffuseLighting', 'feSpecularLighting',
              'feTurbulence', 'feDisplacementMap'}
_UNSUPPORTED = set()
_SVG_NS = '{http://www.w3.org/2000/svg}'


def _local(el):
    tag = el.tag
    if isinstance(tag, str) and tag.startswith(_SVG_NS):
        return tag[len(_SVG_NS):]
    return None


def _numbers(s):
    """Numbers of a list attribute (None if absent or malformed)."""
    if s is None:
        return None
    from .values import parse_number_list
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


def resolve_filter_property(builder, el, value, kids, st):
    """Resolve a ``filter`` property value for an element.

    Parameters
    ----------
    builder : raster.svg.build._Builder
        The tree builder (for ids, styles, lengths and warnings).
    el : lxml element
        The filtered element.
    value : str
        The property value, e.g. ``'url(#f1)'`` (several ``url()`` apply in
        order).
    kids : list of tree nodes
        The element's content in its user space (for objectBoundingBox).
    st : build state (viewport size for percentages).

    Returns
    -------
    FilterList or None
        ``None`` when the element must not be rendered (invalid reference,
        empty filter, zero region); an empty list when the value is ignored
        (an invalid filter function list, a recursive reference; with a
        warning).
    """
    from .values import parse_url
    refs = _functions(value)
    out = FilterList()
    if not refs:
        builder.warn('filter-syntax', 'invalid filter value %r ignored' % (value,))
        return out
    for name, args in refs:
        if name != 'url':
            f = _filter_function(builder, el, name, args, st)
            if f is None:
                builder.warn('filter-syntax', 'invalid filter value %r ignored' % (value,))
                return FilterList()
            out.append(f)
            continue
        u = parse_url('url(%s)' % args)
        tgt = builder.by_id.get(u[0]) if u is not None else None
        if tgt is None or _local(tgt) != 'filter':
            return None
        if tgt in builder._active_refs:
            # used inside its own feImage: the inner use is dropped (resvg)
            builder.warn('filter-recursive', 'recursive filter reference ignored')
            continue
        f = _resolve_filter(builder, tgt, kids, st)
        if f is None:
            return None
        out.append(f)
    return out


def _functions(value):
    """``'url(#a) blur(2px)'`` -> ``[('url', '#a'), ('blur', '2px')]``
    (nested parentheses kept in the arguments); None when malformed."""
    out = []
    i, n = 0, len(value)
    while i < n:
        if value[i].isspace() or value[i] == ',':
            i += 1
            continue
        m = re.compile(r'([A-Za-z-]+)\(').match(value, i)
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
    from .values import parse_number
    a = args.strip()
    if not a:
        return default
    v = parse_number(a[:-1]) / 100.0 if a.endswith('%') and parse_number(a[:-1]) is not None \
        else parse_number(a)
    if v is None or not math.isfinite(v) or v < 0:
        return None
    return min(v, 1.0) if clamp else v


def _fn_primitive(kind, **params):
    return Primitive(kind=kind, inputs=(None,), subregion=(None,) * 4, linear=False,
                     params=params)


def _filter_function(b, el, name, args, st):
    """A CSS filter function as a Filter without a region (None: invalid)."""
    from .values import parse_angle, parse_color, parse_length
    lin = np.hstack([np.eye(4), np.zeros((4, 1))])
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
                m = lin.copy()
                if name == 'grayscale':
                    m[:3, :3] = [[0.2126 + 0.7874 * r, 0.7152 - 0.7152 * r, 0.0722 - 0.0722 * r],
                                 [0.2126 - 0.2126 * r, 0.7152 + 0.2848 * r, 0.0722 - 0.0722 * r],
                                 [0.2126 - 0.2126 * r, 0.7152 - 0.7152 * r, 0.0722 + 0.9278 * r]]
                else:
                    m[:3, :3] = [[0.393 + 0.607 * r, 0.769 - 0.769 * r, 0.189 - 0.189 * r],
                                 [0.349 - 0.349 * r, 0.686 + 0.314 * r, 0.168 - 0.168 * r],
                                 [0.272 - 0.272 * r, 0.534 - 0.534 * r, 0.131 + 0.869 * r]]
        return Filter(region=None, primitives=[_fn_primitive('feColorMatrix', matrix=m)])
    if name in ('invert', 'opacity', 'brightness', 'contrast'):
        v = _amount(args, 1.0, name in ('invert', 'opacity'))
        if v is None:
            return None
        if name == 'invert':
            funcs = {i: ('table', (v, 1.0 - v)) for i in range(3)}
        elif name == 'opacity':
            funcs = {3: ('table', (0.0, v))}
        elif name == 'brightness':
            funcs = {i: ('linear', (v, 0.0)) for i in range(3)}
        else:
            funcs = {i: ('linear', (v, 0.5 - 0.5 * v)) for i in range(3)}
        return Filter(region=None,
                      primitives=[_fn_primitive('feComponentTransfer', funcs=funcs)])
    inh, _own = b.doc_style(el)
    ctx = b.ctx(inh, st)
    if name == 'blur':
        v = 0.0 if not args else parse_length(args, 'other', ctx)
        if v is None or v < 0 or args.strip().endswith('%'):
            return None
        return Filter(region=None, primitives=[_fn_primitive('feGaussianBlur', std=(v, v))])
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
        return Filter(region=None, primitives=[_fn_primitive(
            'feDropShadow', std=(std, std), dx=lens[0], dy=lens[1], color=tuple(color))])
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
    m = np.hstack([np.eye(4), np.zeros((4, 1))])
    m[:3, :3] = [[0.213 + 0.787 * s, 0.715 - 0.715 * s, 0.072 - 0.072 * s],
                 [0.213 - 0.213 * s, 0.715 + 0.285 * s, 0.072 - 0.072 * s],
                 [0.213 - 0.213 * s, 0.715 - 0.715 * s, 0.072 + 0.928 * s]]
    return m


def _resolve_filter(b, fel, kids, st):
    from .values import LengthContext, parse_length
    chain = b.href_chain(fel, ('filter',))
    inh, _own = b.doc_style(fel)
    units = chain_attr(chain, 'filterUnits')
    obb = units != 'userSpaceOnUse'
    pobb = chain_attr(chain, 'primitiveUnits') == 'objectBoundingBox'
    box = None
    if obb or pobb:
        box = b.object_box(kids)
        if box is None or box[2] <= 0 or box[3] <= 0:
            return None
    unit_ctx = LengthContext(font_size=inh['_fs'], width=1.0, height=1.0, dpi=b.dpi)
    user_ctx = b.ctx(inh, st)

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
        from .values import parse_length as pl
        dflt = (pl('-10%', 'x', user_ctx), pl('-10%', 'y', user_ctx),
                pl('120%', 'x', user_ctx), pl('120%', 'y', user_ctx))
    region = rect(chain, unit_ctx if obb else user_ctx, obb, dflt)
    if not (region[2] > 0 and region[3] > 0):
        return None
    src = next((e for e in chain if any(_local(c) for c in e)), fel)
    prims = []
    with b.referencing(fel):
        for c in src:
            name = _local(c)
            if name is None or not name.startswith('fe'):
                continue
            p = _resolve_primitive(b, c, name, region, box if pobb else None,
                                   unit_ctx if pobb else user_ctx, st)
            if p is not None:
                prims.append(p)
    if not prims:
        return None
    return Filter(region=tuple(float(v) for v in region), primitives=prims,
                  id=fel.get('id') or '')


def _resolve_primitive(b, el, name, region, pbox, ctx, st):
    from .values import parse_color, parse_length
    inh, own = b.doc_style(el)
    if name not in _SUPPORTED:
        if name in _UNSUPPORTED:
            b.warn('filter-' + name, 'filter primitive %s is not supported; its result is '
                   'transparent' % name)
        else:
            b.warn('filter-unknown', 'unknown filter primitive <%s> skipped' % name)
            return None         # unknown elements are skipped (resvg)
    sub = []
    for attr, axis, i in (('x', 'x', 0), ('y', 'y', 1), ('width', 'x', 2), ('height', 'y', 3)):
        s = el.get(attr)
        v = parse_length(s, axis, ctx) if s is not None else None
        if v is not None and pbox is not None:
            # as resvg: fractions of the filter region, not of the bbox,
            # except for feImage and feFlood
            ref = pbox if name in ('feImage', 'feFlood') else region
            v = ref[i] + v * ref[i + 2] if i < 2 else v * ref[i]
        sub.append(v)
    cif = inh.get('color-interpolation-filters', 'linearRGB')
    linear = cif == 'linearRGB'
    sx, sy = (pbox[2], pbox[3]) if pbox is not None else (1.0, 1.0)
    pr = {}
    ins = (el.get('in'),)
    if name in ('feComposite', 'feBlend', 'feDisplacementMap'):
        ins = (el.get('in'), el.get('in2'))
    elif name == 'feMerge':
        ins = tuple(c.get('in') for c in el if _local(c) == 'feMergeNode')
    elif name in ('feFlood',) or name in _UNSUPPORTED:
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

    if name in ('feGaussianBlur', 'feDropShadow'):
        v = _numbers(el.get('stdDeviation'))
        if v is None or len(v) not in (1, 2):
            v = [2.0, 2.0] if name == 'feDropShadow' else [0.0, 0.0]
        if len(v) == 1:
            v = [v[0], v[0]]
        pr['std'] = (v[0] * sx, v[1] * sy)
    if name in ('feOffset', 'feDropShadow'):
        d = 2.0 if name == 'feDropShadow' else 0.0
        pr['dx'] = _number(el.get('dx'), d) * sx
        pr['dy'] = _number(el.get('dy'), d) * sy
    if name in ('feFlood', 'feDropShadow'):
        pr['color'] = color('flood-color', 'flood-opacity')
    if name == 'feComposite':
        op = el.get('operator', 'over')
        pr['operator'] = op if op in ('over', 'in', 'out', 'atop', 'xor', 'arithmetic') \
            else 'over'
        pr['k'] = tuple(_number(el.get(k), 0.0) for k in ('k1', 'k2', 'k3', 'k4'))
    if name == 'feBlend':
        pr['mode'] = el.get('mode', 'normal').strip()
    if name == 'feColorMatrix':
        pr['matrix'] = _color_matrix_of(el.get('type', 'matrix').strip(), el.get('values'))
    if name == 'feComponentTransfer':
        funcs = {}
        for c in el:
            n = _local(c)
            if n in ('feFuncR', 'feFuncG', 'feFuncB', 'feFuncA'):
                funcs['RGBA'.index(n[-1])] = _transfer_of(c)
        pr['funcs'] = funcs
    if name == 'feMorphology':
        op = el.get('operator', 'erode')
        pr['operator'] = op if op in ('erode', 'dilate') else 'erode'
        v = _numbers(el.get('radius'))
        if v is None or len(v) not in (1, 2):
            v = [-1.0, -1.0]                    # invalid: the input unchanged
        if len(v) == 1:
            v = [v[0], v[0]]
        pr['radius'] = (v[0] * sx, v[1] * sy)
    if name == 'feTurbulence':
        ins = ()
        bf = _numbers(el.get('baseFrequency', '0'))
        if bf is None or len(bf) not in (1, 2) or min(bf) < 0:
            bf = None
        elif len(bf) == 1:
            bf = [bf[0], bf[0]]
        octaves = _number(el.get('numOctaves'), 1.0)
        pr['turb'] = None if bf is None else (
            tuple(bf), max(int(octaves), 0), int(_number(el.get('seed'), 0.0)),
            el.get('type') == 'fractalNoise')
    if name == 'feDisplacementMap':
        pr['scale'] = _number(el.get('scale'), 0.0) * (sx + sy) / 2.0
        pr['channels'] = tuple('RGBA'.index(v) if v in ('R', 'G', 'B', 'A') else 3
                               for v in (el.get('xChannelSelector', 'A'),
                                         el.get('yChannelSelector', 'A')))
    if name == 'feConvolveMatrix':
        pr['conv'] = _convolve_params(el)
    if name in ('feDiffuseLighting', 'feSpecularLighting'):
        pr['light'] = _light_of(el, pbox)
        lc = own.get('lighting-color', 'white')
        c = parse_color(lc)
        if c is None:
            c = (1.0, 1.0, 1.0, 1.0)
        elif not isinstance(c, tuple):
            c = inh.get('_color', (0.0, 0.0, 0.0, 1.0))
        pr['color'] = tuple(c[:3])
        pr['surface'] = _number(el.get('surfaceScale'), 1.0)
        if name == 'feDiffuseLighting':
            pr['k'] = _number(el.get('diffuseConstant'), 1.0)
            pr['exp'] = 1.0
        else:
            pr['k'] = _number(el.get('specularConstant'), 1.0)
            pr['exp'] = _number(el.get('specularExponent'), 1.0)
    if name == 'feImage':
        ins = ()
        rect = tuple(r if v is None else v for v, r in zip(sub, region))
        pr['nodes'], is_element = _image_nodes(b, el, st, rect)
        # as resvg: an element is placed at the subregion's origin
        pr['shift'] = rect[:2] if is_element else (0.0, 0.0)
    return Primitive(kind=name, inputs=ins, result=el.get('result') or '',
                     subregion=tuple(None if v is None else float(v) for v in sub),
                     linear=linear, params=pr)


def _image_nodes(b, el, st, rect):
    """``(nodes, is_element)``: tree nodes of an feImage.  A reference to
    an element gives that element's nodes (drawn in the filtered element's
    user space, like ``use``); an image (data URI or file) gives an
    ImageNode fitted into ``rect`` (x, y, w, h) with preserveAspectRatio."""
    href = el.get('href') or el.get('{http://www.w3.org/1999/xlink}href') or ''
    href = href.strip()
    if not href.startswith('#'):
        return _image_file_nodes(b, el, href, rect), False
    tgt = b.by_id.get(href[1:])
    if tgt is None or _local(tgt) is None or tgt in b._active_refs:
        return [], True
    if st.use_depth >= b.max_use_depth:
        return [], True
    parent = tgt.getparent()
    pinh, pown = b.doc_style(parent) if parent is not None else (b._inh0, {})
    nodes = []
    with b.referencing(tgt):
        b.node(tgt, pinh, pown, st.sub(use_depth=st.use_depth + 1), nodes)
    return nodes, True


def _image_file_nodes(b, el, href, rect):
    from .image import _NESTING, ImageError, _source_of, load_image
    from .tree import ImageNode
    from .values import parse_preserve_aspect_ratio, viewbox_transform
    x, y, w, h = rect
    if not href or not (w > 0 and h > 0):
        return []
    cache = getattr(b, '_image_cache', None)
    nest = _NESTING.get()
    depth = 0 if nest is None else nest.depth     # nested documents read no files
    try:
        img = load_image(href, _source_of(b, depth), builder=b, depth=depth, cache=cache)
    except (ImageError, RasterError) as e:
        b.warn(('image', str(e)), 'feImage not rendered: %s' % e)
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


def _light_of(el, pbox):
    """The first light source child of a lighting primitive as
    ``(kind, params)`` in user units, or None."""
    for c in el:
        n = _local(c)
        if n == 'feDistantLight':
            return ('distant', (_number(c.get('azimuth'), 0.0), _number(c.get('elevation'), 0.0)))
        if n in ('fePointLight', 'feSpotLight'):
            # positions are user units even with objectBoundingBox
            # primitive units (what resvg's references show)
            def num(a):
                return _number(c.get(a), 0.0)
            pos = (num('x'), num('y'), num('z'))
            if n == 'fePointLight':
                return ('point', pos)
            at = (num('pointsAtX'), num('pointsAtY'), num('pointsAtZ'))
            cone = _number(c.get('limitingConeAngle'), None) \
                if c.get('limitingConeAngle') is not None else None
            sexp = _number(c.get('specularExponent'), 1.0)
            return ('spot', (pos, at, sexp if sexp > 0 else 1.0, cone))
    return None


def lighting(alpha, light, color, surface, k, exponent, specular, t=None):
    """feDiffuseLighting / feSpecularLighting.

    Parameters
    ----------
    alpha : (H, W) float32 ndarray
        The bump map (input alpha).
    light : (kind, params)
        ``('distant', (azimuth, elevation))`` in degrees,
        ``('point', (x, y, z))`` or
        ``('spot', ((x, y, z), (px, py, pz), exponent, cone or None))``,
        positions in user units.
    color : 3 floats, the light colour (in the working colour space)
    surface, k, exponent : float
        surfaceScale, diffuse/specular constant, specular exponent.
    specular : bool
    t : raster.transform.Affine or None
        User space to pixels for light positions (None: identity).

    Returns
    -------
    (H, W, 4) float32 ndarray, premultiplied
    """
    a = np.asarray(alpha, np.float64)
    h, w = a.shape
    p = np.pad(a, 1, mode='edge')
    # Sobel normal of the surface z = surface * alpha
    nx = -surface / 4.0 * ((p[:-2, 2:] + 2 * p[1:-1, 2:] + p[2:, 2:])
                           - (p[:-2, :-2] + 2 * p[1:-1, :-2] + p[2:, :-2]))
    ny = -surface / 4.0 * ((p[2:, :-2] + 2 * p[2:, 1:-1] + p[2:, 2:])
                           - (p[:-2, :-2] + 2 * p[:-2, 1:-1] + p[:-2, 2:]))
    norm = np.sqrt(nx * nx + ny * ny + 1.0)
    n = np.stack([nx / norm, ny / norm, 1.0 / norm], -1)
    col = np.broadcast_to(np.asarray(color, np.float64), (h, w, 3)).copy()
    kind, prm = light
    if kind == 'distant':
        az, el = math.radians(prm[0]), math.radians(prm[1])
        lv = np.broadcast_to(np.array([math.cos(az) * math.cos(el),
                                       math.sin(az) * math.cos(el), math.sin(el)]), (h, w, 3))
    else:
        pos = prm if kind == 'point' else prm[0]
        sc = 1.0
        if t is not None:
            x, y = t.apply(np.array([[pos[0], pos[1]]]))[0]
            sc = math.sqrt(abs(t.a * t.d - t.b * t.c))
        else:
            x, y = pos[0], pos[1]
        z = pos[2] * sc
        jj, ii = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
        lv = np.stack([x - jj, y - ii, z - surface * a], -1)
        lv = lv / np.maximum(np.linalg.norm(lv, axis=-1, keepdims=True), 1e-12)
        if kind == 'spot':
            at, sexp, cone = prm[1], prm[2], prm[3]
            if t is not None:
                ax, ay = t.apply(np.array([[at[0], at[1]]]))[0]
            else:
                ax, ay = at[0], at[1]
            sv = np.array([ax - x, ay - y, at[2] * sc - z])
            sv = sv / max(np.linalg.norm(sv), 1e-12)
            minus_ls = -(lv @ sv)
            f = np.where(minus_ls > 0, np.power(np.maximum(minus_ls, 0.0), sexp), 0.0)
            if cone is not None:
                f = np.where(minus_ls >= math.cos(math.radians(abs(cone))), f, 0.0)
            col = col * f[..., None]
    if specular:
        hv = lv + np.array([0.0, 0.0, 1.0])
        hv = hv / np.maximum(np.linalg.norm(hv, axis=-1, keepdims=True), 1e-12)
        f = k * np.power(np.maximum((n * hv).sum(-1), 0.0), exponent)
        rgb = np.clip(col * f[..., None], 0.0, 1.0)
        out_a = rgb.max(-1)
        out = np.concatenate([rgb, out_a[..., None]], -1)    # already premultiplied-like
        return out.astype(np.float32)
    f = k * np.maximum((n * lv).sum(-1), 0.0)
    rgb = np.clip(col * f[..., None], 0.0, 1.0)
    return np.concatenate([rgb, np.ones((h, w, 1))], -1).astype(np.float32)


def displace(img, dmap, scale, xch=3, ych=3):
    """feDisplacementMap: ``out(x, y) = img(x + scale (X(x, y) - 0.5),
    y + scale (Y(x, y) - 0.5))`` with X, Y the channels ``xch``, ``ych``
    (0..3 = R, G, B, A) of the unpremultiplied ``dmap``; ``scale`` in
    device pixels; samples outside ``img`` are transparent (nearest pixel).
    """
    src, m = _check(img), _check(dmap, 'displacement map')
    _finite(scale)
    c, a = _unpremul(m)
    mm = np.concatenate([c, a], -1)
    h, w = src.shape[:2]
    jj, ii = np.meshgrid(np.arange(w), np.arange(h))
    u = np.floor(jj + 0.5 + scale * (mm[..., xch] - 0.5)).astype(np.int64)
    v = np.floor(ii + 0.5 + scale * (mm[..., ych] - 0.5)).astype(np.int64)
    ok = (u >= 0) & (u < w) & (v >= 0) & (v < h)
    out = src[np.clip(v, 0, h - 1), np.clip(u, 0, w - 1)]
    return np.where(ok[..., None], out, 0.0).astype(np.float32)


_PERLIN = {}


def _perlin_tables(seed):
    """Lattice selector (514,) int64 and gradients (4, 514, 2) float64 of
    the Filter Effects reference turbulence for ``seed`` (its Park-Miller
    generator; a sequential recurrence, run once per seed and cached)."""
    r = _PERLIN.get(seed)
    if r is not None:
        return r
    m, a, q, rr = 2147483647, 16807, 127773, 2836
    s = seed
    if s <= 0:
        s = -int(math.fmod(s, m - 1)) + 1           # C remainder (sign of s)
    if s > m - 1:
        s = m - 1

    def rnd(x):
        x = a * (x % q) - rr * (x // q)
        return x + m if x <= 0 else x

    lattice = list(range(256)) + [0] * 258
    grad = np.zeros((4, 514, 2))
    for k in range(4):
        for i in range(256):
            for j in range(2):
                s = rnd(s)
                grad[k, i, j] = ((s % 512) - 256) / 256.0
            n = math.hypot(grad[k, i, 0], grad[k, i, 1])
            if n > 0:
                grad[k, i] /= n
    for i in range(255, 0, -1):
        s = rnd(s)
        j = s % 256
        lattice[i], lattice[j] = lattice[j], lattice[i]
    for i in range(258):
        lattice[256 + i] = lattice[i]
        grad[:, 256 + i] = grad[:, i]
    r = (np.array(lattice, np.int64), grad)
    if len(_PERLIN) < 64:
        _PERLIN[seed] = r
    return r


def _noise2(lattice, grad, vx, vy):
    """Perlin noise of the four channels at points (vx, vy): (4, N)."""
    t = vx + 4096.0
    ix = t.astype(np.int64)
    bx0, rx0 = ix & 255, t - ix
    bx1 = (bx0 + 1) & 255
    t = vy + 4096.0
    iy = t.astype(np.int64)
    by0, ry0 = iy & 255, t - iy
    by1 = (by0 + 1) & 255
    rx1, ry1 = rx0 - 1.0, ry0 - 1.0
    i, j = lattice[bx0], lattice[bx1]
    b00, b10 = lattice[i + by0], lattice[j + by0]
    b01, b11 = lattice[i + by1], lattice[j + by1]
    sx = rx0 * rx0 * (3.0 - 2.0 * rx0)
    sy = ry0 * ry0 * (3.0 - 2.0 * ry0)
    g = grad
    u = rx0 * g[:, b00, 0] + ry0 * g[:, b00, 1]
    v = rx1 * g[:, b10, 0] + ry0 * g[:, b10, 1]
    a_ = u + sx * (v - u)
    u = rx0 * g[:, b01, 0] + ry1 * g[:, b01, 1]
    v = rx1 * g[:, b11, 0] + ry1 * g[:, b11, 1]
    b_ = u + sx * (v - u)
    return a_ + sy * (b_ - a_)


def turbulence(x, y, base_freq, octaves, seed, fractal):
    """feTurbulence (without stitching) at user-space points.

    Parameters
    ----------
    x, y : (H, W) float64 ndarrays, user-space coordinates
    base_freq : (fx, fy) floats >= 0
    octaves : int >= 0
    seed : int
    fractal : bool
        True for ``fractalNoise`` (``(sum + 1) / 2``), False for
        ``turbulence`` (sum of absolute values).

    Returns
    -------
    (H, W, 4) float32 ndarray, unpremultiplied RGBA in [0, 1]
    """
    lattice, grad = _perlin_tables(int(seed))
    h, w = x.shape
    vx = x.ravel() * base_freq[0]
    vy = y.ravel() * base_freq[1]
    total = np.zeros((4, vx.size))
    ratio = 1.0
    for _ in range(octaves):                 # loop over octaves, not pixels
        n = _noise2(lattice, grad, vx, vy)
        total += (n if fractal else np.abs(n)) / ratio
        vx, vy, ratio = vx * 2.0, vy * 2.0, ratio * 2.0
    if fractal:
        total = (total + 1.0) / 2.0
    return np.clip(total.T.reshape(h, w, 4), 0.0, 1.0).astype(np.float32)


def _convolve_params(el):
    """(kernel (oy, ox) float64, divisor, bias, (tx, ty), edge mode,
    preserve alpha) of an feConvolveMatrix, or None when it is in error
    (its result is then transparent black)."""
    order = _numbers(el.get('order', '3'))
    if not order or len(order) > 2 or any(o != int(o) or o < 1 for o in order):
        return None
    ox = int(order[0])
    oy = int(order[-1])
    k = _numbers(el.get('kernelMatrix'))
    if not k or len(k) != ox * oy:
        return None
    kern = np.array(k, np.float64).reshape(oy, ox)
    if el.get('divisor') is not None:
        div = _number(el.get('divisor'), 0.0)
        if div == 0:
            return None
    else:
        div = float(kern.sum()) or 1.0
    tx = _number(el.get('targetX'), ox // 2)
    ty = _number(el.get('targetY'), oy // 2)
    if not (0 <= tx < ox and 0 <= ty < oy) or tx != int(tx) or ty != int(ty):
        return None
    edge = el.get('edgeMode', 'duplicate')
    edge = edge if edge in ('duplicate', 'wrap', 'none') else 'duplicate'
    return (kern, div, _number(el.get('bias'), 0.0), (int(tx), int(ty)), edge,
            el.get('preserveAlpha') == 'true')


def convolve(img, kernel, divisor=None, bias=0.0, target=None, edge='duplicate',
             preserve_alpha=False):
    """feConvolveMatrix: ``out[y, x] = sum_ij src[y - ty + i, x - tx + j]
    * K[oy-1-i, ox-1-j] / divisor`` on premultiplied values, then ``bias``
    added to alpha and ``bias * alpha`` to the colours (as resvg); on
    unpremultiplied colour plus ``bias``, alpha kept, when
    ``preserve_alpha``.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied
    kernel : (oy, ox) array of floats
    divisor : float or None (None: the kernel's sum, or 1 when it is 0)
    bias : float
    target : (tx, ty) or None (None: the kernel's centre, rounded down)
    edge : {'duplicate', 'wrap', 'none'}
        How pixels outside the image are taken.

    >>> img = np.zeros((3, 3, 4), np.float32); img[1, 1] = 1
    >>> convolve(img, [[0, 0, 0], [0, 0, 1], [0, 0, 0]], edge='none')[1, 2].tolist()
    [1.0, 1.0, 1.0, 1.0]
    """
    src = _check(img)
    k = np.asarray(kernel, np.float64)
    if k.ndim != 2 or k.size == 0 or not np.isfinite(k).all():
        raise FilterError('convolution kernel must be a finite non-empty 2-D array')
    oy, ox = k.shape
    if divisor is None:
        divisor = float(k.sum()) or 1.0
    _finite(divisor, bias)
    if divisor == 0:
        raise FilterError('convolution divisor must not be 0')
    tx, ty = (ox // 2, oy // 2) if target is None else target
    if preserve_alpha:
        c, a = _unpremul(src)
        work = c
    else:
        work = src
    h, w = src.shape[:2]
    mode = {'duplicate': 'edge', 'wrap': 'wrap', 'none': 'constant'}.get(edge)
    if mode is None:
        raise FilterError('unknown edge mode %r' % (edge,))
    pad = np.pad(work, ((ty, oy - 1 - ty), (tx, ox - 1 - tx), (0, 0)), mode=mode)
    acc = np.zeros(work.shape, np.float64)
    for i in range(oy):                   # loop over kernel taps, not pixels
        for j in range(ox):
            wgt = k[oy - 1 - i, ox - 1 - j]
            if wgt:
                acc += wgt * pad[i:i + h, j:j + w]
    acc = acc / divisor
    if preserve_alpha:
        acc += bias
    else:                                  # bias added to straight colour (resvg)
        acc[..., 3] += bias
        acc[..., :3] += bias * acc[..., 3:4]
    if preserve_alpha:
        return _premul(np.clip(acc, 0, 1).astype(np.float32), a)
    out = np.clip(acc, 0.0, 1.0)
    out[..., :3] = np.minimum(out[..., :3], out[..., 3:4])
    return out.astype(np.float32)


def _color_matrix_of(kind, values):
    """(4, 5) float64 matrix of an feColorMatrix (identity when invalid)."""
    ident = np.hstack([np.eye(4), np.zeros((4, 1))])
    v = _numbers(values)
    if kind == 'saturate':
        s = v[0] if v and len(v) == 1 else 1.0
        return _saturate_matrix(min(max(s, 0.0), 1.0))
    if kind == 'hueRotate':
        a = math.radians(v[0]) if v and len(v) == 1 else 0.0
        co, si = math.cos(a), math.sin(a)
        m = ident.copy()
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
    if kind not in ('saturate', 'hueRotate', 'luminanceToAlpha') and v is not None \
            and len(v) == 20:                   # 'matrix', and unknown types (resvg)
        return np.array(v, np.float64).reshape(4, 5)
    return ident


def _transfer_of(el):
    kind = el.get('type', '')
    if kind == 'table' or kind == 'discrete':
        v = _numbers(el.get('tableValues'))
        if not v:
            return None
        return (kind, tuple(v))
    if kind == 'linear':
        return ('linear', (_number(el.get('slope'), 1.0), _number(el.get('intercept'), 0.0)))
    if kind == 'gamma':
        return ('gamma', (_number(el.get('amplitude'), 1.0), _number(el.get('exponent'), 1.0),
                          _number(el.get('offset'), 0.0)))
    return None


# ---------------------------------------------------------------------------
# Colour spaces
# ---------------------------------------------------------------------------

def srgb_to_linear(c):
    """sRGB-encoded values in [0, 1] to linear light (any shape; float32
    arithmetic, returns float32).

    >>> round(float(srgb_to_linear(0.5)), 5)
    0.21404
    """
    c = np.asarray(c, np.float32)
    out = np.array(c * np.float32(1 / 1.055), ndmin=1)
    out += np.float32(0.055 / 1.055)
    np.maximum(out, np.float32(0.0), out=out)        # keeps power() real below -0.055
    np.power(out, np.float32(2.4), out=out)
    np.copyto(out, c * np.float32(1 / 12.92), where=c <= np.float32(0.04045))
    return out.reshape(c.shape)


def linear_to_srgb(c):
    """Linear-light values in [0, 1] to sRGB encoding (any shape; float32
    arithmetic, returns float32).

    >>> float(linear_to_srgb(srgb_to_linear(0.5)))  # doctest: +ELLIPSIS
    0.5...
    """
    c = np.asarray(c, np.float32)
    out = np.array(np.maximum(c, np.float32(0.0)), ndmin=1)
    np.power(out, np.float32(1 / 2.4), out=out)
    out *= np.float32(1.055)
    out -= np.float32(0.055)
    np.copyto(out, c * np.float32(12.92), where=c <= np.float32(0.0031308))
    return out.reshape(c.shape)


def _unpremul(img):
    """Unpremultiply.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA

    Returns
    -------
    c : (H, W, 3) float32 ndarray
        Straight colour clipped to [0, 1]; 0 where alpha is not positive.
    a : (H, W, 1) float32 ndarray
        The alpha channel (a view of ``img``).
    """
    a = img[..., 3:4]
    inv = np.zeros(a.shape, np.float32)
    np.divide(np.float32(1.0), a, out=inv, where=a > 0)
    c = np.multiply(img[..., :3], inv)
    np.clip(c, 0.0, 1.0, out=c)
    return c, a


def _premul(c, a):
    """(H, W, 4) float32 premultiplied RGBA from straight colour ``c``
    (H, W, 3) and alpha ``a`` (H, W, 1)."""
    out = np.empty(c.shape[:-1] + (4,), np.float32)
    np.multiply(c, a, out=out[..., :3])
    out[..., 3:4] = a
    return out


#: Largest deviation (premultiplied units) from ``colour x alpha`` for an
#: image to count as one solid colour (:func:`_solid_colour`); float32
#: rounding of composited layers stays near 1e-7.
_SOLID_TOL = 1e-5


def _solid_colour(img, tol=_SOLID_TOL):
    """The straight colour of an image painted in one colour, or None.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA
    tol : float
        Largest allowed ``|img[..., k] - c[k] img[..., 3]|``.

    Returns
    -------
    (3,) float32 ndarray or None
        ``c`` in [0, 1] with every pixel within ``tol`` of
        ``c x alpha`` (0 for a transparent image), or None.  Operations that
        are linear in the premultiplied values (blurs) then only need the
        alpha channel.
    """
    if img.size == 0:
        return np.zeros(3, np.float32)
    a = img[..., 3]
    i, j = np.unravel_index(int(np.argmax(a)), a.shape)
    am = float(a[i, j])
    c = np.zeros(3, np.float32)
    if am > 0:
        c = np.clip(img[i, j, :3] / np.float32(am), 0.0, 1.0).astype(np.float32)
    # a sparse sample rejects most non-solid images at a small cost
    for view in (img[::7, ::7], img):
        va = view[..., 3]
        for k in range(3):
            if c[k] == 0 and not view[..., k].any():
                continue                 # exactly 0: one cheap pass
            r = view[..., k] - va * c[k]
            if r.max() > tol or r.min() < -tol:
                return None
    return c


def _solid_image(alpha, c):
    """(H, W, 4) float32 premultiplied image of straight colour ``c`` (3,)
    with ``alpha`` (H, W)."""
    out = np.empty(alpha.shape + (4,), np.float32)
    for k, v in enumerate(c):            # loop over 3 channels
        if v == 0:
            out[..., k] = 0.0
        else:
            np.multiply(alpha, np.float32(v), out=out[..., k])
    out[..., 3] = alpha
    return out


def _nonzero_box(x):
    """Bounding rows and columns of the non-zero pixels of ``x``.

    Parameters
    ----------
    x : (H, W) or (H, W, C) ndarray
        A pixel is non-zero when any of its channels is.

    Returns
    -------
    (y0, y1, x0, x1) ints (half-open) or None when every pixel is zero
    """
    rows = np.flatnonzero(x.any(axis=tuple(range(1, x.ndim))))
    if rows.size == 0:
        return None
    cols = x[rows[0]:rows[-1] + 1].any(axis=0)
    if cols.ndim > 1:
        cols = cols.any(axis=1)
    cols = np.flatnonzero(cols)
    return int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1


class _Image:
    """An intermediate result of a filter chain.

    Either premultiplied pixels or, for content painted in one colour, a
    straight colour and an alpha channel: colour conversions then change
    three numbers, and blurs and offsets move one channel instead of four.

    Parameters
    ----------
    data : (H, W, 4) float32 ndarray or None
        Premultiplied RGBA (made from ``alpha`` and ``colour`` on first
        use when None).
    alpha : (H, W) float32 ndarray or None
        With ``colour``: the image is ``colour x alpha``.
    colour : (3,) float32 ndarray or None
        Straight colour in [0, 1]; None for a general image.
    """
    __slots__ = ('_data', 'alpha', 'colour')

    def __init__(self, data=None, alpha=None, colour=None):
        self._data, self.alpha, self.colour = data, alpha, colour

    @classmethod
    def of(cls, data):
        """Wrap pixels, recognising a solid colour (see :func:`_solid_colour`)."""
        box = _nonzero_box(data)
        if box is None:
            return cls(data, data[..., 3], np.zeros(3, np.float32))
        y0, y1, x0, x1 = box
        c = _solid_colour(data[y0:y1, x0:x1])
        return cls(data, None if c is None else data[..., 3], c)

    @property
    def solid(self):
        return self.colour is not None

    @property
    def alpha_channel(self):
        """(H, W) float32 alpha (a view)."""
        return self.alpha if self.solid else self._data[..., 3]

    @property
    def data(self):
        """(H, W, 4) float32 premultiplied pixels."""
        if self._data is None:
            self._data = _solid_image(self.alpha, self.colour)
        return self._data

    def clip(self, rect):
        """The image with everything outside ``rect`` (x0, y0, x1, y1)
        transparent."""
        x0, y0, x1, y1 = rect
        src = self.alpha if self.solid else self._data
        if (x0, y0, x1, y1) == (0, 0, src.shape[1], src.shape[0]):
            return self
        out = np.zeros(src.shape, np.float32)
        out[y0:y1, x0:x1] = src[y0:y1, x0:x1]
        return _Image(alpha=out, colour=self.colour) if self.solid else _Image(out)


#: Bytes of one work block of :func:`_by_rows` and :func:`_box_passes`:
#: blocks this small keep their temporaries in the processor's cache.
_BLOCK_BYTES = 1 << 19


def _by_rows(fn, img):
    """``fn`` (a per-pixel map of (h, W, 4) float32 blocks to (h, W, 4)
    float32) applied to cache-sized blocks of rows of ``img`` (H, W, 4):
    its temporaries stay small."""
    h, w = img.shape[:2]
    out = np.empty((h, w, 4), np.float32)
    step = max(1, _BLOCK_BYTES // (16 * max(w, 1)))
    for y in range(0, h, step):          # loop over blocks of rows
        out[y:y + step] = fn(img[y:y + step])
    return out


def _convert_pixels(img, fn):
    """Apply the transfer ``fn`` to the straight colour of the
    premultiplied ``img`` (H, W, 4); only the bounding box of the visible
    pixels is worked on (transparent pixels stay transparent)."""
    box = _nonzero_box(img)
    if box is None:
        return np.zeros_like(img)
    y0, y1, x0, x1 = box

    def block(b):
        c, a = _unpremul(b)
        return _premul(fn(c), a)

    res = _by_rows(block, img[y0:y1, x0:x1])
    if res.shape == img.shape:
        return res
    out = np.zeros_like(img)
    out[y0:y1, x0:x1] = res
    return out


def _convert(img, linear_from, linear_to):
    """An :class:`_Image` converted from linearRGB (``linear_from`` True)
    or sRGB to the other space (``img`` itself when they agree)."""
    if linear_from == linear_to:
        return img
    fn = srgb_to_linear if linear_to else linear_to_srgb
    if img.solid:
        return _Image(alpha=img.alpha, colour=fn(img.colour))
    return _Image(_convert_pixels(img.data, fn))


# ---------------------------------------------------------------------------
# Pixel operations (premultiplied float32 (H, W, 4) images)
# ---------------------------------------------------------------------------

def _check(img, name='image'):
    a = np.asarray(img)
    if a.ndim != 3 or a.shape[2] != 4:
        raise FilterError('%s must be an (H, W, 4) array, got shape %r' % (name, a.shape))
    return a.astype(np.float32, copy=False)


def _finite(*vals):
    for v in vals:
        if not math.isfinite(float(v)):
            raise FilterError('filter parameter must be finite, got %r' % (v,))


def _box_passes(x, boxes):
    """Successive box sums along axis 0.

    Pass ``(d, left)`` maps ``x`` to ``y[i] = sum(x[i - left : i - left +
    d])`` with zeros outside the array.  Each window sum is built from
    sums of power-of-two windows (``W_2k[i] = W_k[i] + W_k[i + k]``), so a
    pass costs about ``log2(d) + popcount(d)`` vectorised additions, all in
    float32 without the cancellation of a running sum.  A window reaching
    past the array on both sides is clipped first, so a huge box costs no
    more than one of about ``2 N``.  The columns (axis 1) are processed in
    blocks that fit in the cache.

    Parameters
    ----------
    x : (N, ...) float32 ndarray
        Any strides.
    boxes : sequence of (int d >= 1, int left)

    Returns
    -------
    (N, ...) float32 ndarray, C-contiguous
        The sums divided by the product of the ``d``.
    """
    if x.ndim == 1:
        return _box_passes(x[:, None], boxes)[:, 0]
    n, m, inner = x.shape[0], x.shape[1], int(np.prod(x.shape[2:], dtype=np.int64))
    # window of output i: x[i + s : i + e], clipped so that |s|, |e| <= n
    spans = [(max(-left, -n), min(d - left, n)) for d, left in boxes]
    width = max(e - s for s, e in spans)
    out = np.zeros(x.shape, np.float32)
    if width <= 0 or x.size == 0 or any(e <= s for s, e in spans):
        return out
    length = n + width - 1
    cm = max(1, min(m, _BLOCK_BYTES // (4 * length * inner)))
    flat = [np.empty(length * cm * inner, np.float32) for _ in range(2)]
    flat_out = np.empty(n * cm * inner, np.float32)
    scale = 1.0
    for d, _ in boxes:
        scale /= d
    for c0 in range(0, m, cm):           # loop over cache-sized blocks of columns
        xb = x[:, c0:c0 + cm]
        shape = xb.shape[1:]
        size = int(np.prod(shape, dtype=np.int64))
        bufs = [f[:length * size].reshape((length,) + shape) for f in flat]
        ob = flat_out[:n * size].reshape((n,) + shape)
        _box_block(xb, spans, bufs, ob)
        if scale != 1.0:
            ob *= np.float32(scale)
        out[:, c0:c0 + cm] = ob
    return out


def _box_block(x, spans, bufs, out):
    """The window sums of :func:`_box_passes` (unscaled) of one block
    ``x`` (N, ...) into ``out`` (N, ...), with two work buffers ``bufs`` of
    at least ``N + max width - 1`` rows; ``spans`` are the clipped windows
    ``(s, e)``: ``y[i] = sum(x[i + s : i + e])``."""
    n = x.shape[0]
    src = x
    for s, e in spans:
        w = e - s
        # p[m] = src[m + s] inside the array, 0 outside
        p = bufs[0][:n + w - 1]
        j0, j1 = max(s, 0), min(n, n + e - 1)
        p[:j0 - s] = 0.0
        p[j0 - s:j1 - s] = src[j0:j1]
        p[j1 - s:] = 0.0
        # cur[m] = sum(p[m : m + size]) lives in bufs[which]
        cur, which, size, off, first, k = p, 0, 1, 0, True, w
        while True:                      # loop over the bits of w
            if k & 1:
                if first:
                    np.copyto(out, cur[off:off + n])
                    first = False
                else:
                    np.add(out, cur[off:off + n], out=out)
                off += size
            k >>= 1
            if not k:
                break
            m = cur.shape[0] - size
            nxt = bufs[1 - which][:m]
            np.add(cur[:m], cur[size:size + m], out=nxt)
            cur, which, size = nxt, 1 - which, size * 2
        src = out                        # copied into p before out is rewritten


def _box_axis(a, d, left, axis):
    """One box mean of width ``d`` along ``axis``: ``out[i] = sum(a[i-left :
    i-left+d]) / d`` with zeros outside the array (float32, the shape of
    ``a``)."""
    out = _box_passes(np.moveaxis(np.asarray(a, np.float32), axis, 0), ((d, left),))
    return np.moveaxis(out, 0, axis)


def _box_size(s):
    return int(math.floor(s * 3.0 * math.sqrt(2.0 * math.pi) / 4.0 + 0.5))


def _box_list(d):
    """The three ``(width, left)`` box passes of the specification for a
    box size ``d`` (none when ``d <= 1``): three centred boxes of an odd
    ``d``; for an even ``d`` two of ``d`` (centred on the pixel's right and
    left edge) and one of ``d + 1``."""
    if d <= 1:
        return ()
    if d % 2:
        return ((d, (d - 1) // 2),) * 3
    return ((d, d // 2), (d, d // 2 - 1), (d + 1, d // 2))


def box_sigma(sigma):
    """Effective standard deviation (px) of the three box blurs
    :func:`box_blur` uses for ``sigma`` (the boxes' variances add up).

    >>> round(box_sigma(10.0), 3)          # three boxes of 19 px
    9.487
    """
    d = _box_size(sigma)
    if d <= 1:
        return 0.0
    if d % 2:
        return math.sqrt(3 * (d * d - 1) / 12.0)
    return math.sqrt((2 * (d * d - 1) + (d + 1) ** 2 - 1) / 12.0)


def _gauss_axis(a, s, axis):
    """Blur along ``axis`` with a Gaussian kernel of deviation ``s`` px
    truncated at ``ceil(4 s)`` and renormalised (zeros outside)."""
    r = max(1, int(math.ceil(4.0 * s)))
    x = np.arange(-r, r + 1, dtype=np.float64)
    k = np.exp(-0.5 * (x / s) ** 2)
    k /= k.sum()
    a = np.moveaxis(a, axis, 0)
    n = a.shape[0]
    pad = np.zeros((n + 2 * r,) + a.shape[1:], np.float32)
    pad[r:r + n] = a
    out = np.zeros(pad[:n].shape, np.float32)
    tmp = np.empty_like(out)
    for j, w in enumerate(k):            # loop over kernel taps, not pixels
        np.multiply(pad[j:j + n], np.float32(w), out=tmp)
        out += tmp
    return np.moveaxis(out, 0, axis)


def _reach(plan):
    """``(before, after)``: how far (px) a blur plan of one axis spreads a
    pixel towards lower and higher indices."""
    if plan is None:
        return 0, 0
    kind, arg = plan
    if kind == 'gauss':
        r = max(1, int(math.ceil(4.0 * arg)))
        return r, r
    # output i reads inputs i - left .. i - left + d - 1
    return sum(d - 1 - left for d, left in arg), sum(left for d, left in arg)


def _blur_array(x, plan_x, plan_y):
    """Separable blur of ``x`` (H, W) or (H, W, C) float32, zero outside,
    one plan per axis.

    A plan is None (axis untouched), ``('box', boxes)`` (successive box
    means, see :func:`_box_passes`) or ``('gauss', sigma)``.  The work is
    restricted to the bounding box of the non-zero pixels grown by the
    blur's reach: outside it the result is exactly 0.

    Returns
    -------
    float32 ndarray, the shape of ``x``
    """
    if plan_x is None and plan_y is None:
        return x
    h, w = x.shape[:2]
    box = _nonzero_box(x)
    if box is None:
        return np.zeros(x.shape, np.float32)
    (bx, ax), (by, ay) = _reach(plan_x), _reach(plan_y)
    y0, y1 = max(box[0] - by, 0), min(box[1] + ay, h)
    x0, x1 = max(box[2] - bx, 0), min(box[3] + ax, w)
    work = x[y0:y1, x0:x1]
    for axis, plan in ((1, plan_x), (0, plan_y)):
        if plan is None:
            continue
        if plan[0] == 'gauss':
            work = _gauss_axis(work, plan[1], axis)
        else:
            work = np.moveaxis(_box_passes(np.moveaxis(work, axis, 0), plan[1]), 0, axis)
    if (y0, y1, x0, x1) == (0, h, 0, w):
        return np.ascontiguousarray(work)
    out = np.zeros(x.shape, np.float32)
    out[y0:y1, x0:x1] = work
    return out


def _blur(img, plan_x, plan_y):
    """:func:`_blur_array` of an :class:`_Image` (a solid-colour image
    blurs its alpha channel only: blurs are linear)."""
    if img.solid:
        return _Image(alpha=_blur_array(img.alpha, plan_x, plan_y), colour=img.colour)
    return _Image(_blur_array(img.data, plan_x, plan_y))


def _blur_plans(sigma_x, sigma_y, tolerance):
    """Per-axis plans (see :func:`_blur_array`) of :func:`gaussian_blur`."""
    plans = []
    for s in (sigma_x, sigma_y):
        plan = None
        if s > 0:
            boxes = _box_list(_box_size(s))
            if s >= 2.0 and (tolerance is None or abs(box_sigma(s) - s) <= tolerance):
                plan = ('box', boxes) if boxes else None
            else:
                plan = ('gauss', float(s))
        plans.append(plan)
    return plans


def box_blur(img, sigma_x, sigma_y):
    """Three successive box blurs approximating a Gaussian of standard
    deviations ``sigma_x``, ``sigma_y`` device pixels (the box sizes of the
    Filter Effects specification: ``d = floor(s * 3 sqrt(2 pi) / 4 + 0.5)``).
    Pixels outside the image are transparent.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA
    sigma_x, sigma_y : float >= 0

    Returns
    -------
    (H, W, 4) float32 ndarray
    """
    out = _check(img)
    _finite(sigma_x, sigma_y)
    boxes = [_box_list(_box_size(s)) for s in (sigma_x, sigma_y)]
    plans = [('box', b) if b else None for b in boxes]
    if plans == [None, None]:
        return out
    return _blur(_Image.of(out), *plans).data


def _tolerance(tolerance):
    """Validate a blur tolerance (None or a positive finite number)."""
    if tolerance is not None:
        _finite(tolerance)
        if not tolerance > 0:
            raise FilterError('tolerance must be positive, got %r' % (tolerance,))
    return tolerance


def gaussian_blur(img, sigma_x, sigma_y=None, tolerance=None):
    """Gaussian blur with standard deviations in device pixels.

    A deviation of at least 2 px may use the specification's three box
    blurs (what resvg does); their effective standard deviation
    (:func:`box_sigma`) is about 6 % below ``sigma``.  Otherwise a separable
    kernel truncated at 4 sigma (renormalised) is used.  Zero or negative
    deviations leave that axis unblurred.  Only the bounding box of the
    non-transparent pixels (grown by the blur's reach) is worked on, and an
    image of one colour blurs its alpha channel only.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA
    sigma_x, sigma_y : float (sigma_y defaults to sigma_x)
    tolerance : float > 0 or None
        None (default, the renderer's choice): boxes for every sigma >= 2,
        as the specification and resvg.  A number of device pixels: boxes
        only where their effective standard deviation is within it of
        ``sigma``, the exact kernel elsewhere.

    Returns
    -------
    (H, W, 4) float32 ndarray

    >>> img = np.zeros((9, 9, 4), np.float32); img[4, 4] = 1
    >>> out = gaussian_blur(img, 1.0)
    >>> round(float(out[..., 3].sum()), 3), bool(out[4, 4, 3] < 0.2)
    (1.0, True)
    """
    out = _check(img)
    sigma_y = sigma_x if sigma_y is None else sigma_y
    _finite(sigma_x, sigma_y)
    plans = _blur_plans(sigma_x, sigma_y, _tolerance(tolerance))
    if plans == [None, None]:
        return out
    return _blur(_Image.of(out), *plans).data


def _shift(x, dx, dy):
    """``x`` (H, W, ...) moved by whole pixels ``dx`` (columns), ``dy``
    (rows); what moves in is 0."""
    h, w = x.shape[:2]
    out = np.zeros(x.shape, np.float32)
    if abs(dx) >= w or abs(dy) >= h:
        return out
    out[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)] = \
        x[max(-dy, 0):h + min(-dy, 0), max(-dx, 0):w + min(-dx, 0)]
    return out


def offset(img, dx, dy):
    """Shift an image by ``(dx, dy)`` device pixels (rounded to whole
    pixels); what moves in from outside is transparent.

    >>> img = np.zeros((3, 3, 4), np.float32); img[0, 0] = 1
    >>> offset(img, 1, 2)[2, 1].tolist()
    [1.0, 1.0, 1.0, 1.0]
    """
    src = _check(img)
    _finite(dx, dy)
    return _shift(src, int(round(dx)), int(round(dy)))


def composite(a, b, operator='over', k=(0.0, 0.0, 0.0, 0.0)):
    """Porter-Duff compositing of premultiplied ``a`` (``in``) over ``b``
    (``in2``), as feComposite.

    Parameters
    ----------
    a, b : (H, W, 4) float32 ndarrays, premultiplied RGBA
    operator : {'over', 'in', 'out', 'atop', 'xor', 'arithmetic'}
    k : 4 floats
        ``k1..k4`` of ``arithmetic``: ``k1 a b + k2 a + k3 b + k4`` per
        premultiplied channel, clamped to [0, 1] and colour <= alpha.

    >>> a = np.full((1, 1, 4), 0.5, np.float32); b = np.full((1, 1, 4), 1.0, np.float32)
    >>> composite(a, b, 'in')[0, 0].tolist(), composite(a, b, 'xor')[0, 0].tolist()
    ([0.5, 0.5, 0.5, 0.5], [0.5, 0.5, 0.5, 0.5])
    """
    a, b = _check(a, 'in'), _check(b, 'in2')
    if a.shape != b.shape:
        raise FilterError('composite inputs differ in shape: %r, %r' % (a.shape, b.shape))
    aa, ba = a[..., 3:4], b[..., 3:4]
    if operator == 'over':
        out = a + b * (1 - aa)
    elif operator == 'in':
        out = a * ba
    elif operator == 'out':
        out = a * (1 - ba)
    elif operator == 'atop':
        out = a * ba + b * (1 - aa)
    elif operator == 'xor':
        out = a * (1 - ba) + b * (1 - aa)
    elif operator == 'arithmetic':
        k1, k2, k3, k4 = (float(v) for v in k)
        _finite(k1, k2, k3, k4)
        out = np.clip(k1 * a * b + k2 * a + k3 * b + k4, 0.0, 1.0)
        out[..., :3] = np.minimum(out[..., :3], out[..., 3:4])
    else:
        raise FilterError('unknown composite operator %r' % (operator,))
    return np.clip(out, 0.0, 1.0).astype(np.float32)


def blend(a, b, mode='normal'):
    """feBlend: premultiplied ``a`` (``in``, source) blended onto ``b``
    (``in2``, backdrop) with a CSS blend mode (unknown modes: normal)."""
    from .render import _NON_SEPARABLE, _SEPARABLE
    a, b = _check(a, 'in'), _check(b, 'in2')
    fn = _SEPARABLE.get(mode) or _NON_SEPARABLE.get(mode)
    if fn is None:
        return composite(a, b, 'over')
    s, d = a.astype(np.float64), b.astype(np.float64)
    sa, da = s[..., 3:4], d[..., 3:4]
    with np.errstate(divide='ignore', invalid='ignore'):
        sc = np.where(sa > 0, s[..., :3] / np.maximum(sa, 1e-12), 0.0)
        dc = np.where(da > 0, d[..., :3] / np.maximum(da, 1e-12), 0.0)
    mix = np.clip(fn(dc, sc), 0, 1)
    out = np.empty_like(s)
    out[..., :3] = s[..., :3] * (1 - da) + d[..., :3] * (1 - sa) + sa * da * mix
    out[..., 3:4] = sa + da - sa * da
    return np.clip(out, 0, 1).astype(np.float32)


def color_matrix(img, matrix):
    """Apply a (4, 5) colour matrix to unpremultiplied RGBA (feColorMatrix):
    ``[R' G' B' A'] = M [R G B A 1]``, clamped to [0, 1].

    >>> img = np.full((1, 1, 4), 0.5, np.float32)
    >>> ident = np.hstack([np.eye(4), np.zeros((4, 1))])
    >>> color_matrix(img, ident)[0, 0].tolist()
    [0.5, 0.5, 0.5, 0.5]
    """
    src = _check(img)
    m = np.asarray(matrix, np.float64)
    if m.shape != (4, 5) or not np.isfinite(m).all():
        raise FilterError('colour matrix must be a finite (4, 5) array')

    def block(b):
        c, a = _unpremul(b)
        x = np.concatenate([c, a], -1).astype(np.float64)
        y = np.clip(x @ m[:, :4].T + m[:, 4], 0.0, 1.0).astype(np.float32)
        return _premul(y[..., :3], y[..., 3:4])

    return _by_rows(block, src)


def _transfer(v, fn):
    if fn is None:
        return v
    kind, p = fn
    if kind == 'table':
        t = np.asarray(p, np.float64)
        n = len(t) - 1
        if n == 0:
            return np.full_like(v, t[0])
        k = np.minimum(np.floor(v * n).astype(np.int64), n - 1)
        return t[k] + (v * n - k) * (t[k + 1] - t[k])
    if kind == 'discrete':
        t = np.asarray(p, np.float64)
        n = len(t)
        k = np.clip(np.floor(v * n).astype(np.int64), 0, n - 1)
        return t[k]
    if kind == 'linear':
        return p[0] * v + p[1]
    if kind == 'gamma':
        return p[0] * np.power(v, p[1]) + p[2]
    return v


def component_transfer(img, funcs):
    """feComponentTransfer on unpremultiplied values.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied
    funcs : dict channel index (0..3) -> (kind, params) or None
        ``('table', values)``, ``('discrete', values)``,
        ``('linear', (slope, intercept))``,
        ``('gamma', (amplitude, exponent, offset))``; missing: identity.
    """
    src = _check(img)

    def block(b):
        c, a = _unpremul(b)
        x = np.concatenate([c, a], -1).astype(np.float64)
        for ch, fn in funcs.items():
            x[..., ch] = _transfer(x[..., ch], fn)
        x = np.clip(x, 0.0, 1.0).astype(np.float32)
        return _premul(x[..., :3], x[..., 3:4])

    return _by_rows(block, src)


def _minmax_axis(a, r, axis, fn):
    a = np.moveaxis(a, axis, 0)
    n = a.shape[0]
    r = min(r, n)
    fill = 0.0
    pad = np.full((n + 2 * r,) + a.shape[1:], fill, np.float32)
    pad[r:r + n] = a
    out = pad[0:n].copy()
    for j in range(1, 2 * r + 1):       # loop over window offsets
        fn(out, pad[j:j + n], out=out)
    return np.moveaxis(out, 0, axis)


def morphology(img, rx, ry, operator='erode'):
    """feMorphology: per-channel minimum (erode) or maximum (dilate) over a
    ``(2 rx + 1) x (2 ry + 1)`` window (radii in whole device pixels);
    outside the image is transparent."""
    src = _check(img)
    _finite(rx, ry)
    fn = np.minimum if operator == 'erode' else np.maximum
    out = src
    h, w = src.shape[:2]
    rx, ry = int(round(rx)), int(round(ry))
    if rx > 0:
        out = _minmax_axis(out, min(rx, w), 1, fn)
    if ry > 0:
        out = _minmax_axis(out, min(ry, h), 0, fn)
    return out


def _tile(img, rect, target):
    """Tile the ``rect`` (x0, y0, x1, y1) part of ``img`` over ``target``."""
    x0, y0, x1, y1 = rect
    out = np.zeros_like(img)
    if x1 <= x0 or y1 <= y0:
        return out
    tx0, ty0, tx1, ty1 = target
    jj = x0 + (np.arange(tx0, tx1) - x0) % (x1 - x0)
    ii = y0 + (np.arange(ty0, ty1) - y0) % (y1 - y0)
    out[ty0:ty1, tx0:tx1] = img[ii[:, None], jj[None, :]]
    return out


# ---------------------------------------------------------------------------
# Applying filters to a layer
# ---------------------------------------------------------------------------

def _device_box(rect, t):
    if rect is None:                     # a filter function: no region
        return (-_UNBOUNDED, -_UNBOUNDED, _UNBOUNDED, _UNBOUNDED)
    x, y, w, h = rect
    pts = t.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]], np.float64))
    lo, hi = pts.min(0), pts.max(0)
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


_UNBOUNDED = 1e9


def filter_box(filters, t):
    """Device box ``(x0, y0, x1, y1)`` covering the regions of ``filters``
    under the CTM ``t`` (user space to device pixels), or None."""
    box = None
    for f in filters:
        b = _device_box(f.region, t)
        box = b if box is None else (min(box[0], b[0]), min(box[1], b[1]),
                                     max(box[2], b[2]), max(box[3], b[3]))
    return box


def filter_pixel_box(box, width, height):
    """Integer pixel box ``(x0, y0, x1, y1)`` of a filter layer for the
    device box ``box`` on a ``width x height`` target, or None if empty.

    The box is rounded outwards and may reach past the target by up to the
    target's size on each side, so that content just outside the canvas
    still feeds offsets and blurs (as resvg); pixel counts stay bounded.

    >>> filter_pixel_box((-20.5, 3.2, 10.1, 8.0), 100, 50)
    (-21, 3, 11, 8)
    """
    if box is None or not all(math.isfinite(v) for v in box):
        return None
    x0 = max(int(math.floor(box[0] + 1e-6)), -width)
    y0 = max(int(math.floor(box[1] + 1e-6)), -height)
    x1 = min(int(math.ceil(box[2] - 1e-6)), 2 * width)
    y1 = min(int(math.ceil(box[3] - 1e-6)), 2 * height)
    if x1 <= max(x0, 0) or y1 <= max(y0, 0) or x0 >= width or y0 >= height:
        return None
    return x0, y0, x1, y1


def _pixel_rect(box, w, h):
    x0, y0, x1, y1 = box
    if not all(math.isfinite(v) for v in box):
        return 0, 0, 0, 0
    px0 = min(max(int(math.floor(x0 + 1e-6)), 0), w)
    py0 = min(max(int(math.floor(y0 + 1e-6)), 0), h)
    px1 = min(max(int(math.ceil(x1 - 1e-6)), px0), w)
    py1 = min(max(int(math.ceil(y1 - 1e-6)), py0), h)
    return px0, py0, px1, py1


def apply_filters(filters, data, t, tolerance=None, draw=None):
    """Apply a list of filters to a rendered layer.

    Parameters
    ----------
    filters : list of Filter
    data : (H, W, 4) float32 ndarray
        Premultiplied sRGB layer holding the element's rendering.
    t : raster.transform.Affine
        The element's user space to layer pixels.
    tolerance : float or None
        Passed to :func:`gaussian_blur` (None: the specification's box
        blurs, as resvg).

    draw : callable or None
        ``draw(nodes, m, w, h)`` renders tree nodes with the CTM ``m`` into
        a new ``(h, w, 4)`` premultiplied array (for ``feImage``; without it
        feImage is transparent).

    Returns
    -------
    (H, W, 4) float32 ndarray
        The filtered layer (transparent outside the filter regions).
    """
    out = _check(data, 'layer')
    for f in filters:
        out = _apply_one(f, out, t, tolerance, draw)
    return out


def _apply_one(f, data, t, tol, draw=None):
    h, w = data.shape[:2]
    rx0, ry0, rx1, ry1 = _pixel_rect(_device_box(f.region, t), w, h)
    if rx1 <= rx0 or ry1 <= ry0:
        return np.zeros_like(data)
    rt = Affine.translate(-rx0, -ry0) @ t
    rw, rh = rx1 - rx0, ry1 - ry0
    src = np.ascontiguousarray(data[ry0:ry1, rx0:rx1])
    full = (0, 0, rw, rh)
    # resvg's scale of a transform: the lengths of the matrix rows
    sx = math.hypot(t.a, t.c)
    sy = math.hypot(t.b, t.d)
    sources = {}                      # SourceGraphic / SourceAlpha, made on first use

    def source(name):
        if name not in sources:
            img = _Image.of(src) if name == 'SourceGraphic' else \
                _Image(alpha=src[..., 3], colour=np.zeros(3, np.float32))
            sources[name] = (img, False, full)
        return sources[name]

    named = {}
    prev = None                       # (_Image, linear, rect)
    for p in f.primitives:
        def get(name):
            if name in ('SourceGraphic', 'SourceAlpha'):
                return source(name)
            if name in named:
                return named[name]
            if prev is not None:
                return prev
            return source('SourceGraphic')

        ins = [get(n) for n in p.inputs]
        if f.region is None:
            sub = full
        else:
            urect = tuple(b if v is None else v for v, b in zip(p.subregion, f.region))
            sub = _pixel_rect(_device_box(urect, rt), rw, rh)
        lin = p.linear
        imgs = [_convert(i[0], i[1], lin) for i in ins]
        img = _run(p, imgs, ins, sx, sy, rt, tol, sub, lin, src.shape, draw)
        out_lin = lin
        if img is None:
            img = _Image(alpha=np.zeros((rh, rw), np.float32), colour=np.zeros(3, np.float32))
        elif isinstance(img, tuple):
            img, out_lin = img
        if isinstance(img, np.ndarray):
            img = _Image(img)
        # an feOffset result keeps its input's area for feTile (resvg)
        area = ins[0][2] if p.kind == 'feOffset' and ins and all(
            ins[0][0] is not v[0] for v in sources.values()) else sub
        prev = (img.clip(sub), out_lin, area)
        if p.result:
            named[p.result] = prev
    img = _convert(prev[0], prev[1], False).data
    if (rx0, ry0, rx1, ry1) == (0, 0, w, h):
        return img.copy() if np.may_share_memory(img, data) else img
    result = np.zeros_like(data)
    result[ry0:ry1, rx0:rx1] = img
    return result


def _run(p, imgs, ins, sx, sy, t, tol, sub, lin, shape, draw=None):
    """The result of one primitive on :class:`_Image` inputs ``imgs`` (in
    the primitive's colour space): an image (array or :class:`_Image`) in
    that space, ``(image, linear)`` for another space, or None
    (transparent)."""
    k, pr = p.kind, p.params
    if k == 'feGaussianBlur':
        s_x, s_y = pr['std'][0] * sx, pr['std'][1] * sy
        if s_x < 0 or s_y < 0 or (s_x == 0 and s_y == 0):
            return imgs[0]                      # disabled: the input (resvg)
        return _blur(imgs[0], *_blur_plans(s_x, s_y, _tolerance(tol)))
    if k == 'feOffset':
        dx, dy = pr['dx'] * sx, pr['dy'] * sy
        _finite(dx, dy)
        dx, dy = int(round(dx)), int(round(dy))
        if imgs[0].solid:
            return _Image(alpha=_shift(imgs[0].alpha, dx, dy), colour=imgs[0].colour)
        return _shift(imgs[0].data, dx, dy)
    if k in ('feDiffuseLighting', 'feSpecularLighting'):
        if pr['light'] is None or (k == 'feSpecularLighting' and not 1 <= pr['exp'] <= 128):
            return None
        col = np.asarray(pr['color'], np.float32)
        if lin:
            col = srgb_to_linear(col)
        return lighting(imgs[0].alpha_channel, pr['light'], col, pr['surface'], pr['k'], pr['exp'],
                        k == 'feSpecularLighting', t)
    if k == 'feDisplacementMap':
        return displace(imgs[0].data, imgs[1].data, pr['scale'] * (sx + sy) / 2.0, *pr['channels'])
    if k == 'feTurbulence':
        if pr['turb'] is None:
            return None
        try:
            inv = t.inverse()
        except RasterError:
            return None
        jj, ii = np.meshgrid(np.arange(shape[1], dtype=np.float64),
                             np.arange(shape[0], dtype=np.float64))
        pts = inv.apply(np.stack([jj, ii], -1))
        bf, octaves, seed, fractal = pr['turb']
        col = turbulence(pts[..., 0], pts[..., 1], bf, octaves, seed, fractal)
        return _premul(col[..., :3], col[..., 3:4])
    if k == 'feConvolveMatrix':
        if pr['conv'] is None:
            return None
        kern, div, bias, target, edge, keep = pr['conv']
        return convolve(imgs[0].data, kern, div, bias, target, edge, keep)
    if k == 'feImage':
        if not pr.get('nodes') or draw is None:
            return None
        img = draw(pr['nodes'], t @ Affine.translate(*pr['shift']), shape[1], shape[0])
        return _check(img, 'feImage content'), False
    if k == 'feFlood':
        c = pr['color']
        return _Image(alpha=np.full(shape[:2], c[3], np.float32),
                      colour=np.asarray(c[:3], np.float32)), False
    if k == 'feMerge':
        if not imgs:
            return None
        out = np.zeros_like(imgs[0].data)
        for im in imgs:
            out = im.data + out * (1 - im.data[..., 3:4])
        return out
    if k == 'feComposite':
        return composite(imgs[0].data, imgs[1].data, pr['operator'], pr['k'])
    if k == 'feBlend':
        return blend(imgs[0].data, imgs[1].data, pr['mode'])
    if k == 'feColorMatrix':
        return color_matrix(imgs[0].data, pr['matrix'])
    if k == 'feComponentTransfer':
        return component_transfer(imgs[0].data, pr['funcs'])
    if k == 'feMorphology':
        r_x, r_y = pr['radius'][0] * sx, pr['radius'][1] * sy
        if r_x < 0 or r_y < 0 or (r_x == 0 and r_y == 0):
            return imgs[0]                      # disabled: the input (resvg)
        return morphology(imgs[0].data, r_x, r_y, pr['operator'])
    if k == 'feTile':
        return _tile(imgs[0].data, ins[0][2], sub)
    if k == 'feDropShadow':
        src = imgs[0].data
        s_x, s_y = pr['std'][0] * sx, pr['std'][1] * sy
        a = src[..., 3]
        if s_x > 0 or s_y > 0:
            a = _blur_array(a, *_blur_plans(max(s_x, 0.0), max(s_y, 0.0), _tolerance(tol)))
        dx, dy = pr['dx'] * sx, pr['dy'] * sy
        _finite(dx, dy)
        a = _shift(a, int(round(dx)), int(round(dy)))
        c = pr['color']
        col = np.array(c[:3], np.float32)
        if lin:
            col = srgb_to_linear(col)
        shadow = _solid_image(a * np.float32(c[3]), col)
        return composite(src, shadow, 'over')
    return None


def group_filters(g):
    """The filters of a tree Group (its ``filters`` list), or None."""
    return g.filters or None


