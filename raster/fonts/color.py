"""Colour glyphs as neutral descriptions: what a glyph of a colour font
paints, in font units (y up), without the render tree's types (the parser
turns a description into nodes).

Formats, tried in this order for a glyph (the order usvg uses):

* ``COLR`` version 1 (a paint graph: layers, solid colours, linear, radial
  and sweep gradients, affine transforms, glyph clips, composite modes)
  and version 0 (layers of glyph outlines with palette colours), colours
  from ``CPAL`` palette 0;
* ``SVG `` (an SVG document per glyph or per range of glyphs; the parser
  renders it: :class:`SvgGlyph`);
* bitmaps: ``sbix`` and ``CBDT``/``CBLC`` (PNG data of the largest strike:
  :class:`BitmapGlyph`);
* otherwise the glyph has no colour description (its outline is drawn).

A description is a tuple of *layers*, painted in order:

* :class:`FillLayer` -- a :class:`Brush` painted inside a path;
* :class:`ClipLayer` -- layers clipped to a path;
* :class:`CompositeLayer` -- a source drawn onto a backdrop with a
  composite mode (the COLRv1 names: ``src_over``, ``multiply``, ...);
* :class:`BitmapGlyph`, :class:`SvgGlyph` -- the whole glyph.

Paths are :class:`~raster.geometry.path.Path` objects in glyph space
(font units, y up) with every transform of the paint graph applied; a
brush carries the transform from its own space to glyph space.  A brush
painted without a glyph around it fills the glyph's clip box (``COLR``
``ClipList``), else the font's bounding box.

Bad tables (cycles of ``PaintColrGlyph``, a paint graph deeper than
:data:`MAX_DEPTH` or with more than :data:`MAX_LAYERS` layers, an SVG
document inflating beyond :data:`MAX_SVG_BYTES`) raise :class:`FontError`
for that glyph; :meth:`ColorFont.glyph` turns that into None (the outline
is drawn instead).
"""

import math
import struct
import zlib
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from ..geometry.path import Path
from ..geometry.transform import IDENTITY, Affine
from .files import FontError, quiet_fonttools

__all__ = ['Brush', 'ColorStop', 'FillLayer', 'ClipLayer', 'CompositeLayer', 'BitmapGlyph',
           'SvgGlyph', 'ColorFont', 'COMPOSITE_MODES', 'MAX_DEPTH', 'MAX_LAYERS',
           'MAX_SVG_BYTES']

#: Deepest COLRv1 paint graph followed (longer chains are an error).
MAX_DEPTH = 64
#: Most layers one colour glyph may expand to.
MAX_LAYERS = 4096
#: Largest SVG glyph document (after gzip inflation), bytes.
MAX_SVG_BYTES = 16 * 1024 * 1024

#: COLRv1 composite modes by their number in the table.
COMPOSITE_MODES = ('clear', 'src', 'dest', 'src_over', 'dest_over', 'src_in', 'dest_in',
                   'src_out', 'dest_out', 'src_atop', 'dest_atop', 'xor', 'plus', 'screen',
                   'overlay', 'darken', 'lighten', 'color_dodge', 'color_burn', 'hard_light',
                   'soft_light', 'difference', 'exclusion', 'multiply', 'hsl_hue',
                   'hsl_saturation', 'hsl_color', 'hsl_luminosity')

_EXTEND = ('pad', 'repeat', 'reflect')
_FOREGROUND = 0xFFFF


@dataclass(frozen=True)
class ColorStop:
    """A colour stop: ``offset`` along the colour line, ``color`` straight
    RGBA floats in [0, 1] with the stop's alpha applied, or None for the
    text's foreground colour (palette index 0xFFFF), then ``alpha``
    multiplies it."""
    offset: float
    color: Optional[Tuple[float, float, float, float]]
    alpha: float = 1.0


@dataclass(frozen=True)
class Brush:
    """What a :class:`FillLayer` paints.

    ``kind`` is ``'solid'`` (``stops[0]`` is the colour), ``'linear'``
    (``geometry`` = x0, y0, x1, y1: the colour line from offset 0 to 1,
    already made perpendicular to COLRv1's rotation point), ``'radial'``
    (x0, y0, r0, x1, y1, r1: circle 0 at offset 0 to circle 1 at offset 1)
    or ``'sweep'`` (cx, cy, start angle, end angle in degrees, counter
    clockwise from the x axis in y-up glyph space).  ``extend`` is
    ``'pad'``, ``'repeat'`` or ``'reflect'``; ``transform`` maps the
    brush's space to glyph space.
    """
    kind: str
    stops: Tuple[ColorStop, ...]
    geometry: Tuple[float, ...] = ()
    extend: str = 'pad'
    transform: Affine = IDENTITY


@dataclass(frozen=True, eq=False)
class FillLayer:
    """``brush`` painted inside ``path`` (glyph space, nonzero rule)."""
    path: Path
    brush: Brush


@dataclass(frozen=True, eq=False)
class ClipLayer:
    """``layers`` clipped to ``path`` (glyph space)."""
    path: Path
    layers: tuple


@dataclass(frozen=True, eq=False)
class CompositeLayer:
    """``source`` layers composited onto ``backdrop`` layers with ``mode``
    (one of :data:`COMPOSITE_MODES`), the result drawn source-over;
    ``box`` (x0, y0, x1, y1) bounds both (the glyph's clip box)."""
    mode: str
    source: tuple
    backdrop: tuple
    box: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True, eq=False)
class BitmapGlyph:
    """A bitmap glyph: ``data`` (PNG bytes) drawn in the rectangle whose
    lower-left corner is (``x``, ``y``) and size ``width`` x ``height``,
    glyph space (font units, y up)."""
    data: bytes
    x: float
    y: float
    width: float
    height: float


@dataclass(frozen=True, eq=False)
class SvgGlyph:
    """An SVG glyph: the document ``data`` (bytes, inflated), drawn in glyph
    space with y down (SVG's convention, the origin on the baseline);
    ``element_id`` is the element to draw (``glyph<id>``), or None for the
    whole document (a document of one glyph).  ``index`` numbers the
    font's documents (a cache key)."""
    data: bytes
    element_id: Optional[str]
    index: int


class ColorFont:
    """The colour tables of one :class:`~raster.fonts.Font`.

    ``font`` gives glyph outlines (``outline(gid)``), the fontTools font
    (``tt``) and the number of glyphs.  Descriptions are made on first use and
    remembered per glyph.

    Attributes
    ----------
    mask : (N,) bool ndarray or None
        For every glyph id: the glyph has a colour description; None when
        the font has no colour tables.
    """

    def __init__(self, font):
        self.font = font
        tt = font.tt
        self._glyphs = {}
        self._palette = None
        self._colr1 = self._colr0 = None
        self._clips = {}
        self._svg = None
        self._bitmaps = None
        n = font.num_glyphs
        mask = np.zeros(n, bool)
        has = False
        with quiet_fonttools():
            try:
                if 'COLR' in tt and 'CPAL' in tt:
                    has |= self._init_colr(tt, mask)
                if 'SVG ' in tt:
                    has |= self._init_svg(tt, mask)
                if 'sbix' in tt or ('CBDT' in tt and 'CBLC' in tt):
                    has |= self._init_bitmaps(tt, mask)
            except FontError:
                raise
            except Exception as e:      # fontTools raises many kinds on bad tables
                raise FontError('bad colour tables in %s: %s'
                                % (font.face.path, ' '.join(str(e).split()) or
                                   type(e).__name__)) from None
        self.mask = mask if has else None

    # -- tables -------------------------------------------------------------------

    def _gid(self, name):
        try:
            return self.font.tt.getGlyphID(name)
        except (KeyError, ValueError):
            return -1

    def _init_colr(self, tt, mask):
        colr = tt['COLR']
        pal = tt['CPAL'].palettes[0] if tt['CPAL'].palettes else []
        self._palette = [(c.red / 255.0, c.green / 255.0, c.blue / 255.0, c.alpha / 255.0)
                         for c in pal]
        n = len(mask)
        found = False
        if getattr(colr, 'version', 0) >= 1 and hasattr(colr, 'table'):
            t = colr.table
            self._colr_table = t
            if t.BaseGlyphList is not None:
                self._colr1 = {}
                for rec in t.BaseGlyphList.BaseGlyphPaintRecord:
                    g = self._gid(rec.BaseGlyph)
                    if 0 <= g < n:
                        self._colr1[g] = rec.Paint
                        mask[g] = True
                        found = True
            if t.ClipList is not None:
                for name, box in t.ClipList.clips.items():
                    g = self._gid(name)
                    if g >= 0:
                        self._clips[g] = (box.xMin, box.yMin, box.xMax, box.yMax)
            layers = None
            if t.BaseGlyphRecordArray is not None and t.LayerRecordArray is not None:
                recs = t.LayerRecordArray.LayerRecord
                self._colr0 = {}
                for rec in t.BaseGlyphRecordArray.BaseGlyphRecord:
                    layers = recs[rec.FirstLayerIndex:rec.FirstLayerIndex + rec.NumLayers]
                    self._add_v0(rec.BaseGlyph, [(r.LayerGlyph, r.PaletteIndex) for r in layers],
                                 mask)
                found |= bool(self._colr0)
        elif hasattr(colr, 'ColorLayers'):
            self._colr0 = {}
            for name, layers in colr.ColorLayers.items():
                self._add_v0(name, [(r.name, r.colorID) for r in layers], mask)
            found |= bool(self._colr0)
        return found

    def _add_v0(self, base, layers, mask):
        g = self._gid(base)
        if 0 <= g < len(mask):
            self._colr0[g] = [(self._gid(name), int(pi)) for name, pi in layers]
            mask[g] = True

    def _init_svg(self, tt, mask):
        """The SVG table's document index, read directly (fontTools would
        inflate every document at once, without a bound)."""
        data = tt.reader['SVG '] if tt.reader is not None and 'SVG ' in tt.reader else None
        if data is None or len(data) < 10:
            return False
        (off,) = struct.unpack_from('>I', data, 2)
        if off + 2 > len(data):
            raise FontError('truncated SVG table')
        (num,) = struct.unpack_from('>H', data, off)
        if off + 2 + 12 * num > len(data):
            raise FontError('truncated SVG document index')
        docs = []
        for k in range(num):
            start, end, doff, dlen = struct.unpack_from('>HHII', data, off + 2 + 12 * k)
            a = off + doff
            if a + dlen > len(data) or end < start:
                continue
            docs.append((start, end, a, dlen))
            lo, hi = min(start, len(mask)), min(end + 1, len(mask))
            mask[lo:hi] |= True
        self._svg = (data, docs, {})
        return bool(docs)

    def _init_bitmaps(self, tt, mask):
        """The largest strike of ``sbix`` or ``CBDT``/``CBLC`` (as usvg):
        glyph id -> (kind, record, pixels per em)."""
        self._bitmaps = {}
        if 'sbix' in tt:
            strikes = tt['sbix'].strikes
            if strikes:
                ppem = max(strikes)
                for name, g in strikes[ppem].glyphs.items():
                    if g.graphicType == 'png ' and g.imageData:
                        gid = self._gid(name)
                        if 0 <= gid < len(mask):
                            self._bitmaps[gid] = ('sbix', g, float(ppem))
        elif 'CBDT' in tt and 'CBLC' in tt:
            cblc, cbdt = tt['CBLC'], tt['CBDT']
            best = None
            for i, s in enumerate(cblc.strikes):
                ppem = s.bitmapSizeTable.ppemY
                if best is None or ppem > best[1]:
                    best = (i, ppem)
            if best is not None and best[0] < len(cbdt.strikeData):
                for name, g in cbdt.strikeData[best[0]].items():
                    gid = self._gid(name)
                    if 0 <= gid < len(mask):
                        self._bitmaps[gid] = ('cbdt', g, float(best[1]))
        for gid in self._bitmaps:
            mask[gid] = True
        return bool(self._bitmaps)

    # -- descriptions --------------------------------------------------------------

    def glyph(self, gid):
        """The colour description of glyph ``gid``: a tuple of layers, or
        None (no colour description, or a bad one: draw the outline)."""
        if self.mask is None or not 0 <= gid < len(self.mask) or not self.mask[gid]:
            return None
        r = self._glyphs.get(gid, False)
        if r is False:
            with quiet_fonttools():
                try:
                    r = self._describe(gid)
                except (FontError, RecursionError):
                    r = None
                except Exception:       # fontTools raises many kinds on bad tables
                    r = None
            if len(self._glyphs) > 4096:
                self._glyphs.clear()
            self._glyphs[gid] = r
        return r

    def _describe(self, gid):
        if self._colr1 is not None and gid in self._colr1:
            walker = _PaintWalker(self, gid)
            return tuple(walker.walk(self._colr1[gid], IDENTITY, 0))
        if self._colr0 is not None and gid in self._colr0:
            out = []
            for g, pi in self._colr0[gid]:
                out.append(FillLayer(self.font.outline(g),
                                     Brush('solid', (self._stop(0.0, pi, 1.0),))))
            return tuple(out)
        if self._svg is not None:
            r = self._svg_glyph(gid)
            if r is not None:
                return (r,)
        if self._bitmaps is not None and gid in self._bitmaps:
            r = self._bitmap_glyph(gid)
            if r is not None:
                return (r,)
        return None

    def _stop(self, offset, palette_index, alpha):
        if palette_index == _FOREGROUND:
            return ColorStop(float(offset), None, float(alpha))
        pal = self._palette
        if not 0 <= palette_index < len(pal):
            raise FontError('palette index %d out of range' % palette_index)
        return ColorStop(float(offset), pal[palette_index], float(alpha))

    def clip_box(self, gid):
        """(x0, y0, x1, y1) the area unbounded paints of glyph ``gid`` fill:
        its clip box, else the font's bounding box (``head``)."""
        b = self._clips.get(gid)
        if b is not None:
            return b
        head = self.font.tt['head']
        return (head.xMin, head.yMin, head.xMax, head.yMax)

    def _svg_glyph(self, gid):
        data, docs, inflated = self._svg
        for k, (start, end, a, n) in enumerate(docs):
            if start <= gid <= end:
                doc = inflated.get(k)
                if doc is None:
                    doc = inflated[k] = _inflate(data[a:a + n])
                return SvgGlyph(doc, None if start == end else 'glyph%d' % gid, k)
        return None

    def _bitmap_glyph(self, gid):
        kind, g, ppem = self._bitmaps[gid]
        upem = self.font.upem
        s = upem / ppem
        if kind == 'sbix':
            png = g.imageData
            w, h = _png_size(png)
            x0, y0 = 0.0, 0.0
            b = _control_box(self.font.outline(gid))
            if b is not None:
                x0 = b[0]
                # usvg: a glyph whose outline starts on the baseline is moved
                # down by 0.128 em (what Apple's renderer appears to do)
                y0 = b[1] if abs(b[1]) > 1e-6 else -0.128 * upem
            return BitmapGlyph(bytes(png), x0 + g.originOffsetX * s,
                               y0 + g.originOffsetY * s, w * s, h * s)
        if hasattr(g, 'ensureDecompiled'):
            g.ensureDecompiled()
        png = getattr(g, 'imageData', None)
        m = getattr(g, 'metrics', None)
        if not png or m is None or png[:8] != b'\x89PNG\r\n\x1a\n':
            return None             # only PNG bitmaps (formats 17, 18, 19)
        w, h = _png_size(png)
        bx = getattr(m, 'BearingX', getattr(m, 'horiBearingX', 0))
        by = getattr(m, 'BearingY', getattr(m, 'horiBearingY', 0))
        # the bitmap's top edge is BearingY pixels above the baseline
        return BitmapGlyph(bytes(png), bx * s, (by - h) * s, w * s, h * s)


def _inflate(doc):
    """An SVG glyph document, gzip-inflated with a bound when compressed."""
    doc = bytes(doc)
    if doc[:2] != b'\x1f\x8b':
        if len(doc) > MAX_SVG_BYTES:
            raise FontError('SVG glyph document larger than %d bytes' % MAX_SVG_BYTES)
        return doc
    d = zlib.decompressobj(16 + zlib.MAX_WBITS)
    try:
        out = d.decompress(doc, MAX_SVG_BYTES + 1)
    except zlib.error as e:
        raise FontError('corrupt compressed SVG glyph document: %s' % e) from None
    if len(out) > MAX_SVG_BYTES:
        raise FontError('SVG glyph document inflates beyond %d bytes' % MAX_SVG_BYTES)
    return out


def _png_size(png):
    """(width, height) from a PNG header."""
    if len(png) < 24 or png[:8] != b'\x89PNG\r\n\x1a\n':
        raise FontError('bitmap glyph is not a PNG image')
    return struct.unpack_from('>II', png, 16)


def _control_box(path):
    """(x0, y0, x1, y1) of a path's points (its control box) or None."""
    if not len(path.points):
        return None
    lo, hi = path.points.min(0), path.points.max(0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _rect(x0, y0, x1, y1):
    pts = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], float)
    return Path(np.array([0, 1, 1, 1, 4], np.uint8), pts, _checked=True)


class _PaintWalker:
    """Turns one COLRv1 paint graph into layers (see the module
    docstring)."""

    def __init__(self, cf, gid):
        self.cf = cf
        self.gid = gid
        self.count = 0
        self.active = set()         # PaintColrGlyph ids being expanded

    def _layers_added(self, k):
        self.count += k
        if self.count > MAX_LAYERS:
            raise FontError('colour glyph with more than %d layers' % MAX_LAYERS)

    def walk(self, p, m, depth):
        """Layers of paint ``p`` under transform ``m`` (paint space ->
        glyph space)."""
        if depth > MAX_DEPTH:
            raise FontError('COLR paint graph deeper than %d' % MAX_DEPTH)
        f = p.Format
        if f == 1:                              # PaintColrLayers
            lst = self.cf._colr_table.LayerList.Paint
            out = []
            for i in range(p.FirstLayerIndex, p.FirstLayerIndex + p.NumLayers):
                if i >= len(lst):
                    raise FontError('COLR layer index out of range')
                out.extend(self.walk(lst[i], m, depth + 1))
            return out
        if f in (2, 3, 4, 5, 6, 7, 8, 9):       # a brush without a glyph
            self._layers_added(1)
            x0, y0, x1, y1 = self.cf.clip_box(self.gid)
            return [FillLayer(_rect(x0, y0, x1, y1), self.brush(p, m))]
        if f == 10:                             # PaintGlyph
            self._layers_added(1)
            g = self.cf._gid(p.Glyph)
            outline = self.cf.font.outline(g).transform(m)
            inner, mi = p.Paint, m
            while 12 <= inner.Format <= 31:     # transforms of the brush
                mi = mi @ _paint_transform(inner)
                inner = inner.Paint
            if 2 <= inner.Format <= 9:
                return [FillLayer(outline, self.brush(inner, mi))]
            return [ClipLayer(outline, tuple(self.walk(p.Paint, m, depth + 1)))]
        if f == 11:                             # PaintColrGlyph
            g = self.cf._gid(p.Glyph)
            base = self.cf._colr1.get(g) if self.cf._colr1 else None
            if base is None or g in self.active:
                raise FontError('PaintColrGlyph cycle or missing base glyph')
            self.active.add(g)
            try:
                out = self.walk(base, m, depth + 1)
            finally:
                self.active.discard(g)
            x0, y0, x1, y1 = self.cf.clip_box(g)
            if g in self.cf._clips:
                return [ClipLayer(_rect(x0, y0, x1, y1).transform(m), tuple(out))]
            return out
        if 12 <= f <= 31:
            return self.walk(p.Paint, m @ _paint_transform(p), depth + 1)
        if f == 32:                             # PaintComposite
            mode = COMPOSITE_MODES[p.CompositeMode] if p.CompositeMode < len(
                COMPOSITE_MODES) else 'src_over'
            src = tuple(self.walk(p.SourcePaint, m, depth + 1))
            back = tuple(self.walk(p.BackdropPaint, m, depth + 1))
            return [CompositeLayer(mode, src, back, tuple(float(v) for v in
                                                          self.cf.clip_box(self.gid)))]
        raise FontError('unsupported COLR paint format %d' % f)

    def brush(self, p, m):
        f = p.Format
        cf = self.cf
        if f in (2, 3):
            return Brush('solid', (cf._stop(0.0, p.PaletteIndex, p.Alpha),), (), 'pad', m)
        line = p.ColorLine
        stops = tuple(sorted((cf._stop(s.StopOffset, s.PaletteIndex, s.Alpha)
                              for s in line.ColorStop), key=lambda s: s.offset))
        if not stops:
            stops = (ColorStop(0.0, (0.0, 0.0, 0.0, 0.0)),)
        ext = _EXTEND[line.Extend] if line.Extend < 3 else 'pad'
        if f in (4, 5):
            x0, y0, x1, y1 = _linear_points(p.x0, p.y0, p.x1, p.y1, p.x2, p.y2)
            return Brush('linear', stops, (x0, y0, x1, y1), ext, m)
        if f in (6, 7):
            return Brush('radial', stops, (float(p.x0), float(p.y0), float(p.r0), float(p.x1),
                                           float(p.y1), float(p.r1)), ext, m)
        return Brush('sweep', stops, (float(p.centerX), float(p.centerY), float(p.startAngle),
                                      float(p.endAngle)), ext, m)


def _linear_points(x0, y0, x1, y1, x2, y2):
    """The colour line of a COLRv1 linear gradient: from p0 to p1 projected
    onto the normal of p0p2 (the gradient is constant along p0p2)."""
    dx, dy = x2 - x0, y2 - y0
    ux, uy = x1 - x0, y1 - y0
    dd = dx * dx + dy * dy
    if dd == 0:
        return float(x0), float(y0), float(x1), float(y1)
    k = (ux * dx + uy * dy) / dd
    return float(x0), float(y0), float(x0 + ux - k * dx), float(y0 + uy - k * dy)


def _around(t, cx, cy):
    return Affine.translate(cx, cy) @ t @ Affine.translate(-cx, -cy)


def _paint_transform(p):
    """The Affine of a COLRv1 transform paint (formats 12..31, variable
    ones at their default values), y-up glyph space."""
    f = p.Format
    if f in (12, 13):
        t = p.Transform
        return Affine(t.xx, t.yx, t.xy, t.yy, t.dx, t.dy)
    if f in (14, 15):
        return Affine.translate(p.dx, p.dy)
    if f in (16, 17, 18, 19):
        t = Affine.scale(p.scaleX, p.scaleY)
    elif f in (20, 21, 22, 23):
        t = Affine.scale(p.scale, p.scale)
    elif f in (24, 25, 26, 27):
        a = math.radians(p.angle)
        c, s = math.cos(a), math.sin(a)
        t = Affine(c, s, -s, c, 0.0, 0.0)       # counter-clockwise, y up
    else:
        t = Affine(1.0, math.tan(math.radians(p.ySkewAngle)),
                   -math.tan(math.radians(p.xSkewAngle)), 1.0, 0.0, 0.0)
    if f in (18, 19, 22, 23, 26, 27, 30, 31):
        return _around(t, p.centerX, p.centerY)
    return t
