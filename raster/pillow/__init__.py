"""A Pillow plugin for SVG and SVGZ, rendered by raster.

Opt in, once per process (``import raster`` alone never registers it)::

    import raster.pillow
    raster.pillow.register()            # or: import raster.pillow.auto
    from PIL import Image
    im = Image.open('drawing.svg')      # .svgz too; also file objects, by content
    im.size, im.mode                    # natural size, 'RGBA'

After registering, ``Image.open`` recognises SVG by its content (XML whose
root is ``<svg>``, or gzip holding it), so files without an extension and
file objects work; ``.svg`` / ``.svgz`` and ``image/svg+xml`` are
registered for saving dialogs and ``formats=['SVG']``.  The document is
parsed and resolved when it is opened and drawn on first access to the
pixels (``load()``, ``convert()``, ``save()`` ...).

Another size or resolution:

* ``raster.pillow.open(path_or_file, width=..., height=..., zoom=...,
  dpi=..., background=...)`` opens at that size directly (no registration
  needed); one of ``width`` / ``height`` keeps the aspect ratio;
* ``im.draft(None, (w, h))`` on an image from ``Image.open``, before its
  pixels are loaded, re-targets the drawing: the result is at least
  ``w`` x ``h`` with the aspect ratio kept, drawn at that size rather than
  scaled from the natural one (Pillow's ``thumbnail()`` calls ``draft``, so
  thumbnails of SVGs are drawn crisply);
* ``register(dpi=..., fonts=..., resources_dir=..., background=...)``
  sets the defaults ``Image.open`` uses.

``im.info['dpi']`` is the resolution at which the document keeps its
physical size (``dpi`` times the scale of the natural size).  Text is drawn
with the fonts of ``fonts`` (a :class:`raster.FontOptions`; default: the
system's fonts); images referenced by file are read
from the document's directory (and ``resources_dir``) when it was opened
by path.
"""

from __future__ import annotations

import contextvars
import os

from PIL import Image, ImageFile

from ..errors import RasterError, SVGError
from ..fonts import FontOptions

__all__ = ['FORMAT', 'SvgImageFile', 'register', 'open']

#: Pillow format name of the plugin.
FORMAT = 'SVG'
EXTENSIONS = ('.svg', '.svgz')
MIME = 'image/svg+xml'

_BUILT_IN = {'dpi': 96.0, 'fonts': None, 'resources_dir': None, 'background': None,
             'limits': None}
_defaults = dict(_BUILT_IN)      # what Image.open uses (set by register())
# options of one raster.pillow.open() call, seen by SvgImageFile._open
_pending = contextvars.ContextVar('raster_pillow_options', default=None)


def _accept(prefix: bytes) -> bool:
    """First bytes that may start an SVG document: gzip data, or markup
    after an optional BOM and white space (``_open`` then checks the root)."""
    if prefix[:2] == b'\x1f\x8b':
        return True
    return prefix.lstrip(b'\xef\xbb\xbf \t\r\n')[:1] == b'<'


def _options(dpi=None, fonts=None, resources_dir=None, background=None, base=None,
             font_dirs=None, limits=None):
    """Checked options, unset ones taken from ``base`` (default: the
    built-in defaults)."""
    from ..svg import font_options, parse_background
    o = dict(_BUILT_IN if base is None else base)
    if limits is not None:
        from .. import limits as budgets
        budgets.resolve(limits)                 # checked now
        o['limits'] = limits
    if dpi is not None:
        try:
            d = float(dpi)
        except (TypeError, ValueError):
            d = float('nan')
        if not (d > 0 and d != float('inf')):
            raise SVGError('dpi must be a positive number, got %r' % (dpi,))
        o['dpi'] = d
    if fonts is not None or font_dirs is not None:
        o['fonts'] = font_options(fonts, font_dirs, stacklevel=4)
    if resources_dir is not None:
        o['resources_dir'] = resources_dir
    if background is not None:
        o['background'] = parse_background(background)
    return o


class SvgImageFile(ImageFile.ImageFile):
    """An SVG document as a Pillow image (mode ``RGBA``, straight alpha).

    Opened by ``Image.open`` once :func:`register` ran, or by :func:`open`.
    The pixels are drawn by :func:`raster.renderer.render_tree` on
    ``load()``; :meth:`draft` changes the size they are drawn at."""

    format = FORMAT
    format_description = 'Scalable Vector Graphics (drawn by raster)'

    def _open(self):
        from .. import limits
        from ..errors import LimitError
        from ..parser.document import load_document
        from ..sources import read_stream
        opts = _pending.get() or _defaults
        self._svg_limits = lim = limits.resolve(opts['limits'])
        with limits.applied(lim):
            data = read_stream(self.fp, lim.max_input_bytes)
            if isinstance(data, str):
                data = data.encode('utf-8')
            try:
                root = load_document(data)
            except LimitError:                  # SVG, over a budget: said as it is
                raise
            except RasterError as e:            # not (readable) SVG: let Pillow try others
                raise SyntaxError(str(e)) from None
            self._open_tree(root, opts)

    def _open_tree(self, root, opts):
        from ..parser import build_tree
        path = self.filename or getattr(self.fp, 'name', None)
        if isinstance(path, bytes):
            path = os.fsdecode(path)
        base = (os.path.dirname(os.path.abspath(path))
                if isinstance(path, str) and path and os.path.isfile(path) else None)
        self._svg_tree = build_tree(root, base_dir=base, dpi=opts['dpi'],
                                    fonts=FontOptions.coerce(opts['fonts']),
                                    resources_dir=opts['resources_dir'])
        self._svg_dpi = opts['dpi']
        self._svg_background = opts['background']
        self._mode = 'RGBA'
        self._set_svg_size(None, None, None)
        self.tile = []

    def _set_svg_size(self, width, height, zoom):
        from ..renderer import output_size
        t = self._svg_tree
        w, h, sx, sy = output_size(t.width, t.height, width, height, zoom)
        self._svg_request = (width, height, zoom)
        self._size = (w, h)
        self.info['dpi'] = (self._svg_dpi * sx, self._svg_dpi * sy)

    def draft(self, mode: str | None, size: tuple[int, int] | None):
        """Draw at no less than ``size`` = ``(w, h)``, keeping the natural
        aspect ratio, instead of the current size; ``mode`` is ignored
        (always RGBA).

        Returns ``('RGBA', box)`` with ``box`` the whole new image (the
        whole original image maps onto it), or None once the pixels are
        loaded or without a size."""
        if size is None or getattr(self, '_svg_tree', None) is None:      # loaded already
            return None
        from ..renderer import output_size
        t = self._svg_tree
        nw, nh = output_size(t.width, t.height)[:2]
        zoom = max(size[0] / nw, size[1] / nh)
        if not zoom > 0:
            return None
        self._set_svg_size(None, None, zoom)
        return self.mode, (0, 0) + self.size

    def load(self):
        tree = getattr(self, '_svg_tree', None)
        if tree is not None:                 # not drawn yet
            from .. import limits
            from ..renderer import render_tree
            width, height, zoom = self._svg_request
            with limits.applied(self._svg_limits):
                canvas = render_tree(tree, width=width, height=height, zoom=zoom,
                                     background=self._svg_background, dtype='uint8')
            self.load_prepare()
            self.frombytes(canvas.to_rgba8().tobytes())
            if self.fp is not None and getattr(self, '_exclusive_fp', False):
                self.fp.close()
            self.fp = None
            self._svg_tree = None
        return super().load()


def register(*, dpi: float | None = None, fonts=None, resources_dir: str | None = None,
             background=None, font_dirs=None, limits=None) -> None:
    """Register the SVG plugin with Pillow (``Image.open`` then opens SVG and
    SVGZ); the keywords set the options it opens with, unset ones being the
    built-in defaults.

    Parameters
    ----------
    dpi : float, optional
        Resolution for absolute units (default 96).
    fonts : raster.FontOptions or dict, optional
        The fonts of text (default: the system's fonts); ``font_dirs`` is
        its deprecated spelling (see :func:`raster.load_svg`).
    resources_dir : str, optional
        A directory images may be read from besides the document's own.
    background : str or tuple, optional
        A CSS colour under the drawing (default transparent).
    limits : raster.limits.Limits, mapping or 'unlimited', optional
        Budgets (:mod:`raster.limits`; default: those in force when an
        image is opened).

    Calling it again replaces the options (``register()`` restores the
    built-in ones).
    """
    global _defaults
    _defaults = _options(dpi, fonts, resources_dir, background, font_dirs=font_dirs,
                         limits=limits)
    Image.register_open(FORMAT, SvgImageFile, _accept)
    Image.register_extensions(FORMAT, list(EXTENSIONS))
    Image.register_mime(FORMAT, MIME)


def open(fp, *, width: int | None = None, height: int | None = None,
         zoom: float | None = None, dpi: float | None = None, background=None,
         fonts=None, resources_dir=None, font_dirs=None, limits=None) -> SvgImageFile:
    """Open an SVG or SVGZ document as a Pillow image of a chosen size.

    Parameters
    ----------
    fp : str, os.PathLike or binary file object
        The document.
    width, height : int, optional
        Output size in pixels; one of them keeps the aspect ratio; neither:
        the natural size.
    zoom : float, optional
        Scale of the natural size (instead of width/height).
    dpi, background, fonts, resources_dir, limits :
        As for :func:`register`; unset ones are the registered defaults.

    Returns
    -------
    SvgImageFile
        Mode ``RGBA``; drawn on first access to its pixels.

    Raises
    ------
    raster.errors.RasterIOError
        The file cannot be read, or ``fp`` is a URL.
    raster.errors.SVGError
        Not an SVG document, a bad option.
    raster.errors.CanvasError
        A bad size or zoom.
    """
    from ..sources import local_path
    opts = _options(dpi, fonts, resources_dir, background, base=_defaults,
                    font_dirs=font_dirs, limits=limits)
    if isinstance(fp, (str, os.PathLike)):
        path = local_path(fp)
        f = _open_file(path)
        exclusive = True
    else:
        f, path, exclusive = fp, None, False
    token = _pending.set(opts)
    try:
        try:
            im = SvgImageFile(f, path)
        except SyntaxError as e:
            if exclusive:
                f.close()
            raise SVGError(str(e) or 'not an SVG document') from None
        except BaseException:
            if exclusive:
                f.close()
            raise
    finally:
        _pending.reset(token)
    im._exclusive_fp = exclusive
    if width is not None or height is not None or zoom is not None:
        im._set_svg_size(width, height, zoom)
    return im


def _open_file(path):
    """``path`` opened for reading (this module's own ``open`` is the plugin's)."""
    import builtins
    from ..errors import RasterIOError
    try:
        return builtins.open(path, 'rb')
    except OSError as e:
        raise RasterIOError(e.errno, e.strerror or str(e), path) from e
