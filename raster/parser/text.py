"""SVG text converted to paths (usvg's "text as paths" model).

:func:`convert_text` converts every ``text`` element.  It lays the text
out and appends ordinary :class:`~raster.tree.PathNode` objects: the glyph
outlines of each run of characters sharing one style, in the text
element's user space (x right, y down), filled and stroked as shapes are.

What is laid out:

* characters of ``text`` and nested ``tspan`` (and ``a``) elements, with
  ``xml:space`` handling (default: newlines removed, tabs to spaces, runs of
  spaces collapsed, leading and trailing spaces dropped; ``preserve``:
  newlines and tabs become spaces);
* ``x``/``y``/``dx``/``dy`` lists, one value per character, on any element
  (an absolute ``x`` or ``y`` starts a new *text chunk*), ``rotate`` (one
  angle per character about its glyph origin, the last angle repeating);
* fonts from :mod:`raster.fonts` (``font-family``/``-weight``/``-style``/
  ``-stretch``; characters the chosen face lacks are taken from the first
  other face that has them), shaping with HarfBuzz, outlines with fontTools;
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
array operation per run of glyphs of one span.

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
from ..geometry.path import Path
from ..geometry.transform import Affine
from ..tree import PathNode
from .effects import wrap
from .shapes import fill_and_stroke, geometry
from .style import (is_displayed, length_context, local_name, paint_order, passes_conditions,
                    style_of, transform_of)
from .values import parse_length, parse_length_list, parse_number_list, parse_transform

__all__ = ['convert_text', 'collapse_whitespace']

_XML_SPACE = '{http://www.w3.org/XML/1998/namespace}space'
_SPAN_NAMES = frozenset(['tspan', 'a'])
_WEIGHTS = {'normal': 400, 'bold': 700}
_DB_CACHE = {}
_SHAPED_LIMIT = 4096    # shaped chunks remembered per build
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
                 'weight', 'parent', 'decor', 'vertical', 'features')

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
    memo = cache.table('text')
    db = memo.get('fontdb')
    if db is None:
        dirs = tuple(str(d) for d in (cache.options.font_dirs or ()))
        db = memo['fontdb'] = cached(_DB_CACHE, dirs, lambda: FontDB(dirs), 16)
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
        with log_warnings('fontTools'):         # a broken font's log lines: our warnings
            _build(el, state, cache, parent)
    except Exception as e:      # text must never break a document (RasterError too)
        del parent[mark:]
        cache.warn('text-error', 'text element not rendered: %s' % (e,))


def _build(el, state, cache, out):
    st = state
    pinh, pown = state.inh, state.own
    inh, own = style_of(el, pinh, pown, cache)
    ctx = length_context(inh, st, cache)
    t = transform_of(el, own, ctx)
    if t is None:
        return
    wm = (inh.get('writing-mode') or 'lr-tb').strip()
    vertical = wm in ('tb', 'tb-rl', 'vertical-rl', 'vertical-lr')
    if vertical:
        cache.warn('text-vertical', 'vertical writing modes are approximated: every glyph is '
               'turned a quarter turn clockwise (no upright CJK, no vertical metrics)')
    db = _font_db(cache)
    if not db.faces:
        cache.warn('text-nofont', 'no fonts available (font_dirs=%r); text is not rendered'
               % (tuple(cache.options.font_dirs or ()),))
        return
    # -- collect characters ---------------------------------------------------
    chars = []          # characters after whitespace processing
    owner = []          # span index of each character
    spans = []
    lists = []          # (start index, attr name, values)
    rot = []            # [start index, angles, element] (last angle repeats)
    ends = {}           # element -> index after its last character
    path_ranges = []    # (first char, end, text path geometry)
    state = {'prev': True}

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
        spans.append(sp)
        add_lists(e, ectx, len(chars))

        def add_text(s):
            if not s:
                return
            txt, state['prev'] = collapse_whitespace(s, preserve, state['prev'])
            chars.extend(txt)
            owner.extend([si] * len(txt))
        if content is not None:         # tref: the referenced element's text
            add_text(content)
            ends[e] = len(chars)
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
                    tp = _text_path_geometry(ch, cctx, cache)
                    if tp is not None:
                        first = len(chars)
                        sp_pres = ch.get(_XML_SPACE)
                        walk(ch, cinh, cown, cctx, sp,
                             preserve if sp_pres is None else sp_pres == 'preserve')
                        path_ranges.append((first, len(chars), tp))
            elif name == 'tref':
                href = ch.get('{http://www.w3.org/1999/xlink}href') or ch.get('href') or ''
                tgt = cache.by_id.get(href[1:].strip()) if href.startswith('#') else None
                if tgt is not None and is_displayed(ch, cache):
                    cinh, cown = style_of(ch, einh, eown, cache)
                    sp_pres = ch.get(_XML_SPACE)
                    walk(ch, cinh, cown, length_context(cinh, st, cache), sp,
                         preserve if sp_pres is None else sp_pres == 'preserve',
                         ''.join(t for t in tgt.itertext() if isinstance(t, str)))
            add_text(ch.tail)
        ends[e] = len(chars)

    root_span = _Span(None, pinh, pown, ctx, None, _parent_weight(el, cache))
    walk(el, inh, own, ctx, root_span, el.get(_XML_SPACE) == 'preserve')
    spans[0].parent = None
    # default mode: drop trailing spaces
    while chars and chars[-1] == ' ' and not _preserved(spans[owner[-1]].el):
        chars.pop()
        owner.pop()
    n = len(chars)
    if n == 0:
        return
    owner_l = owner
    owner = np.asarray(owner_l, np.int64)
    ax = np.full(n, np.nan)
    ay = np.full(n, np.nan)
    arrs = {'x': ax, 'y': ay}       # dx, dy, angle: None while all zero
    for start, name, vals, e in lists:
        k = min(len(vals), min(ends.get(e, n), n) - start)   # own characters only
        if k > 0:
            a = arrs.get(name)
            if a is None:
                a = arrs[name] = np.zeros(n)
            a[start:start + k] = vals[:k]
    dx, dy = arrs.get('dx'), arrs.get('dy')
    angle = np.zeros(n) if rot else None
    for start, vals, e in rot:
        end = min(ends.get(e, n), n)
        if start >= end:
            continue
        k = min(len(vals), end - start)
        angle[start:start + k] = vals[:k]
        angle[start + k:end] = vals[-1]
    if math.isnan(ax[0]):
        ax[0] = 0.0
    if math.isnan(ay[0]):
        ay[0] = 0.0
    # -- fonts and per-span metrics --------------------------------------------
    fonts_of = _span_fonts(db, cache)
    for sp in spans:
        i = sp.inh
        style = (i.get('font-style') or 'normal').strip()
        stretch = (i.get('font-stretch') or 'normal').strip()
        sp.face, sp.font = fonts_of(i.get('font-family', ''), sp.weight, style, stretch)
        if sp.font is not None and sp.font.axes:
            sp.font = sp.font.variant(_variations(sp, style, stretch))
        sp.ls = _spacing(i.get('letter-spacing'), sp.ctx)
        tl = sp.el.get('textLength')
        sp.tl = None
        if tl is not None and tl.strip() != 'inherit':
            v = parse_length(tl, 'x', sp.ctx)
            sp.tl = float(v) if v is not None and v >= 0 else None
        sp.ws = _spacing(i.get('word-spacing'), sp.ctx)
        # baseline-shift applies to tspans; on the text element itself it
        # has no effect (as in resvg)
        sp.shift = (sp.parent.shift + _baseline_shift(sp)) if sp.parent is not None else 0.0
        decos = [sp.own.get('text-decoration', sp.el.get('text-decoration'))]
        if sp is spans[0]:
            decos += _ancestor_decorations(el, cache)
        sp.decor = tuple(w for d in decos for w in _decoration(d))
        kern = (i.get('font-kerning') or 'auto').strip()
        no_kern = kern == 'none' or (i.get('kerning') or 'auto').strip() == '0'
        sp.features = {'kern': False} if no_kern else None
        sp.vertical = vertical
    sm = _SpanMetrics(spans, owner, chars)
    # -- layout ------------------------------------------------------------------
    brk = ~np.isnan(np.fmin(ax, ay))     # an absolute x or y
    onpath = np.full(n, -1, np.int64) if path_ranges else None
    for pi, (p0, p1, tp) in enumerate(path_ranges):
        p1 = min(p1, n)
        if p0 >= p1:
            continue
        ax[p0:p1] = np.nan
        ay[p0:p1] = np.nan
        brk[p0:p1] = False
        brk[p0] = True
        if p1 < n:
            brk[p1] = True
        onpath[p0:p1] = pi
    bounds = np.flatnonzero(brk).tolist() + [n]
    glyph_runs = []     # (span index, Path in user space)
    under, over = [], []
    cur_x = cur_y = 0.0
    # vertical text advances along y: dy moves along the line, dx across
    # it (a positive dx to the right is a negative glyph-frame y)
    along, across = (dy, None if dx is None else -dx) if vertical else (dx, dy)
    for c0, c1 in zip(bounds[:-1], bounds[1:]):
        x0 = ax[c0] if not math.isnan(ax[c0]) else cur_x
        y0 = ay[c0] if not math.isnan(ay[c0]) else cur_y
        if len(spans) == 1:     # shaped like any chunk of the same text and style
            shaped = _shape_single(db, ''.join(chars[c0:c1]), spans[0], cache)
        else:
            shaped = _shape_chunk(db, chars, owner_l, spans, c0, c1)
        res = _place_chunk(shaped, sm, c0, c1, along, across, angle)
        adj = _text_length_spacing(spans, sm, owner[c0:c1], res[1], res[2])
        if adj is not None:
            res = _place_chunk(shaped, sm, c0, c1, along, across, angle, adj)
        gl, char_l, char_r, width, end_dy, cdy = res
        anchor = (spans[owner_l[c0]].inh.get('text-anchor') or 'start').strip()
        shift = 0.0
        if anchor == 'middle':
            shift = -width * 0.5
        elif anchor == 'end':
            shift = -width
        ox, oy = x0 + shift, y0
        cur_x, cur_y = ox + width, y0 + end_dy
        if onpath is not None and onpath[c0] >= 0:
            tp = path_ranges[int(onpath[c0])][2]
            gl, end = _on_path(gl, tp, tp[2] + shift)
            ox = oy = 0.0
            cur_x, cur_y = end
            char_l = char_r = None
        elif vertical:
            # vertical: the chunk runs down a line through (x0, y0), each
            # glyph turned clockwise and centred on it (central baseline)
            big = 1e7
            tp = (np.array([[[x0, y0 - big], [x0, y0 + big]]]), np.array([0.0, 2 * big]), big)
            gl, end = _on_path(gl, tp, big + shift)
            ox = oy = 0.0
            cur_x, cur_y = end
            char_l = char_r = None
        # glyph outlines, grouped by consecutive owner span
        if len(gl):
            g_span = gl.span
            cuts = [] if len(spans) == 1 else \
                (np.flatnonzero(g_span[1:] != g_span[:-1]) + 1).tolist()
            for a, z in zip([0] + cuts, cuts + [len(gl)]):
                p = _glyph_path(gl.take(slice(a, z)) if cuts else gl, ox, oy)
                if len(p.verbs):
                    glyph_runs.append((int(g_span[a]), p))
        # decorations of every span carrying text-decoration, over its chars
        for si, sp in enumerate(spans):
            if not sp.decor or char_l is None:
                continue
            mask = sm.descends[si][owner[c0:c1]]
            if not mask.any():
                continue
            idx = np.flatnonzero(mask)
            f = sp.font
            if f is None:
                continue
            s = sp.fs / f.upem
            # one line piece per run of characters on the same dy level
            cuts = np.flatnonzero((np.diff(idx) != 1) | (np.diff(cdy[idx]) != 0)) + 1
            for grp in np.split(idx, cuts):
                left = float(char_l[grp].min()) + ox
                right = float(char_r[grp].max()) + ox
                if not right > left:
                    continue
                base = oy + float(cdy[grp[0]]) + sp.shift + _dominant(sp)
                for kind in sp.decor:
                    if kind == 'underline':
                        th = f.underline_thickness * s
                        yc = base - f.underline_position * s
                        under.append((si, _rect(left, yc - th / 2, right, yc + th / 2)))
                    elif kind == 'overline':
                        th = f.underline_thickness * s
                        yc = base - f.ascender * s
                        under.append((si, _rect(left, yc - th / 2, right, yc + th / 2)))
                    else:
                        th = f.strikeout_size * s
                        yc = base - f.strikeout_position * s
                        over.append((si, _rect(left, yc, right, yc + th)))
    kids = []
    for si, p in under + glyph_runs + over:
        big = np.abs(p.points).max() if len(p.points) else 0.0
        if not big <= limits.MAX_COORD:
            if not np.isfinite(big):    # (glyph paths are not validated)
                Path.from_arrays(p.verbs, p.points)     # raises PathError
            cache.warn('text-coord', 'text beyond the coordinate limit is not rendered')
            continue
        node = _paint_node(spans[si], p, st, cache)
        if node is not None:
            kids.append(node)
    out.extend(wrap(el, own, t, kids, st, cache))


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


def _rect(x0, y0, x1, y1):
    return Path.polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])


def _baseline_shift(sp):
    v = sp.own.get('baseline-shift', sp.el.get('baseline-shift'))
    if v is None:
        return 0.0
    v = v.strip()
    f = sp.font
    if v == 'baseline' or f is None:
        return 0.0
    s = sp.fs / f.upem
    if v == 'sub':
        return f.subscript_y * s
    if v == 'super':
        return -f.superscript_y * s
    if v.endswith('%'):
        try:
            return -float(v[:-1]) / 100.0 * sp.fs
        except ValueError:
            return 0.0
    L = parse_length(v, 'other', sp.ctx)
    return 0.0 if L is None else -float(L)


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


def _fallback_font(db, ch, font, cache={}):
    key = (id(db), ch)
    if key in cache:
        return cache[key]
    r = font
    for face in db.fallback_faces(font.face):
        try:
            f = Font.load(face)
        except RasterError:
            continue
        if f.has_char(ch):
            r = f
            break
    if len(cache) > 10000:
        cache.clear()
    cache[key] = r
    return r


def _text_path_geometry(tp_el, ctx, cache):
    """(edges (E, 2, 2), cumulative start lengths (E,), start offset) of
    the path a textPath follows, or None when it has no usable path."""
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
    path = geometry(tgt, name, ctx, 0.01, cache)     # basic shapes too (SVG 2)
    if path is None or not len(path.verbs):
        return None
    if t is not None:
        path = path.transform(t)
    pl = flatten(path, 0.01)
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


def _on_path(glyphs, tp, offset):
    """Move chunk-local glyphs onto a text path: each glyph's horizontal
    middle goes to the point at arc length ``offset + x + advance / 2``,
    the glyph turned to the path's direction there; glyphs off the path's
    ends are dropped.  Returns ``(glyphs, end point)``."""
    edges, cum, _ = tp
    total = cum[-1]
    if not len(glyphs):
        return glyphs, tuple(edges[-1, 1])
    gx, gy, adv = glyphs.x, glyphs.y, glyphs.adv
    mid = offset + gx + adv * 0.5
    keep = (mid >= 0) & (mid <= total)
    i = np.clip(np.searchsorted(cum, mid, 'right') - 1, 0, len(edges) - 1)
    a, bpt = edges[i, 0], edges[i, 1]
    seg = cum[i + 1] - cum[i]
    tt = np.where(seg > 0, (mid - cum[i]) / np.where(seg > 0, seg, 1.0), 0.0)
    P = a + (bpt - a) * tt[:, None]
    th = np.arctan2(bpt[:, 1] - a[:, 1], bpt[:, 0] - a[:, 0])
    c, s = np.cos(th), np.sin(th)
    lx, ly = -adv * 0.5, gy
    ox = P[:, 0] + c * lx - s * ly
    oy = P[:, 1] + s * lx + c * ly
    deg = np.degrees(th)
    rot = deg if glyphs.rot is None else deg + glyphs.rot
    out = glyphs.replace(x=ox, y=oy, rot=rot).take(keep)
    # the text after the path continues where the last glyph ends (also
    # when it fell off the path's end: extrapolated along the last edge)
    end = (float(P[-1, 0] + c[-1] * adv[-1] * 0.5), float(P[-1, 1] + s[-1] * adv[-1] * 0.5))
    return out, end


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


class _SpanMetrics:
    """Arrays of one text element used by the layout of all its chunks.

    Attributes
    ----------
    owner : (n,) int64 ndarray
        Span index of every character.
    single : bool
        The element has one span only.
    fs, ys, ls : (S,) float64 ndarray, or float when ``single``
        Per span: font size, downward shift of the baseline (baseline-shift
        and dominant baseline), letter spacing.
    extra : (n,) float64 ndarray
        Spacing after every character: letter spacing (not for cursive
        scripts, whose joins it would break, as resvg does) plus word
        spacing after spaces.
    no_extra : bool
        ``extra`` is all zero.
    descends : (S, S) bool ndarray
        ``descends[i, j]``: span ``j`` is span ``i`` or nested in it.
    """

    def __init__(self, spans, owner, chars):
        self.owner = owner
        n = len(chars)
        self.single = len(spans) == 1
        if self.single:         # numbers broadcast like the arrays
            sp = spans[0]
            self.fs, self.ys, self.ls = sp.fs, sp.shift + _dominant(sp), sp.ls
        else:
            self.fs = np.array([sp.fs for sp in spans])
            self.ys = np.array([sp.shift + _dominant(sp) for sp in spans])
            self.ls = np.array([sp.ls for sp in spans])
        self.no_extra = not any(sp.ls or sp.ws for sp in spans)
        if self.no_extra:
            self.extra = np.zeros(n)
        else:
            ws = np.array([sp.ws for sp in spans])
            cps = np.fromiter(map(ord, chars), np.int64, n)
            ls = np.array([sp.ls for sp in spans])[owner]
            if cps.max() >= _CURSIVE[0][0]:
                cursive = np.zeros(n, bool)
                for lo, hi in _CURSIVE:
                    cursive |= (cps >= lo) & (cps <= hi)
                ls = np.where(cursive, 0.0, ls)
            self.extra = ls + np.where((cps == 0x20) | (cps == 0xA0), ws[owner], 0.0)
        if len(spans) == 1:
            self.descends = np.ones((1, 1), bool)
            return
        index = {id(sp): k for k, sp in enumerate(spans)}
        self.descends = np.zeros((len(spans), len(spans)), bool)
        for j, sp in enumerate(spans):
            while sp is not None:
                self.descends[index[id(sp)], j] = True
                sp = sp.parent


def _text_length_spacing(spans, sm, own_idx, char_l, char_r):
    """Extra spacing after each character of a chunk that stretches the
    elements with ``textLength`` to that length (``lengthAdjust`` spacing),
    or None when no element asks for it.

    ``sm`` is the element's :class:`_SpanMetrics`, ``own_idx`` ((m,) int64)
    the span of each character of the chunk, ``char_l``/``char_r`` ((m,)
    float64) their horizontal extents."""
    if len(own_idx) < 2 or all(sp.tl is None for sp in spans):
        return None
    if sm.single:
        natural = float(char_r.max() - char_l.min())
        return np.full(len(own_idx), (spans[0].tl - natural) / (len(own_idx) - 1))
    adj = None
    # the owners and their ancestors
    present = np.flatnonzero(sm.descends[:, own_idx].any(axis=1)).tolist()
    for si in present:
        tl = spans[si].tl
        if tl is None:
            continue
        idx = np.flatnonzero(sm.descends[si][own_idx])
        if len(idx) < 2:
            continue
        natural = float(char_r[idx].max() - char_l[idx].min())
        if adj is None:
            adj = np.zeros(len(own_idx))
        # every character, the last one too, gets the same extra (resvg)
        adj[idx] += (tl - natural) / (len(idx) - 1)
    return adj


_CURSIVE = ((0x0600, 0x08FF), (0xFB50, 0xFDFF), (0xFE70, 0xFEFF), (0x0700, 0x074F),
            (0x07C0, 0x07FF), (0x1800, 0x18AF))


class _Shaped:
    """The glyphs of one chunk as shaped, before spacing and positions.

    Attributes
    ----------
    fonts : list of Font
        Fonts used; ``fi`` indexes it.
    fi, gid, j : (G,) int64 ndarray
        Font, glyph id and (chunk-local) character of every glyph, in
        visual order run by run.
    xa, xo, yo : (G,) float64 ndarray
        Advance and offsets in font units (y up).
    upem : float or (G,) float64 ndarray
        Units per em of each glyph's font (one number for one font).
    rtl : list of (g0, g1, k)
        Glyph ranges of right-to-left runs and the run's first character.
    gaps : list of (k, e, g)
        Character ranges without any font, and the number of glyphs before.
    simple : bool
        One glyph per character in logical order (``j == arange(m)``).
    """
    __slots__ = ('fonts', 'fi', 'gid', 'j', 'xa', 'xo', 'yo', 'upem', 'rtl', 'gaps', 'simple')


def _shape_chunk(db, chars, owner, spans, c0, c1):
    """Shape characters ``c0:c1`` of one chunk (``chars``: sequence of all
    characters, ``owner``: list of their span indices); returns a
    :class:`_Shaped` (shared: not to be modified)."""
    m = c1 - c0
    # font of each character (fallback for missing glyphs)
    fonts = [spans[o].font for o in owner[c0:c1]]
    text = chars[c0:c1]
    for k, ch in enumerate(text):
        f = fonts[k]
        if f is not None and not f.has_char(ch) and ch not in ' \u00a0' and ord(ch) >= 32:
            fonts[k] = _fallback_font(db, ch, f)
    sh = _Shaped()
    sh.fonts, sh.rtl, sh.gaps = [], [], []
    parts = []          # (font index, Shaped arrays, characters)
    index = {}
    ng = 0
    k = 0
    # runs of one font are shaped together even across spans (kerning and
    # ligatures across tspan boundaries, as usvg does); each glyph is later
    # scaled by the font size of its own span
    while k < m:
        f = fonts[k]
        e = k + 1
        if text[k] == ' ':
            # leading/trailing spaces are shaped on their own: between
            # right-to-left text and the end of an LTR chunk they stay at
            # the visual end (a minimal stand-in for the bidi algorithm)
            while e < m and fonts[e] is f and text[e] == ' ':
                e += 1
        else:
            while e < m and fonts[e] is f:
                e += 1
            while e - 1 > k and text[e - 1] == ' ':
                e -= 1
        if f is None:
            sh.gaps.append((k, e, ng))
            k = e
            continue
        r = f.shape_arrays(''.join(text[k:e]), spans[owner[c0 + k]].features)
        cl = r.cluster
        fidx = index.get(id(f))
        if fidx is None:
            fidx = index[id(f)] = len(sh.fonts)
            sh.fonts.append(f)
        parts.append((fidx, r, cl + k if k else cl))
        # a right-to-left run comes back in visual order: its spacing adds
        # up from the left, i.e. from its logically last character
        if len(cl) > 1 and cl[0] > cl[-1]:
            sh.rtl.append((ng, ng + len(cl), k))
        ng += len(cl)
        k = e
    sh.simple = not sh.gaps and all(r.ordered for _, r, _ in parts)
    if len(parts) == 1:
        fidx, r, sh.j = parts[0]
        sh.gid, pos = r.gid, r.pos
        sh.fi = np.zeros(ng, np.int64)
    elif parts:
        sh.gid = np.concatenate([r.gid for _, r, _ in parts])
        pos = np.concatenate([r.pos for _, r, _ in parts])
        sh.j = np.concatenate([j for _, _, j in parts])
        sh.fi = np.repeat([fi for fi, _, _ in parts], [len(r.gid) for _, r, _ in parts])
    else:
        sh.gid = sh.j = sh.fi = np.zeros(0, np.int64)
        pos = np.zeros((0, 4))
    sh.xa, sh.xo, sh.yo = pos[:, 0], pos[:, 2], pos[:, 3]
    if len(sh.fonts) == 1:
        sh.upem = sh.fonts[0].upem
    else:
        sh.upem = np.array([f.upem for f in sh.fonts])[sh.fi] if sh.fonts else np.zeros(0)
    return sh


def _shape_single(db, text, span, cache):
    """The :class:`_Shaped` glyphs of a chunk ``text`` owned by the one
    span ``span``, remembered for the whole document (at most
    ``_SHAPED_LIMIT`` chunks): documents repeat short strings."""
    memo = cache.table('text_shaped')
    key = (text, span.font, span.features is None)
    return cached(memo, key, lambda: _shape_chunk(db, text, [0] * len(text), [span], 0, len(text)),
                  _SHAPED_LIMIT)


class _Glyphs:
    """Positioned glyphs of a chunk, as (G,) arrays: ``span`` (int64, span
    index), ``font`` (int64, index into ``fonts``), ``gid`` (int64), ``x``,
    ``y`` (float64, glyph origin), ``s`` (float64, font units to user
    units; a float when all glyphs share it), ``rot`` (float64, degrees
    about the origin; None: all zero), ``adv`` (float64, advance)."""
    FIELDS = ('span', 'font', 'gid', 'x', 'y', 's', 'rot', 'adv')
    __slots__ = FIELDS + ('fonts',)

    def __init__(self, fonts, span, font, gid, x, y, s, rot, adv):
        self.fonts = fonts
        self.span, self.font, self.gid, self.x, self.y = span, font, gid, x, y
        self.s, self.rot, self.adv = s, rot, adv

    def __len__(self):
        return len(self.gid)

    def take(self, idx):
        """The glyphs selected by a slice, mask or index array."""
        return _Glyphs(self.fonts, *(a if a is None or np.ndim(a) == 0 else a[idx] for a in
                                     (getattr(self, name) for name in self.FIELDS)))

    def replace(self, **arrays):
        """A copy with some arrays replaced."""
        return _Glyphs(self.fonts, *(arrays.get(name, getattr(self, name))
                                     for name in self.FIELDS))


def _place_chunk(sh, sm, c0, c1, dx, dy, angle, adjust=None):
    """Position the shaped glyphs ``sh`` of characters ``c0:c1`` of one
    chunk at origin (0, 0).

    ``sm`` is the element's :class:`_SpanMetrics`; ``dx``/``dy``/``angle``
    ((n,) float64, or None for all zero) the per-character shifts along
    and across the line and rotations of the element; ``adjust``
    ((c1 - c0,) float64 or None) extra spacing after each character
    (``textLength``).

    Returns ``(glyphs, char_left, char_right, width, total_dy, cum_dy)``:
    :class:`_Glyphs` in chunk coordinates (x right, y down, baseline at
    y = 0 plus dy/baseline shifts; only glyphs of a positive size), the
    horizontal extent of every character ((m,) float64), the chunk
    advance, and the accumulated dy ((m,) float64).
    """
    m = c1 - c0
    no_extra = sm.no_extra and adjust is None
    extra = sm.extra[c0:c1]          # spacing added after each character
    if adjust is not None:
        extra = extra + adjust
    ex_before = np.zeros(m)          # spacing of earlier characters
    if not no_extra:
        np.cumsum(extra[:-1], out=ex_before[1:])
    dxcum = None if dx is None else np.cumsum(dx[c0:c1])
    before = ex_before if dx is None else dxcum + ex_before
    cdy = np.zeros(m) if dy is None else np.cumsum(dy[c0:c1])
    own = sm.owner[c0:c1]
    j = sh.j
    simple = sh.simple and not sh.rtl
    if simple:                       # glyph g is character g
        g_span, before_j, cdy_j = own, before, cdy
        angle_j = None if angle is None else angle[c0:c1]
    else:
        g_span, before_j, cdy_j = own[j], before[j], cdy[j]
        angle_j = None if angle is None else angle[c0:c1][j]
    if sm.single:
        s, ys = sm.fs / sh.upem, sm.ys
    else:
        s, ys = sm.fs[g_span] / sh.upem, sm.ys[g_span]
    adv = sh.xa * s
    pen = np.zeros(len(j) + 1)       # pen before each glyph, then the end
    np.cumsum(adv, out=pen[1:])
    for g0, g1, k in sh.rtl:
        # right to left: the spacing of a character is added when the
        # (visually preceding) glyphs of the next character begin
        jj = j[g0:g1]
        inc = np.zeros(g1 - g0)
        inc[0] = ex_before[k]
        inc[1:] = np.where(jj[1:] != jj[:-1], extra[jj[:-1]], 0.0)
        vis = np.cumsum(inc)
        before_j[g0:g1] = vis if dx is None else dxcum[jj] + vis
    # (with no spacing and no dx, before_j is zero: adding it changes nothing)
    lo = pen[:-1] if no_extra and dx is None and simple else pen[:-1] + before_j
    if dy is not None:
        ys = cdy_j + ys
    glyphs = _Glyphs(sh.fonts, g_span, sh.fi, sh.gid, lo + sh.xo * s, ys - sh.yo * s,
                     s, angle_j, adv)
    keep = s > 0
    if np.ndim(keep) == 0:
        if not keep:
            glyphs = glyphs.take(slice(0, 0))
    elif not keep.all():
        glyphs = glyphs.take(keep)
    if simple:
        char_l, char_r = lo, lo + adv
    else:
        char_l = np.full(m, np.nan)
        char_r = np.full(m, np.nan)
        np.fmin.at(char_l, j, lo)
        np.fmax.at(char_r, j, lo + adv)
        for k, e, g in sh.gaps:
            char_l[k:e] = char_r[k:e] = pen[g] + before[k:e]
        # characters merged into a cluster take their neighbours' extent
        for arr in (char_l, char_r):
            good = ~np.isnan(arr)
            if not good.any():
                arr[:] = 0.0
            elif not good.all():
                idx = np.where(good, np.arange(m), -1)
                np.maximum.accumulate(idx, out=idx)
                idx[idx < 0] = np.flatnonzero(good)[0]
                arr[:] = arr[idx]
    # the letter spacing after the last character is not part of the advance
    ls_last = sm.ls if sm.single else float(sm.ls[own[-1]])
    width = float(pen[-1]) + (0.0 if no_extra else float(extra.sum())) - ls_last
    if dx is not None:
        width += float(dx[c0:c1].sum())
    return glyphs, char_l, char_r, width, float(cdy[-1]), cdy


def _glyph_path(glyphs, ox, oy):
    """One Path of glyph outlines: each outline (font units, y up) scaled by
    its ``s`` with y flipped, turned by its ``rot`` and moved to its origin
    plus ``(ox, oy)``.  The outlines come from each font's packed outline
    arrays (:meth:`raster.fonts.Font.outlines`) in one gather per run of
    glyphs of one font.  The points are not checked for being finite."""
    fi = glyphs.font
    if not len(fi):
        return Path.empty()
    if len(glyphs.fonts) == 1:
        verbs, P, npts = glyphs.fonts[0].outlines(glyphs.gid)
    else:
        cuts = (np.flatnonzero(fi[1:] != fi[:-1]) + 1).tolist()
        parts = [glyphs.fonts[int(fi[a])].outlines(glyphs.gid[a:z])
                 for a, z in zip([0] + cuts, cuts + [len(fi)])]
        verbs = np.concatenate([v for v, _, _ in parts])
        P = np.concatenate([p for _, p, _ in parts])
        npts = np.concatenate([c for _, _, c in parts])
    if not len(verbs):
        return Path.empty()
    s = glyphs.s
    if glyphs.rot is not None and glyphs.rot.any():
        S = s if isinstance(s, float) else np.repeat(s, npts)
        X = P[:, 0] * S
        Y = -P[:, 1] * S
        R = np.radians(np.repeat(glyphs.rot, npts))
        c, s_ = np.cos(R), np.sin(R)
        out = np.empty_like(P)
        out[:, 0] = c * X - s_ * Y
        out[:, 1] = s_ * X + c * Y
    elif isinstance(s, float):
        out = P * np.array([s, -s])     # (x s, -y s): y flipped
    else:
        S = np.repeat(s, npts)
        out = np.empty_like(P)
        out[:, 0] = P[:, 0] * S
        out[:, 1] = P[:, 1] * -S
    off = np.empty((len(npts), 2))
    off[:, 0] = glyphs.x + ox
    off[:, 1] = glyphs.y + oy
    out += np.repeat(off, npts, axis=0)
    # every outline is a valid path starting with a move: so is the whole
    return Path(verbs, out, _checked=True)


def _paint_node(sp, path, st, cache):
    inh = sp.inh
    vis = inh.get('visibility', 'visible')
    if vis in ('hidden', 'collapse'):
        return None
    fill, stroke = fill_and_stroke(inh, sp.ctx, path, st, cache)
    if fill is None and stroke is None:
        return None
    return PathNode(id='', path=path, fill=fill, stroke=stroke,
                    paint_order=paint_order(inh.get('paint-order')))

