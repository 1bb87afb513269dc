"""Text layout: one text chunk to positioned glyph clusters (usvg's model).

A *chunk* is a run of characters laid out from one position (a new chunk
starts at every absolute ``x``/``y``, at a ``textPath`` and after it).
:func:`layout_chunk` turns it into :class:`Clusters`:

1. **Bidi.** The chunk's embedding levels come from the Unicode
   Bidirectional Algorithm (python-bidi, which wraps the ``unicode-bidi``
   crate resvg uses) with a left-to-right paragraph; maximal runs of one
   level are put in visual order (rule L2) and each is shaped in its
   direction.
2. **Shaping across spans.**  The whole chunk is shaped with the font of
   every span it holds; each cluster takes the glyphs of the shaping by
   its own span's font, so kerning and ligatures work across ``tspan``
   boundaries.  Characters a font has no glyph for are shaped again with
   a fallback face (:meth:`raster.fonts.FontDB.fallback_face`).
3. **Clusters.**  Glyphs sharing a cluster (HarfBuzz's first character)
   form one cluster: its width is the widest glyph advance, its metrics
   those of its first glyph's font at its span's font size.
4. **Spacing.**  ``letter-spacing`` after every cluster but the chunk's
   last (not for scripts whose letters join: Arabic, Syriac, N'Ko,
   Mongolian, the Brahmic scripts that connect, Ogham ...); a cluster whose
   advance becomes zero or negative is dropped (Chrome, usvg).
   ``word-spacing`` after word separators.  ``textLength`` with
   ``lengthAdjust="spacing"`` spreads the difference between the
   clusters of the span, ``spacingAndGlyphs`` scales them.
5. **Positions.**  Along a line: ``text-anchor`` by the chunk's advance,
   ``dx``/``dy`` of each cluster's first character, ``rotate``.  On a
   ``textPath``: each cluster's middle at its arc length, turned to the
   path's tangent.  ``writing-mode: tb`` lays the chunk out horizontally
   and turns it a quarter turn about its start; clusters of upright
   characters (Unicode Vertical_Orientation U: CJK, kana, Hangul, ...) are
   turned back upright about their centre.

Every cluster ends with an affine transform (arrays, one row per
cluster), every glyph with its offset inside its cluster, so the outlines
of a whole chunk are placed in one array operation.
"""

import math
import re

import numpy as np

from ..geometry.rows import distinct_values

__all__ = ['bidi_levels', 'visual_runs', 'is_upright', 'joins_letters', 'Clusters',
           'shape_clusters', 'affines', 'compose', 'translate', 'rotate', 'scale']


# -- bidi -----------------------------------------------------------------------

_LEVEL_RE = re.compile(r'levels:\s*\[(.*?)\]', re.S)
_NUM_RE = re.compile(r'Level\(\s*(\d+)')


def bidi_levels(text):
    """Embedding levels ((n,) int64, one per character) of ``text`` by the
    Unicode Bidirectional Algorithm with a left-to-right paragraph level.

    All zeros for text without right-to-left characters (no call then).

    >>> bidi_levels('ab').tolist()
    [0, 0]
    >>> bidi_levels('a \\u05d0\\u05d1').tolist()
    [0, 0, 1, 1]
    """
    n = len(text)
    if _RTL_RE.search(text) is None:
        return np.zeros(n, np.int64)
    try:
        from bidi.bidi import get_display_inner
        dump = get_display_inner(text, 'L', True)
        m = _LEVEL_RE.search(dump)
        byte_levels = [int(v) for v in _NUM_RE.findall(m.group(1))] if m else []
    except Exception:       # python-bidi missing or changed: no reordering
        byte_levels = []
    enc = [len(c.encode('utf-8')) for c in text]
    if len(byte_levels) != sum(enc):
        return np.zeros(n, np.int64)
    starts = np.cumsum([0] + enc[:-1])
    return np.asarray(byte_levels, np.int64)[starts]


# characters that may make a run right to left (Hebrew, Arabic and the other
# RTL blocks, the bidi controls): text without any needs no bidi pass
_RTL_RE = re.compile('[\u0590-\u08ff\ufb1d-\ufdff\ufe70-\ufeff\u200e\u200f\u202a-\u202e'
                     '\u2066-\u2069\U00010800-\U00010fff\U0001e800-\U0001efff]')


def visual_runs(levels):
    """The runs of equal level of ``levels`` in visual order (rule L2 of the
    bidi algorithm): a list of ``(start, end, rtl)``.

    >>> visual_runs(np.array([0, 0, 1, 1, 2, 1, 0]))
    [(0, 2, False), (5, 6, True), (4, 5, False), (2, 4, True), (6, 7, False)]
    """
    n = len(levels)
    if n == 0:
        return []
    if not levels.any():
        return [(0, n, False)]
    cuts = (np.flatnonzero(np.diff(levels)) + 1).tolist()
    runs = [(a, b, int(levels[a])) for a, b in zip([0] + cuts, cuts + [n])]
    hi = max(r[2] for r in runs)
    lo = min((r[2] for r in runs if r[2] % 2), default=None)
    if lo is not None:
        for level in range(hi, lo - 1, -1):
            out, k = [], 0
            while k < len(runs):
                if runs[k][2] >= level:
                    j = k
                    while j < len(runs) and runs[j][2] >= level:
                        j += 1
                    out.extend(reversed(runs[k:j]))
                    k = j
                else:
                    out.append(runs[k])
                    k += 1
            runs = out
    return [(a, b, bool(lv % 2)) for a, b, lv in runs]


# -- Unicode properties used by the layout ----------------------------------------

# Vertical_Orientation = U (UAX #50), as inclusive ranges; the rest (R, and
# Tu/Tr, which usvg rotates as well) is turned with the line.
_UPRIGHT = (
    (0x00A7, 0x00A7), (0x00A9, 0x00A9), (0x00AE, 0x00AE), (0x00B1, 0x00B1),
    (0x00BC, 0x00BE), (0x00D7, 0x00D7), (0x00F7, 0x00F7), (0x02EA, 0x02EB),
    (0x1100, 0x11FF), (0x1401, 0x167F), (0x18B0, 0x18FF), (0x2016, 0x2016),
    (0x2020, 0x2021), (0x2030, 0x2031), (0x203B, 0x203C), (0x2042, 0x2042),
    (0x2047, 0x2049), (0x2051, 0x2051), (0x2065, 0x2065), (0x20DD, 0x20E0),
    (0x20E2, 0x20E4), (0x2100, 0x2101), (0x2103, 0x2109), (0x210F, 0x210F),
    (0x2113, 0x2114), (0x2116, 0x2117), (0x211E, 0x2123), (0x2125, 0x2125),
    (0x2127, 0x2127), (0x2129, 0x2129), (0x212E, 0x212E), (0x2135, 0x213F),
    (0x2145, 0x214A), (0x214C, 0x214D), (0x214F, 0x2189), (0x218C, 0x218F),
    (0x221E, 0x221E), (0x2234, 0x2235), (0x2300, 0x2307), (0x230C, 0x231F),
    (0x2324, 0x2328), (0x232B, 0x232B), (0x237D, 0x239A), (0x23BE, 0x23CD),
    (0x23CF, 0x23CF), (0x23D1, 0x23DB), (0x23E2, 0x2422), (0x2424, 0x24FF),
    (0x25A0, 0x2619), (0x2620, 0x2767), (0x2776, 0x2793), (0x2B12, 0x2B2F),
    (0x2B50, 0x2B59), (0x2BB8, 0x2BD1), (0x2BD3, 0x2BEB), (0x2BF0, 0x2BFF),
    (0x2E50, 0x2E51), (0x2E80, 0x3000), (0x3003, 0x3007), (0x3012, 0x3013),
    (0x3020, 0x302F), (0x3031, 0x3040), (0x3042, 0x3042), (0x3044, 0x3044),
    (0x3046, 0x3046), (0x3048, 0x3048), (0x304A, 0x3062), (0x3064, 0x3082),
    (0x3084, 0x3084), (0x3086, 0x3086), (0x3088, 0x308D), (0x308F, 0x3094),
    (0x3097, 0x309A), (0x309D, 0x309F), (0x30A2, 0x30A2), (0x30A4, 0x30A4),
    (0x30A6, 0x30A6), (0x30A8, 0x30A8), (0x30AA, 0x30C2), (0x30C4, 0x30E2),
    (0x30E4, 0x30E4), (0x30E6, 0x30E6), (0x30E8, 0x30ED), (0x30EF, 0x30F4),
    (0x30F7, 0x30FB), (0x30FD, 0x31EF), (0x31F0 + 16, 0x3247), (0x3250, 0x32FF),
    (0x3358, 0x337A), (0x3380, 0x33FF), (0x3400, 0x4DBF), (0x4DC0, 0xA4CF),
    (0xA960, 0xA97F), (0xAC00, 0xD7FF), (0xE000, 0xFAFF), (0xFE10, 0xFE1F),
    (0xFE30, 0xFE48), (0xFE53, 0xFE57), (0xFE5F, 0xFE62), (0xFE67, 0xFE6F),
    (0xFF02, 0xFF07), (0xFF0A, 0xFF0B), (0xFF0F, 0xFF19), (0xFF1F, 0xFF3A),
    (0xFF3C, 0xFF3C), (0xFF3E, 0xFF3E), (0xFF40, 0xFF5A), (0xFFE0, 0xFFE2),
    (0xFFE4, 0xFFE7), (0xFFF0, 0xFFF8), (0xFFFC, 0xFFFD), (0x10980, 0x1099F),
    (0x11580, 0x115FF), (0x11A00, 0x11AAF), (0x13000, 0x1345F), (0x14400, 0x1467F),
    (0x16FE0, 0x18D8F), (0x1AFF0, 0x1B2FF), (0x1D000, 0x1D1FF), (0x1D2E0, 0x1D37F),
    (0x1D800, 0x1DAAF), (0x1F000, 0x1F1FF), (0x1F210, 0x1F7FF), (0x1F900, 0x1FAFF),
    (0x20000, 0x2FFFD), (0x30000, 0x3FFFD), (0xF0000, 0x10FFFD))
_UP_LO = np.array([a for a, _ in _UPRIGHT], np.int64)
_UP_HI = np.array([b for _, b in _UPRIGHT], np.int64)

# scripts whose letters join (CSS Text 3, cursive tracking): no letter-spacing
_JOINING = ((0x0600, 0x08FF), (0xFB50, 0xFDFF), (0xFE70, 0xFEFF), (0x0700, 0x074F),
            (0x0860, 0x086F), (0x07C0, 0x07FF), (0x0840, 0x085F), (0x1800, 0x18AF),
            (0xA840, 0xA87F), (0x0900, 0x0963), (0x0966, 0x097F), (0xA8E0, 0xA8FF),
            (0x0980, 0x09FF), (0x0A00, 0x0A7F), (0x1680, 0x169F), (0xA800, 0xA82F),
            (0x10AC0, 0x10AFF), (0x10B80, 0x10BAF), (0x11600, 0x1165F),
            (0x11180, 0x111DF), (0x11480, 0x114DF))
_JOIN_LO = np.array([a for a, _ in _JOINING], np.int64)
_JOIN_HI = np.array([b for _, b in _JOINING], np.int64)

#: Word separators (CSS Text 3): word-spacing applies after them.
WORD_SEPARATORS = (0x20, 0xA0, 0x1361, 0x10100, 0x10101, 0x1039F, 0x1091F)


def _in_ranges(cps, lo, hi):
    cps = np.asarray(cps, np.int64)
    i = np.searchsorted(lo, cps, 'right') - 1
    ok = i >= 0
    return ok & (cps <= hi[np.maximum(i, 0)])


def is_upright(cps):
    """(n,) bool: codepoints set upright in vertical text (UAX #50 U).

    >>> is_upright([ord('A'), 0x4E2D, 0x3001]).tolist()
    [False, True, False]
    """
    return _in_ranges(cps, _UP_LO, _UP_HI)


def joins_letters(cps):
    """(n,) bool: codepoints of scripts whose letters join (no
    letter-spacing)."""
    return _in_ranges(cps, _JOIN_LO, _JOIN_HI)


# -- batched affines: (n, 3, 3) float64 ------------------------------------------------

def translate(tx, ty):
    """(n, 3, 3) translations (``tx``, ``ty`` broadcast)."""
    tx, ty = np.broadcast_arrays(np.asarray(tx, float), np.asarray(ty, float))
    m = np.zeros(tx.shape + (3, 3))
    m[..., 0, 0] = m[..., 1, 1] = m[..., 2, 2] = 1.0
    m[..., 0, 2] = tx
    m[..., 1, 2] = ty
    return m


def rotate(deg):
    """(n, 3, 3) rotations by ``deg`` degrees (y down: clockwise)."""
    r = np.radians(np.asarray(deg, float))
    c, s = np.cos(r), np.sin(r)
    m = np.zeros(r.shape + (3, 3))
    m[..., 0, 0] = c
    m[..., 0, 1] = -s
    m[..., 1, 0] = s
    m[..., 1, 1] = c
    m[..., 2, 2] = 1.0
    return m


def scale(sx, sy):
    """(n, 3, 3) scalings."""
    sx, sy = np.broadcast_arrays(np.asarray(sx, float), np.asarray(sy, float))
    m = np.zeros(sx.shape + (3, 3))
    m[..., 0, 0] = sx
    m[..., 1, 1] = sy
    m[..., 2, 2] = 1.0
    return m


def compose(*ms):
    """Product of batched affines, left to right (the last applies first)."""
    out = ms[0]
    for m in ms[1:]:
        out = np.matmul(out, m)
    return out


def affines(m):
    """(n, 6) ``a b c d e f`` rows of (n, 3, 3) matrices."""
    return np.stack([m[:, 0, 0], m[:, 1, 0], m[:, 0, 1], m[:, 1, 1], m[:, 0, 2], m[:, 1, 2]],
                    axis=1)


# -- shaping into clusters ----------------------------------------------------------------

class Clusters:
    """The glyph clusters of one chunk, in visual order.

    Attributes (C clusters, G glyphs)
    ----------
    char : (C,) int64
        Chunk-local index of each cluster's first character.
    span : (C,) int64
        Span of that character.
    width, advance : (C,) float64
        Widest glyph advance, and the advance after spacing (user units).
    ascent, descent, x_height : (C,) float64
        Metrics of the cluster's font at its size (y up: descent < 0).
    visible : (C,) bool
        False for clusters off a text path.
    relshift : (C,) bool
        The cluster is moved relative to the previous one (``dx``, ``dy``,
        ``rotate``, a text path): a decoration line breaks there.
    m : (C, 3, 3) float64
        Cluster transform (set by the positioning).
    pm : (C, 3, 3) float64 or None
        Path transform applied before ``m`` (upright vertical clusters).
    pre : (C, 3, 3) float64 or None
        Transform applied before the position (vertical shift, glyph
        scaling of ``spacingAndGlyphs``).
    g_cluster, g_font, g_gid : (G,) int64
        Cluster, font (index into ``fonts``) and glyph id of each glyph.
    g_x, g_y : (G,) float64
        Glyph offset inside its cluster, font units (y up).
    g_scale : (G,) float64
        Font size over units per em of each glyph's font.
    fonts : list of Font
    missing : str
        Characters no font has a glyph for (drawn as the first font's
        .notdef glyph), in order, without repeats.
    """
    __slots__ = ('char', 'span', 'width', 'advance', 'ascent', 'descent', 'x_height', 'visible',
                 'relshift', 'm', 'pm', 'pre', 'g_cluster', 'g_font', 'g_gid', 'g_x', 'g_y',
                 'g_scale', 'fonts', 'cps', 'x', 'y', 'missing')

    def mats(self):
        """(C, 3, 3) cluster transforms (made from the positions ``x``,
        ``y`` when the clusters are only translated: ``m`` None)."""
        if self.m is None:
            self.m = translate(self.x, self.y)
        return self.m

    def __len__(self):
        return len(self.char)

    def copy(self):
        """A copy whose per-cluster arrays can be changed (the glyph arrays
        are shared: they are never changed)."""
        c = Clusters()
        for name in self.__slots__:
            setattr(c, name, getattr(self, name))
        c.advance = self.advance.copy()
        c.width = self.width.copy()
        return c

    def drop(self, keep):
        """Keep only clusters where ``keep`` ((C,) bool) is True."""
        if keep.all():
            return
        idx = np.flatnonzero(keep)
        remap = np.full(len(keep), -1, np.int64)
        remap[idx] = np.arange(len(idx))
        gk = keep[self.g_cluster]
        for name in ('char', 'span', 'width', 'advance', 'ascent', 'descent', 'x_height',
                     'visible', 'relshift', 'cps'):
            setattr(self, name, getattr(self, name)[idx])
        for name in ('m', 'pm', 'pre'):
            v = getattr(self, name)
            if v is not None:
                setattr(self, name, v[idx])
        self.g_cluster = remap[self.g_cluster[gk]]
        for name in ('g_font', 'g_gid', 'g_x', 'g_y', 'g_scale'):
            setattr(self, name, getattr(self, name)[gk])


def _shape_runs(font, text, runs, features, memo):
    """Glyphs of ``text`` shaped with ``font`` run by run (visual order):
    (gid, cluster (chunk-local first character), x_advance, x_offset,
    y_offset) arrays; remembered in ``memo``."""
    key = (id(font), text, features and tuple(sorted(features.items())), tuple(runs))
    r = memo.get(key)
    if r is not None:
        return r
    parts = []
    for a, b, rtl in runs:
        sh = font.shape_arrays(text[a:b], features, 'rtl' if rtl else 'ltr')
        parts.append((sh.gid, sh.cluster + a, sh.pos))
    if len(parts) == 1:
        gid, cl, pos = parts[0]
    else:
        gid = np.concatenate([p[0] for p in parts])
        cl = np.concatenate([p[1] for p in parts])
        pos = np.concatenate([p[2] for p in parts])
    r = (gid, cl, pos[:, 0], pos[:, 2], pos[:, 3])
    if len(memo) > 4096:
        memo.clear()
    memo[key] = r
    return r


def _groups(cl):
    """(starts, ends) of runs of equal cluster id in glyph order."""
    if not len(cl):
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    cuts = np.flatnonzero(cl[1:] != cl[:-1]) + 1
    return np.r_[0, cuts], np.r_[cuts, len(cl)]


def _font_key(sp):
    return (id(sp.font), None if sp.features is None else tuple(sorted(sp.features.items())),
            getattr(sp, 'families', None))


def shape_clusters(text, owner, spans, fallback, memo):
    """Shape a chunk into :class:`Clusters` (steps 1 to 3 of the module
    docstring).

    Parameters
    ----------
    text : str
        The chunk's characters.
    owner : (n,) int64 ndarray
        Span of every character.
    spans : sequence
        Span objects with ``font`` (a Font or None), ``fs`` (font size),
        ``features`` (dict or None).
    fallback : callable
        ``fallback(font, ch, span) -> Font or None``: a font with a glyph
        for ``ch`` (``span``: the span of the character).
    memo : dict
        Shaping results shared by the chunks of a document (the clusters
        of a repeated chunk are copied from it).

    Returns None when no span has a font.
    """
    n = len(text)
    cuts = (np.flatnonzero(owner[1:] != owner[:-1]) + 1).tolist()
    starts = [0] + cuts
    key = ('clusters', text, tuple((a, _font_key(spans[int(owner[a])]), spans[int(owner[a])].fs)
                                   for a in starts))
    tmpl = memo.get(key)
    if tmpl is None:
        tmpl = _shape_clusters(text, owner, spans, fallback, memo, starts)
        if len(memo) > 4096:
            memo.clear()
        memo[key] = tmpl if tmpl is not None else False
    if not tmpl:
        return None
    c = tmpl.copy()
    c.span = owner[c.char]          # this element's spans
    return c


def _shape_clusters(text, owner, spans, fallback, memo, starts):
    n = len(text)
    runs = visual_runs(bidi_levels(text))
    keys = []               # distinct (font, features) in order of first use
    key_of = {}
    for a in starts:
        sp = spans[int(owner[a])]
        if sp.font is None:
            continue
        k = _font_key(sp)
        key_of[int(owner[a])] = k
        if k not in keys:
            keys.append(k)
    if not keys:
        return None
    feats = {k: spans[s].features for s, k in key_of.items()}
    fonts_k = {k: spans[s].font for s, k in key_of.items()}
    # the key of every character's span (-1: a span without a font: base)
    if len(keys) > 1:
        kidx = np.zeros(n, np.int64)
        for s, k in key_of.items():
            kidx[owner == s] = keys.index(k)
    parts = []
    for ki, k in enumerate(keys):
        gid, cl, adv, xo, yo = _shape_runs(fonts_k[k], text, runs, feats[k], memo)
        if len(keys) == 1:
            parts.append((ki, gid, cl, adv, xo, yo))
            break
        sel = kidx[cl] == ki
        parts.append((ki, gid[sel], cl[sel], adv[sel], xo[sel], yo[sel]))
    fonts = [fonts_k[k] for k in keys]
    if len(parts) == 1:
        _, gid, cl, adv, xo, yo = parts[0]
        fi = np.zeros(len(gid), np.int64)
    else:
        # every cluster from the shaping by its own span's font, in visual order
        rank = np.empty(n, np.int64)
        pos = 0
        for a, b, rtl in runs:
            rank[a:b] = np.arange(pos + b - a - 1, pos - 1, -1) if rtl else \
                np.arange(pos, pos + b - a)
            pos += b - a
        gid = np.concatenate([p[1] for p in parts])
        cl = np.concatenate([p[2] for p in parts])
        adv = np.concatenate([p[3] for p in parts])
        xo = np.concatenate([p[4] for p in parts])
        yo = np.concatenate([p[5] for p in parts])
        fi = np.repeat([p[0] for p in parts], [len(p[1]) for p in parts])
        order = np.argsort(rank[cl], kind='stable')
        gid, cl, adv, xo, yo, fi = gid[order], cl[order], adv[order], xo[order], yo[order], \
            fi[order]
    missing = (gid == 0)
    if missing.any():
        gid, cl, adv, xo, yo, fi = _fallbacks(text, runs, owner, spans, fonts, fallback, memo,
                                              gid, cl, adv, xo, yo, fi)
    c = _build_clusters(text, owner, spans, fonts, gid, cl, adv, xo, yo, fi)
    c.missing = _missing(text, gid, cl) if missing.any() else ''
    return c


def _missing(text, gid, cl):
    """The characters of clusters still drawn with a .notdef glyph (gid 0)
    after the fallback, without spaces, controls and default-ignorable
    characters, in order, once each."""
    out = []
    for c in distinct_values(cl[gid == 0]).tolist():
        ch = text[c]
        cp = ord(ch)
        if cp < 32 or ch.isspace() or 0x200B <= cp <= 0x200F or 0x2060 <= cp <= 0x206F or \
                0xFE00 <= cp <= 0xFE0F or 0xE0000 <= cp <= 0xE0FFF or cp == 0xFEFF:
            continue
        if ch not in out:
            out.append(ch)
    return ''.join(out)


def _fallbacks(text, runs, owner, spans, fonts, fallback, memo, gid, cl, adv, xo, yo, fi):
    """Replace the glyphs of clusters with a missing glyph by those of a
    fallback font (up to 8 fonts tried per cluster, each shaping the whole
    chunk, as usvg does).

    A fallback font may join more characters into one cluster than the
    first font did (an emoji sequence with ZWJ, a flag, a skin tone): the
    replacement then covers all of them and the first font's clusters
    inside it are dropped.
    """
    n = len(text)
    st, en = _groups(cl)
    starts = cl[st]
    # end (exclusive, logical order) of every cluster: the next cluster start
    srt = distinct_values(starts)
    nxt = np.r_[srt[1:], n]
    cend = nxt[np.searchsorted(srt, starts)]
    missing = np.logical_or.reduceat(gid == 0, st) if len(st) else np.zeros(0, bool)
    repl = {}           # group index -> replacement arrays
    covered = np.zeros(n, bool)     # characters taken by a replacement
    for k in np.flatnonzero(missing).tolist():
        c = int(starts[k])
        if covered[c]:
            continue
        ch = text[c]
        font = fonts[int(fi[st[k]])]
        # a space keeps the font's missing glyph, unless the font's face may
        # not be used for it (unicode-range): then it is another font's
        if ord(ch) < 32 or (ch in ' \u00a0\t' and not font.face.unicode_range):
            continue
        tried = {id(font)}
        for _ in range(8):
            f = fallback(font, ch, spans[int(owner[c])])
            if f is None or id(f) in tried:
                break
            tried.add(id(f))
            g2, c2, a2, x2, y2 = _shape_runs(f, text, runs, spans[int(owner[c])].features, memo)
            later = c2[c2 > c]
            fend = int(later.min()) if len(later) else n
            end = max(int(cend[k]), fend)
            idx = np.flatnonzero((c2 >= c) & (c2 < end))
            if len(idx) and not (g2[idx] == 0).any() and (c2[idx] == c).any():
                if all(x is not f for x in fonts):
                    fonts.append(f)
                j = next(i for i, x in enumerate(fonts) if x is f)
                repl[k] = (g2[idx], np.full(len(idx), c, np.int64), a2[idx], x2[idx], y2[idx],
                           np.full(len(idx), j, np.int64))
                covered[c + 1:end] = True
                break
            font = f
    if not repl:
        return gid, cl, adv, xo, yo, fi
    cols = (gid, cl, adv, xo, yo, fi)
    keep_group = ~covered[starts]
    for k in repl:
        keep_group[k] = True
    parts = []
    prev = 0            # first glyph not yet copied
    for k in sorted(set(repl) | set(np.flatnonzero(~keep_group).tolist())):
        if st[k] > prev:
            parts.append(tuple(a[prev:st[k]] for a in cols))
        if k in repl:
            parts.append(repl[k])
        prev = int(en[k])
    if prev < len(gid):
        parts.append(tuple(a[prev:] for a in cols))
    return tuple(np.concatenate([p[i] for p in parts]) for i in range(6))


def _build_clusters(text, owner, spans, fonts, gid, cl, adv, xo, yo, fi):
    """:class:`Clusters` of glyph arrays in visual order (runs of equal
    ``cl`` are clusters), on whole arrays."""
    G = len(gid)
    c = Clusters()
    fs = np.array([sp.fs for sp in spans])
    upem = np.array([f.upem for f in fonts])
    asc = np.array([f.ascender for f in fonts])
    desc = np.array([f.descender for f in fonts])
    xh = np.array([f.x_height for f in fonts])
    if G:
        is_start = np.ones(G, bool)
        is_start[1:] = cl[1:] != cl[:-1]
        starts = np.flatnonzero(is_start)
    else:
        is_start = np.zeros(0, bool)
        starts = np.zeros(0, np.int64)
    g_cluster = np.cumsum(is_start) - 1
    char = cl[starts]
    span = owner[char] if len(char) else np.zeros(0, np.int64)
    g_scale = fs[owner[cl]] / upem[fi] if G else np.zeros(0)
    excl = np.zeros(G)
    if G > 1:
        np.cumsum(adv[:-1], out=excl[1:])
    pen = excl - excl[starts][g_cluster] if G else excl
    sc = g_scale[starts]
    f0 = fi[starts]
    # the cluster's advance: its glyphs' advances (a mark or a vowel sign of
    # its own in a cluster moves the pen, as resvg's references show)
    width = np.add.reduceat(adv * g_scale, starts) if G else np.zeros(0)
    c.char, c.span, c.width = char, span, width
    c.advance = width.copy()
    c.ascent, c.descent, c.x_height = asc[f0] * sc, desc[f0] * sc, xh[f0] * sc
    C = len(char)
    c.visible = np.ones(C, bool)
    c.relshift = np.zeros(C, bool)
    c.m = c.pm = c.pre = c.x = c.y = None
    c.cps = np.frombuffer(text.encode('utf-32-le'), np.uint32).astype(np.int64)[char]
    c.fonts = fonts
    c.g_cluster, c.g_font, c.g_gid = g_cluster, fi, gid.astype(np.int64)
    c.g_x, c.g_y, c.g_scale = pen + xo, np.asarray(yo, float), g_scale
    return c


# -- spacing and length ----------------------------------------------------------------------

def apply_vertical(cl):
    """Vertical writing: every cluster is centred on the line (moved down by
    the middle of its ascent and descent, before the quarter turn of the
    chunk); upright clusters are also turned back a quarter turn about
    their centre (a path transform), as usvg lays vertical text out."""
    up = is_upright(cl.cps)
    C = len(cl)
    w = cl.width
    c = (cl.ascent + cl.descent) / 2
    pm = compose(translate(0.0, c), translate(w / 2, -c), rotate(np.full(C, -90.0)),
                 translate(-w / 2, c))
    eye = translate(np.zeros(C), np.zeros(C))
    cl.pm = np.where(up[:, None, None], pm, eye)
    cl.pre = np.where(up[:, None, None], eye, translate(0.0, c))
    cl.ascent = np.where(up, w / 2, cl.ascent)
    cl.descent = np.where(up, -w / 2, cl.descent)


def apply_spacing(cl, ls, ws):
    """Letter and word spacing (per span arrays ``ls``, ``ws``); clusters
    whose advance is no longer positive are dropped."""
    if np.any(ls):
        add = ls[cl.span].copy()
        add[joins_letters(cl.cps)] = 0.0
        add[-1] = 0.0
        adv = cl.advance + add
        cl.advance = adv
        bad = ~(adv > 0) & (ls[cl.span] != 0)
        if bad.any():
            cl.drop(~bad)
    if np.any(ws) and len(cl):
        sep = np.isin(cl.cps, WORD_SEPARATORS)
        cl.advance = cl.advance + np.where(sep, ws[cl.span], 0.0)


def apply_length(cl, segments, on_path):
    """``textLength``: ``segments`` is a list of ``(first char, end char,
    length, spacing_and_glyphs)`` of the chunk's spans that ask for one."""
    for c0, c1, target, glyphs in segments:
        idx = np.flatnonzero((cl.char >= c0) & (cl.char < c1))
        if not len(idx):
            continue
        width = float(cl.width[idx].sum())
        if not glyphs:
            f = (target - width) / (len(idx) - 1) if len(idx) > 1 else 0.0
            cl.advance[idx] = cl.width[idx] + f
        else:
            if not width > 0:
                continue
            f = target / width
            if f < 0.001:
                continue
            pre = cl.pre if cl.pre is not None else translate(np.zeros(len(cl)), 0.0)
            pre = pre.copy()
            pre[idx] = compose(pre[idx], scale(np.full(len(idx), f), 1.0))
            cl.pre = pre
            if on_path:
                cl.advance[idx] *= f
                cl.width[idx] *= f


def anchor_shift(anchor, length):
    """Start offset of a chunk of advance ``length`` for a text-anchor."""
    if anchor == 'middle':
        return -length / 2
    if anchor == 'end':
        return -length
    return 0.0


def position_linear(cl, anchor, dx, dy, rot, vertical):
    """Cluster transforms along a line (chunk frame: origin at the chunk's
    start, x along the line); ``dx``/``dy``/``rot`` are per chunk
    character ((n,) float64 or None).  Returns the end position."""
    C = len(cl)
    ch = cl.char
    ddx = dx[ch] if dx is not None else np.zeros(C)
    ddy = dy[ch] if dy is not None else np.zeros(C)
    if vertical:
        ax, ay = ddy, -ddx
    else:
        ax, ay = ddx, ddy
    x0 = anchor_shift(anchor, float(cl.advance.sum()))
    before = np.zeros(C)
    if C > 1:
        np.cumsum(cl.advance[:-1], out=before[1:])
    x = x0 + np.cumsum(ax) + before
    y = np.cumsum(ay)
    cl.relshift = (ddx != 0) | (ddy != 0)
    cl.x, cl.y = x, y
    cl.m = None                 # translations only, unless turned or scaled
    nz = None
    if rot is not None:
        r = rot[ch]
        nz = r != 0
        if not nz.any():
            nz = None
    if nz is not None or cl.pre is not None:
        m = translate(x, y)
        if nz is not None:
            m = np.where(nz[:, None, None], compose(m, rotate(r)), m)
            cl.relshift |= nz
        if cl.pre is not None:
            m = compose(cl.pre, m)
        cl.m = m
    end_x = float(x[-1] + cl.advance[-1]) if C else x0
    end_y = float(y[-1]) if C else 0.0
    return end_x, end_y


def path_points(edges, cum, offsets):
    """Points and tangent angles (degrees) at arc lengths ``offsets`` of a
    polyline given by ``edges`` ((E, 2, 2)) and cumulative lengths ``cum``
    ((E + 1,)); None rows (NaN) off the path."""
    total = cum[-1]
    ok = (offsets >= 0) & (offsets <= total)
    i = np.clip(np.searchsorted(cum, offsets, 'right') - 1, 0, len(edges) - 1)
    a, b = edges[i, 0], edges[i, 1]
    seg = cum[i + 1] - cum[i]
    t = np.where(seg > 0, (offsets - cum[i]) / np.where(seg > 0, seg, 1.0), 0.0)
    p = a + (b - a) * t[:, None]
    ang = np.degrees(np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0]))
    return p, ang, ok


def position_on_path(cl, path, start, anchor, dx, dy, rot, shifts):
    """Cluster transforms on a text path (``path``: (edges, cum)), the
    chunk's start offset ``start`` along it; ``shifts`` ((C,) float64) the
    baseline shift of each cluster's span (down positive).  Returns the end
    position (the last visible cluster's point plus its advance in x, as
    usvg continues)."""
    edges, cum = path
    C = len(cl)
    ch = cl.char
    ddx = dx[ch] if dx is not None else np.zeros(C)
    ddy = dy[ch] if dy is not None else np.zeros(C)
    s0 = start + anchor_shift(anchor, float(cl.advance.sum()))
    before = np.zeros(C)
    if C > 1:
        np.cumsum(cl.advance[:-1], out=before[1:])
    adv_at = s0 + np.cumsum(ddx) + before
    hw = cl.width / 2
    p, ang, ok = path_points(edges, cum, adv_at + hw)
    cl.visible = ok
    cl.relshift = np.ones(C, bool)
    acc_dy = np.cumsum(ddy)
    m = compose(translate(p[:, 0] - hw, p[:, 1]), translate(hw, 0.0), rotate(ang),
                translate(-hw, 0.0), translate(0.0, acc_dy + shifts))
    if rot is not None:
        r = rot[ch]
        if np.any(r != 0):
            m = compose(m, rotate(r))
    if cl.pre is not None:
        m = compose(m, cl.pre)
    cl.m = m
    vis = np.flatnonzero(ok)
    if not len(vis):
        return 0.0, 0.0
    k = vis[-1]
    return float(p[k, 0] + cl.advance[k]), float(p[k, 1])


def decoration_pieces(cl, span_mask):
    """``(widths, transforms)`` of the decoration pieces of a span: runs of
    consecutive clusters of the span (``span_mask`` (C,) bool), broken
    where a cluster is moved relative to the previous one; each piece has
    the width of its clusters' advances and the transform of its first
    cluster (without the vertical path transform)."""
    idx = np.flatnonzero(span_mask & cl.visible)
    if not len(idx):
        return np.zeros(0), np.zeros((0, 3, 3))
    brk = np.ones(len(idx), bool)
    brk[1:] = (np.diff(idx) != 1) | cl.relshift[idx[1:]]
    starts = np.flatnonzero(brk)
    group = np.cumsum(brk) - 1
    widths = np.bincount(group, weights=cl.advance[idx], minlength=len(starts))
    if cl.m is None:
        first = idx[starts]
        return widths, (cl.x[first], cl.y[first])
    return widths, cl.m[idx[starts]]


def metric_boxes(cl):
    """(4 corners per visible cluster) of each cluster's metric box
    (advance by ascent to descent) under its transforms: ((V * 4, 2)
    float64, chunk frame), for the text's bounding box."""
    vis = np.flatnonzero(cl.visible)
    if not len(vis):
        return np.zeros((0, 2))
    adv = np.where(cl.advance[vis] > 0, cl.advance[vis], 1.0)
    a = cl.ascent[vis]
    d = cl.descent[vis]
    if cl.m is None and cl.pm is None:
        # translations only (the common case): the box's two corners
        x, y = cl.x[vis], cl.y[vis]
        return np.array([[x.min(), (y - a).min()], [(x + adv).max(), (y - d).max()]])
    m = cl.mats()[vis]
    xs = np.stack([np.zeros_like(adv), adv, adv, np.zeros_like(adv)], 1)
    ys = np.stack([-a, -a, -d, -d], 1)
    if cl.pm is not None:
        m = compose(m, cl.pm[vis])
    X = m[:, 0, 0, None] * xs + m[:, 0, 1, None] * ys + m[:, 0, 2, None]
    Y = m[:, 1, 0, None] * xs + m[:, 1, 1, None] * ys + m[:, 1, 2, None]
    return np.stack([X.ravel(), Y.ravel()], 1)


def glyph_matrices(cl):
    """(G, 3, 3) transforms of every glyph's outline (font units, y up) to
    the chunk frame (y down), and the (G,) mask of glyphs of visible
    clusters."""
    g = cl.g_cluster
    m = cl.mats()[g]
    if cl.pm is not None:
        m = compose(m, cl.pm[g])
    s = cl.g_scale
    local = compose(scale(s, -s), translate(cl.g_x, cl.g_y))
    return compose(m, local), cl.visible[g]


def _finite(v):
    return v is not None and math.isfinite(v)
