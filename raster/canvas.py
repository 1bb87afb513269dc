"""A premultiplied float32 RGBA canvas: fills, source-over compositing, PNG.

Pixel (row ``i``, column ``j``) of a canvas covers ``[j, j+1] x [i, i+1]`` in
device space (x right, y down).  :attr:`Canvas.data` is ``(H, W, 4)`` float32
holding *premultiplied* red, green, blue and alpha in [0, 1].  Colours passed
in are *straight* (not premultiplied) RGB or RGBA in [0, 1].

>>> import numpy as np
>>> from raster.scan import Mask
>>> c = Canvas(2, 1, background=(1, 1, 1))
>>> c.fill(Mask(np.array([[1.0, 0.5]], np.float32), 0, 0), (0, 0, 1))
>>> c.to_rgba8().tolist()
[[[0, 0, 255, 255], [128, 128, 255, 255]]]
"""

import numpy as np

from .errors import CanvasError
from .scan import check_canvas_size

__all__ = ['Canvas', 'DEFAULT_COMPRESS_LEVEL']

#: zlib level used by :meth:`Canvas.save_png`.  Measured on a 2000x2000 RGBA
#: picture (gradients and a disc) with Pillow on the 2-core build machine:
#: level 1: 0.33 s, 1.11 MB; level 3: 0.37 s, 0.88 MB; level 6: 0.68 s,
#: 0.64 MB; level 9: 5.8 s, 0.48 MB.  Level 3 compresses 20% better than 1 for
#: about the same time, and 6 costs twice the time of 3.
DEFAULT_COMPRESS_LEVEL = 3

# Pixels per block of rows in fill / composite (bounds temporaries).
_BLOCK = 1 << 16


def _color(color, opacity):
    """Straight RGB/RGBA + opacity -> (r, g, b) float64, alpha*opacity."""
    try:
        c = [float(v) for v in color]
    except (TypeError, ValueError):
        raise CanvasError('colour must be 3 or 4 numbers, got %r' % (color,)) from None
    if len(c) not in (3, 4):
        raise CanvasError('colour must have 3 or 4 components, got %d' % len(c))
    try:
        op = float(opacity)
    except (TypeError, ValueError):
        raise CanvasError('opacity must be a number, got %r' % (opacity,)) from None
    if not all(np.isfinite(c)) or not np.isfinite(op):
        raise CanvasError('colour and opacity must be finite')
    c = [min(max(v, 0.0), 1.0) for v in c]
    a = (c[3] if len(c) == 4 else 1.0) * min(max(op, 0.0), 1.0)
    return c[0], c[1], c[2], a


class Canvas:
    """Premultiplied RGBA float32 pixel buffer.

    Parameters
    ----------
    width, height : int
        Size in pixels (whole numbers; integral floats accepted).
    background : sequence of 3 or 4 float, optional
        Straight RGB(A) colour in [0, 1] to start from; transparent black
        when omitted.

    Attributes
    ----------
    data : (height, width, 4) float32 ndarray
        Premultiplied RGBA in [0, 1].

    Raises
    ------
    CanvasError
        Size not a positive whole number, a side above
        :data:`raster.limits.MAX_SIDE` or more than
        :data:`raster.limits.MAX_PIXELS` pixels; malformed background.

    >>> Canvas(3, 2).data.shape
    (2, 3, 4)
    """

    def __init__(self, width, height, background=None):
        self.width, self.height = check_canvas_size(width, height)
        self.data = np.zeros((self.height, self.width, 4), np.float32)
        if background is not None:
            r, g, b, a = _color(background, 1.0)
            self.data[...] = (r * a, g * a, b * a, a)

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
        mask : raster.scan.Mask or None
            Coverage (h, w) float32 at (x0, y0); the part outside the
            canvas is ignored.  None does nothing.
        color : sequence of 3 or 4 float
            Straight RGB(A) in [0, 1] (values outside are clamped).
        opacity : float
            Extra alpha factor in [0, 1].

        Each pixel becomes ``src + dst * (1 - src_alpha)`` with
        ``src = coverage * opacity * alpha * (r, g, b, 1)``.

        >>> from raster.scan import Mask
        >>> c = Canvas(1, 1)
        >>> c.fill(Mask(np.ones((1, 1), np.float32), 0, 0), (1, 0, 0, 0.5))
        >>> c.data.tolist()
        [[[0.5, 0.0, 0.0, 0.5]]]
        """
        if mask is None:
            return
        r, g, b, a = _color(color, opacity)
        if a == 0.0:
            return
        cov = np.asarray(mask.data, np.float32)
        if cov.ndim != 2:
            raise CanvasError('mask data must be 2-D, got shape %r' % (cov.shape,))
        win = self._window(int(mask.x0), int(mask.y0), cov.shape[0], cov.shape[1])
        if win is None:
            return
        dst_sl, src_sl = win
        k = cov[src_sl]
        # crop to the rows holding coverage (masks are often mostly empty)
        rows = np.flatnonzero(k.any(axis=1))
        if len(rows) == 0:
            return
        r0, r1 = int(rows[0]), int(rows[-1]) + 1
        k = k[r0:r1]
        region = self.data[dst_sl][r0:r1]
        alpha = np.float32(a)
        vec = (np.float32(r), np.float32(g), np.float32(b), np.float32(1.0))
        # region += k * (vec - region), channel by channel (long strided
        # loops; a broadcast over the 4 channels runs 4-element inner
        # loops), in blocks of rows that stay in cache; each block is
        # cropped to its columns holding coverage
        w = k.shape[1]
        step = max(1, _BLOCK // max(1, w))
        tmp = np.empty(min(step, k.shape[0]) * w, np.float32)
        kbuf = np.empty(min(step, k.shape[0]) * w, np.float32) if alpha != 1.0 else None
        for i0 in range(0, k.shape[0], step):
            kk = k[i0:i0 + step]
            cols = np.flatnonzero(kk.any(axis=0))
            if len(cols) == 0:
                continue
            c0, c1 = int(cols[0]), int(cols[-1]) + 1
            kk = kk[:, c0:c1]
            n = kk.size
            if kbuf is not None:
                kk = np.multiply(kk, alpha, out=kbuf[:n].reshape(kk.shape))
            reg = region[i0:i0 + step, c0:c1]
            t = tmp[:n].reshape(kk.shape)
            for ch in range(4):
                rc = reg[..., ch]
                np.subtract(vec[ch], rc, out=t)
                t *= kk
                rc += t

    def composite(self, src_premul, x0=0, y0=0, opacity=1.0):
        """Source-over of a premultiplied RGBA layer onto the canvas.

        Parameters
        ----------
        src_premul : (h, w, 4) array_like of float32
            Premultiplied RGBA; ``src_premul[0, 0]`` lands on canvas pixel
            (row ``y0``, column ``x0``).  Parts off the canvas are ignored.
        x0, y0 : int
        opacity : float
            Factor applied to the whole layer (all four channels).

        >>> c = Canvas(1, 1, background=(0, 0, 1))
        >>> c.composite(np.array([[[0.5, 0, 0, 0.5]]], np.float32))
        >>> c.data.tolist()
        [[[0.5, 0.0, 0.5, 1.0]]]
        """
        src = np.asarray(src_premul, dtype=np.float32)
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
        step = max(1, _BLOCK // max(1, s.shape[1]))
        for i0 in range(0, s.shape[0], step):
            ss = s[i0:i0 + step]
            if op != 1.0:
                ss = ss * np.float32(op)
            reg = region[i0:i0 + step]
            reg *= (np.float32(1.0) - ss[..., 3:4])
            reg += ss

    def to_rgba8(self, premultiplied=False):
        """8-bit RGBA image, (H, W, 4) uint8.

        With ``premultiplied=False`` (the default) colours are demultiplied
        (divided by alpha) before rounding; pixels whose alpha rounds to 0
        become (0, 0, 0, 0).  Rounding is to nearest, values are clamped to
        [0, 255].
        """
        d = np.clip(self.data, 0.0, 1.0)
        a8 = np.floor(d[..., 3] * 255.0 + 0.5)
        out = np.empty(d.shape, np.uint8)
        if premultiplied:
            out[...] = np.floor(d * 255.0 + 0.5)
            return out
        alpha = d[..., 3:4]
        with np.errstate(divide='ignore', invalid='ignore'):
            rgb = np.where(alpha > 0, d[..., :3] / alpha, 0.0)
        rgb8 = np.floor(np.clip(rgb, 0.0, 1.0) * 255.0 + 0.5)
        rgb8[a8 == 0] = 0
        out[..., :3] = rgb8
        out[..., 3] = a8
        return out

    def to_image(self):
        """The canvas as a ``PIL.Image.Image`` in mode RGBA (straight alpha)."""
        from PIL import Image
        return Image.fromarray(self.to_rgba8(), 'RGBA')

    def save_png(self, path_or_file, compress_level=DEFAULT_COMPRESS_LEVEL):
        """Write the canvas as an RGBA PNG (straight alpha) with Pillow.

        Parameters
        ----------
        path_or_file : str, os.PathLike or binary file object
        compress_level : int
            zlib level 0-9 (see :data:`DEFAULT_COMPRESS_LEVEL`).
        """
        try:
            level = int(compress_level)
        except (TypeError, ValueError):
            raise CanvasError('compress_level must be an integer 0-9') from None
        if not 0 <= level <= 9:
            raise CanvasError('compress_level must be 0-9, got %d' % level)
        self.to_image().save(path_or_file, format='PNG', compress_level=level)
