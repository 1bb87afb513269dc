"""A premultiplied RGBA canvas: fills, source-over compositing, PNG.

Pixel (row ``i``, column ``j``) of a canvas covers ``[j, j+1] x [i, i+1]`` in
device space (x right, y down).  :attr:`Canvas.data` is ``(H, W, 4)``
holding *premultiplied* red, green, blue and alpha: float32 in [0, 1] (the
default), or uint8 in 0..255 for an *8-bit canvas* (``dtype=np.uint8``, a
quarter of the memory, as resvg's pixmaps: every fill and composite is
computed in float32 and rounded to the nearest of the 256 levels).  Colours
passed in are *straight* (not premultiplied) RGB or RGBA in [0, 1].

>>> import numpy as np
>>> from raster.pixels.scan import Mask
>>> c = Canvas(2, 1, background=(1, 1, 1))
>>> c.fill(Mask(np.array([[1.0, 0.5]], np.float32), 0, 0), (0, 0, 1))
>>> c.to_rgba8().tolist()
[[[0, 0, 255, 255], [128, 128, 255, 255]]]
"""

import math

import numpy as np

from ..errors import CanvasError
from .png import DEFAULT_LEVEL, write_png
from .scan import check_canvas_size

__all__ = ['Canvas', 'DEFAULT_COMPRESS_LEVEL', 'MANY_MASK_PIXELS', 'MANY_GROUP_PIXELS']

#: zlib level used by :meth:`Canvas.save_png` (:func:`raster.pixels.png.encode_png`:
#: levels 1-3 use zlib's run-length strategy, 4-9 the default strategy).
DEFAULT_COMPRESS_LEVEL = DEFAULT_LEVEL

# Masks of at most _SPARSE_MAX pixels with at most 1 / _SPARSE_SHARE of them
# covered are filled pixel by pixel (gather, update, scatter).
_SPARSE_MAX = 1 << 24
_SPARSE_SHARE = 8

# Masks of at most this many pixels are filled in one pass over the window
# (about 8 array operations, where finding the covered and full pixels
# takes about 25: below 4096 pixels the calls cost more than the pixels;
# maps and charts at 2000 px rendered 3-9 % faster than with 1024, pixels
# the same).
_SMALL = 4096

# Pixels per block of rows in fill / composite (bounds temporaries).
_BLOCK = 1 << 14

# Pixels per block when an 8-bit canvas is demultiplied for output (its
# translucent pixels' float32 copies and indices: about 1.5 MB at most).
_DEMULTIPLY_BLOCK = 1 << 16

# Masks of more pixels are filled in windows of rows of about this many
# pixels: the tests of the coverage (covered, full, their indices) stay
# small beside a canvas-sized mask.
_FILL_ROWS = 1 << 18

#: Masks of at most this many pixels are composited together by
#: :meth:`Canvas.fill_many` (larger ones one by one: gathering a pixel
#: costs more than blending it in a window, so only masks whose fill costs
#: mostly its fixed overhead gain; maps at 2000 px composited 10-30 %
#: faster with 1024-4096 than with 65536 or 256).
MANY_MASK_PIXELS = 1 << 12

#: Mask pixels per group of :meth:`Canvas.fill_many` (bounds the gathered
#: pixels: about 40 bytes each).
MANY_GROUP_PIXELS = 1 << 16

# Pixel storage types of a canvas.
_DTYPES = (np.dtype(np.float32), np.dtype(np.uint8))
_U8 = np.dtype(np.uint8)
_S255 = np.float32(255.0)
_HALF = np.float32(0.5)


def _color(color, opacity):
    """Straight RGB/RGBA + opacity -> (r, g, b) float64, alpha*opacity."""
    try:
        c = list(map(float, color))
    except (TypeError, ValueError):
        raise CanvasError('colour must be 3 or 4 numbers, got %r' % (color,)) from None
    if len(c) not in (3, 4):
        raise CanvasError('colour must have 3 or 4 components, got %d' % len(c))
    try:
        op = float(opacity)
    except (TypeError, ValueError):
        raise CanvasError('opacity must be a number, got %r' % (opacity,)) from None
    # one test for the common case (a sum of finite numbers may still
    # overflow, hence the exact test when it is not finite)
    if not math.isfinite(sum(c) + op) and not (
            all(map(math.isfinite, c)) and math.isfinite(op)):
        raise CanvasError('colour and opacity must be finite')
    r, g, b = [min(max(v, 0.0), 1.0) for v in c[:3]]
    a = (min(max(c[3], 0.0), 1.0) if len(c) == 4 else 1.0) * min(max(op, 0.0), 1.0)
    return r, g, b, a


# Recent paints of fill (see _paint): {(color, opacity): (alpha, vec)}.
_PAINTS = {}
_PAINTS_MAX = 64


def _paint(color, opacity):
    """Straight RGB/RGBA + opacity -> (alpha * opacity as float32,
    (r, g, b, 1) as a read-only (4,) float32 array), validated by
    :func:`_color`; remembered for tuples (renderers repeat few paints)."""
    key = (color, opacity) if type(color) is tuple else None
    if key is not None:
        try:
            hit = _PAINTS.get(key)
        except TypeError:               # unhashable parts
            key = hit = None
        if hit is not None:
            return hit
    r, g, b, a = _color(color, opacity)
    vec = np.array([r, g, b, 1.0], np.float32)
    vec.flags.writeable = False
    hit = (np.float32(a), vec)
    if key is not None:
        if len(_PAINTS) >= _PAINTS_MAX:
            _PAINTS.clear()
        _PAINTS[key] = hit
    return hit


def _tile4(vec, n):
    """``vec`` ((4,) float32) repeated ``n`` times: (4 n,) float32 (a
    broadcast assignment, cheaper than ``np.tile`` for short rows)."""
    out = np.empty((n, 4), np.float32)
    out[...] = vec
    return out.reshape(4 * n)


# Recent colours repeated along a row (see _row_of): {vec bytes: (4 n,)
# float32, read-only}; documents alternate between few colours.
_ROWS = {}
_ROWS_MAX = 8


def _row_of(vec, n):
    """``vec`` ((4,) float32 RGBA, alpha 1) repeated at least ``n`` times,
    as a read-only (4 m,) float32 array (m >= n) shared between calls."""
    key = vec.tobytes()
    row = _ROWS.get(key)
    if row is None or len(row) < 4 * n:
        if len(_ROWS) >= _ROWS_MAX:
            _ROWS.clear()
        row = _tile4(vec, max(n, 256))
        row.flags.writeable = False
        _ROWS[key] = row
    return row


def _spread4(k, lanes):
    """Each value of ``k`` ((r, c) float32) repeated 4 times: (r, 4 c) float32.

    Bit copies, faster than ``np.repeat``: each value's 32 bits are
    doubled into a uint64 (``u * (2**32 + 1)``), and that uint64 is written
    twice into ``lanes`` (scratch, at least (r c, 2) uint64).
    """
    r, c = k.shape
    u = k.view(np.uint32).astype(np.uint64)
    u *= np.uint64(0x100000001)
    out = lanes[:r * c]
    u = u.reshape(-1)
    out[:, 0] = u
    out[:, 1] = u
    return out.view(np.float32).reshape(r, 4 * c)


def _over8(reg, row, k4, f=None, t=None):
    """``reg += k4 (row - reg)`` on uint8 ``reg`` (levels 0..255), in float32,
    rounded half up: ``row`` and ``k4`` are float32 broadcasting to
    ``reg``'s shape (``row`` in levels); ``f``, ``t``: optional float32
    scratch of that shape."""
    if f is None:
        f = reg.astype(np.float32)
    else:
        np.copyto(f, reg)
    t = np.subtract(row, f, out=t)
    t *= k4
    t += f
    t += _HALF
    np.copyto(reg, t, casting='unsafe')      # truncation of values >= 0: rounding


def _quantize(dst, values):
    """Store float32 premultiplied ``values`` in [0, 1] into the uint8
    array ``dst`` (of the same shape), rounded to the nearest level and
    clamped to 0..255."""
    v = np.multiply(values, _S255, dtype=np.float32)
    v += _HALF
    np.clip(v, 0.0, 255.0, out=v)
    np.copyto(dst, v, casting='unsafe')


def _demultiply(flat):
    """Divide the colour of (n, 4) float32 pixels in [0, 1] by their alpha,
    in place, where 0 < alpha < 1 (other pixels are left as they are)."""
    one, zero = np.float32(1.0), np.float32(0.0)
    a = flat[:, 3]
    part = a < one
    part &= a > zero
    idx = np.flatnonzero(part)
    with np.errstate(over='ignore'):     # tiny alphas: zeroed by the caller
        if 4 * len(idx) > len(a):
            # mostly translucent: divide everything (alpha 0 and 1 leave
            # the colour unchanged)
            safe = np.where(a > zero, a, one)
            for ch in range(3):
                np.divide(flat[:, ch], safe, out=flat[:, ch])
        elif len(idx):
            sub = flat[idx]
            sub[:, :3] /= sub[:, 3:]
            flat[idx] = sub


def _depth_order(pix):
    """Where each pixel of ``pix`` ((n,) int64 canvas pixels, listed in
    drawing order) is composited: None when every pixel occurs once, else
    ``(perm, ends)``: ``perm`` ((n,) int64) lists the entries by *depth*
    (the k-th occurrence of a pixel has depth k), in drawing order within
    a depth, and ``ends`` (list of int) where the entries of each depth
    end in it.  The entries of one depth are
    distinct pixels; compositing depth after depth keeps every pixel's
    order."""
    n = len(pix)
    if n < 2:
        return None
    # (the entries are runs of increasing pixels, one a mask: a stable
    # merge sort finds and merges the runs)
    order = np.argsort(pix, kind='stable')
    sp = pix[order]
    new = np.empty(n, bool)
    new[0] = True
    np.not_equal(sp[1:], sp[:-1], out=new[1:])
    del sp
    if new.all():
        return None
    # depth = position in the sorted order - that of the pixel's first entry
    pos = np.arange(n, dtype=np.int64)
    first = np.where(new, pos, 0)
    del new
    np.maximum.accumulate(first, out=first)
    pos -= first
    del first
    top_depth = int(pos.max())
    # (a stable sort of 8- or 16-bit integers is a radix sort)
    if top_depth < 256:
        by = np.argsort(pos.astype(np.uint8), kind='stable')
    elif top_depth < 65536:
        by = np.argsort(pos.astype(np.uint16), kind='stable')
    else:
        by = np.argsort(pos, kind='stable')
    ends = np.cumsum(np.bincount(pos, minlength=top_depth + 1)).tolist()
    return order[by], ends


class Canvas:
    """Premultiplied RGBA pixel buffer, float32 or 8-bit.

    Parameters
    ----------
    width, height : int
        Size in pixels (whole numbers; integral floats accepted).
    background : sequence of 3 or 4 float, optional
        Straight RGB(A) colour in [0, 1] to start from; transparent black
        when omitted.
    dtype : numpy.float32 or numpy.uint8
        Storage: float32 (exact to float precision, 16 bytes a pixel) or
        uint8 (4 bytes a pixel; each fill, composite and store rounds to
        1/255).

    Attributes
    ----------
    data : (height, width, 4) float32 or uint8 ndarray
        Premultiplied RGBA, in [0, 1] (float32) or in 0..255 (uint8).

    Raises
    ------
    CanvasError
        Size not a positive whole number, a side above
        ``max_side`` or more than ``max_pixels`` pixels
        (:mod:`raster.limits`); malformed background; a dtype other than
        float32 and uint8.

    >>> Canvas(3, 2).data.shape, Canvas(3, 2, dtype=np.uint8).data.dtype
    ((2, 3, 4), dtype('uint8'))
    >>> Canvas(1, 1, (1, 0.5, 0), dtype=np.uint8).data.tolist()
    [[[255, 128, 0, 255]]]
    """

    def __init__(self, width, height, background=None, dtype=np.float32):
        self.width, self.height = check_canvas_size(width, height)
        try:
            dt = np.dtype(dtype)
        except TypeError:
            dt = None
        if dt not in _DTYPES:
            raise CanvasError('canvas dtype must be float32 or uint8, got %r' % (dtype,))
        self.data = np.zeros((self.height, self.width, 4), dt)
        if background is not None:
            r, g, b, a = _color(background, 1.0)
            px = np.array([r * a, g * a, b * a, a], np.float32)
            if dt == _U8:
                _quantize(self.data[:1, :1], px.reshape(1, 1, 4))
                px = self.data[0, 0].copy()
            self.data[...] = px

    @property
    def dtype(self):
        """The storage type, ``numpy.dtype('float32')`` or ``('uint8')``."""
        return self.data.dtype

    @property
    def nbytes(self):
        """Bytes held by the pixels."""
        return self.data.nbytes

    @property
    def shape(self):
        """(height, width)."""
        return (self.height, self.width)

    def _window(self, x0, y0, h, w):
        """Intersection of a (h, w) window at (x0, y0) with the canvas:
        canvas slices and source slices, or None."""
        cx0, cy0 = max(x0, 0), max(y0, 0)
        cx1, cy1 = min(x0 + w, self.width), min(y0 + h, self.height)
        if cx1 <= cx0 or cy1 <= cy0:
            return None
        dst = (slice(cy0, cy1), slice(cx0, cx1))
        src = (slice(cy0 - y0, cy1 - y0), slice(cx0 - x0, cx1 - x0))
        return dst, src

    def fill(self, mask, color, opacity=1.0):
        """Composite ``color`` through a coverage mask, source-over.

        Parameters
        ----------
        mask : raster.pixels.scan.Mask or None
            Coverage (h, w) float32 at (x0, y0); the part outside the
            canvas is ignored.  None does nothing.
        color : sequence of 3 or 4 float
            Straight RGB(A) in [0, 1] (values outside are clamped).
        opacity : float
            Extra alpha factor in [0, 1].

        Each pixel becomes ``src + dst * (1 - src_alpha)`` with
        ``src = coverage * opacity * alpha * (r, g, b, 1)``.

        >>> from raster.pixels.scan import Mask
        >>> c = Canvas(1, 1)
        >>> c.fill(Mask(np.ones((1, 1), np.float32), 0, 0), (1, 0, 0, 0.5))
        >>> c.data.tolist()
        [[[0.5, 0.0, 0.0, 0.5]]]
        """
        if mask is None:
            return
        alpha, vec = _paint(color, opacity)
        if alpha == 0.0:
            return
        eight = self.data.dtype == _U8
        if eight:
            vec = vec * _S255           # the colour in levels
        cov = np.asarray(mask.data, np.float32)
        if cov.ndim != 2:
            raise CanvasError('mask data must be 2-D, got shape %r' % (cov.shape,))
        win = self._window(int(mask.x0), int(mask.y0), cov.shape[0], cov.shape[1])
        if win is None:
            return
        dst_sl, src_sl = win
        k = cov[src_sl]
        step = max(1, _FILL_ROWS // k.shape[1])
        if k.shape[0] <= step:
            self._fill_window(k, dst_sl, alpha, vec, eight)
            return
        ys, xs = dst_sl
        for r0 in range(0, k.shape[0], step):
            r1 = min(r0 + step, k.shape[0])
            self._fill_window(k[r0:r1], (slice(ys.start + r0, ys.start + r1), xs), alpha, vec,
                              eight)

    def fill_many(self, fills):
        """Composite a sequence of solid fills in order: the pixels of
        ``for mask, color, opacity in fills: self.fill(mask, color,
        opacity)``, bit for bit, with the small masks composited together.

        Parameters
        ----------
        fills : iterable of (raster.pixels.scan.Mask or None, color, opacity)
            As the arguments of :meth:`fill`, in drawing order.

        The masks of at most :data:`MANY_MASK_PIXELS` pixels (inside the
        canvas) are gathered in groups of at most :data:`MANY_GROUP_PIXELS`
        mask pixels: the covered pixels of a group are composited in one
        vectorized pass per *depth* (the k-th mask of the group covering a
        pixel is composited in pass k, so overlapping masks keep their
        order), each with the arithmetic :meth:`fill` would use for its
        mask (the blend of :meth:`fill`'s small, sparse and dense paths, or
        the colour copied where an opaque paint fully covers a pixel of a
        mask that :meth:`fill` treats as dense).  Larger masks, and every
        mask on canvas data that is not C-contiguous, are filled one by
        one.  An invalid colour or mask raises as :meth:`fill` does, after
        the fills before it are composited.

        >>> from raster.pixels.scan import Mask
        >>> a, b = Canvas(2, 1), Canvas(2, 1)
        >>> fills = [(Mask(np.array([[1.0, 0.5]], np.float32), 0, 0), (1, 0, 0), 0.5),
        ...          (Mask(np.array([[0.25]], np.float32), 1, 0), (0, 0, 1), 1.0)]
        >>> a.fill_many(fills)
        >>> for f in fills:
        ...     b.fill(*f)
        >>> bool(np.array_equal(a.data, b.data))
        True
        """
        group, pixels = [], 0
        batch = self.data.flags.c_contiguous
        W, H = self.width, self.height
        f32 = np.dtype(np.float32)
        try:
            for mask, color, opacity in fills:
                if mask is None:
                    continue
                alpha, vec = _paint(color, opacity)
                if alpha == 0.0:
                    continue
                cov = mask.data
                if type(cov) is not np.ndarray or cov.dtype != f32:
                    cov = np.asarray(cov, np.float32)
                if not batch or cov.ndim != 2 or cov.size > MANY_MASK_PIXELS or 0 in cov.strides:
                    done, group, pixels = group, [], 0
                    self._fill_group(done)
                    self.fill(mask, color, opacity)
                    continue
                x0, y0 = int(mask.x0), int(mask.y0)
                h, w = cov.shape
                if x0 < 0 or y0 < 0 or x0 + w > W or y0 + h > H:
                    win = self._window(x0, y0, h, w)
                    if win is None:
                        continue
                    dst_sl, src_sl = win
                    cov = cov[src_sl]
                    y0, x0 = dst_sl[0].start, dst_sl[1].start
                    h, w = cov.shape
                if pixels + h * w > MANY_GROUP_PIXELS:
                    done, group, pixels = group, [], 0
                    self._fill_group(done)
                group.append((cov, y0, x0, alpha, vec))
                pixels += h * w
        finally:
            # (the fills before an error are composited, as one by one)
            done, group = group, []
            self._fill_group(done)

    def _fill_group(self, group):
        """:meth:`fill_many` of a group of small masks: ``group`` is a list
        of ``(k, y0, x0, alpha, vec)``: the mask window ``k`` ((h, w)
        float32, inside the canvas) at canvas row ``y0``, column ``x0``,
        the paint's opacity ``alpha`` (float32) and colour ``vec`` ((4,)
        float32, alpha 1, not in levels)."""
        if not group:
            return
        eight = self.data.dtype == _U8
        if len(group) == 1:
            k, y0, x0, alpha, vec = group[0]
            self._fill_window(k, (slice(y0, y0 + k.shape[0]), slice(x0, x0 + k.shape[1])), alpha,
                              vec * _S255 if eight else vec, eight)
            return
        W = self.width
        flat = np.concatenate([g[0].reshape(-1) for g in group])
        nz = np.flatnonzero(flat)
        if len(nz) == 0:
            return
        kv = flat[nz]
        del flat
        # per mask: its height, width and first canvas pixel; per mask row:
        # its mask and what takes a pixel of it from the concatenated masks
        # to the canvas
        geo = np.array([(g[0].shape[0], g[0].shape[1], g[1] * W + g[2]) for g in group], np.int64)
        hs, ws = geo[:, 0], geo[:, 1]
        sizes = hs * ws
        F = len(group)
        row_mask = np.repeat(np.arange(F, dtype=np.int64), hs)
        row_first = np.cumsum(hs) - hs
        r = np.arange(len(row_mask), dtype=np.int64) - row_first[row_mask]
        shift = (geo[:, 2] - (np.cumsum(sizes) - sizes))[row_mask] + r * (W - ws[row_mask])
        row_of = np.repeat(np.arange(len(row_mask), dtype=np.int32), ws[row_mask])
        row = row_of[nz]
        del row_of, r
        pix = nz + shift[row]
        del nz
        fid = row_mask[row]
        del row
        alphas = np.array([g[3] for g in group], np.float32)
        vecs = np.stack([g[4] for g in group])
        if eight:
            vecs = vecs * _S255             # the colours in levels (as fill)
        # opaque paint on a mask that fill treats as dense (_fill_opaque):
        # the colour is copied where the coverage is 1
        nnz = np.bincount(fid, minlength=F)
        copy = (alphas == np.float32(1.0)) & (sizes > _SMALL) & (nnz * _SPARSE_SHARE > sizes)
        k4 = kv * alphas[fid]
        full = (copy[fid] & (kv == np.float32(1.0))) if copy.any() else None
        del kv
        plan = _depth_order(pix)
        if plan is None:
            self._blend_pixels(pix, fid, k4, full, vecs, eight)
            return
        perm, ends = plan
        pix, fid, k4 = pix[perm], fid[perm], k4[perm]
        if full is not None:
            full = full[perm]
        del perm
        a = 0
        for b in ends:
            self._blend_pixels(pix[a:b], fid[a:b], k4[a:b], None if full is None else full[a:b],
                               vecs, eight)
            a = b

    def _blend_pixels(self, pix, fid, k4, full, vecs, eight):
        """Blend distinct canvas pixels ``pix`` ((n,) int64 flat indices)
        towards the colours ``vecs[fid]`` ((F, 4) float32, in levels on an
        8-bit canvas) by ``k4`` ((n,) float32: coverage times opacity) with
        :meth:`fill`'s arithmetic; where ``full`` ((n,) bool or None) is
        set the colour is copied (an opaque paint's full coverage)."""
        rows = np.take(vecs, fid, axis=0)
        k = k4[:, None]
        if full is not None:
            fsel = np.flatnonzero(full)
            if not len(fsel):
                full = None
        if eight:
            px = self.data.view(np.uint32).reshape(-1)
            reg = px[pix]
            r8 = reg.view(np.uint8).reshape(-1, 4)
            f = r8.astype(np.float32)
            t = np.subtract(rows, f, out=rows)
            t *= k
            t += f
            t += _HALF
            np.copyto(r8, t, casting='unsafe')      # truncation of values >= 0: rounding
            if full is not None:
                levels = np.floor(vecs + _HALF).astype(np.uint8).view(np.uint32).reshape(-1)
                reg[fsel] = levels[fid[fsel]]
            px[pix] = reg
            return
        flat = self.data.reshape(-1, 4)
        reg = np.take(flat, pix, axis=0)
        t = np.subtract(rows, reg, out=rows)
        t *= k
        reg += t
        if full is not None:
            reg[fsel] = np.take(vecs, fid[fsel], axis=0)
        flat[pix] = reg

    def _fill_window(self, k, dst_sl, alpha, vec, eight):
        """:meth:`fill` through the mask window ``k`` ((h, w) float32) onto
        ``self.data[dst_sl]``: paint ``vec`` ((4,) float32, in levels on an
        8-bit canvas) of opacity ``alpha``."""
        if k.size <= _SMALL or not self.data.flags.c_contiguous:
            # small masks: a few whole-window operations cost less than
            # finding the covered pixels; rows of interleaved RGBA with the
            # coverage repeated to 4 lanes keep numpy's loops long (a
            # (h, w, 1) x (h, w, 4) broadcast runs w h loops of 4).  Canvas
            # data replaced by a non-contiguous array has no such rows:
            # plain broadcasting over the window
            h, w = k.shape
            if self.data.flags.c_contiguous:
                reg = self.data[dst_sl].reshape(h, 4 * w, copy=False)
                k4 = k.repeat(4, axis=1)
                row = _row_of(vec, w)[:4 * w]
            else:
                reg, k4, row = self.data[dst_sl], k[..., None].copy(), vec
            if alpha != 1.0:
                k4 *= alpha
            if eight:
                _over8(reg, row, k4)
                return
            t = row - reg
            t *= k4
            reg += t
            return
        # (counting, finding and testing the nonzero pixels of a bool array
        # is several times faster than of the float32 coverage)
        covered = k != 0.0
        if k.size <= _SPARSE_MAX:
            nnz = np.count_nonzero(covered)
            if nnz == 0:
                return
            if nnz * _SPARSE_SHARE <= k.size:
                self._fill_pixels(np.flatnonzero(covered), k, dst_sl, alpha, vec)
                return
            if alpha == 1.0:
                self._fill_opaque(k, covered, nnz, dst_sl, vec)
                return
        # crop to the rows holding coverage (masks are often mostly empty)
        rows = np.flatnonzero(covered.any(axis=1))
        if len(rows) == 0:
            return
        r0, r1 = int(rows[0]), int(rows[-1]) + 1
        k = k[r0:r1]
        covered = covered[r0:r1]
        region = self.data[dst_sl][r0:r1]
        # region += k * (vec - region) on contiguous rows of interleaved
        # RGBA: the coverage is spread to 4 lanes per pixel (see _spread4)
        # so every operation runs long SIMD loops, in blocks of rows that
        # stay in cache; each block is cropped to its columns with coverage
        w = k.shape[1]
        step = max(1, _BLOCK // max(1, w))
        nb = min(step, k.shape[0]) * w
        tmp = np.empty(4 * nb, np.float32)
        ftmp = np.empty(4 * nb, np.float32) if eight else None
        lanes = np.empty((nb, 2), np.uint64)
        vt = _row_of(vec, nb)
        for i0 in range(0, k.shape[0], step):
            kk = k[i0:i0 + step]
            cols = np.flatnonzero(covered[i0:i0 + step].any(axis=0))
            if len(cols) == 0:
                continue
            c0, c1 = int(cols[0]), int(cols[-1]) + 1
            kk = kk[:, c0:c1]
            if alpha != 1.0:
                kk = kk * alpha
            rows, n4 = kk.shape[0], 4 * (c1 - c0)
            k4 = _spread4(kk, lanes)
            reg = region[i0:i0 + step, c0:c1].reshape(rows, n4, copy=False)
            t = tmp[:rows * n4].reshape(rows, n4)
            if eight:
                _over8(reg, vt[:rows * n4].reshape(rows, n4), k4,
                       ftmp[:rows * n4].reshape(rows, n4), t)
                continue
            np.subtract(vt[:rows * n4].reshape(rows, n4), reg, out=t)
            t *= k4
            reg += t

    def _fill_opaque(self, k, covered, nnz, dst_sl, vec):
        """:meth:`fill` of opaque paint (``alpha * opacity == 1``) through
        the mask window ``k`` ((h, w) float32) onto ``self.data[dst_sl]``.

        ``covered`` ((h, w) bool) is ``k != 0`` and ``nnz`` its count.
        Pixels of full coverage (``k == 1``) take the colour ``vec`` ((4,)
        float32, alpha 1; in levels on an 8-bit canvas, rounded there) by a
        masked copy, without reading the canvas; the partly covered ones
        (edges) are blended by :meth:`_fill_pixels`.
        """
        h, w = k.shape
        full = k == 1.0
        nfull = np.count_nonzero(full)
        if self.data.dtype == _U8:
            # a pixel is one uint32: the colour (the blend of coverage 1,
            # rounded) copied where the coverage is full
            px = np.floor(vec + _HALF).astype(np.uint8).view(np.uint32)
            reg = self.data[dst_sl].view(np.uint32)[..., 0]
            np.copyto(reg, px, where=full)
        else:
            # the bool mask repeated to the 4 lanes of each pixel: each byte
            # times 0x01010101 fills a uint32 with 4 copies of it
            full4 = full.view(np.uint8).astype(np.uint32)
            full4 *= np.uint32(0x01010101)
            reg = self.data[dst_sl].reshape(h, 4 * w, copy=False)
            np.copyto(reg, _row_of(vec, w)[:4 * w],
                      where=full4.view(np.bool_).reshape(h, 4 * w))
        if nfull < nnz:
            covered &= ~full
            self._fill_pixels(np.flatnonzero(covered), k, dst_sl, np.float32(1.0), vec)

    def _fill_pixels(self, idx, k, dst_sl, alpha, vec):
        """:meth:`fill` of the pixels ``idx`` (flat indices into the mask
        window ``k``, the nonzero ones) by gathering and scattering them."""
        w = k.shape[1]
        rows, cols = np.divmod(idx, w)
        pix = (rows + dst_sl[0].start) * self.width + (cols + dst_sl[1].start)
        flat = self.data.reshape(-1, 4)
        reg = flat[pix]
        kk = k.reshape(-1)[idx] if k.flags.c_contiguous else k[rows, cols]
        if alpha != 1.0:
            kk = kk * alpha
        n = len(idx)
        k4 = _spread4(kk.reshape(1, n), np.empty((n, 2), np.uint64)).reshape(n, 4)
        t = _tile4(vec, n).reshape(n, 4)
        if reg.dtype == _U8:
            _over8(reg, t, k4, t=t)
            flat[pix] = reg
            return
        t -= reg
        t *= k4
        reg += t
        flat[pix] = reg

    def composite(self, src_premul, x0=0, y0=0, opacity=1.0):
        """Source-over of a premultiplied RGBA layer onto the canvas.

        Parameters
        ----------
        src_premul : (h, w, 4) array_like of float32, or uint8 ndarray
            Premultiplied RGBA, floats in [0, 1] or uint8 levels (the data
            of an 8-bit layer); ``src_premul[0, 0]`` lands on canvas pixel
            (row ``y0``, column ``x0``).  Parts off the canvas are ignored.
        x0, y0 : int
        opacity : float
            Factor applied to the whole layer (all four channels).

        >>> c = Canvas(1, 1, background=(0, 0, 1))
        >>> c.composite(np.array([[[0.5, 0, 0, 0.5]]], np.float32))
        >>> c.data.tolist()
        [[[0.5, 0.0, 0.5, 1.0]]]
        """
        src = np.asarray(src_premul)
        levels = src.dtype == _U8
        if not levels:
            src = src.astype(np.float32, copy=False)
        if src.ndim != 3 or src.shape[2] != 4:
            raise CanvasError('layer must have shape (h, w, 4), got %r' % (src.shape,))
        try:
            op = float(opacity)
            x0, y0 = int(x0), int(y0)
        except (TypeError, ValueError):
            raise CanvasError('layer offset and opacity must be numbers') from None
        if not np.isfinite(op):
            raise CanvasError('opacity must be finite')
        op = min(max(op, 0.0), 1.0)
        if op == 0.0:
            return
        win = self._window(x0, y0, src.shape[0], src.shape[1])
        if win is None:
            return
        dst_sl, src_sl = win
        s = src[src_sl]
        region = self.data[dst_sl]
        eight = region.dtype == _U8
        # region = region * (1 - alpha) + s, with the factor spread to the 4
        # lanes of each pixel (see _spread4) so the loops stay long (on an
        # 8-bit canvas in float32 levels, rounded)
        w = s.shape[1]
        step = max(1, _BLOCK // max(1, w))
        lanes = np.empty((min(step, s.shape[0]) * w, 2), np.uint64)
        one = np.float32(1.0)
        for i0 in range(0, s.shape[0], step):
            ss = s[i0:i0 + step]
            if levels:
                ss = np.multiply(ss, np.float32(op / 255.0), dtype=np.float32)
            elif op != 1.0:
                ss = ss * np.float32(op)
            reg = region[i0:i0 + step]
            keep = _spread4(np.subtract(one, ss[..., 3]), lanes).reshape(reg.shape)
            if eight:
                f = reg.astype(np.float32)
                f *= keep
                f += ss * _S255
                f += _HALF
                np.clip(f, 0.0, 255.0, out=f)
                np.copyto(reg, f, casting='unsafe')
                continue
            reg *= keep
            reg += ss

    def store(self, y0, y1, x0, x1, pixels):
        """Replace canvas pixels ``[y0:y1, x0:x1]`` by ``pixels`` ((y1-y0,
        x1-x0, 4) premultiplied RGBA floats in [0, 1]; the window must lie
        on the canvas; rounded to levels on an 8-bit canvas)."""
        if self.data.dtype == _U8:
            _quantize(self.data[y0:y1, x0:x1], pixels)
        else:
            self.data[y0:y1, x0:x1] = pixels

    def scale(self, factor):
        """Multiply every pixel (all four channels) by ``factor`` ((H, W)
        float32 in [0, 1]: a clip path's coverage, a mask's values);
        rounded on an 8-bit canvas.

        >>> c = Canvas(2, 1, (1, 1, 1), dtype=np.uint8)
        >>> c.scale(np.array([[0.5, 0.25]], np.float32)); c.data[0, :, 3].tolist()
        [128, 64]
        """
        f = np.asarray(factor, np.float32)
        if f.shape != (self.height, self.width):
            raise CanvasError('factor must have shape %r, got %r'
                              % ((self.height, self.width), f.shape))
        if self.data.dtype != _U8:
            self.data *= f[..., None]
            return
        step = max(1, _BLOCK // self.width)
        for y in range(0, self.height, step):
            reg = self.data[y:y + step]
            v = np.multiply(reg, f[y:y + step, :, None], dtype=np.float32)
            v += _HALF
            np.copyto(reg, v, casting='unsafe')

    def combine(self, weights):
        """``sum(weights[c] * channel c)`` per pixel, channels R, G, B, A in
        [0, 1]: (H, W) float32 (the alpha, ``(0, 0, 0, 1)``, or the
        luminance of a mask), computed in blocks of rows.

        >>> c = Canvas(1, 1, (1, 0, 0, 0.5), dtype=np.uint8)     # levels (128, 0, 0, 128)
        >>> c.combine((1, 0, 0, 0)) == c.combine((0, 0, 0, 1)) == np.float32(128 / 255)
        array([[ True]])
        """
        w = np.asarray(weights, np.float32).reshape(4)
        if self.data.dtype == _U8:
            w = w / _S255
        out = np.empty((self.height, self.width), np.float32)
        step = max(1, _BLOCK // self.width)
        for y in range(0, self.height, step):
            np.dot(self.data[y:y + step].astype(np.float32, copy=False), w, out=out[y:y + step])
        return out

    def read(self, y0, y1, x0, x1):
        """A float32 copy of canvas pixels ``[y0:y1, x0:x1]``:
        ((y1-y0, x1-x0, 4) premultiplied RGBA in [0, 1]; levels divided by
        255 on an 8-bit canvas)."""
        d = self.data[y0:y1, x0:x1]
        if d.dtype == _U8:
            return np.divide(d, _S255, dtype=np.float32)
        return d.copy()

    def to_rgba8(self, premultiplied=False):
        """8-bit RGBA image, (H, W, 4) uint8.

        With ``premultiplied=False`` (the default) colours are demultiplied
        (divided by alpha) before rounding; pixels whose alpha rounds to 0
        become (0, 0, 0, 0).  Rounding is to nearest, values are clamped to
        [0, 255].  Computed in float32, in blocks of rows that stay in
        cache; only pixels with 0 < alpha < 1 are divided (alpha 1 leaves
        the colour as it is, alpha 0 gives 0).  An 8-bit canvas is
        demultiplied from its levels: ``c * 255 / a`` rounded.

        >>> c = Canvas(2, 1)
        >>> c.data[0] = [[0.25, 0.0, 0.0, 0.5], [0.2, 0.4, 0.6, 1.0]]
        >>> c.to_rgba8().tolist()
        [[[128, 0, 0, 128], [51, 102, 153, 255]]]
        >>> c.to_rgba8(premultiplied=True)[0, 0].tolist()
        [64, 0, 0, 128]
        >>> c8 = Canvas(1, 1, dtype=np.uint8)
        >>> c8.data[0, 0] = [64, 0, 0, 128]
        >>> c8.to_rgba8().tolist()
        [[[128, 0, 0, 128]]]
        """
        return self.rgba8_rows(0, self.height, premultiplied)

    def rgba8_rows(self, y0, y1, premultiplied=False):
        """Rows ``y0:y1`` of :meth:`to_rgba8`: ((y1-y0), W, 4) uint8 (what
        an encoder writing a strip at a time reads, without an image of the
        whole canvas)."""
        H, W = self.height, self.width
        y0, y1 = max(0, int(y0)), min(H, int(y1))
        n = max(0, y1 - y0) * W
        flat = self.data.reshape(-1, 4)[y0 * W:y0 * W + n]
        if self.data.dtype == _U8:
            return self._rows8(flat, premultiplied).reshape(-1, W, 4)
        out = np.empty((n, 4), np.uint8)
        step = max(1, 2 * _BLOCK // W) * W          # pixels per block
        buf = np.empty((min(step, max(n, 1)), 4), np.float32)
        zero, one = np.float32(0.0), np.float32(1.0)
        s255, half = np.float32(255.0), np.float32(0.5)
        for p0 in range(0, n, step):
            src = flat[p0:p0 + step]
            b = buf[:len(src)]
            np.multiply(src, s255, out=b)
            clipped = b.min() < zero or b.max() > s255
            if clipped:                 # values out of [0, 1] (rare)
                np.clip(b, zero, s255, out=b)
            if not premultiplied:
                # demultiply the translucent pixels (0 < alpha < 1) from the
                # float data, as clip(colour) / clip(alpha) * 255; alpha 1
                # leaves the colour as it is and alpha 0 zeroes it below
                part = src[:, 3] < one
                part &= src[:, 3] > zero
                idx = np.flatnonzero(part)
                if len(idx):
                    sub = src[idx]
                    if clipped:
                        np.clip(sub, zero, one, out=sub)
                    _demultiply(sub)
                    sub *= s255
                    np.minimum(sub, s255, out=sub)   # colour may exceed 1
                    b[idx] = sub
            b += half
            o = out[p0:p0 + len(b)]
            np.copyto(o, b, casting='unsafe')   # truncation = floor (b >= 0.5)
            if not premultiplied:
                # pixels whose alpha rounds to 0 become (0, 0, 0, 0): as
                # little-endian uint32 the alpha byte is the top one
                px = o.view('<u4').reshape(-1)
                np.multiply(px, px >= np.uint32(1 << 24), out=px)
        return out.reshape(-1, W, 4)

    @staticmethod
    def _rows8(flat, premultiplied):
        """:meth:`rgba8_rows` of an 8-bit canvas's (n, 4) uint8 pixels,
        demultiplied in blocks of :data:`_DEMULTIPLY_BLOCK` pixels (the
        float32 copies of the translucent pixels, 16 bytes each, and their
        indices stay small when most pixels are edges)."""
        out = flat.copy()
        if premultiplied:
            return out
        for p0 in range(0, len(out), _DEMULTIPLY_BLOCK):
            o = out[p0:p0 + _DEMULTIPLY_BLOCK]
            a = o[:, 3]
            idx = np.flatnonzero((a != 0) & (a != 255))
            if len(idx):
                sub = o[idx].astype(np.float32)
                c = sub[:, :3]
                c *= _S255
                c /= sub[:, 3:]
                c += _HALF
                np.minimum(c, _S255, out=c)
                o[idx] = sub.astype(np.uint8)   # (c is a view of sub; truncation: rounding)
            # alpha 0: colour 0 (as little-endian uint32 the alpha byte is the top one)
            px = o.view('<u4').reshape(-1)
            np.multiply(px, px >= np.uint32(1 << 24), out=px)
        return out

    def to_image(self):
        """The canvas as a ``PIL.Image.Image`` in mode RGBA (straight alpha)."""
        from PIL import Image
        return Image.fromarray(self.to_rgba8(), 'RGBA')

    def save_png(self, path_or_file, compress_level=DEFAULT_COMPRESS_LEVEL):
        """Write the canvas as an RGBA PNG (straight alpha) with
        :func:`raster.pixels.png.write_png`.

        Parameters
        ----------
        path_or_file : str, os.PathLike or binary file object
        compress_level : int
            zlib level 0-9 (see :data:`DEFAULT_COMPRESS_LEVEL`).
        """
        write_png(path_or_file, self.to_rgba8(), compress_level)
