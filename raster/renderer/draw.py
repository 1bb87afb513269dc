"""The renderer's loop: a resolved tree onto a canvas.

Every node is drawn with its *current transformation matrix* (CTM), user
space to device (or layer) pixels, x right and y down:

* a :class:`~raster.tree.Group` that only transforms composes its
  transform onto the CTM; one that needs a layer renders its children into
  a transparent layer over its device box, then applies its filters, clip
  path and mask, and composites the layer with its opacity and blend mode
  (a group clipped by one device rectangle is drawn through the
  rectangle's coverage instead, :class:`~raster.pixels.views.ClipRect`);
* a :class:`~raster.tree.PathNode` draws its fill, stroke and markers in
  ``paint_order``; masks come from :class:`~raster.renderer.batch.Masks`,
  colours from the paint (:mod:`raster.renderer.paint`);
* an :class:`~raster.tree.ImageNode` resamples its pixels, or renders its
  SVG document, clipped to its viewport.

The loop never parses a string and never imports the parser.
"""

import math
import warnings

import numpy as np

from .. import limits
from ..errors import LimitError, RasterError, RasterWarning
from ..geometry.path import Path
from ..pixels.canvas import MANY_GROUP_PIXELS, MANY_MASK_PIXELS, Canvas
from ..pixels.compositing import blend_layer
from ..geometry.flattening import flatten
from ..pixels.scan import Mask, coverage
from ..pixels.views import ClipRect, pixel_overlaps
from ..geometry.transform import Affine
from ..tree import Group, ImageNode, MaskType, PaintItem, PathNode, SolidPaint
from .batch import Masks
from .bounds import clip_rect, group_box, pixel_box
from .paint import STRIP_PIXELS, draw_pixels, gradient_colors, mesh_colors, sample

__all__ = ['Renderer']

# Work (raster.limits max_pixel_work, in array passes over a pixel) of a
# layer, clip or mask canvas: per pixel (made, drawn into, combined and
# composited), and what one costs whatever its size (planning and batching
# its content: a few milliseconds).  A painted path costs its mask's
# pixels: its fixed costs are bounded by max_elements, but not its area.
_LAYER_PASSES = 4
_LAYER_FIXED = 1 << 21

# Mask pixels of solid fills held by the renderer before they are
# composited together (:meth:`Renderer.settle`): one group of fill_many
# (holding more gains nothing and costs memory).
_RUN_PIXELS = MANY_GROUP_PIXELS


class Renderer:
    """Draws tree nodes onto canvases with flattening ``tolerance`` (device
    pixels), keeping the outlines that reach past a window in ``store``
    (a :class:`~raster.renderer.batch.EdgeStore` or None).  The layers it
    makes (groups, masks, SVG images) have the storage ``dtype`` (float32,
    or uint8 when drawing onto an 8-bit canvas: a quarter of the memory);
    clip coverage is one float32 channel."""

    def __init__(self, tolerance, dtype=np.float32, store=None):
        self.tol = tolerance
        self.dtype = np.dtype(dtype)
        self.masks = Masks(tolerance, store)
        self._limit_warned = False
        # windowed rendering: id(canvas) -> (ox, oy, fw, fh), see draw()
        self._places = {}
        self._too_deep = False
        # solid fills held for one canvas, composited together by settle():
        # [(mask, colour, opacity)], their canvas and their mask pixels
        self._run = []
        self._run_canvas = None
        self._run_pixels = 0

    def draw(self, node, t, canvas, origin=(0, 0), size=None):
        """Draw ``node`` (and what is below it) with CTM ``t`` on ``canvas``,
        planning the masks of its subtree first.

        ``origin`` : (ox, oy) ints
            Where the canvas's pixel (0, 0) lies in the output that ``t``
            maps to (its *frame*, of ``size`` (w, h) pixels, default the
            canvas's size): a canvas that is a window of a larger output is
            drawn with the whole output's CTM.  Every path is then
            flattened and stroked in the whole output's pixels, exactly as
            the whole render does, and only its edges are moved onto the
            window (by whole pixels: exact); layers are placed and clipped
            as on the whole output, and filter layers reach past the window
            by the margin their primitives read
            (:func:`raster.renderer.filters.filter_margin`), so the
            window's pixels are those of the whole render."""
        ox, oy = (int(v) for v in origin)
        fw, fh = (canvas.width, canvas.height) if size is None else (int(v) for v in size)
        place = (ox, oy, fw, fh)
        windowed = place != (0, 0, canvas.width, canvas.height)
        if windowed:
            self._places[id(canvas)] = place
        try:
            self.masks.plan([node], t, canvas, (ox, oy), output=True)
            self.node(node, t, canvas)
        finally:
            try:
                self.settle()
            finally:
                if windowed:
                    self._places.pop(id(canvas), None)
        if self._too_deep:
            self._too_deep = False
            self._left_out(LimitError('nested too deeply'))

    def settle(self):
        """Composite the solid fills held (see :meth:`paint`) onto their
        canvas, in order (:meth:`raster.pixels.canvas.Canvas.fill_many`:
        the pixels of filling them one by one).  Called before anything
        else reads or writes a canvas: another paint, a layer's effects or
        compositing, an image, the end of :meth:`draw`."""
        if not self._run:
            return
        run, canvas = self._run, self._run_canvas
        self._run, self._run_canvas, self._run_pixels = [], None, 0
        canvas.fill_many(run)

    def _hold(self, canvas, mask, color, opacity):
        """Hold a solid fill of ``canvas`` (a Canvas) for :meth:`settle`."""
        if canvas is not self._run_canvas or self._run_pixels + mask.data.size > _RUN_PIXELS:
            self.settle()
            self._run_canvas = canvas
        self._run.append((mask, color, opacity))
        self._run_pixels += mask.data.size

    def place(self, canvas):
        """``(ox, oy, fw, fh)``: where ``canvas`` (or the canvas of a
        view) lies in its frame, and the frame's size (see :meth:`draw`)."""
        base = canvas
        while isinstance(base, ClipRect):       # a view: its canvas's place
            base = base.canvas
        p = self._places.get(id(base))
        return (0, 0, base.width, base.height) if p is None else p

    def local(self, t, canvas):
        """The CTM ``t`` (to ``canvas``'s frame) as a CTM to the canvas's
        own pixels: for paints, images and filters, which work in them."""
        p = self._places.get(id(canvas))
        if p is None and isinstance(canvas, ClipRect):
            p = self.place(canvas)
        if p is None or (p[0] == 0 and p[1] == 0):
            return t
        return Affine.translate(-p[0], -p[1]) @ t

    def _push(self, canvas, place):
        """Record ``canvas``'s place (see :meth:`place`) unless it is the
        whole of its frame; returns whether it was recorded."""
        if place == (0, 0, canvas.width, canvas.height):
            return False
        self._places[id(canvas)] = place
        return True

    def coverage(self, path, t, w, h, off, rule='nonzero', antialias=True, straddle=True):
        """Coverage Mask (or None) of ``path`` under ``t`` (CTM to the
        frame) on a ``w x h`` canvas at ``off`` (ox, oy) in that frame:
        flattened in the frame's pixels, the edges moved by whole pixels."""
        e = flatten(path, self.tol, transform=t, straddle=straddle).edges(close_all=True)
        if off[0] or off[1]:
            e = e - np.array(off[:2], np.float64)
        return coverage(e, w, h, rule, antialias)

    def _layer_box(self, g, ct, canvas):
        """``(px, full)``: the pixel box of a group's layer and the box of
        the whole render's layer, both in the frame of ``canvas``
        (:meth:`place`), or None.  ``px`` is ``full`` clipped to the
        canvas, grown by the reach of the group's filters."""
        ox, oy, fw, fh = self.place(canvas)
        if g.filters:
            from .filters import filter_box, filter_margin, filter_pixel_box
            box = filter_box(g.filters, ct, lambda: group_box(g, ct))
        else:
            box = group_box(g, ct)
        if box is None:
            return None
        full = filter_pixel_box(box, fw, fh) if g.filters else pixel_box(box, fw, fh)
        if full is None:
            return None
        w, h = canvas.width, canvas.height
        if ox == 0 and oy == 0 and w == fw and h == fh:
            return full, full
        m = filter_margin(g.filters, ct) if g.filters else 0
        if m is None:                   # reads the whole region (feTile...)
            px = full
        else:
            m = int(math.ceil(m))
            px = (max(full[0], ox - m), max(full[1], oy - m),
                  min(full[2], ox + w + m), min(full[3], oy + h + m))
        if px[2] <= px[0] or px[3] <= px[1]:
            return None
        return px, full

    def node(self, node, t, canvas):
        try:
            if isinstance(node, Group):
                self.group(node, t, canvas)
            elif isinstance(node, PathNode):
                self.path(node, t, canvas)
            elif isinstance(node, ImageNode):
                self.image(node, t, canvas)
        except LimitError as e:         # a budget of raster.limits: this node left out
            self._left_out(e)
        except RecursionError:          # nested deeper than Python's stack allows
            self._too_deep = True       # warned by draw(), once the stack has unwound

    # -- groups ----------------------------------------------------------------
    def group(self, g, t, canvas):
        ct = t @ g.transform
        if not g.needs_layer:
            for c in g.children:
                self.node(c, ct, canvas)
            return
        if g.opacity <= 0:
            return
        box = clip_rect(g, t)
        if box is not None:
            # clipped by an axis-aligned rectangle only: no layer, the
            # children are drawn through the rectangle's coverage
            ox, oy = self.place(canvas)[:2]
            if ox or oy:
                box = (box[0] - ox, box[1] - oy, box[2] - ox, box[3] - oy)
            view = ClipRect(canvas, box)
            if not view.empty:
                for c in g.children:
                    self.node(c, ct, view)
            return
        # what a layer costs whatever its size, before its box is measured
        limits.spend_work(_LAYER_FIXED, 'a group layer')
        # the layer: the group's box, or its filter region (effects draw
        # outside the content); the filter machinery loads with the first
        # filter drawn
        boxes = self._layer_box(g, ct, canvas)
        if boxes is None:
            return
        (x0, y0, x1, y1), full = boxes
        limits.spend_work(_LAYER_PASSES * (x1 - x0) * (y1 - y0), 'a group layer')
        layer = Canvas(x1 - x0, y1 - y0, dtype=self.dtype)
        # the CTM of the whole render's layer (its pixels from full's corner)
        lt = Affine.translate(-full[0], -full[1]) @ ct
        place = (x0 - full[0], y0 - full[1], full[2] - full[0], full[3] - full[1])
        pushed = self._push(layer, place)
        try:
            self.masks.plan(g.children, lt, layer, place[:2])
            for c in g.children:
                self.node(c, lt, layer)
            self.settle()
            if g.filters:
                from .filters import filter_layer
                filter_layer(g.filters, layer, self.local(lt, layer), draw=self._draw_new)
            if g.clip_path is not None:
                layer.scale(self.clip_coverage(g.clip_path, lt, layer.width, layer.height,
                                               place[:2]))
            if g.mask is not None:
                layer.scale(self.mask_values(g.mask, lt, layer.width, layer.height, place))
        finally:
            if pushed:
                self._places.pop(id(layer), None)
        self.settle()
        ox, oy = self.place(canvas)[:2]
        blend_layer(canvas, layer.data, x0 - ox, y0 - oy, float(g.opacity), g.blend_mode)

    def _draw_new(self, node, m, w, h):
        """``node`` drawn with CTM ``m`` into a new (h, w, 4) premultiplied
        array (feImage content)."""
        img = Canvas(w, h)
        self.node(node, m, img)
        self.settle()
        return img.data

    # -- clip paths and masks ------------------------------------------------
    def clip_coverage(self, clip, t, w, h, off=(0, 0)):
        """(h, w) float32 coverage of a ClipPath with CTM ``t`` (the
        clipped group's user space to the layer's frame; the layer lies at
        ``off`` in it, see :meth:`draw`)."""
        limits.spend_work(_LAYER_PASSES * w * h + _LAYER_FIXED, 'a clip path')
        cov = np.zeros((h, w), np.float32)
        self._clip_node(clip.root, t @ clip.transform, cov, off)
        if clip.clip_path is not None:
            cov *= self.clip_coverage(clip.clip_path, t, w, h, off)
        return cov

    def _clip_node(self, n, t, cov, off=(0, 0)):
        """Inside a clip path only geometry counts: the coverage of each path
        (with its rule, which carries ``clip-rule``, whatever its paint) is
        united with ``cov`` ((h, w) float32, in place) as alpha composites:
        ``cov + k (1 - cov)``; a clip path on a child still restricts that
        child."""
        if isinstance(n, Group):
            ct = t @ n.transform
            if n.clip_path is not None:
                limits.spend_work(_LAYER_PASSES * cov.size + _LAYER_FIXED, 'a clip path')
                sub = np.zeros_like(cov)
                for c in n.children:
                    self._clip_node(c, ct, sub, off)
                h, w = cov.shape
                sub *= self.clip_coverage(n.clip_path, ct, w, h, off)
                sub *= 1.0 - cov
                cov += sub
                return
            for c in n.children:
                self._clip_node(c, ct, cov, off)
        elif isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
            rule = n.fill.rule if n.fill is not None else 'nonzero'
            h, w = cov.shape
            try:
                m = self.coverage(n.path, t, w, h, off, rule, n.antialias)
            except LimitError as e:
                self._left_out(e)
                return
            if m is not None:
                limits.spend_work(m.data.size, 'a clip path')
                _unite(cov, m)

    def mask_values(self, mask, t, w, h, place=None):
        """(h, w) float32 values of a Mask with CTM ``t`` (to the masked
        layer's frame; ``place``: the layer's, see :meth:`place`)."""
        limits.spend_work(_LAYER_PASSES * w * h + _LAYER_FIXED, 'a mask')
        layer = Canvas(w, h, dtype=self.dtype)
        place = (0, 0, w, h) if place is None else place
        pushed = self._push(layer, place)
        try:
            self.node(mask.root, t, layer)
            self.settle()
        finally:
            if pushed:
                self._places.pop(id(layer), None)
        if mask.kind == MaskType.ALPHA:
            m = layer.combine((0.0, 0.0, 0.0, 1.0))
        else:
            # luminance of the premultiplied colour = luminance * alpha
            m = layer.combine((0.2125, 0.7154, 0.0721, 0.0))
        del layer
        x, y, rw, rh = mask.rect
        if t.b == 0.0 and t.c == 0.0:
            # an axis-aligned rectangle: exact-area coverage, separable
            x0, x1 = sorted((t.a * x + t.e, t.a * (x + rw) + t.e))
            y0, y1 = sorted((t.d * y + t.f, t.d * (y + rh) + t.f))
            ox, oy = place[:2]
            _times_rect(m, x0 - ox, y0 - oy, x1 - ox, y1 - oy)
        else:
            rect = Path.polygon([(x, y), (x + rw, y), (x + rw, y + rh), (x, y + rh)])
            rc = self.coverage(rect, t, w, h, place, straddle=False)
            if rc is None:
                return np.zeros((h, w), np.float32)
            _times_mask(m, rc)
        if mask.mask is not None:
            m *= self.mask_values(mask.mask, t, w, h, place)
        np.clip(m, 0.0, 1.0, out=m)
        return m

    # -- paths ---------------------------------------------------------------
    def path(self, n, t, canvas):
        if n.path is None or len(n.path.verbs) == 0:
            return
        try:
            for item in n.paint_order:
                if item == PaintItem.FILL and n.fill is not None:
                    self.fill(n, t, canvas)
                elif item == PaintItem.STROKE and n.stroke is not None:
                    self.stroke(n, t, canvas)
                elif item == PaintItem.MARKERS and n.markers is not None:
                    self.node(n.markers, t, canvas)
        except LimitError as e:
            self._left_out(e)

    def _left_out(self, e):
        """One element beyond a budget of :mod:`raster.limits` (a
        coordinate above max_coord, too many dashes, the pixel work
        spent...) is left out, with one warning per render; the rest of the
        document is drawn."""
        if not self._limit_warned:
            self._limit_warned = True
            warnings.warn('element not drawn: %s' % e, RasterWarning, stacklevel=3)

    def fill(self, n, t, canvas):
        f = n.fill
        if f.opacity <= 0:
            return
        m = self.masks.fill(n, t, canvas, self.place(canvas)[:2])
        if m is not None:
            self.paint(canvas, m, f.paint, f.opacity, t)

    def stroke(self, n, t, canvas):
        s = n.stroke
        if s.opacity <= 0 or s.style.width <= 0:
            return
        m, factor = self.masks.stroke(n, t, canvas, self.place(canvas)[:2])
        if m is not None:
            self.paint(canvas, m, s.paint, s.opacity * factor, t)

    def paint(self, canvas, mask, paint, opacity, t):
        """Composite ``paint`` (in the user space that ``t`` maps to the
        canvas's frame) through coverage ``mask`` with ``opacity``.  Gradient and
        pattern colours are made and composited a strip of rows at a time
        (:data:`raster.renderer.paint.STRIP_PIXELS`).  A solid paint through
        a small mask on a canvas (or on a canvas seen through a
        :class:`~raster.pixels.views.ClipRect`) is held and composited with
        the solid fills that follow it (:meth:`settle`); anything else
        composites the fills held first."""
        limits.spend_work(mask.data.size, 'a path')
        if isinstance(paint, SolidPaint):
            if mask.data.size <= MANY_MASK_PIXELS:
                if type(canvas) is Canvas:
                    self._hold(canvas, mask, paint.color, opacity)
                    return
                if type(canvas) is ClipRect and type(canvas.canvas) is Canvas:
                    for m in canvas.masks(mask):
                        self._hold(canvas.canvas, m, paint.color, opacity)
                    return
            self.settle()
            canvas.fill(mask, paint.color, opacity)
            return
        self.settle()
        # a paint server: the parser loaded their module
        from ..tree.servers import (LinearGradient, MeshGradient, Pattern, RadialGradient,
                                    SweepGradient)
        # colours are computed at the pixel centres of the canvas's frame
        # with the frame's CTM: a window gets the whole render's colours
        ox, oy = self.place(canvas)[:2]
        if isinstance(paint, (LinearGradient, RadialGradient, SweepGradient)):
            def colors(m):
                return gradient_colors(paint, m, t)
        elif isinstance(paint, MeshGradient):
            def colors(m):
                return mesh_colors(paint, m, t, self.tol)
        elif isinstance(paint, Pattern):
            limits.spend_work(8 * mask.data.size, 'a pattern')     # sampled per pixel
            tile = self.pattern_tile(paint, t)
            if tile is None:
                return

            def colors(m):
                return _sample_tile(tile, m)
        else:
            return
        h, w = mask.data.shape
        step = max(1, STRIP_PIXELS // max(1, w))
        for r0 in range(0, h, step):
            m = mask if h <= step else Mask(mask.data[r0:r0 + step], mask.x0, mask.y0 + r0)
            src = colors(m if not (ox or oy) else Mask(m.data, m.x0 + ox, m.y0 + oy))
            if src is not None:
                canvas.composite(src, m.x0, m.y0, opacity)

    def pattern(self, p, mask, t):
        """Premultiplied (h, w, 4) colours of a pattern over the mask window,
        multiplied by the coverage; None when the tile is empty (see
        :meth:`pattern_tile`)."""
        tile = self.pattern_tile(p, t)
        return None if tile is None else _sample_tile(tile, mask)

    def pattern_tile(self, p, t):
        """``(tile pixels, device -> tile transform)`` of a pattern painting
        a node whose user space ``t`` maps to the canvas; None when the tile
        is empty.

        The tile is rendered once into a raster at device resolution and
        sampled (bilinear, wrapping) through the inverse of the tile-to-device
        transform, the way resvg paints patterns."""
        x, y, w, h = p.rect
        if not (w > 0 and h > 0):
            return None
        tile_to_dev = t @ p.transform @ Affine.translate(x, y)
        sx = math.hypot(tile_to_dev.a, tile_to_dev.b)
        sy = math.hypot(tile_to_dev.c, tile_to_dev.d)
        if not (math.isfinite(w * sx) and math.isfinite(h * sy) and sx > 0 and sy > 0):
            return None                 # a tile of no or of infinite size
        tw = max(1, int(math.ceil(w * sx)))
        th = max(1, int(math.ceil(h * sy)))
        if tw * th > limits.current().max_pixels // 4:
            return None
        limits.spend_work(_LAYER_PASSES * tw * th + _LAYER_FIXED, 'a pattern')
        # As resvg: the tile raster has whole-pixel size (rounded up) and the
        # content is drawn at the device scale, so the period is tw / sx
        # (up to a pixel longer than the tile): references tile this way.
        tile = Canvas(tw, th)
        self.node(p.root, Affine.scale(sx, sy) @ p.content_transform, tile)
        self.settle()
        try:
            inv = (tile_to_dev @ Affine.scale(1.0 / sx, 1.0 / sy)).inverse()
        except RasterError:
            return None
        return tile.data, inv

    # -- images ----------------------------------------------------------------
    def image(self, n, t, canvas):
        if n.opacity <= 0:
            return
        self.settle()
        if n.tree is not None:
            self.svg_image(n, t, canvas)
        elif n.pixels is not None:
            draw_pixels(n, self.local(t, canvas), canvas, self.tol)

    def svg_image(self, n, t, canvas):
        it = t @ n.transform
        g = Group(children=[n.tree.root])
        if n.clip is None:
            self.node(g, it, canvas)
            return
        x, y, w, h = n.clip
        # the layer of the whole render (the clip's pixel box in the frame),
        # clipped to the canvas
        ox, oy, fw, fh = self.place(canvas)
        box = t.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]], float))
        full = pixel_box((box[:, 0].min(), box[:, 1].min(), box[:, 0].max(), box[:, 1].max()),
                         fw, fh)
        if full is None:
            return
        x0, y0 = max(full[0], ox), max(full[1], oy)
        x1, y1 = min(full[2], ox + canvas.width), min(full[3], oy + canvas.height)
        if x1 <= x0 or y1 <= y0:
            return
        limits.spend_work(_LAYER_PASSES * (x1 - x0) * (y1 - y0) + _LAYER_FIXED,
                          'an SVG image')
        layer = Canvas(x1 - x0, y1 - y0, dtype=self.dtype)
        lt = Affine.translate(-full[0], -full[1])
        place = (x0 - full[0], y0 - full[1], full[2] - full[0], full[3] - full[1])
        pushed = self._push(layer, place)
        try:
            self.masks.plan([g], lt @ it, layer, place[:2])
            self.node(g, lt @ it, layer)
            self.settle()
        finally:
            if pushed:
                self._places.pop(id(layer), None)
        rect = Path.polygon([(x, y), (x + w, y), (x + w, y + h), (x, y + h)])
        rc = self.coverage(rect, lt @ t, layer.width, layer.height, place, straddle=False)
        if rc is None:
            return
        layer.scale(rc.full(layer.width, layer.height))
        self.settle()
        canvas.composite(layer.data, x0 - ox, y0 - oy, n.opacity)


def _sample_tile(tile, mask):
    """Premultiplied (h, w, 4) float32 colours of a pattern tile
    ``(pixels, device -> tile transform)`` (see
    :meth:`Renderer.pattern_tile`) at the pixel centres of the mask window,
    multiplied by the coverage."""
    pix, inv = tile
    hh, ww = mask.data.shape
    jj, ii = np.meshgrid(np.arange(ww) + mask.x0 + 0.5, np.arange(hh) + mask.y0 + 0.5)
    uv = inv.apply(np.stack([jj, ii], -1))
    col = sample(pix, uv[..., 0], uv[..., 1], smooth=True, wrap=True)
    return (col * mask.data[..., None]).astype(np.float32)


def _unite(cov, m):
    """``cov += k (1 - cov)`` over the window of Mask ``m`` (coverage ``k``)
    inside ``cov`` ((h, w) float32): the alpha of source-over."""
    h, w = cov.shape
    mh, mw = m.data.shape
    cx0, cy0 = max(m.x0, 0), max(m.y0, 0)
    cx1, cy1 = min(m.x0 + mw, w), min(m.y0 + mh, h)
    if cx1 <= cx0 or cy1 <= cy0:
        return
    k = m.data[cy0 - m.y0:cy1 - m.y0, cx0 - m.x0:cx1 - m.x0]
    reg = cov[cy0:cy1, cx0:cx1]
    reg += k * (1.0 - reg)


def _times_mask(m, rc):
    """``m *= coverage`` of Mask ``rc``, in place ((h, w) float32; zero
    outside the mask's window), without a canvas-sized copy of the mask."""
    h, w = m.shape
    rh, rw = rc.data.shape
    cx0, cy0 = max(rc.x0, 0), max(rc.y0, 0)
    cx1, cy1 = min(rc.x0 + rw, w), min(rc.y0 + rh, h)
    if cx1 <= cx0 or cy1 <= cy0:
        m[...] = 0.0
        return
    m[:cy0] = 0.0
    m[cy1:] = 0.0
    m[:, :cx0] = 0.0
    m[:, cx1:] = 0.0
    m[cy0:cy1, cx0:cx1] *= rc.data[cy0 - rc.y0:cy1 - rc.y0, cx0 - rc.x0:cx1 - rc.x0]


def _times_rect(m, x0, y0, x1, y1):
    """``m *= coverage`` of the device rectangle [x0, x1] x [y0, y1], in
    place ((h, w) float32): the exact area of the rectangle in each pixel,
    the product of its x and y overlaps."""
    h, w = m.shape
    cx = pixel_overlaps(x0, x1, 0, w)
    cy = pixel_overlaps(y0, y1, 0, h)
    m *= cy.astype(np.float32)[:, None]
    m *= cx.astype(np.float32)[None, :]
