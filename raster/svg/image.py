"""The SVG ``<image>`` element: fetch, decode and place raster and SVG images.

:func:`build_image` is called by the tree builder (:mod:`raster.svg.build`)
for every ``image`` element and appends an
:class:`~raster.svg.tree.ImageNode` (wrapped in a Group when the element has a
transform, clip path, mask, blend mode ...) to the output list.

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
:data:`MAX_IMAGE_BYTES` bytes -- is skipped with one
:class:`raster.errors.RasterWarning`; no exception escapes.

SVG images are parsed with :func:`raster.svg.document.load_document` and
resolved with :func:`raster.svg.build.build_tree` into ``ImageNode.tree``.
Like a browser showing an SVG through ``<img>``, an SVG image is
self-contained: images inside it may only come from ``data:`` URIs (file
references are refused with a warning, so a document that references itself
stops after one level, as resvg's ``recursive-*`` tests expect), and images
nest at most :data:`MAX_IMAGE_DEPTH` levels deep.  The builder's
``tolerance`` (device pixels at the document's natural size) is honoured
inside SVG images: an image document drawn larger than its natural size is
built with a proportionally finer tolerance.

Geometry: ``x``, ``y``, ``width``, ``height`` (``auto`` or absent: the
intrinsic size, the other side keeping the aspect ratio; zero or negative:
not rendered), ``preserveAspectRatio`` through
:func:`raster.svg.values.viewbox_transform`; ``ImageNode.transform`` maps
image pixels (SVG images: the image document's pixels) to the element's user
space, ``ImageNode.clip`` is the visible rectangle (set for ``slice`` and
for every SVG image, whose content may overflow its natural size).
``image-rendering`` ``optimizeSpeed``/``pixelated``/``crisp-edges`` selects
nearest-neighbour sampling (``smooth=False``).  EXIF orientation of JPEG
files is ignored, as resvg does.

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
import contextvars
import io
import math
import os
import urllib.parse
import warnings
from typing import NamedTuple, Optional

import numpy as np

from .. import limits
from ..errors import RasterError
from ..geometry.pathdata import rect_path
from .tree import ImageNode, PathNode
from .values import parse_length, parse_preserve_aspect_ratio, viewbox_transform

__all__ = ['build_image', 'load_image', 'decode_raster', 'sniff', 'parse_data_uri',
           'ImageSource', 'ImageError', 'MAX_IMAGE_DEPTH', 'MAX_IMAGE_BYTES', 'MAX_IMAGE_PIXELS']

#: Deepest nesting of SVG images (an image inside an SVG image inside ...).
MAX_IMAGE_DEPTH = 4

#: Largest encoded image (file or decoded data URI) read, in bytes.
MAX_IMAGE_BYTES = 64 * 1024 * 1024

#: Largest decoded raster image, in pixels (Pillow's decompression-bomb limit,
#: at most :data:`raster.limits.MAX_PIXELS`).
MAX_IMAGE_PIXELS = min(limits.MAX_PIXELS, 89_478_485)

_NEAREST = frozenset(['optimizeSpeed', 'pixelated', 'crisp-edges'])
_XLINK_HREF = '{http://www.w3.org/1999/xlink}href'
_PIL_FORMATS = {'png': 'PNG', 'jpeg': 'JPEG', 'gif': 'GIF', 'webp': 'WEBP'}


class ImageError(RasterError):
    """An image cannot be used (refused, missing, broken, unsupported or
    too large).  :func:`build_image` turns it into a warning."""


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


class _Nesting(NamedTuple):
    depth: int          # nesting depth of the document being built
    cache: dict         # shared decode cache of the outermost build


# Set while an SVG image is being built (build_tree has no parameter for it).
_NESTING = contextvars.ContextVar('raster_svg_image_nesting', default=None)


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
        if len(raw) > MAX_IMAGE_BYTES * 4 // 3 + 4:
            raise ImageError('data URI larger than %d bytes' % MAX_IMAGE_BYTES)
        try:
            payload = base64.b64decode(raw, validate=False)
        except (ValueError, TypeError) as e:
            raise ImageError('invalid base64 in data URI (%s)' % e) from None
    else:
        payload = urllib.parse.unquote_to_bytes(data)
    if len(payload) > MAX_IMAGE_BYTES:
        raise ImageError('data URI larger than %d bytes' % MAX_IMAGE_BYTES)
    return mime, payload


def _under(path, root):
    try:
        return os.path.commonpath([path, root]) == root
    except ValueError:          # different drives
        return False


def _resolve_file(href, source):
    """Real path of a file reference, checked against the allowed dirs."""
    if href[:5].lower() == 'file:':
        p = urllib.parse.urlparse(href)
        if p.netloc not in ('', 'localhost'):
            raise ImageError('file URL on another host refused: %s' % _short(href))
        href = urllib.parse.unquote(p.path)
    if not source.files:
        raise ImageError('file reference inside an SVG image refused: %s' % _short(href))
    base = source.base_dir
    if not os.path.isabs(href):
        if base is None:
            raise ImageError('relative image path with no base directory: %s' % _short(href))
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
        raise ImageError('image file outside the allowed directories refused: %s'
                         % _short(href))
    if not os.path.isfile(real):
        raise ImageError('image file not found: %s' % _short(href))
    return real


def _read_file(path):
    try:
        with open(path, 'rb') as f:
            data = f.read(MAX_IMAGE_BYTES + 1)
    except OSError as e:
        raise ImageError('cannot read image file %s (%s)'
                         % (_short(path), e.strerror or e)) from None
    if len(data) > MAX_IMAGE_BYTES:
        raise ImageError('image file larger than %d bytes: %s' % (MAX_IMAGE_BYTES, _short(path)))
    return data


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
            if w * h > MAX_IMAGE_PIXELS:
                raise ImageError('image of %dx%d pixels exceeds the limit of %d pixels'
                                 % (w, h, MAX_IMAGE_PIXELS))
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
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        raise ImageError('cannot decode %s image (%s)' % (kind.upper(), _short(msg))) from None


def _load_svg(data, builder, source, depth, cache, tolerance):
    """Parse and build an SVG image one nesting level deeper."""
    from .build import build_tree
    from .document import load_document
    if depth > MAX_IMAGE_DEPTH:
        raise ImageError('SVG images nested deeper than %d levels' % MAX_IMAGE_DEPTH)
    root = load_document(data, max_bytes=MAX_IMAGE_BYTES)
    token = _NESTING.set(_Nesting(depth, cache))
    try:
        return build_tree(root, base_dir=source.base_dir, dpi=getattr(builder, 'dpi', 96),
                          font_size=getattr(builder, 'font_size', 12),
                          languages=getattr(builder, 'languages', ('en',)) or ('en',),
                          tolerance=tolerance)
    finally:
        _NESTING.reset(token)


def _fetch(href, source, cache):
    """(key, kind, payload): payload is read-only pixels for raster kinds,
    the document bytes for 'svg'.  Results and errors are cached by key."""
    href = href.strip()
    scheme = urllib.parse.urlsplit(href).scheme.lower() if ':' in href else ''
    if len(scheme) == 1:        # a Windows drive letter
        scheme = ''
    if href.startswith('//') or href.startswith('\\\\'):
        scheme = 'network'      # protocol-relative URL or UNC path
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


def load_image(href, source=ImageSource(), *, builder=None, depth=0, cache=None,
               tolerance=None):
    """Fetch and decode the image an ``href`` names.

    Parameters
    ----------
    href : str
        A ``data:`` URI, a file path or a ``file:`` URL.
    source : ImageSource
        Where files may be read from.
    builder : optional
        The tree builder (its dpi, font size, languages and tolerance are
        used for SVG images).
    depth : int
        Nesting depth of the document the reference appears in (0: the
        outermost document).
    cache : dict, optional
        Results by resolved reference (and tolerance for SVG images), shared
        between uses.
    tolerance : float, optional
        Flattening tolerance for an SVG image, in pixels of the image
        document at its natural size (see
        :func:`raster.svg.build.build_tree`); default: the builder's, else
        0.1.

    Returns
    -------
    (H, W, 4) uint8 ndarray or raster.svg.tree.Tree
        A raster image (read-only) or a resolved SVG document.

    Raises
    ------
    ImageError
        The reference is refused or the image cannot be used (see the
        module docstring).
    """
    if cache is None:
        cache = {}
    key, kind, payload = _fetch(href, source, cache)
    if kind != 'svg':
        return payload
    if tolerance is None:
        tolerance = getattr(builder, 'tolerance', 0.1)
    tkey = ('tree', key, float(tolerance))
    r = cache.get(tkey)
    if r is None:
        base = os.path.dirname(key[1]) if key[0] == 'file' else None
        try:
            r = _load_svg(payload, builder, ImageSource(base, (), False), depth + 1, cache,
                          tolerance)
        except ImageError as e:
            r = e
        except (RasterError, OSError, ValueError) as e:
            msg = str(e).splitlines()[0] if str(e) else type(e).__name__
            r = ImageError('cannot use SVG image %s (%s)' % (_short(href, 40), msg))
        cache[tkey] = r
    if isinstance(r, ImageError):
        raise r
    return r


# ---------------------------------------------------------------------------
# The element
# ---------------------------------------------------------------------------

def _source_of(builder, depth):
    """ImageSource of the document ``builder`` is building."""
    if depth > 0:
        return ImageSource(None, (), False)
    opts = getattr(builder, 'image_sources', None)
    if opts is None:
        opts = (getattr(builder, 'base_dir', None), getattr(builder, 'allow_files_under', None),
                getattr(builder, 'resources_dir', None))
    base_dir, allow_under, resources_dir = opts
    roots = []
    first = allow_under if allow_under is not None else base_dir
    for d in (first, resources_dir):
        if d is not None:
            roots.append(os.path.realpath(os.fspath(d)))
    if base_dir is None and resources_dir is not None:
        base_dir = resources_dir
    return ImageSource(None if base_dir is None else os.fspath(base_dir), tuple(roots), True)


def _size_attr(builder, el, name, axis, ctx):
    """A width/height attribute: a length, None for auto (absent, 'auto',
    invalid)."""
    s = el.get(name)
    if s is None or s.strip() == 'auto':
        return None
    return parse_length(s, axis, ctx)


def build_image(builder, el, pinh, pown, st, out):
    """Build an ``image`` element and append its node(s) to ``out``.

    Parameters
    ----------
    builder : raster.svg.build._Builder
        The tree builder (styles, lengths, effects, warnings).
    el : lxml element
        The ``image`` element.
    pinh, pown : dict
        Computed inherited / own style of the rendering parent.
    st : raster.svg.build._State
        Viewport size, CTM and nesting state of the parent.
    out : list
        Nodes of the parent; receives an ImageNode, or a Group holding it
        when the element has a transform or group effects.

    Returns
    -------
    ImageNode or None
        None when nothing is drawn (hidden, zero size, or the image cannot
        be used: then one RasterWarning says why).
    """
    decl = builder.styles.get(el)
    if decl and decl.get('display', '').strip() == 'none':
        return None
    if not builder.passes_conditions(el) or not builder.tick():
        return None
    inh, own = builder.style(el, pinh, pown)
    if inh.get('visibility', 'visible') in ('hidden', 'collapse'):
        return None
    ctx = builder.ctx(inh, st)
    t = builder.transform_of(el, own, ctx)
    if t is None:
        return None
    w = _size_attr(builder, el, 'width', 'x', ctx)
    h = _size_attr(builder, el, 'height', 'y', ctx)
    if (w is not None and not w > 0) or (h is not None and not h > 0):
        return None
    href = el.get('href')
    if href is None:
        href = el.get(_XLINK_HREF)
    if href is None or not href.strip():
        return None
    nest = _NESTING.get()
    depth = 0 if nest is None else nest.depth
    cache = getattr(builder, '_image_cache', None)
    if cache is None:
        cache = {} if nest is None else nest.cache
        try:
            builder._image_cache = cache
        except AttributeError:
            pass
    source = _source_of(builder, depth)
    tol = float(getattr(builder, 'tolerance', 0.1))
    try:
        img = load_image(href, source, builder=builder, depth=depth, cache=cache, tolerance=tol)
    except ImageError as e:
        builder.warn(('image', str(e)), 'image not rendered: %s' % e)
        return None
    if isinstance(img, np.ndarray):
        iw, ih = float(img.shape[1]), float(img.shape[0])
        tree = None
    else:
        iw, ih = float(img.width), float(img.height)
        tree = img
    if not (iw > 0 and ih > 0):
        return None
    if w is None and h is None:
        w, h = iw, ih
    elif w is None:
        w = h * iw / ih
    elif h is None:
        h = w * ih / iw
    x = builder.length(el, 'x', 'x', ctx)
    y = builder.length(el, 'y', 'y', ctx)
    par = parse_preserve_aspect_ratio(el.get('preserveAspectRatio', ''))
    try:
        m = viewbox_transform((0.0, 0.0, iw, ih), par, w, h, x, y)
    except RasterError:
        return None
    if tree is not None:
        # the image document's tolerance is in its own pixels: when it is
        # scaled up, rebuild it finer (by powers of two, so uses share)
        scale = (st.ctm @ t @ m).max_scale()
        if scale > 1.0 and math.isfinite(scale):
            fine = tol * 2.0 ** math.floor(math.log2(1.0 / scale))
            try:
                tree = load_image(href, source, builder=builder, depth=depth, cache=cache,
                                  tolerance=max(fine, 1e-9))
            except ImageError as e:
                builder.warn(('image', str(e)), 'image not rendered: %s' % e)
                return None
    clip = None
    slice_ = par is not None and par[0] != 'none' and par[1] == 'slice'
    if tree is not None or slice_:
        # visible part: the image's box (under m) within the viewport
        x0 = max(x, m.e)
        y0 = max(y, m.f)
        x1 = min(x + w, m.e + m.a * iw)
        y1 = min(y + h, m.f + m.d * ih)
        if not (x1 > x0 and y1 > y0):
            return None
        clip = (x0, y0, x1 - x0, y1 - y0)
    smooth = inh.get('image-rendering', 'auto').strip() not in _NEAREST
    node = ImageNode(id=el.get('id') or '', view_rect=(x, y, w, h), transform=m, clip=clip,
                     pixels=None if tree is not None else img, tree=tree, smooth=smooth)
    builder.note_id(el, node)
    # group effects; an object bounding box (clip path / mask units) is the
    # image's viewport, so effects see a rectangle standing in for the image
    proxy = [PathNode(path=rect_path(x, y, w, h))]
    e = builder.effects(el, own, st.sub(t), proxy)
    if not e.ok or e.opacity <= 0.0:
        return None
    if not e.composited:
        node.opacity = e.opacity        # drawn in one pass: no layer needed
        e = dataclasses.replace(e, opacity=1.0)
    builder.emit(node, t, e, out)
    return node
