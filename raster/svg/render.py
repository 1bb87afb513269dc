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

>>> from raster.geometry.path import Path
>>> from raster.svg.tree import Tree, Group, PathNode, Fill, SolidPaint
>>> sq = Path.polygon([(2, 2), (8, 2), (8, 8), (2, 8)])
>>> tree = Tree(10, 10, Group(children=[PathNode(path=sq, fill=Fill(SolidPaint((1, 0, 0, 1))))]))
>>> img = render_tree(tree).to_rgba8()
>>> img.shape, img[5, 5].tolist(), img[0, 0].tolist()
((10, 10, 4), [255, 0, 0, 255], [0, 0, 0, 0])
"""

import math
import warnings

import numpy as np

from .. import _malloc, limits
from ..canvas import Canvas
from ..errors import CanvasError, LimitError, RasterError, RasterWarning, SVGError
from ..geometry.flattening import flatten, flatten_joined
from ..geometry.path import CLOSE, LINE, MOVE, Path
from ..scan import Mask, coverage, coverage_batch, path_coverage
from ..geometry.stroking import StrokeStyle, hairline_scale, stroke as stroke_outline, stroke_many
from ..geometry.transform import IDENTITY, Affine
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
    _malloc.tune()
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
_ABSENT = object()


class _Renderer:
    def __init__(self, tolerance):
        self.tol = tolerance
        self._limit_warned = False
        self._flat_key = self._flat_path = self._flat = None
        # batched fills and undashed hairlines: (id(node), t) -> (node, t,
        # size, area, fill?, hair?) waiting in document order (see plan)
        self._geo_pending = {}
        # -> Mask (or None) of fills / hairlines already scan converted; a
        # hairline is absent when the general stroker is needed
        self._fill_ready = {}
        self._hair_ready = {}
        # batched strokes (not hairlines): (id(node), t) -> (node, t, size,
        # area, style) waiting, and -> Mask (or None) already scan converted
        self._stroke_pending = {}
        self._stroke_ready = {}

    # -- batched geometry ------------------------------------------------------
    def plan(self, nodes, t, canvas):
        """Queue the paths of ``nodes`` (with CTM ``t``) drawn directly on
        ``canvas`` (not inside layered groups): fills and undashed
        hairlines for :meth:`_flush_geometry`, other strokes for
        :meth:`_flush_strokes`.  Those compute the masks of a batch of
        nodes in document order at once (compositing stays in document
        order: only the masks are computed ahead)."""
        stack = [(n, t) for n in reversed(nodes)]
        geo = self._geo_pending
        strokes = self._stroke_pending
        size = (canvas.width, canvas.height)
        while stack:
            n, m = stack.pop()
            if isinstance(n, Group):
                if n.needs_layer and _clip_rect(n, m) is None:
                    continue
                ct = m @ n.transform
                stack.extend((c, ct) for c in reversed(n.children))
            elif isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
                f = n.fill
                wf = f is not None and f.opacity > 0
                wh = _wants_hair(n, m)
                # (hairlines are never outlined by the general stroker here)
                style = None if wh else _batch_stroke_style(n, m)
                if not (wf or wh or style is not None):
                    continue
                area = _device_area(n.path, m, size)
                if wf or wh:
                    geo.setdefault((id(n), m), (n, m, size, area, wf, wh))
                if style is not None:
                    reach = _stroke_reach(n.stroke) * m.max_scale() + 1.0
                    sarea = _device_area(n.path, m, size, reach)
                    strokes.setdefault((id(n), m), (n, m, size, sarea, style))

    def _take(self, pending, key, canvas, verbs_max):
        """Pop queued entries of ``pending`` in document order, up to and
        including ``key`` and then while the batch holds fewer than
        ``verbs_max`` verbs and :data:`_BATCH_AREA` pixels of masks; return
        those drawn on ``canvas`` (others are drawn one by one)."""
        size = (canvas.width, canvas.height)
        keys, verbs, area, seen = [], 0, 0.0, False
        for k in pending:
            v = pending[k]
            if seen and (verbs >= verbs_max or area + v[3] > _BATCH_AREA):
                break
            keys.append(k)
            seen = seen or k == key
            if v[2] == size:
                verbs += len(v[0].path.verbs)
                area += v[3]
        out = []
        for k in keys:
            v = pending.pop(k)
            if v[2] == size:
                out.append((k,) + v)
        return out

    def _flush_geometry(self, key, canvas):
        """Masks of queued fills and undashed hairlines for ``canvas``, in
        document order up to and including ``key`` and then while the batch
        has room: the paths are flattened together
        (:func:`raster.flatten.flatten_joined`), the hairlines outlined in
        one pass (:func:`_hairline_outline`) and all masks scan converted
        in one :func:`raster.scan.coverage_batch` call (hairlines with
        ``exact=False``)."""
        items = self._take(self._geo_pending, key, canvas, _BATCH_VERBS)
        if not items:
            return
        try:
            pl, first = flatten_joined([it[1].path for it in items], [it[2] for it in items],
                                       self.tol)
        except RasterError:
            return          # drawn one by one (errors where they were)
        k = len(items)
        npl = np.diff(first)
        poly_item = np.repeat(np.arange(k), npl)
        wf = np.array([it[5] for it in items], bool)
        wh = np.array([it[6] for it in items], bool)
        parts, counts, rules, aas, exact, keys = [], [], [], [], [], []
        fi = np.flatnonzero(wf)
        if len(fi):
            sub = pl if wf.all() else pl.take(np.flatnonzero(wf[poly_item]))
            e, own = sub.edges(close_all=True, owners=True)
            parts.append(e)
            counts.append(np.bincount(np.repeat(np.arange(len(fi)), npl[fi])[own]
                                      if len(own) else own, minlength=len(fi)))
            for i in fi.tolist():
                n = items[i][1]
                rules.append(n.fill.rule)
                aas.append(bool(n.antialias))
                exact.append(True)
                keys.append((self._fill_ready, items[i][0]))
        hi = np.flatnonzero(wh)
        if len(hi):
            sub = pl if wh.all() else pl.take(np.flatnonzero(wh[poly_item]))
            strokes = [items[i][1].stroke for i in hi.tolist()]
            per = npl[hi]
            capped = np.repeat([s.cap != 'butt' for s in strokes], per).astype(bool)
            mitered = np.repeat([s.join in ('miter', 'miter-clip', 'arcs') for s in strokes],
                                per).astype(bool)
            limit = np.repeat([float(s.miterlimit) for s in strokes], per).astype(np.float64)
            e, own, dots = _hairline_outline(sub, capped, mitered, limit)
            hair_of = np.repeat(np.arange(len(hi)), per)
            dotted = np.zeros(len(hi), bool)
            dotted[hair_of[dots]] = True
            keep = ~dotted[hair_of[own]]
            parts.append(e[keep])
            cnt = np.bincount(hair_of[own[keep]], minlength=len(hi))
            cnt[dotted] = 0
            counts.append(cnt)
            for j, i in enumerate(hi.tolist()):
                n = items[i][1]
                rules.append('nonzero')
                aas.append(bool(n.antialias))
                exact.append(False)
                # a dotted hairline is left to the general stroker
                keys.append(None if dotted[j] else (self._hair_ready, items[i][0]))
        try:
            masks = coverage_batch(np.concatenate(parts), np.concatenate(counts),
                                   canvas.width, canvas.height, rules, aas, exact=exact)
        except RasterError:
            return          # drawn one by one (errors where they were)
        for where, m in zip(keys, masks):
            if where is not None:
                where[0][where[1]] = m

    def _flush_strokes(self, key, canvas):
        """Outline queued strokes for ``canvas`` in document order, up to
        and including ``key`` and then while the batch has room: one
        :func:`raster.stroke.stroke_many` call per stroke style, then one
        :func:`raster.flatten.flatten_joined` and one
        :func:`raster.scan.coverage_batch` call for all outlines."""
        items = self._take(self._stroke_pending, key, canvas, _BATCH_VERBS // 4)
        if not items:
            return
        by_style = {}
        for j, it in enumerate(items):
            by_style.setdefault(it[5], []).append(j)
        outlines = [None] * len(items)
        try:
            for style, js in by_style.items():
                outs = stroke_many([items[j][1].path for j in js], style,
                                   transforms=[items[j][2] for j in js], tolerance=self.tol)
                for j, o in zip(js, outs):
                    outlines[j] = o
            pl, first = flatten_joined(outlines, None, self.tol)
            e, own = pl.edges(close_all=True, owners=True)
            counts = np.bincount(np.repeat(np.arange(len(items)), np.diff(first))[own]
                                 if len(own) else own, minlength=len(items))
            masks = coverage_batch(e, counts, canvas.width, canvas.height, 'nonzero',
                                   [bool(it[1].antialias) for it in items])
        except RasterError:
            return          # stroked one by one by stroke() (errors where they were)
        self._stroke_ready.update(zip([it[0] for it in items], masks))

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
        box = _clip_rect(g, t)
        if box is not None:
            # clipped by an axis-aligned rectangle only: no layer, the
            # children are drawn through the rectangle's coverage
            view = _ClipRect(canvas, box)
            if view.empty:
                return
            for c in g.children:
                self.node(c, ct, view)
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
        rc = path_coverage(rect, w, h, 'nonzero', True, tolerance=self.tol, transform=t)
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
        try:
            self._path(n, t, canvas, clip_mode)
        except LimitError as e:
            # one element beyond a limit (a coordinate above MAX_COORD, too
            # many dashes...) is left out; the rest of the document is drawn
            if not self._limit_warned:
                self._limit_warned = True
                warnings.warn('element not drawn: %s' % e, RasterWarning, stacklevel=2)

    def _path(self, n, t, canvas, clip_mode):
        if clip_mode:
            # a clip path uses the geometry whatever the paint (fill="none"
            # has no effect); the fill rule carries clip-rule
            rule = n.fill.rule if n.fill is not None else 'nonzero'
            m = path_coverage(n.path, canvas.width, canvas.height, rule, n.antialias,
                              tolerance=self.tol, transform=t)
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
        if key in self._geo_pending:
            self._flush_geometry(key, canvas)
        if key in self._fill_ready:
            m = self._fill_ready.pop(key)
        else:
            edges = self.flat(n.path, t).edges(close_all=True)
            if len(edges) == 0:
                return
            m = coverage(edges, canvas.width, canvas.height, f.rule, n.antialias)
        if m is not None:
            self.paint(canvas, m, f.paint, f.opacity, n.path, t)

    def flat(self, path, t):
        """Polylines of ``path`` flattened under ``t`` (device pixels).  The
        last result is kept: a filled and stroked hairline path drawn one
        by one is flattened once."""
        key = (id(path), t)
        if self._flat_key == key and self._flat_path is path:
            return self._flat
        pl = flatten(path, self.tol, transform=t)
        self._flat_key, self._flat_path, self._flat = key, path, pl
        return pl

    def stroke(self, n, t, canvas):
        s = n.stroke
        if s.opacity <= 0 or s.width <= 0:
            return
        key = (id(n), t)
        if key in self._geo_pending:
            self._flush_geometry(key, canvas)
        m = self._hair_ready.pop(key, _ABSENT)
        if m is not _ABSENT:
            # a batched hairline: coverage scaled by its device width, as
            # raster.stroke.hairline_scale gives it
            if m is not None:
                self.paint(canvas, m, s.paint, s.opacity * (s.width * t.mean_scale()),
                           n.path, t)
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
                edges = _hairline_edges(self.flat(n.path, t), s.cap, s.join, s.miterlimit)
                if edges is not None:
                    m = coverage(edges, canvas.width, canvas.height, 'nonzero', n.antialias,
                                 exact=False) if len(edges) else None
                    if m is not None:
                        self.paint(canvas, m, s.paint, opacity, n.path, t)
                    return
        if hair is None and key in self._stroke_pending:
            self._flush_strokes(key, canvas)
        if hair is None and key in self._stroke_ready:
            m = self._stroke_ready.pop(key)
        else:
            outline = stroke_outline(n.path, style, transform=t, tolerance=self.tol)
            if len(outline.verbs) == 0:
                return
            m = path_coverage(outline, canvas.width, canvas.height, 'nonzero', n.antialias,
                              tolerance=self.tol)
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
            rc = path_coverage(rect, layer.width, layer.height, 'nonzero', True,
                               tolerance=self.tol, transform=lt @ t)
            if rc is None:
                return
            layer.data *= rc.full(layer.width, layer.height)[..., None]
            canvas.composite(layer.data, x0, y0, n.opacity)
        else:
            self.node(g, it, canvas)


# ---------------------------------------------------------------------------
# Geometry helpers
# ---------------------------------------------------------------------------

#: Verbs per batch of :meth:`_Renderer._flush_geometry` (a quarter of it
#: for :meth:`_Renderer._flush_strokes`): bounds the batch's geometry.
_BATCH_VERBS = 100_000

#: Mask pixels per batch (the masks of a batch are held until drawn).
_BATCH_AREA = 4_000_000


def _device_area(path, t, size, reach=1.0):
    """Pixels of the device box of ``path``'s control points under ``t``,
    grown by ``reach`` and clipped to the canvas ``size`` (w, h): a bound
    of the mask area, for batch budgets."""
    x0, y0, x1, y1 = path.control_box()
    a, b, c, d, e, f = t.a, t.b, t.c, t.d, t.e, t.f
    xs = (a * x0 + c * y0, a * x1 + c * y0, a * x0 + c * y1, a * x1 + c * y1)
    ys = (b * x0 + d * y0, b * x1 + d * y0, b * x0 + d * y1, b * x1 + d * y1)
    w = min(max(xs) + e + reach, size[0]) - max(min(xs) + e - reach, 0.0)
    h = min(max(ys) + f + reach, size[1]) - max(min(ys) + f - reach, 0.0)
    return max(w, 0.0) * max(h, 0.0)


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



def _hairline_edges(pl, cap, join, miterlimit):
    """Outline edges of a 1 device pixel wide stroke along device-space
    polylines ``pl`` (:class:`raster.flatten.Polylines`), for hairlines:
    :func:`_hairline_outline` with one cap, join and miter limit.

    Returns
    -------
    (E, 2, 2) float64 ndarray, or None when the general stroker must be used
    (a polyline of one distinct point with a non-butt cap: a dot).
    """
    k = len(pl)
    edges, _, dots = _hairline_outline(pl, np.full(k, cap != 'butt'),
                                       np.full(k, join in ('miter', 'miter-clip', 'arcs')),
                                       np.full(k, float(miterlimit)))
    return None if dots.any() else edges


def _hairline_outline(pl, capped, mitered, miterlimit):
    """Outline edges of 1 device pixel wide strokes along device-space
    polylines ``pl`` (:class:`raster.flatten.Polylines`), for hairlines.

    The stroke of a polyline is the union of a 1 px wide rectangle per
    segment, a bevel triangle at each vertex between two segments (plus the
    miter triangle where the polyline is ``mitered`` and the join within
    its ``miterlimit``) and, for ``capped`` polylines (square and round
    caps), a half-pixel extension at the ends of open polylines (a round
    cap is drawn square: at most 0.054 px^2 more per end).  Round joins are
    drawn bevelled (at most 0.04 px^2 less per join).  The pieces are
    separate polygons of one orientation (negative signed area), meant for
    the nonzero rule; :func:`raster.scan.coverage` with ``exact=False``
    sums their areas per pixel (clipped to 1), which counts the small
    overlaps of consecutive rectangles inside a turn twice, as a hairline
    renderer drawing one segment at a time does.  One vectorized pass for
    all polylines: no offset curves and no per-vertex Python work.

    Parameters
    ----------
    pl : raster.flatten.Polylines
        K polylines, device pixels.
    capped, mitered : (K,) bool ndarray
    miterlimit : (K,) float64 ndarray

    Returns
    -------
    edges : (E, 2, 2) float64 ndarray
        Polyline after polyline; each segment's rectangle, then the join
        after it.
    owner : (E,) int64 ndarray
        The polyline of each edge (non-decreasing).
    dots : (K,) bool ndarray
        Capped polylines of one distinct point: they draw a dot, which
        this outline leaves out (the general stroker draws it).
    """
    r = 0.5
    P = pl.points
    n = len(P)
    K = len(pl)
    none = (np.zeros((0, 2, 2)), np.zeros(0, np.int64), np.zeros(K, bool))
    if n == 0:
        return none
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
    counts = np.bincount(poly, minlength=K)
    dots = capped & (counts == 0)
    S = len(a)
    if S == 0:
        return none[0], none[1], dots
    u = d / length[:, None]
    nv = np.stack([-u[:, 1], u[:, 0]], 1) * r
    j = np.arange(S)
    first = np.ones(S, bool)
    first[1:] = poly[1:] != poly[:-1]
    last = np.ones(S, bool)
    last[:-1] = poly[1:] != poly[:-1]
    op = capped[poly] & ~closed[poly]
    if op.any():
        # square (and round, drawn square) caps on open polylines
        a = a - (u * r) * (first & op)[:, None]
        b = b + (u * r) * (last & op)[:, None]
    # joins: each segment with the next one of its polyline (closed: wrap)
    head = np.maximum.accumulate(np.where(first, j, 0))
    nseg = np.where(~last, j + 1, np.where(closed[poly], head, -1))
    has_join = nseg >= 0
    i1 = np.flatnonzero(has_join)
    i2 = nseg[i1]
    v = P[nxt[a_idx[i1]]]
    cr = u[i1, 0] * u[i2, 1] - u[i1, 1] * u[i2, 0]
    side = np.where(cr > 0, -1.0, 1.0)[:, None]          # the outer side
    p1, p2 = v + side * nv[i1], v + side * nv[i2]
    within = np.zeros(S, bool)
    if len(i1):
        cos_t = np.clip((u[i1] * u[i2]).sum(1), -1.0, 1.0)   # turning angle
        # miter length / stroke width = 1 / sin(phi / 2), phi the angle
        # between the segments = pi - turning angle: 1 / cos(turn / 2)
        half = np.sqrt(np.maximum((1.0 + cos_t) / 2.0, 0.0))
        w_j = (mitered[poly[i1]] & (half > 1e-12) & (1.0 <= miterlimit[poly[i1]] * half)
               & (cos_t < 1.0 - 1e-12))
        within[i1] = w_j
    # edge slots: 4 per rectangle, 3 per bevel, 3 per miter triangle
    cnt = 4 + 3 * has_join + 3 * within
    off = np.cumsum(cnt) - cnt
    out = np.empty((int(cnt.sum()), 2, 2))
    # a + n, b + n, b - n, a - n with n = r (-uy, ux): negative signed area
    quad = np.stack([a + nv, b + nv, b - nv, a - nv], 1)
    for k in range(4):
        out[off + k, 0] = quad[:, k]
        out[off + k, 1] = quad[:, (k + 1) % 4]
    if len(i1):
        _put_triangles(out, off[i1] + 4, v, p1, p2)
        if w_j.any():
            bis = side[w_j] * (nv[i1][w_j] + nv[i2][w_j])
            bl = np.hypot(bis[:, 0], bis[:, 1])[:, None]
            tip = v[w_j] + bis / np.maximum(bl, 1e-300) * (r / half[w_j][:, None])
            _put_triangles(out, off[i1[w_j]] + 7, p1[w_j], tip, p2[w_j])
    return out, np.repeat(poly, cnt), dots


def _put_triangles(out, at, p, q, s):
    """Write the triangles (p, q, s) ((M, 2) each) as 3 edges each at
    ``out[at .. at + 2]``, turned to negative signed area."""
    flip = ((q[:, 0] - p[:, 0]) * (s[:, 1] - p[:, 1])
            - (q[:, 1] - p[:, 1]) * (s[:, 0] - p[:, 0])) > 0
    if flip.any():
        q, s = np.where(flip[:, None], s, q), np.where(flip[:, None], q, s)
    for k, (x, y) in enumerate(((p, q), (q, s), (s, p))):
        out[at + k, 0] = x
        out[at + k, 1] = y


def _clip_rect(g, t):
    """The device box (x0, y0, x1, y1) of group ``g``'s clip path (CTM of
    the parent ``t``) when the clip path is all that needs a layer and it
    is one antialiased axis-aligned rectangle in device space; else None.

    Drawing the children through the rectangle's coverage instead of into
    a clipped layer gives the same pixels except where children overlap
    each other in a pixel the rectangle's edge crosses (there a layer
    clips the composite of the children, this clips each child)."""
    cp = g.clip_path
    if (cp is None or cp.clip_path is not None or g.mask is not None or g.filters
            or g.opacity < 1.0 or g.blend_mode != 'normal' or g.isolate):
        return None
    rect = _RECT_CLIPS.get(id(cp), _UNSEEN)
    if rect is _UNSEEN or rect[0] is not cp:
        rect = (cp, _clip_rectangle(cp))
        _RECT_CLIPS[id(cp)] = rect
        if len(_RECT_CLIPS) > 4096:
            _RECT_CLIPS.clear()
    r = rect[1]
    if r is None:
        return None
    m = t @ g.transform @ cp.transform @ cp.root.transform
    if m.b != 0.0 or m.c != 0.0:
        return None
    x0, y0, x1, y1 = r
    xa, xb = m.a * x0 + m.e, m.a * x1 + m.e
    ya, yb = m.d * y0 + m.f, m.d * y1 + m.f
    box = (min(xa, xb), min(ya, yb), max(xa, xb), max(ya, yb))
    if not all(math.isfinite(v) for v in box):
        return None
    return box


_UNSEEN = object()
# id(ClipPath) -> (ClipPath, (x0, y0, x1, y1) in the root's units or None)
_RECT_CLIPS = {}


def _clip_rectangle(cp):
    """(x0, y0, x1, y1) when clip path ``cp`` is one antialiased polygon
    ``M L L L Z`` (or with a fifth point back at the start) whose sides
    are axis-aligned, in its root group's coordinates; else None."""
    root = cp.root
    if not isinstance(root, Group) or len(root.children) != 1 or root.needs_layer:
        return None
    n = root.children[0]
    if not isinstance(n, PathNode) or n.path is None or not n.antialias:
        return None
    p = n.path
    v = p.verbs.tolist()
    q = p.points.tolist()
    if len(q) not in (4, 5) or len(v) != len(q) + 1:
        return None
    if v[0] != MOVE or v[-1] != CLOSE or any(x != LINE for x in v[1:-1]):
        return None
    if len(q) == 5:
        if q[4] != q[0]:
            return None
        q = q[:4]
    xs = [x for x, _ in q]
    ys = [y for _, y in q]
    # consecutive corners differ in exactly one coordinate, alternately
    steps = [(xs[(k + 1) % 4] != xs[k], ys[(k + 1) % 4] != ys[k]) for k in range(4)]
    if not all(dx != dy for dx, dy in steps):
        return None
    if not all(steps[k][0] != steps[k + 1][0] for k in range(3)):
        return None
    return (min(xs), min(ys), max(xs), max(ys))


class _ClipRect:
    """A canvas seen through an axis-aligned device rectangle ``box``
    (x0, y0, x1, y1): :meth:`fill`, :meth:`composite` and :meth:`store`
    act on the canvas with the source multiplied by the rectangle's exact
    area coverage of each pixel (the product of its x and y overlaps).
    ``width``, ``height`` and ``data`` are the canvas's."""

    def __init__(self, canvas, box):
        self.canvas = canvas
        self.width, self.height = canvas.width, canvas.height
        x0, y0, x1, y1 = box
        self.X0 = max(0, int(math.floor(x0)))
        self.Y0 = max(0, int(math.floor(y0)))
        self.X1 = min(self.width, int(math.ceil(x1)))
        self.Y1 = min(self.height, int(math.ceil(y1)))
        self.empty = self.X1 <= self.X0 or self.Y1 <= self.Y0 or x1 <= x0 or y1 <= y0
        if not self.empty:
            j = np.arange(self.X0, self.X1, dtype=np.float64)
            i = np.arange(self.Y0, self.Y1, dtype=np.float64)
            self.cx = np.clip(np.minimum(x1, j + 1) - np.maximum(x0, j), 0, 1).astype(np.float32)
            self.cy = np.clip(np.minimum(y1, i + 1) - np.maximum(y0, i), 0, 1).astype(np.float32)

    @property
    def data(self):
        return self.canvas.data

    def _window(self, x0, y0, h, w):
        """(a0, b0, a1, b1, cov): the window's part inside the rectangle in
        canvas pixels and the coverage there, or None."""
        if self.empty:
            return None
        a0, b0 = max(x0, self.X0), max(y0, self.Y0)
        a1, b1 = min(x0 + w, self.X1), min(y0 + h, self.Y1)
        if a1 <= a0 or b1 <= b0:
            return None
        cov = self.cy[b0 - self.Y0:b1 - self.Y0, None] * self.cx[None, a0 - self.X0:a1 - self.X0]
        return a0, b0, a1, b1, cov

    def fill(self, mask, color, opacity=1.0):
        if mask is None:
            return
        h, w = mask.data.shape
        win = self._window(int(mask.x0), int(mask.y0), h, w)
        if win is None:
            return
        a0, b0, a1, b1, cov = win
        k = mask.data[b0 - mask.y0:b1 - mask.y0, a0 - mask.x0:a1 - mask.x0] * cov
        self.canvas.fill(Mask(k, a0, b0), color, opacity)

    def composite(self, src, x0=0, y0=0, opacity=1.0):
        src = np.asarray(src, np.float32)
        win = self._window(int(x0), int(y0), src.shape[0], src.shape[1])
        if win is None:
            return
        a0, b0, a1, b1, cov = win
        s = src[b0 - y0:b1 - y0, a0 - x0:a1 - x0] * cov[..., None]
        self.canvas.composite(s, a0, b0, opacity)

    def store(self, y0, y1, x0, x1, out):
        """Replace canvas pixels [y0:y1, x0:x1] by ``out`` (h, w, 4) as
        seen through the rectangle: ``old + coverage (out - old)``."""
        win = self._window(x0, y0, y1 - y0, x1 - x0)
        if win is None:
            return
        a0, b0, a1, b1, cov = win
        new = out[b0 - y0:b1 - y0, a0 - x0:a1 - x0]
        if isinstance(self.canvas, _ClipRect):
            old = self.canvas.data[b0:b1, a0:a1]
            self.canvas.store(b0, b1, a0, a1, old + (new - old) * cov[..., None])
        else:
            old = self.canvas.data[b0:b1, a0:a1]
            old += (new - old) * cov[..., None]


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
    out = np.clip(out, 0, 1).astype(np.float32)
    if isinstance(canvas, _ClipRect):
        canvas.store(cy0, cy1, cx0, cx1, out)
    else:
        canvas.data[cy0:cy1, cx0:cx1] = out
