"""Paint sources: gradients, raster images and image sampling.

Every function here works on device pixels of a window (a coverage
:class:`raster.pixels.scan.Mask` or a pixel box) and returns premultiplied float32
RGBA, x right and y down, pixel (i, j) centred at (j + 0.5, i + 0.5).

Gradients work in float32 over the window (or only over its nonzero
pixels when the mask is sparse) and map the gradient parameter ``s``
(after the spread method) to colour: two stops in closed form, more
through a premultiplied lookup table sized to stay within 1/255 of the
exact piecewise-linear interpolation, or per stop interval when no table
that small can (hard stops, very steep ramps).  Raster images are
resampled in C by Pillow on the premultiplied 8-bit image, over the device
window actually drawn only.
"""

import math

import numpy as np

from .. import limits
from ..errors import RasterError
from ..geometry.path import Path
from ..pixels.scan import path_coverage
from ..pixels.views import pixel_overlaps
from ..geometry.transform import Affine

__all__ = ['gradient_colors', 'mesh_colors', 'draw_pixels', 'sample', 'resample_window', 'STRIP_PIXELS']

#: Pixels of an image, gradient or pattern window computed and composited at
#: a time (the float32 colours of a strip are what is held, not those of the
#: whole window).
STRIP_PIXELS = 1 << 18

_F32 = np.float32

# Work (raster.limits max_pixel_work) per covered pixel of a raster image:
# resampled (bilinear: four taps), covered and composited.
_IMAGE_PASSES = 40



# ---------------------------------------------------------------------------
# Gradients
# ---------------------------------------------------------------------------

#: Masks with fewer nonzero pixels than this fraction of their window are
#: painted pixel by pixel (gather/scatter) instead of over the whole window.
_SPARSE = 0.25
#: Smallest and largest colour lookup tables (entries over s in [0, 1]).
_LUT_MIN, _LUT_MAX = 256, 4096
#: Largest error of a lookup table against the exact interpolation, in
#: units of one 8-bit level (kept below 1 with a margin for float32).
_LUT_ERR = 0.9


def _stop_table(stops):
    offs = np.array([s.offset for s in stops], np.float64)
    cols = np.array([s.color for s in stops], np.float64).reshape(-1, 4)
    offs = np.maximum.accumulate(np.clip(offs, 0.0, 1.0))
    return offs, cols


def gradient_colors(paint, mask, t):
    """Premultiplied colours of a gradient over a coverage mask's window.

    Parameters
    ----------
    paint : raster.tree.LinearGradient, RadialGradient or SweepGradient
        In the painted node's user space.
    mask : raster.pixels.scan.Mask
        Coverage; ``mask.data`` is (h, w) float32.
    t : Affine
        User units -> device pixels.

    Returns
    -------
    (h, w, 4) float32 ndarray or None
        Premultiplied RGBA already multiplied by the coverage; None when
        nothing is painted.
    """
    from ..tree.servers import LinearGradient, SweepGradient   # loaded with the paint
    stops = paint.stops
    if not stops:
        return None
    offs, cols = _stop_table(stops)
    cover = np.asarray(mask.data, _F32)
    h, w = cover.shape
    pt = t @ paint.transform            # paint space -> device
    try:
        inv = pt.inverse()
    except RasterError:
        return None
    if len(stops) == 1:
        return _solid(cols[0], cover)
    nz = np.count_nonzero(cover)
    if nz == 0:
        return None
    # device pixel centres of the window, as separable terms: a paint-space
    # coordinate is  kx * X + ky * Y + k0  with X (columns) and Y (rows)
    xs = np.arange(w, dtype=np.float64) + (mask.x0 + 0.5)
    ys = np.arange(h, dtype=np.float64) + (mask.y0 + 0.5)
    if nz < _SPARSE * cover.size:
        flat = np.flatnonzero(cover)
        ii, jj = np.divmod(flat, w)

        def field(kx, ky, k0):
            """(n,) float64 values of kx*X + ky*Y + k0 at the nonzero pixels."""
            return (kx * xs + k0)[jj] + (ky * ys)[ii]
    else:
        flat = None

        def field(kx, ky, k0):
            """(h, w) float32 values of kx*X + ky*Y + k0 over the window:
            the sum of a row and a column term in float64, rounded once, so
            a pixel's value depends on its centre only (a window of a
            render gets the whole render's colours)."""
            out = np.add((ky * ys + k0)[:, None], (kx * xs)[None, :])
            return out.astype(_F32)

    if isinstance(paint, LinearGradient):
        dx, dy = paint.x2 - paint.x1, paint.y2 - paint.y1
        dd = dx * dx + dy * dy
        if dd == 0:
            return _solid(cols[-1], cover)
        s = field((inv.a * dx + inv.b * dy) / dd, (inv.c * dx + inv.d * dy) / dd,
                  ((inv.e - paint.x1) * dx + (inv.f - paint.y1) * dy) / dd)
    elif isinstance(paint, SweepGradient):
        span = paint.end_angle - paint.start_angle
        if span == 0:
            return _solid(cols[-1], cover)
        px = np.asarray(field(inv.a, inv.c, inv.e - paint.cx), np.float64)
        py = np.asarray(field(inv.b, inv.d, inv.f - paint.cy), np.float64)
        ang = np.degrees(np.arctan2(py, px))
        ang %= 360.0
        s = (ang - paint.start_angle) / span
    else:
        px = field(inv.a, inv.c, inv.e - paint.fx)      # paint space, focal-relative
        py = field(inv.b, inv.d, inv.f - paint.fy)
        s = _radial_param(paint, px, py)
        if s is None:
            return _solid(cols[-1], cover)
        if s.dtype == np.float64:
            # outside the cone of a focal circle not inside the end circle
            outside = np.isnan(s)
            if outside.any():
                cover = np.where(outside.reshape(cover.shape) if flat is None else
                                 _scatter(outside, flat, cover.shape), 0, cover).astype(_F32)
                s = np.where(outside, 0.0, s)
    s = _spread(s, paint.spread)
    if flat is None:
        return stop_colors(s, offs, cols, cover).astype(_F32, copy=False)
    out = np.zeros((h * w, 4), _F32)
    out[flat] = stop_colors(s, offs, cols, np.ravel(cover)[flat])
    return out.reshape(h, w, 4)


def _scatter(values, flat, shape):
    """(h, w) bool array: ``values`` at the flat indices ``flat``, False
    elsewhere."""
    out = np.zeros(shape[0] * shape[1], bool)
    out[flat] = values
    return out.reshape(shape)


def mesh_colors(paint, mask, t, tolerance):
    """Premultiplied colours of a mesh gradient over a coverage mask's
    window, multiplied by the coverage (None: nothing painted).

    Parameters
    ----------
    paint : raster.tree.MeshGradient
        In the painted node's user space.
    mask : raster.pixels.scan.Mask
    t : Affine
        User units -> device pixels.
    tolerance : float
        Device pixels: each painted pixel shows the colour of a mesh point
        within it of its centre (:func:`raster.pixels.mesh.mesh_gradient`).
    """
    cover = np.asarray(mask.data, _F32)
    h, w = cover.shape
    if h == 0 or w == 0 or not cover.any():
        return None
    from ..pixels.mesh import mesh_gradient      # loaded by the first mesh gradient
    m = t @ paint.transform
    dev = m.apply(np.asarray(paint.patches).reshape(-1, 2)).reshape(-1, 12, 2)
    col = mesh_gradient(dev, paint.colors, (int(mask.x0), int(mask.y0), w, h),
                        interpolation=paint.interpolation.value, shape=paint.shape,
                        tolerance=tolerance)
    col *= cover[..., None]
    return col


def _solid(color, cover):
    """(h, w, 4) float32: one straight RGBA colour premultiplied, times the
    (h, w) float32 coverage."""
    c = np.asarray(color, np.float64)
    pm = np.array([c[0] * c[3], c[1] * c[3], c[2] * c[3], c[3]], _F32)
    return cover[..., None] * pm


def stop_colors(s, offs, cols, cover=None, exact=None):
    """Premultiplied colours of gradient parameters ``s`` (after the spread
    method, in [0, 1]), optionally times a coverage.

    The colour is interpolated linearly (straight alpha) between stops and
    premultiplied afterwards.  At an offset shared by several stops (a hard
    stop) the colour jumps from the first of them to the last; s at or
    before the first offset takes the first stop's colour, at or after the
    last offset the last stop's.

    Two stops (one ramp, the usual gradient) are evaluated in closed form,
    exactly; more through a lookup table within 1/255 of exact (see
    :func:`color_lut`), or per stop interval when no table fits.

    Parameters
    ----------
    s : (...) float32 or float64 ndarray
        Gradient parameters in [0, 1].
    offs : (K,) float64 ndarray
        Non-decreasing stop offsets in [0, 1], K >= 1.
    cols : (K, 4) float64 ndarray
        Straight RGBA stop colours in [0, 1].
    cover : (...) float32 ndarray or None
        Coverage to multiply the colours by (same shape as ``s``).
    exact : bool or None
        True: interpolate per stop interval; False: use the lookup table
        (an error if none within 1/255 fits); None: choose as above.

    Returns
    -------
    (..., 4) ndarray, float32 (float64 for float64 ``s`` without a table)
        Premultiplied RGBA (a new array).
    """
    if exact is None and len(offs) == 2 and offs[1] > offs[0]:
        return _ramp(s, offs, cols, cover)
    lut = None
    if not exact:
        lut = color_lut(offs, cols)
        if lut is None and exact is False:
            raise ValueError('no lookup table of at most %d entries fits these stops' % _LUT_MAX)
    if lut is not None:
        n = len(lut)
        idx = np.multiply(s, _F32(n - 1), dtype=_F32)
        idx += _F32(0.5)
        with np.errstate(invalid='ignore'):
            idx = idx.astype(np.intp)
        col = np.take(lut, idx, axis=0, mode='clip')
    else:
        col = _premultiply(_interp_exact(s, offs, cols))
    if cover is not None:
        col *= cover[..., None]
    return col


def _ramp(s, offs, cols, cover):
    """:func:`stop_colors` of two stops with offs[0] < offs[1], exactly.

    With u = (clip(s, o0, o1) - o0) / (o1 - o0), the straight colour is
    c0 + u dc and the premultiplied one (c0 + u dc)(a0 + u da) =
    A + u B + u^2 C, evaluated one channel at a time with the coverage
    folded in (no (..., 4) temporaries)."""
    dt = _F32 if s.dtype == _F32 else np.float64
    o0, o1 = offs
    c0, c1 = cols
    dc = c1 - c0
    a0, da = c0[3], dc[3]
    coef_a = np.append(c0[:3] * a0, a0)
    coef_b = np.append(dc[:3] * a0 + c0[:3] * da, da)
    coef_c = np.append(dc[:3] * da, 0.0)
    u = np.clip(s, o0, o1).astype(dt, copy=False)
    u -= dt(o0)
    u *= dt(1.0 / (o1 - o0))
    k = u if cover is None else u * cover            # u * coverage
    kk = k * u if coef_c.any() else None             # u^2 * coverage
    out = np.empty(s.shape + (4,), dt)
    tmp = np.empty(s.shape, dt)
    for ch in range(4):
        o = out[..., ch]
        np.multiply(k, dt(coef_b[ch]), out=o)
        if kk is not None and coef_c[ch] != 0:
            o += np.multiply(kk, dt(coef_c[ch]), out=tmp)
        if cover is None:
            o += dt(coef_a[ch])
        else:
            o += np.multiply(cover, dt(coef_a[ch]), out=tmp)
    return out


def color_lut(offs, cols):
    """Premultiplied colour table of a stop list over s in [0, 1].

    Entry k holds the exact colour at ``s = k / (N - 1)``; looking up the
    nearest entry is within 1/255 of the exact colour because N is chosen
    from the steepest premultiplied ramp.  None when that needs more than
    ``_LUT_MAX`` entries or when a hard stop (offsets repeated with
    different colours) makes the colour jump.

    Returns
    -------
    (N, 4) float32 ndarray or None
    """
    span = np.diff(offs)
    dc = np.abs(np.diff(cols, axis=0))
    jump = dc.max(axis=1) > 0
    if np.any((span <= 0) & jump):
        return None
    ok = span > 0
    if not np.any(ok):
        steep = 0.0
    else:
        # |d(c * a)/ds| <= |dc/ds| + |da/ds| for c, a in [0, 1]
        steep = float(((dc[ok, :3].max(axis=1) + dc[ok, 3]) / span[ok]).max())
    n = max(_LUT_MIN, int(math.ceil(0.5 * 255.0 * steep / _LUT_ERR)) + 1)
    if n > _LUT_MAX:
        return None
    grid = np.linspace(0.0, 1.0, n)
    return _premultiply(_interp_exact(grid, offs, cols)).astype(_F32)


def _interp_exact(s, offs, cols):
    """Straight colours of parameters ``s`` ((...) float) interpolated per
    stop interval: (..., 4) of the dtype of ``s`` when it is float32, else
    float64 (see :func:`stop_colors` for the rules at hard stops)."""
    dt = _F32 if np.asarray(s).dtype == _F32 else np.float64
    k = len(offs)
    # interval table, row q: pixels with q offsets <= s (q = 0: before the
    # first offset; q = K: after the last); colour = base + (s - o) * slope
    o = np.zeros(k + 1)
    base = np.empty((k + 1, 4))
    slope = np.zeros((k + 1, 4))
    base[0], base[k] = cols[0], cols[-1]
    span = offs[1:] - offs[:-1]
    live = span > 0
    o[1:k] = offs[:-1]
    base[1:k] = cols[:-1]
    slope[1:k][live] = (cols[1:] - cols[:-1])[live] / span[live, None]
    table = np.concatenate([base, slope], axis=1).astype(dt)
    s = np.asarray(s, dt)
    q = np.searchsorted(offs.astype(dt), s, side='right')
    q[s <= dt(offs[0])] = 0
    bs = np.take(table, q, axis=0)
    d = s - np.take(o.astype(dt), q)
    col = bs[..., 4:]
    col *= d[..., None]
    col += bs[..., :4]
    return col


def _premultiply(col):
    """Premultiply straight RGBA ((..., 4) float) in place; returns it."""
    col[..., :3] *= col[..., 3:4]
    return col


def _spread(s, mode):
    """Apply the spread method to ``s`` (float ndarray), in place when
    possible; returns s in [0, 1] of the same dtype."""
    if mode == 'repeat':
        s -= np.floor(s)
        return s
    if mode == 'reflect':
        # |((s + 1) mod 2) - 1|: a triangle wave, 0 at even s, 1 at odd s
        s += s.dtype.type(1.0)
        np.mod(s, s.dtype.type(2.0), out=s)
        s -= s.dtype.type(1.0)
        np.abs(s, out=s)
        return s
    return np.clip(s, 0.0, 1.0, out=s)


def _radial_param(p, px, py):
    """Gradient parameter of a two-point conical gradient: focal circle
    (fx, fy, fr) at s = 0 to the end circle (cx, cy, r) at s = 1; the
    largest s with a positive radius.

    Parameters
    ----------
    p : RadialGradient
    px, py : (...) float32 or float64 ndarrays
        Paint-space positions relative to the focal point (fx, fy); may be
        overwritten.

    Returns
    -------
    (...) float ndarray or None
        None when the end radius is not positive; NaN where the point is on
        no circle of positive radius (outside the cone that a focal circle
        not inside the end circle makes: transparent, SVG 2 and canvas).
    """
    cx, cy, r, fx, fy, fr = p.cx, p.cy, p.r, p.fx, p.fy, p.fr
    if r <= 0:
        return None
    cdx, cdy, dr = cx - fx, cy - fy, r - fr
    a = cdx * cdx + cdy * cdy - dr * dr
    if fr == 0 and a < -1e-9:
        # the focal point strictly inside the end circle (the usual case):
        # one root is >= 0, the other <= 0, and the discriminant >= 0
        if cdx == 0 and cdy == 0:
            s = np.hypot(px, py, out=px)
            s *= s.dtype.type(1.0 / r)
            return s
        ft = px.dtype.type
        b = px * ft(cdx)
        b += py * ft(cdy)
        px *= px
        py *= py
        px += py                              # c = |p|^2
        px *= ft(-a)
        px += b * b                           # b^2 - a c
        np.sqrt(px, out=px)
        b -= px
        b *= ft(1.0 / a)                      # (b - sqrt(b^2 - a c)) / a
        return b
    px = np.asarray(px, np.float64)
    py = np.asarray(py, np.float64)
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
        return np.where(ok, s, np.nan)
    # the focal circle not inside the end circle: the gradient is a cone
    # touching both circles, and a point on no circle of the cone (or only
    # on circles of negative radius) is left transparent (NaN)
    disc = b * b - a * c
    sq = np.sqrt(np.maximum(disc, 0.0))
    s1 = (b + sq) / a
    s2 = (b - sq) / a
    hi = np.maximum(s1, s2)
    lo = np.minimum(s1, s2)
    s = np.where(fr + hi * dr >= 0, hi, lo)
    return np.where((disc >= 0) & (fr + s * dr >= 0), s, np.nan)


# ---------------------------------------------------------------------------
# Raster images
# ---------------------------------------------------------------------------

#: Pillow filters by name (``PIL.Image.Resampling`` members, looked up
#: when Pillow is loaded, with the first image), and the source margin
#: (pixels) each one reads around a sample position.  resvg draws smooth
#: images with a bicubic (Mitchell) filter; Pillow has only the sharper
#: Catmull-Rom-like cubic, which lands further from the suite's references
#: than bilinear does.
_FILTERS = {'nearest': ('NEAREST', 1), 'bilinear': ('BILINEAR', 2)}
#: Largest edge padding (source pixels) of a resampled crop; only images
#: drawn more than this many times smaller than their size could show it.
_MAX_PAD = 512
#: Shift (image pixels) of nearest-neighbour positions, see resample_window.
_NUDGE = 1e-7


def draw_pixels(n, t, canvas, tol):
    """Draw a raster image node onto a canvas.

    The image rectangle (and the node's clip rectangle) is covered with
    exact-area anti-aliasing; inside, the image is resampled (bilinear when
    ``n.smooth``, else nearest) with its edge pixels extended outwards, over
    the covered window only (see :func:`resample_window`), in strips of
    rows of about :data:`STRIP_PIXELS` pixels.  When both rectangles map to
    axis-aligned device rectangles (no rotation or skew), their coverage is
    separable (a pixel's area inside is the product of its x and y
    overlaps) and only the partly covered edge rows and columns of each
    strip are multiplied, so no window-sized mask is held; other transforms
    use :func:`raster.pixels.scan.path_coverage` masks.

    Parameters
    ----------
    n : ImageNode
        ``n.pixels`` is (H, W, 4) uint8 straight RGBA; ``n.transform`` maps
        image pixels to user units.
    t : Affine
        User units -> device pixels.
    canvas : raster.pixels.canvas.Canvas
    tol : float
        Flattening tolerance (device pixels) of the covered region.
    """
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
    clip_rect = None
    if n.clip is not None:
        x, y, w, h = n.clip
        clip_rect = np.array([(x, y), (x + w, y), (x + w, y + h), (x, y + h)], float)
    rects = [_device_rect(img_rect, t)]
    if clip_rect is not None:
        rects.append(_device_rect(clip_rect, t))
    if all(r is not None for r in rects):
        # axis-aligned in device space: coverage separably, strip by strip
        win = _rects_window(rects, canvas.width, canvas.height)
        if win is None:
            return
        x0, y0, w, h = win
        axes = [(pixel_overlaps(r[0], r[2], x0, w), pixel_overlaps(r[1], r[3], y0, h))
                for r in rects]
        cov = None
    else:
        cov, x0, y0 = _path_window(img_rect, clip_rect, t, canvas, tol)
        if cov is None:
            return
        h, w = cov.shape
    limits.spend_work(_IMAGE_PASSES * w * h, 'an image')
    flt = 'bilinear' if n.smooth else 'nearest'
    step = max(1, STRIP_PIXELS // w)
    for r0 in range(0, h, step):        # strips of rows: bounded temporaries
        rows = min(step, h - r0)
        col = resample_window(pix, inv, x0, y0 + r0, w, rows, flt)
        if col is None:
            continue
        if cov is not None:
            _apply_coverage(col, cov[r0:r0 + rows])
        else:
            _apply_rect_coverage(col, axes, r0)
        canvas.composite(col, x0, y0 + r0, n.opacity)


def _device_rect(pts, t):
    """The device rectangle (x0, y0, x1, y1), floats, of a user-space
    rectangle given by its four corners ``pts`` ((4, 2) float64, in path
    order) when ``t`` maps it to one with axis-aligned edges; else None.
    The corners are mapped with the arithmetic of
    :func:`raster.geometry.flattening.flatten`; non-finite ones are left
    to :func:`path_coverage` (which raises), too large ones raise as there."""
    d = pts if t.is_identity else t.apply(pts)
    if not np.all(np.isfinite(d)):
        return None
    x, y = d[:, 0], d[:, 1]
    if (y[0] == y[1] and y[2] == y[3] and x[0] == x[3] and x[1] == x[2]) or \
            (x[0] == x[1] and x[2] == x[3] and y[0] == y[3] and y[1] == y[2]):
        limits.check_coord(float(np.abs(d).max()), 'edge')
        return float(x.min()), float(y.min()), float(x.max()), float(y.max())
    return None


def _rects_window(rects, width, height):
    """The pixel window (x0, y0, w, h) that :func:`path_coverage` gives each
    device rectangle (x0, y0, x1, y1), intersected (its pixel bounding box
    clipped to the canvas); None when it is empty or a rectangle has no
    area."""
    X0, Y0, X1, Y1 = 0, 0, width, height
    for rx0, ry0, rx1, ry1 in rects:
        if not (rx1 > rx0 and ry1 > ry0):
            return None
        X0, Y0 = max(X0, math.floor(rx0)), max(Y0, math.floor(ry0))
        X1, Y1 = min(X1, math.ceil(rx1)), min(Y1, math.ceil(ry1))
    if X1 <= X0 or Y1 <= Y0:
        return None
    return X0, Y0, X1 - X0, Y1 - Y0


def _strip_coverage(axes, rows, cols=slice(None)):
    """(len(rows), len(cols)) float32 coverage of some pixels of the window
    (``rows`` an index array, ``cols`` a slice or index array): the exact
    area of each pixel inside each axis-aligned rectangle (the product of
    its x and y overlaps, ``axes`` one (cx, cy) float64 pair per rectangle),
    rounded to float32 per rectangle and multiplied, as the masks of
    :func:`path_coverage` would be."""
    out = None
    for cx, cy in axes:
        x = cx[cols]
        k = np.empty((len(rows), len(x)), _F32)
        np.multiply(cy[rows, None], x[None, :], out=k, casting='same_kind')
        if out is None:
            out = k
        else:
            out *= k
    return out


def _apply_rect_coverage(col, axes, r0):
    """Multiply premultiplied colours (h, w, 4) float32 in place by the
    coverage of rows r0 .. r0 + h of the window, given separably (``axes``,
    see :func:`_strip_coverage`), as :func:`_apply_coverage` would with the
    whole (h, w) mask: only partly covered pixels are touched, the rows and
    columns where some rectangle's overlap is below 1 (its edges)."""
    h = col.shape[0]
    part_rows = np.zeros(h, bool)
    part_cols = np.zeros(col.shape[1], bool)
    for cx, cy in axes:
        part_rows |= cy[r0:r0 + h] < 1
        part_cols |= cx < 1
    rows = np.flatnonzero(part_rows)
    cols = np.flatnonzero(part_cols)
    if len(rows):
        col[rows] *= _strip_coverage(axes, rows + r0)[..., None]
    if len(cols):
        full = np.flatnonzero(~part_rows)
        if len(full) == h:
            col[:, cols] *= _strip_coverage(axes, [r0], cols)[..., None]
        elif len(full):
            sub = np.ix_(full, cols)
            col[sub] *= _strip_coverage(axes, [r0 + full[0]], cols)[..., None]


def _path_window(img_rect, clip_rect, t, canvas, tol):
    """Coverage (h, w) float32 of the image rectangle (user-space corners
    ``img_rect``) times that of the clip rectangle (corners or None), by
    :func:`path_coverage`, over the intersection of their windows only (no
    canvas-sized arrays); returns (cov, x0, y0), cov None when empty."""
    m = path_coverage(Path.polygon(img_rect), canvas.width, canvas.height, 'nonzero', True,
                      tolerance=tol, transform=t)
    if m is None:
        return None, 0, 0
    cov, x0, y0 = m.data, m.x0, m.y0
    if clip_rect is not None:
        cm = path_coverage(Path.polygon(clip_rect), canvas.width, canvas.height, 'nonzero',
                           True, tolerance=tol, transform=t)
        if cm is None:
            return None, 0, 0
        ax0, ay0 = max(m.x0, cm.x0), max(m.y0, cm.y0)
        ax1 = min(m.x0 + cov.shape[1], cm.x0 + cm.data.shape[1])
        ay1 = min(m.y0 + cov.shape[0], cm.y0 + cm.data.shape[0])
        if ax1 <= ax0 or ay1 <= ay0:
            return None, 0, 0
        cov = (cov[ay0 - m.y0:ay1 - m.y0, ax0 - m.x0:ax1 - m.x0]
               * cm.data[ay0 - cm.y0:ay1 - cm.y0, ax0 - cm.x0:ax1 - cm.x0])
        x0, y0 = ax0, ay0
    return cov, x0, y0


def _apply_coverage(col, cov):
    """Multiply premultiplied colours (h, w, 4) float32 in place by the
    coverage (h, w) float32; when few pixels are partly covered (an image
    rectangle: only its edges), only those are touched."""
    part = np.flatnonzero(cov < 1)
    if 8 * len(part) < cov.size:
        flat = col.reshape(-1, 4)
        flat[part] *= np.ravel(cov)[part][:, None]
    else:
        col *= cov[..., None]


def _premultiply8(rgba):
    """Premultiplied copy of straight (h, w, 4) uint8 RGBA, rounded as
    ``round(c * a / 255)``; the same array when it is opaque."""
    a = rgba[..., 3]
    if a.min() == 255:
        return rgba
    out = np.empty_like(rgba)
    c = rgba[..., :3].astype(np.uint16)
    c *= a[..., None]
    c += 127
    c //= 255
    out[..., :3] = c
    out[..., 3] = a
    return out


def resample_window(pix, inv, x0, y0, w, h, filter='bilinear'):
    """Resample an image onto a window of device pixels.

    Device pixel (y0 + i, x0 + j) of the window is the image sampled at the
    image-space position of its centre, ``inv((x0 + j + 0.5, y0 + i + 0.5))``
    (image pixel (r, c) centred at (c + 0.5, r + 0.5)), with the image's edge
    pixels extended outwards (no dark fringe at the image border).  Only the
    part of the image the window reads is converted; Pillow does the
    interpolation in C on the premultiplied 8-bit image (``Image.resize``
    with a source box when the transform only scales, flips or swaps the
    axes, ``Image.transform`` otherwise).  Nearest neighbour picks straight
    pixels and premultiplies them in float, exactly.

    Parameters
    ----------
    pix : (H, W, 4) uint8 ndarray
        Straight RGBA image.
    inv : Affine
        Device -> image pixel coordinates.
    x0, y0, w, h : int
        The device window.
    filter : {'nearest', 'bilinear'}

    Returns
    -------
    (h, w, 4) float32 ndarray or None
        Premultiplied RGBA in [0, 1]; None when the window is empty.
    """
    from PIL import Image
    resample, margin = _FILTERS[filter]
    resample = Image.Resampling[resample]
    ih, iw = pix.shape[:2]
    if w <= 0 or h <= 0:
        return None
    # window -> image: u = a*xw + c*yw + e, v = b*xw + d*yw + f, where
    # (xw, yw) are window coordinates (pixel centres at j + 0.5, i + 0.5)
    a, b, c, d = inv.a, inv.b, inv.c, inv.d
    e = a * x0 + c * y0 + inv.e
    f = b * x0 + d * y0 + inv.f
    # the window reaches at most one device pixel outside the image (the
    # centre of a partly covered pixel, half a pixel): pad the image by that
    # much in image pixels, plus the filter's reach
    pad_u = min(int(math.ceil(abs(a) + abs(c))) + margin, _MAX_PAD)
    pad_v = min(int(math.ceil(abs(b) + abs(d))) + margin, _MAX_PAD)
    us = [e, e + a * w, e + c * h, e + a * w + c * h]
    vs = [f, f + b * w, f + d * h, f + b * w + d * h]
    cu0 = max(int(math.floor(min(us))) - margin, -pad_u)
    cu1 = min(int(math.ceil(max(us))) + margin, iw + pad_u)
    cv0 = max(int(math.floor(min(vs))) - margin, -pad_v)
    cv1 = min(int(math.ceil(max(vs))) + margin, ih + pad_v)
    if cu1 <= cu0 or cv1 <= cv0:
        return None
    # the crop, edge pixels repeated outside the image
    crop = pix
    if cv0 != 0 or cv1 != ih:
        crop = crop.take(np.clip(np.arange(cv0, cv1), 0, ih - 1), axis=0)
    if cu0 != 0 or cu1 != iw:
        crop = crop.take(np.clip(np.arange(cu0, cu1), 0, iw - 1), axis=1)
    if filter != 'nearest':
        crop = _premultiply8(np.ascontiguousarray(crop))
    e -= cu0
    f -= cv0
    if filter == 'nearest':
        # a centre exactly on a pixel boundary belongs to the pixel after it
        # (floor); Pillow's own arithmetic may land a hair before it
        e += _NUDGE
        f += _NUDGE
    # Image.resize (separable, faster) filters a downscale over the whole
    # footprint of a device pixel; resvg and Image.transform sample at the
    # pixel centre, which matches the references better: resize magnifies
    # only.  Its source box is single precision, which is harmless for
    # bilinear but could move nearest-neighbour picks: nearest transforms.
    if filter != 'nearest' and (b == 0 and c == 0 or a == 0 and d == 0) \
            and max(abs(a), abs(b), abs(c), abs(d)) <= 1.0 \
            and _box_inside(a, b, c, d, e, f, w, h, crop):
        if a == 0:
            # the axes swap: transpose the crop, then it only scales
            crop = np.ascontiguousarray(crop.transpose(1, 0, 2))
            a, b, c, d, e, f = b, a, d, c, f, e
        if a < 0:
            crop = crop[:, ::-1]
            a, e = -a, crop.shape[1] - e
        if d < 0:
            crop = crop[::-1]
            d, f = -d, crop.shape[0] - f
        im = _pil(crop, 'RGBa')
        out = im.resize((w, h), resample, box=(e, f, e + a * w, f + d * h))
    else:
        im = _pil(crop, 'RGBA' if filter == 'nearest' else 'RGBa')
        out = im.transform((w, h), Image.Transform.AFFINE, (a, c, e, b, d, f), resample)
    col = np.multiply(np.asarray(out), _F32(1.0 / 255.0), dtype=_F32)
    if filter == 'nearest':
        col[..., :3] *= col[..., 3:4]
    return col


def _box_inside(a, b, c, d, e, f, w, h, crop):
    """True when the window's image-space box (whole window, not only the
    pixel centres) lies inside the crop, as ``Image.resize`` requires."""
    ch, cw = crop.shape[:2]
    us = (e, e + a * w + c * h)
    vs = (f, f + b * w + d * h)
    return min(us) >= 0 and max(us) <= cw and min(vs) >= 0 and max(vs) <= ch


def _pil(rgba, mode):
    """A Pillow image of (h, w, 4) uint8 pixels: ``mode`` 'RGBa' for
    premultiplied ones, 'RGBA' for straight ones (nearest only: Pillow
    premultiplies 'RGBA' itself for the other filters)."""
    from PIL import Image
    rgba = np.ascontiguousarray(rgba)
    return Image.frombuffer(mode, (rgba.shape[1], rgba.shape[0]), rgba, 'raw', mode, 0, 1)


def sample(img, u, v, smooth=True, wrap=False):
    """Sample an image at continuous pixel coordinates.

    Parameters
    ----------
    img : (H, W, 4) float ndarray
        Premultiplied RGBA; pixel (i, j) is centred at (j + 0.5, i + 0.5).
    u, v : (...) float ndarrays
        Positions (u right, v down), same shape.
    smooth : bool
        Bilinear when True, else nearest.
    wrap : bool
        Repeat the image (tiling); otherwise positions clamp to the edge
        pixels.

    Returns
    -------
    (..., 4) ndarray of img's dtype
    """
    img = np.asarray(img)
    ih, iw = img.shape[:2]
    flat = np.ascontiguousarray(img).reshape(ih * iw, img.shape[2])
    u = np.asarray(u, np.float64)
    v = np.asarray(v, np.float64)
    if not smooth:
        ui = _cell(np.floor(u), iw, wrap)
        vi = _cell(np.floor(v), ih, wrap)
        vi *= iw
        vi += ui
        return np.take(flat, vi, axis=0)
    fu = u - 0.5
    fv = v - 0.5
    u0 = np.floor(fu)
    v0 = np.floor(fv)
    au = (fu - u0).astype(img.dtype)[..., None]
    av = (fv - v0).astype(img.dtype)[..., None]
    i0 = _cell(u0, iw, wrap)
    j0 = _cell(v0, ih, wrap)
    if wrap:
        i1 = _next_cell(i0, iw)
        j1 = _next_cell(j0, ih)
    else:
        u0 += 1.0
        v0 += 1.0
        i1 = _cell(u0, iw, False)
        j1 = _cell(v0, ih, False)
    j0 *= iw
    j1 *= iw
    top = np.take(flat, j0 + i0, axis=0)
    right = np.take(flat, j0 + i1, axis=0)
    right -= top
    right *= au
    top += right
    bot = np.take(flat, j1 + i0, axis=0)
    right = np.take(flat, j1 + i1, axis=0)
    right -= bot
    right *= au
    bot += right
    bot -= top
    bot *= av
    top += bot
    return top


def _cell(k, n, wrap):
    """Integer cells ((...) intp) of floored positions ``k`` on an axis of
    ``n`` pixels: wrapped, or clamped to [0, n - 1]."""
    if wrap:
        # k - floor(k / n) * n: exact for integral k (faster than np.mod)
        q = k / n
        np.floor(q, out=q)
        q *= -n
        q += k
        return q.astype(np.intp)
    return np.clip(k, 0, n - 1).astype(np.intp)


def _next_cell(i, n):
    """The cell after ``i`` ((...) intp in [0, n - 1]) on a wrapping axis
    of ``n`` pixels."""
    j = i + 1
    j[j == n] = 0
    return j
