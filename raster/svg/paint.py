"""Paint sources: gradients, raster images and image sampling.

Every function here works on device pixels of a window (a coverage
:class:`raster.scan.Mask` or a pixel box) and returns premultiplied float32
RGBA, x right and y down, pixel (i, j) centred at (j + 0.5, i + 0.5).
"""

import math

import numpy as np

from ..errors import RasterError
from ..path import Path
from ..scan import coverage
from ..flatten import flatten
from ..transform import Affine
from .tree import LinearGradient

__all__ = ['gradient_colors', 'draw_pixels', 'sample', 'user_bbox']


def _cover(path, t, w, h, rule, antialias, tol):
    """Coverage Mask of ``path`` filled under ``t`` on a w x h target."""
    pl = flatten(path, tol, transform=t)
    edges = pl.edges(close_all=True)
    if len(edges) == 0:
        return None
    return coverage(edges, w, h, rule, antialias)


# ---------------------------------------------------------------------------
# Gradients
# ---------------------------------------------------------------------------

def user_bbox(path):
    """Bounding box (x, y, w, h) of a path in its own units, for
    objectBoundingBox paints."""
    try:
        from ..bbox import bbox as exact_bbox
        x0, y0, x1, y1 = exact_bbox(path)
    except (ImportError, RasterError, TypeError, ValueError):
        x0, y0, x1, y1 = path.control_box()
    return x0, y0, x1 - x0, y1 - y0


def _stop_table(stops):
    offs = np.array([s.offset for s in stops], np.float64)
    cols = np.array([s.color for s in stops], np.float64).reshape(-1, 4)
    offs = np.maximum.accumulate(np.clip(offs, 0.0, 1.0))
    return offs, cols


def gradient_colors(paint, mask, path, t):
    """Premultiplied (h, w, 4) float32 colours of a gradient over the mask's
    window, already multiplied by the mask's coverage; None if nothing."""
    stops = paint.stops
    if not stops:
        return None
    offs, cols = _stop_table(stops)
    h, w = mask.data.shape
    # paint space -> device
    pt = t
    if paint.units == 'objectBoundingBox':
        bx, by, bw, bh = user_bbox(path)
        if bw <= 0 or bh <= 0:
            return None
        pt = pt @ Affine(bw, 0, 0, bh, bx, by)
    pt = pt @ paint.transform
    try:
        inv = pt.inverse()
    except RasterError:
        return None
    if len(stops) == 1:
        col = np.broadcast_to(cols[0], (h, w, 4))
        return _premul_cover(np.array(col), mask)
    jj, ii = np.meshgrid(np.arange(w) + mask.x0 + 0.5, np.arange(h) + mask.y0 + 0.5)
    pts = inv.apply(np.stack([jj, ii], -1))
    x, y = pts[..., 0], pts[..., 1]
    if isinstance(paint, LinearGradient):
        dx, dy = paint.x2 - paint.x1, paint.y2 - paint.y1
        dd = dx * dx + dy * dy
        if dd == 0:
            return _premul_cover(np.broadcast_to(cols[-1], (h, w, 4)).copy(), mask)
        s = ((x - paint.x1) * dx + (y - paint.y1) * dy) / dd
    else:
        s = _radial_param(paint, x, y)
        if s is None:
            return _premul_cover(np.broadcast_to(cols[-1], (h, w, 4)).copy(), mask)
    s = _spread(s, paint.spread)
    # interpolate straight colours per stop interval, then premultiply
    col = np.empty(s.shape + (4,), np.float64)
    for k in range(4):
        col[..., k] = np.interp(s, offs, cols[:, k]) if len(np.unique(offs)) == len(offs) \
            else _interp_steps(s, offs, cols[:, k])
    return _premul_cover(col, mask)


def _interp_steps(s, offs, vals):
    """np.interp that handles repeated offsets (hard colour stops): at an
    offset shared by several stops, the value jumps from the first stop's
    to the last stop's."""
    idx = np.searchsorted(offs, s, side='right')          # stops with offset <= s
    idx = np.clip(idx, 1, len(offs) - 1)
    o0, o1 = offs[idx - 1], offs[idx]
    v0, v1 = vals[idx - 1], vals[idx]
    span = o1 - o0
    f = np.where(span > 0, (s - o0) / np.where(span > 0, span, 1.0), 1.0)
    out = v0 + (v1 - v0) * np.clip(f, 0.0, 1.0)
    out = np.where(s <= offs[0], vals[0], out)
    out = np.where(s >= offs[-1], vals[-1], out)
    return out


def _spread(s, mode):
    if mode == 'repeat':
        return s - np.floor(s)
    if mode == 'reflect':
        m = np.mod(s, 2.0)
        return np.where(m > 1.0, 2.0 - m, m)
    return np.clip(s, 0.0, 1.0)


def _radial_param(p, x, y):
    """Gradient parameter of a two-point conical gradient: focal circle
    (fx, fy, fr) at s = 0 to the end circle (cx, cy, r) at s = 1; the
    largest s with a positive radius."""
    cx, cy, r, fx, fy, fr = p.cx, p.cy, p.r, p.fx, p.fy, p.fr
    if r <= 0:
        return None
    cdx, cdy, dr = cx - fx, cy - fy, r - fr
    px, py = x - fx, y - fy
    a = cdx * cdx + cdy * cdy - dr * dr
    b = px * cdx + py * cdy + fr * dr
    c = px * px + py * py - fr * fr
    if abs(a) < 1e-9:
        if abs(cdx) + abs(cdy) + abs(dr) < 1e-12:
            # concentric circles of equal radius: the start colour inside,
            # the end colour outside (as resvg)
            return np.where(c <= 0, 0.0, 1.0)
        with np.errstate(divide='ignore', invalid='ignore'):
            s = c / (2.0 * b)
        ok = (fr + s * dr >= 0) & np.isfinite(s)
        return np.where(ok, s, 0.0)
    disc = b * b - a * c
    sq = np.sqrt(np.maximum(disc, 0.0))
    s1 = (b + sq) / a
    s2 = (b - sq) / a
    hi = np.maximum(s1, s2)
    lo = np.minimum(s1, s2)
    s = np.where(fr + hi * dr >= 0, hi, lo)
    return np.where(disc >= 0, s, 0.0)


def _premul_cover(col, mask):
    col = np.asarray(col, np.float32)
    out = np.empty(col.shape, np.float32)
    a = col[..., 3] * mask.data
    out[..., :3] = col[..., :3] * a[..., None]
    out[..., 3] = a
    return out


# ---------------------------------------------------------------------------
# Raster images
# ---------------------------------------------------------------------------

def draw_pixels(n, t, canvas, tol):
    pix = np.asarray(n.pixels)
    if pix.ndim != 3 or pix.shape[2] != 4 or pix.shape[0] == 0 or pix.shape[1] == 0:
        return
    ih, iw = pix.shape[:2]
    it = t @ n.transform                                 # image px -> device
    try:
        inv = it.inverse()
    except RasterError:
        return
    # the drawn region: the image rectangle, clipped to the viewport
    img_rect = n.transform.apply(np.array([[0, 0], [iw, 0], [iw, ih], [0, ih]], float))
    region = Path.polygon(img_rect)
    m = _cover(region, t, canvas.width, canvas.height, 'nonzero', True, tol)
    if m is None:
        return
    cov, x0, y0 = m.data, m.x0, m.y0
    if n.clip is not None:
        x, y, w, h = n.clip
        rect = Path.polygon([(x, y), (x + w, y), (x + w, y + h), (x, y + h)])
        cm = _cover(rect, t, canvas.width, canvas.height, 'nonzero', True, tol)
        if cm is None:
            return
        # the two windows' intersection only (no canvas-sized arrays)
        ax0, ay0 = max(m.x0, cm.x0), max(m.y0, cm.y0)
        ax1 = min(m.x0 + cov.shape[1], cm.x0 + cm.data.shape[1])
        ay1 = min(m.y0 + cov.shape[0], cm.y0 + cm.data.shape[0])
        if ax1 <= ax0 or ay1 <= ay0:
            return
        cov = (cov[ay0 - m.y0:ay1 - m.y0, ax0 - m.x0:ax1 - m.x0]
               * cm.data[ay0 - cm.y0:ay1 - cm.y0, ax0 - cm.x0:ax1 - cm.x0])
        x0, y0 = ax0, ay0
    h, w = cov.shape
    jj, ii = np.meshgrid(np.arange(w) + x0 + 0.5, np.arange(h) + y0 + 0.5)
    src = inv.apply(np.stack([jj, ii], -1))
    u, v = src[..., 0], src[..., 1]
    # convert only the source pixels the window samples (one pixel of margin
    # for bilinear neighbours; clamping at a crop edge that is not an image
    # edge never happens because of the margin)
    u0 = min(max(int(math.floor(float(u.min()))) - 2, 0), iw - 1)
    v0 = min(max(int(math.floor(float(v.min()))) - 2, 0), ih - 1)
    u1 = max(min(int(math.ceil(float(u.max()))) + 2, iw), u0 + 1)
    v1 = max(min(int(math.ceil(float(v.max()))) + 2, ih), v0 + 1)
    p = pix[v0:v1, u0:u1].astype(np.float32) * np.float32(1.0 / 255.0)
    pm = np.empty_like(p)
    pm[..., :3] = p[..., :3] * p[..., 3:4]
    pm[..., 3] = p[..., 3]
    col = sample(pm, u - u0, v - v0, smooth=n.smooth, wrap=False)
    col = col * cov[..., None]
    canvas.composite(col.astype(np.float32), x0, y0, n.opacity)


def sample(img, u, v, smooth=True, wrap=False):
    """Sample an (H, W, 4) float32 image at continuous pixel coordinates
    (u right, v down; pixel (i, j) is centred at (j + 0.5, i + 0.5)).

    Bilinear when ``smooth`` else nearest; ``wrap`` repeats the image
    (tiling), otherwise coordinates clamp to the edge pixels."""
    ih, iw = img.shape[:2]
    if smooth:
        fu, fv = u - 0.5, v - 0.5
        u0 = np.floor(fu)
        v0 = np.floor(fv)
        au = (fu - u0).astype(np.float32)[..., None]
        av = (fv - v0).astype(np.float32)[..., None]
        u0 = u0.astype(np.int64)
        v0 = v0.astype(np.int64)
        u1, v1 = u0 + 1, v0 + 1
        if wrap:
            u0, u1, v0, v1 = u0 % iw, u1 % iw, v0 % ih, v1 % ih
        else:
            u0, u1 = np.clip(u0, 0, iw - 1), np.clip(u1, 0, iw - 1)
            v0, v1 = np.clip(v0, 0, ih - 1), np.clip(v1, 0, ih - 1)
        top = img[v0, u0] * (1 - au) + img[v0, u1] * au
        bot = img[v1, u0] * (1 - au) + img[v1, u1] * au
        return top * (1 - av) + bot * av
    ui = np.floor(u).astype(np.int64)
    vi = np.floor(v).astype(np.int64)
    if wrap:
        ui, vi = ui % iw, vi % ih
    else:
        ui, vi = np.clip(ui, 0, iw - 1), np.clip(vi, 0, ih - 1)
    return img[vi, ui]
