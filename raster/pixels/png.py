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

__all__ = ['encode_png', 'write_png', 'phys_chunk', 'DEFAULT_LEVEL']

#: zlib level of :func:`encode_png` (levels 1-3 use the run-length strategy).
DEFAULT_LEVEL = 1

_SIGNATURE = b'\x89PNG\r\n\x1a\n'
_IDAT_MAX = 1 << 20          # bytes per IDAT chunk


def _chunk(kind, payload):
    return (struct.pack('>I', len(payload)) + kind + payload
            + struct.pack('>I', zlib.crc32(payload, zlib.crc32(kind)) & 0xFFFFFFFF))


def _filtered(raw):
    """Rows of ``raw`` ((H, N) uint8) each prefixed with its filter type
    (0 None, 1 Sub, 2 Up) and filtered by it: (H, N + 1) uint8."""
    H, N = raw.shape
    out = np.empty((H, N + 1), np.uint8)
    up = np.empty_like(raw)
    up[:1] = raw[:1]
    np.subtract(raw[1:], raw[:-1], out=up[1:])
    sub = np.empty_like(raw)
    sub[:, :4] = raw[:, :4]
    np.subtract(raw[:, 4:], raw[:, :-4], out=sub[:, 4:])

    def cost(a):        # sum of |byte as int8|: min(b, 256 - b) per byte
        return np.minimum(a, np.uint8(0) - a).sum(1, dtype=np.uint64)
    costs = np.stack([cost(raw), cost(sub), cost(up)])
    kind = np.argmin(costs, axis=0).astype(np.uint8)      # ties: the lower type
    out[:, 0] = kind
    for k, src in ((0, raw), (1, sub), (2, up)):
        rows = kind == k
        if rows.any():
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
    try:
        level = int(level)
    except (TypeError, ValueError):
        raise CanvasError('PNG level must be an integer 0-9') from None
    if not 0 <= level <= 9:
        raise CanvasError('PNG level must be 0-9, got %d' % level)
    phys = phys_chunk(dpi) if dpi is not None else b''
    H, W = a.shape[:2]
    rows = _filtered(np.ascontiguousarray(a).reshape(H, W * 4))
    strategy = zlib.Z_RLE if 1 <= level <= 3 else zlib.Z_DEFAULT_STRATEGY
    co = zlib.compressobj(level, zlib.DEFLATED, 15, 8, strategy)
    z = co.compress(memoryview(rows).cast('B')) + co.flush()
    parts = [_SIGNATURE, _chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 6, 0, 0, 0)), phys]
    parts.extend(_chunk(b'IDAT', z[i:i + _IDAT_MAX]) for i in range(0, len(z), _IDAT_MAX))
    parts.append(_chunk(b'IEND', b''))
    return b''.join(parts)


def write_png(path_or_file, rgba, level=DEFAULT_LEVEL, dpi=None):
    """Write :func:`encode_png` bytes to a path or a binary file object."""
    data = encode_png(rgba, level, dpi)
    if hasattr(path_or_file, 'write'):
        path_or_file.write(data)
    else:
        with open(path_or_file, 'wb') as f:
            f.write(data)
