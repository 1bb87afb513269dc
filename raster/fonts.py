"""Font discovery and CSS font matching.

Fonts are looked for only in the directories a caller names (nothing is
taken from the system unless ``system=True`` is passed to :class:`FontDB`).
Every ``.ttf``, ``.otf``, ``.ttc`` and ``.otc`` file is read with fontTools
for its family names, weight (``OS/2.usWeightClass``), style (italic or
oblique from ``OS/2.fsSelection``/``head.macStyle``) and stretch
(``OS/2.usWidthClass``, 1..9).  Scans are cached by path and modification
time, so building many documents with the same font directory is cheap.

Matching follows CSS Fonts level 3 (section 5.2) in a reduced form: the
first family of a ``font-family`` list that exists wins; within it the
closest stretch, then the style (italic, else oblique, else normal), then
the weight by the CSS rule (400 prefers 500 next, 500 prefers 400, lighter
weights look lighter first, heavier ones heavier first).  Generic families
are mapped to concrete families (:data:`GENERIC_FAMILIES`, the mapping the
resvg test harness uses).  When nothing matches, :data:`DEFAULT_FAMILY` is
tried, then the serif family, then any font.

>>> parse_font_family('"Noto Sans", Arial ,serif')
['Noto Sans', 'Arial', 'serif']
>>> db = FontDB([])
>>> db.match(['serif']) is None
True
"""

import io
import os
import re
import warnings
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .errors import RasterError, RasterWarning
from .geometry.path import Path
from .geometry.pens import PathBuilder

__all__ = ['FontError', 'FontFace', 'FontDB', 'Font', 'parse_font_family',
           'GENERIC_FAMILIES', 'DEFAULT_FAMILY', 'FONT_EXTENSIONS']

#: Generic CSS families and the concrete family each maps to.
GENERIC_FAMILIES = {'serif': 'Noto Serif', 'sans-serif': 'Noto Sans', 'cursive': 'Yellowtail',
                    'fantasy': 'Sedgwick Ave Display', 'monospace': 'Noto Mono'}

#: Family used when no family of a list is available (usvg's default).
DEFAULT_FAMILY = 'Times New Roman'

#: File name endings scanned for fonts (lower case).
FONT_EXTENSIONS = ('.ttf', '.otf', '.ttc', '.otc')

_SYSTEM_DIRS = ('/usr/share/fonts', '/usr/local/share/fonts', '~/.fonts',
                '~/.local/share/fonts', '/Library/Fonts', '/System/Library/Fonts',
                'C:/Windows/Fonts')

_STRETCH = {'ultra-condensed': 1, 'extra-condensed': 2, 'condensed': 3,
            'semi-condensed': 4, 'normal': 5, 'semi-expanded': 6, 'expanded': 7,
            'extra-expanded': 8, 'ultra-expanded': 9}


class FontError(RasterError):
    """A font file cannot be read or used (corrupt file, no outlines)."""


@dataclass(frozen=True)
class FontFace:
    """One face of a font file.

    Attributes
    ----------
    path : str
        File path.
    index : int
        Face index inside a collection (0 for plain files).
    families : tuple of str
        Family names (typographic family first, then the legacy family),
        lower-cased for comparison is done by :class:`FontDB`.
    weight : int
        ``usWeightClass`` (100..900).
    style : str
        ``'normal'``, ``'italic'`` or ``'oblique'``.
    stretch : int
        ``usWidthClass`` (1 ultra-condensed .. 5 normal .. 9 ultra-expanded).
    """
    path: str
    index: int
    families: tuple
    weight: int = 400
    style: str = 'normal'
    stretch: int = 5


_SCAN_CACHE = {}      # (path, mtime_ns, size) -> tuple of FontFace
_FONT_CACHE = {}      # (path, index, mtime_ns) -> Font

#: Bounds of the caches: font descriptions matched per :class:`FontDB`,
#: shaped strings per :class:`Font`, and outline points packed per
#: :class:`Font` (the packed outlines start over beyond it).
_MATCH_LIMIT = 4096
_SHAPE_LIMIT = 4096
_ATLAS_MAX_POINTS = 1 << 22
#: Glyph sequences of up to ``_RUN_GLYPHS`` glyphs have their gathered
#: outlines remembered, ``_RUN_LIMIT`` sequences per :class:`Font`.
_RUN_GLYPHS = 32
_RUN_LIMIT = 1024


def cached(cache, key, make, limit):
    """``cache[key]``, made by ``make()`` when missing; the dict is emptied
    once it holds more than ``limit`` entries (a bound, not an LRU)."""
    value = cache.get(key)
    if value is None:
        value = make()
        if len(cache) > limit:
            cache.clear()
        cache[key] = value
    return value


def parse_font_family(value):
    """Split a CSS ``font-family`` value into a list of names.

    Quoted names keep their inner spaces; unquoted names have runs of
    whitespace collapsed.  Empty entries are dropped.

    >>> parse_font_family("'Times New Roman',  Noto   Serif, monospace")
    ['Times New Roman', 'Noto Serif', 'monospace']
    """
    out = []
    for m in re.finditer(r'\s*(?:"([^"]*)"|\'([^\']*)\'|([^,]*))\s*(?:,|$)', value or ''):
        q = m.group(1) if m.group(1) is not None else m.group(2)
        if q is not None:
            name = q.strip()
        else:
            name = ' '.join((m.group(3) or '').split())
        if name:
            out.append(name)
    return out


def _read_faces(path):
    from fontTools.ttLib import TTFont, TTCollection
    low = path.lower()
    if low.endswith(('.ttc', '.otc')):
        coll = TTCollection(path, lazy=True)
        fonts = list(coll.fonts)
    else:
        fonts = [TTFont(path, lazy=True)]
    try:
        return _faces_of(path, fonts)
    finally:
        for f in fonts:
            f.close()


def _faces_of(path, fonts):
    faces = []
    for index, f in enumerate(fonts):
        if 'name' not in f:
            continue
        name = f['name']
        fams = []
        for nid in (16, 1):
            rec = name.getDebugName(nid)
            if rec and rec not in fams:
                fams.append(rec)
        if not fams:
            continue
        weight, style, stretch = 400, 'normal', 5
        if 'OS/2' in f:
            os2 = f['OS/2']
            weight = int(os2.usWeightClass) or 400
            if weight < 10:             # some old fonts store 1..9
                weight *= 100
            stretch = min(max(int(os2.usWidthClass), 1), 9)
            sel = int(os2.fsSelection)
            if sel & 1:
                style = 'italic'
            elif sel & (1 << 9):
                style = 'oblique'
        elif 'head' in f and int(f['head'].macStyle) & 2:
            style = 'italic'
        faces.append(FontFace(path, index, tuple(fams), weight, style, stretch))
    return tuple(faces)


def _scan_file(path):
    try:
        s = os.stat(path)
    except OSError:
        return ()
    key = (path, s.st_mtime_ns, s.st_size)
    r = _SCAN_CACHE.get(key)
    if r is None:
        try:
            r = _read_faces(path)
        except Exception as e:      # fontTools raises many kinds on bad files
            warnings.warn('font file %s ignored: %s' % (path, e), RasterWarning, stacklevel=3)
            r = ()
        _SCAN_CACHE[key] = r
    return r


class FontDB:
    """The fonts of some directories, and CSS matching over them.

    Parameters
    ----------
    dirs : sequence of str
        Directories scanned recursively (missing ones are skipped).
    system : bool
        Also scan the usual system font directories.
    generic : dict, optional
        Generic family -> family name; defaults to :data:`GENERIC_FAMILIES`.

    >>> FontDB(['/nonexistent']).faces
    []
    """

    def __init__(self, dirs=(), system=False, generic=None):
        self.generic = dict(GENERIC_FAMILIES if generic is None else generic)
        self.faces = []
        roots = [str(d) for d in (dirs or ())]
        if system:
            roots += [os.path.expanduser(d) for d in _SYSTEM_DIRS]
        seen = set()
        for root in roots:
            if not os.path.isdir(root):
                continue
            for dirpath, dirnames, filenames in os.walk(root):
                dirnames.sort()
                for fn in sorted(filenames):
                    if not fn.lower().endswith(FONT_EXTENSIONS):
                        continue
                    p = os.path.join(dirpath, fn)
                    if p in seen:
                        continue
                    seen.add(p)
                    self.faces.extend(_scan_file(p))
        self._by_family = {}
        self._matches = {}      # (families, weight, style, stretch) -> FontFace
        for f in self.faces:
            for fam in f.families:
                lst = self._by_family.setdefault(fam.lower(), [])
                if f not in lst:
                    lst.append(f)

    def family_faces(self, family):
        """Faces of one family name (generic names resolved), maybe empty."""
        fam = self.generic.get(family.lower(), family) if family.lower() in self.generic else family
        return self._by_family.get(fam.lower(), [])

    def match(self, families, weight=400, style='normal', stretch='normal'):
        """The best :class:`FontFace` for a CSS font description, or None.

        Parameters
        ----------
        families : sequence of str
            ``font-family`` list (see :func:`parse_font_family`).
        weight : int
            100..900.
        style : str
            'normal', 'italic' or 'oblique'.
        stretch : str or int
            CSS keyword or 1..9.
        """
        if not self.faces:
            return None
        if isinstance(stretch, str):
            stretch = _STRETCH.get(stretch, 5)
        key = (tuple(families), int(weight), style, int(stretch))
        return cached(self._matches, key, lambda: self._match(*key), _MATCH_LIMIT)

    def _match(self, families, weight, style, stretch):
        for fam in list(families) + [DEFAULT_FAMILY, 'serif']:
            cands = self.family_faces(fam)
            if cands:
                return _best(cands, weight, style, stretch)
        return _best(self.faces, weight, style, stretch)

    def fallback_faces(self, face):
        """Other faces to try for characters ``face`` has no glyph for, in
        a fixed order (same style first)."""
        return [f for f in self.faces if f != face]


def _best(cands, weight, style, stretch):
    # stretch: closest, narrower first when desired <= normal
    def sdist(f):
        d = f.stretch - stretch
        if stretch <= 5:
            return (d > 0, abs(d))
        return (d < 0, abs(d))
    best_s = min(sdist(f) for f in cands)
    cands = [f for f in cands if sdist(f) == best_s]
    order = {'italic': ('italic', 'oblique', 'normal'),
             'oblique': ('oblique', 'italic', 'normal')}.get(style, ('normal', 'oblique', 'italic'))
    for s in order:
        sub = [f for f in cands if f.style == s]
        if sub:
            cands = sub
            break

    def wkey(f):
        w = f.weight
        if w == weight:
            return (0, 0)
        if 400 <= weight <= 500 and weight < w <= 500:
            return (1, w - weight)
        if weight < 400 or (weight <= 500 and w < weight):
            # lighter first (descending), then heavier (ascending)
            return (2, weight - w) if w < weight else (3, w - weight)
        # heavier first (ascending), then lighter (descending)
        return (2, w - weight) if w > weight else (3, weight - w)
    return min(cands, key=wkey)


class Font:
    """A loaded face: shaping with uharfbuzz, outlines with fontTools.

    Attributes
    ----------
    face : FontFace
    upem : int
        Units per em; all metrics below are in font units (y up).
    ascender, descender, x_height, cap_height : float
    underline_position, underline_thickness : float
        From the ``post`` table (position of the top of the underline... as
        stored: the centre line offset below the baseline is negative).
    strikeout_position, strikeout_size : float
        From ``OS/2``.
    subscript_y, superscript_y : float
        ``OS/2`` subscript/superscript offsets (subscript positive = down).
    """

    def __init__(self, face):
        import uharfbuzz as hb
        from fontTools.ttLib import TTFont
        self.face = face
        try:
            with open(face.path, 'rb') as fh:
                data = fh.read()
            self.tt = TTFont(io.BytesIO(data), fontNumber=face.index, lazy=True)
            self.glyph_set = self.tt.getGlyphSet()
            self.glyph_order = self.tt.getGlyphOrder()
            self.hb_face = hb.Face(hb.Blob(data), face.index)
            self.hb_font = hb.Font(self.hb_face)
        except Exception as e:
            raise FontError('cannot load font %s: %s' % (face.path, e)) from None
        tt = self.tt
        self.upem = float(tt['head'].unitsPerEm)
        hhea = tt['hhea'] if 'hhea' in tt else None
        os2 = tt['OS/2'] if 'OS/2' in tt else None
        self.ascender = float(hhea.ascent if hhea else 0.8 * self.upem)
        self.descender = float(hhea.descent if hhea else -0.2 * self.upem)
        if os2 is not None and getattr(os2, 'fsSelection', 0) & (1 << 7):
            self.ascender = float(os2.sTypoAscender)
            self.descender = float(os2.sTypoDescender)
        self.x_height = float(getattr(os2, 'sxHeight', 0) or 0.5 * self.upem) if os2 else 0.5 * self.upem
        self.cap_height = float(getattr(os2, 'sCapHeight', 0) or 0.7 * self.upem) if os2 else 0.7 * self.upem
        post = tt['post'] if 'post' in tt else None
        self.underline_position = float(post.underlinePosition if post else -0.1 * self.upem)
        self.underline_thickness = float(post.underlineThickness if post else 0.05 * self.upem) \
            or 0.05 * self.upem
        self.strikeout_position = float(os2.yStrikeoutPosition) if os2 else 0.3 * self.upem
        self.strikeout_size = float(os2.yStrikeoutSize) if os2 else self.underline_thickness
        self.subscript_y = float(os2.ySubscriptYOffset) if os2 else 0.15 * self.upem
        self.superscript_y = float(os2.ySuperscriptYOffset) if os2 else 0.45 * self.upem
        self._cmap = tt.getBestCmap() or {}
        self._axes = None
        self._reset_caches()

    def _reset_caches(self):
        """Empty the per-font caches: shaped strings (see
        :meth:`shape_arrays`) and packed outlines (see :meth:`outlines`)."""
        self._shaped = {}
        self._atlas = _GlyphAtlas(self._draw_glyph, len(self.glyph_order))

    @property
    def axes(self):
        """Variation axes: dict tag -> (min, default, max); empty for a
        static font."""
        if self._axes is None:
            self._axes = {} if 'fvar' not in self.tt else {
                a.axisTag: (float(a.minValue), float(a.defaultValue), float(a.maxValue))
                for a in self.tt['fvar'].axes}
        return self._axes

    def variant(self, coords):
        """This font at a variation-space location.

        Parameters
        ----------
        coords : dict
            Axis tag -> user-space value (``{'wght': 700}``); unknown axes
            are ignored, values are clamped to the axis range.

        Returns
        -------
        Font
            ``self`` for a static font or the default location, else a
            cached instance sharing the file data (shaping and outlines at
            that location).
        """
        axes = self.axes
        loc = {}
        for tag, v in coords.items():
            if tag in axes:
                lo, dflt, hi = axes[tag]
                v = min(max(float(v), lo), hi)
                if v != dflt:
                    loc[tag] = v
        if not loc:
            return self
        key = tuple(sorted(loc.items()))
        cache = self.__dict__.setdefault('_variants', {})
        f = cache.get(key)
        if f is None:
            import copy
            import uharfbuzz as hb
            f = copy.copy(self)
            f._variants = {}
            f.hb_font = hb.Font(self.hb_face)
            f.hb_font.set_variations(loc)
            f.glyph_set = self.tt.getGlyphSet(location=loc)
            f.location = loc
            f._reset_caches()
            if len(cache) > 64:
                cache.clear()
            cache[key] = f
        return f

    @classmethod
    def load(cls, face):
        """The cached :class:`Font` of a face (cache keyed by path, index and
        modification time).  Raises :class:`FontError`."""
        try:
            mt = os.stat(face.path).st_mtime_ns
        except OSError as e:
            raise FontError('cannot read font %s: %s' % (face.path, e.strerror)) from None
        return cached(_FONT_CACHE, (face.path, face.index, mt), lambda: cls(face), 64)

    def has_char(self, ch):
        """True when the font maps the character to a glyph."""
        return ord(ch) in self._cmap

    def shape(self, text, features=None):
        """Shape ``text`` (direction/script/language guessed).

        Returns
        -------
        list of (glyph_id, cluster, x_advance, y_advance, x_offset, y_offset)
            ``cluster`` is the index of the first character of the glyph's
            cluster in ``text``; advances and offsets in font units, y up.
        """
        r = self.shape_arrays(text, features)
        return list(zip(r.gid.tolist(), r.cluster.tolist(), *(r.pos.astype(np.int64).T.tolist())))

    def shape_arrays(self, text, features=None):
        """Shape ``text`` like :meth:`shape`, as arrays; cached per font by
        ``(text, features)`` (at most ``_SHAPE_LIMIT`` strings).

        Returns
        -------
        Shaped
            ``gid`` (G,) int64 glyph ids, ``cluster`` (G,) int64 first
            character of each glyph's cluster (at most ``len(text) - 1``),
            ``pos`` (G, 4) float64 x_advance, y_advance, x_offset, y_offset
            in font units (y up), glyphs in visual order; ``ordered`` is
            True when there is one glyph per character in logical order.
            The arrays are read-only.
        """
        key = (text, tuple(sorted(features.items())) if features else ())
        return cached(self._shaped, key, lambda: self._shape(text, features), _SHAPE_LIMIT)

    def _shape(self, text, features):
        import uharfbuzz as hb
        buf = hb.Buffer()
        buf.add_codepoints([ord(c) for c in text])
        buf.guess_segment_properties()
        hb.shape(self.hb_font, buf, features or {})
        infos = buf.glyph_infos
        gid = np.array([i.codepoint for i in infos], np.int64)
        cluster = np.minimum(np.array([i.cluster for i in infos], np.int64), max(len(text) - 1, 0))
        # GlyphPosition.position is (x_offset, y_offset, x_advance, y_advance)
        raw = np.array([p.position for p in buf.glyph_positions], np.float64).reshape(-1, 4)
        pos = raw[:, [2, 3, 0, 1]]
        for a in (gid, cluster, pos):
            a.flags.writeable = False
        ordered = len(gid) == len(text) and bool((cluster == np.arange(len(gid))).all())
        return Shaped(gid, cluster, pos, ordered)

    def outline(self, gid):
        """The outline of glyph ``gid`` as a :class:`~raster.geometry.path.Path` in
        font units (y up)."""
        verbs, points, _ = self._atlas.gather(np.array([gid], np.int64))
        return Path(verbs, points, _checked=True)

    def outlines(self, gids):
        """The outlines of many glyphs, concatenated in order.

        Parameters
        ----------
        gids : (G,) int ndarray
            Glyph ids (ids the font does not have give empty outlines).

        Returns
        -------
        verbs : (V,) uint8 ndarray
        points : (P, 2) float64 ndarray
            Font units, y up: a valid path (every outline starts with a
            move).
        npoints : (G,) int64 ndarray
            Number of points of each glyph (``npoints.sum() == P``).
        """
        return self._atlas.gather(np.asarray(gids, np.int64).reshape(-1))

    def _draw_glyph(self, gid):
        """(verbs, points) of one glyph drawn through fontTools (empty
        arrays for a glyph that cannot be drawn)."""
        from fontTools.pens.recordingPen import DecomposingRecordingPen
        try:
            name = self.glyph_order[gid]
            rec = DecomposingRecordingPen(self.glyph_set)     # components drawn in place
            self.glyph_set[name].draw(rec)
            b = PathBuilder()           # implied on-curve points: raster.geometry.pens
            rec.replay(b)
            p = b.path()
        except (KeyError, IndexError, RasterError):
            p = Path.empty()
        return p.verbs, p.points


class Shaped(NamedTuple):
    """Arrays of one shaped string (see :meth:`Font.shape_arrays`);
    ``ordered``: one glyph per character, in logical order."""
    gid: np.ndarray
    cluster: np.ndarray
    pos: np.ndarray
    ordered: bool


def _ranges(starts, counts):
    """Concatenated ``arange(start, start + count)`` of each pair.

    ``starts``, ``counts`` : (G,) int64 ndarrays; returns (counts.sum(),)
    int64.

    >>> _ranges(np.array([5, 0, 2]), np.array([2, 0, 3])).tolist()
    [5, 6, 2, 3, 4]
    """
    ends = np.cumsum(counts)
    total = int(ends[-1]) if len(ends) else 0
    return np.arange(total) + np.repeat(starts - (ends - counts), counts)


class _GlyphAtlas:
    """The outlines of the glyphs of one font drawn so far, packed into
    growing verb and point arrays, with each glyph's start and length
    indexed by glyph id, so that many glyphs are gathered with a few array
    operations.

    ``draw(gid) -> (verbs, points)`` draws a missing glyph.  Once more than
    ``_ATLAS_MAX_POINTS`` points are stored the atlas starts over (before a
    gather), which bounds its memory.  Glyph ids outside ``0..nglyphs-1``
    have empty outlines.
    """

    def __init__(self, draw, nglyphs):
        self.draw = draw
        self.nglyphs = int(nglyphs)
        self._clear()

    def _clear(self):
        n = self.nglyphs + 1            # the last slot: the empty outline
        self.vstart = np.full(n, -1, np.int64)     # -1: not drawn yet
        self.vstart[-1] = 0
        self.vcount = np.zeros(n, np.int64)
        self.pstart = np.zeros(n, np.int64)
        self.pcount = np.zeros(n, np.int64)
        self.verbs = np.zeros(256, np.uint8)
        self.points = np.zeros((1024, 2))
        self.nv = self.np = 0
        self.runs = {}          # gids.tobytes() -> gathered arrays (short runs)

    def gather(self, gids):
        """(verbs (V,) uint8, points (P, 2) float64, npoints (G,) int64)
        of the glyphs ``gids`` ((G,) int64), concatenated in order.  The
        result of a short run (``_RUN_GLYPHS`` glyphs at most) is
        remembered (``_RUN_LIMIT`` runs) and its arrays are read-only."""
        if self.np > _ATLAS_MAX_POINTS:
            self._clear()
        if len(gids) > _RUN_GLYPHS:
            return self._gather(gids)
        key = gids.tobytes()
        r = self.runs.get(key)
        if r is None:
            r = self._gather(gids)
            for a in r:
                a.flags.writeable = False
            if len(self.runs) >= _RUN_LIMIT:
                self.runs.clear()
            self.runs[key] = r
        return r

    def _gather(self, gids):
        gids = np.where((gids >= 0) & (gids < self.nglyphs), gids, self.nglyphs)
        missing = gids[self.vstart[gids] < 0]
        if len(missing):
            for g in np.unique(missing).tolist():
                self._add(g)
        vs, vn = self.vstart[gids], self.vcount[gids]
        ps, pn = self.pstart[gids], self.pcount[gids]
        return self.verbs[_ranges(vs, vn)], self.points[_ranges(ps, pn)], pn

    def _add(self, gid):
        verbs, points = self.draw(gid)
        nv, npt = len(verbs), len(points)
        if self.nv + nv > len(self.verbs):      # grow by doubling
            grown = np.zeros(max(2 * len(self.verbs), self.nv + nv), np.uint8)
            grown[:self.nv] = self.verbs[:self.nv]
            self.verbs = grown
        if self.np + npt > len(self.points):
            grown = np.zeros((max(2 * len(self.points), self.np + npt), 2))
            grown[:self.np] = self.points[:self.np]
            self.points = grown
        self.verbs[self.nv:self.nv + nv] = verbs
        self.points[self.np:self.np + npt] = points
        self.vstart[gid], self.vcount[gid] = self.nv, nv
        self.pstart[gid], self.pcount[gid] = self.np, npt
        self.nv += nv
        self.np += npt
