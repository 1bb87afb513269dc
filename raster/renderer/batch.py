"""Coverage masks of paths, computed a batch of nodes at a time.

The renderer's loop asks for one node's fill or stroke mask at a time, in
document order; drawing one path costs a fixed overhead that dominates
documents of thousands of small shapes.  :class:`Masks` therefore plans
ahead: :meth:`Masks.plan` queues the paths of a subtree drawn directly on
one canvas (not inside layered groups), and the first request for a
queued node computes the masks of a whole batch of queued nodes at once:

* fills and undashed hairlines are flattened together
  (:func:`raster.geometry.flattening.flatten_joined`), the hairlines outlined in one
  pass (:func:`raster.pixels.hairline.hairline_outline`) and every mask
  scan converted in one :func:`raster.pixels.scan.coverage_batch` call
  (hairlines with ``exact=False``); the hairline of a filled path whose
  box is above :data:`BATCH_AREA` is drawn on its own after its fill, so
  that two box-sized masks are never held together;
* other strokes are outlined with one :func:`raster.geometry.stroking.stroke_many`
  call per stroke style, flattened together and scan converted in one
  batch.

Only the masks are computed ahead; compositing stays in document order.
Queued entries are keyed by ``(id(node), CTM)`` and remember the canvas
size they were planned for; a batch holds at most :data:`BATCH_VERBS`
verbs and :data:`BATCH_AREA` mask pixels.  A node that was not queued (or
whose batch failed) is drawn on its own.
"""

import numpy as np

from .. import limits
from ..errors import RasterError
from ..geometry.flattening import ContourCache, flatten, flatten_joined
from ..pixels.hairline import hairline_edges, hairline_outline
from ..pixels.scan import Mask, coverage, coverage_batch
from ..geometry.stroking import StrokeStyle, hairline_scale, stroke as stroke_outline, stroke_many
from ..tree import Group, PathNode
from ..geometry.culling import cull_fill, cull_stroke
from .bounds import clip_rect, device_area, device_box, stroke_reach

__all__ = ['Masks', 'EdgeStore', 'BATCH_VERBS', 'BATCH_AREA', 'STORE_EDGES']

#: Verbs per batch of fills and hairlines (a quarter of it for strokes):
#: bounds the batch's geometry.
BATCH_VERBS = 5_000

#: Mask pixels per batch (the masks of a batch are held until drawn).
BATCH_AREA = 1_000_000

#: Most edges an :class:`EdgeStore` holds (32 bytes each).
STORE_EDGES = 2_000_000

_ABSENT = object()


class EdgeStore:
    """Edges of outlines that reach past the window being drawn, kept
    for the next windows of the same output (:func:`raster.renderer.render_tree`
    with ``store=``): a path crossing several strips or tiles is flattened
    and stroked once.  Edges are in the output's pixels (windows draw with
    the whole output's CTM), so they are the same for every window; an
    entry is dropped once a window starts below its device box (windows
    drawn top to bottom, as strips and tile rows are; in another order
    an outline is only flattened again).  Holds at most
    :data:`STORE_EDGES` edges.  One store serves one tree, output and
    tolerance: :meth:`bind` empties it for another."""

    def __init__(self, max_edges: int = STORE_EDGES) -> None:
        self._d = {}
        self._edges = 0
        self._max = int(max_edges)
        self._bound = None
        self.hits = 0

    def bind(self, tree, transform, tolerance, y0):
        """Use the store for a window of ``tree`` drawn with the output
        CTM ``transform`` and ``tolerance``, starting at row ``y0``."""
        bound = (tree, tuple(transform), float(tolerance))
        if self._bound is None or self._bound[0] is not tree or self._bound[1:] != bound[1:]:
            self._d.clear()
            self._edges = 0
            self._bound = bound
        gone = [k for k, v in self._d.items() if v[1] <= y0]
        for k in gone:
            self._edges -= len(self._d.pop(k)[0])

    def get(self, key):
        v = self._d.get(key)
        if v is None:
            return None
        self.hits += 1
        return v[0]

    def put(self, key, edges, bottom):
        """Keep a copy of ``edges`` (an array, or a fill's and hairline's
        pair) under ``key`` until a window starts below row ``bottom``."""
        if self._edges + len(edges) <= self._max:
            edges = edges.copy()
            old = self._d.pop(key, None)
            if old is not None:
                self._edges -= len(old[0])
            self._d[key] = (edges, bottom)
            self._edges += len(edges)

    def __len__(self):
        return len(self._d)


class Masks:
    """Fill and stroke masks of path nodes, batched (see the module
    docstring); ``tolerance`` is the flattening tolerance in device
    pixels."""

    def __init__(self, tolerance, store=None):
        self.tol = tolerance
        # an EdgeStore shared by the windows of one output (or None), and
        # the canvas (w, h, ox, oy) whose paths it serves (the window's own)
        self.store = store
        self._store_size = None
        self._flat_key = self._flat_path = self._flat = None
        # distinct contours flattened so far (glyphs, markers), for the
        # later batches of this render
        self._shapes = ContourCache()
        # fills and undashed hairlines: key -> (node, t, size, area, fill?,
        # hair?) waiting in document order (per canvas), and key -> Mask or
        # None of those already scan converted (a hairline is absent when
        # the general stroker is needed)
        self._geo_pending = _Queue()
        self._fill_ready = {}
        self._hair_ready = {}
        # other strokes: key -> (node, t, size, area, style) waiting, and
        # key -> Mask or None already scan converted
        self._stroke_pending = _Queue()
        self._stroke_ready = {}
        # keys of fills / strokes whose device box misses their canvas:
        # they cover nothing (a closed outline wholly outside a canvas adds
        # no winding inside it) and are never flattened -- what makes a
        # window of a large render cost about its share of the paths
        # (key -> the canvas size it was planned for)
        self._outside_fill = {}
        self._outside_stroke = {}
        # keys of fills that are rectangles covering their whole canvas
        # (backgrounds): coverage 1 everywhere, never scan converted (key ->
        # the canvas size it was planned for)
        self._cover_fill = {}

    # -- planning ----------------------------------------------------------------
    def plan(self, nodes, t, canvas, off=(0, 0), output=False):
        """Queue the paths of ``nodes`` (with CTM ``t`` to the canvas's
        frame, where the canvas lies at ``off`` (ox, oy): see
        :meth:`raster.renderer.draw.Renderer.draw`) drawn directly on
        ``canvas`` (not inside layered groups).  ``output``: the canvas is
        (a window of) the output, whose outlines the store keeps."""
        stack = [(n, t) for n in reversed(nodes)]
        geo = self._geo_pending
        strokes = self._stroke_pending
        size = (canvas.width, canvas.height, int(off[0]), int(off[1]))
        if output and self.store is not None:
            self._store_size = size
        while stack:
            n, m = stack.pop()
            if isinstance(n, Group):
                if n.needs_layer and clip_rect(n, m) is None:
                    continue
                ct = m @ n.transform
                stack.extend((c, ct) for c in reversed(n.children))
            elif isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
                if n.markers is not None:       # drawn after the path: planned after it
                    stack.append((n.markers, m))
                f = n.fill
                wf = f is not None and f.opacity > 0
                wh = _wants_hair(n, m)
                # (hairlines are never outlined by the general stroker here)
                style = None if wh else _batch_stroke_style(n, m)
                if not (wf or wh or style is not None):
                    continue
                area = device_area(n.path, m, size[:2], off=size[2:])
                if wf and wh and area > BATCH_AREA:
                    # a filled hairline over a large box: its masks would
                    # be held together (two box-sized arrays); the hairline
                    # is drawn on its own once the fill is drawn
                    wh = False
                key = (id(n), m)
                if wf and key not in geo and covers_canvas(n.path, m, *size):
                    self._cover_fill[key] = size
                    wf = False
                if wf or wh:
                    if area > 0:
                        geo.put(key, (n, m, size, area, wf, wh))
                    elif key not in geo:
                        self._outside_fill[key] = size
                        if wh:
                            self._outside_stroke[key] = size
                if style is not None:
                    reach = stroke_reach(style) * m.max_scale() + 1.0
                    sarea = device_area(n.path, m, size[:2], reach, off=size[2:])
                    if sarea > 0:
                        strokes.put(key, (n, m, size, sarea, style))
                    elif key not in strokes:
                        self._outside_stroke[key] = size

    # -- masks -------------------------------------------------------------------
    def fill(self, n, t, canvas, off=(0, 0)):
        """The fill coverage Mask of PathNode ``n`` under ``t`` on
        ``canvas`` at ``off`` (as for :meth:`plan`; None: nothing covered)."""
        key = (id(n), t)
        size = (canvas.width, canvas.height, int(off[0]), int(off[1]))
        if self._outside_fill.get(key) == size:
            del self._outside_fill[key]
            return None
        if self._cover_fill.get(key) == size or (
                key not in self._geo_pending and key not in self._fill_ready
                and covers_canvas(n.path, t, *size)):
            self._cover_fill.pop(key, None)
            return full_mask(*size[:2])
        if key in self._geo_pending:
            self._flush_geometry(key, size)
        if key in self._fill_ready:
            return self._fill_ready.pop(key)
        edges = _onto(self.flat(n, t, size).edges(close_all=True), size)[0]
        if len(edges) == 0:
            return None
        return coverage(edges, canvas.width, canvas.height, n.fill.rule, n.antialias)

    def stroke(self, n, t, canvas, off=(0, 0)):
        """``(Mask or None, opacity factor)`` of PathNode ``n``'s stroke
        under ``t`` on ``canvas``.  A stroke thinner than one device pixel
        is drawn one pixel wide with its coverage scaled by its device width
        (the factor), as resvg does, unless the node is not anti-aliased
        (then it is outlined at its width and filled aliased); an undashed one is outlined from the
        fill's polylines (:func:`raster.pixels.hairline.hairline_edges`)."""
        s = n.stroke.style
        key = (id(n), t)
        size = (canvas.width, canvas.height, int(off[0]), int(off[1]))
        if self._outside_stroke.get(key) == size:
            del self._outside_stroke[key]
            return None, 1.0
        if key in self._geo_pending:
            self._flush_geometry(key, size)
        m = self._hair_ready.pop(key, _ABSENT)
        if m is not _ABSENT:            # a batched hairline
            return m, s.width * t.mean_scale()
        factor = 1.0
        style = s
        # without anti-aliasing (shape-rendering crispEdges, optimizeSpeed) a
        # thin stroke is outlined at its own width and filled aliased at
        # full opacity, as resvg does (no hairline substitute)
        hair = hairline_scale(s, t) if n.antialias else None
        if hair is not None:
            style = StrokeStyle(width=1.0 / t.mean_scale(), join=s.join, cap=s.cap,
                                miterlimit=s.miterlimit, dash=s.dash, dash_offset=s.dash_offset)
            factor = hair
            if s.dash is None:
                edges = hairline_edges(self.flat(n, t, size), s.cap, s.join, s.miterlimit)
                if edges is not None:
                    if not len(edges):
                        return None, factor
                    return coverage(_onto(edges, size)[0], canvas.width, canvas.height, 'nonzero',
                                    n.antialias, exact=False), factor
        else:
            if key in self._stroke_pending:
                self._flush_strokes(key, size)
            if key in self._stroke_ready:
                return self._stroke_ready.pop(key), factor
        outline = stroke_outline(self.cut_stroke(n, style, t, size), style, transform=t,
                                 tolerance=self.tol, straddle=True, window=self._box(size))
        if len(outline.verbs) == 0:
            return None, factor
        edges = _onto(flatten(outline, self.tol).edges(close_all=True), size)[0]
        return coverage(edges, canvas.width, canvas.height, 'nonzero', n.antialias), factor

    def flat(self, n, t, size):
        """Polylines of PathNode ``n``'s path flattened under ``t`` (device
        pixels), cut down to what reaches the canvas of ``size`` (see
        :meth:`cut_fill`).  The last result is kept: a filled and stroked
        hairline path drawn one by one is flattened once."""
        key = (id(n.path), t, size)
        if self._flat_key == key and self._flat_path is n.path:
            return self._flat
        pl = flatten(self.cut_fill(n, t, size), self.tol, transform=t, straddle=True)
        self._flat_key, self._flat_path, self._flat = key, n.path, pl
        return pl

    # -- cutting paths to their canvas -------------------------------------------
    def _box(self, size):
        """The frame rectangle a canvas of ``size`` (w, h, ox, oy) draws;
        for the output window whose outlines the store keeps, every row
        from its top down (the windows after it lie right of it or below)."""
        w, h, ox, oy = size
        if self.store is not None and size == self._store_size:
            return (-np.inf, float(oy), np.inf, np.inf)
        return (float(ox), float(oy), float(ox + w), float(oy + h))

    def cut_fill(self, n, t, size):
        """PathNode ``n``'s path with the segments far from the canvas of
        ``size`` replaced by lines (:func:`raster.geometry.culling.cull_fill`):
        the same fill, and the same hairline, on the canvas."""
        margin = 2.0 + self.tol
        if n.stroke is not None:
            margin += 0.5 * max(float(n.stroke.style.miterlimit), 1.5)
        return self._cut(cull_fill, n.path, t, size, margin)

    def cut_stroke(self, n, style, t, size):
        """PathNode ``n``'s path without the segments its stroke of
        ``style`` (undashed) cannot bring onto the canvas of ``size``
        (:func:`raster.geometry.culling.cull_stroke`).  A dashed stroke is
        cut after dashing, by the stroker (its ``window``)."""
        if style.dash is not None:
            return n.path
        reach = stroke_reach(style) * t.max_scale() + 2.0 + self.tol
        return self._cut(cull_stroke, n.path, t, size, reach)

    def _cut(self, cull, path, t, size, margin):
        box = self._box(size)
        x0, y0, x1, y1 = device_box(path, t)
        if (x0 >= box[0] - margin and y0 >= box[1] - margin and x1 <= box[2] + margin
                and y1 <= box[3] + margin):
            return path
        return cull(path, t, box, margin)

    # -- batches -----------------------------------------------------------------
    def _take(self, pending, key, size, verbs_max):
        """Pop entries of ``pending`` (a :class:`_Queue`) queued for a
        canvas of ``size`` (w, h, ox, oy), in document order, up to and
        including ``key`` and then while the batch holds fewer than
        ``verbs_max`` verbs and :data:`BATCH_AREA` pixels of masks.
        Entries of other canvases stay queued: a layer drawn between two
        paths of the output does not send the output's later paths to be
        drawn one by one."""
        queue = pending.of(size)
        keys, verbs, area, seen = [], 0, 0.0, False
        for k in queue:
            v = queue[k]
            if seen and (verbs >= verbs_max or area + v[3] > BATCH_AREA):
                break
            keys.append(k)
            seen = seen or k == key
            verbs += len(v[0].path.verbs)
            area += v[3]
        return [(k,) + pending.pop(k) for k in keys]

    def _kept(self, items, size, tag):
        """``(todo, kept)``: the items to outline, and for the others the
        stored edges (``(item, edges)``; see :class:`EdgeStore`)."""
        if self.store is None or size != self._store_size:
            return items, []
        todo, kept = [], []
        for it in items:
            e = self.store.get((tag, it[0]))
            if e is None:
                todo.append(it)
            else:
                kept.append((it, e))
        return todo, kept

    def _keep(self, items, edges, size, tag):
        """Store ``edges[i]`` (what the store keeps of ``items[i]``) of
        the items whose device box reaches past the window's right or
        bottom."""
        w, h, ox, oy = size
        for it, e in zip(items, edges):
            m = it[2]
            _, _, right, bottom = device_box(it[1].path, m)
            reach = 2.0
            if tag == 'stroke':
                reach += stroke_reach(it[5]) * m.max_scale()
            bottom += reach
            if bottom > oy + h or right + reach > ox + w:
                self.store.put((tag, it[0]), e, bottom)

    def _flush_geometry(self, key, size):
        """Masks of queued fills and undashed hairlines for ``canvas``, in
        document order up to and including ``key`` and then while the batch
        has room."""
        items = self._take(self._geo_pending, key, size, BATCH_VERBS)
        if not items:
            return
        items, kept = self._kept(items, size, 'geo')
        self._geometry(items, kept, size)

    def _geometry(self, items, kept, size):
        """Masks of fills and hairlines: ``items`` outlined now, ``kept``
        with stored edges (``(item, (fill edges, hair edges or None))``)."""
        if not items:
            self._scan_geometry([], [], [], [], [], [], kept, size)
            return
        try:
            pl, first = flatten_joined([self.cut_fill(it[1], it[2], size) for it in items],
                                       [it[2] for it in items], self.tol, straddle=True,
                                       cache=self._shapes)
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
            styles = [items[i][1].stroke.style for i in hi.tolist()]
            per = npl[hi]
            capped = np.repeat([s.cap != 'butt' for s in styles], per).astype(bool)
            mitered = np.repeat([s.join in ('miter', 'miter-clip', 'arcs') for s in styles],
                                per).astype(bool)
            limit = np.repeat([float(s.miterlimit) for s in styles], per).astype(np.float64)
            e, own, dots = hairline_outline(sub, capped, mitered, limit)
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
        # (only the parts are scanned: the polylines and per-edge owners go
        # before the coverage, the peak of a large batch)
        pl = sub = e = own = poly_item = keep = None
        self._scan_geometry(items, parts, counts, rules, aas, exact, kept, size, keys)

    def _scan_geometry(self, items, parts, counts, rules, aas, exact, kept, size, keys=()):
        """Scan convert the masks of :meth:`_geometry` in one batch; the
        edges of items reaching past the window are stored."""
        keys = list(keys)
        e = np.concatenate(parts) if parts else np.zeros((0, 2, 2))
        cnt = np.concatenate(counts) if counts else np.zeros(0, np.int64)
        if self.store is not None and size == self._store_size and items:
            # per item: its fill edges, then its hairline edges (None: dotted)
            nf = sum(1 for it in items if it[5])
            fill_items = [it for it in items if it[5]]
            hair_items = [it for it in items if it[6]]
            ends = np.cumsum(cnt)
            starts = ends - cnt
            fe = {it[0]: e[a:b] for it, a, b in zip(fill_items, starts[:nf].tolist(),
                                                    ends[:nf].tolist())}
            he = {}
            for j, it in enumerate(hair_items):
                a, b = int(starts[nf + j]), int(ends[nf + j])
                he[it[0]] = None if keys[nf + j] is None else e[a:b]
            self._keep(items, [_Pair(fe.get(it[0]), he.get(it[0])) for it in items], size,
                       'geo')
        if kept:
            ep, cp = [e], [cnt]
            for it, pair in kept:
                n = it[1]
                if it[5]:
                    ep.append(pair.fill)
                    cp.append([len(pair.fill)])
                    rules.append(n.fill.rule)
                    aas.append(bool(n.antialias))
                    exact.append(True)
                    keys.append((self._fill_ready, it[0]))
                if it[6]:
                    h = pair.hair
                    ep.append(np.zeros((0, 2, 2)) if h is None else h)
                    cp.append([0 if h is None else len(h)])
                    rules.append('nonzero')
                    aas.append(bool(n.antialias))
                    exact.append(False)
                    keys.append(None if h is None else (self._hair_ready, it[0]))
            e = np.concatenate(ep)
            cnt = np.concatenate([np.asarray(c, np.int64) for c in cp])
        if not keys:
            return
        try:
            e, cnt = _onto(e, size, cnt)
            # (e is this batch's own: moved into the boxes in place)
            masks = coverage_batch(e, cnt, size[0], size[1], rules, aas, exact=exact,
                                   overwrite=True)
        except RasterError:
            return          # drawn one by one (errors where they were)
        for where, m in zip(keys, masks):
            if where is not None:
                where[0][where[1]] = m

    def _flush_strokes(self, key, size):
        """Outline queued strokes for ``canvas`` in document order, up to
        and including ``key`` and then while the batch has room: one
        :func:`raster.geometry.stroking.stroke_many` call per stroke style, then one
        :func:`raster.geometry.flattening.flatten_joined` and one
        :func:`raster.pixels.scan.coverage_batch` call for all outlines."""
        items = self._take(self._stroke_pending, key, size, BATCH_VERBS // 4)
        if not items:
            return
        items, kept = self._kept(items, size, 'stroke')
        by_style = {}
        for j, it in enumerate(items):
            by_style.setdefault(it[5], []).append(j)
        outlines = [None] * len(items)
        try:
            for style, js in by_style.items():
                outs = stroke_many([self.cut_stroke(items[j][1], style, items[j][2], size)
                                    for j in js], style,
                                   transforms=[items[j][2] for j in js], tolerance=self.tol,
                                   straddle=True, window=self._box(size))
                for j, o in zip(js, outs):
                    outlines[j] = o
            if items:
                pl, first = flatten_joined(outlines, None, self.tol, cache=self._shapes)
                outlines = outs = o = None          # (in the polylines now)
                e, own = pl.edges(close_all=True, owners=True)
                pl = None
                counts = np.bincount(np.repeat(np.arange(len(items)), np.diff(first))[own]
                                     if len(own) else own, minlength=len(items))
                if self.store is not None and size == self._store_size:
                    ends = np.cumsum(counts)
                    self._keep(items, [e[a:b] for a, b in zip((ends - counts).tolist(),
                                                              ends.tolist())], size, 'stroke')
            else:
                e, counts = np.zeros((0, 2, 2)), np.zeros(0, np.int64)
            own = None          # (freed before the coverage, the peak of a long stroke)
            if kept:
                items = items + [it for it, _ in kept]
                e = np.concatenate([e] + [k for _, k in kept])
                counts = np.concatenate([counts, [len(k) for _, k in kept]]).astype(np.int64)
            e, counts = _onto(e, size, counts)
            masks = coverage_batch(e, counts, size[0], size[1], 'nonzero',
                                   [bool(it[1].antialias) for it in items], overwrite=True)
        except RasterError:
            return          # stroked one by one (errors where they were)
        self._stroke_ready.update(zip([it[0] for it in items], masks))


class _Queue:
    """Queued entries ``key -> (node, t, size, ...)`` of :class:`Masks`,
    one document-ordered dict per canvas ``size`` (an entry's third
    item), a key in one of them at most."""
    __slots__ = ('_by_size', '_size_of')

    def __init__(self):
        self._by_size = {}
        self._size_of = {}

    def __contains__(self, key):
        return key in self._size_of

    def put(self, key, entry):
        """Queue ``entry`` under ``key`` unless the key is queued."""
        if key not in self._size_of:
            self._size_of[key] = entry[2]
            self._by_size.setdefault(entry[2], {})[key] = entry

    def values(self):
        """Every queued entry (canvas after canvas)."""
        for q in self._by_size.values():
            yield from q.values()

    def of(self, size):
        """The entries queued for ``size`` (a dict, in order; read only)."""
        return self._by_size.get(size, {})

    def pop(self, key):
        size = self._size_of.pop(key)
        q = self._by_size[size]
        entry = q.pop(key)
        if not q:
            del self._by_size[size]
        return entry


class _Pair:
    """The stored edges of a fill and of its hairline (None: none, or a
    dotted hairline left to the general stroker)."""
    __slots__ = ('fill', 'hair')

    def __init__(self, fill, hair):
        self.fill, self.hair = fill, hair

    def copy(self):
        return _Pair(None if self.fill is None else self.fill.copy(),
                     None if self.hair is None else self.hair.copy())

    def __len__(self):
        return (0 if self.fill is None else len(self.fill)) + \
            (0 if self.hair is None else len(self.hair))


def _onto(edges, size, counts=None):
    """Edges ((E, 2, 2) float64, in the pixels of a canvas's frame) moved
    onto a canvas of ``size`` (w, h, ox, oy) lying at (ox, oy) in it --
    by whole pixels, so the fractional parts stay as they are -- without
    those wholly above or below it (they touch no row of it; those beside
    it take part in the scan's running sums and stay).  ``counts`` (edges
    per mask, consecutive) are recounted; returns ``(edges, counts)``
    (``edges`` is never modified)."""
    w, h, ox, oy = size
    if len(edges):
        ya, yb = edges[:, 0, 1], edges[:, 1, 1]
        top, bottom = float(oy), float(oy + h)
        off = ((ya <= top) & (yb <= top)) | ((ya >= bottom) & (yb >= bottom))
        if off.any():
            keep = ~off
            if counts is not None:
                owner = np.repeat(np.arange(len(counts)), np.asarray(counts, np.int64))
                counts = np.bincount(owner[keep], minlength=len(counts))
            edges = edges[keep]             # a copy: moved in place below
            if ox or oy:
                edges -= np.array((ox, oy), np.float64)
            return edges, counts
    if ox or oy:
        edges = edges - np.array((ox, oy), np.float64)
    return edges, counts


def _batch_stroke_style(n, t):
    """The StrokeStyle of PathNode ``n``'s stroke when it can be outlined in
    a batch (visible, not a hairline), else None."""
    s = n.stroke
    if s is None or s.opacity <= 0 or s.style.width <= 0:
        return None
    if n.antialias and hairline_scale(s.style, t) is not None:
        return None
    return s.style


def _wants_hair(n, t):
    """Whether PathNode ``n`` under ``t`` has an undashed hairline stroke
    (outlined from the fill's polylines)."""
    s = n.stroke
    return (s is not None and s.style.dash is None and s.opacity > 0 and n.antialias
            and 0.0 < s.style.width * t.mean_scale() < 1.0)


def covers_canvas(path, t, width, height, ox=0, oy=0):
    """True when ``path`` under ``t`` is one closed axis-aligned rectangle
    (``M L L L Z``) containing the whole ``width`` x ``height`` canvas
    lying at (``ox``, ``oy``) in the pixels of ``t`` (a window's canvas in
    its frame), within ``max_coord``: its exact-area coverage is 1 at every pixel
    under both fill rules (winding +-1 everywhere inside), aliased or not,
    so it needs no scan conversion (a chart's background)."""
    # (plain Python on the four corners: a chart of many small rectangles
    # calls this once a rectangle; the arithmetic is numpy's apply's)
    if path.verbs.tobytes() != _RECT_VERBS:
        return False
    a, b, c, d, e, f = t.a, t.b, t.c, t.d, t.e, t.f
    p = [(a * x + c * y + e, b * x + d * y + f) for x, y in path.points[:4].tolist()]
    # consecutive corners (cyclically) differ in x or in y, alternately:
    # the four sides are horizontal, vertical, horizontal, vertical (or the
    # other way round), each of non-zero length
    dx = [p[i][0] != p[i - 3][0] for i in range(4)]
    dy = [p[i][1] != p[i - 3][1] for i in range(4)]
    if dx != [not v for v in dy] or dx not in ([True, False, True, False],
                                               [False, True, False, True]):
        return False
    mc = limits.current().max_coord
    if not all(abs(x) <= mc and abs(y) <= mc for x, y in p):     # (NaN: not inside)
        return False
    xs, ys = [x for x, _ in p], [y for _, y in p]
    return min(xs) <= ox and min(ys) <= oy and max(xs) >= ox + width and max(ys) >= oy + height


#: The verbs of one closed polygon of four corners (M L L L Z).
_RECT_VERBS = bytes([0, 1, 1, 1, 4])


def full_mask(width, height):
    """A Mask of coverage 1 over the whole ``width`` x ``height`` canvas
    whose data is one float32 value broadcast (read-only, no pixels
    stored)."""
    return Mask(np.broadcast_to(np.float32(1.0), (height, width)), 0, 0)
