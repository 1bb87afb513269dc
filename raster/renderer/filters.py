"""Filters on a rendered layer: the primitives of a
:class:`raster.tree.filter.Filter` run in order on device pixels, through
the operations of :mod:`raster.pixels.effects` and
:mod:`raster.pixels.compositing`, dispatched on the primitive's class.

Regions: the filter region is transformed to device space and rounded
outwards to whole pixels; everything outside it is transparent; each
primitive's result is limited to its subregion.  Transforms: an
axis-aligned CTM (scale + translate) is exact.  Under rotation or skew the
region is the device bounding box of the transformed user-space region;
blur radii and offsets are scaled by the lengths of the CTM matrix's rows
(not rotated), and turbulence runs along the device axes at that scale: an
approximation, the one resvg makes.  Offsets (feOffset, feDropShadow) move
by whole device pixels, truncated toward zero as resvg does (a 7.5 px offset
moves 7 px).  ``stitchTiles="stitch"`` tiles the
turbulence across its primitive subregion (user space).  Colour: results
carry their colour space; an input is converted to the primitive's space
(``linear``) on unpremultiplied values, and the final result back to sRGB.
"""

import math

import numpy as np

from .. import limits
from ..errors import RasterError
from ..pixels import compositing
from ..pixels import effects as fx
from ..pixels.effects import FilterImage
from ..geometry.transform import Affine
from ..tree import filter as F

__all__ = ['apply_filters', 'filter_layer', 'filter_box', 'filter_pixel_box', 'filter_margin',
           'filter_work']

_UNBOUNDED = 1e9


def _device_box(rect, t):
    if rect is None:                     # a filter function: no region
        return (-_UNBOUNDED, -_UNBOUNDED, _UNBOUNDED, _UNBOUNDED)
    x, y, w, h = rect
    pts = t.apply(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]], np.float64))
    lo, hi = pts.min(0), pts.max(0)
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def filter_box(filters, t, content=None):
    """Device box ``(x0, y0, x1, y1)`` covering the regions of ``filters``
    under the CTM ``t`` (user space to device pixels), or None.

    A filter without a region (a CSS filter function) covers the canvas,
    unless ``content`` is given: a callable returning the device box of
    what the filtered group draws (or None).  When every such filter keeps
    transparent pixels transparent (colour functions, blurs, shadows,
    offsets, as the CSS functions do) its box is that content box grown by
    how far its primitives move or spread pixels -- every pixel it can
    make non-zero, so the result is the same as over the canvas, for a
    fraction of the work."""
    box = None
    reach = None
    for f in filters:
        if f.region is None and content is not None:
            r = _function_reach(f, t)
            if r is not None:
                reach = r if reach is None else (reach[0] + r[0], reach[1] + r[1])
                continue
        b = _device_box(f.region, t)
        box = b if box is None else (min(box[0], b[0]), min(box[1], b[1]),
                                     max(box[2], b[2]), max(box[3], b[3]))
    if reach is not None:
        c = content()
        if c is not None:
            c = (c[0] - reach[0], c[1] - reach[1], c[2] + reach[0], c[3] + reach[1])
            box = c if box is None else (min(box[0], c[0]), min(box[1], c[1]),
                                         max(box[2], c[2]), max(box[3], c[3]))
    return box


def _keeps_transparent(p):
    """Whether primitive ``p`` (of a region-less filter) maps transparent
    black to transparent black, so it draws nothing outside its input."""
    k = type(p)
    if k is F.ColorMatrix:
        a = np.asarray(p.matrix, np.float64)[3]
        return bool(a[0] == 0 and a[1] == 0 and a[2] == 0 and a[4] == 0)
    if k is F.ComponentTransfer:
        fn = p.funcs.get(3)
        if fn is None:
            return True
        if isinstance(fn, (F.TableTransfer, F.DiscreteTransfer)):
            return bool(fn.values) and fn.values[0] == 0
        if isinstance(fn, F.LinearTransfer):
            return fn.intercept == 0
        return False
    return k in (F.GaussianBlur, F.DropShadow, F.Offset)


def _function_reach(f, t):
    """``(rx, ry)``: how far (device px) filter ``f``'s primitives can move
    or spread pixels under ``t``, or None when one may draw where its input
    is transparent (or reads anything but the previous result)."""
    sx, sy = math.hypot(t.a, t.c), math.hypot(t.b, t.d)
    rx = ry = 0.0
    for p in f.primitives:
        if not _keeps_transparent(p):
            return None
        if any(i is not F.Source.GRAPHIC and i is not F.PREVIOUS for i in p.inputs):
            return None
        k = type(p)
        if k is F.GaussianBlur or k is F.DropShadow:
            # box blurs reach under 3 sigma + 3 px, kernels 4 sigma + 1 px
            rx += 4.0 * max(p.std_dev[0], 0.0) * sx + 3.0
            ry += 4.0 * max(p.std_dev[1], 0.0) * sy + 3.0
        if k is F.Offset or k is F.DropShadow:
            rx += abs(p.dx) * sx + 1.0
            ry += abs(p.dy) * sy + 1.0
    if not (math.isfinite(rx) and math.isfinite(ry)):
        return None
    return rx, ry


def filter_pixel_box(box, width, height):
    """Integer pixel box ``(x0, y0, x1, y1)`` of a filter layer for the
    device box ``box`` on a ``width x height`` target, or None if empty.

    The box is rounded outwards and may reach past the target by up to the
    target's size on each side, so that content just outside the canvas
    still feeds offsets and blurs (as resvg); pixel counts stay bounded.

    >>> filter_pixel_box((-20.5, 3.2, 10.1, 8.0), 100, 50)
    (-21, 3, 11, 8)
    """
    if box is None or not all(math.isfinite(v) for v in box):
        return None
    x0 = max(int(math.floor(box[0] + 1e-6)), -width)
    y0 = max(int(math.floor(box[1] + 1e-6)), -height)
    x1 = min(int(math.ceil(box[2] - 1e-6)), 2 * width)
    y1 = min(int(math.ceil(box[3] - 1e-6)), 2 * height)
    if x1 <= max(x0, 0) or y1 <= max(y0, 0) or x0 >= width or y0 >= height:
        return None
    return x0, y0, x1, y1


def filter_margin(filters, t):
    """How far (device pixels) the result of ``filters`` under the CTM
    ``t`` reads its input away from the pixel it computes, summed over
    every primitive (a bound for any chain of them); None when a primitive
    can read anywhere in its region (``feTile``, ``feConvolveMatrix`` with
    ``edgeMode="wrap"``).

    A window of a render (:func:`raster.renderer.render_tree` with
    ``window``) draws a filtered group's layer over the window grown by
    this margin, so the window's pixels equal the whole render's.  Blurs
    count ``4 sigma + 4`` (the three box blurs of a Gaussian reach about
    ``2.8 sigma + 2``), offsets their length, morphology its radius,
    convolution its kernel, displacement half its scale, lighting one
    pixel.

    >>> from raster.tree.filter import Filter, GaussianBlur, Offset
    >>> f = Filter(region=None, primitives=[GaussianBlur(std_dev=(2.0, 1.0)), Offset(dx=3.0)])
    >>> filter_margin([f], Affine.scale(2.0))
    27.0
    """
    sx, sy = math.hypot(t.a, t.c), math.hypot(t.b, t.d)
    s = max(sx, sy)
    total = 0.0
    for f in filters:
        for p in f.primitives:
            if isinstance(p, (F.GaussianBlur, F.DropShadow)):
                sd = max(abs(p.std_dev[0]) * sx, abs(p.std_dev[1]) * sy)
                total += 4.0 * sd + 4.0 if sd > 0 else 0.0
            if isinstance(p, (F.Offset, F.DropShadow)):
                total += abs(p.dx) * sx + abs(p.dy) * sy + 1.0
            elif isinstance(p, F.Morphology):
                total += max(abs(p.radius[0]) * sx, abs(p.radius[1]) * sy) + 1.0
            elif isinstance(p, F.ConvolveMatrix):
                if p.edge_mode == F.EdgeMode.WRAP or p.kernel is None:
                    return None
                total += max(np.shape(p.kernel)) + 1.0
            elif isinstance(p, F.DisplacementMap):
                total += abs(p.scale) * s / 2.0 + 2.0
            elif isinstance(p, (F.DiffuseLighting, F.SpecularLighting)):
                total += 2.0
            elif isinstance(p, F.Tile):
                return None
    if not math.isfinite(total):
        return None
    return total


def _pixel_rect(box, w, h):
    x0, y0, x1, y1 = box
    if not all(math.isfinite(v) for v in box):
        return 0, 0, 0, 0
    px0 = min(max(int(math.floor(x0 + 1e-6)), 0), w)
    py0 = min(max(int(math.floor(y0 + 1e-6)), 0), h)
    px1 = min(max(int(math.ceil(x1 - 1e-6)), px0), w)
    py1 = min(max(int(math.ceil(y1 - 1e-6)), py0), h)
    return px0, py0, px1, py1


def apply_filters(filters, data, t, tolerance=None, draw=None):
    """Apply a list of filters to a rendered layer.

    Parameters
    ----------
    filters : sequence of raster.tree.filter.Filter
    data : (H, W, 4) float32 ndarray
        Premultiplied sRGB layer holding the element's rendering.
    t : raster.geometry.transform.Affine
        The element's user space to layer pixels.
    tolerance : float or None
        Passed to the blurs (None: the specification's box blurs, as
        resvg; see :func:`raster.pixels.effects.gaussian_blur`).
    draw : callable or None
        ``draw(node, m, w, h)`` renders a tree node with the CTM ``m`` into
        a new ``(h, w, 4)`` premultiplied array (for ``feImage``; without
        it feImage is transparent).

    Returns
    -------
    (H, W, 4) float32 ndarray
        The filtered layer (transparent outside the filter regions).
    """
    out = fx.check_image(data, 'layer')
    for f in filters:
        out = _apply_one(f, out, t, tolerance, draw)
    return out


class _Run:
    """What the primitives of one filter application share: the layer
    transform ``t`` (user space to region pixels), the scales ``sx``,
    ``sy`` of lengths, the blur tolerance, the region's pixel ``shape``
    and the ``draw`` callback."""
    __slots__ = ('t', 'sx', 'sy', 'tol', 'shape', 'draw', 'urect', 'spare')

    def __init__(self, t, sx, sy, tol, shape, draw):
        self.t, self.sx, self.sy, self.tol, self.shape, self.draw = t, sx, sy, tol, shape, draw
        self.urect = None           # the current primitive's subregion, user space
        self.spare = ()             # per input: whether its pixels may be overwritten


def _apply_one(f, data, t, tol, draw=None):
    r = _filter_image(f, data, t, tol, draw)
    if r is None:
        return np.zeros_like(data)
    img, (rx0, ry0, rx1, ry1) = r
    img = img.data
    h, w = data.shape[:2]
    if (rx0, ry0, rx1, ry1) == (0, 0, w, h):
        return img.copy() if np.may_share_memory(img, data) else img
    result = np.zeros_like(data)
    result[ry0:ry1, rx0:rx1] = img
    return result


def filter_layer(filters, layer, t, draw=None):
    """:func:`apply_filters` on a :class:`~raster.pixels.canvas.Canvas`
    layer, in place.

    The filters work on float32 pixels read from the layer once; the last
    filter's result is written back a strip of rows at a time, an image of
    one colour (a blurred shadow) from its alpha channel alone, so an
    8-bit layer is never held as two float32 copies.

    Parameters
    ----------
    filters : sequence of raster.tree.filter.Filter
    layer : raster.pixels.canvas.Canvas
    t, draw :
        As for :func:`apply_filters`.
    """
    w, h = layer.width, layer.height
    data = _layer_source(layer) if len(filters) == 1 else None
    if data is None:
        data = fx.check_image(layer.read(0, h, 0, w), 'layer')
    for f in filters[:-1]:
        data = _apply_one(f, data, t, None, draw)
    # handed over: the layer's copy is freed once the region is cut from it
    # and may be overwritten
    hand = [data]
    del data
    r = _filter_image(filters[-1], hand, t, None, draw)
    layer.data[...] = 0
    if r is None:
        return
    img, (rx0, ry0, rx1, ry1) = r
    step = max(1, _STRIP_PIXELS // max(1, rx1 - rx0))
    colour = None if not img.solid else np.append(img.colour, np.float32(1.0))
    for y in range(0, ry1 - ry0, step):
        if colour is not None:
            px = img.alpha[y:y + step, :, None] * colour
        else:
            px = img.data[y:y + step]
        layer.store(ry0 + y, ry0 + y + len(px), rx0, rx1, px)


#: Pixels of a filter result written into a layer at a time (filter_layer).
_STRIP_PIXELS = 1 << 16
#: Largest difference (levels) between an 8-bit layer's colour channels and
#: its brightest pixel's straight colour times its alpha for the layer to
#: count as painted in that one colour (the rounding of two levels).
_SOLID_LEVELS = 1.0


def _layer_source(layer):
    """An 8-bit layer painted in one colour (a shadow's shape) as a
    FilterImage of its alpha channel and that colour, found without a
    float32 copy of the layer; None for anything else."""
    d = layer.data
    if d.dtype != np.uint8:
        return None
    flat = d.reshape(-1, 4)
    i = int(np.argmax(flat[:, 3]))
    am = int(flat[i, 3])
    c = np.zeros(3, np.float32) if am == 0 else (flat[i, :3] / np.float32(am))
    step = max(1, (1 << 14) // max(1, layer.width))       # blocks that stay in cache
    for y in range(0, layer.height, step):
        blk = d[y:y + step].astype(np.float32)
        a = blk[..., 3]
        for k in range(3):
            if np.abs(blk[..., k] - a * c[k]).max() > _SOLID_LEVELS:
                return None
    return FilterImage(alpha=np.divide(d[..., 3], np.float32(255), dtype=np.float32),
                       colour=np.clip(c, 0.0, 1.0).astype(np.float32))


def _last_reads(prims):
    """For the primitives ``prims`` of a filter: ``(keys, last)``, the
    record each input reads (``'S'`` for the filter's sources, which share
    one buffer, or the index of the primitive that made it) per primitive,
    and the index of the last primitive reading each record (``len(prims)``
    for the final result)."""
    keys, last, names, prev = [], {}, {}, 'S'
    for i, p in enumerate(prims):
        ks = []
        for inp in p.inputs:
            if inp is F.Source.PREVIOUS:
                k = prev
            elif isinstance(inp, F.Result):
                k = names.get(inp.name)
            else:
                k = 'S'
            ks.append(k)
            last[k] = i
        keys.append(ks)
        prev = i
        if p.result:
            names[p.result] = i
    last[prev] = len(prims)
    return keys, last


def _buffers(img):
    """The arrays holding a FilterImage's pixels (a solid image's other
    channels, if made, are around its alpha channel)."""
    return [img.alpha] if img.solid else [img.data]


def _shares(img, arrays):
    """Whether ``img`` (a FilterImage) may share memory with any of ``arrays``."""
    return any(np.may_share_memory(a, b) for a in _buffers(img) for b in arrays)


def _filter_image(f, data, t, tol, draw=None):
    """One filter on ``data`` ((H, W, 4) float32, or a one-colour
    FilterImage of that size): ``(FilterImage in sRGB, (x0, y0, x1, y1)
    pixel region)`` (transparent outside the region), or None when the
    region is empty.

    ``data`` may be handed over as a one-item list: it is then taken out
    of the list, dropped once the region is cut from it, and its pixels
    may be overwritten; otherwise they are left unchanged.  Buffers that
    no later primitive reads (SourceGraphic and named results are followed
    to their last reader) are converted between colour spaces, blurred and
    clipped in place."""
    owned = isinstance(data, list)
    if owned:
        data = data.pop()
    solid = isinstance(data, FilterImage)
    h, w = (data.alpha if solid else data).shape[:2]
    rx0, ry0, rx1, ry1 = _pixel_rect(_device_box(f.region, t), w, h)
    if rx1 <= rx0 or ry1 <= ry0:
        return None
    rt = Affine.translate(-rx0, -ry0) @ t
    rw, rh = rx1 - rx0, ry1 - ry0
    # resvg's scale of a transform: the lengths of the matrix rows
    run = _Run(rt, math.hypot(t.a, t.c), math.hypot(t.b, t.d), fx.check_tolerance(tol),
               (rh, rw, 4), draw)
    # the work budget (raster.limits), before any primitive runs or the
    # source is copied
    limits.spend_work(filter_work(f, rw, rh, run.sx, run.sy, run.tol), 'a filter')
    if solid:
        src_alpha = np.ascontiguousarray(data.alpha[ry0:ry1, rx0:rx1])
        src_colour = data.colour
        src = src_alpha
    else:
        src = np.ascontiguousarray(data[ry0:ry1, rx0:rx1])
        src_alpha = src[..., 3]
        src_colour = None
    # the caller's pixels, unless handed over
    kept = [] if owned else _buffers(data) if solid else [data]
    del data
    full = (0, 0, rw, rh)
    sources = {}                      # SourceGraphic / SourceAlpha, made on first use

    def source(name):
        if name not in sources:
            if name is not F.Source.GRAPHIC:
                img = FilterImage(alpha=src_alpha, colour=np.zeros(3, np.float32))
            elif solid:
                img = FilterImage(alpha=src_alpha, colour=src_colour)
            else:
                img = FilterImage.of(src)
            sources[name] = (img, False, full)
        return sources[name]

    keys, last = _last_reads(f.primitives)
    records = {}                      # primitive index -> its record, while read later
    named = {}
    prev = None                       # (FilterImage, linear, rect)
    for n, p in enumerate(f.primitives):
        def get(i):
            if i is F.Source.PREVIOUS:
                return prev if prev is not None else source(F.Source.GRAPHIC)
            if isinstance(i, F.Result):
                return named[i.name]
            return source(i)

        ins = [get(i) for i in p.inputs]
        # buffers read after this primitive: not to be overwritten
        later = list(kept)
        if last.get('S', -1) > n:
            later.append(src)
        for k, rec in records.items():
            if last.get(k, -1) > n:
                later.extend(_buffers(rec[0]))
        spare = [not _shares(r[0], later) and not any(
            _shares(r[0], _buffers(o[0])) for j, o in enumerate(ins) if j != m)
            for m, r in enumerate(ins)]
        if f.region is None:
            sub = full
            run.urect = None
        else:
            urect = tuple(b if v is None else v for v, b in zip(p.subregion, f.region))
            sub = _pixel_rect(_device_box(urect, rt), rw, rh)
            run.urect = urect
        lin = p.linear
        imgs = [fx.convert_space(i[0], i[1], lin, ok) for i, ok in zip(ins, spare)]
        # a converted copy is the primitive's own
        run.spare = [ok or not _shares(im, _buffers(i[0])) for im, i, ok in zip(imgs, ins, spare)]
        img = _PRIMITIVES[type(p)](p, imgs, ins, sub, lin, run)
        del imgs
        out_lin = lin
        if img is None:
            img = FilterImage(alpha=np.zeros((rh, rw), np.float32),
                              colour=np.zeros(3, np.float32))
        elif isinstance(img, tuple):
            img, out_lin = img
        if isinstance(img, np.ndarray):
            img = FilterImage(img)
        # an feOffset result keeps its input's area for feTile (resvg)
        area = ins[0][2] if isinstance(p, F.Offset) and ins and all(
            ins[0][0] is not v[0] for v in sources.values()) else sub
        prev = (img.clip(sub, not _shares(img, later)), out_lin, area)
        del img, ins, later
        # forget what nothing reads any more (its memory can go)
        for k in [k for k in records if last.get(k, -1) <= n]:
            del records[k]
        if last.get('S', -1) <= n:
            sources.clear()
            src = src_alpha = None
        records[n] = prev
        if p.result:
            named[p.result] = prev
        for name in [name for name, rec in named.items() if
                     not any(rec is r for r in records.values())]:
            del named[name]
    img, img_lin = prev[0], prev[1]
    del prev, records, named
    return fx.convert_space(img, img_lin, False, not _shares(img, kept)), (rx0, ry0, rx1, ry1)


# -- the cost model ------------------------------------------------------------------
# Work per region pixel of each primitive, in array passes over an RGBA
# float32 pixel (measured: numpy on one core), the conversion between
# colour spaces included.
_PASSES = {F.Offset: 24, F.Flood: 4, F.Merge: 30, F.Composite: 30, F.Blend: 40,
           F.ColorMatrix: 60, F.ComponentTransfer: 60, F.Tile: 24, F.Image: 24,
           F.DisplacementMap: 100, F.DiffuseLighting: 200, F.SpecularLighting: 200}
# one octave of feTurbulence (four channels of Perlin noise)
_OCTAVE_PASSES = 240
# one tap of feConvolveMatrix
_TAP_PASSES = 5
# what making a filter layer costs whatever its size (a few milliseconds)
_FILTER_FIXED = 1 << 21


def filter_work(f, width, height, sx=1.0, sy=1.0, tolerance=None):
    """Estimated pixel work of one filter on a ``width x height`` region:
    the sum over its primitives of the region's pixels times the array
    passes each costs -- by its parameters: blurs by their box or kernel
    sizes (:func:`raster.pixels.effects.blur_cost`), feMorphology by its
    window, feConvolveMatrix by its taps, feTurbulence by its octaves (at
    most :data:`raster.pixels.effects.MAX_OCTAVES`), the others a few
    passes.  ``sx``, ``sy`` scale user lengths to pixels; ``tolerance`` is
    the blur tolerance.  Cheap: no pixel is touched.

    >>> filter_work(F.Filter(region=None, primitives=[F.Flood()]), 10, 10) - 2 ** 21
    400.0
    """
    px = float(width) * float(height)
    total = float(_FILTER_FIXED)
    for p in f.primitives:
        k = type(p)
        if k is F.GaussianBlur or k is F.DropShadow:
            s_x, s_y = p.std_dev[0] * sx, p.std_dev[1] * sy
            c = 24.0
            if s_x > 0 or s_y > 0:
                c += 1.5 * fx.blur_cost(*fx.blur_plans(max(s_x, 0.0), max(s_y, 0.0), tolerance))
            if k is F.DropShadow:
                c += 30.0
        elif k is F.Morphology:
            r_x = min(max(p.radius[0] * sx, 0.0), width)
            r_y = min(max(p.radius[1] * sy, 0.0), height)
            c = 24.0 + 2.0 * (r_x + r_y)
        elif k is F.ConvolveMatrix:
            c = 24.0 + _TAP_PASSES * float(np.count_nonzero(p.kernel))
        elif k is F.Turbulence:
            c = 24.0 + _OCTAVE_PASSES * min(max(int(p.num_octaves), 0), fx.MAX_OCTAVES)
        else:
            c = _PASSES.get(k, 24)
        total += px * c
    return total


# -- the primitives ------------------------------------------------------------------
# Each takes (primitive, inputs as FilterImages in its colour space, the
# inputs' (image, linear, area) records, its pixel subregion, its space,
# the run) and returns an image (array or FilterImage) in its space,
# ``(image, linear)`` for another space, or None (transparent).

def _gaussian_blur(p, imgs, ins, sub, lin, run):
    s_x, s_y = p.std_dev[0] * run.sx, p.std_dev[1] * run.sy
    if s_x < 0 or s_y < 0 or (s_x == 0 and s_y == 0):
        return imgs[0]                      # disabled: the input (resvg)
    return fx.blur_image(imgs[0], *fx.blur_plans(s_x, s_y, run.tol), in_place=run.spare[0])


def _offset(p, imgs, ins, sub, lin, run):
    dx, dy = p.dx * run.sx, p.dy * run.sy
    fx.check_finite(dx, dy)
    dx, dy = int(dx), int(dy)
    if imgs[0].solid:
        return FilterImage(alpha=fx.shift(imgs[0].alpha, dx, dy), colour=imgs[0].colour)
    return fx.shift(imgs[0].data, dx, dy)


def _light(light):
    """A tree light source as the ``(kind, params)`` of
    :func:`raster.pixels.effects.lighting`."""
    if isinstance(light, F.DistantLight):
        return ('distant', (light.azimuth, light.elevation))
    if isinstance(light, F.PointLight):
        return ('point', (light.x, light.y, light.z))
    return ('spot', ((light.x, light.y, light.z), light.points_at, light.specular_exponent,
                     light.limiting_cone_angle))


def _lighting(p, imgs, ins, sub, lin, run):
    col = np.asarray(p.color, np.float32)
    if lin:
        col = fx.srgb_to_linear(col)
    if isinstance(p, F.SpecularLighting):
        k, exponent, specular = p.specular_constant, p.specular_exponent, True
    else:
        k, exponent, specular = p.diffuse_constant, 1.0, False
    return fx.lighting(imgs[0].alpha_channel, _light(p.light), col, p.surface_scale, k, exponent,
                       specular, run.t)


def _displacement_map(p, imgs, ins, sub, lin, run):
    return fx.displace(imgs[0].data, imgs[1].data, p.scale * (run.sx + run.sy) / 2.0,
                       p.x_channel, p.y_channel)


def _turbulence(p, imgs, ins, sub, lin, run):
    t = run.t
    if t.b == 0 and t.c == 0:
        m = t                               # scale and translation: exact
    elif run.sx > 0 and run.sy > 0:
        # rotated or skewed: the noise runs along the device axes, scaled
        # by the lengths of the CTM's rows, like the other primitives'
        # lengths (resvg's approximation); the region is axis-aligned too
        m = Affine(run.sx, 0.0, 0.0, run.sy, t.e, t.f)
    else:
        return None
    try:
        inv = m.inverse()
    except RasterError:
        return None
    shape = run.shape
    jj, ii = np.meshgrid(np.arange(shape[1], dtype=np.float64),
                         np.arange(shape[0], dtype=np.float64))
    pts = inv.apply(np.stack([jj, ii], -1))
    tile = None
    if p.stitch and run.urect is not None:
        tile = run.urect
    col = fx.turbulence(pts[..., 0], pts[..., 1], p.base_frequency, p.num_octaves, p.seed,
                        p.fractal, tile)
    return fx.premultiply(col[..., :3], col[..., 3:4])


def _convolve_matrix(p, imgs, ins, sub, lin, run):
    return fx.convolve(imgs[0].data, p.kernel, p.divisor, p.bias, p.target, p.edge_mode.value,
                       p.preserve_alpha)


def _image(p, imgs, ins, sub, lin, run):
    if p.root is None or run.draw is None:
        return None
    img = run.draw(p.root, run.t @ Affine.translate(*p.shift), run.shape[1], run.shape[0])
    return fx.check_image(img, 'feImage content'), False


def _flood(p, imgs, ins, sub, lin, run):
    c = p.color
    return FilterImage(alpha=np.full(run.shape[:2], c[3], np.float32),
                       colour=np.asarray(c[:3], np.float32)), False


def _merge(p, imgs, ins, sub, lin, run):
    if not imgs:
        return None
    out = np.zeros_like(imgs[0].data)
    for im in imgs:
        out = im.data + out * (1 - im.data[..., 3:4])
    return out


def _composite(p, imgs, ins, sub, lin, run):
    return compositing.composite(imgs[0].data, imgs[1].data, p.operator.value, p.k)


def _blend(p, imgs, ins, sub, lin, run):
    return compositing.blend(imgs[0].data, imgs[1].data, p.mode.value)


def _color_matrix(p, imgs, ins, sub, lin, run):
    return fx.color_matrix(imgs[0].data, p.matrix)


def _transfer(fn):
    """A tree transfer function as the ``(kind, params)`` of
    :func:`raster.pixels.effects.component_transfer`."""
    if isinstance(fn, F.TableTransfer):
        return ('table', fn.values)
    if isinstance(fn, F.DiscreteTransfer):
        return ('discrete', fn.values)
    if isinstance(fn, F.LinearTransfer):
        return ('linear', (fn.slope, fn.intercept))
    return ('gamma', (fn.amplitude, fn.exponent, fn.offset))


def _component_transfer(p, imgs, ins, sub, lin, run):
    return fx.component_transfer(imgs[0].data, {ch: _transfer(fn) for ch, fn in p.funcs.items()})


def _morphology(p, imgs, ins, sub, lin, run):
    r_x, r_y = p.radius[0] * run.sx, p.radius[1] * run.sy
    if r_x < 0 or r_y < 0 or (r_x == 0 and r_y == 0):
        return imgs[0]                      # disabled: the input (resvg)
    return fx.morphology(imgs[0].data, r_x, r_y, p.operator.value)


def _tile(p, imgs, ins, sub, lin, run):
    return fx.tile(imgs[0].data, ins[0][2], sub)


def _drop_shadow(p, imgs, ins, sub, lin, run):
    src = imgs[0].data
    s_x, s_y = p.std_dev[0] * run.sx, p.std_dev[1] * run.sy
    a = src[..., 3]
    if s_x > 0 or s_y > 0:
        a = fx.blur_array(a, *fx.blur_plans(max(s_x, 0.0), max(s_y, 0.0), run.tol))
    dx, dy = p.dx * run.sx, p.dy * run.sy
    fx.check_finite(dx, dy)
    a = fx.shift(a, int(dx), int(dy))
    c = p.color
    col = np.array(c[:3], np.float32)
    if lin:
        col = fx.srgb_to_linear(col)
    shadow = fx.solid_image(a * np.float32(c[3]), col)
    return compositing.composite(src, shadow, 'over')


_PRIMITIVES = {
    F.GaussianBlur: _gaussian_blur, F.Offset: _offset, F.DiffuseLighting: _lighting,
    F.SpecularLighting: _lighting, F.DisplacementMap: _displacement_map,
    F.Turbulence: _turbulence, F.ConvolveMatrix: _convolve_matrix, F.Image: _image,
    F.Flood: _flood, F.Merge: _merge, F.Composite: _composite, F.Blend: _blend,
    F.ColorMatrix: _color_matrix, F.ComponentTransfer: _component_transfer,
    F.Morphology: _morphology, F.Tile: _tile, F.DropShadow: _drop_shadow,
}
