"""Encode straight-alpha RGBA images as PNG, JPEG, WebP, TIFF or BMP.

PNG goes through raster's own encoder (:mod:`raster.pixels.png`, with an optional
``pHYs`` resolution and zlib level); the other formats through Pillow:

=======  ============================  =====================================
format   extensions                    what is written
=======  ============================  =====================================
png      ``.png``                      RGBA, ``pHYs`` from ``dpi``
jpeg     ``.jpg`` ``.jpeg`` ``.jpe``   RGB flattened on ``matte`` (default
                                       white), 4:4:4, ``quality`` (default
                                       90), JFIF density from ``dpi``
webp     ``.webp``                     RGBA, lossless unless ``quality`` is
                                       given (then lossy); no resolution
tiff     ``.tif`` ``.tiff``            RGBA, deflate-compressed, resolution
                                       from ``dpi`` (default 96)
bmp      ``.bmp``                      RGB flattened on ``matte`` (most BMP
                                       readers ignore alpha), resolution
                                       from ``dpi``
=======  ============================  =====================================

>>> import numpy as np
>>> img = np.zeros((2, 3, 4), np.uint8); img[..., 0] = 255; img[..., 3] = 128
>>> format_of_path('out/picture.JPG'), format_of_path('out/picture'), format_name('tif')
('jpeg', None, 'tiff')
>>> flatten(img)[0, 0].tolist()         # half-opaque red on white
[255, 127, 127]
>>> encode(img, 'bmp')[:2]
b'BM'
"""

from __future__ import annotations

import io
import math
import os
from typing import Sequence

import numpy as np

from ..errors import FormatError
from .png import DEFAULT_LEVEL, STRIP_PIXELS, encode_png, encode_png_strips

__all__ = ['FORMATS', 'EXTENSIONS', 'DEFAULT_JPEG_QUALITY', 'format_name', 'format_of_path',
           'flatten', 'encode', 'encode_canvas']

#: Formats :func:`encode` writes.
FORMATS = ('png', 'jpeg', 'webp', 'tiff', 'bmp')

#: File extension (lower case) -> format.
EXTENSIONS = {'.png': 'png', '.jpg': 'jpeg', '.jpeg': 'jpeg', '.jpe': 'jpeg',
              '.webp': 'webp', '.tif': 'tiff', '.tiff': 'tiff', '.bmp': 'bmp'}

#: JPEG quality when none is given.
DEFAULT_JPEG_QUALITY = 90

_ALIASES = {'jpg': 'jpeg', 'tif': 'tiff'}
_PIL_NAMES = {'jpeg': 'JPEG', 'webp': 'WEBP', 'tiff': 'TIFF', 'bmp': 'BMP'}
_QUALITY = ('jpeg', 'webp')
_DPI = ('png', 'jpeg', 'tiff', 'bmp')


def format_name(name: str) -> str:
    """The canonical name of a format (``'JPG'`` -> ``'jpeg'``).

    Raises
    ------
    FormatError
        A format :func:`encode` does not write.
    """
    key = str(name).strip().lower()
    key = _ALIASES.get(key, key)
    if key not in FORMATS:
        raise FormatError('unknown output format %r (known: %s)' % (name, ', '.join(FORMATS)))
    return key


def format_of_path(path: str | os.PathLike) -> str | None:
    """The format a file name asks for by its extension (case-insensitive);
    None when the name has no extension (``-``, ``/dev/stdout``, a FIFO
    named ``p``).

    Raises
    ------
    FormatError
        An extension that is not one of :data:`EXTENSIONS`.
    """
    ext = os.path.splitext(os.path.basename(os.fspath(path)))[1].lower()
    if not ext:
        return None
    fmt = EXTENSIONS.get(ext)
    if fmt is None:
        raise FormatError('cannot write %r files: %s (known: %s)'
                          % (ext, os.fspath(path), ' '.join(sorted(EXTENSIONS))))
    return fmt


def _check_rgba(rgba):
    a = np.asarray(rgba)
    if a.dtype != np.uint8 or a.ndim != 3 or a.shape[2] != 4 or 0 in a.shape:
        raise FormatError('encoding needs an (H, W, 4) uint8 array, got %s %r'
                          % (a.dtype, a.shape))
    return a


def flatten(rgba: np.ndarray, matte: Sequence[float] = (1.0, 1.0, 1.0)) -> np.ndarray:
    """Composite a straight-alpha image over an opaque colour.

    Parameters
    ----------
    rgba : (H, W, 4) uint8 ndarray
        Straight (not premultiplied) RGBA.
    matte : sequence of 3 floats in [0, 1]
        The colour under the image (default white).

    Returns
    -------
    (H, W, 3) uint8 ndarray
        ``c * a + matte * (1 - a)`` per channel, rounded half up.

    Raises
    ------
    FormatError
        Not an RGBA uint8 image, or a matte that is not 3 floats in [0, 1].
    """
    a = _check_rgba(rgba)
    try:
        m = np.array([float(v) for v in matte], np.float64)
    except (TypeError, ValueError):
        raise FormatError('matte must be 3 floats in [0, 1], got %r' % (matte,)) from None
    if m.shape != (3,) or not np.all((m >= 0) & (m <= 1)):
        raise FormatError('matte must be 3 floats in [0, 1], got %r' % (matte,))
    m8 = np.round(m * 255).astype(np.uint32)
    alpha = a[..., 3:4].astype(np.uint32)
    # exact integer arithmetic: (c a + m (255 - a)) / 255, rounded half up
    num = a[..., :3].astype(np.uint32) * alpha + m8 * (255 - alpha)
    return ((num * 2 + 255) // 510).astype(np.uint8)


def _int_option(name, value, lo, hi):
    try:
        v = int(value)
    except (TypeError, ValueError):
        v = None
    if v is None or v != value or not lo <= v <= hi:
        raise FormatError('%s must be a whole number %d-%d, got %r' % (name, lo, hi, value))
    return v


def _dpi_pair(dpi):
    try:
        xy = (float(dpi), float(dpi)) if np.ndim(dpi) == 0 else tuple(float(v) for v in dpi)
    except (TypeError, ValueError):
        xy = ()
    if len(xy) != 2 or not all(math.isfinite(v) and v > 0 for v in xy):
        raise FormatError('dpi must be a positive number or (x, y), got %r' % (dpi,))
    return xy


def _check_options(fmt, quality, compress_level):
    if quality is not None:
        if fmt not in _QUALITY:
            raise FormatError('quality applies to JPEG and WebP, not %s' % fmt.upper())
        quality = _int_option('quality', quality, 1, 100)
    if compress_level is not None:
        if fmt != 'png':
            raise FormatError('compression level applies to PNG, not %s' % fmt.upper())
        compress_level = _int_option('compression level', compress_level, 0, 9)
    return quality, compress_level


def encode_canvas(canvas, format: str = 'png', *,
                  dpi: float | tuple[float, float] | None = None, quality: int | None = None,
                  compress_level: int | None = None,
                  matte: Sequence[float] = (1.0, 1.0, 1.0)) -> bytes:
    """:func:`encode` of a canvas's straight-alpha 8-bit image
    (:meth:`~raster.pixels.canvas.Canvas.to_rgba8`), the same bytes; a PNG
    is written a strip of rows at a time
    (:func:`raster.pixels.png.encode_png_strips`), without an 8-bit copy of
    the whole canvas.

    Parameters
    ----------
    canvas : raster.pixels.canvas.Canvas
    format, dpi, quality, compress_level, matte :
        As for :func:`encode`.

    Raises
    ------
    FormatError
        As :func:`encode`.
    """
    fmt = format_name(format)
    quality, compress_level = _check_options(fmt, quality, compress_level)
    if fmt != 'png':
        return encode(canvas.to_rgba8(), fmt, dpi=dpi, quality=quality, matte=matte)
    xy = _dpi_pair(dpi) if dpi is not None else None
    W, H = canvas.width, canvas.height
    step = max(1, STRIP_PIXELS // W)
    strips = (canvas.rgba8_rows(y, y + step) for y in range(0, H, step))
    return encode_png_strips(W, H, strips, DEFAULT_LEVEL if compress_level is None
                             else compress_level, xy)


def encode(rgba: np.ndarray, format: str = 'png', *,
           dpi: float | tuple[float, float] | None = None, quality: int | None = None,
           compress_level: int | None = None,
           matte: Sequence[float] = (1.0, 1.0, 1.0)) -> bytes:
    """Encode an image as ``format``.

    Parameters
    ----------
    rgba : (H, W, 4) uint8 ndarray
        Straight-alpha RGBA, row 0 at the top.
    format : str
        One of :data:`FORMATS` (or ``'jpg'``, ``'tif'``).
    dpi : float, (float, float) or None
        Resolution to record (PNG ``pHYs``, JPEG density, TIFF and BMP
        resolution); None: none recorded (TIFF: 96 dpi).  WebP has none,
        so it is not written there.
    quality : int or None
        JPEG quality 1-100 (default :data:`DEFAULT_JPEG_QUALITY`); WebP:
        lossy at this quality (default: lossless).  Other formats: refused.
    compress_level : int or None
        PNG zlib level 0-9 (default :data:`raster.pixels.png.DEFAULT_LEVEL`).
        Other formats: refused.
    matte : sequence of 3 floats in [0, 1]
        Colour JPEG and BMP images are flattened on (default white).

    Returns
    -------
    bytes

    Raises
    ------
    FormatError
        Unknown format, an option the format does not take, a bad option
        value or a bad image.
    """
    fmt = format_name(format)
    a = _check_rgba(rgba)
    quality, compress_level = _check_options(fmt, quality, compress_level)
    xy = _dpi_pair(dpi) if dpi is not None else None
    if fmt == 'png':
        return encode_png(a, DEFAULT_LEVEL if compress_level is None else compress_level, xy)
    from PIL import Image
    opts = {}
    if xy is not None and fmt in _DPI:
        opts['dpi'] = xy
    if fmt in ('jpeg', 'bmp'):
        im = Image.fromarray(flatten(a, matte), 'RGB')
        if fmt == 'jpeg':
            opts.update(quality=DEFAULT_JPEG_QUALITY if quality is None else quality,
                        subsampling=0)
    else:
        im = Image.fromarray(np.ascontiguousarray(a), 'RGBA')
        if fmt == 'webp':
            opts.update(lossless=True) if quality is None else opts.update(quality=quality)
        elif fmt == 'tiff':
            opts['compression'] = 'tiff_adobe_deflate'
            # without one, Pillow's TIFF writer records a resolution of 1
            # (read as 1 dpi): record the CSS pixel's 96 dpi instead
            opts.setdefault('dpi', (96.0, 96.0))
    buf = io.BytesIO()
    im.save(buf, _PIL_NAMES[fmt], **opts)
    return buf.getvalue()
