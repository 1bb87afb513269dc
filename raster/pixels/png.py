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
from typing import NamedTuple

import numpy as np

from ..errors import CanvasError

__all__ = ['encode_png', 'encode_png_strips', 'write_png', 'phys_chunk', 'DEFAULT_LEVEL',
           'STRIP_PIXELS', 'PNGWriter', 'compress_strip', 'CompressedStrip']

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


def _filtered(raw, prev=None, scratch=None, first_up=True):
    """Rows of ``raw`` ((H, N) uint8) each prefixed with its filter type
    (0 None, 1 Sub, 2 Up) and filtered by it: (H, N + 1) uint8.  ``prev``
    ((N,) uint8) is the image row above ``raw[0]`` (None: ``raw`` starts the
    image, where Up sees a row of zeros).  ``scratch``: optional (3, h, N)
    uint8 work space, h >= H, reused from strip to strip.  ``first_up``
    False: the first row is not given the Up filter (the row above it is
    not known here: a strip compressed on its own)."""
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
    if not first_up:
        costs[2, 0] = np.iinfo(np.uint32).max
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


class CompressedStrip(NamedTuple):
    """Rows of a PNG image filtered and deflated on their own
    (:func:`compress_strip`): ``data`` (raw deflate, ending on a byte
    boundary, not final), the ``adler`` checksum (Adler-32) and ``length``
    in bytes of the filtered rows, and their count ``rows``."""
    data: bytes
    adler: int
    length: int
    rows: int


def compress_strip(rgba, level=DEFAULT_LEVEL, first=False):
    """Filter and deflate a strip of rows of a PNG image on its own, so
    strips can be compressed in any order (or in other processes) and
    joined by :meth:`PNGWriter.write_compressed`.

    Parameters
    ----------
    rgba : (h, W, 4) uint8 ndarray
        Straight RGBA rows.
    level : int
        zlib level 0-9 (as for :func:`encode_png`).
    first : bool
        The strip starts the image (its first row may use the Up filter
        against the zero row above the image); otherwise that row is
        filtered with None or Sub, as the row above is not known.

    Returns
    -------
    CompressedStrip

    Raises
    ------
    CanvasError
        Not an (h, W, 4) uint8 array with h, W >= 1, or a bad level.
    """
    a = np.asarray(rgba)
    if a.dtype != np.uint8 or a.ndim != 3 or a.shape[2] != 4 or 0 in a.shape:
        raise CanvasError('PNG strip must be (h, W, 4) uint8, got %s %r' % (a.dtype, a.shape))
    level = _check_level(level)
    h, w = a.shape[:2]
    raw = np.ascontiguousarray(a).reshape(h, w * 4)
    step = max(1, STRIP_PIXELS // w)
    co = zlib.compressobj(level, zlib.DEFLATED, -15, 8, _strategy(level))
    scratch = np.empty((3, min(step, h), w * 4), np.uint8)
    parts, adler, prev = [], 1, None
    for y in range(0, h, step):
        f = memoryview(_filtered(raw[y:y + step], prev, scratch,
                                 first_up=first or y > 0)).cast('B')
        adler = zlib.adler32(f, adler)
        parts.append(co.compress(f))
        prev = raw[min(h, y + step) - 1]
    parts.append(co.flush(zlib.Z_SYNC_FLUSH))
    return CompressedStrip(b''.join(parts), adler, h * (w * 4 + 1), h)


def _strategy(level):
    return zlib.Z_RLE if 1 <= level <= 3 else zlib.Z_DEFAULT_STRATEGY


_ADLER_BASE = 65521


def _adler_join(a1, a2, len2):
    """Adler-32 of two byte strings joined, from their checksums and the
    second one's length (s1 = 1 + the bytes' sum, s2 = the sum of the
    running s1 values, both modulo 65521)."""
    s1a, s2a = a1 & 0xFFFF, a1 >> 16
    s1b, s2b = a2 & 0xFFFF, a2 >> 16
    s1 = (s1a + s1b - 1) % _ADLER_BASE
    s2 = (s2a + s2b + len2 * (s1a - 1)) % _ADLER_BASE
    return (s2 << 16) | s1


class PNGWriter:
    """A PNG file written as strips of rows arrive, top to bottom, with a
    fixed amount of memory whatever the image's size.

    Each strip is filtered and deflated on its own (:func:`compress_strip`;
    the first row of every strip but the first uses the None or Sub filter)
    and its bytes go to the file in ``IDAT`` chunks at once; the zlib stream
    is the strips' deflate data joined, with one checksum.  The bytes do
    not depend on who compressed the strips: :meth:`write` compresses here,
    :meth:`write_compressed` takes strips compressed elsewhere (worker
    processes).

    Parameters
    ----------
    file : binary file object
        Where the PNG goes (only ``write`` is called).
    width, height : int
        Image size in pixels.
    level, dpi :
        As for :func:`encode_png`.

    Raises
    ------
    CanvasError
        Bad size, level or resolution; strips of the wrong width; more or
        (at :meth:`close`) fewer than ``height`` rows.

    >>> import io
    >>> img = np.arange(4 * 3 * 4, dtype=np.uint8).reshape(4, 3, 4)
    >>> out = io.BytesIO()
    >>> with PNGWriter(out, 3, 4) as png:
    ...     png.write(img[:3]); png.write(img[3:])
    >>> from PIL import Image
    >>> np.array_equal(np.asarray(Image.open(io.BytesIO(out.getvalue()))), img)
    True
    """

    def __init__(self, file, width, height, level=DEFAULT_LEVEL, dpi=None):
        W, H = int(width), int(height)
        if W < 1 or H < 1:
            raise CanvasError('PNG size must be positive, got %r x %r' % (width, height))
        self.file, self.width, self.height = file, W, H
        self.level = _check_level(level)
        self.rows = 0
        self._adler = 1
        self._closed = False
        # zlib header: deflate, 32 kB window, no dictionary (31 divides it)
        cmf = 0x78
        flg = 31 - (cmf * 256) % 31
        file.write(_SIGNATURE + _chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 6, 0, 0, 0))
                   + (phys_chunk(dpi) if dpi is not None else b''))
        self._pending = bytearray((cmf, flg))

    def write(self, rgba):
        """Append rows: (h, width, 4) uint8 straight RGBA."""
        a = np.asarray(rgba)
        if a.ndim != 3 or a.shape[1:] != (self.width, 4):
            raise CanvasError('PNG strip must be (h, %d, 4) uint8, got %s %r'
                              % (self.width, a.dtype, a.shape))
        if len(a):
            self.write_compressed(compress_strip(a, self.level, first=self.rows == 0))

    def write_compressed(self, strip):
        """Append the rows of a :class:`CompressedStrip` (made with this
        writer's level and width, and ``first`` for the first one)."""
        if self._closed:
            raise CanvasError('PNG already closed')
        if strip.length != strip.rows * (self.width * 4 + 1):
            raise CanvasError('PNG strip of another width')
        self.rows += strip.rows
        if self.rows > self.height:
            raise CanvasError('PNG strips hold more than %d rows' % self.height)
        self._adler = _adler_join(self._adler, strip.adler, strip.length)
        self._pending += strip.data
        if len(self._pending) >= _IDAT_MAX:
            n = len(self._pending) - len(self._pending) % _IDAT_MAX
            for i in range(0, n, _IDAT_MAX):
                self.file.write(_chunk(b'IDAT', bytes(self._pending[i:i + _IDAT_MAX])))
            del self._pending[:n]

    def close(self):
        """Finish the stream (checks that ``height`` rows were written)."""
        if self._closed:
            return
        if self.rows != self.height:
            raise CanvasError('PNG strips hold %d rows, not %d' % (self.rows, self.height))
        self._closed = True
        self._pending += zlib.compressobj(self.level, zlib.DEFLATED, -15).flush()
        self._pending += struct.pack('>I', self._adler)
        z = bytes(self._pending)
        self._pending = bytearray()
        for i in range(0, len(z), _IDAT_MAX):
            self.file.write(_chunk(b'IDAT', z[i:i + _IDAT_MAX]))
        self.file.write(_chunk(b'IEND', b''))

    def __enter__(self):
        return self

    def __exit__(self, kind, value, tb):
        if kind is None:
            self.close()


def write_png(path_or_file, rgba, level=DEFAULT_LEVEL, dpi=None):
    """Write :func:`encode_png` bytes to a path or a binary file object."""
    data = encode_png(rgba, level, dpi)
    if hasattr(path_or_file, 'write'):
        path_or_file.write(data)
    else:
        with open(path_or_file, 'wb') as f:
            f.write(data)
