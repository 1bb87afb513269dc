"""Resolve an SVG document (an lxml tree) into the render tree of
:mod:`raster.svg.tree`.

Everything the renderer needs is decided here, so the renderer never parses
a string:

* the CSS cascade (:func:`raster.svg.css.declared_styles`) followed by
  inheritance along the *rendering* parent chain: content instantiated by
  ``use`` inherits from the ``use`` element, not from its place in ``defs``;
  ``inherit`` takes the parent's computed value; ``currentColor`` resolves
  to the element's computed ``color``;
* lengths in user units (``em``/``ex`` from the computed font size, ``%`` of
  the nearest viewport: root ``svg``, nested ``svg`` or ``symbol``
  instance), transforms with ``transform-origin``, viewBoxes with
  ``preserveAspectRatio``;
* basic shapes and path data to :class:`~raster.path.Path` (SVG's
  prefix-on-error rule for path data);
* structure: ``g``, ``a``, nested ``svg`` (clipped to its viewport unless
  ``overflow`` is ``visible``/``auto``), ``use`` (with cycle detection and
  limits), ``symbol``, ``switch`` with ``systemLanguage``/
  ``requiredExtensions``, ``display`` and ``visibility``.

Coordinates: user units, x right, y down.  The tree's root group maps the
root element's user space to document pixels (the natural size).

Paint servers and effects: linear and radial gradients (``href``
inheritance with cycle detection, stop offsets clamped and made monotonic,
``stop-color``/``stop-opacity`` with ``currentColor``, ``transform-origin``),
patterns, clip paths and masks (user space or object bounding box units,
nested references; a recursive reference is ignored, as resvg does),
``context-fill``/``context-stroke`` in ``use`` content.  Markers are built
by :mod:`raster.svg.markers` and images by :mod:`raster.svg.image`, both
called from here.

Speed: path data of ``path`` elements without arcs is parsed for the
whole document in one vectorized pass (:func:`raster.svgpath.parse_paths`),
and parsed paths are shared by every element with the same ``d`` (paths are
immutable), as are basic shapes with the same attributes; transform lists,
colours, paints and opacities are parsed once per distinct string; computed
styles are shared by siblings with the same declarations, and what a style
says about painting (paints, stroke parameters, paint order) is worked out
once per computed style; the CTM's scale and arc tolerance, needed only for
arcs, are memoized per subtree; the cyclic garbage collector is paused
while the tree is built.

Not supported yet, each reported once per build with a
:class:`raster.errors.RasterWarning` (through :func:`warnings.warn`) and then
left out rather than drawn wrongly: text; references to
other documents.

>>> from raster.svg.document import load_document
>>> root = load_document(b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10">'
...                      b'<rect width="5" height="5" fill="red"/></svg>')
>>> tree = build_tree(root)
>>> tree.width, tree.height, tree.root.children[0].fill.paint.color
(20.0, 10.0, (1.0, 0.0, 0.0, 1.0))
"""

import contextlib
import dataclasses
import gc
import math
import types
import warnings

from .. import limits
from ..errors import RasterError, RasterWarning, SVGError, TransformError
from ..geometry.bounds import bbox as exact_bbox
from ..geometry.pathdata import (circle_path, ellipse_path, line_path, parse_path, parse_paths,
                                 polyline_path, rect_path)
from ..geometry.stroking import LineCap, LineJoin
from ..geometry.transform import IDENTITY, Affine
from .css import declared_styles
from .document import chain_attr
from .properties import INHERITED, PROPERTIES
from .tree import (ClipPath, Fill, GradientStop, Group, LinearGradient, Mask, PathNode,
                   Pattern, RadialGradient, SolidPaint, Stroke, Tree, walk)
from .values import (CURRENT_COLOR, LengthContext, parse_color, parse_length, parse_number,
                     parse_url,
                     parse_length_list, parse_paint, parse_preserve_aspect_ratio,
                     parse_transform, parse_transform_origin, parse_viewbox, viewbox_transform)

__all__ = ['build_tree']

SVG_NS = 'http://www.w3.org/2000/svg'
XLINK_HREF = '{http://www.w3.org/1999/xlink}href'
_P = '{%s}' % SVG_NS
_PLEN = len(_P)

_SHAPES = frozenset(['rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon', 'path'])
_CONTAINERS = frozenset(['g', 'a', 'svg', 'switch', 'use'])
# elements a <switch> may choose
_SWITCH_CHOICES = _SHAPES | _CONTAINERS | frozenset(['text', 'image', 'foreignObject'])
# never rendered directly
_NOT_RENDERED = frozenset(['defs', 'symbol', 'title', 'desc', 'metadata', 'style', 'script',
                           'linearGradient', 'radialGradient', 'pattern', 'clipPath', 'mask',
                           'marker', 'filter', 'stop', 'font', 'font-face', 'glyph',
                           'missing-glyph', 'cursor', 'view', 'animate', 'set',
                           'animateMotion', 'animateTransform', 'animateColor'])
_PAINT_SERVERS = frozenset(['linearGradient', 'radialGradient', 'pattern'])
# the attributes that define each basic shape
_GEOMETRY_ATTRS = {'rect': ('x', 'y', 'width', 'height', 'rx', 'ry'), 'circle': ('cx', 'cy', 'r'),
                   'ellipse': ('cx', 'cy', 'rx', 'ry'), 'line': ('x1', 'y1', 'x2', 'y2'),
                   'polyline': ('points',), 'polygon': ('points',)}

_FONT_KEYWORDS = {'xx-small': 3 / 5, 'x-small': 3 / 4, 'small': 8 / 9, 'medium': 1.0,
                  'large': 6 / 5, 'x-large': 3 / 2, 'xx-large': 2.0, 'xxx-large': 3.0}
_BLEND = frozenset(['normal', 'multiply', 'screen', 'overlay', 'darken', 'lighten',
                    'color-dodge', 'color-burn', 'hard-light', 'soft-light', 'difference',
                    'exclusion', 'hue', 'saturation', 'color', 'luminosity'])
_BLACK = (0.0, 0.0, 0.0, 1.0)
_EMPTY = object()         # a clip path or mask that leaves nothing visible
_UNSUPPORTED = object()   # a paint server that cannot paint (no stops, empty box): fallback
_ARC_SAFETY = 0.1   # arcs are made 10x finer than `tolerance` so zooming in stays smooth


@dataclasses.dataclass(frozen=True, slots=True)
class _Effects:
    """What an element does to its content as a group: opacity, blend mode,
    isolation, clip path, mask and filters; ``ok`` False: not rendered."""
    opacity: float = 1.0
    blend: str = 'normal'
    isolate: bool = False
    clip: object = None
    mask: object = None
    filters: tuple = ()
    ok: bool = True
    #: Needs a layer for something other than opacity (derived).
    composited: bool = dataclasses.field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, 'composited', (
            self.clip is not None or self.mask is not None or self.blend != 'normal'
            or self.isolate or bool(self.filters)))

    @property
    def trivial(self):
        """Changes nothing: no Group is needed (but for a transform or id)."""
        return self.opacity >= 1.0 and not self.composited

    def group(self, id, transform, children):
        return Group(id=id, transform=transform, opacity=self.opacity, clip_path=self.clip,
                     mask=self.mask, filters=list(self.filters), blend_mode=self.blend,
                     isolate=self.isolate, children=children)


_NO_EFFECTS = _Effects()
# properties that make _Effects more than an opacity
_EFFECT_PROPS = frozenset(['clip-path', 'mask', 'filter', 'mix-blend-mode', 'isolation'])
_NO_OWN = types.MappingProxyType({})    # the own style of an element without declarations
_EFFECTS_NOT_DRAWN = _Effects(ok=False)


def _local(el):
    """Local name of an SVG-namespace element, else None."""
    tag = el.tag
    if isinstance(tag, str) and tag.startswith(_P):
        return tag[_PLEN:]
    return None


def _number_or_percent(s):
    """A number or a percentage (as a fraction), or None."""
    s = s.strip()
    if s.endswith('%'):
        v = parse_number(s[:-1])
        return None if v is None else v / 100.0
    return parse_number(s)


_OPACITY_CACHE = {}


def _opacity(s, default=1.0):
    if s is None:
        return default
    v = _OPACITY_CACHE.get(s)
    if v is None:
        v = _number_or_percent(s)
        v = False if v is None else min(max(v, 0.0), 1.0)
        if len(_OPACITY_CACHE) < 4096:
            _OPACITY_CACHE[s] = v
    return default if v is False else v


class _State:
    """Per-subtree context: viewport size for percentages, the CTM at the
    document's natural size (for arc tolerances and overflow checks), the
    active ``use`` depth.  The CTM's scale is memoized."""
    __slots__ = ('vw', 'vh', 'ctm', '_scale', '_arc_tol', 'use_depth', 'mode', 'context')

    def __init__(self, vw, vh, ctm, use_depth=0, mode=None, context=None):
        self.vw, self.vh, self.ctm, self.use_depth = vw, vh, ctm, use_depth
        self._scale = None
        self._arc_tol = None    # the builder's arc tolerance at this CTM (memo)
        self.mode = mode        # None, or 'clip' inside a clipPath
        self.context = context  # (fill paint, stroke paint) for context-fill/-stroke

    def scale(self):
        """Largest singular value of the CTM (memoized)."""
        s = self._scale
        if s is None:
            s = self._scale = self.ctm.max_scale()
        return s

    def check(self, t):
        """Raise :class:`~raster.errors.TransformError` when ``ctm @ t``
        overflows (no Affine is built for a translation)."""
        if t.is_translation:
            m = self.ctm
            e = m.a * t.e + m.c * t.f + m.e
            f = m.b * t.e + m.d * t.f + m.f
            if not (math.isfinite(e) and math.isfinite(f)):
                raise TransformError('transform overflows')
        else:
            self.ctm @ t

    def sub(self, transform=None, vw=None, vh=None, use_depth=None, context=False):
        same = transform is None or transform.is_identity
        st = _State(self.vw if vw is None else vw, self.vh if vh is None else vh,
                    self.ctm if same else self.ctm @ transform,
                    self.use_depth if use_depth is None else use_depth, self.mode,
                    self.context if context is False else context)
        if same or transform.is_translation:
            st._scale = self._scale
            st._arc_tol = self._arc_tol
        return st


class _Builder:
    def __init__(self, root, dpi, font_size, languages, tolerance, max_elements,
                 max_use_depth, extra_css):
        self.root = root
        self.dpi = float(dpi)
        self.font_size = float(font_size)
        self.languages = tuple(str(x).strip().lower() for x in languages)
        self.lang_primary = frozenset(x.split('-')[0] for x in self.languages)
        self.tolerance = float(tolerance)
        self.max_elements = int(max_elements)
        self.max_use_depth = int(max_use_depth)
        found = {'id': [], 'requiredExtensions': [], 'systemLanguage': []}
        self.styles = declared_styles(root, extra_css, found)
        self.by_id = {}
        for el in found['id']:
            i = el.get('id')
            if i not in self.by_id:
                self.by_id[i] = el
        # elements with conditional processing attributes (most have none)
        self._conditional = set(found['requiredExtensions']) | set(found['systemLanguage'])
        self.count = 0
        self.stopped = False
        self.warned = set()
        self.tree_ids = {}
        self._recursive = {}
        self._active_refs = set()
        self._stroke_cache = {}
        self._doc_styles = {}
        self._servers = {}
        self._inh0 = _initial_inherited(font_size)
        self._ctx_cache = {}
        self._path_cache = {}
        self._path_batch = None
        self._el_paths = {}     # path element -> Path, for arc-free data (see _batch_paths)
        self._cut_masks = None
        self._style_memo = {}
        self._opacity_effects = {}
        self._solid = {}
        self._shape_cache = {}
        self._shape_styles = {}

    # -- helpers ---------------------------------------------------------------
    def warn(self, kind, msg):
        if kind not in self.warned:
            self.warned.add(kind)
            warnings.warn(msg, RasterWarning, stacklevel=4)

    def ctx(self, inh, st):
        key = (inh['_fs'], st.vw, st.vh)
        c = self._ctx_cache.get(key)
        if c is None:
            c = LengthContext(font_size=key[0], width=st.vw, height=st.vh, dpi=self.dpi)
            if len(self._ctx_cache) < 4096:
                self._ctx_cache[key] = c
        return c

    def length(self, el, name, axis, ctx, default=0.0):
        s = el.get(name)
        if s is None:
            return default
        v = parse_length(s, axis, ctx)
        return default if v is None else v

    def note_id(self, el, node):
        i = el.get('id')
        if i and i not in self.tree_ids:
            self.tree_ids[i] = node
        return node

    def tick(self):
        """Count one element; False (with a warning) once the limit is hit."""
        self.count += 1
        if self.count > self.max_elements:
            if not self.stopped:
                self.stopped = True
                self.warn('limit', 'document needs more than %d nodes; the rest is not '
                          'rendered' % self.max_elements)
            return False
        return True

    # -- style -------------------------------------------------------------------
    def style(self, el, pinh, pown):
        """(inherited dict, own non-inherited dict) of ``el`` given its
        rendering parent's.

        Both dicts may be shared with other elements (siblings with the same
        declarations get the same pair): callers must not modify them."""
        return self._style_of(self.styles.get(el), pinh, pown)

    def _style_of(self, decl, pinh, pown):
        """:meth:`style` of an element with declarations ``decl``."""
        if not decl:
            return pinh, _NO_OWN
        key = (id(pinh), id(pown), tuple(decl.items()))
        hit = self._style_memo.get(key)
        if hit is not None:
            return hit[2], hit[3]
        inh, own = self._style(decl, pinh, pown)
        # the parents are kept alive with the result, so their ids stay unique
        self._style_memo[key] = (pinh, pown, inh, own)
        return inh, own

    def _style(self, decl, pinh, pown):
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
                    fs = self.font_size_value(v, pinh['_fs'])
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

    def font_size_value(self, v, parent):
        low = v.strip().lower()
        if low in _FONT_KEYWORDS:
            return self.font_size * _FONT_KEYWORDS[low]
        if low == 'larger':
            return parent * 1.2
        if low == 'smaller':
            return parent / 1.2
        fs = parse_length(v, 'other', LengthContext(font_size=parent, width=parent,
                                                     height=parent, dpi=self.dpi))
        if fs is None or fs < 0:
            return None
        return fs

    # -- conditions ----------------------------------------------------------------
    def passes_conditions(self, el):
        if el not in self._conditional:
            return True
        attrib = el.attrib
        if 'requiredExtensions' in attrib:
            return False
        sl = attrib.get('systemLanguage')
        if sl is not None:
            ok = False
            for tag in sl.split(','):
                tag = tag.strip().lower()
                if tag and tag.split('-')[0] in self.lang_primary:
                    ok = True
                    break
            if not ok:
                return False
        return True

    # -- transforms ------------------------------------------------------------------
    def transform_of(self, el, own, ctx):
        """The element's transform (with transform-origin); None if
        singular.  An identity is always the object ``IDENTITY``."""
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
            p = parse_transform_origin(o, ctx)
            if p is not None and (p[0] or p[1]):
                t = Affine.translate(p[0], p[1]) @ t @ Affine.translate(-p[0], -p[1])
                if t.is_identity:
                    return IDENTITY
        return t

    # -- nodes -----------------------------------------------------------------------
    def children(self, el, inh, own, st, out):
        node = self.node
        for ch in el:
            tag = ch.tag
            # SVG elements only (node() would skip the others)
            if isinstance(tag, str) and tag.startswith(_P):
                node(ch, inh, own, st, out, tag[_PLEN:])

    def node(self, el, pinh, pown, st, out, name=None):
        """Build ``el`` (rendered in the context of a parent with computed
        style ``pinh``/``pown``) and append its nodes to ``out``."""
        if name is None:
            name = _local(el)
            if name is None:
                return
        if name in _NOT_RENDERED:
            return
        if name not in _SHAPES and name not in _CONTAINERS:
            if name == 'text':
                from .text import build_text    # text layout: raster/svg/text.py
                build_text(self, el, pinh, pown, st, out)
            elif name == 'image':
                from .image import build_image
                build_image(self, el, pinh, pown, st, out)
            return
        decl = self.styles.get(el)
        if decl:
            v = decl.get('display')
            if v is not None and v.strip() == 'none':
                return
        if el in self._conditional and not self.passes_conditions(el):
            return
        if not self.tick():
            return
        mark = len(out)
        try:
            self._element(el, name, decl, pinh, pown, st, out)
        except RasterError as e:
            # numbers that overflow when combined (1e308 scales, ...): the
            # element is left out, the rest of the document still renders
            del out[mark:]
            self.warn('element-error', 'element <%s> not rendered: %s' % (name, e))

    def _element(self, el, name, decl, pinh, pown, st, out):
        inh, own = self._style_of(decl, pinh, pown)
        ctx = self.ctx(inh, st)
        t = self.transform_of(el, own, ctx)
        if t is None:
            return
        if name in _SHAPES:
            self.shape(el, name, inh, own, ctx, t, st, out)
        elif name == 'use':
            self.use(el, inh, own, ctx, t, st, out)
        elif name == 'svg':
            self.nested_svg(el, inh, own, ctx, t, st, out)
        else:
            kids = []
            sub = st.sub(t)
            if name == 'switch':
                for ch in el:
                    cn = _local(ch) if isinstance(ch.tag, str) else None
                    if cn in _SWITCH_CHOICES and self.passes_conditions(ch):
                        self.node(ch, inh, own, sub, kids, cn)
                        break
            else:
                self.children(el, inh, own, sub, kids)
            out.extend(self.wrap(el, own, t, kids, st))

    def effects(self, el, own, st, kids, t=None):
        """Group effects of an element whose content is ``kids`` (nodes in
        its user space), as an :class:`_Effects`; its ``ok`` is False when
        the element is not rendered (an empty clip path, an
        object-bounding-box clip or mask of an empty box, an invalid filter)."""
        if not own:
            return _NO_EFFECTS
        for k in own:
            if k in _EFFECT_PROPS:
                break
        else:       # at most an opacity (ignored inside a clip path)
            o = own.get('opacity')
            if o is None or st.mode == 'clip':
                return _NO_EFFECTS
            e = self._opacity_effects.get(o)
            if e is None:
                e = self._opacity_effects[o] = _Effects(opacity=_opacity(o))
            return e
        mask = None
        if t is not None and not t.is_identity and ('clip-path' in own or 'mask' in own):
            st = st.sub(t)
        clip = self.clip_property(own, kids, st)
        if clip is _EMPTY:
            return _EFFECTS_NOT_DRAWN
        if st.mode == 'clip':
            return _Effects(clip=clip)
        v = own.get('mask')
        if v is not None and v.strip() != 'none' and el not in self.cut_masks():
            mask = self.reference(v, 'mask', 'mask')
            if mask is not None:
                mask = self.build_mask(mask, kids, st)
                if mask is _EMPTY:
                    return _EFFECTS_NOT_DRAWN
        v = own.get('filter')
        filters = None
        if v is not None and v.strip() != 'none':
            from .filters import resolve_filter_property
            filters = resolve_filter_property(self, el, v, kids, st)
            if filters is None:         # invalid reference, empty filter: not rendered
                return _EFFECTS_NOT_DRAWN
        blend = own.get('mix-blend-mode', 'normal')
        if blend not in _BLEND:
            blend = 'normal'
        return _Effects(opacity=_opacity(own.get('opacity')), blend=blend,
                        isolate=own.get('isolation') == 'isolate', clip=clip, mask=mask,
                        filters=filters or ())

    def cut_masks(self):
        """Elements inside ``mask`` elements whose ``mask`` property is
        dropped to break a cycle, decided once per document as resvg does:
        for every mask M in document order, a descendant that references M
        itself loses its ``mask``; one that references another mask N
        keeps it, and the descendants of N that reference M lose theirs.
        (Which link of a cycle to cut is not specified; this order matches
        resvg's output.)"""
        cut = self._cut_masks
        if cut is not None:
            return cut
        cut = self._cut_masks = set()
        masks = [m for m in self.root.iter(_P + 'mask')]
        if not masks:
            return cut

        def target(e):
            if e in cut:
                return None
            decl = self.styles.get(e)
            v = decl.get('mask') if decl else None
            if not v or v.strip() == 'none':
                return None
            u = parse_url(v)
            t = self.by_id.get(u[0]) if u is not None else None
            return t if t is not None and _local(t) == 'mask' else None
        for m in masks:
            for e in m.iter():
                if e is m or not isinstance(e.tag, str):
                    continue
                n = target(e)
                if n is None:
                    continue
                if n is m:
                    cut.add(e)
                    continue
                for f in n.iter():
                    if f is not n and isinstance(f.tag, str) and target(f) is m:
                        cut.add(f)
        return cut

    def reference(self, value, kind, prop):
        """The element of local name ``kind`` referenced by a ``url(#id)``
        property value, or None (missing or wrong references are ignored,
        as resvg does)."""
        u = parse_url(value)
        if u is None:
            self.warn(prop + '-syntax', 'unsupported %s value %r ignored' % (prop, value))
            return None
        tgt = self.by_id.get(u[0])
        if tgt is None or _local(tgt) != kind:
            return None
        return tgt

    def wrap(self, el, own, t, kids, st, clip=None, keep=False):
        """Wrap ``kids`` in a Group when the element changes something (or
        has an id); return the list of nodes to add to the parent.
        ``clip`` is a viewport clip (nested svg, symbol)."""
        if not kids and own.get('filter', 'none').strip() == 'none':
            return []       # (a filter can draw for an empty element: feFlood)
        e = self.effects(el, own, st, kids, t)
        if not e.ok or e.opacity <= 0.0:
            return []
        if clip is not None:
            if e.clip is not None:      # viewport clip inside the element's clip path
                kids = [Group(clip_path=clip, children=kids)]
            else:
                e = dataclasses.replace(e, clip=clip)
        kids, e = _fold_opacity(kids, e)
        i = el.get('id') or ''
        if not keep and not i and t.is_identity and e.trivial:
            return kids
        g = e.group(i, t, kids)
        self.note_id(el, g)
        return [g]

    # -- clip paths and masks -------------------------------------------------------
    def object_box(self, kids):
        """(x, y, w, h) fill bounding box of nodes in their parent's user
        space, or None when there is no geometry."""
        b = _nodes_box(kids)
        return None if b is None else (b[0], b[1], b[2] - b[0], b[3] - b[1])

    @contextlib.contextmanager
    def referencing(self, el):
        """While building ``el``'s content: references back to ``el``
        (clip paths, masks, patterns, markers, filters) are recursion."""
        self._active_refs.add(el)
        try:
            yield
        finally:
            self._active_refs.discard(el)

    def build_clip(self, cp, kids, st):
        """A clipPath element to a ClipPath for content ``kids``; None when
        the reference is ignored (recursion), _EMPTY when nothing is left."""
        if cp in self._active_refs:
            self.warn('clip-recursive', 'recursive clip-path reference ignored')
            return None
        with self.referencing(cp):
            inh, own = self.doc_style(cp)
            ctx = self.ctx(inh, st)
            t = self.transform_of(cp, own, ctx)
            if t is None:
                return _EMPTY
            if cp.get('clipPathUnits') == 'objectBoundingBox':
                box = self.object_box(kids)
                if box is None or box[2] <= 0 or box[3] <= 0:
                    return _EMPTY
                t = t @ Affine(box[2], 0, 0, box[3], box[0], box[1])
            sub = _State(st.vw, st.vh, st.ctm @ t, st.use_depth, 'clip')
            nodes = []
            for ch in cp:
                name = _local(ch) if isinstance(ch.tag, str) else None
                if name in _SHAPES:
                    self.node(ch, inh, own, sub, nodes, name)
                elif name == 'use':
                    tgt = self.href_target(ch)
                    if tgt is not None and _local(tgt) in _SHAPES:
                        self.node(ch, inh, own, sub, nodes, name)
                elif name == 'text':
                    self.node(ch, inh, own, sub, nodes, name)
            nested = self.clip_property(own, kids, st)
            if nested is _EMPTY:
                return _EMPTY
            if not nodes:
                return _EMPTY
            return ClipPath(root=Group(children=nodes), transform=t, clip_path=nested,
                            id=cp.get('id') or '')

    def clip_property(self, own, kids, st):
        """The ClipPath of a ``clip-path`` value in ``own`` for content
        ``kids``: None (none, or a reference that is ignored) or _EMPTY
        (nothing is visible)."""
        v = own.get('clip-path')
        if v is None or v.strip() == 'none':
            return None
        ref = self.reference(v, 'clipPath', 'clip-path')
        return None if ref is None else self.build_clip(ref, kids, st)

    def build_mask(self, mk, kids, st):
        """A mask element to a Mask for content ``kids`` (None: reference
        ignored; _EMPTY: nothing is visible)."""
        if mk in self._active_refs:
            self.warn('mask-recursive', 'recursive mask reference ignored')
            return None
        with self.referencing(mk):
            inh, own = self.doc_style(mk)
            box = None
            obb = mk.get('maskUnits') != 'userSpaceOnUse'
            cobb = mk.get('maskContentUnits') == 'objectBoundingBox'
            if obb or cobb:
                box = self.object_box(kids)
                if box is None or box[2] <= 0 or box[3] <= 0:
                    return _EMPTY
            if obb:
                lctx = LengthContext(font_size=inh['_fs'], width=1.0, height=1.0, dpi=self.dpi)
            else:
                lctx = self.ctx(inh, st)
            x = self.length(mk, 'x', 'x', lctx, None)
            y = self.length(mk, 'y', 'y', lctx, None)
            w = self.length(mk, 'width', 'x', lctx, None)
            h = self.length(mk, 'height', 'y', lctx, None)
            x = parse_length('-10%', 'x', lctx) if x is None else x
            y = parse_length('-10%', 'y', lctx) if y is None else y
            w = parse_length('120%', 'x', lctx) if w is None else w
            h = parse_length('120%', 'y', lctx) if h is None else h
            if obb:
                x, y, w, h = box[0] + x * box[2], box[1] + y * box[3], w * box[2], h * box[3]
            if not (w > 0 and h > 0):
                return _EMPTY
            ct = IDENTITY
            if cobb:
                ct = Affine(box[2], 0, 0, box[3], box[0], box[1])
            sub = _State(st.vw, st.vh, st.ctm @ ct, st.use_depth, None)
            nodes = []
            self.children(mk, inh, own, sub, nodes)
            if not ct.is_identity and nodes:
                nodes = [Group(transform=ct, children=nodes)]
            nested = None
            v = own.get('mask')
            if v is not None and v.strip() != 'none':
                ref = self.reference(v, 'mask', 'mask')
                # a chain of mask-on-mask references that comes back is
                # dropped as a whole (resvg)
                seen = set()
                r = ref
                while r is not None and r not in seen:
                    if r is mk or r in self._active_refs:
                        ref = None
                        self.warn('mask-recursive', 'recursive mask reference ignored')
                        break
                    seen.add(r)
                    rv = self.doc_style(r)[1].get('mask')
                    r = self.reference(rv, 'mask', 'mask') if rv and rv.strip() != 'none' else None
                if ref is not None:
                    nested = self.build_mask(ref, kids, st)
                    if nested is _EMPTY:
                        return _EMPTY
            if not nodes:
                return _EMPTY
            kind = 'alpha' if own.get('mask-type') == 'alpha' else 'luminance'
            return Mask(rect=(x, y, w, h), root=Group(children=nodes), kind=kind, mask=nested,
                        id=mk.get('id') or '')

    def clip_rect(self, x, y, w, h):
        rect = PathNode(path=rect_path(x, y, w, h), fill=Fill(SolidPaint(_BLACK)))
        return ClipPath(root=Group(children=[rect]))

    # -- structure ---------------------------------------------------------------------
    def viewport_group(self, el, inh, own, t, st, out, x, y, w, h, vb_el, content_el,
                       overflow_own):
        """Common part of nested svg and symbol instances: content of
        ``content_el`` in a viewport (x, y, w, h) with the viewBox of
        ``vb_el``."""
        if not (w > 0 and h > 0):
            return
        vb_attr = vb_el.get('viewBox')
        inner = Affine.translate(x, y)
        vw, vh = w, h
        if vb_attr is not None:
            vb = parse_viewbox(vb_attr)
            if vb is None:
                return
            par = parse_preserve_aspect_ratio(vb_el.get('preserveAspectRatio', ''))
            inner = viewbox_transform(vb, par, w, h, x, y)
            vw, vh = vb[2], vb[3]
        ov = overflow_own.get('overflow', 'hidden').strip()
        clip = None if ov in ('visible', 'auto') else self.clip_rect(x, y, w, h)
        kids = []
        self.children(content_el, inh, own, st.sub(t @ inner, vw, vh), kids)
        if not kids:
            return
        if clip is None:
            out.extend(self.wrap(el, own, t @ inner, kids, st))
        else:
            if not inner.is_identity:
                kids = [Group(transform=inner, children=kids)]
            out.extend(self.wrap(el, own, t, kids, st, clip=clip))

    def nested_svg(self, el, inh, own, ctx, t, st, out, use_size=None):
        x = self.length(el, 'x', 'x', ctx)
        y = self.length(el, 'y', 'y', ctx)
        w, h = use_size if use_size is not None else (None, None)
        if w is None:
            w = self.length(el, 'width', 'x', ctx, None)
            if w is None:
                w = st.vw
        if h is None:
            h = self.length(el, 'height', 'y', ctx, None)
            if h is None:
                h = st.vh
        self.viewport_group(el, inh, own, t, st, out, x, y, w, h, el, el, own)

    def href_target(self, el):
        href = el.get('href')
        if href is None:
            href = el.get(XLINK_HREF)
        if href is None:
            return None
        href = href.strip()
        if not href.startswith('#'):
            if href:
                self.warn('external', 'references to other documents are not supported')
            return None
        return self.by_id.get(href[1:])

    def is_recursive(self, use):
        """True when instantiating ``use`` would (directly or through other
        ``use`` elements) instantiate itself, or nests deeper than the use
        depth limit.  Memoized per element."""
        memo = self._recursive
        gray = 'gray'

        def visit(u, depth):
            v = memo.get(u)
            if v is gray:
                return True
            if v is not None:
                return v
            if depth > self.max_use_depth:
                return True
            memo[u] = gray
            res = False
            tgt = self.href_target(u)
            if tgt is not None:
                anc = u
                while anc is not None:
                    if anc is tgt:
                        res = True
                        break
                    anc = anc.getparent()
                if not res:
                    for u2 in tgt.iter(_P + 'use'):
                        if visit(u2, depth + 1):
                            res = True
                            break
            memo[u] = res
            return res

        return visit(use, 0)

    def use(self, el, inh, own, ctx, t, st, out):
        tgt = self.href_target(el)
        if tgt is None:
            return
        if self.is_recursive(el):
            self.warn('use-cycle', 'recursive use reference ignored (id %r)' % el.get('id'))
            return
        if st.use_depth >= self.max_use_depth:
            self.warn('use-depth', 'use nesting deeper than %d ignored' % self.max_use_depth)
            return
        x = self.length(el, 'x', 'x', ctx)
        y = self.length(el, 'y', 'y', ctx)
        name = _local(tgt)
        if name is None:
            return
        # the use element is the context element of its content (SVG 2)
        cfill = self.paint(inh.get('fill', 'black'), inh, ctx, None, st)
        sv = inh.get('stroke')
        cstroke = self.paint(sv, inh, ctx, None, st) if sv is not None else None
        st2 = st.sub(use_depth=st.use_depth + 1, context=(cfill, cstroke))
        kids = []
        if name == 'symbol':
            decl = self.styles.get(tgt)
            if decl and decl.get('display', '').strip() == 'none':
                return
            sinh, sown = self.style(tgt, inh, own)
            w = self.length(el, 'width', 'x', ctx, None)
            h = self.length(el, 'height', 'y', ctx, None)
            if w is None:
                w = self.length(tgt, 'width', 'x', ctx, None)
            if h is None:
                h = self.length(tgt, 'height', 'y', ctx, None)
            w = st.vw if w is None else w
            h = st.vh if h is None else h
            sym = []
            self.viewport_group(tgt, sinh, sown, IDENTITY, st2.sub(t), sym, x, y, w, h,
                                tgt, tgt, sown)
            kids = sym
            self._rebase_context(kids, IDENTITY, inh, cfill, cstroke)
            out.extend(self.wrap(el, own, t, kids, st))
            return
        move = Affine.translate(x, y) if (x or y) else IDENTITY
        tt = t @ move
        if name == 'svg':
            w = self.length(el, 'width', 'x', ctx, None)
            h = self.length(el, 'height', 'y', ctx, None)
            decl = self.styles.get(tgt)
            if decl and decl.get('display', '').strip() == 'none':
                return
            if not self.tick():
                return
            sinh, sown = self.style(tgt, inh, own)
            sctx = self.ctx(sinh, st2)
            stt = self.transform_of(tgt, sown, sctx)
            if stt is None:
                return
            self.nested_svg(tgt, sinh, sown, sctx, stt, st2.sub(tt), kids, use_size=(w, h))
        else:
            self.node(tgt, inh, own, st2.sub(tt), kids, name)
        self._rebase_context(kids, move, inh, cfill, cstroke)
        out.extend(self.wrap(el, own, tt, kids, st))

    def _rebase_context(self, kids, move, inh, cfill, cstroke):
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
        if any(p.units == 'objectBoundingBox' or
               getattr(p, 'content_units', '') == 'objectBoundingBox' for p in todo):
            b = _layer_box(kids, move)
            if b is not None:
                box = (b[0], b[1], b[2] - b[0], b[3] - b[1])
        cache = {}
        for n, m in _walk_all(kids, move):
            if isinstance(n, Group):
                continue
            for attr in ('fill', 'stroke'):
                f = getattr(n, attr, None)
                if f is None or not any(f.paint is p for p in todo):
                    continue
                key = (id(f.paint), m)
                if key not in cache:
                    cache[key] = _rebased(f.paint, m, box)
                f.paint = cache[key]

    # -- shapes -----------------------------------------------------------------------
    def arc_tolerance(self, st, t):
        """Tolerance for arcs of an element with transform ``t`` in state
        ``st`` (memoized in ``st`` for translations)."""
        if t.is_translation:
            tol = st._arc_tol
            if tol is None:
                tol = st._arc_tol = self._arc_tolerance(st.scale())
            return tol
        return self._arc_tolerance((st.ctm @ t).max_scale())

    def _arc_tolerance(self, s):
        tol = self.tolerance * _ARC_SAFETY
        if s > 0 and math.isfinite(s):
            tol = tol / s
        return min(max(tol, 1e-9), 1e9)

    def path_data(self, d, tol):
        """``parse_path(d, tol, strict=False)``, memoized per document.

        Paths are immutable, so repeated ``d`` strings (chart symbols, map
        markers) share one Path.  Data without arcs does not depend on the
        tolerance and is cached under one key."""
        key = (d, tol) if ('a' in d or 'A' in d) else d
        cache = self._path_cache
        if self._path_batch is None:
            self._batch_paths()
        p = cache.get(key)
        if p is None:
            p = parse_path(d, tol, strict=False)
            if len(cache) < 65536:
                cache[key] = p
        return p

    def _batch_paths(self):
        """Parse the document's arc-free path data in one vectorized pass
        (:func:`raster.svgpath.parse_paths`) into the path cache: a map
        with thousands of ``path`` elements would otherwise pay the
        per-string overhead thousands of times.  The paths are also
        recorded per element (``_el_paths``), so that building a path
        element reads its data only once."""
        ds = {}
        els = []
        for el in self.root.iter(_P + 'path'):
            d = el.get('d')
            if d and 'a' not in d and 'A' not in d:
                els.append((el, d))
                if d not in self._path_cache:
                    ds[d] = None
                    if len(ds) >= 65536:
                        break
        self._path_batch = len(ds)
        if len(ds) >= 32:
            ds = list(ds)
            try:
                paths = parse_paths(ds, self.tolerance)
            except RasterError:
                paths = None            # one of them overflows: parsed one by one later
            if paths is not None:
                self._path_cache.update(zip(ds, paths))
        cache = self._path_cache
        self._el_paths = {el: cache[d] for el, d in els if d in cache}

    def geometry(self, el, name, ctx, tol):
        """The Path of a basic shape or ``path`` element (None when it has
        no valid geometry); lengths resolve against ``ctx``, curves are
        flattened within ``tol``.  Basic shapes are memoized on their
        attribute strings (charts repeat the same symbol many times)."""
        if name == 'path':
            d = el.get('d')
            if not d:
                return None
            return self.path_data(d, tol)
        key = (name, ctx, tol) + tuple(map(el.get, _GEOMETRY_ATTRS.get(name, ('points',))))
        cache = self._shape_cache
        p = cache.get(key, cache)
        if p is cache:
            p = self._shape_geometry(el, name, ctx, tol)
            if len(cache) < 65536:
                cache[key] = p
        return p

    def _shape_geometry(self, el, name, ctx, tol):
        L = self.length
        if name == 'rect':
            w = L(el, 'width', 'x', ctx, None)
            h = L(el, 'height', 'y', ctx, None)
            if w is None or h is None or w <= 0 or h <= 0:
                return None
            rx = L(el, 'rx', 'x', ctx, None)
            ry = L(el, 'ry', 'y', ctx, None)
            if rx is not None and rx < 0:
                rx = None
            if ry is not None and ry < 0:
                ry = None
            return rect_path(L(el, 'x', 'x', ctx), L(el, 'y', 'y', ctx), w, h, rx, ry, tol)
        if name == 'circle':
            r = L(el, 'r', 'other', ctx, None)
            if r is None or r <= 0:
                return None
            return circle_path(L(el, 'cx', 'x', ctx), L(el, 'cy', 'y', ctx), r, tol)
        if name == 'ellipse':
            rx = L(el, 'rx', 'x', ctx, None)
            ry = L(el, 'ry', 'y', ctx, None)
            # a negative radius is invalid: treated as auto (resvg)
            rx = None if rx is not None and rx < 0 else rx
            ry = None if ry is not None and ry < 0 else ry
            if rx is None and ry is None:
                return None
            return ellipse_path(L(el, 'cx', 'x', ctx), L(el, 'cy', 'y', ctx), rx, ry, tol)
        if name == 'line':
            return line_path(L(el, 'x1', 'x', ctx), L(el, 'y1', 'y', ctx),
                             L(el, 'x2', 'x', ctx), L(el, 'y2', 'y', ctx))
        pts = el.get('points')
        if not pts:
            return None
        return polyline_path(pts, closed=(name == 'polygon'))

    def paint(self, value, inh, ctx, path=None, st=None):
        p = parse_paint(value)
        if p is None:
            return None
        kind = p.kind
        if kind == 'color':
            c = self._solid.get(p.color)        # shared: paints are never modified
            if c is None:
                c = self._solid[p.color] = SolidPaint(p.color)
            return c
        if kind == 'current':
            return SolidPaint(inh['_color'])
        if kind == 'url':
            tgt = self.by_id.get(p.url)
            name = _local(tgt) if tgt is not None else None
            if name in _PAINT_SERVERS:
                server = self._resolve_paint_server(tgt, name, ctx)
                if (server is not None and server is not _UNSUPPORTED and path is not None
                        and getattr(server, 'units', '') == 'objectBoundingBox'):
                    # a bounding box of zero width or height cannot be used
                    try:
                        x0, y0, x1, y1 = exact_bbox(path)
                    except RasterError:
                        x0 = x1 = 0.0
                    if not (x1 > x0 and y1 > y0):
                        server = _UNSUPPORTED
                if server is not _UNSUPPORTED:
                    return server
            fb = p.fallback
            if fb is None:
                return None
            if fb.kind == 'color':
                return SolidPaint(fb.color)
            if fb.kind == 'current':
                return SolidPaint(inh['_color'])
            return None
        if kind in ('context-fill', 'context-stroke') and st is not None and st.context:
            return st.context[0 if kind == 'context-fill' else 1]
        return None     # none, or context-fill / context-stroke without a context

    # -- paint servers --------------------------------------------------------------
    def doc_style(self, el):
        """(inherited, own) style of ``el`` along its *document* ancestors
        (for gradients, stops and patterns).  Memoized."""
        memo = self._doc_styles
        r = memo.get(el)
        if r is not None:
            return r
        chain = []
        e = el
        while e is not None and e not in memo:
            chain.append(e)
            e = e.getparent()
        if e is None:
            pinh, pown = self._inh0, {}
        else:
            pinh, pown = memo[e]
        for e in reversed(chain):
            pinh, pown = self.style(e, pinh, pown)
            memo[e] = (pinh, pown)
        return memo[el]

    def href_chain(self, el, kinds):
        """``el`` and the elements it references through ``href`` while they
        are of one of the local names ``kinds`` (cycles cut)."""
        chain = [el]
        seen = {el}
        while True:
            nxt = self.href_target(chain[-1])
            if nxt is None or nxt in seen or _local(nxt) not in kinds:
                return chain
            chain.append(nxt)
            seen.add(nxt)

    def _resolve_paint_server(self, el, name, ctx):
        """A paint server element to a tree paint: LinearGradient,
        RadialGradient, SolidPaint (a gradient with one stop), None (paints
        nothing) or _UNSUPPORTED (use the fallback)."""
        key = (el, ctx)
        cache = self._servers
        if key in cache:
            return cache[key]
        if name == 'pattern':
            r = self._pattern(el, ctx)
        else:
            r = self._gradient(el, name, ctx)
        cache[key] = r
        return r

    def _with_origin(self, el, t, lctx):
        """``t`` about the element's ``transform-origin`` (lengths in the
        paint server's units)."""
        o = self.doc_style(el)[1].get('transform-origin')
        if o is None or t.is_identity:
            return t
        p = parse_transform_origin(o, lctx)
        if p is None or not (p[0] or p[1]):
            return t
        return Affine.translate(p[0], p[1]) @ t @ Affine.translate(-p[0], -p[1])

    def _pattern(self, el, ctx):
        """A pattern element to a tree Pattern (None: paints nothing)."""
        if el in self._active_refs:
            self.warn('pattern-recursive', 'recursive pattern reference ignored')
            return None
        chain = self.href_chain(el, ('pattern',))

        def attr(n):
            return chain_attr(chain, n)
        content_el = None
        for e in chain:
            if any(isinstance(c.tag, str) and c.tag.startswith(_P) for c in e):
                content_el = e
                break
        if content_el is None:
            return None
        units = 'userSpaceOnUse' if attr('patternUnits') == 'userSpaceOnUse' \
            else 'objectBoundingBox'
        cunits = 'objectBoundingBox' if attr('patternContentUnits') == 'objectBoundingBox' \
            else 'userSpaceOnUse'
        if units == 'objectBoundingBox':
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
            return None
        tf = IDENTITY
        ts = attr('patternTransform')
        if ts is not None:
            t = parse_transform(ts)
            if t is not None and t.determinant != 0:
                # patternTransform acts in user space whatever the units
                tf = self._with_origin(el, t, ctx)
        vb = par = None
        content_t = IDENTITY
        vbs = attr('viewBox')
        if vbs is not None:
            vb = parse_viewbox(vbs)
            if vb is None:
                return None
            par = parse_preserve_aspect_ratio(attr('preserveAspectRatio') or '')
            if units == 'userSpaceOnUse':
                content_t = viewbox_transform(vb, par, w, h)
        with self.referencing(el):
            inh, own = self.doc_style(content_el)
            scale = 1000.0 if (cunits == 'objectBoundingBox' or units == 'objectBoundingBox') \
                else 1.0
            st = _State(ctx.width, ctx.height, tf @ Affine.scale(scale))
            nodes = []
            self.children(content_el, inh, own, st, nodes)
        if not nodes:
            return None
        return Pattern(rect=(x, y, w, h), root=Group(children=nodes), units=units,
                       content_units=cunits, transform=tf, content_transform=content_t,
                       view_box=vb, preserve_aspect_ratio=par, id=el.get('id') or '')

    def _gradient(self, el, name, ctx):
        chain = self.href_chain(el, ('linearGradient', 'radialGradient'))

        def attr(n, same_kind=False):
            return chain_attr(chain, n, el.tag if same_kind else None)
        stops_el = None
        for e in chain:
            ss = [c for c in e if isinstance(c.tag, str) and c.tag == _P + 'stop']
            if ss:
                stops_el = ss
                break
        if stops_el is None:
            return _UNSUPPORTED     # no stops: the fallback colour, else nothing
        stops = []
        last = 0.0
        for stop in stops_el:
            off = _number_or_percent(stop.get('offset', '0'))
            off = 0.0 if off is None else min(max(off, 0.0), 1.0)
            off = max(off, last)
            last = off
            sinh, sown = self.doc_style(stop)
            c = parse_color(sown.get('stop-color', 'black'))
            if c is None:
                c = _BLACK
            elif c is CURRENT_COLOR:
                c = sinh['_color']
            a = _opacity(sown.get('stop-opacity'))
            stops.append(GradientStop(off, (c[0], c[1], c[2], c[3] * a)))
        if len(stops) == 1:
            return SolidPaint(stops[0].color)
        units = 'userSpaceOnUse' if attr('gradientUnits') == 'userSpaceOnUse' \
            else 'objectBoundingBox'
        if units == 'objectBoundingBox':
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
                tf = self._with_origin(el, t, lctx)
        spread = attr('spreadMethod')
        if spread not in ('pad', 'reflect', 'repeat'):
            spread = 'pad'
        gid = el.get('id') or ''
        if name == 'linearGradient':
            x1 = length('x1', 'x', 0.0)
            y1 = length('y1', 'y', 0.0)
            x2 = length('x2', 'x', lctx.width if units == 'userSpaceOnUse' else 1.0)
            y2 = length('y2', 'y', 0.0)
            return LinearGradient(x1, y1, x2, y2, stops, units=units, transform=tf,
                                  spread=spread, id=gid)
        half_w = 0.5 * lctx.width if units == 'userSpaceOnUse' else 0.5
        half_h = 0.5 * lctx.height if units == 'userSpaceOnUse' else 0.5
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
        return RadialGradient(cx, cy, r, fx, fy, stops, fr=fr, units=units, transform=tf,
                              spread=spread, id=gid)

    def _shape_style(self, inh, ctx):
        """What a shape's computed style ``inh`` (lengths against ``ctx``)
        says about its painting, worked out once per style (``inh`` dicts
        are shared, see :meth:`style`): ``(inh, hidden, has markers, paint
        order, antialias, static paints, ctx)``; see :meth:`_static_paints`."""
        key = (id(inh), id(ctx))
        r = self._shape_styles.get(key)
        if r is None or r[0] is not inh or r[6] is not ctx:
            vis = inh.get('visibility', 'visible')
            sr = inh.get('shape-rendering', 'auto')
            r = (inh, vis == 'hidden' or vis == 'collapse',
                 inh.get('marker-start', 'none') != 'none'
                 or inh.get('marker-mid', 'none') != 'none'
                 or inh.get('marker-end', 'none') != 'none',
                 _paint_order(inh.get('paint-order')),
                 sr != 'crispEdges' and sr != 'optimizeSpeed',
                 self._static_paints(inh, ctx), ctx)
            if len(self._shape_styles) < 65536:
                self._shape_styles[key] = r     # (keeps inh, ctx alive: their ids stay unique)
        return r

    def shape(self, el, name, inh, own, ctx, t, st, out):
        _, hidden, has_markers, order, antialias, paints, _ = self._shape_style(inh, ctx)
        clip_mode = st.mode == 'clip'
        if hidden and clip_mode:
            return
        ident = t is IDENTITY       # (transform_of returns no other identity)
        trans = ident or t.is_translation
        try:
            if not ident:
                st.check(t)     # an overflowing CTM: the element is left out
            if name == 'path':
                if self._path_batch is None:
                    self._batch_paths()
                path = self._el_paths.get(el)
                if path is None:
                    d = el.get('d')
                    if not d:
                        return
                    if 'a' in d or 'A' in d:
                        tol = st._arc_tol if trans else None
                        if tol is None:
                            tol = self.arc_tolerance(st, t)
                        path = self._path_cache.get((d, tol))   # (path_data's key)
                    else:
                        tol = self.tolerance
                        path = self._path_cache.get(d)
                    if path is None:
                        path = self.path_data(d, tol)
            else:
                if name == 'line' or name == 'polyline' or name == 'polygon':
                    tol = self.tolerance        # no curves: the tolerance is not used
                elif name == 'rect' and el.get('rx') is None and el.get('ry') is None:
                    tol = self.tolerance
                else:
                    tol = self.arc_tolerance(st, t)
                path = self.geometry(el, name, ctx, tol)
        except RasterError:
            return
        if path is None or len(path.verbs) == 0:
            return
        # an invisible shape paints nothing but still counts in its parent's
        # object bounding box (resvg): keep it unpainted
        if hidden:
            fill = stroke = None
        elif paints is not None and not clip_mode:     # (fill_and_stroke, inlined)
            fp, fop, rule, sp, params = paints
            fill = None if fp is None else Fill(fp, fop, rule)
            stroke = None if sp is None else Stroke(sp, *params)
        else:
            fill, stroke = self.fill_and_stroke(inh, ctx, path, st)
        markers = None
        if has_markers and not hidden and not clip_mode:
            from .markers import build_markers      # marker logic: raster/svg/markers.py
            markers = build_markers(self, el, name, path, inh, own, ctx, st.sub(t), fill, stroke)
        if fill is None and stroke is None and markers is None and not hidden:
            return
        i = el.get('id') or ''
        node = PathNode(id=i, path=path, fill=fill, stroke=stroke,
                        paint_order=order, markers=markers, antialias=antialias)
        e = self.effects(el, own, st, [node], t) if own else _NO_EFFECTS
        if e is not _NO_EFFECTS:
            if not e.ok or e.opacity <= 0.0:
                return
            if e.opacity < 1.0 and not e.composited and markers is None \
                    and (fill is None) != (stroke is None):
                # group opacity over one paint: folded into it (the Fill or
                # Stroke was made for this node alone, so it is updated in
                # place; see _fold_opacity)
                if fill is not None:
                    fill.opacity = fill.opacity * e.opacity
                else:
                    stroke.opacity = stroke.opacity * e.opacity
                e = _NO_EFFECTS
        if i and i not in self.tree_ids:
            self.tree_ids[i] = node
        if ident and (e is _NO_EFFECTS or e.trivial):
            out.append(node)
        else:           # (as emit does)
            g = (Group(id=i, transform=t, children=[node]) if e is _NO_EFFECTS
                 else e.group(i, t, [node]))
            if i:
                self.tree_ids[i] = g
            out.append(g)

    def fill_and_stroke(self, inh, ctx, path, st):
        """The resolved ``(Fill or None, Stroke or None)`` of a shape or text
        run with computed style ``inh`` and geometry ``path`` (for
        object-bounding-box paints); inside a clip path, a black fill with
        the clip-rule."""
        if st.mode == 'clip':
            rule = inh.get('clip-rule', 'nonzero')
            return Fill(SolidPaint(_BLACK), 1.0, 'evenodd' if rule == 'evenodd' else 'nonzero'), None
        # colours and 'none' depend on the style alone: resolved once per
        # computed style
        spec = self._shape_style(inh, ctx)[5]
        if spec is not None:
            fp, fop, rule, sp, params = spec
            return (None if fp is None else Fill(fp, fop, rule),
                    None if sp is None else Stroke(sp, *params))
        fill = stroke = None
        fp = self.paint(inh.get('fill', 'black'), inh, ctx, path, st)
        if fp is not None:
            rule = inh.get('fill-rule', 'nonzero')
            fill = Fill(fp, _opacity(inh.get('fill-opacity')),
                        'evenodd' if rule == 'evenodd' else 'nonzero')
        sv = inh.get('stroke')
        if sv is not None:
            sp = self.paint(sv, inh, ctx, path, st)
            if sp is not None:
                stroke = self.stroke(sp, inh, ctx)
        return fill, stroke

    def emit(self, node, t, e, out):
        """Append a leaf node to ``out``, inside a Group when its transform
        ``t`` or its effects ``e`` need one (the Group then stands for the
        node's id)."""
        if t.is_identity and e.trivial:
            out.append(node)
            return
        g = e.group(node.id, t, [node])
        if node.id:
            self.tree_ids[node.id] = g
        out.append(g)

    def _static_paints(self, inh, ctx):
        """``(fill paint, fill opacity, fill rule, stroke paint, stroke
        parameters)`` of computed style ``inh`` when neither paint depends
        on the shape or the context (colours, ``currentColor``, ``none``,
        invalid values); None otherwise (references, context paints).  A
        paint is None when not painted."""
        fv = inh.get('fill', 'black')
        sv = inh.get('stroke')
        for v in (fv, sv):
            p = parse_paint(v) if v is not None else None
            if p is not None and p.kind not in ('none', 'color', 'current'):
                return None
        fp = self.paint(fv, inh, ctx)
        rule = inh.get('fill-rule', 'nonzero')
        sp = self.paint(sv, inh, ctx) if sv is not None else None
        params = self._stroke_params_cached(inh, ctx) if sp is not None else False
        if params is False:
            sp = None
        return (fp, _opacity(inh.get('fill-opacity')),
                'evenodd' if rule == 'evenodd' else 'nonzero', sp, params)

    def stroke(self, paint, inh, ctx):
        params = self._stroke_params_cached(inh, ctx)
        if params is False:
            return None
        return Stroke(paint, *params)

    def _stroke_params_cached(self, inh, ctx):
        key = (inh.get('stroke-width'), inh.get('stroke-linejoin'), inh.get('stroke-linecap'),
               inh.get('stroke-miterlimit'), inh.get('stroke-dasharray'),
               inh.get('stroke-dashoffset'), inh.get('stroke-opacity'), ctx)
        params = self._stroke_cache.get(key)
        if params is None:
            params = self._stroke_params(inh, ctx)
            if len(self._stroke_cache) < 4096:
                self._stroke_cache[key] = params
        return params

    def _stroke_params(self, inh, ctx):
        """(width, opacity, join, cap, miterlimit, dash, dash_offset) or
        False when the stroke is not drawn."""
        w = 1.0
        s = inh.get('stroke-width')
        if s is not None:
            v = parse_length(s, 'other', ctx)
            if v is not None:
                w = v
        if not w > 0:
            return False
        join = inh.get('stroke-linejoin', 'miter')
        cap = inh.get('stroke-linecap', 'butt')
        ml = parse_number(inh.get('stroke-miterlimit', '4'))
        if ml is None or ml < 1:
            ml = 4.0
        dash = None
        da = inh.get('stroke-dasharray')
        if da is not None and da.strip() != 'none':
            vals = parse_length_list(da, 'other', ctx)
            if vals and all(v >= 0 for v in vals) and sum(vals) > 0:
                if len(vals) % 2:
                    vals = vals * 2
                dash = tuple(vals)
        off = 0.0
        do = inh.get('stroke-dashoffset')
        if do is not None:
            v = parse_length(do, 'other', ctx)
            if v is not None:
                off = v
        return (w, _opacity(inh.get('stroke-opacity')),
                join if LineJoin.lookup(join) is not None else 'miter',
                cap if LineCap.lookup(cap) is not None else 'butt', ml, dash, off)


def _layer_box(nodes, t):
    """(x0, y0, x1, y1) bounding box of ``nodes`` mapped by ``t``, composed
    the way resvg composes the box of a ``use`` element: each group's box
    is the box of its children's boxes' corners under the group transform
    (not the exact box of the transformed geometry).  None when empty."""
    lo = [math.inf, math.inf]
    hi = [-math.inf, -math.inf]
    for n in nodes:
        if isinstance(n, Group):
            b = _layer_box(n.children, IDENTITY)
        elif isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
            try:
                b = exact_bbox(n.path)
            except RasterError:
                b = None
        else:
            b = None
        if b is None:
            continue
        m = t @ n.transform if isinstance(n, Group) else t
        c = m.apply([[b[0], b[1]], [b[2], b[1]], [b[2], b[3]], [b[0], b[3]]])
        lo = [min(lo[0], c[:, 0].min()), min(lo[1], c[:, 1].min())]
        hi = [max(hi[0], c[:, 0].max()), max(hi[1], c[:, 1].max())]
    if not math.isfinite(lo[0]):
        return None
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _rebased(p, m, box):
    """Paint server ``p`` (in the coordinates that ``m`` maps a shape's user
    space into, with bounding box ``box`` there) as a user-space paint of
    the shape; None when an object bounding box is needed but empty."""
    try:
        inv = m.inverse()
    except RasterError:
        return None
    obb = p.units == 'objectBoundingBox'
    cobb = getattr(p, 'content_units', '') == 'objectBoundingBox'
    if (obb or cobb) and (box is None or not (box[2] > 0 and box[3] > 0)):
        return None
    if isinstance(p, Pattern):
        x, y, w, h = p.rect
        content = p.content_transform
        if obb:
            x, y, w, h = box[0] + x * box[2], box[1] + y * box[3], w * box[2], h * box[3]
            if p.view_box is not None:
                content = viewbox_transform(p.view_box, None, w, h)
        if p.view_box is None and cobb:
            content = content @ Affine.scale(box[2], box[3])
        return dataclasses.replace(p, rect=(x, y, w, h), units='userSpaceOnUse',
                                   content_units='userSpaceOnUse', transform=inv @ p.transform,
                                   content_transform=content)
    t = p.transform
    if obb:
        t = Affine(box[2], 0, 0, box[3], box[0], box[1]) @ t
    return dataclasses.replace(p, units='userSpaceOnUse', transform=inv @ t)


def _walk_all(nodes, transform=IDENTITY):
    """:func:`raster.svg.tree.walk` over a list of sibling nodes."""
    for node in nodes:
        yield from walk(node, transform)


def _fold_opacity(kids, e):
    """Group opacity over a single path painted once (fill or stroke, no
    markers) equals that paint's own opacity times the group's: fold it in
    and spare the renderer a layer.  Returns ``(kids, effects)``."""
    if e.opacity >= 1.0 or e.composited or len(kids) != 1 or not isinstance(kids[0], PathNode):
        return kids, e
    n = kids[0]
    if n.markers is not None or (n.fill is None) == (n.stroke is None):
        return kids, e
    if n.fill is not None:
        n = dataclasses.replace(n, fill=dataclasses.replace(n.fill, opacity=n.fill.opacity * e.opacity))
    else:
        n = dataclasses.replace(n, stroke=dataclasses.replace(n.stroke, opacity=n.stroke.opacity * e.opacity))
    return [n], dataclasses.replace(e, opacity=1.0)


_PAINT_ORDERS = {}


def _paint_order(v):
    r = _PAINT_ORDERS.get(v)
    if r is None:
        r = _parse_paint_order(v)
        if len(_PAINT_ORDERS) < 256:
            _PAINT_ORDERS[v] = r
    return r


def _parse_paint_order(v):
    if v is None:
        return ('fill', 'stroke', 'markers')
    words = v.split()
    if not words or words == ['normal']:
        return ('fill', 'stroke', 'markers')
    seen = []
    for w in words:
        if w not in ('fill', 'stroke', 'markers') or w in seen:
            return ('fill', 'stroke', 'markers')
        seen.append(w)
    for w in ('fill', 'stroke', 'markers'):
        if w not in seen:
            seen.append(w)
    return tuple(seen)


def _initial_inherited(font_size):
    inh = {k: p.initial for k, p in PROPERTIES.items() if p.inherited}
    del inh['font-size']
    del inh['color']
    inh['_fs'] = float(font_size)
    inh['_color'] = _BLACK
    return inh


def build_tree(root, *, base_dir=None, allow_files_under=None, resources_dir=None,
               font_dirs=(), dpi=96, font_size=12, languages=('en',), tolerance=0.1,
               max_elements=limits.MAX_ELEMENTS, max_use_depth=limits.MAX_USE_DEPTH,
               extra_css=''):
    """Resolve an SVG document into a render :class:`~raster.svg.tree.Tree`.

    Parameters
    ----------
    root : lxml element
        The root ``svg`` element (see :func:`raster.svg.document.load_document`).
    base_dir, allow_files_under, resources_dir, font_dirs :
        Where external resources may come from (accepted; images and fonts
        are not used yet).
    dpi : float
        Pixels per inch for absolute units (``in``, ``mm``, ``pt`` ...).
    font_size : float
        The ``medium`` font size in px (for ``em``/``ex`` units).
    languages : sequence of str
        User languages for ``systemLanguage`` (``'en'`` matches ``en-US``
        and ``en-GB``: primary subtags are compared).
    tolerance : float
        Flattening tolerance in device pixels at the natural size; arcs are
        converted to cubics ten times finer (``tolerance / 10`` divided by
        the element's scale), so a 10x zoom stays within ``tolerance``.
    max_elements : int
        Most nodes to build; beyond it a warning is issued and the rest of
        the document is dropped (protects against ``use`` bombs).
    max_use_depth : int
        Deepest ``use`` nesting followed.
    extra_css : str
        A user stylesheet applied after the document's own.

    Returns
    -------
    Tree
        ``width``/``height``: natural size in px; ``root``: a Group whose
        transform maps user space to document px; ``ids``: id -> first node
        built for that id.

    Raises
    ------
    raster.errors.SVGError
        The root is not ``svg`` or the document size is zero, negative or
        invalid.

    Warns
    -----
    raster.errors.RasterWarning
        Once per kind of unsupported or ignored content.
    """
    if _local(root) != 'svg':
        raise SVGError('not an SVG document: root element is not <svg>')
    if not (isinstance(tolerance, (int, float)) and math.isfinite(tolerance) and tolerance > 0):
        raise SVGError('tolerance must be a positive number, got %r' % (tolerance,))
    with _gc_paused():
        b = _Builder(root, dpi, font_size, languages, tolerance, max_elements, max_use_depth,
                     extra_css)
        b.image_sources = (base_dir, allow_files_under, resources_dir)  # for raster.svg.image
        b.font_dirs = tuple(font_dirs or ())      # for raster.svg.text
        return _build_root(b, root, font_size)


@contextlib.contextmanager
def _gc_paused():
    """Pause Python's cyclic garbage collector while a tree is built.

    Building allocates tens of thousands of small objects (nodes, paints,
    lists) that all stay alive, and the collector would keep scanning them
    (a sixth of the build time of a chart).  Afterwards the objects alive
    are moved to the oldest generation (``gc.freeze()`` then
    ``gc.unfreeze()``, which moves lists without scanning them) rather than
    scanned as young objects right away: the tree is long-lived.  That is
    skipped when the application has frozen objects of its own (the pair
    would unfreeze them) or had the collector disabled."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            if gc.get_freeze_count() == 0:
                gc.freeze()
                gc.unfreeze()
            gc.enable()


def _build_root(b, root, font_size):
    """The Tree of document ``root`` (see :func:`build_tree`), built by ``b``."""
    inh0 = _initial_inherited(font_size)
    inh, own = b.style(root, inh0, {})
    vb_attr = root.get('viewBox')
    vb = parse_viewbox(vb_attr) if vb_attr is not None else None
    rw, rh = (vb[2], vb[3]) if vb is not None else (100.0, 100.0)
    ctx = LengthContext(font_size=inh['_fs'], width=rw, height=rh, dpi=b.dpi)
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
    t_root = b.transform_of(root, own, ctx)
    vbt = IDENTITY
    if vb is not None:
        par = parse_preserve_aspect_ratio(root.get('preserveAspectRatio', ''))
        vbt = viewbox_transform(vb, par, w, h)
    kids = []
    rt = vbt if t_root is None else t_root @ vbt
    vw, vh = (vb[2], vb[3]) if vb is not None else (w, h)
    st = _State(vw, vh, rt)
    if t_root is not None and b.passes_conditions(root):
        b.children(root, inh, own, st, kids)
    e = b.effects(root, own, st, kids)
    if not e.ok:
        kids = []
    bg = _root_background(root, rt, w, h) if not auto else None
    if bg is not None:
        kids = [bg] + kids
    group = e.group(root.get('id') or '', rt, kids)
    if auto and kids:
        box = _content_box(group)
        if box is not None:
            x0, y0, x1, y1 = box
            w, h = x1 - x0, y1 - y0
            group.transform = Affine.translate(-x0, -y0) @ rt
    if group.id:
        b.tree_ids.setdefault(group.id, group)
    return Tree(width=float(w), height=float(h), root=group, ids=b.tree_ids)


def _root_background(root, rt, w, h):
    """A PathNode filling the whole viewport (0, 0, w, h) in document px
    with the root element's CSS ``background-color`` (from its ``style``
    attribute), in the root's user space (``rt`` maps it to document px);
    None when there is none or it is transparent.  resvg paints it under
    the content."""
    style = root.get('style')
    if not style or 'background-color' not in style.lower():
        return None
    from .css import parse_declarations
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


def _nodes_box(nodes, stroke_pad=False):
    """(x0, y0, x1, y1) exact fill box of the paths under ``nodes`` in
    their parent's coordinates, widened by half of each stroke's width when
    ``stroke_pad``; None when there is no geometry."""
    lo = [math.inf, math.inf]
    hi = [-math.inf, -math.inf]
    for n, t in _walk_all(nodes):
        if isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
            try:
                x0, y0, x1, y1 = exact_bbox(n.path, t)
            except RasterError:
                continue
            pad = 0.0
            if stroke_pad and n.stroke is not None:
                pad = n.stroke.width * 0.5 * t.max_scale()
            lo = [min(lo[0], x0 - pad), min(lo[1], y0 - pad)]
            hi = [max(hi[0], x1 + pad), max(hi[1], y1 + pad)]
    if not math.isfinite(lo[0]):
        return None
    return lo[0], lo[1], hi[0], hi[1]


def _content_box(group):
    """Visual bounds (exact fill boxes widened by half the stroke width) of
    a group's content in its parent's coordinates, or None when empty."""
    b = _nodes_box([group], stroke_pad=True)
    if b is None or not (b[2] > b[0] and b[3] > b[1]):
        return None
    return b
