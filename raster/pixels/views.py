"""Views of a canvas: :class:`ClipRect`, a canvas seen through an
axis-aligned device rectangle (a group clipped by one rectangle is drawn
through it without a layer of its own)."""

import math

import numpy as np

from .scan import Mask

__all__ = ['ClipRect', 'STRIP_PIXELS', 'pixel_overlaps']

#: Pixels of a window multiplied by the rectangle's coverage at a time.
STRIP_PIXELS = 1 << 18


def pixel_overlaps(lo, hi, k0, n):
    """The length of the interval [lo, hi] inside each pixel interval
    [k, k + 1], k = k0 .. k0 + n - 1: (n,) float64 in [0, 1].  The exact
    area of a pixel inside an axis-aligned rectangle is the product of its
    x and y overlaps.

    >>> pixel_overlaps(0.25, 2.5, 0, 4).tolist()
    [0.75, 1.0, 0.5, 0.0]
    """
    k = np.arange(k0, k0 + n, dtype=np.float64)
    out = np.minimum(k + 1.0, hi)
    out -= np.maximum(k, lo)
    return np.clip(out, 0.0, 1.0, out=out)


class ClipRect:
    """A canvas seen through an axis-aligned device rectangle ``box``
    (x0, y0, x1, y1): :meth:`fill`, :meth:`composite` and :meth:`store`
    act on the canvas with the source multiplied by the rectangle's exact
    area coverage of each pixel (the product of its x and y overlaps);
    :meth:`read` reads the canvas.  ``width``, ``height`` and ``data`` are
    the canvas's."""

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
            self.cx = pixel_overlaps(x0, x1, self.X0, self.X1 - self.X0).astype(np.float32)
            self.cy = pixel_overlaps(y0, y1, self.Y0, self.Y1 - self.Y0).astype(np.float32)

    @property
    def data(self):
        return self.canvas.data

    def read(self, y0, y1, x0, x1):
        """The canvas's :meth:`~raster.pixels.canvas.Canvas.read`."""
        return self.canvas.read(y0, y1, x0, x1)

    def _window(self, x0, y0, h, w):
        """(a0, b0, a1, b1): the window's part inside the rectangle in
        canvas pixels, or None."""
        if self.empty:
            return None
        a0, b0 = max(x0, self.X0), max(y0, self.Y0)
        a1, b1 = min(x0 + w, self.X1), min(y0 + h, self.Y1)
        if a1 <= a0 or b1 <= b0:
            return None
        return a0, b0, a1, b1

    def _strips(self, win):
        """``(b0, b1, coverage)`` of strips of rows of the window ``win``
        (at most :data:`STRIP_PIXELS` pixels each): what is multiplied and
        composited at a time, so temporaries stay a strip's size."""
        a0, b0, a1, b1 = win
        step = max(1, STRIP_PIXELS // (a1 - a0))
        cx = self.cx[None, a0 - self.X0:a1 - self.X0]
        for r0 in range(b0, b1, step):
            r1 = min(r0 + step, b1)
            yield r0, r1, self.cy[r0 - self.Y0:r1 - self.Y0, None] * cx

    def fill(self, mask, color, opacity=1.0):
        """The canvas's :meth:`~raster.pixels.canvas.Canvas.fill` through
        each of :meth:`masks`."""
        for m in self.masks(mask):
            self.canvas.fill(m, color, opacity)

    def masks(self, mask):
        """The Masks (in the canvas's pixels) of ``mask`` (a Mask or None)
        multiplied by the rectangle's coverage, a strip of rows at a time
        (none when nothing of it is inside the rectangle)."""
        if mask is None:
            return
        h, w = mask.data.shape
        win = self._window(int(mask.x0), int(mask.y0), h, w)
        if win is None:
            return
        a0, _, a1, _ = win
        for r0, r1, cov in self._strips(win):
            k = mask.data[r0 - mask.y0:r1 - mask.y0, a0 - mask.x0:a1 - mask.x0] * cov
            yield Mask(k, a0, r0)

    def composite(self, src, x0=0, y0=0, opacity=1.0):
        """The canvas's :meth:`~raster.pixels.canvas.Canvas.composite` of
        ``src`` (floats in [0, 1] or uint8 levels) times the coverage."""
        src = np.asarray(src)
        if src.dtype != np.uint8:
            src = src.astype(np.float32, copy=False)
        win = self._window(int(x0), int(y0), src.shape[0], src.shape[1])
        if win is None:
            return
        a0, _, a1, _ = win
        for r0, r1, cov in self._strips(win):
            if src.dtype == np.uint8:
                cov = cov / np.float32(255.0)
            s = src[r0 - y0:r1 - y0, a0 - x0:a1 - x0] * cov[..., None]
            self.canvas.composite(s, a0, r0, opacity)

    def store(self, y0, y1, x0, x1, out):
        """Replace canvas pixels [y0:y1, x0:x1] by ``out`` (h, w, 4) as
        seen through the rectangle: ``old + coverage (out - old)``."""
        win = self._window(x0, y0, y1 - y0, x1 - x0)
        if win is None:
            return
        a0, _, a1, _ = win
        for r0, r1, cov in self._strips(win):
            new = out[r0 - y0:r1 - y0, a0 - x0:a1 - x0]
            old = self.canvas.read(r0, r1, a0, a1)
            self.canvas.store(r0, r1, a0, a1, old + (new - old) * cov[..., None])
