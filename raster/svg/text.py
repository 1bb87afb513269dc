"""SVG text converted to paths (usvg's "text as paths" model).

:func:`build_text` is called by the tree builder (:mod:`raster.svg.build`)
for every ``text`` element.  It lays the text out and appends ordinary
:class:`~raster.svg.tree.PathNode` objects: the glyph outlines of each run
of characters sharing one style, in the text element's user space (x right,
y down), filled and stroked as the builder resolves paints for shapes.

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
from ..errors import RasterError
from ..path import Path
from ..transform import Affine
from .tree import PathNode
from .values import parse_length, parse_length_list, parse_number_list

__all__ = ['build_text', 'collapse_whitespace']

_XML_SPACE = '{http://www.w3.org/XML/1998/namespace}space'
_SPAN_NAMES = frozenset(['tspan', 'a'])
_WEIGHTS = {'normal': 400, 'bold': 700}
_DB_CACHE = {}


def _local(el):
    tag = el.tag
    if not isinstance(tag, str):
        return None
    return tag.rsplit('}', 1)[-1]


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
    s = text.replace('\n', '').replace('\r', '').replace('\t', ' ')
    out = []
    for ch in s:
        if ch == ' ':
            if prev_space:
                continue
            prev_space = True
        else:
            prev_space = False
        out.append(ch)
    return ''.join(out), prev_space


class _Span:
    """Style of one element contributing characters."""
    __slots__ = ('el', 'inh', 'own', 'ctx', 'face', 'font', 'fs', 'shift', 'ls', 'ws', 'tl',
                 'weight', 'parent', 'decor', 'vertical')

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


def _font_db(b):
    from ..fonts import FontDB, cached
    db = getattr(b, '_text_fontdb', None)
    if db is None:
        dirs = tuple(str(d) for d in (getattr(b, 'font_dirs', ()) or ()))
        db = cached(_DB_CACHE, dirs, lambda: FontDB(dirs), 16)
        b._text_fontdb = db
    return db


def build_text(b, el, pinh, pown, st, out):
    """Lay out the ``text`` element ``el`` and append its nodes to ``out``.

    ``b`` is the tree builder (:class:`raster.svg.build._Builder`); ``pinh``/
    ``pown`` the rendering parent's computed style; ``st`` the builder
    state.  Never raises for bad text: problems warn
    (:class:`~raster.errors.RasterWarning`) and the element is skipped.
    """
    decl = b.styles.get(el)
    if decl and decl.get('display', '').strip() == 'none':
        return
    if not b.passes_conditions(el) or not b.tick():
        return
    mark = len(out)
    try:
        _build(b, el, pinh, pown, st, out)
    except Exception as e:      # text must never break a document (RasterError too)
        del out[mark:]
        b.warn('text-error', 'text element not rendered: %s' % (e,))


def _build(b, el, pinh, pown, st, out):
    inh, own = b.style(el, pinh, pown)
    ctx = b.ctx(inh, st)
    t = b.transform_of(el, own, ctx)
    if t is None:
        return
    wm = (inh.get('writing-mode') or 'lr-tb').strip()
    vertical = wm in ('tb', 'tb-rl', 'vertical-rl', 'vertical-lr')
    if vertical:
        b.warn('text-vertical', 'vertical writing modes are approximated: every glyph is '
               'turned a quarter turn clockwise (no upright CJK, no vertical metrics)')
    db = _font_db(b)
    if not db.faces:
        b.warn('text-nofont', 'no fonts available (font_dirs=%r); text is not rendered'
               % (tuple(getattr(b, 'font_dirs', ()) or ()),))
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
            name = _local(ch)
            if name in _SPAN_NAMES:
                d = b.styles.get(ch)
                if not (d and d.get('display', '').strip() == 'none') and b.passes_conditions(ch):
                    cinh, cown = b.style(ch, einh, eown)
                    cctx = b.ctx(cinh, st)
                    sp_pres = ch.get(_XML_SPACE)
                    walk(ch, cinh, cown, cctx, sp,
                         preserve if sp_pres is None else sp_pres == 'preserve')
            elif name == 'textPath' and e is el:
                d = b.styles.get(ch)
                if not (d and d.get('display', '').strip() == 'none'):
                    cinh, cown = b.style(ch, einh, eown)
                    cctx = b.ctx(cinh, st)
                    tp = _text_path_geometry(b, ch, cctx)
                    if tp is not None:
                        first = len(chars)
                        sp_pres = ch.get(_XML_SPACE)
                        walk(ch, cinh, cown, cctx, sp,
                             preserve if sp_pres is None else sp_pres == 'preserve')
                        path_ranges.append((first, len(chars), tp))
            elif name == 'tref':
                href = ch.get('{http://www.w3.org/1999/xlink}href') or ch.get('href') or ''
                tgt = b.by_id.get(href[1:].strip()) if href.startswith('#') else None
                d = b.styles.get(ch)
                if tgt is not None and not (d and d.get('display', '').strip() == 'none'):
                    cinh, cown = b.style(ch, einh, eown)
                    sp_pres = ch.get(_XML_SPACE)
                    walk(ch, cinh, cown, b.ctx(cinh, st), sp,
                         preserve if sp_pres is None else sp_pres == 'preserve',
                         ''.join(t for t in tgt.itertext() if isinstance(t, str)))
            add_text(ch.tail)
        ends[e] = len(chars)

    root_span = _Span(None, pinh, pown, ctx, None, _parent_weight(b, el))
    walk(el, inh, own, ctx, root_span, el.get(_XML_SPACE) == 'preserve')
    spans[0].parent = None
    # default mode: drop trailing spaces
    while chars and chars[-1] == ' ' and not _preserved(spans[owner[-1]].el):
        chars.pop()
        owner.pop()
    n = len(chars)
    if n == 0:
        return
    owner = np.asarray(owner, np.int64)
    ax = np.full(n, np.nan)
    ay = np.full(n, np.nan)
    dx = np.zeros(n)
    dy = np.zeros(n)
    arrs = {'x': ax, 'y': ay, 'dx': dx, 'dy': dy}
    for start, name, vals, e in lists:
        k = min(len(vals), min(ends.get(e, n), n) - start)   # own characters only
        if k > 0:
            arrs[name][start:start + k] = vals[:k]
    angle = np.zeros(n)
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
    from ..fonts import Font, parse_font_family
    for sp in spans:
        i = sp.inh
        fam = parse_font_family(i.get('font-family', ''))
        style = (i.get('font-style') or 'normal').strip()
        stretch = (i.get('font-stretch') or 'normal').strip()
        sp.face = db.match(fam, sp.weight, style, stretch)
        sp.font = _load_font(b, db, sp.face)
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
            decos += _ancestor_decorations(b, el)
        sp.decor = tuple(w for d in decos for w in _decoration(d))
    for sp in spans:
        sp.vertical = vertical
    # -- layout ------------------------------------------------------------------
    brk = ~np.isnan(ax) | ~np.isnan(ay)
    onpath = np.full(n, -1, np.int64)
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
    starts = np.flatnonzero(brk)
    bounds = list(starts) + [n]
    glyph_runs = []     # (span index, Path in user space)
    under, over = [], []
    cur_x = cur_y = 0.0
    for ci in range(len(bounds) - 1):
        c0, c1 = int(bounds[ci]), int(bounds[ci + 1])
        x0 = ax[c0] if not math.isnan(ax[c0]) else cur_x
        y0 = ay[c0] if not math.isnan(ay[c0]) else cur_y
        # vertical text advances along y: dy moves along the line, dx across
        # it (a positive dx to the right is a negative glyph-frame y)
        along, across = (dy, -dx) if vertical else (dx, dy)
        res = _layout_chunk(db, chars, owner, spans, c0, c1, along, across, angle)
        adj = _text_length_spacing(spans, owner[c0:c1], res[1], res[2])
        if adj is not None:
            res = _layout_chunk(db, chars, owner, spans, c0, c1, along, across, angle, adj)
        if res is None:
            continue
        gl, char_l, char_r, width, end_dy, cdy = res
        anchor = (spans[owner[c0]].inh.get('text-anchor') or 'start').strip()
        shift = 0.0
        if anchor == 'middle':
            shift = -width * 0.5
        elif anchor == 'end':
            shift = -width
        ox, oy = x0 + shift, y0
        cur_x, cur_y = ox + width, y0 + end_dy
        if onpath[c0] >= 0:
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
        if gl:
            g_span = np.array([g[0] for g in gl], np.int64)
            cuts = np.flatnonzero(np.diff(g_span)) + 1
            for a, z in zip(np.r_[0, cuts], np.r_[cuts, len(gl)]):
                p = _glyph_path(gl[a:z], ox, oy)
                if len(p.verbs):
                    glyph_runs.append((int(g_span[a]), p))
        # decorations of every span carrying text-decoration, over its chars
        for si, sp in enumerate(spans):
            if not sp.decor or char_l is None:
                continue
            mask = _descends(spans, owner[c0:c1], si)
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
        if len(p.points) and np.abs(p.points).max() > limits.MAX_COORD:
            b.warn('text-coord', 'text beyond the coordinate limit is not rendered')
            continue
        node = _paint_node(b, spans[si], p, st)
        if node is not None:
            kids.append(node)
    out.extend(b.wrap(el, own, t, kids, st))


def _parent_weight(b, el):
    """Computed font-weight of the document parent of ``el`` (relative
    keywords resolved along the ancestor chain)."""
    chain = []
    e = el.getparent()
    while e is not None:
        chain.append(e)
        e = e.getparent()
    w = 400
    for e in reversed(chain):
        d = b.styles.get(e)
        if d and 'font-weight' in d and d['font-weight'] != 'inherit':
            w = _weight(d['font-weight'], w)
    return w


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
    words = (value or '').split()
    if not all(w in ('underline', 'overline', 'line-through', 'none') for w in words):
        return ()
    return tuple(w for w in words if w != 'none')


def _ancestor_decorations(b, el):
    """text-decoration values declared on document ancestors of ``el``
    (they decorate the text too)."""
    out = []
    e = el.getparent()
    while e is not None:
        d = b.styles.get(e)
        if d and d.get('text-decoration'):
            out.append(d['text-decoration'])
        e = e.getparent()
    return out


def _preserved(e):
    while e is not None:
        v = e.get(_XML_SPACE)
        if v is not None:
            return v == 'preserve'
        e = e.getparent()
    return False


def _descends(spans, own_idx, si):
    """Boolean mask: which characters (span indices ``own_idx``) belong to
    span ``si`` or a span nested in it."""
    anc = np.zeros(len(spans), bool)
    for j, sp in enumerate(spans):
        p = sp
        while p is not None:
            if p is spans[si]:
                anc[j] = True
                break
            p = p.parent
    return anc[np.asarray(own_idx)]


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


def _load_font(b, db, face):
    """The Font of a matched face; a face that cannot be used (no outlines,
    a broken file) warns and is replaced by the default family's face, else
    by the first usable face."""
    from ..fonts import Font, FontError
    if face is None:
        return None
    try:
        return Font.load(face)
    except FontError as e:
        b.warn('text-font-' + face.path, 'font not usable, default family used: %s' % (e,))
    for other in [db.match([])] + list(db.faces):
        if other is None or other == face:
            continue
        try:
            return Font.load(other)
        except FontError:
            continue
    return None


def _fallback_font(db, ch, font, cache={}):
    from ..fonts import Font
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


def _text_path_geometry(b, tp_el, ctx):
    """(edges (E, 2, 2), cumulative start lengths (E,), start offset) of
    the path a textPath follows, or None when it has no usable path."""
    from ..flatten import flatten
    from .values import parse_transform
    # the SVG 2 ``path`` attribute is not used (resvg ignores it too)
    href = tp_el.get('{http://www.w3.org/1999/xlink}href') or tp_el.get('href')
    if not href or not href.startswith('#'):
        return None
    tgt = b.by_id.get(href[1:].strip())
    name = _local(tgt) if tgt is not None else None
    if name not in ('path', 'rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon'):
        return None
    ts = tgt.get('transform')
    t = parse_transform(ts) if ts else None
    path = b.geometry(tgt, name, ctx, 0.01)     # basic shapes too (SVG 2)
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
    if not glyphs:
        return [], tuple(edges[-1, 1])
    gx = np.array([g[3] for g in glyphs])
    gy = np.array([g[4] for g in glyphs])
    adv = np.array([g[7] for g in glyphs])
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
    out = [(g[0], g[1], g[2], float(ox[k]), float(oy[k]), g[5], float(deg[k] + g[6]), g[7])
           for k, g in enumerate(glyphs) if keep[k]]
    # the text after the path continues where the last glyph ends (also
    # when it fell off the path's end: extrapolated along the last edge)
    end = (float(P[-1, 0] + c[-1] * adv[-1] * 0.5), float(P[-1, 1] + s[-1] * adv[-1] * 0.5))
    return out, end


def _text_length_spacing(spans, own_idx, char_l, char_r):
    """Extra spacing after each character of a chunk that stretches the
    elements with ``textLength`` to that length (``lengthAdjust`` spacing),
    or None when no element asks for it."""
    adj = None
    present = set()
    for i in set(int(i) for i in own_idx):      # the owners and their ancestors
        sp = spans[i]
        while sp is not None:
            present.add(sp)
            sp = sp.parent
    for si, sp in enumerate(spans):
        tl = sp.tl if sp in present else None
        if tl is None:
            continue
        mask = _descends(spans, own_idx, si)
        idx = np.flatnonzero(mask)
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


def _cursive(ch):
    o = ord(ch)
    return any(lo <= o <= hi for lo, hi in _CURSIVE)


def _layout_chunk(db, chars, owner, spans, c0, c1, dx, dy, angle, adjust=None):
    """Shape characters ``c0:c1`` of one chunk at origin (0, 0).

    Returns ``(glyphs, char_left, char_right, width, total_dy)``: glyphs as
    ``(span, font, gid, x, y)`` tuples in chunk coordinates (x right, y
    down, baseline at y = 0 plus dy/baseline shifts), the horizontal extent
    of every character and the chunk advance.
    """
    m = c1 - c0
    # font of each character (fallback for missing glyphs)
    fonts = []
    for i in range(c0, c1):
        sp = spans[owner[i]]
        f = sp.font
        ch = chars[i]
        if f is not None and not f.has_char(ch) and ch not in ' \u00a0' and ord(ch) >= 32:
            f = _fallback_font(db, ch, f)
        fonts.append(f)
    # runs of equal (span, font)
    extra = np.zeros(m)       # spacing added after each character
    for k in range(m):
        sp = spans[owner[c0 + k]]
        ch = chars[c0 + k]
        # letter-spacing would break the joins of cursive scripts (Arabic,
        # Syriac, N'Ko...): it is not applied to them (as resvg does)
        ls = 0.0 if _cursive(ch) else sp.ls
        extra[k] = ls + (sp.ws if ch in ' \u00a0' else 0.0)
    if adjust is not None:
        extra = extra + adjust
    dxcum = np.cumsum(dx[c0:c1])
    ex_before = np.r_[0.0, np.cumsum(extra)[:-1]]     # spacing of earlier characters
    before = dxcum + ex_before
    cdy = np.cumsum(dy[c0:c1])
    char_l = np.full(m, np.nan)
    char_r = np.full(m, np.nan)
    glyphs = []
    pen = 0.0
    k = 0
    # runs of one font are shaped together even across spans (kerning and
    # ligatures across tspan boundaries, as usvg does); each glyph is then
    # scaled by the font size of its own span
    yshift = {}
    while k < m:
        f = fonts[k]
        e = k + 1
        if chars[c0 + k] == ' ':
            # leading/trailing spaces are shaped on their own: between
            # right-to-left text and the end of an LTR chunk they stay at
            # the visual end (a minimal stand-in for the bidi algorithm)
            while e < m and fonts[e] is f and chars[c0 + e] == ' ':
                e += 1
        else:
            while e < m and fonts[e] is f:
                e += 1
            while e - 1 > k and chars[c0 + e - 1] == ' ':
                e -= 1
        if f is None:
            char_l[k:e] = char_r[k:e] = pen + before[k:e]
            k = e
            continue
        sp0 = spans[owner[c0 + k]]
        kern = (sp0.inh.get('font-kerning') or 'auto').strip()
        no_kern = kern == 'none' or (sp0.inh.get('kerning') or 'auto').strip() == '0'
        shaped = f.shape(''.join(chars[c0 + k:c0 + e]), {'kern': False} if no_kern else None)
        # a right-to-left run comes back in visual order: its spacing adds
        # up from the left, i.e. from its logically last character
        rtl = len(shaped) > 1 and shaped[0][1] > shaped[-1][1]
        vis, prev = ex_before[k], None
        for gid, cl, xa, ya, xo, yo in shaped:
            j = k + min(int(cl), e - k - 1)
            if rtl:
                if prev is not None and j != prev:
                    vis += extra[prev]
                before_j = dxcum[j] + vis
                prev = j
            else:
                before_j = before[j]
            sp_i = int(owner[c0 + j])
            sp = spans[sp_i]
            s = sp.fs / f.upem
            ys = yshift.get(sp_i)
            if ys is None:
                ys = yshift[sp_i] = sp.shift + _dominant(sp)
            lo = pen + before_j
            hi = lo + xa * s
            if s > 0:
                glyphs.append((sp_i, f, gid, lo + xo * s, cdy[j] + ys - yo * s, s,
                               angle[c0 + j], xa * s))
            char_l[j] = lo if math.isnan(char_l[j]) else min(char_l[j], lo)
            char_r[j] = hi if math.isnan(char_r[j]) else max(char_r[j], hi)
            pen += xa * s
        k = e
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
    last = spans[owner[c1 - 1]]
    width = pen + float(extra.sum()) - last.ls + float(dx[c0:c1].sum())
    return glyphs, char_l, char_r, width, float(cdy[-1]), cdy


def _glyph_path(glyphs, ox, oy):
    """One Path of glyph outlines: each outline (font units, y up) scaled by
    its ``s`` with y flipped and moved to its pen position."""
    verbs, pts, scales, offs, rots = [], [], [], [], []
    for _, f, gid, gx, gy, s, rot, _adv in glyphs:
        p = f.outline(gid)
        if not len(p.verbs):
            continue
        verbs.append(p.verbs)
        pts.append(p.points)
        npt = len(p.points)
        scales.append(np.full(npt, s))
        offs.append(np.repeat([[gx + ox, gy + oy]], npt, axis=0))
        rots.append(np.full(npt, rot))
    if not verbs:
        return Path.empty()
    P = np.concatenate(pts)
    S = np.concatenate(scales)
    O = np.concatenate(offs)
    X = P[:, 0] * S
    Y = -P[:, 1] * S
    R = np.radians(np.concatenate(rots))
    if R.any():
        c, s_ = np.cos(R), np.sin(R)
        X, Y = c * X - s_ * Y, s_ * X + c * Y
    out = np.empty_like(P)
    out[:, 0] = X + O[:, 0]
    out[:, 1] = Y + O[:, 1]
    return Path.from_arrays(np.concatenate(verbs), out)


def _paint_node(b, sp, path, st):
    inh = sp.inh
    vis = inh.get('visibility', 'visible')
    if vis in ('hidden', 'collapse'):
        return None
    fill, stroke = b.fill_and_stroke(inh, sp.ctx, path, st)
    if fill is None and stroke is None:
        return None
    from .build import _paint_order
    return PathNode(id='', path=path, fill=fill, stroke=stroke,
                    paint_order=_paint_order(inh.get('paint-order')))

