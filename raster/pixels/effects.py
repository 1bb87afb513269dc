"""Filter-effect pixel operations on premultiplied float32 RGBA images.

Images are ``(H, W, 4)`` float32 arrays of premultiplied RGBA, row 0 at
the top; pixel ``(i, j)`` covers ``[j, j+1] x [i, i+1]``.  Lengths
(deviations, offsets, radii, scales) are device pixels.  Each function
works on the whole image it is given; the renderer
(:mod:`raster.renderer.filters`) decides regions and colour spaces.

:class:`FilterImage` is an intermediate result that can stand for an image
painted in one colour by that colour and an alpha channel, so colour
conversions change three numbers and blurs and offsets move one channel.

>>> img = np.zeros((1, 5, 4), np.float32); img[0, 1] = (1, 0, 0, 1)
>>> offset(img, 2, 0)[0, :, 3].tolist()
[0.0, 0.0, 0.0, 1.0, 0.0]
"""

import math

import numpy as np

from ..errors import RasterError

__all__ = ['FilterError', 'FilterImage', 'gaussian_blur', 'box_blur', 'box_sigma', 'blur_plans',
           'blur_image', 'blur_array', 'offset', 'shift', 'color_matrix', 'component_transfer',
           'morphology', 'convolve', 'lighting', 'turbulence', 'displace', 'tile',
           'srgb_to_linear', 'linear_to_srgb', 'premultiply', 'unpremultiply', 'solid_image',
           'convert_space', 'check_image', 'check_finite', 'check_tolerance',
           'DEFAULT_TOLERANCE', 'MAX_OCTAVES', 'blur_cost']

#: Default tolerance (device pixels) for explicit-accuracy blurs (see
#: :func:`gaussian_blur`; the renderer follows the specification's box
#: approximation instead, as resvg).
DEFAULT_TOLERANCE = 0.25


class FilterError(RasterError, ValueError):
    """Invalid input to a filter operation (bad image shape, non-finite
    parameter)."""


def lighting(alpha, light, color, surface, k, exponent, specular, t=None):
    """feDiffuseLighting / feSpecularLighting.

    Parameters
    ----------
    alpha : (H, W) float32 ndarray
        The bump map (input alpha).
    light : (kind, params)
        ``('distant', (azimuth, elevation))`` in degrees,
        ``('point', (x, y, z))`` or
        ``('spot', ((x, y, z), (px, py, pz), exponent, cone or None))``,
        positions in user units.
    color : 3 floats, the light colour (in the working colour space)
    surface, k, exponent : float
        surfaceScale, diffuse/specular constant, specular exponent.
    specular : bool
    t : raster.geometry.transform.Affine or None
        User space to pixels for light positions (None: identity).

    Returns
    -------
    (H, W, 4) float32 ndarray, premultiplied
    """
    a = np.asarray(alpha, np.float64)
    h, w = a.shape
    p = np.pad(a, 1, mode='edge')
    # Sobel normal of the surface z = surface * alpha
    nx = -surface / 4.0 * ((p[:-2, 2:] + 2 * p[1:-1, 2:] + p[2:, 2:])
                           - (p[:-2, :-2] + 2 * p[1:-1, :-2] + p[2:, :-2]))
    ny = -surface / 4.0 * ((p[2:, :-2] + 2 * p[2:, 1:-1] + p[2:, 2:])
                           - (p[:-2, :-2] + 2 * p[:-2, 1:-1] + p[:-2, 2:]))
    norm = np.sqrt(nx * nx + ny * ny + 1.0)
    n = np.stack([nx / norm, ny / norm, 1.0 / norm], -1)
    col = np.broadcast_to(np.asarray(color, np.float64), (h, w, 3)).copy()
    kind, prm = light
    if kind == 'distant':
        az, el = math.radians(prm[0]), math.radians(prm[1])
        lv = np.broadcast_to(np.array([math.cos(az) * math.cos(el),
                                       math.sin(az) * math.cos(el), math.sin(el)]), (h, w, 3))
    else:
        pos = prm if kind == 'point' else prm[0]
        sc = 1.0
        if t is not None:
            x, y = t.apply(np.array([[pos[0], pos[1]]]))[0]
            sc = math.sqrt(abs(t.a * t.d - t.b * t.c))
        else:
            x, y = pos[0], pos[1]
        z = pos[2] * sc
        jj, ii = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
        lv = np.stack([x - jj, y - ii, z - surface * a], -1)
        lv = lv / np.maximum(np.linalg.norm(lv, axis=-1, keepdims=True), 1e-12)
        if kind == 'spot':
            at, sexp, cone = prm[1], prm[2], prm[3]
            if t is not None:
                ax, ay = t.apply(np.array([[at[0], at[1]]]))[0]
            else:
                ax, ay = at[0], at[1]
            sv = np.array([ax - x, ay - y, at[2] * sc - z])
            sv = sv / max(np.linalg.norm(sv), 1e-12)
            minus_ls = -(lv @ sv)
            f = np.where(minus_ls > 0, np.power(np.maximum(minus_ls, 0.0), sexp), 0.0)
            if cone is not None:
                f = np.where(minus_ls >= math.cos(math.radians(abs(cone))), f, 0.0)
            col = col * f[..., None]
    if specular:
        hv = lv + np.array([0.0, 0.0, 1.0])
        hv = hv / np.maximum(np.linalg.norm(hv, axis=-1, keepdims=True), 1e-12)
        f = k * np.power(np.maximum((n * hv).sum(-1), 0.0), exponent)
        rgb = np.clip(col * f[..., None], 0.0, 1.0)
        out_a = rgb.max(-1)
        out = np.concatenate([rgb, out_a[..., None]], -1)    # already premultiplied-like
        return out.astype(np.float32)
    f = k * np.maximum((n * lv).sum(-1), 0.0)
    rgb = np.clip(col * f[..., None], 0.0, 1.0)
    return np.concatenate([rgb, np.ones((h, w, 1))], -1).astype(np.float32)


def displace(img, dmap, scale, xch=3, ych=3):
    """feDisplacementMap: ``out(x, y) = img(x + scale (X(x, y) - 0.5),
    y + scale (Y(x, y) - 0.5))`` with X, Y the channels ``xch``, ``ych``
    (0..3 = R, G, B, A) of the unpremultiplied ``dmap``; ``scale`` in
    device pixels; samples outside ``img`` are transparent (nearest pixel).
    """
    src, m = check_image(img), check_image(dmap, 'displacement map')
    check_finite(scale)
    c, a = unpremultiply(m)
    mm = np.concatenate([c, a], -1)
    h, w = src.shape[:2]
    jj, ii = np.meshgrid(np.arange(w), np.arange(h))
    u = np.floor(jj + 0.5 + scale * (mm[..., xch] - 0.5)).astype(np.int64)
    v = np.floor(ii + 0.5 + scale * (mm[..., ych] - 0.5)).astype(np.int64)
    ok = (u >= 0) & (u < w) & (v >= 0) & (v < h)
    out = src[np.clip(v, 0, h - 1), np.clip(u, 0, w - 1)]
    return np.where(ok[..., None], out, 0.0).astype(np.float32)


_PERLIN = {}


def _perlin_tables(seed):
    """Lattice selector (514,) int64 and gradients (4, 514, 2) float64 of
    the Filter Effects reference turbulence for ``seed`` (its Park-Miller
    generator; a sequential recurrence, run once per seed and cached)."""
    r = _PERLIN.get(seed)
    if r is not None:
        return r
    m, a, q, rr = 2147483647, 16807, 127773, 2836
    s = seed
    if s <= 0:
        s = -int(math.fmod(s, m - 1)) + 1           # C remainder (sign of s)
    if s > m - 1:
        s = m - 1

    def rnd(x):
        x = a * (x % q) - rr * (x // q)
        return x + m if x <= 0 else x

    lattice = list(range(256)) + [0] * 258
    grad = np.zeros((4, 514, 2))
    for k in range(4):
        for i in range(256):
            for j in range(2):
                s = rnd(s)
                grad[k, i, j] = ((s % 512) - 256) / 256.0
            n = math.hypot(grad[k, i, 0], grad[k, i, 1])
            if n > 0:
                grad[k, i] /= n
    for i in range(255, 0, -1):
        s = rnd(s)
        j = s % 256
        lattice[i], lattice[j] = lattice[j], lattice[i]
    for i in range(258):
        lattice[256 + i] = lattice[i]
        grad[:, 256 + i] = grad[:, i]
    r = (np.array(lattice, np.int64), grad)
    if len(_PERLIN) < 64:
        _PERLIN[seed] = r
    return r


#: Octaves of feTurbulence computed: octave ``k`` adds at most ``2**-k`` to
#: a channel, so the ones past the 32nd change no channel by more than
#: ``2**-31`` (far below 8-bit output and float32 resolution near 1) and a
#: ``numOctaves`` of 10**9 costs what 32 cost.
MAX_OCTAVES = 32

# Lattice coordinates at or beyond this are whole numbers; they are reduced
# modulo it (a multiple of the lattice's 256) before the integer cast.
_WRAP = float(2 ** 52)


def _lattice_coord(v):
    """``v + 4096`` with huge (or non-finite) values reduced so that the
    integer cast is exact: the lattice index (mod 256) and the fraction
    (0) of a whole number beyond 2**52 are kept; NaN and infinities are
    0."""
    t = v + 4096.0
    big = ~(np.abs(t) < _WRAP)
    if big.any():
        with np.errstate(invalid='ignore'):
            r = np.fmod(t[big], _WRAP)
        t = t.copy()
        t[big] = np.nan_to_num(r, nan=0.0, posinf=0.0, neginf=0.0)
    return t


def _noise2(lattice, grad, vx, vy, stitch=None):
    """Perlin noise of the four channels at points (vx, vy): (4, N).
    ``stitch`` is ``(width, wrap_x, height, wrap_y)`` of the reference's
    stitching: lattice columns at or past ``wrap_x`` are taken ``width``
    columns back (rows likewise), so the noise repeats across the tile."""
    t = _lattice_coord(vx)
    ix = t.astype(np.int64)
    rx0 = t - ix
    bx0, bx1 = ix, ix + 1
    t = _lattice_coord(vy)
    iy = t.astype(np.int64)
    ry0 = t - iy
    by0, by1 = iy, iy + 1
    if stitch is not None:
        sw, wx, sh, wy = stitch
        bx0 = np.where(bx0 >= wx, bx0 - sw, bx0)
        bx1 = np.where(bx1 >= wx, bx1 - sw, bx1)
        by0 = np.where(by0 >= wy, by0 - sh, by0)
        by1 = np.where(by1 >= wy, by1 - sh, by1)
    bx0, bx1, by0, by1 = bx0 & 255, bx1 & 255, by0 & 255, by1 & 255
    rx1, ry1 = rx0 - 1.0, ry0 - 1.0
    i, j = lattice[bx0], lattice[bx1]
    b00, b10 = lattice[i + by0], lattice[j + by0]
    b01, b11 = lattice[i + by1], lattice[j + by1]
    sx = rx0 * rx0 * (3.0 - 2.0 * rx0)
    sy = ry0 * ry0 * (3.0 - 2.0 * ry0)
    g = grad
    u = rx0 * g[:, b00, 0] + ry0 * g[:, b00, 1]
    v = rx1 * g[:, b10, 0] + ry0 * g[:, b10, 1]
    a_ = u + sx * (v - u)
    u = rx0 * g[:, b01, 0] + ry1 * g[:, b01, 1]
    v = rx1 * g[:, b11, 0] + ry1 * g[:, b11, 1]
    b_ = u + sx * (v - u)
    return a_ + sy * (b_ - a_)


def _stitch_frequency(f, size):
    """The base frequency nearest ``f`` (by ratio) that fits a whole
    number of lattice cells in ``size`` (Filter Effects' reference)."""
    if f == 0 or not size > 0:
        return f
    lo = math.floor(size * f) / size
    hi = math.ceil(size * f) / size
    return lo if lo > 0 and f / lo < hi / f else hi


def turbulence(x, y, base_freq, octaves, seed, fractal, tile=None):
    """feTurbulence at user-space points.

    Parameters
    ----------
    x, y : (H, W) float64 ndarrays, user-space coordinates
    base_freq : (fx, fy) floats >= 0
    octaves : int >= 0
        Only the first :data:`MAX_OCTAVES` are computed (the others are
        below the output's resolution).
    seed : int
    fractal : bool
        True for ``fractalNoise`` (``(sum + 1) / 2``), False for
        ``turbulence`` (sum of absolute values).
    tile : (x, y, w, h) or None
        ``stitchTiles="stitch"``: the tile (the primitive subregion, user
        units) that the noise repeats across without seams -- the base
        frequencies are adjusted to whole numbers of lattice cells per tile
        and the lattice wraps at the tile's far edges, octave by octave.

    Returns
    -------
    (H, W, 4) float32 ndarray, unpremultiplied RGBA in [0, 1]
    """
    lattice, grad = _perlin_tables(int(seed))
    h, w = x.shape
    fx, fy = float(base_freq[0]), float(base_freq[1])
    stitch = None
    if tile is not None:
        tx, ty, tw, th = (float(v) for v in tile)
        fx, fy = _stitch_frequency(fx, tw), _stitch_frequency(fy, th)
        sw, sh = tw * fx + 0.5, th * fy + 0.5
        edges = (sw, sh, tx * fx + 4096, ty * fy + 4096)
        if all(abs(v) < 2.0 ** 52 for v in edges):      # (hostile sizes: no stitching)
            sw, sh = int(sw), int(sh)
            stitch = (sw, int(edges[2] + sw), sh, int(edges[3] + sh))
    with np.errstate(over='ignore', invalid='ignore'):
        vx = x.ravel() * fx
        vy = y.ravel() * fy
    total = np.zeros((4, vx.size))
    ratio = 1.0
    for _ in range(min(int(octaves), MAX_OCTAVES)):     # loop over octaves, not pixels
        n = _noise2(lattice, grad, vx, vy, stitch)
        total += (n if fractal else np.abs(n)) / ratio
        with np.errstate(over='ignore'):
            vx, vy, ratio = vx * 2.0, vy * 2.0, ratio * 2.0
        if stitch is not None:
            sw, wx, sh, wy = stitch
            stitch = (2 * sw, 2 * wx - 4096, 2 * sh, 2 * wy - 4096)
    if fractal:
        total = (total + 1.0) / 2.0
    return np.clip(total.T.reshape(h, w, 4), 0.0, 1.0).astype(np.float32)


def convolve(img, kernel, divisor=None, bias=0.0, target=None, edge='duplicate',
             preserve_alpha=False):
    """feConvolveMatrix: ``out[y, x] = sum_ij src[y - ty + i, x - tx + j]
    * K[oy-1-i, ox-1-j] / divisor`` on premultiplied values, then ``bias``
    added to alpha and ``bias * alpha`` to the colours (as resvg); on
    unpremultiplied colour plus ``bias``, alpha kept, when
    ``preserve_alpha``.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied
    kernel : (oy, ox) array of floats
    divisor : float or None (None: the kernel's sum, or 1 when it is 0)
    bias : float
    target : (tx, ty) or None (None: the kernel's centre, rounded down)
    edge : {'duplicate', 'wrap', 'none'}
        How pixels outside the image are taken.

    >>> img = np.zeros((3, 3, 4), np.float32); img[1, 1] = 1
    >>> convolve(img, [[0, 0, 0], [0, 0, 1], [0, 0, 0]], edge='none')[1, 2].tolist()
    [1.0, 1.0, 1.0, 1.0]
    """
    src = check_image(img)
    k = np.asarray(kernel, np.float64)
    if k.ndim != 2 or k.size == 0 or not np.isfinite(k).all():
        raise FilterError('convolution kernel must be a finite non-empty 2-D array')
    oy, ox = k.shape
    if divisor is None:
        divisor = float(k.sum()) or 1.0
    check_finite(divisor, bias)
    if divisor == 0:
        raise FilterError('convolution divisor must not be 0')
    tx, ty = (ox // 2, oy // 2) if target is None else target
    if preserve_alpha:
        c, a = unpremultiply(src)
        work = c
    else:
        work = src
    h, w = src.shape[:2]
    mode = {'duplicate': 'edge', 'wrap': 'wrap', 'none': 'constant'}.get(edge)
    if mode is None:
        raise FilterError('unknown edge mode %r' % (edge,))
    pad = np.pad(work, ((ty, oy - 1 - ty), (tx, ox - 1 - tx), (0, 0)), mode=mode)
    acc = np.zeros(work.shape, np.float64)
    for i in range(oy):                   # loop over kernel taps, not pixels
        for j in range(ox):
            wgt = k[oy - 1 - i, ox - 1 - j]
            if wgt:
                acc += wgt * pad[i:i + h, j:j + w]
    acc = acc / divisor
    if preserve_alpha:
        acc += bias
    else:                                  # bias added to straight colour (resvg)
        acc[..., 3] += bias
        acc[..., :3] += bias * acc[..., 3:4]
    if preserve_alpha:
        return premultiply(np.clip(acc, 0, 1).astype(np.float32), a)
    out = np.clip(acc, 0.0, 1.0)
    out[..., :3] = np.minimum(out[..., :3], out[..., 3:4])
    return out.astype(np.float32)


def srgb_to_linear(c):
    """sRGB-encoded values in [0, 1] to linear light (any shape; float32
    arithmetic, returns float32).

    >>> round(float(srgb_to_linear(0.5)), 5)
    0.21404
    """
    c = np.asarray(c, np.float32)
    out = np.array(c * np.float32(1 / 1.055), ndmin=1)
    out += np.float32(0.055 / 1.055)
    np.maximum(out, np.float32(0.0), out=out)        # keeps power() real below -0.055
    np.power(out, np.float32(2.4), out=out)
    np.copyto(out, c * np.float32(1 / 12.92), where=c <= np.float32(0.04045))
    return out.reshape(c.shape)


def linear_to_srgb(c):
    """Linear-light values in [0, 1] to sRGB encoding (any shape; float32
    arithmetic, returns float32).

    >>> float(linear_to_srgb(srgb_to_linear(0.5)))  # doctest: +ELLIPSIS
    0.5...
    """
    c = np.asarray(c, np.float32)
    out = np.array(np.maximum(c, np.float32(0.0)), ndmin=1)
    np.power(out, np.float32(1 / 2.4), out=out)
    out *= np.float32(1.055)
    out -= np.float32(0.055)
    np.copyto(out, c * np.float32(12.92), where=c <= np.float32(0.0031308))
    return out.reshape(c.shape)


def unpremultiply(img):
    """Unpremultiply.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA

    Returns
    -------
    c : (H, W, 3) float32 ndarray
        Straight colour clipped to [0, 1]; 0 where alpha is not positive.
    a : (H, W, 1) float32 ndarray
        The alpha channel (a view of ``img``).
    """
    a = img[..., 3:4]
    inv = np.zeros(a.shape, np.float32)
    np.divide(np.float32(1.0), a, out=inv, where=a > 0)
    c = np.multiply(img[..., :3], inv)
    np.clip(c, 0.0, 1.0, out=c)
    return c, a


def premultiply(c, a):
    """(H, W, 4) float32 premultiplied RGBA from straight colour ``c``
    (H, W, 3) and alpha ``a`` (H, W, 1)."""
    out = np.empty(c.shape[:-1] + (4,), np.float32)
    np.multiply(c, a, out=out[..., :3])
    out[..., 3:4] = a
    return out


#: Largest deviation (premultiplied units) from ``colour x alpha`` for an
#: image to count as one solid colour (:func:`solid_colour`); float32
#: rounding of composited layers stays near 1e-7.
_SOLID_TOL = 1e-5


def solid_colour(img, tol=_SOLID_TOL):
    """The straight colour of an image painted in one colour, or None.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA
    tol : float
        Largest allowed ``|img[..., k] - c[k] img[..., 3]|``.

    Returns
    -------
    (3,) float32 ndarray or None
        ``c`` in [0, 1] with every pixel within ``tol`` of
        ``c x alpha`` (0 for a transparent image), or None.  Operations that
        are linear in the premultiplied values (blurs) then only need the
        alpha channel.
    """
    if img.size == 0:
        return np.zeros(3, np.float32)
    a = img[..., 3]
    i, j = np.unravel_index(int(np.argmax(a)), a.shape)
    am = float(a[i, j])
    c = np.zeros(3, np.float32)
    if am > 0:
        c = np.clip(img[i, j, :3] / np.float32(am), 0.0, 1.0).astype(np.float32)
    # a sparse sample rejects most non-solid images at a small cost
    for view in (img[::7, ::7], img):
        va = view[..., 3]
        for k in range(3):
            if c[k] == 0 and not view[..., k].any():
                continue                 # exactly 0: one cheap pass
            r = view[..., k] - va * c[k]
            if r.max() > tol or r.min() < -tol:
                return None
    return c


def solid_image(alpha, c):
    """(H, W, 4) float32 premultiplied image of straight colour ``c`` (3,)
    with ``alpha`` (H, W)."""
    out = np.empty(alpha.shape + (4,), np.float32)
    for k, v in enumerate(c):            # loop over 3 channels
        if v == 0:
            out[..., k] = 0.0
        else:
            np.multiply(alpha, np.float32(v), out=out[..., k])
    out[..., 3] = alpha
    return out


def nonzero_box(x):
    """Bounding rows and columns of the non-zero pixels of ``x``.

    Parameters
    ----------
    x : (H, W) or (H, W, C) ndarray
        A pixel is non-zero when any of its channels is.

    Returns
    -------
    (y0, y1, x0, x1) ints (half-open) or None when every pixel is zero
    """
    rows = np.flatnonzero(x.any(axis=tuple(range(1, x.ndim))))
    if rows.size == 0:
        return None
    cols = x[rows[0]:rows[-1] + 1].any(axis=0)
    if cols.ndim > 1:
        cols = cols.any(axis=1)
    cols = np.flatnonzero(cols)
    return int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1


class FilterImage:
    """An intermediate result of a filter chain.

    Either premultiplied pixels or, for content painted in one colour, a
    straight colour and an alpha channel: colour conversions then change
    three numbers, and blurs and offsets move one channel instead of four.

    Parameters
    ----------
    data : (H, W, 4) float32 ndarray or None
        Premultiplied RGBA (made from ``alpha`` and ``colour`` on first
        use when None).
    alpha : (H, W) float32 ndarray or None
        With ``colour``: the image is ``colour x alpha``.
    colour : (3,) float32 ndarray or None
        Straight colour in [0, 1]; None for a general image.
    """
    __slots__ = ('_data', 'alpha', 'colour')

    def __init__(self, data=None, alpha=None, colour=None):
        self._data, self.alpha, self.colour = data, alpha, colour

    @classmethod
    def of(cls, data):
        """Wrap pixels, recognising a solid colour (see :func:`solid_colour`)."""
        box = nonzero_box(data)
        if box is None:
            return cls(data, data[..., 3], np.zeros(3, np.float32))
        y0, y1, x0, x1 = box
        c = solid_colour(data[y0:y1, x0:x1])
        return cls(data, None if c is None else data[..., 3], c)

    @property
    def solid(self):
        return self.colour is not None

    @property
    def alpha_channel(self):
        """(H, W) float32 alpha (a view)."""
        return self.alpha if self.solid else self._data[..., 3]

    @property
    def data(self):
        """(H, W, 4) float32 premultiplied pixels."""
        if self._data is None:
            self._data = solid_image(self.alpha, self.colour)
        return self._data

    def clip(self, rect, in_place=False):
        """The image with everything outside ``rect`` (x0, y0, x1, y1)
        transparent; with ``in_place`` the pixels outside are zeroed in
        this image's arrays (which must not be read elsewhere) and the
        image is returned."""
        x0, y0, x1, y1 = rect
        src = self.alpha if self.solid else self.data
        if (x0, y0, x1, y1) == (0, 0, src.shape[1], src.shape[0]):
            return self
        if in_place:
            h, w = src.shape[:2]
            y0, y1 = min(max(y0, 0), h), min(max(y1, y0), h)
            x0, x1 = min(max(x0, 0), w), min(max(x1, x0), w)
            src[:y0] = 0.0
            src[y1:] = 0.0
            src[y0:y1, :x0] = 0.0
            src[y0:y1, x1:] = 0.0
            if self.solid:
                self._data = None        # (made again from the alpha channel)
            return self
        out = np.zeros(src.shape, np.float32)
        out[y0:y1, x0:x1] = src[y0:y1, x0:x1]
        return FilterImage(alpha=out, colour=self.colour) if self.solid else FilterImage(out)


#: Bytes of one work block of :func:`_by_rows` and :func:`_box_passes`:
#: blocks this small keep their temporaries in the processor's cache.
_BLOCK_BYTES = 1 << 19


def _by_rows(fn, img, out=None):
    """``fn`` (a per-pixel map of (h, W, 4) float32 blocks to (h, W, 4)
    float32) applied to cache-sized blocks of rows of ``img`` (H, W, 4):
    its temporaries stay small.  The result goes to ``out`` ((H, W, 4)
    float32, any strides: e.g. a window of a larger array) if given."""
    h, w = img.shape[:2]
    if out is None:
        out = np.empty((h, w, 4), np.float32)
    step = max(1, _BLOCK_BYTES // (16 * max(w, 1)))
    for y in range(0, h, step):          # loop over blocks of rows
        out[y:y + step] = fn(img[y:y + step])
    return out


def _convert_pixels(img, fn, in_place=False):
    """Apply the transfer ``fn`` to the straight colour of the
    premultiplied ``img`` (H, W, 4); only the bounding box of the visible
    pixels is worked on (transparent pixels stay transparent).  With
    ``in_place`` the result overwrites ``img`` (a block of rows at a time,
    each block converted before it is written: the same values) and is
    ``img``."""
    box = nonzero_box(img)
    if box is None:
        return img if in_place else np.zeros_like(img)
    y0, y1, x0, x1 = box

    def block(b):
        c, a = unpremultiply(b)
        return premultiply(fn(c), a)

    if in_place:
        # outside the box the pixels are 0 already
        _by_rows(block, img[y0:y1, x0:x1], img[y0:y1, x0:x1])
        return img
    if (y1 - y0, x1 - x0) == img.shape[:2]:
        return _by_rows(block, img)
    # written in place into the zero image: no box-sized intermediate
    out = np.zeros_like(img)
    _by_rows(block, img[y0:y1, x0:x1], out[y0:y1, x0:x1])
    return out


def convert_space(img, linear_from, linear_to, in_place=False):
    """An :class:`FilterImage` converted from linearRGB (``linear_from`` True)
    or sRGB to the other space (``img`` itself when they agree).  With
    ``in_place`` the pixels of ``img`` (when it is not solid) are
    overwritten by the result instead of copied: for an input nothing
    reads again."""
    if linear_from == linear_to:
        return img
    fn = srgb_to_linear if linear_to else linear_to_srgb
    if img.solid:
        return FilterImage(alpha=img.alpha, colour=fn(img.colour))
    return FilterImage(_convert_pixels(img.data, fn, in_place))


# ---------------------------------------------------------------------------
# Pixel operations (premultiplied float32 (H, W, 4) images)
# ---------------------------------------------------------------------------

def check_image(img, name='image'):
    a = np.asarray(img)
    if a.ndim != 3 or a.shape[2] != 4:
        raise FilterError('%s must be an (H, W, 4) array, got shape %r' % (name, a.shape))
    return a.astype(np.float32, copy=False)


def check_finite(*vals):
    for v in vals:
        if not math.isfinite(float(v)):
            raise FilterError('filter parameter must be finite, got %r' % (v,))


def _box_passes(x, boxes, out=None):
    """Successive box sums along axis 0.

    Pass ``(d, left)`` maps ``x`` to ``y[i] = sum(x[i - left : i - left +
    d])`` with zeros outside the array.  Each window sum is built from
    sums of power-of-two windows (``W_2k[i] = W_k[i] + W_k[i + k]``), so a
    pass costs about ``log2(d) + popcount(d)`` vectorised additions, all in
    float32 without the cancellation of a running sum.  A window reaching
    past the array on both sides is clipped first, so a huge box costs no
    more than one of about ``2 N``.  The columns (axis 1) are processed in
    blocks that fit in the cache.

    Parameters
    ----------
    x : (N, ...) float32 ndarray
        Any strides.
    boxes : sequence of (int d >= 1, int left)

    out : (N, ...) float32 ndarray or None
        Where to write the result (any strides; it may be ``x`` itself:
        each block of columns is read before it is written).

    Returns
    -------
    (N, ...) float32 ndarray, C-contiguous (or ``out``)
        The sums divided by the product of the ``d``.
    """
    if x.ndim == 1:
        return _box_passes(x[:, None], boxes, None if out is None else out[:, None])[:, 0]
    n, m, inner = x.shape[0], x.shape[1], int(np.prod(x.shape[2:], dtype=np.int64))
    # window of output i: x[i + s : i + e], clipped so that |s|, |e| <= n
    spans = [(max(-left, -n), min(d - left, n)) for d, left in boxes]
    width = max(e - s for s, e in spans)
    if out is None:
        out = np.zeros(x.shape, np.float32)
    if width <= 0 or x.size == 0 or any(e <= s for s, e in spans):
        out[...] = 0.0
        return out
    length = n + width - 1
    cm = max(1, min(m, _BLOCK_BYTES // (4 * length * inner)))
    flat = [np.empty(length * cm * inner, np.float32) for _ in range(2)]
    flat_out = np.empty(n * cm * inner, np.float32)
    scale = 1.0
    for d, _ in boxes:
        scale /= d
    for c0 in range(0, m, cm):           # loop over cache-sized blocks of columns
        xb = x[:, c0:c0 + cm]
        shape = xb.shape[1:]
        size = int(np.prod(shape, dtype=np.int64))
        bufs = [f[:length * size].reshape((length,) + shape) for f in flat]
        ob = flat_out[:n * size].reshape((n,) + shape)
        _box_block(xb, spans, bufs, ob)
        if scale != 1.0:
            ob *= np.float32(scale)
        out[:, c0:c0 + cm] = ob
    return out


def _box_block(x, spans, bufs, out):
    """The window sums of :func:`_box_passes` (unscaled) of one block
    ``x`` (N, ...) into ``out`` (N, ...), with two work buffers ``bufs`` of
    at least ``N + max width - 1`` rows; ``spans`` are the clipped windows
    ``(s, e)``: ``y[i] = sum(x[i + s : i + e])``."""
    n = x.shape[0]
    src = x
    for s, e in spans:
        w = e - s
        # p[m] = src[m + s] inside the array, 0 outside
        p = bufs[0][:n + w - 1]
        j0, j1 = max(s, 0), min(n, n + e - 1)
        p[:j0 - s] = 0.0
        p[j0 - s:j1 - s] = src[j0:j1]
        p[j1 - s:] = 0.0
        # cur[m] = sum(p[m : m + size]) lives in bufs[which]
        cur, which, size, off, first, k = p, 0, 1, 0, True, w
        while True:                      # loop over the bits of w
            if k & 1:
                if first:
                    np.copyto(out, cur[off:off + n])
                    first = False
                else:
                    np.add(out, cur[off:off + n], out=out)
                off += size
            k >>= 1
            if not k:
                break
            m = cur.shape[0] - size
            nxt = bufs[1 - which][:m]
            np.add(cur[:m], cur[size:size + m], out=nxt)
            cur, which, size = nxt, 1 - which, size * 2
        src = out                        # copied into p before out is rewritten


def _box_axis(a, d, left, axis):
    """One box mean of width ``d`` along ``axis``: ``out[i] = sum(a[i-left :
    i-left+d]) / d`` with zeros outside the array (float32, the shape of
    ``a``)."""
    out = _box_passes(np.moveaxis(np.asarray(a, np.float32), axis, 0), ((d, left),))
    return np.moveaxis(out, 0, axis)


def _box_size(s):
    return int(math.floor(s * 3.0 * math.sqrt(2.0 * math.pi) / 4.0 + 0.5))


def _box_list(d):
    """The three ``(width, left)`` box passes of the specification for a
    box size ``d`` (none when ``d <= 1``): three centred boxes of an odd
    ``d``; for an even ``d`` two of ``d`` (centred on the pixel's right and
    left edge) and one of ``d + 1``."""
    if d <= 1:
        return ()
    if d % 2:
        return ((d, (d - 1) // 2),) * 3
    return ((d, d // 2), (d, d // 2 - 1), (d + 1, d // 2))


def box_sigma(sigma):
    """Effective standard deviation (px) of the three box blurs
    :func:`box_blur` uses for ``sigma`` (the boxes' variances add up).

    >>> round(box_sigma(10.0), 3)          # three boxes of 19 px
    9.487
    """
    d = _box_size(sigma)
    if d <= 1:
        return 0.0
    if d % 2:
        return math.sqrt(3 * (d * d - 1) / 12.0)
    return math.sqrt((2 * (d * d - 1) + (d + 1) ** 2 - 1) / 12.0)


def _gauss_axis(a, s, axis, out=None):
    """Blur along ``axis`` with a Gaussian kernel of deviation ``s`` px
    truncated at ``ceil(4 s)`` and renormalised (zeros outside); the
    result goes to ``out`` (the shape of ``a``, any strides, possibly
    ``a`` itself) if given, else to a new float32 array.

    The other axes are processed in blocks of columns (axis 1 after the
    blurred one) of about :data:`_BLOCK_BYTES` of padded input, so the
    padded copy and the products are block-sized, not layer-sized; every
    output value is the same sum in the same order whatever the blocks.
    """
    if a.ndim == 1:
        return _gauss_axis(a[:, None], s, 0, None if out is None else out[:, None])[:, 0]
    r = max(1, int(math.ceil(4.0 * s)))
    x = np.arange(-r, r + 1, dtype=np.float64)
    k = np.exp(-0.5 * (x / s) ** 2)
    k /= k.sum()
    taps = [np.float32(w) for w in k]
    a = np.moveaxis(a, axis, 0)
    n = a.shape[0]
    if out is None:
        out = np.zeros(a.shape, np.float32)
        fresh = True
    else:
        out, fresh = np.moveaxis(out, axis, 0), False
    inner = int(np.prod(a.shape[2:], dtype=np.int64))
    cm = max(1, min(a.shape[1], _BLOCK_BYTES // max(1, 4 * (n + 2 * r) * inner)))
    for sl in [slice(c0, c0 + cm) for c0 in range(0, a.shape[1], cm)]:                    # loop over blocks of columns
        ab = a[:, sl]
        ob = out[:, sl]
        pad = np.zeros((n + 2 * r,) + ab.shape[1:], np.float32)
        pad[r:r + n] = ab
        if not fresh:
            ob[...] = 0.0                # (after ab is copied: ob may be ab)
        tmp = np.empty(ob.shape, np.float32)
        for j, w in enumerate(taps):     # loop over kernel taps, not pixels
            np.multiply(pad[j:j + n], w, out=tmp)
            ob += tmp
    return np.moveaxis(out, 0, axis)


def _reach(plan):
    """``(before, after)``: how far (px) a blur plan of one axis spreads a
    pixel towards lower and higher indices."""
    if plan is None:
        return 0, 0
    kind, arg = plan
    if kind == 'gauss':
        r = max(1, int(math.ceil(4.0 * arg)))
        return r, r
    # output i reads inputs i - left .. i - left + d - 1
    return sum(d - 1 - left for d, left in arg), sum(left for d, left in arg)


def _blur_axis(work, plan, axis, out=None):
    """One axis of :func:`blur_array` on ``work``, into ``out`` if given."""
    if plan[0] == 'gauss':
        return _gauss_axis(work, plan[1], axis, out)
    o = None if out is None else np.moveaxis(out, axis, 0)
    return np.moveaxis(_box_passes(np.moveaxis(work, axis, 0), plan[1], o), 0, axis)


def blur_array(x, plan_x, plan_y, in_place=False):
    """Separable blur of ``x`` (H, W) or (H, W, C) float32, zero outside,
    one plan per axis.

    A plan is None (axis untouched), ``('box', boxes)`` (successive box
    means, see :func:`_box_passes`) or ``('gauss', sigma)``.  The work is
    restricted to the bounding box of the non-zero pixels grown by the
    blur's reach: outside it the result is exactly 0.  The last axis is
    written straight into the result, so at most ``x``, the first axis's
    result (of the work box's size) and the result are alive at once;
    with ``in_place`` the result is ``x`` itself (overwritten) and the
    output costs nothing.

    Returns
    -------
    float32 ndarray, the shape of ``x`` (``x`` with ``in_place``)
    """
    if plan_x is None and plan_y is None:
        return x
    h, w = x.shape[:2]
    box = nonzero_box(x)
    if box is None:
        return x if in_place else np.zeros(x.shape, np.float32)
    (bx, ax), (by, ay) = _reach(plan_x), _reach(plan_y)
    y0, y1 = max(box[0] - by, 0), min(box[1] + ay, h)
    x0, x1 = max(box[2] - bx, 0), min(box[3] + ax, w)
    work = x[y0:y1, x0:x1]
    plans = [(axis, plan) for axis, plan in ((1, plan_x), (0, plan_y)) if plan is not None]
    for axis, plan in plans[:-1]:
        work = _blur_axis(work, plan, axis)
    # outside the work box x is 0, and so is the result
    out = x if in_place else np.zeros(x.shape, np.float32)
    _blur_axis(work, plans[-1][1], plans[-1][0], out[y0:y1, x0:x1])
    return out


def blur_cost(plan_x, plan_y):
    """Array passes per pixel (and channel) of :func:`blur_array` with
    these plans: a box pass of width ``d`` costs about ``log2(d) +
    popcount(d)`` additions plus two copies (:func:`_box_passes`), a
    Gaussian of reach ``r`` a multiply and an add per tap.  Used to weigh
    a blur against a work budget before running it.

    >>> blur_cost(*blur_plans(5.0, 5.0, None))      # three boxes of 9 px per axis
    48.0
    """
    cost = 0.0
    for plan in (plan_x, plan_y):
        if plan is None:
            continue
        kind, arg = plan
        if kind == 'gauss':
            cost += 2.0 * (2 * max(1, int(math.ceil(4.0 * arg))) + 1)
        else:
            cost += sum(max(int(d), 1).bit_length() + bin(max(int(d), 1)).count('1') + 2
                        for d, _ in arg)
    return float(cost)


def blur_image(img, plan_x, plan_y, in_place=False):
    """:func:`blur_array` of an :class:`FilterImage` (a solid-colour image
    blurs its alpha channel only: blurs are linear); with ``in_place`` the
    pixels of ``img`` are overwritten by the result (for an input nothing
    reads again)."""
    if img.solid:
        return FilterImage(alpha=blur_array(img.alpha, plan_x, plan_y, in_place),
                           colour=img.colour)
    return FilterImage(blur_array(img.data, plan_x, plan_y, in_place))


def blur_plans(sigma_x, sigma_y, tolerance):
    """Per-axis plans (see :func:`blur_array`) of :func:`gaussian_blur`."""
    plans = []
    for s in (sigma_x, sigma_y):
        plan = None
        if s > 0:
            boxes = _box_list(_box_size(s))
            if s >= 2.0 and (tolerance is None or abs(box_sigma(s) - s) <= tolerance):
                plan = ('box', boxes) if boxes else None
            else:
                plan = ('gauss', float(s))
        plans.append(plan)
    return plans


def box_blur(img, sigma_x, sigma_y):
    """Three successive box blurs approximating a Gaussian of standard
    deviations ``sigma_x``, ``sigma_y`` device pixels (the box sizes of the
    Filter Effects specification: ``d = floor(s * 3 sqrt(2 pi) / 4 + 0.5)``).
    Pixels outside the image are transparent.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA
    sigma_x, sigma_y : float >= 0

    Returns
    -------
    (H, W, 4) float32 ndarray
    """
    out = check_image(img)
    check_finite(sigma_x, sigma_y)
    boxes = [_box_list(_box_size(s)) for s in (sigma_x, sigma_y)]
    plans = [('box', b) if b else None for b in boxes]
    if plans == [None, None]:
        return out
    return blur_image(FilterImage.of(out), *plans).data


def check_tolerance(tolerance):
    """Validate a blur tolerance (None or a positive finite number)."""
    if tolerance is not None:
        check_finite(tolerance)
        if not tolerance > 0:
            raise FilterError('tolerance must be positive, got %r' % (tolerance,))
    return tolerance


def gaussian_blur(img, sigma_x, sigma_y=None, tolerance=None):
    """Gaussian blur with standard deviations in device pixels.

    A deviation of at least 2 px may use the specification's three box
    blurs (what resvg does); their effective standard deviation
    (:func:`box_sigma`) is about 6 % below ``sigma``.  Otherwise a separable
    kernel truncated at 4 sigma (renormalised) is used.  Zero or negative
    deviations leave that axis unblurred.  Only the bounding box of the
    non-transparent pixels (grown by the blur's reach) is worked on, and an
    image of one colour blurs its alpha channel only.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied RGBA
    sigma_x, sigma_y : float (sigma_y defaults to sigma_x)
    tolerance : float > 0 or None
        None (default, the renderer's choice): boxes for every sigma >= 2,
        as the specification and resvg.  A number of device pixels: boxes
        only where their effective standard deviation is within it of
        ``sigma``, the exact kernel elsewhere.

    Returns
    -------
    (H, W, 4) float32 ndarray

    >>> img = np.zeros((9, 9, 4), np.float32); img[4, 4] = 1
    >>> out = gaussian_blur(img, 1.0)
    >>> round(float(out[..., 3].sum()), 3), bool(out[4, 4, 3] < 0.2)
    (1.0, True)
    """
    out = check_image(img)
    sigma_y = sigma_x if sigma_y is None else sigma_y
    check_finite(sigma_x, sigma_y)
    plans = blur_plans(sigma_x, sigma_y, check_tolerance(tolerance))
    if plans == [None, None]:
        return out
    return blur_image(FilterImage.of(out), *plans).data


def shift(x, dx, dy):
    """``x`` (H, W, ...) moved by whole pixels ``dx`` (columns), ``dy``
    (rows); what moves in is 0."""
    h, w = x.shape[:2]
    out = np.zeros(x.shape, np.float32)
    if abs(dx) >= w or abs(dy) >= h:
        return out
    out[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)] = \
        x[max(-dy, 0):h + min(-dy, 0), max(-dx, 0):w + min(-dx, 0)]
    return out


def offset(img, dx, dy):
    """Shift an image by ``(dx, dy)`` device pixels (rounded to whole
    pixels); what moves in from outside is transparent.

    >>> img = np.zeros((3, 3, 4), np.float32); img[0, 0] = 1
    >>> offset(img, 1, 2)[2, 1].tolist()
    [1.0, 1.0, 1.0, 1.0]
    """
    src = check_image(img)
    check_finite(dx, dy)
    return shift(src, int(round(dx)), int(round(dy)))


def color_matrix(img, matrix):
    """Apply a (4, 5) colour matrix to unpremultiplied RGBA (feColorMatrix):
    ``[R' G' B' A'] = M [R G B A 1]``, clamped to [0, 1].

    >>> img = np.full((1, 1, 4), 0.5, np.float32)
    >>> ident = np.hstack([np.eye(4), np.zeros((4, 1))])
    >>> color_matrix(img, ident)[0, 0].tolist()
    [0.5, 0.5, 0.5, 0.5]
    """
    src = check_image(img)
    m = np.asarray(matrix, np.float64)
    if m.shape != (4, 5) or not np.isfinite(m).all():
        raise FilterError('colour matrix must be a finite (4, 5) array')

    def block(b):
        c, a = unpremultiply(b)
        x = np.concatenate([c, a], -1).astype(np.float64)
        y = np.clip(x @ m[:, :4].T + m[:, 4], 0.0, 1.0).astype(np.float32)
        return premultiply(y[..., :3], y[..., 3:4])

    return _by_rows(block, src)


def _transfer(v, fn):
    if fn is None:
        return v
    kind, p = fn
    if kind == 'table':
        t = np.asarray(p, np.float64)
        n = len(t) - 1
        if n == 0:
            return np.full_like(v, t[0])
        k = np.minimum(np.floor(v * n).astype(np.int64), n - 1)
        return t[k] + (v * n - k) * (t[k + 1] - t[k])
    if kind == 'discrete':
        t = np.asarray(p, np.float64)
        n = len(t)
        k = np.clip(np.floor(v * n).astype(np.int64), 0, n - 1)
        return t[k]
    if kind == 'linear':
        return p[0] * v + p[1]
    if kind == 'gamma':
        return p[0] * np.power(v, p[1]) + p[2]
    return v


def component_transfer(img, funcs):
    """feComponentTransfer on unpremultiplied values.

    Parameters
    ----------
    img : (H, W, 4) float32 ndarray, premultiplied
    funcs : dict channel index (0..3) -> (kind, params) or None
        ``('table', values)``, ``('discrete', values)``,
        ``('linear', (slope, intercept))``,
        ``('gamma', (amplitude, exponent, offset))``; missing: identity.
    """
    src = check_image(img)

    def block(b):
        c, a = unpremultiply(b)
        x = np.concatenate([c, a], -1).astype(np.float64)
        for ch, fn in funcs.items():
            x[..., ch] = _transfer(x[..., ch], fn)
        x = np.clip(x, 0.0, 1.0).astype(np.float32)
        return premultiply(x[..., :3], x[..., 3:4])

    return _by_rows(block, src)


def _minmax_axis(a, r, axis, fn):
    a = np.moveaxis(a, axis, 0)
    n = a.shape[0]
    r = min(r, n)
    fill = 0.0
    pad = np.full((n + 2 * r,) + a.shape[1:], fill, np.float32)
    pad[r:r + n] = a
    out = pad[0:n].copy()
    for j in range(1, 2 * r + 1):       # loop over window offsets
        fn(out, pad[j:j + n], out=out)
    return np.moveaxis(out, 0, axis)


def morphology(img, rx, ry, operator='erode'):
    """feMorphology: per-channel minimum (erode) or maximum (dilate) over a
    ``(2 rx + 1) x (2 ry + 1)`` window (radii in whole device pixels);
    outside the image is transparent."""
    src = check_image(img)
    check_finite(rx, ry)
    fn = np.minimum if operator == 'erode' else np.maximum
    out = src
    h, w = src.shape[:2]
    rx, ry = int(round(rx)), int(round(ry))
    if rx > 0:
        out = _minmax_axis(out, min(rx, w), 1, fn)
    if ry > 0:
        out = _minmax_axis(out, min(ry, h), 0, fn)
    return out


def tile(img, rect, target):
    """Tile the ``rect`` (x0, y0, x1, y1) part of ``img`` over ``target``."""
    x0, y0, x1, y1 = rect
    out = np.zeros_like(img)
    if x1 <= x0 or y1 <= y0:
        return out
    tx0, ty0, tx1, ty1 = target
    jj = x0 + (np.arange(tx0, tx1) - x0) % (x1 - x0)
    ii = y0 + (np.arange(ty0, ty1) - y0) % (y1 - y0)
    out[ty0:ty1, tx0:tx1] = img[ii[:, None], jj[None, :]]
    return out
