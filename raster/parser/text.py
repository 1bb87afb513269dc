"""SVG text converted to paths (usvg's "text as paths" model).

:func:`convert_text` converts every ``text`` element.  It lays the text
out and appends ordinary :class:`~raster.tree.PathNode` objects: the glyph
outlines of each run of characters sharing one style, in the text
element's user space (x right, y down), filled and stroked as shapes are.

What is laid out:

* characters of ``text`` and nested ``tspan`` (and ``a``) elements, with
  ``xml:space`` handling (default: newlines removed, tabs to spaces, runs of
  spaces collapsed, leading and trailing spaces dropped; ``preserve``:
  newlines and tabs become spaces; where a child element's characters end
  with a space and the text after it starts with one, the later space is
  kept, as usvg and Chrome do: at the end of a ``textPath`` the space
  starts the next chunk; an undrawn ``textPath``'s characters still take
  part);
* ``x``/``y``/``dx``/``dy`` lists, one value per character, on any element
  (an absolute ``x`` or ``y`` starts a new *text chunk*), ``rotate`` (one
  angle per character about its glyph origin, the last angle repeating);
* fonts from :mod:`raster.fonts` (``font-family``/``-weight``/``-style``/
  ``-stretch``; characters the chosen face lacks are taken from the first
  other face that has them), shaping, metrics and outlines with HarfBuzz;
* ``text-anchor`` per chunk, ``letter-spacing``, ``word-spacing``,
  ``baseline-shift`` (``sub``, ``super``, percentages, lengths, nested sums),
  basic ``dominant-baseline``/``alignment-baseline`` values,
  ``text-decoration`` (underline, overline, line-through from the font's
  ``post`` and ``OS/2`` tables, also when set on ancestors);
* ``textPath`` (``href`` to a ``path``, ``startOffset``): every glyph's
  horizontal middle is put on the path at its arc length and the glyph
  turned to the path's direction; glyphs off the path are dropped;
* ``textLength`` with ``lengthAdjust="spacing"``; ``tref``;
* variable fonts: ``font-variation-settings`` over automatic ``wght``,
  ``wdth``, ``slnt``/``ital`` and ``opsz`` (= font size) coordinates.

Speed: a document's text elements share work through caches, all bounded:
font matching and loading per build, shaped chunks per build, shaped
strings and glyph outlines per font (:meth:`raster.fonts.Font.shape_arrays`,
:meth:`raster.fonts.Font.outlines`).  A chunk is laid out on arrays (one
entry per glyph) and its outlines are scaled, turned and moved in one
array operation per run of glyphs of one span.  A text element of
character data only (a terminal screenshot's thousands of them) sets up
its span once per document and style and takes its chunk from the chunk
memo: per element only its position, paint and effects are resolved.

Not supported, ignored or approximated: vertical writing modes (laid out
horizontally, with a :class:`~raster.errors.RasterWarning`), ``lengthAdjust="spacingAndGlyphs"`` (spacing only), the
Unicode bidi algorithm (each run gets HarfBuzz's guessed direction), colour
glyphs (outlines only).  Any other failure while laying out
one ``text`` element warns and skips that element only: text never stops a
document from rendering.
"""

import math
import re

import numpy as np

from .. import limits
from ..errors import RasterError, log_warnings
from ..geometry.flattening import flatten
from ..fonts import Font, FontDB, FontError, cached, parse_font_family
from ..fonts.matching import best_face
from ..geometry.path import Path
from ..geometry.pathdata import rect_path
from ..geometry.transform import Affine
from ..tree import PathNode, SolidPaint
from .fontface import document_font_db
from .boxes import Boxed
from .effects import wrap
from .shapes import fill_and_stroke, geometry
from .textlayout import (apply_length, apply_spacing, apply_vertical, compose, glyph_matrices,
                         metric_boxes, position_linear, position_on_path, rotate, scale,
                         shape_clusters, translate, decoration_pieces)
from .style import (is_displayed, length_context, local_name, paint_order, passes_conditions,
                    style_of, transform_of)
from .values import parse_length, parse_length_list, parse_number_list, parse_transform

__all__ = ['convert_text', 'collapse_whitespace']

_XML_SPACE = '{http://www.w3.org/XML/1998/namespace}space'
_SPAN_NAMES = frozenset(['tspan', 'a'])
_WEIGHTS = {'normal': 400, 'bold': 700}
_SPACES = re.compile(' {2,}')


def collapse_whitespace(text, preserve=False, prev_space=True):
    """Apply SVG ``xml:space`` rules to one piece of character data.

    Parameters
    ----------
    text : str
    preserve : bool
        ``xml:space="preserve"``: newlines and tabs become spaces, nothing
        is removed.
    prev_space : bool
        Whether the text laid out before ends with a (kept) space; leading
        spaces are then dropped (default mode only).

    Returns
    -------
    (str, bool)
        The processed text and the new ``prev_space`` state.

    >>> collapse_whitespace('  a \\n  b\\tc  ')
    ('a b c ', True)
    >>> collapse_whitespace(' a\\nb', preserve=True)
    (' a b', False)
    """
    if preserve:
        s = text.replace('\r\n', ' ').replace('\n', ' ').replace('\r', ' ').replace('\t', ' ')
        return s, s.endswith(' ') if s else prev_space
    s = _SPACES.sub(' ', text.replace('\n', '').replace('\r', '').replace('\t', ' '))
    if prev_space and s.startswith(' '):
        s = s[1:]
    return s, s.endswith(' ') if s else prev_space


class _Span:
    """Style of one element contributing characters."""
    __slots__ = ('el', 'inh', 'own', 'ctx', 'face', 'font', 'fs', 'shift', 'ls', 'ws', 'tl',
                 'weight', 'parent', 'decor', 'vertical', 'features', 'glyph_adjust', 'index',
                 'key', 'families', 'style', 'stretch')

    def __init__(self, el, inh, own, ctx, parent, weight):
        self.el, self.inh, self.own, self.ctx, self.parent = el, inh, own, ctx, parent
        self.weight = weight
        self.fs = float(inh['_fs'])
        self.face = self.font = None
        self.shift = 0.0
        self.decor = ()
        self.vertical = False


def _weight(value, parent):
    v = (value or 'normal').strip().lower()
    if v in _WEIGHTS:
        return _WEIGHTS[v]
    if v == 'bolder':
        return 400 if parent < 350 else (700 if parent < 550 else 900)
    if v == 'lighter':
        return 100 if parent < 550 else (400 if parent < 750 else 700)
    try:
        w = float(v)
    except ValueError:
        return parent
    if not 1 <= w <= 1000:
        return parent       # invalid: the inherited weight
    return int(w)


def _spacing(value, ctx):
    if value is None or value.strip() in ('normal', ''):
        return 0.0
    v = parse_length(value, 'x', ctx)
    return 0.0 if v is None else float(v)


def _font_db(cache):
    """The document's FontDB: its options' fonts and its ``@font-face``
    fonts (:mod:`raster.parser.fontface`), made once per document."""
    memo = cache.table('text')
    db = memo.get('fontdb')
    if db is None:
        db = memo['fontdb'] = document_font_db(FontDB.for_options(cache.options.fonts), cache)
    return db


def convert_text(el, state, cache, parent):
    """Lay out the ``text`` element ``el`` and append its nodes to
    ``parent``.  Never raises for bad text: problems warn
    (:class:`~raster.errors.RasterWarning`) and the element is skipped.
    """
    mark = len(parent)
    # the layout budget (raster.limits max_glyphs), before any layout
    if not cache.spend('glyphs', sum(map(len, el.itertext())), 'text'):
        return
    try:
        _build(el, state, cache, parent)
    except Exception as e:      # text must never break a document (RasterError too)
        del parent[mark:]
        cache.warn('text-error', 'text element not rendered: %s' % (e,))


def _build(el, state, cache, out):
    inh, own = style_of(el, state.inh, state.own, cache)
    ctx = length_context(inh, state, cache)
    t = transform_of(el, own, ctx)
    if t is None:
        return
    if (len(el) == 0 and el.get('dx') is None and el.get('dy') is None
            and el.get('rotate') is None and _leaf(el, inh, own, ctx, t, state, cache, out)):
        return
    with log_warnings('fontTools'):         # a broken font's log lines: our warnings
        _build_any(el, inh, own, ctx, t, state, cache, out)


class _Text:
    """The characters of one text element after whitespace processing
    and what they belong to: ``chars`` (list of str), ``owner`` (span index
    of each character), ``spans`` (:class:`_Span`, the text element's
    first), ``lists`` ((start, attribute, values, element) of x, y, dx,
    dy), ``rot`` ([start, angles, element]), ``ends`` (element -> index
    after its last character), ``path_ranges`` ((first, end, text path
    geometry))."""
    __slots__ = ('chars', 'owner', 'spans', 'lists', 'rot', 'ends', 'path_ranges')


def _collect(el, inh, own, ctx, st, cache, scale=1.0):
    """The :class:`_Text` of text element ``el`` (computed style ``inh``,
    ``own``, lengths ``ctx``) in state ``st``; ``scale``: device pixels per
    unit of its user space (how finely text paths are followed)."""
    chars = []          # characters after whitespace processing
    owner = []          # span index of each character
    spans = []
    lists = []          # (start index, attr name, values)
    rot = []            # [start index, angles, element] (last angle repeats)
    ends = {}           # element -> index after its last character
    path_ranges = []    # (first char, end, text path geometry)
    state = {'prev': True}
    keeps = []          # xml:space="preserve" of each span
    ended = []          # elements whose characters end at len(chars)

    def add_lists(e, ectx, start):
        for name, axis in (('x', 'x'), ('y', 'y'), ('dx', 'x'), ('dy', 'y'), ('rotate', None)):
            s = e.get(name)
            if s is None:
                continue
            if axis is None:
                vals = parse_number_list(s) if s.strip() else []
                if vals:
                    rot.append([start, [float(v) for v in vals], e])
                continue
            vals = parse_length_list(s, axis, ectx)
            if vals:
                lists.append((start, name, [float(v) for v in vals], e))

    def walk(e, einh, eown, ectx, parent, preserve, content=None):
        sp = _Span(e, einh, eown, ectx, parent,
                   _weight(einh.get('font-weight'), parent.weight if parent else 400))
        si = len(spans)
        sp.index = si
        spans.append(sp)
        keeps.append(preserve)
        if local_name(e) != 'textPath':         # positions on a textPath are ignored
            add_lists(e, ectx, len(chars))

        def add_text(s):
            if not s:
                return
            txt, state['prev'] = collapse_whitespace(s, preserve, state['prev'])
            if txt:
                chars.extend(txt)
                owner.extend([si] * len(txt))
                del ended[:]

        def hand_over_space(tail):
            # a space ending the characters before the end of a child,
            # followed by one starting the child's tail: the tail keeps its
            # space and the child loses its own (usvg's and Chrome's rule:
            # at a textPath's end the space goes to the next chunk)
            if (preserve or not tail or not chars or chars[-1] != ' '
                    or keeps[owner[-1]]):
                return
            if collapse_whitespace(tail, False, False)[0].startswith(' '):
                chars.pop()
                owner.pop()
                for done in ended:
                    ends[done] -= 1
                state['prev'] = False
        if content is not None:         # tref: the referenced element's text
            add_text(content)
            ends[e] = len(chars)
            ended.append(e)
            return
        add_text(e.text)
        for ch in e:
            name = local_name(ch)
            if name in _SPAN_NAMES:
                if is_displayed(ch, cache) and passes_conditions(ch, cache):
                    cinh, cown = style_of(ch, einh, eown, cache)
                    cctx = length_context(cinh, st, cache)
                    sp_pres = ch.get(_XML_SPACE)
                    walk(ch, cinh, cown, cctx, sp,
                         preserve if sp_pres is None else sp_pres == 'preserve')
            elif name == 'textPath' and e is el:
                if is_displayed(ch, cache):
                    cinh, cown = style_of(ch, einh, eown, cache)
                    cctx = length_context(cinh, st, cache)
                    tp = _text_path_geometry(ch, cctx, cache, 0.01 / max(scale, 1.0))
                    if tp is not None:
                        first = len(chars)
                        sp_pres = ch.get(_XML_SPACE)
                        walk(ch, cinh, cown, cctx, sp,
                             preserve if sp_pres is None else sp_pres == 'preserve')
                        hand_over_space(ch.tail)
                        path_ranges.append((first, len(chars), tp))
                        add_text(ch.tail)
                        continue
                # a textPath that is not drawn still takes part in the
                # whitespace processing (as in usvg): after its characters
                # the tail keeps its leading space
                if collapse_whitespace(''.join(ch.itertext()), preserve, True)[0].strip():
                    state['prev'] = False
                    add_text(ch.tail)
                    continue
            elif name == 'tref':
                href = ch.get('{http://www.w3.org/1999/xlink}href') or ch.get('href') or ''
                tgt = cache.by_id.get(href[1:].strip()) if href.startswith('#') else None
                if tgt is not None and is_displayed(ch, cache):
                    cinh, cown = style_of(ch, einh, eown, cache)
                    sp_pres = ch.get(_XML_SPACE)
                    walk(ch, cinh, cown, length_context(cinh, st, cache), sp,
                         preserve if sp_pres is None else sp_pres == 'preserve',
                         ''.join(t for t in tgt.itertext() if isinstance(t, str)))
            if isinstance(ch.tag, str):
                hand_over_space(ch.tail)
            add_text(ch.tail)
        ends[e] = len(chars)
        ended.append(e)

    root_span = _Span(None, st.inh, st.own, ctx, None, _parent_weight(el, cache))
    try:
        walk(el, inh, own, ctx, root_span, el.get(_XML_SPACE) == 'preserve')
    finally:
        # walk calls itself through its closure: the cycle would keep this
        # element's spans and lists until the garbage collector runs (which
        # the commands pause): textual's 1,147 texts held 16 MB
        del walk
    spans[0].parent = None
    # default mode: drop trailing spaces
    while chars and chars[-1] == ' ' and not _preserved(spans[owner[-1]].el):
        chars.pop()
        owner.pop()
    tx = _Text()
    tx.chars, tx.owner, tx.spans, tx.lists, tx.rot = chars, owner, spans, lists, rot
    tx.ends, tx.path_ranges = ends, path_ranges
    return tx


def _set_up_spans(spans, db, cache, vertical):
    """Fonts and metrics of every span (its ``face``, ``font``, spacings,
    ``textLength``, features, baseline shift and memo ``key``)."""
    fonts_of = _span_fonts(db, cache)
    for sp in spans:
        i = sp.inh
        style = (i.get('font-style') or 'normal').strip()
        stretch = (i.get('font-stretch') or 'normal').strip()
        family = i.get('font-family', '')
        sp.families = _families(family)
        sp.style, sp.stretch = style, stretch
        sp.face, sp.font = fonts_of(family, sp.weight, style, stretch)
        if sp.font is not None and sp.font.axes:
            sp.font = sp.font.variant(_variations(sp, style, stretch))
        sp.ls = _spacing(i.get('letter-spacing'), sp.ctx)
        tl = sp.el.get('textLength')
        sp.tl = None
        if tl is not None and tl.strip() != 'inherit':
            v = parse_length(tl, 'x', sp.ctx)
            sp.tl = float(v) if v is not None and v >= 0 else None
        sp.glyph_adjust = (sp.el.get('lengthAdjust') or '').strip() == 'spacingAndGlyphs'
        sp.ws = _spacing(i.get('word-spacing'), sp.ctx)
        kern = (i.get('font-kerning') or 'auto').strip()
        no_kern = kern == 'none' or (i.get('kerning') or 'auto').strip() == '0'
        sp.features = _features(i, no_kern)
        sp.vertical = vertical
    for sp in spans:
        sp.shift = _span_shift(sp, vertical)
        sp.key = (sp.font, None if sp.features is None else tuple(sorted(sp.features.items())),
                  sp.fs, sp.ls, sp.ws, sp.tl, sp.glyph_adjust, sp.shift, sp.families)


def _chunk_env(el, spans, db, cache, vertical):
    """The :class:`_ChunkEnv` of a text element's spans (set up)."""
    decor = _decorations(el, spans, cache)
    spacing = any(sp.ls or sp.ws for sp in spans)
    ls = np.array([sp.ls for sp in spans]) if spacing else None
    ws = np.array([sp.ws for sp in spans]) if spacing else None
    fallbacks = cache.table('text_fallback')

    def fallback(font, ch, sp):
        if font is None:
            return None
        k = (font, ch, sp.families, sp.weight, sp.style, sp.stretch)
        f = fallbacks.get(k)
        if f is None:
            f = fallbacks[k] = _fallback_font(db, ch, font, sp, cache)
        return f
    return _ChunkEnv(spans, decor, vertical, spacing, ls, ws, fallback,
                     cache.table('text_shaped'))


def _vertical(inh):
    wm = (inh.get('writing-mode') or 'lr-tb').strip()
    return wm in ('tb', 'tb-rl', 'vertical-rl', 'vertical-lr')


def _line_chunk(db, chunk_text, own_c, run_starts, order, anchor, env):
    """A chunk laid out along a line without per-character positions,
    through the process's chunk memo."""
    key = (db, _chunk_key(chunk_text, own_c, run_starts, order, anchor, env))
    res = _CHUNKS.get(key)
    if res is None:
        res = _lay_chunk(chunk_text, own_c, run_starts, order, anchor, None, None, None,
                         None, 0.0, env)
        _CHUNKS.put(key, res)
    return res


#: Styles of leaf text elements remembered per document (see _leaf)
_LEAF_MEMO = 4096


class _LeafStyle:
    """What a leaf text element's layout depends on but its text and
    position (see :func:`_leaf`): its computed style (kept alive, so that
    the memo's ids stay unique), set-up spans, chunk environment, anchor,
    writing mode and the style part of its chunk memo key."""
    __slots__ = ('inh', 'spans', 'env', 'anchor', 'vertical', 'props')


def _leaf(el, inh, own, ctx, t, st, cache, out):
    """Convert a text element with character data only (no children, no
    ``dx``, ``dy``, ``rotate``; at most one ``x`` and ``y`` for more than
    one character): what its layout depends on but its text and position
    (computed style, lengths, ``textLength``, ``lengthAdjust``, inherited
    weight and decorations) is set up once per document, and its chunk
    comes from the process's chunk memo, so that a document of many such
    elements (a terminal screenshot) spends little per element.  The
    result is that of the general path.  False when the element needs the
    general path (no fonts loaded yet, several positions)."""
    db = cache.table('text').get('fontdb')
    if db is None:
        return False
    s = el.text
    txt = collapse_whitespace(s, el.get(_XML_SPACE) == 'preserve')[0] if s else ''
    if txt.endswith(' ') and not _preserved(el):
        txt = txt.rstrip(' ')
    n = len(txt)
    if n == 0:
        return True
    x, y = el.get('x'), el.get('y')
    xs = None if x is None else parse_length_list(x, 'x', ctx)
    ys = None if y is None else parse_length_list(y, 'y', ctx)
    if n > 1 and ((xs and len(xs) > 1) or (ys and len(ys) > 1)):
        return False
    parent = el.getparent()
    # of the own (non-inherited) properties only these two reach the
    # layout (a text element's baseline-shift does not): elements that
    # differ in their clip paths share a style
    key = (id(inh), own.get('alignment-baseline'), own.get('text-decoration'), ctx,
           el.get('textLength'), el.get('lengthAdjust'), el.get('text-decoration'),
           (400, ()) if parent is None else _ancestry(parent, cache))
    memo = cache.table('text_leaf')
    ls = memo.get(key)
    if ls is None or ls.inh is not inh:
        with log_warnings('fontTools'):
            ls = _leaf_style(el, inh, own, ctx, st, cache, db)
        if len(memo) < _LEAF_MEMO:
            memo[key] = ls
    ckey = (db, (txt, ((0, 0),), ls.props, ls.anchor, ls.vertical))   # as _chunk_key
    res = _CHUNKS.get(ckey)
    if res is None:
        with log_warnings('fontTools'):
            res = _lay_chunk(txt, np.zeros(n, np.int64), [0], [0], ls.anchor, None, None, None,
                             None, 0.0, ls.env)
        _CHUNKS.put(ckey, res)
    if res.empty:
        return True
    if res.missing:
        _warn_missing(res.missing, cache)
    x0 = float(xs[0]) if xs else 0.0
    y0 = float(ys[0]) if ys else 0.0
    base = Affine.translate(x0, y0) @ Affine.rotate(90.0) if ls.vertical else (x0, y0)
    pieces = []
    corners = []
    _place(res, base, (0,), corners, pieces)
    if any(kind == 'color' for _, kind, _ in pieces):
        with log_warnings('fontTools'):
            _emit(el, own, t, st, cache, out, ls.spans, ls.env.decor, pieces, corners)
        return True
    if res.reach is None:
        res.reach = max((float(np.abs(p.points).max()) for _, _, p in res.pieces
                         if len(p.points)), default=0.0)
    # the pieces moved by (x0, y0) stay well inside the coordinate limit
    # (a NaN reach fails this and the pieces are checked one by one)
    inside = res.reach + abs(x0) + abs(y0) < 0.5 * limits.MAX_COORD
    _emit(el, own, t, st, cache, out, ls.spans, ls.env.decor, pieces, corners, inside)
    return True


def _leaf_style(el, inh, own, ctx, st, cache, db):
    """The :class:`_LeafStyle` of a leaf text element with some text,
    set up as the general path does."""
    ls = _LeafStyle()
    ls.inh = inh
    ls.vertical = _vertical(inh)
    spans = ls.spans = _collect(el, inh, own, ctx, st, cache).spans
    _set_up_spans(spans, db, cache, ls.vertical)
    ls.env = _chunk_env(el, spans, db, cache, ls.vertical)
    ls.anchor = (spans[0].inh.get('text-anchor') or 'start').strip()
    ls.props = _chunk_key('', np.zeros(1, np.int64), [0], [0], ls.anchor, ls.env)[2]
    return ls


def _place(res, base, order, corners, pieces):
    """Append the metric box and the pieces of chunk ``res`` placed at
    ``base`` (None, a translation ``(x, y)`` or an Affine) to ``corners``
    and ``pieces`` (span ranks mapped to span indices by ``order``)."""
    if res.box is not None:
        if isinstance(base, tuple):
            x, y = base
            b = res.box
            corners.append((b[0] + x, b[1] + y, b[2] + x, b[3] + y))
        else:
            c = _moved_points(res.corners, base)
            lo, hi = c.min(0), c.max(0)
            corners.append((float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])))
    for rel, kind, path in res.pieces:
        if kind == 'color':
            pieces.append((order[rel], kind, _moved_color(path, base)))
        else:
            pieces.append((order[rel], kind, _moved_path(path, base)))


def _emit(el, own, t, st, cache, out, spans, decor, pieces, corners, inside=False):
    """Paint the placed pieces of a text element (see :func:`_place`) and
    append them, with its effects, to ``out`` (``inside``: the pieces are
    known to be finite and within the coordinate limit)."""
    if not pieces:
        return
    bbox = None
    if corners:
        bbox = (min(b[0] for b in corners), min(b[1] for b in corners),
                max(b[2] for b in corners), max(b[3] for b in corners))
    for si, kind, p in pieces:
        if kind not in ('glyphs', 'color'):
            x0, y0, x1, y1 = _path_extent(p)
            if bbox is not None and x1 >= x0:
                bbox = (min(bbox[0], x0), min(bbox[1], y0), max(bbox[2], x1), max(bbox[3], y1))
    kids = []
    undrawn = False
    for si, kind, path in pieces:
        if kind == 'color':
            kids.extend(_color_nodes(spans[si], path, st, cache, bbox))
            continue
        if kind == 'glyphs':
            node = _paint_node(spans[si], path, st, cache, bbox)
        else:
            node = _paint_node(decor[(si, kind)], path, st, cache, bbox, spans[si])
        if node is None:
            undrawn = True
            continue
        pts = path.points
        if not inside and len(pts):
            big = np.abs(pts).max()
            if not big <= limits.MAX_COORD:
                if not np.isfinite(big):    # (glyph paths are not validated)
                    Path.from_arrays(path.verbs, path.points)   # raises PathError
                cache.warn('text-coord', 'text beyond the coordinate limit is not rendered')
                continue
        kids.append(node)
    box = None if bbox is None else (bbox[0], bbox[1], bbox[2] - bbox[0], bbox[3] - bbox[1])
    if undrawn and box is not None:
        # hidden or unpainted glyphs draw nothing but the text still counts
        # in its parents' object bounding box (which ignores visibility and
        # paint, SVG 2 8.10): an unpainted rectangle of its metric box, the
        # box resvg gives text (painting/visibility/bbox-impact-3)
        kids.append(PathNode(id='', path=rect_path(*box)))
    out.extend(wrap(el, own, t, Boxed(kids, box), st, cache))


def _build_any(el, inh, own, ctx, t, st, cache, out):
    """The general path: any text element."""
    vertical = _vertical(inh)
    db = _font_db(cache)
    if db.bundled_only:
        cache.warn('text-nofont', 'no usable fonts found; text is drawn with the bundled '
                   'Noto Sans (ASCII only)')
    # -- collect characters ---------------------------------------------------
    tx = _collect(el, inh, own, ctx, st, cache, st.scale() * t.max_scale())
    chars, spans, path_ranges = tx.chars, tx.spans, tx.path_ranges
    n = len(chars)
    if n == 0:
        return
    owner_l = tx.owner
    owner = np.asarray(owner_l, np.int64)
    ax = np.full(n, np.nan)
    ay = np.full(n, np.nan)
    arrs = {'x': ax, 'y': ay}       # dx, dy, angle: None while all zero
    ends = tx.ends
    for start, name, vals, e in tx.lists:
        k = min(len(vals), min(ends.get(e, n), n) - start)   # own characters only
        if k > 0:
            a = arrs.get(name)
            if a is None:
                a = arrs[name] = np.zeros(n)
            a[start:start + k] = vals[:k]
    dx, dy = arrs.get('dx'), arrs.get('dy')
    angle = np.zeros(n) if tx.rot else None
    last = 0.0
    for start, vals, e in tx.rot:      # document order; the last angle given repeats
        end = min(ends.get(e, n), n)
        if start >= end:
            continue
        k = min(len(vals), end - start)
        angle[start:start + k] = vals[:k]
        if k:
            last = vals[k - 1]
        angle[start + k:end] = last
    if math.isnan(ax[0]):
        ax[0] = 0.0
    if math.isnan(ay[0]):
        ay[0] = 0.0
    # -- fonts and per-span metrics --------------------------------------------
    _set_up_spans(spans, db, cache, vertical)
    env = _chunk_env(el, spans, db, cache, vertical)
    # -- chunks ------------------------------------------------------------------
    brk = ~np.isnan(np.fmin(ax, ay))     # an absolute x or y
    onpath = np.full(n, -1, np.int64) if path_ranges else None
    for pi, (p0, p1, tp) in enumerate(path_ranges):
        p1 = min(p1, n)
        if p0 >= p1:
            continue
        brk[p0] = True
        if p1 < n:
            brk[p1] = True
        onpath[p0:p1] = pi
    bounds = np.flatnonzero(brk).tolist() + [n]
    text = ''.join(chars)
    pieces = []         # (span index, kind, Path) in user space
    corners = []        # metric box corners in user space
    cur_x = cur_y = 0.0
    for c0, c1 in zip(bounds[:-1], bounds[1:]):
        tp = path_ranges[int(onpath[c0])][2] if onpath is not None and onpath[c0] >= 0 else None
        own_c = owner[c0:c1]
        anchor = (spans[owner_l[c0]].inh.get('text-anchor') or 'start').strip()
        sub = (lambda a: None if a is None else a[c0:c1])
        chunk_text = text[c0:c1]
        cuts = (np.flatnonzero(own_c[1:] != own_c[:-1]) + 1).tolist()
        run_starts = [0] + cuts
        order = []              # the chunk's spans in order of first use
        for a in run_starts:
            si = owner_l[c0 + a]
            if si not in order:
                order.append(si)
        if tp is None and dx is None and dy is None and angle is None:
            res = _line_chunk(db, chunk_text, own_c, run_starts, order, anchor, env)
        else:
            res = _lay_chunk(chunk_text, own_c, run_starts, order, anchor, tp, sub(dx), sub(dy),
                             sub(angle), _path_start(tp, ax[c0], ay[c0], vertical), env)
        if res.empty:
            continue
        if res.missing:
            _warn_missing(res.missing, cache)
        if tp is None:
            cx = ax[c0] if not math.isnan(ax[c0]) else None
            cy = ay[c0] if not math.isnan(ay[c0]) else None
            x0 = cur_x if cx is None else cx
            y0 = cur_y if cy is None else cy
            ex, ey = res.end
            if vertical:
                base = Affine.translate(x0, y0) @ Affine.rotate(90.0)
                ex, ey = ey, ex
            else:
                base = (x0, y0)
            cur_x, cur_y = x0 + ex, y0 + ey
        else:
            base = None
            cur_x, cur_y = res.end
        _place(res, base, order, corners, pieces)
    _emit(el, own, t, st, cache, out, spans, env.decor, pieces, corners)


class _ChunkEnv:
    """What the chunks of one text element share while they are laid out."""
    __slots__ = ('spans', 'decor', 'vertical', 'spacing', 'ls', 'ws', 'fallback', 'memo')

    def __init__(self, spans, decor, vertical, spacing, ls, ws, fallback, memo):
        self.spans, self.decor, self.vertical, self.spacing = spans, decor, vertical, spacing
        self.ls, self.ws, self.fallback, self.memo = ls, ws, fallback, memo


class _Chunk:
    """One laid-out chunk in its own frame (origin at the chunk's start, x
    along the line; user space for a chunk on a text path).

    ``pieces``: ``(span rank, kind, Path)`` with kind ``'overline'``,
    ``'underline'``, ``'glyphs'`` or ``'line-through'`` in painting order,
    the rank indexing the chunk's spans in order of first use;
    ``corners``: (K, 2) float64 corners of the clusters' metric boxes;
    ``box``: their extent (x0, y0, x1, y1) or None; ``end``: the pen
    position after the chunk; ``empty``: no clusters; ``missing``: the
    characters no font has a glyph for; ``reach``: the largest absolute
    coordinate of its outline and decoration pieces (see :func:`_leaf`),
    None until asked for.
    """
    __slots__ = ('pieces', 'corners', 'box', 'end', 'empty', 'missing', 'reach')

    def __init__(self):
        self.reach = None
        self.missing = ''
        self.pieces = []
        self.corners = np.zeros((0, 2))
        self.box = None
        self.end = (0.0, 0.0)
        self.empty = True


_DECOR_KINDS = ('underline', 'overline', 'line-through')


class _ChunkMemo:
    """Chunks laid out along a line without per-character positions,
    remembered for the process by everything their layout depends on (the
    FontDB, the Font objects, the text, the spans' sizes, spacings,
    lengths, shifts and decorations, the anchor): a document repeating a
    word, or a document rendered again, lays it out once.  The memo holds
    at most ``limit`` points of outlines and starts over beyond that."""

    def __init__(self, limit=1 << 20):
        self.limit = limit
        self.table = {}
        self.points = 0

    def get(self, key):
        return self.table.get(key)

    def put(self, key, chunk):
        size = len(chunk.corners) + sum(len(p.points) if kind != 'color' else 64 * len(p)
                                        for _, kind, p in chunk.pieces)
        if self.points + size > self.limit:
            self.table.clear()
            self.points = 0
        chunk.corners.flags.writeable = False
        self.table[key] = chunk
        self.points += size


_CHUNKS = _ChunkMemo()


def _chunk_key(chunk_text, own_c, run_starts, order, anchor, env):
    """The memo key of a chunk laid out along a line without per-character
    positions: everything its layout depends on."""
    rank = {si: k for k, si in enumerate(order)}
    runs = tuple((a, rank[int(own_c[a])]) for a in run_starts)
    spans, decor = env.spans, env.decor
    props = tuple(spans[si].key + (tuple(k for k in _DECOR_KINDS if (si, k) in decor),)
                  for si in order)
    return (chunk_text, runs, props, anchor, env.vertical)


def _path_start(tp, x, y, vertical):
    """Start offset along a text path of a chunk (its ``startOffset`` plus
    an absolute ``x``, ``y`` in vertical text), 0 for a chunk on a line."""
    if tp is None:
        return 0.0
    v = y if vertical else x
    return tp[2] + (0.0 if math.isnan(v) else float(v))


_EYE = np.eye(3)


def _lay_chunk(chunk_text, own_c, run_starts, order, anchor, tp, dx, dy, rot, start, env):
    """Lay out one chunk (see :class:`_Chunk`): shaping, vertical writing,
    spacing, textLength, positions, then each span's decorations, glyph
    outlines and metric boxes."""
    out = _Chunk()
    spans, vertical = env.spans, env.vertical
    cl = shape_clusters(chunk_text, own_c, spans, env.fallback, env.memo)
    if cl is None or not len(cl):
        return out
    if vertical:
        apply_vertical(cl)
    if env.spacing:
        apply_spacing(cl, env.ls, env.ws)
    if not len(cl):
        return out
    out.empty = False
    out.missing = cl.missing
    segs = []
    for a, z in zip(run_starts, run_starts[1:] + [len(chunk_text)]):
        sp = spans[int(own_c[a])]
        if sp.tl is not None:
            segs.append((a, z, sp.tl, sp.glyph_adjust))
    if segs:
        apply_length(cl, segs, tp is not None)
    if tp is None:
        out.end = position_linear(cl, anchor, dx, dy, rot, vertical)
    else:
        edges, cum, _ = tp
        shifts = np.array([-spans[int(s)].shift for s in cl.span])
        out.end = position_on_path(cl, (edges, cum), start, anchor, dx, dy, rot, -shifts)
    if cl.m is None and cl.pm is None and not vertical:
        gm, gvis = None, cl.visible[cl.g_cluster]
    else:
        gm, gvis = glyph_matrices(cl)
    box = metric_boxes(cl)
    corners = []
    pieces = out.pieces
    single = len(order) == 1
    for rank, si in enumerate(order):
        sp = spans[si]
        if tp is None:
            sts = translate(0.0, sp.shift)
        else:
            sts = _EYE
        if len(box):
            corners.append(_apply(sts, box))
        mask = None if single else cl.span == si
        for kind in ('overline', 'underline'):
            if (si, kind) in env.decor:
                p = _decoration_path(cl, mask, sp, kind, sts, vertical)
                if p is not None:
                    pieces.append((rank, kind, p))
        g = np.flatnonzero(gvis) if mask is None else np.flatnonzero(mask[cl.g_cluster] & gvis)
        if len(g):
            _glyph_pieces(cl, g, sts, gm, rank, pieces)
        if (si, 'line-through') in env.decor:
            p = _decoration_path(cl, mask, sp, 'line-through', sts, vertical)
            if p is not None:
                pieces.append((rank, 'line-through', p))
    if corners:
        c = out.corners = np.concatenate(corners) if len(corners) > 1 else corners[0]
        if len(c):
            lo, hi = c.min(0), c.max(0)
            out.box = (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
    return out


def _color_of(cl, g):
    """``(descriptions, flags)`` of glyphs ``g`` of a chunk: each glyph's
    colour description (:meth:`raster.fonts.color.ColorFont.glyph`) or
    None, and (len(g),) bool; None when no glyph has one."""
    fi = cl.g_font[g]
    gid = cl.g_gid[g]
    flags = None
    for k, font in enumerate(cl.fonts):
        cf = font.color
        if cf is None:
            continue
        sel = fi == k
        ids = gid[sel]
        ok = (ids >= 0) & (ids < len(cf.mask))
        hit = np.zeros(len(ids), bool)
        hit[ok] = cf.mask[ids[ok]]
        if hit.any():
            if flags is None:
                flags = np.zeros(len(g), bool)
            flags[np.flatnonzero(sel)[hit]] = True
    if flags is None:
        return None
    descs = [None] * len(g)
    for j in np.flatnonzero(flags).tolist():
        descs[j] = cl.fonts[int(fi[j])].color.glyph(int(gid[j]))
        if descs[j] is None:
            flags[j] = False
    return (descs, flags) if flags.any() else None


def _glyph_pieces(cl, g, sts, gm, rank, pieces):
    """Append the pieces of glyphs ``g`` of one span: runs of outline
    glyphs as one ``'glyphs'`` Path, colour glyphs as ``'color'`` pieces
    (tuples of (font, glyph id, description, (3, 3) glyph-space to
    chunk-frame matrix)), in glyph order."""
    colour = _color_of(cl, g)
    if colour is None:
        p = _outline_path(cl, g, sts if gm is None else compose(sts[None], gm[g]))
        if p is not None:
            pieces.append((rank, 'glyphs', p))
        return
    descs, flags = colour
    if gm is None:              # translated clusters: the glyph matrices
        s = cl.g_scale[g]
        gc = cl.g_cluster[g]
        ms = compose(sts[None], translate(cl.x[gc] + cl.g_x[g] * s, cl.y[gc] - cl.g_y[g] * s),
                     scale(s, -s))
    else:
        ms = compose(sts[None], gm[g])
    cuts = (np.flatnonzero(flags[1:] != flags[:-1]) + 1).tolist()
    for a, z in zip([0] + cuts, cuts + [len(g)]):
        if flags[a]:
            items = tuple((cl.fonts[int(cl.g_font[g[j]])], int(cl.g_gid[g[j]]), descs[j], ms[j])
                          for j in range(a, z))
            pieces.append((rank, 'color', items))
        else:
            p = _outline_path(cl, g[a:z], ms[a:z])
            if p is not None:
                pieces.append((rank, 'glyphs', p))


def _moved_color(items, base):
    """Colour glyph items of a chunk frame in user space (``base`` as for
    _moved_points)."""
    if base is None:
        return items
    if isinstance(base, tuple):
        out = []
        for f, gid, d, m in items:
            m = m.copy()
            m[0, 2] += base[0]
            m[1, 2] += base[1]
            out.append((f, gid, d, m))
        return tuple(out)
    bm = np.vstack([base.matrix, [0.0, 0.0, 1.0]])
    return tuple((f, gid, d, bm @ m) for f, gid, d, m in items)


def _color_nodes(sp, items, st, cache, bbox):
    """The nodes of colour glyph items of span ``sp`` (user space): one
    Group per glyph (see :mod:`raster.parser.colorglyph`).  Inside a clip
    path the outlines are used instead, filled like other glyphs."""
    if sp.inh.get('visibility', 'visible') in ('hidden', 'collapse'):
        return []
    # colour glyphs (and the filters and images they may use) load with
    # the first one drawn
    from .colorglyph import color_glyph_node
    out = []
    fg = None
    plain = []
    for font, gid, desc, m in items:
        if st.clip:
            plain.append(font.outline(gid).transform(Affine.from_matrix(m)))
            continue
        if fg is None:
            fg = _foreground(sp, st, cache, bbox)
        node = color_glyph_node(font, desc, Affine.from_matrix(m), fg, cache)
        if node is None:
            continue
        if not abs(m[:2, 2]).max() <= limits.MAX_COORD:
            cache.warn('text-coord', 'text beyond the coordinate limit is not rendered')
            continue
        out.append(node)
    if plain:
        node = _paint_node(sp, Path.concat(plain), st, cache, bbox)
        if node is not None:
            out.append(node)
    return out


def _foreground(sp, st, cache, bbox):
    """Straight RGBA of a colour glyph's foreground colour: the span's fill
    when it is a solid colour (its fill-opacity applied), else black."""
    fill, _ = fill_and_stroke(sp.inh, sp.ctx, Path.empty(), st, cache, box=bbox)
    if fill is not None and isinstance(fill.paint, SolidPaint):
        r, g, b, a = fill.paint.color
        return (r, g, b, a * fill.opacity)
    return (0.0, 0.0, 0.0, 1.0)


def _warn_missing(chars, cache):
    """One warning per document: characters without a glyph in any font."""
    shown = ' '.join('U+%04X' % ord(c) for c in chars[:5]) + (' ...' if len(chars) > 5 else '')
    cache.warn('text-missing-glyphs', 'no font has a glyph for some characters (drawn as '
               'boxes): %s' % shown)


def _moved_points(pts, base):
    """Points (K, 2) of a chunk frame in user space: ``base`` is None (the
    same), a translation ``(x, y)`` or an Affine."""
    if base is None:
        return pts
    if isinstance(base, tuple):
        return pts + base
    return base.apply(pts)


def _moved_path(path, base):
    """A chunk-frame Path in user space (``base`` as for _moved_points)."""
    if base is None:
        return path
    if isinstance(base, tuple):
        return Path(path.verbs, path.points + base, _checked=True)
    return path.transform(base)


def _apply(m, pts):
    """Points (P, 2) under one 3x3 affine."""
    return pts @ m[:2, :2].T + m[:2, 2]


def _path_extent(path):
    pts = path.points
    if not len(pts):
        return (0.0, 0.0, -1.0, -1.0)
    lo, hi = pts.min(0), pts.max(0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _span_shift(sp, vertical):
    """Downward shift of a span's baseline: its baseline-shift values (those
    of the span and its ancestors inside the text element, summed) and,
    in horizontal text, its dominant or alignment baseline."""
    shift = 0.0
    e = sp
    font = sp.font
    while e is not None and e.parent is not None:       # the text element adds nothing
        v = e.own.get('baseline-shift', e.el.get('baseline-shift') if e.el is not None else None)
        if v is not None:
            shift += _baseline_shift_value(v.strip(), e, font, sp.fs)
        e = e.parent
    if not vertical:
        shift += _dominant(sp)
    return shift


def _baseline_shift_value(v, e, font, fs):
    if v == 'baseline' or font is None:
        return 0.0
    s = fs / font.upem
    if v == 'sub':
        return font.subscript_y * s
    if v == 'super':
        return -font.superscript_y * s
    if v.endswith('%'):
        try:
            return -float(v[:-1]) / 100.0 * e.fs
        except ValueError:
            return 0.0
    L = parse_length(v, 'other', e.ctx)
    return 0.0 if L is None else -float(L)


def _decorations(el, spans, cache):
    """``{(span index, kind): span whose fill and stroke paint it}``: a
    span is decorated by a kind declared on it, on an ancestor inside the
    text, or on an ancestor of the text element; the paint is that of the
    nearest span declaring it (the text element for declarations outside
    it), as usvg resolves it."""
    outer = set()
    for d in _ancestor_decorations(el, cache):
        outer.update(_decoration(d))
    own = [set(_decoration(sp.own.get('text-decoration', sp.el.get('text-decoration')
                                      if sp.el is not None else None))) for sp in spans]
    if not outer and not any(own):
        return {}
    index = {id(sp): k for k, sp in enumerate(spans)}
    out = {}
    for k, sp in enumerate(spans):
        for kind in ('underline', 'overline', 'line-through'):
            e = sp
            found = None
            while e is not None:
                j = index.get(id(e))
                if j is not None and kind in own[j]:
                    found = e
                    break
                e = e.parent
            if found is None and kind in outer:
                found = spans[0]
            if found is not None:
                out[(k, kind)] = found
    return out


def _decoration_path(cl, mask, sp, kind, span_ts, vertical):
    """The Path of one decoration of one span in a chunk (``span_ts``: the
    span's (3, 3) frame in the chunk's), or None; ``mask`` (C,) bool
    selects the span's clusters (None: all)."""
    if sp.font is None:
        return None
    widths, mats = decoration_pieces(cl, np.ones(len(cl), bool) if mask is None else mask)
    if not len(widths):
        return None
    f = sp.font
    s = sp.fs / f.upem
    th = f.underline_thickness * s
    if vertical:
        h = (f.ascender - f.descender) * s
        off = {'underline': h / 2, 'overline': -h / 2, 'line-through': 0.0}[kind]
    else:
        off = {'underline': -f.underline_position * s, 'overline': -f.ascender * s,
               'line-through': -f.strikeout_position * s}[kind]
    ok = widths > 0
    if not ok.any():
        return None
    widths = widths[ok]
    if not isinstance(mats, tuple):
        mats = mats[ok]
    k = len(widths)
    xs = np.stack([np.zeros(k), widths, widths, np.zeros(k)], 1)
    ys = np.tile(np.array([-th / 2, -th / 2, th / 2, th / 2]) + off, (k, 1))
    if isinstance(mats, tuple):          # translations of the pieces
        mats = translate(mats[0][ok], mats[1][ok])
    m = compose(span_ts[None], mats)
    X = m[:, 0, 0, None] * xs + m[:, 0, 1, None] * ys + m[:, 0, 2, None]
    Y = m[:, 1, 0, None] * xs + m[:, 1, 1, None] * ys + m[:, 1, 2, None]
    pts = np.stack([X, Y], 2).reshape(-1, 2)
    verbs = np.tile(np.array([0, 1, 1, 1, 4], np.uint8), k)
    return Path.from_arrays(verbs, pts)


def _outline_path(cl, g, mats):
    fi = cl.g_font[g]
    gid = cl.g_gid[g]
    if len(cl.fonts) == 1:
        verbs, P, npts = cl.fonts[0].outlines(gid)
    else:
        cuts = (np.flatnonzero(fi[1:] != fi[:-1]) + 1).tolist()
        parts = [cl.fonts[int(fi[a])].outlines(gid[a:z])
                 for a, z in zip([0] + cuts, cuts + [len(fi)])]
        verbs = np.concatenate([v for v, _, _ in parts])
        P = np.concatenate([p for _, p, _ in parts])
        npts = np.concatenate([c for _, _, c in parts])
    if not len(verbs):
        return None
    if mats.ndim == 2:          # translated clusters: scale, flip and move each glyph
        s = cl.g_scale[g]
        gc = cl.g_cluster[g]
        ox = cl.x[gc] + cl.g_x[g] * s + mats[0, 2]
        oy = cl.y[gc] - cl.g_y[g] * s + mats[1, 2]
        S = np.repeat(s, npts)
        out = np.empty_like(P)
        out[:, 0] = P[:, 0] * S + np.repeat(ox, npts)
        out[:, 1] = np.repeat(oy, npts) - P[:, 1] * S
        return Path(verbs, out, _checked=True)
    M = np.repeat(mats, npts, axis=0)
    out = np.empty_like(P)
    out[:, 0] = M[:, 0, 0] * P[:, 0] + M[:, 0, 1] * P[:, 1] + M[:, 0, 2]
    out[:, 1] = M[:, 1, 0] * P[:, 0] + M[:, 1, 1] * P[:, 1] + M[:, 1, 2]
    # every outline is a valid path starting with a move: so is the whole
    return Path(verbs, out, _checked=True)


_FEATURE = re.compile(r"""\s*(['"])([\x20-\x7e]{4})\1(?:\s+(on|off|\d+))?\s*$""")


def _features(inh, no_kern):
    """HarfBuzz features of a span: ``font-feature-settings`` (CSS Fonts 4:
    ``"tag" [on | off | integer]`` items; an invalid list is ignored as a
    whole), ``smcp`` for ``font-variant: small-caps``, ``kern`` off for
    ``font-kerning: none`` or ``kerning: 0``; None when there are none."""
    feats = {}
    v = (inh.get('font-feature-settings') or 'normal').strip()
    if v != 'normal':
        items = []
        for item in v.split(','):
            m = _FEATURE.match(item)
            if m is None:
                items = []
                break
            val = m.group(3)
            items.append((m.group(2), 1 if val in (None, 'on') else 0 if val == 'off'
                          else int(val)))
        for tag, val in items:
            feats[tag] = val
    variant = (inh.get('font-variant') or 'normal').split()
    if 'small-caps' in variant or (inh.get('font-variant-caps') or '').strip() == 'small-caps':
        feats['smcp'] = 1
    if no_kern:
        feats['kern'] = 0
    return feats or None


def _parent_weight(el, cache):
    """Computed font-weight of the document parent of ``el`` (relative
    keywords resolved along the ancestor chain)."""
    parent = el.getparent()
    return 400 if parent is None else _ancestry(parent, cache)[0]


def _ancestry(el, cache):
    """``(font-weight, text-decoration values)`` that ``el`` passes on:
    its computed weight (relative keywords resolved along the ancestor
    chain) and the decorations declared on it and its ancestors, nearest
    first.  Remembered per element for the whole document."""
    memo = cache.table('text_ancestry')
    chain = []
    e = el
    while e is not None and e not in memo:
        chain.append(e)
        e = e.getparent()
    w, decos = (400, ()) if e is None else memo[e]
    for e in reversed(chain):
        d = cache.styles.get(e)
        if d:
            if 'font-weight' in d and d['font-weight'] != 'inherit':
                w = _weight(d['font-weight'], w)
            if d.get('text-decoration'):
                decos = (d['text-decoration'],) + decos
        memo[e] = (w, decos)
    return w, decos


_STRETCH_PCT = {'ultra-condensed': 50, 'extra-condensed': 62.5, 'condensed': 75,
                'semi-condensed': 87.5, 'normal': 100, 'semi-expanded': 112.5,
                'expanded': 125, 'extra-expanded': 150, 'ultra-expanded': 200}


def _variations(sp, style, stretch):
    """Variation coordinates of a span: automatic ones from font-weight,
    font-stretch and font-style, overridden by font-variation-settings."""
    coords = {'wght': sp.weight, 'opsz': sp.fs}     # font-optical-sizing: auto
    if stretch in _STRETCH_PCT:
        coords['wdth'] = _STRETCH_PCT[stretch]
    elif stretch.endswith('%'):
        try:
            coords['wdth'] = float(stretch[:-1])
        except ValueError:
            pass
    if style == 'oblique':
        coords['slnt'] = -14.0
    elif style == 'italic':
        coords['ital'] = 1.0
    v = (sp.inh.get('font-variation-settings') or 'normal').strip()
    if v != 'normal':
        for item in v.split(','):
            m = re.fullmatch(r"\s*(['\"])(.{4})\1\s+([-+0-9.eE]+)\s*", item)
            if m is None:
                return coords       # invalid list: automatic values only
        for item in v.split(','):
            m = re.fullmatch(r"\s*(['\"])(.{4})\1\s+([-+0-9.eE]+)\s*", item)
            try:
                coords[m.group(2)] = float(m.group(3))
            except ValueError:
                pass
    return coords


def _decoration(value):
    """Decoration kinds of one ``text-decoration`` value (space-separated
    keywords; anything else makes the whole value invalid: none)."""
    if not value:
        return ()
    words = value.split()
    if not all(w in ('underline', 'overline', 'line-through', 'none') for w in words):
        return ()
    return tuple(w for w in words if w != 'none')


def _ancestor_decorations(el, cache):
    """text-decoration values declared on document ancestors of ``el``
    (they decorate the text too), nearest first."""
    parent = el.getparent()
    return [] if parent is None else list(_ancestry(parent, cache)[1])


def _preserved(e):
    while e is not None:
        v = e.get(_XML_SPACE)
        if v is not None:
            return v == 'preserve'
        e = e.getparent()
    return False


def _dominant(sp):
    """Downward shift of the glyphs making the dominant baseline sit at y."""
    v = (sp.own.get('alignment-baseline') or 'auto').strip()
    if v in ('auto', 'baseline', 'inherit'):
        v = (sp.inh.get('dominant-baseline') or 'auto').strip()
    if sp.vertical and v == 'auto':
        v = 'central'
    v = {'before-edge': 'text-before-edge', 'after-edge': 'text-after-edge'}.get(v, v)
    f = sp.font
    if f is None:
        return 0.0
    s = sp.fs / f.upem
    if v == 'central':
        return (f.ascender + f.descender) * 0.5 * s
    if v == 'middle':
        return f.x_height * 0.5 * s
    if v in ('hanging',):
        return f.ascender * 0.8 * s
    if v == 'mathematical':
        return f.ascender * 0.5 * s
    if v in ('text-before-edge', 'text-top'):
        return f.ascender * s
    if v in ('text-after-edge', 'text-bottom', 'ideographic'):
        return f.descender * s
    return 0.0


def _load_font(db, face, cache):
    """The Font of a matched face; a face that cannot be used (no outlines,
    a broken file) warns and is replaced by the default family's face, else
    by the first usable face."""
    if face is None:
        return None
    try:
        return Font.load(face)
    except FontError as e:
        cache.warn('text-font-' + face.path, 'font not usable, default family used: %s' % (e,))
    for other in [db.match([])] + list(db.faces):
        if other is None or other == face:
            continue
        try:
            return Font.load(other)
        except FontError:
            continue
    return None


def _fallback_font(db, ch, font, sp, cache):
    """The font to draw character ``ch`` with when ``font`` has no glyph
    for it (``font`` itself when no face has one): CSS Fonts' order, the
    span's other ``font-family`` entries first (their best face for the
    span's weight, style and stretch), then every face
    (:meth:`raster.fonts.FontDB.fallback_face`).  The faces of a family
    split by ``unicode-range`` are tried one by one."""
    cp = ord(ch)
    for fam in sp.families:
        cands = db.match_family([fam])
        if not cands:
            continue
        best = best_face(cands, sp.weight, sp.style, _STRETCH_CLASS.get(sp.stretch, 5))
        # a family split by unicode-range: its faces with the same weight,
        # style and stretch make one face (in the family's order)
        same = [best] + [f for f in cands if f != best and f.unicode_range
                         and (f.weight, f.style, f.stretch) ==
                         (best.weight, best.style, best.stretch)]
        for face in same:
            if face == font.face or not db.has_char(face, cp):
                continue
            try:
                return Font.load(face)
            except RasterError:
                continue
    face = db.fallback_face(font.face, ch)
    if face is None:
        return font
    try:
        return Font.load(face)
    except RasterError:
        return font


_STRETCH_CLASS = {'ultra-condensed': 1, 'extra-condensed': 2, 'condensed': 3,
                  'semi-condensed': 4, 'normal': 5, 'semi-expanded': 6, 'expanded': 7,
                  'extra-expanded': 8, 'ultra-expanded': 9}


def _families(value):
    """The parsed ``font-family`` list of a span (a tuple: a memo key)."""
    return tuple(parse_font_family(value))


def _text_path_geometry(tp_el, ctx, cache, tolerance=0.01):
    """(edges (E, 2, 2), cumulative start lengths (E,), start offset) of
    the path a textPath follows, or None when it has no usable path; the
    path is flattened within ``tolerance`` (in its user units: the
    callers ask for 0.01, and 0.01 device pixels when the text is scaled
    up, so that a tiny path scaled up is followed as closely as a large
    one)."""
    # the SVG 2 ``path`` attribute is not used (resvg ignores it too)
    href = tp_el.get('{http://www.w3.org/1999/xlink}href') or tp_el.get('href')
    if not href or not href.startswith('#'):
        return None
    tgt = cache.by_id.get(href[1:].strip())
    name = local_name(tgt) if tgt is not None else None
    if name not in ('path', 'rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon'):
        return None
    ts = tgt.get('transform')
    t = parse_transform(ts) if ts else None
    path = geometry(tgt, name, ctx, tolerance, cache)     # basic shapes too (SVG 2)
    if path is None or not len(path.verbs):
        return None
    if t is not None:
        path = path.transform(t)
    pl = flatten(path, tolerance)
    if not len(pl):
        return None
    edges = pl.edges(close_all=False)
    if not len(edges):
        return None
    seg = np.hypot(*(edges[:, 1] - edges[:, 0]).T)
    cum = np.r_[0.0, np.cumsum(seg)]
    total = float(cum[-1])
    if not total > 0:
        return None
    so = (tp_el.get('startOffset') or '0').strip()
    if so.endswith('%'):
        try:
            off = float(so[:-1]) / 100.0 * total
        except ValueError:
            off = 0.0
    else:
        v = parse_length(so, 'x', ctx)
        off = 0.0 if v is None else float(v)
    return edges, cum, off


def _span_fonts(db, cache):
    """A function ``(font-family value, weight, style, stretch) -> (face,
    Font or None)`` with its answers remembered for the whole document: a
    document's text elements share a few font descriptions."""
    memo = cache.table('text_fonts')

    def fonts_of(family, weight, style, stretch):
        key = (family, weight, style, stretch)
        r = memo.get(key)
        if r is None:
            face = db.match(parse_font_family(family), weight, style, stretch)
            r = memo[key] = (face, _load_font(db, face, cache))
        return r
    return fonts_of


def _paint_node(sp, path, st, cache, box=None, vis_span=None):
    """A PathNode of ``path`` painted with the fill and stroke of span
    ``sp`` (objectBoundingBox units resolved against the text's ``box``,
    x0 y0 x1 y1); None when hidden (``visibility`` of ``vis_span``, default
    ``sp``) or not painted."""
    inh = sp.inh
    vis = (vis_span or sp).inh.get('visibility', 'visible')
    if vis in ('hidden', 'collapse'):
        return None
    fill, stroke = fill_and_stroke(inh, sp.ctx, path, st, cache, box=box)
    if fill is None and stroke is None:
        return None
    return PathNode(id='', path=path, fill=fill, stroke=stroke,
                    paint_order=paint_order(inh.get('paint-order')))

