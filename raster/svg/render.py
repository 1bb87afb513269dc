"""Render a resolved SVG tree (:mod:`raster.svg.tree`) onto a canvas.

The renderer is a short loop over the tree: it never parses a string.

Coordinates: the tree's root group maps user space to *document pixels*
(the natural size ``tree.width x tree.height``).  :func:`output_size`
chooses the output size in device pixels and the scale from document to
device pixels; every node is drawn with its *current transformation matrix*
(CTM), user space to device (or layer) pixels, x right and y down.

Per node:

* :class:`~raster.svg.tree.PathNode`: for each item of ``paint_order``, the
  fill is flattened with the CTM (``tolerance`` device pixels), scan
  converted with the node's fill rule and composited with the fill paint and
  ``fill-opacity``; the stroke is outlined in device space
  (:func:`raster.stroke.stroke`), scan converted with the nonzero rule and
  composited likewise.  A stroke thinner than one device pixel is drawn one
  pixel wide with its coverage scaled by its device width
  (:func:`raster.stroke.hairline_scale`); an undashed hairline is outlined
  here from the fill's flattened polylines (:func:`_hairline_edges`: one
  rectangle per segment plus join triangles, one vectorized pass) instead
  of by the general stroker.  Markers are a group drawn with the node's
  CTM.  Geometry is batched across nodes: the paths drawn directly on one
  canvas (not inside a layered group) are queued in document order
  (``_Renderer.plan``) and flattened, outlined and scan converted a batch at
  a time (:func:`raster.flatten.flatten_many`,
  :func:`raster.stroke.stroke_many`, :func:`raster.scan.coverage_many`);
  only the masks are computed ahead, compositing stays in document order.
* :class:`~raster.svg.tree.Group`: a group that only transforms composes
  its transform with the CTM.  A group that needs a layer (opacity, clip
  path, mask, isolation, blend mode) renders its children into a transparent
  layer covering only the group's device bounding box (clipped to the
  target), applies the clip path and mask, and composites the layer with its
  opacity.  A filtered group's layer is its filter region and the filters
  (:mod:`raster.svg.filters`) run on it before clip, mask and opacity.
  Blend modes follow Compositing 1 (the non-separable ones with resvg's
  ClipColor, see :func:`_clip_color`).
* :class:`~raster.svg.tree.ImageNode`: raster pixels are resampled
  (bilinear when ``smooth``, else nearest) through the inverse of the CTM
  and clipped to the image's viewport; an SVG image is rendered as a nested
  tree.
* text arrives as glyph-outline PathNodes (raster.svg.text).

Paints: solid colours and linear and radial gradients (pad, reflect and
repeat spreads; ``objectBoundingBox`` units) and patterns (a tile raster
at device resolution, sampled with wrapping).

>>> from raster.path import Path
>>> from raster.svg.tree import Tree, Group, PathNode, Fill, SolidPaint
>>> sq = Path.polygon([(2, 2), (8, 2), (8, 8), (2, 8)])
>>> tree = Tree(10, 10, Group(children=[PathNode(path=sq, fill=Fill(SolidPaint((1, 0, 0, 1))))]))
>>> img = render_tree(tree).to_rgba8()
>>> img.shape, img[5, 5].tolist(), img[0, 0].tolist()
((10, 10, 4), [255, 0, 0, 255], [0, 0, 0, 0])
"""

import math

import numpy as np

from .. import limits
from ..canvas import Canvas
from ..errors import CanvasError, RasterError, SVGError
from ..flatten import flatten, flatten_many
from ..path import Path
from ..scan import coverage, coverage_many
from ..stroke import StrokeStyle, hairline_scale, stroke as stroke_outline, stroke_many
from ..transform import IDENTITY, Affine
from .paint import draw_pixels, gradient_colors, sample, user_bbox
from .tree import (Group, ImageNode, LinearGradient, PathNode, Pattern, RadialGradient,
                   SolidPaint, Tree)

__all__ = ['render_tree', 'output_size', 'DEFAULT_TOLERANCE']

#: Default flattening tolerance in device pixels.
DEFAULT_TOLERANCE = 0.25


# ---------------------------------------------------------------------------
# Output size
# ---------------------------------------------------------------------------

def _positive(name, v):
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise CanvasError('%s must be a number, got %r' % (name, v)) from None
    if not math.isfinite(f) or f <= 0:
        raise CanvasError('%s must be positive and finite, got %r' % (name, v))
    return f


def output_size(doc_width, doc_height, width=None, height=None, zoom=None):
    """Output size in pixels and the document-to-device scale.

    Parameters
    ----------
    doc_width, doc_height : float
        The document's natural size in px (> 0).
    width, height : int or None
        Requested output size.  Only ``width``: the height keeps the aspect
        ratio of the natural pixel size (rounded half up), the scaled side rounded up; only ``height``:
        likewise for the width; both: non-uniform scale.
    zoom : float or None
        Scale factor of the natural size (not with ``width``/``height``).

    Returns
    -------
    (w, h, sx, sy)
        Integer output size and the scales mapping document px to device
        px (``w / doc_width``, ``h / doc_height``).

    Raises
    ------
    CanvasError
        A size or zoom that is not positive and finite, both zoom and a
        size, or an output of more than :data:`raster.limits.MAX_PIXELS`
        pixels or a side above :data:`raster.limits.MAX_SIDE`.

    >>> output_size(100, 50)
    (100, 50, 1.0, 1.0)
    >>> output_size(100, 50, width=300)
    (300, 150, 3.0, 3.0)
    >>> output_size(100, 50, zoom=1.5)
    (150, 75, 1.5, 1.5)
    >>> output_size(10.5, 10, width=20)[:2]          # natural pixel size 11 x 10
    (20, 19)
    """
    dw = _positive('document width', doc_width)
    dh = _positive('document height', doc_height)
    if zoom is not None and (width is not None or height is not None):
        raise CanvasError('give a zoom or an output size, not both')
    # natural pixel size: rounded half up, as resvg does (1000 x 507.224 ->
    # 1000 x 507; 10.5 x 10 -> 11 x 10)
    nw, nh = max(1, math.floor(dw + 0.5)), max(1, math.floor(dh + 0.5))
    if zoom is not None:
        z = _positive('zoom', zoom)
        w, h = math.ceil(nw * z), math.ceil(nh * z)
    elif width is not None and height is not None:
        w, h = _positive('width', width), _positive('height', height)
    elif width is not None:
        w = _positive('width', width)
        h = math.ceil(w * nh / nw)
    elif height is not None:
        h = _positive('height', height)
        w = math.ceil(h * nw / nh)
    else:
        w, h = nw, nh
    if w != int(w) or h != int(h):
        raise CanvasError('output size must be whole pixels, got %r x %r' % (w, h))
    w, h = int(w), int(h)
    if w > limits.MAX_SIDE or h > limits.MAX_SIDE or w * h > limits.MAX_PIXELS:
        raise CanvasError('output size %d x %d exceeds the limit (%d px per side, %d pixels)'
                          % (w, h, limits.MAX_SIDE, limits.MAX_PIXELS))
    return w, h, w / dw, h / dh


# ---------------------------------------------------------------------------
# Entry point
# ---------------------------------------------------------------------------

def render_tree(tree, width=None, height=None, zoom=None, background=None, node_id=None,
                tolerance=DEFAULT_TOLERANCE):
    """Render a resolved tree.

    Parameters
    ----------
    tree : raster.svg.tree.Tree
    width, height, zoom :
        Output size, see :func:`output_size` (default: the natural size).
    background : RGBA tuple of floats in [0, 1] (straight alpha) or None
        Canvas background (None: transparent).
    node_id : str or None
        Render only the subtree of the node with this id, with the
        transforms of its ancestors.
    tolerance : float
        Flattening tolerance in device pixels (> 0).

    Returns
    -------
    raster.canvas.Canvas
        Premultiplied float32 RGBA canvas of the output size.

    Raises
    ------
    CanvasError
        Bad output size (see :func:`output_size`) or tolerance.
    SVGError
        ``node_id`` names no node of the tree.
    """
    if not isinstance(tree, Tree):
        raise SVGError('render_tree needs a raster.svg.tree.Tree, got %s' % type(tree).__name__)
    tol = _positive('tolerance', tolerance)
    w, h, sx, sy = output_size(tree.width, tree.height, width, height, zoom)
    canvas = Canvas(w, h, background)
    base = Affine.scale(sx, sy)
    r = _Renderer(tol)
    if node_id is None:
        r.plan([tree.root], base, canvas)
        r.node(tree.root, base, canvas)
    else:
        node, t = _find(tree, node_id)
        r.plan([node], base @ t, canvas)
        r.node(node, base @ t, canvas)
    return canvas


def _find(tree, node_id):
    """The node with ``node_id`` and the transform of its ancestors (root
    transform included) mapping its coordinates to document px."""
    target = tree.ids.get(node_id) if isinstance(tree.ids, dict) else None
    stack = [(tree.root, IDENTITY)]
    while stack:
        n, t = stack.pop()
        if n is target or (target is None and getattr(n, 'id', '') == node_id and node_id):
            return n, t
        if isinstance(n, Group):
            t2 = t @ n.transform
            stack.extend((c, t2) for c in reversed(n.children))
    raise SVGError('no element with id %r' % (node_id,))


# ---------------------------------------------------------------------------
# The renderer
# ---------------------------------------------------------------------------

_CLIP_FILL = SolidPaint((0.0, 0.0, 0.0, 1.0))


class _Renderer:
    def __init__(self, tolerance):
        self.tol = tolerance
        self._flat_key = self._flat_path = self._flat = None
        # batched flattening: (id(path), t) -> (path, t) waiting in document
        # order, and -> Polylines already flattened (see plan / flat)
        self._pending = {}
        self._ready = {}
        # batched coverage: (id(node), t) -> (node, t, size) of fills waiting,
        # and -> Mask (or None) of fills already scan converted
        self._fill_pending = {}
        self._fill_ready = {}
        # batched strokes (not hairlines): (id(node), t) -> (node, t, size,
        # style) waiting, and -> Mask (or None) already scan converted
        self._stroke_pending = {}
        self._stroke_ready = {}
        # batched undashed hairlines: (id(node), t) -> (node, t, size) and
        # -> Mask (or None), or absent when the general stroker is needed
        self._hair_pending = {}
        self._hair_ready = {}
        self._hair_edges = {}

    # -- batched geometry ------------------------------------------------------
    def plan(self, nodes, t, canvas):
        """Queue the paths of ``nodes`` (with CTM ``t``) drawn directly on
        ``canvas`` (not inside layered groups) whose fill or hairline needs
        flattened polylines; :meth:`flat` then flattens them in batches with
        :func:`raster.flatten.flatten_many`, in document order, and
        :meth:`fill` scan converts their fills in batches with
        :func:`raster.scan.coverage_many` (compositing stays in document
        order: only the masks are computed ahead)."""
        stack = [(n, t) for n in reversed(nodes)]
        pending = self._pending
        fills = self._fill_pending
        strokes = self._stroke_pending
        hairs = self._hair_pending
        size = (canvas.width, canvas.height)
        while stack:
            n, m = stack.pop()
            if isinstance(n, Group):
                if n.needs_layer:
                    continue
                ct = m @ n.transform
                stack.extend((c, ct) for c in reversed(n.children))
            elif isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
                if _wants_flat(n, m):
                    pending.setdefault((id(n.path), m), (n.path, m))
                    if n.fill is not None and n.fill.opacity > 0:
                        fills.setdefault((id(n), m), (n, m, size))
                if _wants_hair(n, m):
                    hairs.setdefault((id(n), m), (n, m, size))
                style = _batch_stroke_style(n, m)
                if style is not None:
                    strokes.setdefault((id(n), m), (n, m, size, style))

    def _flush(self, key):
        """Flatten pending paths in document order, up to and including
        ``key``, at least :data:`_BATCH_VERBS` verbs' worth."""
        pending = self._pending
        batch, verbs, seen = [], 0, False
        for k in pending:
            batch.append(k)
            verbs += len(pending[k][0].verbs)
            seen = seen or k == key
            if seen and verbs >= _BATCH_VERBS:
                break
        items = [pending.pop(k) for k in batch]
        try:
            pls = flatten_many([p for p, _ in items], [m for _, m in items], self.tol)
        except RasterError:
            return          # flattened one by one (errors where they were)
        self._ready.update(zip(batch, pls))

    # -- dispatch ------------------------------------------------------------
    def node(self, node, t, canvas, clip_mode=False):
        if isinstance(node, Group):
            self.group(node, t, canvas, clip_mode)
        elif isinstance(node, PathNode):
            self.path(node, t, canvas, clip_mode)
        elif isinstance(node, ImageNode):
            if not clip_mode:
                self.image(node, t, canvas)

    # -- groups ----------------------------------------------------------------
    def group(self, g, t, canvas, clip_mode=False):
        ct = t @ g.transform
        if clip_mode:
            # inside a clip path only geometry counts; a clip-path on a child
            # still restricts that child
            if g.clip_path is not None:
                self.layered(g, t, canvas, clip_mode=True)
                return
            for c in g.children:
                self.node(c, ct, canvas, True)
            return
        if not g.needs_layer:
            for c in g.children:
                self.node(c, ct, canvas)
            return
        if g.opacity <= 0:
            return
        self.layered(g, t, canvas)

    def layered(self, g, t, canvas, clip_mode=False):
        ct = t @ g.transform
        from .filters import apply_filters, filter_box, filter_pixel_box, group_filters
        filters = None if clip_mode else group_filters(g)
        # a filtered group's layer is its filter region (effects draw outside)
        box = _group_box(g, ct) if filters is None else filter_box(filters, ct)
        if box is None:
            return
        px = (_pixel_box(box, canvas.width, canvas.height) if filters is None
              else filter_pixel_box(box, canvas.width, canvas.height))
        if px is None:
            return
        x0, y0, x1, y1 = px
        layer = Canvas(x1 - x0, y1 - y0)
        lt = Affine.translate(-x0, -y0) @ ct
        if not clip_mode:
            self.plan(g.children, lt, layer)
        for c in g.children:
            self.node(c, lt, layer, clip_mode)
        if filters is not None:
            def draw(nodes, m, w, h):       # feImage content
                img = Canvas(w, h)
                for n in nodes:
                    self.node(n, m, img)
                return img.data
            layer.data[...] = apply_filters(filters, layer.data, lt, draw=draw)
        if g.clip_path is not None:
            cov = self.clip_coverage(g.clip_path, lt, layer.width, layer.height)
            layer.data *= cov[..., None]
        if g.mask is not None and not clip_mode:
            m = self.mask_values(g.mask, lt, layer.width, layer.height)
            layer.data *= m[..., None]
        opacity = 1.0 if clip_mode else float(g.opacity)
        if clip_mode or g.blend_mode in ('normal', '', None):
            canvas.composite(layer.data, x0, y0, opacity)
        else:
            _blend(canvas, layer.data, x0, y0, opacity, g.blend_mode)

    # -- clip paths and masks ------------------------------------------------
    def clip_coverage(self, clip, t, w, h):
        """(h, w) float32 coverage of a clip path (ClipPath) with CTM ``t``
        (the clipped element's user space to layer pixels)."""
        ct = t @ clip.transform
        layer = Canvas(w, h)
        self.node(clip.root, ct, layer, clip_mode=True)
        cov = layer.data[..., 3].copy()
        if clip.clip_path is not None:
            cov *= self.clip_coverage(clip.clip_path, t, w, h)
        return cov

    def mask_values(self, mask, t, w, h):
        """(h, w) float32 mask values of a Mask with CTM ``t``."""
        layer = Canvas(w, h)
        self.node(mask.root, t, layer)
        d = layer.data
        if mask.kind == 'alpha':
            m = d[..., 3].copy()
        else:
            # luminance of the premultiplied colour = luminance * alpha
            m = (0.2125 * d[..., 0] + 0.7154 * d[..., 1] + 0.0721 * d[..., 2]).astype(np.float32)
        x, y, rw, rh = mask.rect
        rect = Path.polygon([(x, y), (x + rw, y), (x + rw, y + rh), (x, y + rh)])
        rc = _cover(rect, t, w, h, 'nonzero', True, self.tol)
        if rc is None:
            return np.zeros((h, w), np.float32)
        m *= rc.full(w, h)
        if mask.mask is not None:
            m *= self.mask_values(mask.mask, t, w, h)
        return np.clip(m, 0.0, 1.0)

    # -- paths ---------------------------------------------------------------
    def path(self, n, t, canvas, clip_mode=False):
        if n.path is None or len(n.path.verbs) == 0:
            return
        if clip_mode:
            # a clip path uses the geometry whatever the paint (fill="none"
            # has no effect); the fill rule carries clip-rule
            rule = n.fill.rule if n.fill is not None else 'nonzero'
            m = _cover(n.path, t, canvas.width, canvas.height, rule, n.antialias, self.tol)
            if m is not None:
                canvas.fill(m, _CLIP_FILL.color, 1.0)
            return
        for item in n.paint_order:
            if item == 'fill' and n.fill is not None:
                self.fill(n, t, canvas)
            elif item == 'stroke' and n.stroke is not None:
                self.stroke(n, t, canvas)
            elif item == 'markers' and n.markers is not None:
                self.node(n.markers, t, canvas)

    def fill(self, n, t, canvas):
        f = n.fill
        if f.opacity <= 0:
            return
        key = (id(n), t)
        if key in self._fill_pending:
            self._flush_fills(key, canvas)
        if key in self._fill_ready:
            m = self._fill_ready.pop(key)
        else:
            edges = self.flat(n.path, t).edges(close_all=True)
            if len(edges) == 0:
                return
            m = coverage(edges, canvas.width, canvas.height, f.rule, n.antialias)
        if m is not None:
            self.paint(canvas, m, f.paint, f.opacity, n.path, t)

    def _flush_fills(self, key, canvas):
        """Scan convert queued fills for ``canvas`` in document order, up to
        and including ``key``, in one :func:`coverage_many` call (bounded by
        :data:`_BATCH_EDGES` edges and :data:`_BATCH_AREA` mask pixels;
        larger fills are left to :meth:`fill`)."""
        batch = _MaskBatch()
        for k, n, m in batch.take(self._fill_pending, key, canvas):
            pl = self.flat(n.path, m)
            if k in self._hair_pending:     # the stroke needs the polylines too
                self._ready[(id(n.path), m)] = pl
            e = pl.edges(close_all=True)
            if len(e) == 0:
                self._fill_ready[k] = None
            elif not batch.add(k, e, pl.points, n.fill.rule, n.antialias):
                self._ready[(id(n.path), m)] = pl   # big: drawn alone by fill()
        masks = batch.run(canvas)
        if masks is not None:       # else drawn one by one by fill() (errors where they were)
            self._fill_ready.update(masks)

    def _flush_strokes(self, key, canvas):
        """Outline queued strokes for ``canvas`` in document order, up to
        and including ``key``: one :func:`raster.stroke.stroke_many` call
        per stroke style, then one :func:`flatten_many` and one
        :func:`coverage_many` call for all outlines (bounded like
        :meth:`_flush_fills`)."""
        pending = self._stroke_pending
        size = (canvas.width, canvas.height)
        items, verbs, seen = [], 0, False
        for k in list(pending):
            if seen and verbs >= _BATCH_VERBS // 4:
                break
            n, m, sz, style = pending.pop(k)
            seen = seen or k == key
            if sz == size:
                items.append((k, n, m, style))
                verbs += len(n.path.verbs)
        by_style = {}
        for j, (k, n, m, style) in enumerate(items):
            by_style.setdefault(style, []).append(j)
        outlines = [None] * len(items)
        try:
            for style, js in by_style.items():
                outs = stroke_many([items[j][1].path for j in js], style,
                                   transforms=[items[j][2] for j in js], tolerance=self.tol)
                for j, o in zip(js, outs):
                    outlines[j] = o
            keep = [j for j in range(len(items)) if len(outlines[j].verbs)]
            pls = flatten_many([outlines[j] for j in keep], None, self.tol)
        except RasterError:
            return          # stroked one by one by stroke() (errors where they were)
        for j in range(len(items)):
            if not len(outlines[j].verbs):
                self._stroke_ready[items[j][0]] = None
        edges, keys, aas, area = [], [], [], 0.0
        for j, pl in zip(keep, pls):
            e = pl.edges(close_all=True)
            if len(e) == 0:
                self._stroke_ready[items[j][0]] = None
                continue
            lo, hi = pl.points.min(0), pl.points.max(0)
            a = float(hi[0] - lo[0] + 2) * float(hi[1] - lo[1] + 2)
            if a > _BATCH_AREA / 16 or area > _BATCH_AREA:
                continue        # big, or enough masks held: stroke() alone
            keys.append(items[j][0])
            edges.append(e)
            aas.append(bool(items[j][1].antialias))
            area += a
        if not keys:
            return
        try:
            masks = coverage_many(edges, canvas.width, canvas.height, 'nonzero', aas)
        except RasterError:
            return
        self._stroke_ready.update(zip(keys, masks))

    def _flush_hairs(self, key, canvas):
        """Hairline outlines (:func:`_hairline_edges`) of queued undashed
        hairlines for ``canvas`` in document order, up to and including
        ``key``, scan converted in one :func:`coverage_many` call."""
        batch = _MaskBatch()
        for k, n, m in batch.take(self._hair_pending, key, canvas):
            pl = self.flat(n.path, m)
            if k in self._fill_pending:     # the fill needs the polylines too
                self._ready[(id(n.path), m)] = pl
            s = n.stroke
            e = _hairline_edges(pl, s.cap, s.join, s.miterlimit)
            if e is None:
                continue        # general stroker, in stroke()
            if len(e) == 0:
                self._hair_ready[k] = None
            elif not batch.add(k, e, e.reshape(-1, 2), 'nonzero', n.antialias):
                self._hair_edges[k] = e     # big: scan converted alone
        masks = batch.run(canvas)
        if masks is None:
            self._hair_edges.update(zip(batch.keys, batch.edges))
        else:
            self._hair_ready.update(masks)

    def flat(self, path, t):
        """Polylines of ``path`` flattened under ``t`` (device pixels).  The
        last result is kept: a filled and stroked hairline path is
        flattened once."""
        key = (id(path), t)
        if self._flat_key == key and self._flat_path is path:
            return self._flat
        if key in self._pending:
            self._flush(key)
        pl = self._ready.pop(key, None)
        if pl is None:
            pl = flatten(path, self.tol, transform=t)
        self._flat_key, self._flat_path, self._flat = key, path, pl
        return pl

    def stroke(self, n, t, canvas):
        s = n.stroke
        if s.opacity <= 0 or s.width <= 0:
            return
        style = StrokeStyle(width=s.width, join=s.join, cap=s.cap, miterlimit=s.miterlimit,
                            dash=s.dash, dash_offset=s.dash_offset)
        opacity = s.opacity
        hair = hairline_scale(style, t)
        if hair is not None:
            style = StrokeStyle(width=1.0 / t.mean_scale(), join=s.join, cap=s.cap,
                                miterlimit=s.miterlimit, dash=s.dash, dash_offset=s.dash_offset)
            opacity *= hair
            if s.dash is None:
                key = (id(n), t)
                if key in self._hair_pending:
                    self._flush_hairs(key, canvas)
                if key in self._hair_ready:
                    m = self._hair_ready.pop(key)
                    if m is not None:
                        self.paint(canvas, m, s.paint, opacity, n.path, t)
                    return
                edges = self._hair_edges.pop(key, None)
                if edges is None:
                    edges = _hairline_edges(self.flat(n.path, t), s.cap, s.join, s.miterlimit)
                if edges is not None:
                    m = coverage(edges, canvas.width, canvas.height, 'nonzero', n.antialias) \
                        if len(edges) else None
                    if m is not None:
                        self.paint(canvas, m, s.paint, opacity, n.path, t)
                    return
        key = (id(n), t)
        if hair is None and key in self._stroke_pending:
            self._flush_strokes(key, canvas)
        if hair is None and key in self._stroke_ready:
            m = self._stroke_ready.pop(key)
        else:
            outline = stroke_outline(n.path, style, transform=t, tolerance=self.tol)
            if len(outline.verbs) == 0:
                return
            m = _cover(outline, IDENTITY, canvas.width, canvas.height, 'nonzero', n.antialias,
                       self.tol)
        if m is not None:
            self.paint(canvas, m, s.paint, opacity, n.path, t)

    def paint(self, canvas, mask, paint, opacity, path, t):
        if isinstance(paint, SolidPaint):
            canvas.fill(mask, paint.color, opacity)
        elif isinstance(paint, (LinearGradient, RadialGradient)):
            src = gradient_colors(paint, mask, path, t)
            if src is not None:
                canvas.composite(src, mask.x0, mask.y0, opacity)
        elif isinstance(paint, Pattern):
            src = self.pattern(paint, mask, path, t)
            if src is not None:
                canvas.composite(src, mask.x0, mask.y0, opacity)
        # unknown paints: skipped

    def pattern(self, p, mask, path, t):
        """Premultiplied (h, w, 4) colours of a pattern over the mask window,
        multiplied by the coverage; None when the tile is empty.

        The tile is rendered once into a raster at device resolution and
        sampled (bilinear, wrapping) through the inverse of the tile-to-device
        transform, the way resvg paints patterns."""
        bx = by = 0.0
        bw = bh = 1.0
        if p.units == 'objectBoundingBox' or p.content_units == 'objectBoundingBox':
            bx, by, bw, bh = user_bbox(path)
            if bw <= 0 or bh <= 0:
                return None
        x, y, w, h = p.rect
        if p.units == 'objectBoundingBox':
            x, y, w, h = bx + x * bw, by + y * bh, w * bw, h * bh
        if not (w > 0 and h > 0):
            return None
        tile_to_dev = t @ p.transform @ Affine.translate(x, y)
        a, b, c, d = tile_to_dev.a, tile_to_dev.b, tile_to_dev.c, tile_to_dev.d
        sx, sy = math.hypot(a, b), math.hypot(c, d)
        tw = max(1, int(math.ceil(w * sx)))
        th = max(1, int(math.ceil(h * sy)))
        if tw * th > limits.MAX_PIXELS // 4:
            return None
        content = p.content_transform
        if p.view_box is None and p.content_units == 'objectBoundingBox':
            content = content @ Affine.scale(bw, bh)
        elif p.view_box is not None and p.units == 'objectBoundingBox':
            # the viewBox maps onto the tile, whose size depends on the bbox
            # (the builder cannot resolve it); patternContentUnits is ignored
            from .values import viewbox_transform
            try:
                content = viewbox_transform(p.view_box,
                                            getattr(p, 'preserve_aspect_ratio', None), w, h)
            except RasterError:
                return None
        # As resvg: the tile raster has whole-pixel size (rounded up) and the
        # content is drawn at the device scale, so the period is tw / sx
        # (up to a pixel longer than the tile): references tile this way.
        tile = Canvas(tw, th)
        self.node(p.root, Affine.scale(sx, sy) @ content, tile)
        try:
            inv = (tile_to_dev @ Affine.scale(1.0 / sx, 1.0 / sy)).inverse()
        except RasterError:
            return None
        hh, ww = mask.data.shape
        jj, ii = np.meshgrid(np.arange(ww) + mask.x0 + 0.5, np.arange(hh) + mask.y0 + 0.5)
        uv = inv.apply(np.stack([jj, ii], -1))
        col = sample(tile.data, uv[..., 0], uv[..., 1], smooth=True, wrap=True)
        return (col * mask.data[..., None]).astype(np.float32)

    # -- images ----------------------------------------------------------------
    def image(self, n, t, canvas):
        if n.opacity <= 0:
            return
        if n.tree is not None:
            self.svg_image(n, t, canvas)
        elif n.pixels is not None:
            draw_pixels(n, t, canvas, self.tol)

    def svg_image(self, n, t, canvas):
        sub = n.tree
        it = t @ n.transform
        g = Group(children=[sub.root])
        if n.clip is not None:
            x, y, w, h = n.clip
            box = t.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]], float))
            px = _pixel_box((box[:, 0].min(), box[:, 1].min(), box[:, 0].max(), box[:, 1].max()),
                            canvas.width, canvas.height)
            if px is None:
                return
            x0, y0, x1, y1 = px
            layer = Canvas(x1 - x0, y1 - y0)
            lt = Affine.translate(-x0, -y0)
            self.node(g, lt @ it, layer)
            rect = Path.polygon([(x, y), (x + w, y), (x + w, y + h), (x, y + h)])
            rc = _cover(rect, lt @ t, layer.width, layer.height, 'nonzero', True, self.tol)
            if rc is None:
                return
            layer.data *= rc.full(layer.width, layer.height)[..., None]
            canvas.composite(layer.data, x0, y0, n.opacity)
        else:
            self.node(g, it, canvas)


# ---------------------------------------------------------------------------
# Geometry helpers
# ---------------------------------------------------------------------------

#: Verbs per batch of :meth:`_Renderer._flush` (bounds its memory).
_BATCH_VERBS = 100_000

#: Edges and mask pixels per batch of :meth:`_Renderer._flush_fills`.
_BATCH_EDGES = 200_000
_BATCH_AREA = 4_000_000


def _batch_stroke_style(n, t):
    """The StrokeStyle of PathNode ``n``'s stroke when it can be outlined in
    a batch (visible, not a hairline, hashable), else None."""
    s = n.stroke
    if s is None or s.opacity <= 0 or s.width <= 0:
        return None
    try:
        style = StrokeStyle(width=s.width, join=s.join, cap=s.cap, miterlimit=s.miterlimit,
                            dash=s.dash, dash_offset=s.dash_offset)
        hash(style)
    except (RasterError, TypeError):
        return None
    if hairline_scale(style, t) is not None:
        return None
    return style


def _wants_hair(n, t):
    """Whether PathNode ``n`` under ``t`` has an undashed hairline stroke
    (outlined from the fill's polylines)."""
    s = n.stroke
    return (s is not None and s.dash is None and s.opacity > 0
            and 0.0 < s.width * t.mean_scale() < 1.0)


def _wants_flat(n, t):
    """Whether drawing PathNode ``n`` under ``t`` flattens its path (a
    visible fill, or an undashed hairline stroke)."""
    f, s = n.fill, n.stroke
    if f is not None and f.opacity > 0:
        return True
    return _wants_hair(n, t)


def _cover(path, t, w, h, rule, antialias, tol):
    """Coverage Mask of ``path`` filled under ``t`` on a w x h target."""
    pl = flatten(path, tol, transform=t)
    edges = pl.edges(close_all=True)
    if len(edges) == 0:
        return None
    return coverage(edges, w, h, rule, antialias)


def _polygon_edges(p, oriented=False):
    """Closed polygons (M, K, 2) as (M K, 2, 2) edges, every polygon turned
    to negative signed area (clockwise on screen, y down) unless
    ``oriented`` says it already is: under the nonzero rule their union is
    filled and overlaps never cancel."""
    m, k = p.shape[:2]
    if not oriented and m:
        x, y = p[..., 0], p[..., 1]
        nx, ny = np.roll(x, -1, axis=1), np.roll(y, -1, axis=1)
        flip = (x * ny - nx * y).sum(1) > 0
        if flip.any():
            p = p.copy()
            p[flip] = p[flip][:, ::-1]
    e = np.empty((m, k, 2, 2))
    e[:, :, 0] = p
    e[:, :-1, 1] = p[:, 1:]
    e[:, -1, 1] = p[:, 0]
    return e.reshape(-1, 2, 2)


class _MaskBatch:
    """Shapes gathered for one :func:`coverage_many` call, within
    :data:`_BATCH_EDGES` edges and :data:`_BATCH_AREA` mask pixels."""

    def __init__(self):
        self.keys, self.edges, self.rules, self.aas = [], [], [], []
        self.n_edges = self.area = 0

    def take(self, pending, key, canvas):
        """Pop queued ``(n, m, size)`` entries of ``pending`` in document
        order and yield ``(key, node, transform)`` for those drawn on
        ``canvas``, up to and including ``key`` and then while the batch
        has room."""
        size = (canvas.width, canvas.height)
        seen = False
        for k in list(pending):
            if seen and (self.n_edges >= _BATCH_EDGES or self.area >= _BATCH_AREA):
                return
            n, m, sz = pending.pop(k)
            seen = seen or k == key
            if sz == size:
                yield k, n, m

    def add(self, key, edges, points, rule, antialias):
        """Add a shape (its edges, and points spanning its box); False when
        its box is too big for a batch (it is then drawn alone)."""
        lo, hi = points.min(0), points.max(0)
        a = float(hi[0] - lo[0] + 2) * float(hi[1] - lo[1] + 2)
        if a > _BATCH_AREA / 16:
            return False
        self.keys.append(key)
        self.edges.append(edges)
        self.rules.append(rule)
        self.aas.append(bool(antialias))
        self.n_edges += len(edges)
        self.area += a
        return True

    def run(self, canvas):
        """``{key: Mask or None}``, or None when scan conversion raised (the
        caller then draws the shapes one by one)."""
        if not self.keys:
            return {}
        try:
            masks = coverage_many(self.edges, canvas.width, canvas.height, self.rules, self.aas)
        except RasterError:
            return None
        return dict(zip(self.keys, masks))


def _hairline_edges(pl, cap, join, miterlimit):
    """Outline edges of a 1 device pixel wide stroke along device-space
    polylines ``pl`` (:class:`raster.flatten.Polylines`), for hairlines.

    The stroke of a polyline is the union of a 1 px wide rectangle per
    segment, a bevel triangle at each vertex between two segments (plus the
    miter triangle when ``join`` is a miter join within ``miterlimit``) and,
    for square and round caps, a half-pixel extension at the ends of open
    polylines (a round cap is drawn square: at most 0.054 px^2 more per
    end).  Round joins are drawn bevelled (at most 0.04 px^2 less per
    join).  The pieces are emitted as separate polygons of one orientation,
    filled with the nonzero rule, all in one vectorized pass: no offset
    curves and no per-vertex Python work.  The polylines are within the
    flattening tolerance of the curves, and so is this outline.

    Returns
    -------
    (E, 2, 2) float64 ndarray, or None when the general stroker must be used
    (a polyline of one distinct point with a non-butt cap: a dot).
    """
    r = 0.5
    P = pl.points
    n = len(P)
    if n == 0:
        return np.zeros((0, 2, 2))
    starts, ends, closed = pl.starts, pl.ends, pl.closed
    nxt = np.arange(1, n + 1)
    nxt[ends - 1] = np.where(closed, starts, -1)
    a_idx = np.flatnonzero(nxt >= 0)
    a, b = P[a_idx], P[nxt[a_idx]]
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    keep = length > 1e-9
    a_idx, a, b, d, length = a_idx[keep], a[keep], b[keep], d[keep], length[keep]
    poly = np.searchsorted(starts, a_idx, side='right') - 1
    counts = np.bincount(poly, minlength=len(starts))
    if cap != 'butt' and (counts == 0).any():
        return None
    if len(a) == 0:
        return np.zeros((0, 2, 2))
    u = d / length[:, None]
    nv = np.stack([-u[:, 1], u[:, 0]], 1) * r
    S = len(a)
    j = np.arange(S)
    first = np.ones(S, bool)
    first[1:] = poly[1:] != poly[:-1]
    last = np.ones(S, bool)
    last[:-1] = poly[1:] != poly[:-1]
    if cap != 'butt':
        # square (and round, drawn square) caps on open polylines
        op = ~closed[poly]
        a = a - (u * r) * (first & op)[:, None]
        b = b + (u * r) * (last & op)[:, None]
    # a + n, b + n, b - n, a - n with n = r (-uy, ux): negative signed area
    pieces = [_polygon_edges(np.stack([a + nv, b + nv, b - nv, a - nv], 1), oriented=True)]
    # joins: each segment with the next one of its polyline (closed: wrap)
    head = np.maximum.accumulate(np.where(first, j, 0))
    nseg = np.where(~last, j + 1, np.where(closed[poly], head, -1))
    ok = nseg >= 0
    i1, i2 = j[ok], nseg[ok]
    if len(i1):
        v = P[nxt[a_idx[i1]]]
        cr = u[i1, 0] * u[i2, 1] - u[i1, 1] * u[i2, 0]
        side = np.where(cr > 0, -1.0, 1.0)[:, None]          # the outer side
        p1, p2 = v + side * nv[i1], v + side * nv[i2]
        pieces.append(_polygon_edges(np.stack([v, p1, p2], 1)))
        if join in ('miter', 'miter-clip', 'arcs'):
            cos_t = np.clip((u[i1] * u[i2]).sum(1), -1.0, 1.0)   # turning angle
            # miter length / stroke width = 1 / sin(phi / 2), phi the angle
            # between the segments = pi - turning angle: 1 / cos(turn / 2)
            half = np.sqrt(np.maximum((1.0 + cos_t) / 2.0, 0.0))
            within = (half > 1e-12) & (1.0 <= miterlimit * half) & (cos_t < 1.0 - 1e-12)
            if within.any():
                bis = side[within] * (nv[i1][within] + nv[i2][within])
                bl = np.hypot(bis[:, 0], bis[:, 1])[:, None]
                tip = v[within] + bis / np.maximum(bl, 1e-300) * (r / half[within][:, None])
                pieces.append(_polygon_edges(np.stack([p1[within], tip, p2[within]], 1)))
    return np.concatenate(pieces)


def _pixel_box(box, w, h, margin=1):
    """Float device box -> integer pixel box clipped to the target, or None."""
    x0, y0, x1, y1 = box
    if not all(math.isfinite(v) for v in box):
        return None
    px0 = max(0, int(math.floor(x0)) - margin)
    py0 = max(0, int(math.floor(y0)) - margin)
    px1 = min(w, int(math.ceil(x1)) + margin)
    py1 = min(h, int(math.ceil(y1)) + margin)
    if px1 <= px0 or py1 <= py0:
        return None
    return px0, py0, px1, py1


def _union(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return (min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3]))


def _points_box(pts):
    if len(pts) == 0:
        return None
    lo, hi = pts.min(0), pts.max(0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _geometry_box(path, t):
    """Conservative device box of a path's geometry: the box of its
    transformed control points (a Bezier lies in the hull of its control
    points).  Used only to size layers, where a slightly large box costs
    nothing and an exact box costs a root solve per segment."""
    return _points_box(t.apply(path.points))


def _stroke_reach(s):
    """How far (in user units) a stroke can reach beyond the path."""
    r = s.width / 2.0
    k = 1.0
    if s.join in ('miter', 'miter-clip', 'arcs'):
        k = max(k, s.miterlimit)
    if s.cap == 'square':
        k = max(k, math.sqrt(2.0))
    return r * k


def _node_box(n, t):
    """Conservative device bounding box (x0, y0, x1, y1) of what ``n``
    draws under the CTM ``t``, or None when it draws nothing."""
    if isinstance(n, Group):
        ct = t @ n.transform
        from .filters import filter_box, group_filters
        if group_filters(n) is not None:
            return filter_box(group_filters(n), ct)
        box = None
        for c in n.children:
            box = _union(box, _node_box(c, ct))
        if box is not None and n.mask is not None:
            x, y, w, h = n.mask.rect
            mb = _points_box(ct.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]],
                                               float)))
            box = (max(box[0], mb[0]), max(box[1], mb[1]), min(box[2], mb[2]), min(box[3], mb[3]))
            if box[2] <= box[0] or box[3] <= box[1]:
                return None
        return box
    if isinstance(n, PathNode):
        if n.path is None or len(n.path.points) == 0:
            return None
        box = _geometry_box(n.path, t) if (n.fill is not None or n.stroke is not None) else None
        if box is not None and n.stroke is not None:
            reach = _stroke_reach(n.stroke) * max(t.max_scale(), 1e-12) + 1.0
            box = (box[0] - reach, box[1] - reach, box[2] + reach, box[3] + reach)
        if n.markers is not None:
            box = _union(box, _node_box(n.markers, t))
        return box
    if isinstance(n, ImageNode):
        x, y, w, h = n.clip if n.clip is not None else n.view_rect
        return _points_box(t.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]],
                                            float)))
    return None


def _group_box(g, ct):
    box = None
    for c in g.children:
        box = _union(box, _node_box(c, ct))
    return box


# ---------------------------------------------------------------------------
# Blend modes (W3C Compositing and Blending Level 1)
# ---------------------------------------------------------------------------

def _soft_light(cb, cs):
    d = np.where(cb <= 0.25, ((16 * cb - 12) * cb + 4) * cb, np.sqrt(cb))
    return np.where(cs <= 0.5, cb - (1 - 2 * cs) * cb * (1 - cb), cb + (2 * cs - 1) * (d - cb))


def _hard_light(cb, cs):
    s2 = 2 * cs
    return np.where(cs <= 0.5, cb * s2, cb + (s2 - 1) - cb * (s2 - 1))


def _dodge(cb, cs):
    with np.errstate(divide='ignore', invalid='ignore'):
        r = np.minimum(1.0, cb / np.maximum(1 - cs, 1e-12))
    return np.where(cb <= 0, 0.0, np.where(cs >= 1, 1.0, r))


def _burn(cb, cs):
    with np.errstate(divide='ignore', invalid='ignore'):
        r = 1 - np.minimum(1.0, (1 - cb) / np.maximum(cs, 1e-12))
    return np.where(cb >= 1, 1.0, np.where(cs <= 0, 0.0, r))


_SEPARABLE = {
    'multiply': lambda cb, cs: cb * cs,
    'screen': lambda cb, cs: cb + cs - cb * cs,
    'overlay': lambda cb, cs: _hard_light(cs, cb),
    'darken': np.minimum,
    'lighten': np.maximum,
    'color-dodge': _dodge,
    'color-burn': _burn,
    'hard-light': _hard_light,
    'soft-light': _soft_light,
    'difference': lambda cb, cs: np.abs(cb - cs),
    'exclusion': lambda cb, cs: cb + cs - 2 * cb * cs,
}


def _lum(c):
    return 0.3 * c[..., 0] + 0.59 * c[..., 1] + 0.11 * c[..., 2]


def _clip_color(c):
    """ClipColor of Compositing 1, as resvg (tiny-skia) computes it.

    The specification first pulls a colour with a negative channel towards
    its luminosity (``C = L + (C - L) L / (L - min)``), then one with a
    channel above 1 (``C = L + (C - L) (1 - L) / (max - L)``).  tiny-skia
    guards the first step with ``max >= 0`` instead of ``min < 0``, so the
    first step never runs (after SetLum the maximum is at least the
    luminosity, which is >= 0) and negative channels are clamped to 0 at
    the end.  The resvg suite's references are drawn that way (e.g.
    painting/mix-blend-mode/saturation: green under a saturated yellow keeps
    G = 0.637, not the specification's 0.5), so we follow it.

    ``c`` is (..., 3) float64 straight RGB; returns the same shape.
    """
    lum = _lum(c)[..., None]
    x = c.max(-1, keepdims=True)
    over = x > 1
    if over.any():
        with np.errstate(divide='ignore', invalid='ignore'):
            c = np.where(over, lum + (c - lum) * (1 - lum) / np.maximum(x - lum, 1e-12), c)
    return np.maximum(c, 0.0)


def _set_lum(c, lum):
    d = lum - _lum(c)
    return _clip_color(c + d[..., None])


def _sat(c):
    return c.max(-1) - c.min(-1)


def _set_sat(c, s):
    mx = c.max(-1, keepdims=True)
    mn = c.min(-1, keepdims=True)
    rng = mx - mn
    with np.errstate(divide='ignore', invalid='ignore'):
        out = np.where(rng > 0, (c - mn) * s[..., None] / np.maximum(rng, 1e-12), 0.0)
    return out


_NON_SEPARABLE = {
    'hue': lambda cb, cs: _set_lum(_set_sat(cs, _sat(cb)), _lum(cb)),
    'saturation': lambda cb, cs: _set_lum(_set_sat(cb, _sat(cs)), _lum(cb)),
    'color': lambda cb, cs: _set_lum(cs, _lum(cb)),
    'luminosity': lambda cb, cs: _set_lum(cb, _lum(cs)),
}


def _blend(canvas, src, x0, y0, opacity, mode):
    """Composite premultiplied ``src`` at (x0, y0) with a blend mode:
    ``result = S (1 - Da) + D (1 - Sa) + Sa Da B(Dc, Sc)``."""
    fn = _SEPARABLE.get(mode)
    fn2 = _NON_SEPARABLE.get(mode)
    if fn is None and fn2 is None:
        canvas.composite(src, x0, y0, opacity)
        return
    h, w = src.shape[:2]
    cx0, cy0 = max(x0, 0), max(y0, 0)
    cx1, cy1 = min(x0 + w, canvas.width), min(y0 + h, canvas.height)
    if cx1 <= cx0 or cy1 <= cy0:
        return
    s = src[cy0 - y0:cy1 - y0, cx0 - x0:cx1 - x0].astype(np.float64) * opacity
    d = canvas.data[cy0:cy1, cx0:cx1].astype(np.float64)
    sa, da = s[..., 3:4], d[..., 3:4]
    with np.errstate(divide='ignore', invalid='ignore'):
        sc = np.where(sa > 0, s[..., :3] / np.maximum(sa, 1e-12), 0.0)
        dc = np.where(da > 0, d[..., :3] / np.maximum(da, 1e-12), 0.0)
    b = fn(dc, sc) if fn is not None else fn2(dc, sc)
    out = np.empty_like(d)
    out[..., :3] = s[..., :3] * (1 - da) + d[..., :3] * (1 - sa) + sa * da * np.clip(b, 0, 1)
    out[..., 3:4] = sa + da - sa * da
    canvas.data[cy0:cy1, cx0:cx1] = np.clip(out, 0, 1).astype(np.float32)
