"""Compositing and blending of premultiplied float32 RGBA images: the 16
blend modes of Compositing and Blending Level 1 and the Porter-Duff
operators, one copy for group compositing (the renderer) and for
``feBlend``/``feComposite`` (the filters).

Images are ``(H, W, 4)`` float32 premultiplied RGBA.  A blend of source
``S`` onto backdrop ``D`` is ``S (1 - Da) + D (1 - Sa) + Sa Da B(Dc, Sc)``
with ``B`` the blend function of the straight colours; the non-separable
modes use resvg's ClipColor (see :func:`_clip_color`).

>>> a = np.full((1, 1, 4), 0.5, np.float32); b = np.full((1, 1, 4), 1.0, np.float32)
>>> composite(a, b, 'in')[0, 0].tolist(), composite(a, b, 'xor')[0, 0].tolist()
([0.5, 0.5, 0.5, 0.5], [0.5, 0.5, 0.5, 0.5])
>>> grey = np.array([[[0.25, 0.25, 0.25, 0.5]]], np.float32)   # 50 % grey, half alpha
>>> blend(grey, b, 'multiply')[0, 0].tolist()                    # onto opaque white
[0.75, 0.75, 0.75, 1.0]
"""

import math

import numpy as np

from ..errors import CanvasError

__all__ = ['BLEND_MODES', 'PORTER_DUFF', 'blend', 'composite', 'blend_layer']

#: Porter-Duff operators of :func:`composite` (``feComposite``).
PORTER_DUFF = ('over', 'in', 'out', 'atop', 'xor', 'arithmetic')


def _check(img, name):
    a = np.asarray(img)
    if a.ndim != 3 or a.shape[2] != 4:
        raise CanvasError('%s must be an (H, W, 4) array, got shape %r' % (name, a.shape))
    return a.astype(np.float32, copy=False)


def _soft_light(cb, cs):
    d = np.where(cb <= 0.25, ((16 * cb - 12) * cb + 4) * cb, np.sqrt(cb))
    return np.where(cs <= 0.5, cb - (1 - 2 * cs) * cb * (1 - cb), cb + (2 * cs - 1) * (d - cb))


def _hard_light(cb, cs):
    s2 = 2 * cs
    return np.where(cs <= 0.5, cb * s2, cb + (s2 - 1) - cb * (s2 - 1))


def _dodge(cb, cs):
    with np.errstate(divide='ignore', invalid='ignore'):
        r = np.minimum(1.0, cb / np.maximum(1 - cs, 1e-12))
    return np.where(cb <= 0, 0.0, np.where(cs >= 1, 1.0, r))


def _burn(cb, cs):
    with np.errstate(divide='ignore', invalid='ignore'):
        r = 1 - np.minimum(1.0, (1 - cb) / np.maximum(cs, 1e-12))
    return np.where(cb >= 1, 1.0, np.where(cs <= 0, 0.0, r))


SEPARABLE = {
    'multiply': lambda cb, cs: cb * cs,
    'screen': lambda cb, cs: cb + cs - cb * cs,
    'overlay': lambda cb, cs: _hard_light(cs, cb),
    'darken': np.minimum,
    'lighten': np.maximum,
    'color-dodge': _dodge,
    'color-burn': _burn,
    'hard-light': _hard_light,
    'soft-light': _soft_light,
    'difference': lambda cb, cs: np.abs(cb - cs),
    'exclusion': lambda cb, cs: cb + cs - 2 * cb * cs,
}


def _lum(c):
    return 0.3 * c[..., 0] + 0.59 * c[..., 1] + 0.11 * c[..., 2]


def _clip_color(c):
    """ClipColor of Compositing 1, as resvg (tiny-skia) computes it.

    The specification first pulls a colour with a negative channel towards
    its luminosity (``C = L + (C - L) L / (L - min)``), then one with a
    channel above 1 (``C = L + (C - L) (1 - L) / (max - L)``).  tiny-skia
    guards the first step with ``max >= 0`` instead of ``min < 0``, so the
    first step never runs (after SetLum the maximum is at least the
    luminosity, which is >= 0) and negative channels are clamped to 0 at
    the end.  The resvg suite's references are drawn that way (e.g.
    painting/mix-blend-mode/saturation: green under a saturated yellow keeps
    G = 0.637, not the specification's 0.5), so we follow it.

    ``c`` is (..., 3) float64 straight RGB; returns the same shape.
    """
    lum = _lum(c)[..., None]
    x = c.max(-1, keepdims=True)
    over = x > 1
    if over.any():
        with np.errstate(divide='ignore', invalid='ignore'):
            c = np.where(over, lum + (c - lum) * (1 - lum) / np.maximum(x - lum, 1e-12), c)
    return np.maximum(c, 0.0)


def _set_lum(c, lum):
    d = lum - _lum(c)
    return _clip_color(c + d[..., None])


def _sat(c):
    return c.max(-1) - c.min(-1)


def _set_sat(c, s):
    mx = c.max(-1, keepdims=True)
    mn = c.min(-1, keepdims=True)
    rng = mx - mn
    with np.errstate(divide='ignore', invalid='ignore'):
        out = np.where(rng > 0, (c - mn) * s[..., None] / np.maximum(rng, 1e-12), 0.0)
    return out


NON_SEPARABLE = {
    'hue': lambda cb, cs: _set_lum(_set_sat(cs, _sat(cb)), _lum(cb)),
    'saturation': lambda cb, cs: _set_lum(_set_sat(cb, _sat(cs)), _lum(cb)),
    'color': lambda cb, cs: _set_lum(cs, _lum(cb)),
    'luminosity': lambda cb, cs: _set_lum(cb, _lum(cs)),
}



#: The blend modes (``normal`` and the 15 others).
BLEND_MODES = ('normal',) + tuple(SEPARABLE) + tuple(NON_SEPARABLE)


def blend(src, dst, mode='normal'):
    """Premultiplied ``src`` blended onto the premultiplied backdrop ``dst``
    (same shape) with a blend mode (``'normal'`` and unknown modes:
    source-over).

    Parameters
    ----------
    src, dst : (H, W, 4) float32 ndarrays
    mode : str
        One of :data:`BLEND_MODES` (a :class:`raster.tree.BlendMode` is one).

    Returns
    -------
    (H, W, 4) float32 ndarray
    """
    s, d = _check(src, 'source'), _check(dst, 'backdrop')
    if s.shape != d.shape:
        raise CanvasError('blend inputs differ in shape: %r, %r' % (s.shape, d.shape))
    fn = SEPARABLE.get(mode) or NON_SEPARABLE.get(mode)
    if fn is None:
        return composite(s, d, 'over')
    return _blend64(s.astype(np.float64), d.astype(np.float64), fn)


def _blend64(s, d, fn):
    """The blend of float64 premultiplied ``s`` onto ``d`` with blend
    function ``fn`` of the straight colours, as float32."""
    sa, da = s[..., 3:4], d[..., 3:4]
    with np.errstate(divide='ignore', invalid='ignore'):
        sc = np.where(sa > 0, s[..., :3] / np.maximum(sa, 1e-12), 0.0)
        dc = np.where(da > 0, d[..., :3] / np.maximum(da, 1e-12), 0.0)
    mix = np.clip(fn(dc, sc), 0, 1)
    out = np.empty_like(s)
    out[..., :3] = s[..., :3] * (1 - da) + d[..., :3] * (1 - sa) + sa * da * mix
    out[..., 3:4] = sa + da - sa * da
    return np.clip(out, 0, 1).astype(np.float32)


def composite(a, b, operator='over', k=(0.0, 0.0, 0.0, 0.0)):
    """Porter-Duff compositing of premultiplied ``a`` over ``b``
    (``feComposite``'s ``in`` over ``in2``).

    Parameters
    ----------
    a, b : (H, W, 4) float32 ndarrays, premultiplied RGBA
    operator : {'over', 'in', 'out', 'atop', 'xor', 'arithmetic'}
    k : 4 floats
        ``k1..k4`` of ``arithmetic``: ``k1 a b + k2 a + k3 b + k4`` per
        premultiplied channel, clamped to [0, 1] and colour <= alpha.

    Returns
    -------
    (H, W, 4) float32 ndarray
    """
    a, b = _check(a, 'in'), _check(b, 'in2')
    if a.shape != b.shape:
        raise CanvasError('composite inputs differ in shape: %r, %r' % (a.shape, b.shape))
    aa, ba = a[..., 3:4], b[..., 3:4]
    if operator == 'over':
        out = a + b * (1 - aa)
    elif operator == 'in':
        out = a * ba
    elif operator == 'out':
        out = a * (1 - ba)
    elif operator == 'atop':
        out = a * ba + b * (1 - aa)
    elif operator == 'xor':
        out = a * (1 - ba) + b * (1 - aa)
    elif operator == 'arithmetic':
        k1, k2, k3, k4 = (float(v) for v in k)
        if not all(math.isfinite(v) for v in (k1, k2, k3, k4)):
            raise CanvasError('arithmetic coefficients must be finite, got %r' % (k,))
        with np.errstate(over='ignore', invalid='ignore'):
            v = k1 * a * b + k2 * a + k3 * b + k4
            if not np.isfinite(v).all():
                # huge coefficients overflow float32: again in float64, and
                # what still overflows (inf - inf) counts as 0
                a64, b64 = a.astype(np.float64), b.astype(np.float64)
                v = np.nan_to_num(k1 * a64 * b64 + k2 * a64 + k3 * b64 + k4, nan=0.0)
        out = np.clip(v, 0.0, 1.0)
        out[..., :3] = np.minimum(out[..., :3], out[..., 3:4])
    else:
        raise CanvasError('unknown composite operator %r' % (operator,))
    return np.clip(out, 0.0, 1.0).astype(np.float32)


def blend_layer(target, src, x0, y0, opacity, mode):
    """Composite the premultiplied layer ``src`` ((h, w, 4) floats in [0, 1],
    or uint8 levels) at (x0, y0) onto
    ``target`` (a :class:`~raster.pixels.canvas.Canvas` or a view with the
    same ``width``/``height``/``read``/``composite``/``store``) with
    ``opacity`` and a blend mode: ``S (1 - Da) + D (1 - Sa) + Sa Da B(Dc, Sc)``
    (``normal``: plain source-over)."""
    fn = SEPARABLE.get(mode) or NON_SEPARABLE.get(mode)
    if fn is None:
        target.composite(src, x0, y0, opacity)
        return
    h, w = src.shape[:2]
    cx0, cy0 = max(x0, 0), max(y0, 0)
    cx1, cy1 = min(x0 + w, target.width), min(y0 + h, target.height)
    if cx1 <= cx0 or cy1 <= cy0:
        return
    s = src[cy0 - y0:cy1 - y0, cx0 - x0:cx1 - x0].astype(np.float64)
    s *= opacity / 255.0 if src.dtype == np.uint8 else opacity      # (uint8: an 8-bit layer)
    d = target.read(cy0, cy1, cx0, cx1).astype(np.float64)
    target.store(cy0, cy1, cx0, cx1, _blend64(s, d, fn))
