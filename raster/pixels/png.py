"""PNG encoding of 8-bit RGBA images (zlib from the standard library).

The encoder filters every row with the cheaper of three PNG filters --
None, Sub and Up, chosen per row by the smallest sum of absolute filtered
bytes (read as signed), the usual heuristic -- in a few numpy passes, and
compresses with zlib's run-length strategy at a low level.  On rendered
pictures (flat colour areas, anti-aliased edges) that is about as small as
Pillow's encoder at level 3 and 2-3 times faster: on the corpus benchmark
at 2000 px, 52 ms instead of 106-149 ms for the tiger (830 kB against
837 kB).

>>> import numpy as np
>>> img = np.zeros((2, 3, 4), np.uint8); img[..., 0] = 255; img[..., 3] = 255
>>> data = encode_png(img)
>>> data[:8] == b'\\x89PNG\\r\\n\\x1a\\n', data[12:16]
(True, b'IHDR')
>>> from PIL import Image; import io
>>> np.array_equal(np.asarray(Image.open(io.BytesIO(data))), img)
True
"""

import struct
import zlib

import numpy as np

from ..errors import CanvasError

__all__ = ['encode_png', 'encode_png_strips', 'write_png', 'phys_chunk', 'DEFAULT_LEVEL',
           'STRIP_PIXELS']

#: zlib level of :func:`encode_png` (levels 1-3 use the run-length strategy).
DEFAULT_LEVEL = 1

_SIGNATURE = b'\x89PNG\r\n\x1a\n'
_IDAT_MAX = 1 << 20          # bytes per IDAT chunk

#: Pixels per strip that :func:`encode_png` filters and compresses at a
#: time (its temporaries are a few times a strip, not a few times the image).
STRIP_PIXELS = 1 << 18


def _chunk(kind, payload):
    return (struct.pack('>I', len(payload)) + kind + payload
            + struct.pack('>I', zlib.crc32(payload, zlib.crc32(kind)) & 0xFFFFFFFF))


def _filtered(raw, prev=None, scratch=None):
    """Rows of ``raw`` ((H, N) uint8) each prefixed with its filter type
    (0 None, 1 Sub, 2 Up) and filtered by it: (H, N + 1) uint8.  ``prev``
    ((N,) uint8) is the image row above ``raw[0]`` (None: ``raw`` starts the
    image, where Up sees a row of zeros).  ``scratch``: optional (3, h, N)
    uint8 work space, h >= H, reused from strip to strip."""
    H, N = raw.shape
    out = np.empty((H, N + 1), np.uint8)
    if scratch is None or scratch.shape[1] < H or scratch.shape[2] != N:
        scratch = np.empty((3, H, N), np.uint8)
    up, sub, tmp = scratch[0, :H], scratch[1, :H], scratch[2, :H]
    if prev is None:
        up[:1] = raw[:1]
    else:
        np.subtract(raw[:1], prev, out=up[:1])
    np.subtract(raw[1:], raw[:-1], out=up[1:])
    sub[:, :4] = raw[:, :4]
    np.subtract(raw[:, 4:], raw[:, :-4], out=sub[:, 4:])

    def cost(a):        # sum of |byte as int8|: min(b, 256 - b) per byte
        np.negative(a, out=tmp)
        np.minimum(a, tmp, out=tmp)
        return tmp.sum(1, dtype=np.uint32)          # (128 N < 2**32)
    costs = np.stack([cost(raw), cost(sub), cost(up)])
    kind = np.argmin(costs, axis=0).astype(np.uint8)      # ties: the lower type
    out[:, 0] = kind
    for k, src in ((0, raw), (1, sub), (2, up)):
        rows = np.flatnonzero(kind == k)
        if len(rows) == H:
            out[:, 1:] = src
        elif len(rows):
            out[rows, 1:] = src[rows]
    return out


def phys_chunk(dpi):
    """The ``pHYs`` chunk of a resolution: pixels per metre (the PNG unit),
    rounded to whole numbers.

    Parameters
    ----------
    dpi : float or (float, float)
        Pixels per inch, one for both axes or ``(x, y)``.

    Raises
    ------
    CanvasError
        A resolution that is not positive and finite, or that rounds to 0
        or beyond 2**31 - 1 pixels per metre.

    >>> phys_chunk(96)[8:17].hex()        # 96 dpi = 3779.5 px/m -> 3780
    '00000ec400000ec401'
    """
    try:
        xy = (float(dpi), float(dpi)) if np.ndim(dpi) == 0 else tuple(float(v) for v in dpi)
    except (TypeError, ValueError):
        raise CanvasError('resolution must be a number or (x, y), got %r' % (dpi,)) from None
    if len(xy) != 2 or not all(np.isfinite(v) and v > 0 for v in xy):
        raise CanvasError('resolution must be positive and finite, got %r' % (dpi,))
    ppm = [int(round(v / 0.0254)) for v in xy]
    if not all(1 <= v <= 2 ** 31 - 1 for v in ppm):
        raise CanvasError('resolution out of range for PNG: %r dpi' % (dpi,))
    return _chunk(b'pHYs', struct.pack('>IIB', ppm[0], ppm[1], 1))


def _check_level(level):
    try:
        level = int(level)
    except (TypeError, ValueError):
        raise CanvasError('PNG level must be an integer 0-9') from None
    if not 0 <= level <= 9:
        raise CanvasError('PNG level must be 0-9, got %d' % level)
    return level


def encode_png(rgba, level=DEFAULT_LEVEL, dpi=None):
    """PNG bytes of an image.

    Parameters
    ----------
    rgba : (H, W, 4) uint8 ndarray
        Straight (not premultiplied) RGBA, row 0 at the top.
    level : int
        zlib level 0-9; 1-3 use the run-length strategy (``Z_RLE``), 4-9
        the default strategy, 0 stores.
    dpi : float, (float, float) or None
        Resolution recorded in a ``pHYs`` chunk (pixels per inch, converted
        to whole pixels per metre); None: no chunk.

    Returns
    -------
    bytes

    Raises
    ------
    CanvasError
        Not an (H, W, 4) uint8 array, a bad level or a bad resolution.
    """
    a = np.asarray(rgba)
    if a.dtype != np.uint8 or a.ndim != 3 or a.shape[2] != 4 or 0 in a.shape:
        raise CanvasError('PNG encoding needs an (H, W, 4) uint8 array, got %s %r'
                          % (a.dtype, a.shape))
    H, W = a.shape[:2]
    step = max(1, STRIP_PIXELS // W)
    return encode_png_strips(W, H, (a[y:y + step] for y in range(0, H, step)), level, dpi)


def encode_png_strips(width, height, strips, level=DEFAULT_LEVEL, dpi=None):
    """PNG bytes of an image given as strips of rows, top to bottom.

    The encoder holds one strip and its filtered rows at a time, so an
    image can be written from a canvas without an 8-bit copy of the whole
    of it (:meth:`raster.pixels.canvas.Canvas.rgba8_rows` makes the
    strips).  The bytes are those :func:`encode_png` gives for the whole
    image.

    Parameters
    ----------
    width, height : int
        Image size in pixels.
    strips : iterable of (h, width, 4) uint8 ndarray
        Straight RGBA rows, ``height`` rows in all.
    level, dpi :
        As for :func:`encode_png`.

    Raises
    ------
    CanvasError
        A strip that is not (h, width, 4) uint8, a row count other than
        ``height``, a bad level or a bad resolution.

    >>> img = np.arange(2 * 3 * 4, dtype=np.uint8).reshape(2, 3, 4)
    >>> encode_png_strips(3, 2, [img[:1], img[1:]]) == encode_png(img)
    True
    """
    W, H = int(width), int(height)
    if W < 1 or H < 1:
        raise CanvasError('PNG size must be positive, got %r x %r' % (width, height))
    level = _check_level(level)
    phys = phys_chunk(dpi) if dpi is not None else b''
    strategy = zlib.Z_RLE if 1 <= level <= 3 else zlib.Z_DEFAULT_STRATEGY
    co = zlib.compressobj(level, zlib.DEFLATED, 15, 8, strategy)
    parts = [_SIGNATURE, _chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 6, 0, 0, 0)), phys]
    pending = []                    # compressed bytes not yet in an IDAT chunk
    npend = 0
    prev = scratch = None
    rows = 0
    for strip in strips:
        a = np.asarray(strip)
        if a.dtype != np.uint8 or a.ndim != 3 or a.shape[1:] != (W, 4):
            raise CanvasError('PNG strip must be (h, %d, 4) uint8, got %s %r'
                              % (W, a.dtype, a.shape))
        if not len(a):
            continue
        rows += len(a)
        if rows > H:
            raise CanvasError('PNG strips hold more than %d rows' % H)
        raw = np.ascontiguousarray(a).reshape(len(a), W * 4)
        if scratch is None or scratch.shape[1] < len(a):
            scratch = np.empty((3, len(a), W * 4), np.uint8)
        z = co.compress(memoryview(_filtered(raw, prev, scratch)).cast('B'))
        prev = raw[-1].copy()
        if z:
            pending.append(z)
            npend += len(z)
            if npend >= _IDAT_MAX:
                npend = _idat(parts, pending, False)
    if rows != H:
        raise CanvasError('PNG strips hold %d rows, not %d' % (rows, H))
    pending.append(co.flush())
    _idat(parts, pending, True)
    parts.append(_chunk(b'IEND', b''))
    return b''.join(parts)


def _idat(parts, pending, last):
    """Append IDAT chunks of :data:`_IDAT_MAX` bytes of the compressed data
    ``pending`` (a list of bytes, emptied) to ``parts``; the remainder stays
    in ``pending`` unless ``last``.  Returns the bytes left pending."""
    z = b''.join(pending)
    pending.clear()
    n = len(z) if last else len(z) - len(z) % _IDAT_MAX
    parts.extend(_chunk(b'IDAT', z[i:i + _IDAT_MAX]) for i in range(0, n, _IDAT_MAX))
    if n < len(z):
        pending.append(z[n:])
    return len(z) - n


def write_png(path_or_file, rgba, level=DEFAULT_LEVEL, dpi=None):
    """Write :func:`encode_png` bytes to a path or a binary file object."""
    data = encode_png(rgba, level, dpi)
    if hasattr(path_or_file, 'write'):
        path_or_file.write(data)
    else:
        with open(path_or_file, 'wb') as f:
            f.write(data)
