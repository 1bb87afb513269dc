"""Views of a canvas: :class:`ClipRect`, a canvas seen through an
axis-aligned device rectangle (a group clipped by one rectangle is drawn
through it without a layer of its own)."""

import math

import numpy as np

from .scan import Mask

__all__ = ['ClipRect']


class ClipRect:
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
        old = self.canvas.data[b0:b1, a0:a1]
        self.canvas.store(b0, b1, a0, a1, old + (new - old) * cov[..., None])
