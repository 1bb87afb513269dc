"""Axes for plots: "nice" tick values, a grid, a frame and tick labels in a
panel of the plot, all as device-space paths (the layers of
:class:`raster.curves.plot.Plot`).

A panel maps a data rectangle ``[x0, x1] x [y0, y1]`` onto a device
rectangle; with ``equal=True`` both axes get one scale (geometry keeps its
shape) and the data range grows along the shorter side to fill the panel.

>>> nice_ticks(0.8, 6.2).tolist()
[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
>>> nice_ticks(0, 1, 5).tolist()
[0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
"""

import math

import numpy as np

from ..geometry.path import Path
from ..geometry.transform import Affine
from .checks import CurveError

__all__ = ['nice_step', 'nice_ticks', 'Panel', 'AXIS_COLORS']

#: Colours (straight RGB(A) in [0, 1]) of the axes layers.
AXIS_COLORS = {
    'grid': (0.88, 0.88, 0.9),
    'grid_zero': (0.62, 0.62, 0.66),
    'frame': (0.35, 0.35, 0.38),
    'tick_label': (0.2, 0.2, 0.22),
    'title': (0.0, 0.0, 0.0),
}


def nice_step(span: float, target: int = 6) -> float:
    """A step of 1, 2 or 5 times a power of ten giving about ``target``
    intervals over ``span`` (> 0)."""
    if not span > 0 or not math.isfinite(span):
        raise CurveError('axis span must be positive and finite')
    raw = span / max(1, int(target))
    mag = 10.0 ** math.floor(math.log10(raw))
    for m in (1.0, 2.0, 2.5, 5.0, 10.0):
        if raw <= m * mag * (1 + 1e-9):
            return m * mag
    return 10.0 * mag


def nice_ticks(lo: float, hi: float, target: int = 6) -> np.ndarray:
    """Tick values: multiples of :func:`nice_step` inside ``[lo, hi]``,
    (K,) float64 (rounded to the step's decimals, so 0.30000000000000004
    becomes 0.3)."""
    lo, hi = float(lo), float(hi)
    if not hi > lo:
        raise CurveError('axis range must have lo < hi')
    step = nice_step(hi - lo, target)
    k0 = math.ceil(lo / step - 1e-9)
    k1 = math.floor(hi / step + 1e-9)
    digits = max(0, -int(math.floor(math.log10(step))) + 1)
    return np.round(np.arange(k0, k1 + 1) * step, digits) + 0.0


def tick_text(v: float, step: float) -> str:
    """Label of tick ``v``: as many decimals as the step needs."""
    if abs(v) < step * 1e-9:
        return '0'
    if abs(v) >= 1e5 or abs(v) < 1e-4:
        return ('%.3g' % v).replace('e+0', 'e').replace('e-0', 'e-')
    dec = max(0, -int(math.floor(math.log10(step) + 1e-9)))
    if step * 10 ** dec % 1 > 1e-6:        # 2.5, 0.25 ...
        dec += 1
    return '%.*f' % (dec, v)


class Panel:
    """A data rectangle shown in a device rectangle.

    Parameters
    ----------
    data : (x0, x1, y0, y1)
        Data range (grown for equal scales and by ``pad``).
    rect : (left, top, width, height)
        Device rectangle of the plotting area.
    y_up : bool
        Mathematical orientation (y grows upwards on the image).
    equal : bool
        One scale for both axes.
    pad : float
        Extra margin around the data, as a fraction of its larger span.

    Attributes
    ----------
    transform : raster.geometry.transform.Affine
        Data to device.
    xlim, ylim : (float, float)
        The data range actually shown.
    """

    def __init__(self, data, rect, y_up=True, equal=True, pad=0.06):
        x0, x1, y0, y1 = (float(v) for v in data)
        left, top, w, h = (float(v) for v in rect)
        if not (w > 0 and h > 0):
            raise CurveError('panel must have a positive size')
        span = max(x1 - x0, y1 - y0)
        if not span > 0:
            span = 1.0
        if x1 - x0 < 1e-9 * span:
            x0, x1 = x0 - 0.5 * span, x1 + 0.5 * span
        if y1 - y0 < 1e-9 * span:
            y0, y1 = y0 - 0.5 * span, y1 + 0.5 * span
        px, py = pad * (x1 - x0 if not equal else span), pad * (y1 - y0 if not equal else span)
        x0, x1, y0, y1 = x0 - px, x1 + px, y0 - py, y1 + py
        sx, sy = w / (x1 - x0), h / (y1 - y0)
        if equal:
            s = min(sx, sy)
            cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
            x0, x1 = cx - 0.5 * w / s, cx + 0.5 * w / s
            y0, y1 = cy - 0.5 * h / s, cy + 0.5 * h / s
            sx = sy = s
        self.rect = (left, top, w, h)
        self.xlim, self.ylim = (x0, x1), (y0, y1)
        self.y_up = bool(y_up)
        if y_up:
            self.transform = Affine(sx, 0, 0, -sy, left - x0 * sx, top + y1 * sy)
        else:
            self.transform = Affine(sx, 0, 0, sy, left - x0 * sx, top - y0 * sy)

    def device(self, pts):
        """Data points (N, 2) to device points (N, 2) float64."""
        return self.transform.apply(np.asarray(pts, dtype=np.float64).reshape(-1, 2))

    @property
    def scale(self):
        """Device pixels per data unit along x."""
        return self.transform.a

    def layers(self, text_path, text_width, xlabel='x', ylabel='y', title=None, target=6,
               font=11.0):
        """Grid, frame, ticks and labels as ``(kind, Path, style)`` layers
        (the grid first, to be drawn under everything)."""
        left, top, w, h = self.rect
        right, bottom = left + w, top + h
        xt = nice_ticks(*self.xlim, target=max(4, int(target * w / max(w, h) + 0.5)))
        yt = nice_ticks(*self.ylim, target=max(4, int(target * h / max(w, h) + 0.5)))
        xs = nice_step(self.xlim[1] - self.xlim[0], max(4, int(target * w / max(w, h) + 0.5)))
        ys = nice_step(self.ylim[1] - self.ylim[0], max(4, int(target * h / max(w, h) + 0.5)))
        T = self.transform
        grid, zero, ticks = [], [], []
        for v in xt:
            X = T.a * v + T.e
            (zero if v == 0 else grid).append([(X, top), (X, bottom)])
            ticks.append([(X, bottom), (X, bottom + 4)])
        for v in yt:
            Y = T.d * v + T.f
            (zero if v == 0 else grid).append([(left, Y), (right, Y)])
            ticks.append([(left - 4, Y), (left, Y)])
        out = []
        if grid:
            out.append(('stroke', _lines(grid), {'color': AXIS_COLORS['grid'], 'width': 1.0}))
        if zero:
            out.append(('stroke', _lines(zero), {'color': AXIS_COLORS['grid_zero'],
                                                 'width': 1.0}))
        frame = Path.polygon([(left, top), (right, top), (right, bottom), (left, bottom)])
        out.append(('stroke', frame, {'color': AXIS_COLORS['frame'], 'width': 1.0}))
        out.append(('stroke', _lines(ticks), {'color': AXIS_COLORS['frame'], 'width': 1.0}))
        texts = []
        for v in xt:
            s = tick_text(v, xs)
            X = T.a * v + T.e
            texts.append((s, X - text_width(s, font) / 2, bottom + 6 + font))
        for v in yt:
            s = tick_text(v, ys)
            Y = T.d * v + T.f
            texts.append((s, left - 7 - text_width(s, font), Y + font * 0.36))
        if xlabel:
            texts.append((xlabel, right - text_width(xlabel, font + 1), bottom + 2 * font + 10))
        if ylabel:
            texts.append((ylabel, left - 7 - text_width(ylabel, font + 1), top - 6))
        paths = [text_path(s, x, y, font) for s, x, y in texts[:len(xt) + len(yt)]]
        paths += [text_path(s, x, y, font + 1) for s, x, y in texts[len(xt) + len(yt):]]
        if title:
            paths.append(text_path(title, left + (w - text_width(title, font + 2)) / 2, top - 8,
                                   font + 2))
        for p in paths:
            if not p.is_empty:
                out.append(('fill', p, {'color': AXIS_COLORS['tick_label'], 'layer': 'axes'}))
        return out


def _lines(segs):
    """A path of separate line segments."""
    from ..geometry.pens import PathBuilder
    b = PathBuilder()
    for seg in segs:
        b.moveTo(tuple(map(float, seg[0])))
        for q in seg[1:]:
            b.lineTo(tuple(map(float, q)))
        b.endPath()
    return b.path()
