"""Images referenced by documents (``<image>``, ``feImage``): fetch and
decode raster images, parse SVG images.

Sources (``href``, else ``xlink:href``):

* ``data:`` URIs, base64 or percent-encoded.  The declared media type is not
  trusted: the bytes are sniffed (as resvg does).  PNG, JPEG, GIF (first
  frame) and WebP are decoded with Pillow; anything else that looks like XML
  or gzip is parsed as an SVG (``.svgz`` too).
* file paths (or ``file:`` URLs), relative paths resolved against the
  document's directory (``base_dir``; without one, against
  ``resources_dir``).  A file is only read when its real path (symlinks
  followed) lies under an allowed directory: ``allow_files_under`` when
  given, else the document's own directory (``base_dir``), plus
  ``resources_dir`` when given (the CLI's ``--allow-dir``).
* network URLs (``http:``, ``https:``, ...) are never fetched.

Anything that cannot be used -- a refused or missing file, broken data, an
unsupported format, an image above :data:`MAX_IMAGE_PIXELS` pixels or
:data:`MAX_IMAGE_BYTES` bytes (budgets of :mod:`raster.limits`) -- is skipped with one
:class:`raster.errors.RasterWarning`; no exception escapes.

SVG images are parsed with :func:`raster.parser.document.load_document` and
resolved by the parser (:attr:`raster.parser.context.Cache.parse_nested`)
into ``ImageNode.tree``.
Like a browser showing an SVG through ``<img>``, an SVG image is
self-contained: images inside it may only come from ``data:`` URIs (file
references are refused with a warning, so a document that references itself
stops after one level, as resvg's ``recursive-*`` tests expect), and images
nest at most :data:`MAX_IMAGE_DEPTH` levels deep.  EXIF orientation of
JPEG files is ignored, as resvg does.

Pixels are ``(H, W, 4) uint8`` straight-alpha RGBA, row 0 at the top; the
arrays are shared between uses of one image and are read-only.

>>> import base64, io
>>> from PIL import Image
>>> buf = io.BytesIO()
>>> Image.new('RGB', (4, 2), (255, 0, 0)).save(buf, 'PNG')
>>> pix = decode_raster(buf.getvalue())
>>> pix.shape, pix.dtype, pix[0, 0].tolist()
((2, 4, 4), dtype('uint8'), [255, 0, 0, 255])
>>> sniff(buf.getvalue()), sniff(b'<svg/>'), sniff(b'GIF89a...')
('png', 'svg', 'gif')
>>> parse_data_uri('data:text/plain;base64,aGk=')
('text/plain', b'hi')
"""

import base64
import dataclasses
import io
import os
import re
import urllib.parse
import warnings
from typing import NamedTuple, Optional

import numpy as np

from .. import limits
from ..errors import RasterError
from .document import load_document

__all__ = ['load_image', 'load_svg_data', 'fetch_image', 'fetch_document', 'fetch_stylesheet',
           'read_reference', 'is_network_reference', 'image_source', 'decode_raster', 'sniff',
           'parse_data_uri', 'ImageSource', 'ImageError', 'MAX_IMAGE_DEPTH', 'MAX_IMAGE_BYTES',
           'MAX_IMAGE_PIXELS', 'MAX_IMPORT_DEPTH', 'MAX_IMPORTS']

#: Deepest nesting of SVG images (an image inside an SVG image inside ...).
MAX_IMAGE_DEPTH = 4

#: Deepest chain of CSS ``@import`` rules followed (a sheet importing a
#: sheet importing ...), and most style sheets imported by one document.
MAX_IMPORT_DEPTH = 8
MAX_IMPORTS = 64

#: Default largest encoded image (file or decoded data URI) read, in bytes
#: (:attr:`raster.limits.Limits.max_image_bytes`).
MAX_IMAGE_BYTES = limits.DEFAULT.max_image_bytes

#: Default largest decoded raster image, in pixels (Pillow's
#: decompression-bomb limit; :attr:`raster.limits.Limits.max_image_pixels`,
#: at most ``max_pixels``).  Pillow's own ``Image.MAX_IMAGE_PIXELS`` still
#: applies (raster never changes it).
MAX_IMAGE_PIXELS = min(limits.DEFAULT.max_pixels, limits.DEFAULT.max_image_pixels)


def _max_bytes():
    return limits.current().max_image_bytes


def _max_pixels():
    lim = limits.current()
    return min(lim.max_pixels, lim.max_image_pixels)

_PIL_FORMATS = {'png': 'PNG', 'jpeg': 'JPEG', 'gif': 'GIF', 'webp': 'WEBP'}


class ImageError(RasterError):
    """An image cannot be used (refused, missing, broken, unsupported or
    too large).  The converters turn it into a warning."""


class ImageSource(NamedTuple):
    """Where image files may come from.

    Attributes
    ----------
    base_dir : str or None
        Directory relative paths resolve against.
    allowed : tuple of str
        Real paths of the directories files may be read from (and below).
    files : bool
        False inside SVG images: only ``data:`` URIs are used.
    """
    base_dir: Optional[str] = None
    allowed: tuple = ()
    files: bool = True


# ---------------------------------------------------------------------------
# Fetching
# ---------------------------------------------------------------------------

def parse_data_uri(href):
    """Split a ``data:`` URI into its media type and payload bytes.

    Parameters
    ----------
    href : str
        ``data:[<media type>][;base64],<data>``; whitespace inside base64
        data is ignored and missing ``=`` padding is tolerated.

    Returns
    -------
    (str, bytes)
        The declared media type (lower case, parameters dropped; may be
        empty) and the decoded bytes.

    Raises
    ------
    ImageError
        No comma, or invalid base64.

    >>> parse_data_uri('data:image/svg+xml,%3Csvg%2F%3E')
    ('image/svg+xml', b'<svg/>')
    """
    body = href.strip()[5:]
    head, sep, data = body.partition(',')
    if not sep:
        raise ImageError('data URI without a comma')
    params = [p.strip() for p in head.split(';')]
    mime = params[0].lower()
    if any(p.lower() == 'base64' for p in params[1:]):
        raw = ''.join(urllib.parse.unquote(data).split())
        raw = raw.rstrip('=')
        raw += '=' * (-len(raw) % 4)
        if len(raw) > _max_bytes() * 4 // 3 + 4:
            raise ImageError('data URI larger than %d bytes (max_image_bytes)' % _max_bytes())
        try:
            payload = base64.b64decode(raw, validate=False)
        except (ValueError, TypeError) as e:
            raise ImageError('invalid base64 in data URI (%s)' % e) from None
    else:
        payload = urllib.parse.unquote_to_bytes(data)
    if len(payload) > _max_bytes():
        raise ImageError('data URI larger than %d bytes (max_image_bytes)' % _max_bytes())
    return mime, payload


def _under(path, root):
    try:
        return os.path.commonpath([path, root]) == root
    except ValueError:          # different drives
        return False


def _resolve_file(href, source, what='image'):
    """Real path of a file reference, checked against the allowed dirs
    (``what`` names the kind of file in messages)."""
    if href[:5].lower() == 'file:':
        p = urllib.parse.urlparse(href)
        if p.netloc not in ('', 'localhost'):
            raise ImageError('file URL on another host refused: %s' % _short(href))
        href = urllib.parse.unquote(p.path)
    if not source.files:
        raise ImageError('%s file reference inside an SVG image refused: %s'
                         % (what, _short(href)))
    base = source.base_dir
    if not os.path.isabs(href):
        if base is None:
            raise ImageError('relative %s path with no base directory: %s' % (what, _short(href)))
        cand = os.path.join(base, href)
    else:
        cand = href
    if not os.path.exists(cand) and '%' in href:
        alt = urllib.parse.unquote(href)       # a URL-escaped file name
        cand2 = alt if os.path.isabs(alt) or base is None else os.path.join(base, alt)
        if os.path.exists(cand2):
            cand = cand2
    real = os.path.realpath(cand)
    if not any(_under(real, root) for root in source.allowed):
        raise ImageError('%s file outside the allowed directories refused: %s'
                         % (what, _short(href)))
    if not os.path.isfile(real):
        raise ImageError('%s file not found: %s' % (what, _short(href)))
    return real


def _read_file(path, what='image'):
    try:
        with open(path, 'rb') as f:
            size = os.fstat(f.fileno()).st_size
            if size > _max_bytes():
                data = b''
            else:
                data = f.read(-1 if _max_bytes() == float('inf') else int(_max_bytes()) + 1)
    except OSError as e:
        raise ImageError('cannot read %s file %s (%s)'
                         % (what, _short(path), e.strerror or e)) from None
    if size > _max_bytes() or len(data) > _max_bytes():
        raise ImageError('%s file larger than %d bytes (max_image_bytes): %s'
                         % (what, _max_bytes(), _short(path)))
    return data


_REPR = re.compile(r'<[^<>]*? at 0x[0-9A-Fa-f]+>')


def _no_reprs(msg):
    """``msg`` without object reprs (``<_io.BytesIO object at 0x...>``)."""
    return ' '.join(_REPR.sub('', msg).split())


def _short(s, n=60):
    s = ' '.join(str(s).split())
    return s if len(s) <= n else s[:n - 3] + '...'


# ---------------------------------------------------------------------------
# Decoding
# ---------------------------------------------------------------------------

def sniff(data):
    """The format of image bytes from their signature.

    Returns
    -------
    str or None
        ``'png'``, ``'jpeg'``, ``'gif'``, ``'webp'``, ``'svg'`` (XML text,
        possibly after a byte order mark, or gzip data: ``.svgz``) or None.
    """
    if data[:8] == b'\x89PNG\r\n\x1a\n':
        return 'png'
    if data[:3] == b'\xff\xd8\xff':
        return 'jpeg'
    if data[:6] in (b'GIF87a', b'GIF89a'):
        return 'gif'
    if data[:4] == b'RIFF' and data[8:12] == b'WEBP':
        return 'webp'
    if data[:2] == b'\x1f\x8b':
        return 'svg'
    head = data[:512]
    if head.startswith(b'\xef\xbb\xbf'):
        head = head[3:]
    if head.lstrip()[:1] == b'<':
        return 'svg'
    return None


def _to_rgba8(im):
    """A Pillow image to an (H, W, 4) uint8 straight RGBA array."""
    mode = im.mode
    if mode in ('I;16', 'I;16B', 'I;16L', 'I;16N', 'I'):
        # 16-bit (or 32-bit) grey: Pillow's convert clips instead of scaling
        g = np.asarray(im).astype(np.int64)
        trns = im.info.get('transparency')
        scale = 257 if mode != 'I' or g.max(initial=0) > 255 else 1
        g8 = np.clip((g + scale // 2) // scale, 0, 255).astype(np.uint8)
        out = np.empty(g.shape + (4,), np.uint8)
        out[..., :3] = g8[..., None]
        out[..., 3] = 255
        if isinstance(trns, int):
            out[g == trns, 3] = 0
        return out
    if mode != 'RGBA':
        im = im.convert('RGBA')
    return np.asarray(im, dtype=np.uint8).reshape(im.height, im.width, 4)


def decode_raster(data, kind=None):
    """Decode PNG, JPEG, GIF (first frame) or WebP bytes with Pillow.

    Parameters
    ----------
    data : bytes
    kind : str, optional
        The format (see :func:`sniff`); sniffed when None.

    Returns
    -------
    (H, W, 4) uint8 ndarray
        Straight-alpha RGBA, row 0 at the top.  16-bit channels are rounded
        to 8 bits; palette and grey images with ``tRNS`` transparency get
        their alpha.

    Raises
    ------
    ImageError
        Unsupported or broken data, or more than :data:`MAX_IMAGE_PIXELS`
        pixels.
    """
    from PIL import Image
    if kind is None:
        kind = sniff(data)
    fmt = _PIL_FORMATS.get(kind)
    if fmt is None:
        raise ImageError('unsupported image format')
    try:
        with warnings.catch_warnings():
            warnings.simplefilter('error', Image.DecompressionBombWarning)
            im = Image.open(io.BytesIO(data), formats=[fmt])
            w, h = im.size
            if w <= 0 or h <= 0:
                raise ImageError('image has no pixels')
            if w * h > _max_pixels():
                raise ImageError('image of %dx%d pixels exceeds the limit of %d pixels '
                                 '(max_image_pixels)' % (w, h, _max_pixels()))
            im.seek(0)
            im.load()
            return _to_rgba8(im)
    except ImageError:
        raise
    except (Image.DecompressionBombError, Image.DecompressionBombWarning):
        raise ImageError('image exceeds the decompression-bomb limit') from None
    except MemoryError:
        raise ImageError('image too large to decode') from None
    except Exception as e:      # Pillow raises many types on broken data
        msg = _no_reprs(str(e).splitlines()[0]) if str(e) else type(e).__name__
        raise ImageError('cannot decode %s image (%s)' % (kind.upper(), _short(msg))) from None


def _load_svg(data, source, cache, tolerance):
    """Parse and convert an SVG image one nesting level deeper."""
    depth = cache.options.image_depth + 1
    if depth > MAX_IMAGE_DEPTH:
        raise ImageError('SVG images nested deeper than %d levels' % MAX_IMAGE_DEPTH)
    root = load_document(data, max_bytes=_max_bytes())
    o = cache.options
    opts = type(o)(dpi=o.dpi, font_size=o.font_size, languages=o.languages or ('en',),
                   tolerance=tolerance, base_dir=source.base_dir, image_depth=depth)
    return cache.parse_nested(root, opts, cache.image_cache)


def load_svg_data(data, cache, tolerance=None):
    """Parse SVG document bytes that come from no file (a font's SVG
    glyph document) into a Tree, like an SVG image one nesting level
    deeper: self-contained (no files are read).

    Raises
    ------
    ImageError or RasterError
        Nested too deep, or not a usable document.
    """
    if tolerance is None:
        tolerance = cache.options.tolerance
    return _load_svg(data, ImageSource(None, (), False), cache, tolerance)


def fetch_image(href, source=ImageSource(), images=None):
    """Fetch the image an ``href`` names and decode it when it is a raster
    image.

    Parameters
    ----------
    href : str
        A ``data:`` URI, a file path or a ``file:`` URL.
    source : ImageSource
        Where files may be read from.
    images : dict or None
        Results (and errors) by resolved reference, shared between calls.

    Returns
    -------
    (kind, payload)
        ``kind`` is ``'png'``, ``'jpeg'``, ``'gif'``, ``'webp'`` (then
        ``payload`` is a read-only (H, W, 4) uint8 straight RGBA array) or
        ``'svg'`` (then ``payload`` is the document's bytes).

    Raises
    ------
    ImageError
        The reference is refused or the image cannot be used.
    """
    return _fetch(href, source, {} if images is None else images)[1:]


def _scheme(href):
    """The lower-case URL scheme of a stripped reference: '' for a path,
    'network' for a protocol-relative URL or a UNC path."""
    scheme = urllib.parse.urlsplit(href).scheme.lower() if ':' in href else ''
    if len(scheme) == 1:        # a Windows drive letter
        scheme = ''
    if href.startswith('//') or href.startswith('\\\\'):
        scheme = 'network'      # protocol-relative URL or UNC path
    return scheme


def is_network_reference(href):
    """True for a reference that would need the network (``http:``,
    ``https:``, ``ftp:``, ``//host/...``): never fetched."""
    return _scheme(href.strip()) in ('http', 'https', 'ftp', 'network')


def read_reference(href, source, what='font'):
    """The bytes a ``data:`` URI or a file reference names, under the rules
    images are read by (see the module docstring): a file only from an
    allowed directory, at most :data:`MAX_IMAGE_BYTES` bytes; network URLs
    are refused.  ``what`` names the kind of resource in messages.

    Raises
    ------
    ImageError
        Refused, missing, unreadable or too large.
    """
    href = href.strip()
    scheme = _scheme(href)
    if scheme == 'data':
        return parse_data_uri(href)[1]
    if scheme in ('', 'file'):
        return _read_file(_resolve_file(href, source, what), what)
    if scheme in ('http', 'https', 'ftp', 'network'):
        raise ImageError('network %s reference not fetched: %s' % (what, _short(href)))
    raise ImageError('%s URL with scheme %r is not supported: %s' % (what, scheme, _short(href)))


def _fetch(href, source, cache):
    """(key, kind, payload): payload is read-only pixels for raster kinds,
    the document bytes for 'svg'.  Results and errors are cached by key."""
    href = href.strip()
    scheme = _scheme(href)
    if scheme == 'data':
        key = ('data', href)
    elif scheme in ('', 'file'):
        key = ('file', _resolve_file(href, source))
    elif scheme in ('http', 'https', 'ftp', 'network'):
        raise ImageError('network image reference not fetched: %s' % _short(href))
    else:
        raise ImageError('image URL with scheme %r is not supported: %s'
                         % (scheme, _short(href)))
    r = cache.get(key)
    if r is None:
        try:
            data = parse_data_uri(href)[1] if key[0] == 'data' else _read_file(key[1])
            kind = sniff(data)
            if kind is None:
                raise ImageError('unrecognised image data: %s' % _short(href))
            if kind != 'svg':
                data = decode_raster(data, kind)
                data.setflags(write=False)
            r = (key, kind, data)
        except ImageError as e:
            r = e
        cache[key] = r
    if isinstance(r, ImageError):
        raise r
    return r


def load_image(href, cache, tolerance=None):
    """Fetch and decode the image an ``href`` names.

    Parameters
    ----------
    href : str
        A ``data:`` URI, a file path or a ``file:`` URL.
    cache : raster.parser.context.Cache
        The document's cache: where files may be read from (its options),
        the decoded images by resolved reference (shared with nested SVG
        images) and the parser for SVG images.
    tolerance : float, optional
        Flattening tolerance for an SVG image, in pixels of the image
        document at its natural size (default: the document's).

    Returns
    -------
    (H, W, 4) uint8 ndarray or raster.tree.Tree
        A raster image (read-only) or a resolved SVG document.

    Raises
    ------
    ImageError
        The reference is refused or the image cannot be used (see the
        module docstring).
    """
    images = cache.image_cache
    key, kind, payload = _fetch(href, image_source(cache.options), images)
    if kind != 'svg':
        return payload
    if tolerance is None:
        tolerance = cache.options.tolerance
    base = os.path.dirname(key[1]) if key[0] == 'file' else None
    return _remembered(images, ('tree', key, float(tolerance)), 'SVG image', href,
                       lambda: _load_svg(payload, ImageSource(base, (), False), cache,
                                         tolerance))


def _remembered(table, key, what, name, load):
    """``table[key]``, made by ``load()`` when missing; a failure is
    remembered too, as the ImageError ``cannot use <what> <name> (...)``,
    and raised on every use."""
    r = table.get(key)
    if r is None:
        try:
            r = load()
        except ImageError as e:
            r = e
        except (RasterError, OSError, ValueError) as e:
            msg = str(e).splitlines()[0] if str(e) else type(e).__name__
            r = ImageError('cannot use %s %s (%s)' % (what, _short(name, 40), msg))
        table[key] = r
    if isinstance(r, ImageError):
        raise r
    return r


def fetch_document(path, options, documents):
    """The real path and root element of another local SVG document that
    a reference (``use href="lib.svg#id"``) names, read under the same
    rules as image files: relative to the document's directory, only below
    the allowed directories, never from inside an SVG image.

    Parameters
    ----------
    path : str
        The file part of the reference (a path or a ``file:`` URL).
    options : raster.parser.Options
        The referencing document's options.
    documents : dict
        Loaded documents (and errors) by real path, shared by the
        documents of one rendering.

    Returns
    -------
    (str, lxml element)

    Raises
    ------
    ImageError
        The file is refused, missing, unreadable or not an SVG document.
    """
    real = _resolve_file(path, image_source(options))
    return _remembered(documents, real, 'document', path,
                       lambda: (real, load_document(_read_file(real), max_bytes=_max_bytes())))


def fetch_stylesheet(href, base_dir, options):
    """A style sheet that a CSS ``@import`` names: read under the rules of
    image files (relative to ``base_dir``, the importing sheet's
    directory; only below the allowed directories; never the network;
    never from inside an SVG image), or decoded from a ``data:`` URI.

    Parameters
    ----------
    href : str
        The import's URL (a path, ``file:`` or ``data:`` URL).
    base_dir : str or None
        Directory of the importing sheet (None: the document's).
    options : raster.parser.Options
        The document's options.

    Returns
    -------
    (str or None, str, str or None)
        The sheet's real path (None for a ``data:`` URI), its text (UTF-8,
        undecodable bytes replaced) and the directory its own imports
        resolve against.

    Raises
    ------
    ImageError
        The sheet is refused, missing, unreadable or too large.
    """
    href = href.strip()
    scheme = urllib.parse.urlsplit(href).scheme.lower() if ':' in href else ''
    if len(scheme) == 1:
        scheme = ''
    if href.startswith('//') or href.startswith('\\\\'):
        scheme = 'network'
    if scheme == 'data':
        return None, parse_data_uri(href)[1].decode('utf-8', 'replace'), base_dir
    if scheme not in ('', 'file'):
        raise ImageError('style sheet URL not fetched: %s' % _short(href))
    source = image_source(options)
    if base_dir is not None:
        source = source._replace(base_dir=base_dir)
    try:
        real = _resolve_file(href, source)
    except ImageError as e:
        raise ImageError(str(e).replace('image file', 'style sheet', 1)) from None
    return real, _read_file(real).decode('utf-8', 'replace'), os.path.dirname(real)


def image_source(options):
    """The :class:`ImageSource` of a document parsed with ``options``
    (nested SVG images read no files)."""
    if options.image_depth > 0:
        return ImageSource(None, (), False)
    base_dir = options.base_dir
    roots = []
    first = options.allow_files_under if options.allow_files_under is not None else base_dir
    for d in (first, options.resources_dir):
        if d is not None:
            roots.append(os.path.realpath(os.fspath(d)))
    if base_dir is None and options.resources_dir is not None:
        base_dir = options.resources_dir
    return ImageSource(None if base_dir is None else os.fspath(base_dir), tuple(roots), True)
