"""A loaded face: shaping with HarfBuzz (uharfbuzz), outlines with fontTools.

:meth:`Font.load` keeps loaded fonts per process (keyed by path, face
index and modification time).  Fonts given as bytes (``@font-face`` with a
``data:`` URI) are registered with :func:`register_memory_font` under a
``memory:`` key and load like files.
"""

import io
import os
from typing import NamedTuple

import numpy as np

from ..errors import RasterError
from ..geometry.path import Path
from ..geometry.pens import PathBuilder
from .files import FontError, FontFace, check_font_data, quiet_fonttools, read_font_bytes, sfnt_bytes
from .matching import cached
from .ranges import in_ranges

__all__ = ['Font', 'Shaped', 'register_memory_font', 'memory_font_data']

_FONT_CACHE = {}      # (path, index, mtime_ns) -> Font
_MEMORY = {}          # 'memory:<sha1>' -> sfnt bytes

#: Bounds of the caches: shaped strings per :class:`Font`, and outline
#: points packed per :class:`Font` (the packed outlines start over beyond it).
_SHAPE_LIMIT = 4096
_ATLAS_MAX_POINTS = 1 << 22
#: Glyph sequences of up to ``_RUN_GLYPHS`` glyphs have their gathered
#: outlines remembered, ``_RUN_LIMIT`` sequences per :class:`Font`.
_RUN_GLYPHS = 32
_RUN_LIMIT = 1024


def register_memory_font(data):
    """Register font ``data`` (bytes: sfnt, WOFF or WOFF2, checked) and
    return its ``memory:`` key (the same data gives the same key).

    Raises
    ------
    FontError
        Not a usable font container.
    """
    # imported here: hashlib maps OpenSSL (3 MB of RSS), which text
    # without @font-face data never needs
    import hashlib
    key = 'memory:' + hashlib.sha1(data).hexdigest()
    if key not in _MEMORY:
        kind = check_font_data(data)
        if len(_MEMORY) > 64:
            _MEMORY.clear()
        _MEMORY[key] = sfnt_bytes(data, kind)
    return key


def memory_font_data(key):
    """The sfnt bytes registered under ``key``, or None."""
    return _MEMORY.get(key)


def _font_data(path):
    if path.startswith('memory:'):
        data = _MEMORY.get(path)
        if data is None:
            raise FontError('font data %s is no longer registered' % path)
        return data
    data = read_font_bytes(path)
    return sfnt_bytes(data)


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
            data = _font_data(face.path)
        except FontError as e:
            raise FontError('cannot load font %s: %s' % (face.path, e)) from None
        with quiet_fonttools():
            try:
                self.tt = TTFont(io.BytesIO(data), fontNumber=face.index, lazy=True)
                # a bitmap-only font (CBDT, sbix without outlines) has empty outlines
                self.glyph_set = self.tt.getGlyphSet() if any(
                    t in self.tt for t in ('glyf', 'CFF ', 'CFF2')) else None
                self.glyph_order = self.tt.getGlyphOrder()
                self.upem = float(self.tt['head'].unitsPerEm)
                if not 16 <= self.upem <= 16384:
                    raise FontError('unitsPerEm %g out of range' % self.upem)
                self.hb_face = hb.Face(hb.Blob(data), face.index)
                self.hb_font = hb.Font(self.hb_face)
                self._init_metrics()
            except Exception as e:      # fontTools raises many kinds on bad fonts
                raise FontError('cannot load font %s: %s'
                                % (face.path, ' '.join(str(e).split()) or type(e).__name__)) \
                    from None
        self._data = data
        self._axes = None
        self._color = None
        self._reset_caches()

    def _init_metrics(self):
        tt = self.tt
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

    def _reset_caches(self):
        """Empty the per-font caches: shaped strings (see
        :meth:`shape_arrays`) and packed outlines (see :meth:`outlines`)."""
        self._shaped = {}
        self._atlas = _GlyphAtlas(self._draw_glyph, len(self.glyph_order))

    @property
    def color(self):
        """The font's colour glyphs (:class:`~raster.fonts.color.ColorFont`),
        or None when it has no usable colour tables."""
        if self._color is None:
            cf = False
            if any(t in self.tt for t in ('COLR', 'SVG ', 'sbix', 'CBDT')):
                from .color import ColorFont        # (only fonts with colour tables)
                try:
                    cf = ColorFont(self)
                except FontError:
                    cf = False
                if cf and cf.mask is None:
                    cf = False
            self._color = cf
        return self._color or None

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
            f.glyph_set = None if self.glyph_set is None else \
                self.tt.getGlyphSet(location=loc)
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
        if face.path.startswith('memory:'):
            mt = 0
        else:
            try:
                mt = os.stat(face.path).st_mtime_ns
            except OSError as e:
                raise FontError('cannot read font %s: %s' % (face.path, e.strerror)) from None
        return cached(_FONT_CACHE, (face.path, face.index, mt, face.unicode_range),
                      lambda: cls(face), 64)

    def has_char(self, ch):
        """True when the font maps the character to a glyph (and its face
        may be used for it: ``unicode_range``)."""
        cp = ord(ch)
        if self.face.unicode_range and not in_ranges(self.face.unicode_range, [cp])[0]:
            return False
        return cp in self._cmap

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

    def shape_arrays(self, text, features=None, direction=None):
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
            The arrays are read-only.  ``direction`` (``'ltr'``, ``'rtl'``,
            ``'ttb'``) overrides HarfBuzz's guess (the bidi level of a run).
        """
        key = (text, tuple(sorted(features.items())) if features else (), direction)
        return cached(self._shaped, key, lambda: self._shape(text, features, direction),
                       _SHAPE_LIMIT)

    def _shape(self, text, features, direction=None):
        import uharfbuzz as hb
        buf = hb.Buffer()
        cps = [ord(c) for c in text]
        outside = None
        if self.face.unicode_range:
            # characters outside the face's unicode-range are not this
            # face's: shaped as a character the font does not map, so that
            # they get glyph 0 (and a fallback font) and no ligature or
            # kerning joins them to the characters around them
            outside = ~in_ranges(self.face.unicode_range, cps)
            if outside.any():
                cps = np.where(outside, self._unmapped(), cps).tolist()
            else:
                outside = None
        buf.add_codepoints(cps)
        buf.guess_segment_properties()
        if direction is not None:
            buf.direction = direction
        hb.shape(self.hb_font, buf, features or {})
        infos = buf.glyph_infos
        gid = np.array([i.codepoint for i in infos], np.int64)
        cluster = np.minimum(np.array([i.cluster for i in infos], np.int64), max(len(text) - 1, 0))
        # GlyphPosition.position is (x_offset, y_offset, x_advance, y_advance)
        raw = np.array([p.position for p in buf.glyph_positions], np.float64).reshape(-1, 4)
        pos = raw[:, [2, 3, 0, 1]]
        if outside is not None and len(gid):
            gid[outside[cluster]] = 0
        for a in (gid, cluster, pos):
            a.flags.writeable = False
        ordered = len(gid) == len(text) and bool((cluster == np.arange(len(gid))).all())
        return Shaped(gid, cluster, pos, ordered)

    def _unmapped(self):
        """A code point the font's cmap does not map (a noncharacter)."""
        for cp in (0x10FFFF, 0x10FFFE, 0xFFFF, 0xFFFE, 0xFDD0):
            if cp not in self._cmap:
                return cp
        return 0x10FFFF         # (its glyphs are set to 0 after shaping anyway)

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
        if self.glyph_set is None:
            return Path.empty().verbs, Path.empty().points
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
