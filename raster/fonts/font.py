"""A loaded face: shaping, metrics and outlines with HarfBuzz (uharfbuzz).

:meth:`Font.load` keeps loaded fonts per process (keyed by path, face
index and modification time).  Fonts given as bytes (``@font-face`` with a
``data:`` URI) are registered with :func:`register_memory_font` under a
``memory:`` key and load like files.
"""

import io
import os
import struct
from typing import NamedTuple

import numpy as np

from ..geometry.path import CLOSE as _CLOSE, CUBIC as _CUBIC, LINE as _LINE, MOVE as _MOVE, \
    QUAD as _QUAD, Path
from ..geometry.rows import concat_ranges
from .files import MAX_FONT_BYTES, FontError, FontFace, check_font_data, quiet_fonttools, \
    read_font_bytes, sfnt_bytes
from ..errors import library_loaded
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
    """The sfnt bytes of a font file or ``memory:`` key (checked; WOFF and
    WOFF2 unpacked)."""
    if path.startswith('memory:'):
        data = _MEMORY.get(path)
        if data is None:
            raise FontError('font data %s is no longer registered' % path)
        return data
    data = read_font_bytes(path)
    return sfnt_bytes(data)


def _font_blob(path):
    """A HarfBuzz blob of the sfnt data of a font file or ``memory:`` key
    (checked like :func:`_font_data`).

    An sfnt file (or collection) is mapped into memory by HarfBuzz instead
    of read: only the pages of the tables it uses become resident, and
    they are the page cache's, not copies.  Its container is checked
    through a read-only mapping of its own first (sizes, the table
    directory).  (As with any mapped font file, a file cut short while a
    process uses it is unsafe; fonts are replaced, not truncated, by
    installers.)
    """
    import uharfbuzz as hb
    if not path.startswith('memory:'):
        kind, size = _check_font_file(path)
        if kind in ('sfnt', 'ttc'):
            try:
                blob = hb.Blob.from_file_path(path)
            except Exception:           # HarfBuzzError: then read it
                blob = None
            if blob is not None and len(blob) == size:
                return blob
    return hb.Blob(_font_data(path))


def _check_font_file(path):
    """(kind, size) of a font file, checked by
    :func:`~raster.fonts.files.check_font_data` through a read-only memory
    mapping (the file is not read).  Raises :class:`FontError`."""
    import mmap
    try:
        with open(path, 'rb') as fh:
            size = os.fstat(fh.fileno()).st_size
            if size > MAX_FONT_BYTES:
                raise FontError('font file is larger than %d bytes' % MAX_FONT_BYTES)
            if size < 12:
                raise FontError('not a font file (too short)')
            with mmap.mmap(fh.fileno(), 0, access=mmap.ACCESS_READ) as mm:
                return check_font_data(mm), size
    except (OSError, ValueError) as e:
        raise FontError('cannot read font file: %s' % (getattr(e, 'strerror', None) or e)) \
            from None


class Font:
    """A loaded face: shaping, metrics, the character map and glyph
    outlines, all through HarfBuzz (uharfbuzz).

    fontTools is not imported for a font in the common case (an sfnt font
    with TrueType or CFF outlines and no colour tables): only the colour
    tables (:attr:`color`), :attr:`tt` and :attr:`glyph_order` load it,
    on first use.

    Attributes
    ----------
    face : FontFace
    upem : float
        Units per em (``head``); all metrics below are in font units (y up).
    num_glyphs : int
        Number of glyphs (``maxp``); glyph ids are ``0 .. num_glyphs - 1``.
    ascender, descender, x_height, cap_height : float
        ``hhea`` ascent and descent (``OS/2`` typographic ones when its
        ``USE_TYPO_METRICS`` bit is set), ``OS/2`` x and cap heights.
    underline_position, underline_thickness : float
        From the ``post`` table (position of the top of the underline... as
        stored: the centre line offset below the baseline is negative).
    strikeout_position, strikeout_size : float
        From ``OS/2``.
    subscript_y, superscript_y : float
        ``OS/2`` subscript/superscript offsets (subscript positive = down).

    The metrics are the default instance's, also for a :meth:`variant`.
    """

    def __init__(self, face):
        import uharfbuzz as hb
        self.face = face
        try:
            blob = _font_blob(face.path)
        except FontError as e:
            raise FontError('cannot load font %s: %s' % (face.path, e)) from None
        self.hb_face = hb.Face(blob, face.index)
        tags = self.hb_face.table_tags
        try:
            if not tags:
                raise FontError('no face %d in the file' % face.index)
            head = self._table('head')
            if len(head) < 54:
                raise FontError("no 'head' table" if not head else "truncated 'head' table")
            self.upem = float(struct.unpack_from('>H', head, 18)[0])
            if not 16 <= self.upem <= 16384:
                raise FontError('unitsPerEm %g out of range' % self.upem)
            self.num_glyphs = int(self.hb_face.glyph_count)
            if self.num_glyphs <= 0:
                raise FontError("no glyphs (no 'maxp' table)")
            self._init_metrics()
        except (FontError, struct.error) as e:
            raise FontError('cannot load font %s: %s' % (face.path, e)) from None
        # a bitmap-only font (CBDT, sbix without outlines) has empty outlines
        self._has_outlines = any(t in tags for t in ('glyf', 'CFF ', 'CFF2'))
        self._color_tables = any(t in tags for t in ('COLR', 'SVG ', 'sbix', 'CBDT'))
        self.hb_font = hb.Font(self.hb_face)
        self.location = {}
        self._base = self
        self._tt = None
        self._axes = None
        self._color = None
        self._reset_caches()

    def _table(self, tag):
        """The bytes of table ``tag`` (empty when the face has none)."""
        return self.hb_face.reference_table(tag).data

    def _init_metrics(self):
        u = self.upem
        hhea, os2, post = self._table('hhea'), self._table('OS/2'), self._table('post')

        def field(data, fmt, off):
            return struct.unpack_from(fmt, data, off)[0] if len(data) >= off + 2 else None

        asc, desc = field(hhea, '>h', 4), field(hhea, '>h', 6)
        self.ascender = float(asc if asc is not None else 0.8 * u)
        self.descender = float(desc if desc is not None else -0.2 * u)
        if len(os2) >= 72 and field(os2, '>H', 62) & (1 << 7):     # USE_TYPO_METRICS
            self.ascender = float(field(os2, '>h', 68))
            self.descender = float(field(os2, '>h', 70))
        version = field(os2, '>H', 0) or 0
        xh = field(os2, '>h', 86) if version >= 2 else None
        ch = field(os2, '>h', 88) if version >= 2 else None
        self.x_height = float(xh or 0.5 * u)
        self.cap_height = float(ch or 0.7 * u)
        pos, thick = field(post, '>h', 8), field(post, '>h', 10)
        self.underline_position = float(pos if pos is not None else -0.1 * u)
        self.underline_thickness = float(thick or 0.05 * u) if thick is not None \
            else 0.05 * u
        has_os2 = len(os2) >= 30
        self.strikeout_position = float(field(os2, '>h', 28)) if has_os2 else 0.3 * u
        self.strikeout_size = float(field(os2, '>h', 26)) if has_os2 else self.underline_thickness
        self.subscript_y = float(field(os2, '>h', 16)) if has_os2 else 0.15 * u
        self.superscript_y = float(field(os2, '>h', 24)) if has_os2 else 0.45 * u

    def _reset_caches(self):
        """Empty the per-font caches: shaped strings (see
        :meth:`shape_arrays`) and packed outlines (see :meth:`outlines`)."""
        self._shaped = {}
        self._atlas = _GlyphAtlas(self._draw_glyph, self.num_glyphs)

    @property
    def tt(self):
        """The fontTools ``TTFont`` of the face (lazy: opened on first use,
        shared with the :meth:`variant` fonts; the colour tables use it)."""
        base = self._base
        if base._tt is None:
            from fontTools.ttLib import TTFont
            library_loaded('fontTools')     # its tables are read later, in log_warnings blocks
            with quiet_fonttools():
                try:
                    data = _font_data(self.face.path)
                    base._tt = TTFont(io.BytesIO(data), fontNumber=self.face.index, lazy=True)
                except FontError as e:
                    raise FontError('cannot load font %s: %s' % (self.face.path, e)) from None
                except Exception as e:      # fontTools raises many kinds on bad fonts
                    raise FontError('cannot load font %s: %s'
                                    % (self.face.path,
                                       ' '.join(str(e).split()) or type(e).__name__)) from None
        return base._tt

    @property
    def glyph_order(self):
        """Glyph names by glyph id (fontTools: loads :attr:`tt`)."""
        return self.tt.getGlyphOrder()

    @property
    def color(self):
        """The font's colour glyphs (:class:`~raster.fonts.color.ColorFont`),
        or None when it has no usable colour tables."""
        if self._color is None:
            cf = False
            if self._color_tables:
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
            self._axes = {a.tag: (float(a.min_value), float(a.default_value), float(a.max_value))
                          for a in self.hb_face.axis_infos}
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
            cached instance sharing the face (shaping and outlines at
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
        return self.hb_font.get_nominal_glyph(cp) is not None

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
            if self.hb_font.get_nominal_glyph(cp) is None:
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
        """(verbs, points) of one glyph drawn by HarfBuzz (empty arrays for
        a glyph that cannot be drawn), in font units at the font's
        variation location; see :class:`_OutlineRecorder`."""
        if not self._has_outlines or not 0 <= gid < self.num_glyphs:
            return Path.empty().verbs, Path.empty().points
        rec = _OutlineRecorder()
        self.hb_font.draw_glyph(gid, _draw_funcs(), rec)
        return rec.arrays()


_DRAW_FUNCS = []


def _draw_funcs():
    """The process's HarfBuzz draw callbacks into an :class:`_OutlineRecorder`."""
    if not _DRAW_FUNCS:
        import uharfbuzz as hb
        funcs = hb.DrawFuncs()
        funcs.set_move_to_func(_OutlineRecorder.move_to)
        funcs.set_line_to_func(_OutlineRecorder.line_to)
        funcs.set_quadratic_to_func(_OutlineRecorder.quadratic_to)
        funcs.set_cubic_to_func(_OutlineRecorder.cubic_to)
        funcs.set_close_path_func(_OutlineRecorder.close_path)
        _DRAW_FUNCS.append(funcs)
    return _DRAW_FUNCS[0]


class _OutlineRecorder:
    """Records what HarfBuzz draws of one glyph as path verbs and points.

    HarfBuzz ends a closed contour with an explicit line back to its first
    point; that line is dropped (the close draws it), so the verbs are
    those fontTools' pens give.  HarfBuzz starts a TrueType contour whose
    first two points are off-curve at their midpoint (fontTools: at the
    first on-curve point): the same closed contour, from another point.
    A contour without segments (a lone point) is left out.
    """

    __slots__ = ('verbs', 'points', 'start')

    def __init__(self):
        self.verbs = []
        self.points = []
        self.start = None

    @staticmethod
    def move_to(x, y, rec):
        rec.start = len(rec.points)
        rec.verbs.append(_MOVE)
        rec.points.append((x, y))

    @staticmethod
    def line_to(x, y, rec):
        rec.verbs.append(_LINE)
        rec.points.append((x, y))

    @staticmethod
    def quadratic_to(x1, y1, x, y, rec):
        rec.verbs.append(_QUAD)
        rec.points += ((x1, y1), (x, y))

    @staticmethod
    def cubic_to(x1, y1, x2, y2, x, y, rec):
        rec.verbs.append(_CUBIC)
        rec.points += ((x1, y1), (x2, y2), (x, y))

    @staticmethod
    def close_path(rec):
        verbs, points = rec.verbs, rec.points
        if rec.start is None:
            return
        if verbs[-1] == _LINE and points[-1] == points[rec.start]:
            verbs.pop()
            points.pop()
        if verbs[-1] == _MOVE:          # nothing drawn: no contour
            verbs.pop()
            points.pop()
        else:
            verbs.append(_CLOSE)
        rec.start = None

    def arrays(self):
        """(verbs (V,) uint8, points (P, 2) float64) of what was drawn."""
        points = np.array(self.points, np.float64).reshape(-1, 2)
        if not np.isfinite(points).all():
            return Path.empty().verbs, Path.empty().points
        return np.array(self.verbs, np.uint8), points


class Shaped(NamedTuple):
    """Arrays of one shaped string (see :meth:`Font.shape_arrays`);
    ``ordered``: one glyph per character, in logical order."""
    gid: np.ndarray
    cluster: np.ndarray
    pos: np.ndarray
    ordered: bool


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
            for g in sorted(set(missing.tolist())):     # (np.unique imports numpy.ma)
                self._add(g)
        vs, vn = self.vstart[gids], self.vcount[gids]
        ps, pn = self.pstart[gids], self.pcount[gids]
        return self.verbs[concat_ranges(vs, vn)], self.points[concat_ranges(ps, pn)], pn

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
