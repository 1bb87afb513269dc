"""SVG documents in one call: load, resolve, render.

The front door over the parser (:mod:`raster.parser`: a document to a
resolved :class:`raster.tree.Tree`) and the renderer
(:mod:`raster.renderer`: a tree onto a canvas):

* :func:`load_svg` -- an SVG source to a resolved Tree;
* :func:`render` -- an SVG source to an ``(H, W, 4) uint8`` RGBA array;
* :func:`render_image` -- the same as a :class:`PIL.Image.Image`.

A *source* is a file path (``str`` or :class:`os.PathLike`, or a ``file:``
URL; ``.svgz`` gzip files are accepted), the document as ``bytes`` or as
XML text, or a binary file object.  Other URLs are refused: raster never
fetches from the network.
Relative references (images) resolve against the file's directory; files
are only read from inside ``resources_dir`` when it is given (and from the
document's own directory).

Output sizes are in device pixels; the document's natural size is its
``width``/``height`` in CSS px (96 per inch at ``dpi=96``).

Every function takes ``limits``: the budgets of :mod:`raster.limits` for
this call (a :class:`~raster.limits.Limits`, a mapping such as
``{'max_xml_text_bytes': 50_000_000}``, or ``'unlimited'`` for trusted
input); by default the budgets in force (:func:`raster.limits.current`).
"""

import math
import os
import warnings
from typing import BinaryIO, Optional, Sequence, Tuple, Union

import numpy as np

from . import limits as _limits
from .errors import SVGError
from .fonts import FontOptions
from .limits import LimitsSpec
from .parser import Options, build_tree, load_document
from .parser.values import CURRENT_COLOR, parse_color
from .renderer import DEFAULT_TOLERANCE, render_tree
from .sources import local_path
from .tree import Tree

#: What :func:`load_svg` and :func:`render` read: a path, the bytes, or a
#: binary file object.
Source = Union[str, 'os.PathLike[str]', bytes, BinaryIO]
#: A background: a CSS colour string or 3 or 4 floats in [0, 1].
Background = Union[None, str, Sequence[float]]

__all__ = ['load_svg', 'render', 'render_image', 'render_tree', 'parse_background',
           'check_dpi', 'font_options']


def font_options(fonts=None, font_dirs=None, stacklevel=3):
    """The :class:`~raster.fonts.FontOptions` of a front door's ``fonts``
    argument (a FontOptions, a dict of its fields, or None for the
    defaults: the system's fonts).

    ``font_dirs`` is the deprecated spelling of
    ``fonts=FontOptions(dirs=..., system=False)`` (only those folders, as
    it always meant); it warns with :class:`DeprecationWarning` and cannot
    be combined with ``fonts``."""
    if font_dirs is not None and (not isinstance(font_dirs, (tuple, list)) or font_dirs):
        if fonts is not None:
            raise SVGError('give fonts= or the deprecated font_dirs=, not both')
        warnings.warn('font_dirs= is deprecated; use fonts=raster.FontOptions(dirs=..., '
                      'system=False)', DeprecationWarning, stacklevel=stacklevel)
        return FontOptions(dirs=font_dirs, system=False)
    return FontOptions.coerce(fonts)


def _source_and_base(source):
    """(source for load_document, base directory or None)."""
    if isinstance(source, str) and source.lstrip().startswith('<'):
        return source, None                     # the document as XML text
    if isinstance(source, (str, os.PathLike)):
        path = local_path(source)               # file: URLs; other URLs refused
        return path, os.path.dirname(os.path.abspath(path))
    return source, None


def load_svg(source: Source, *, dpi: float = 96, fonts: Optional[FontOptions] = None,
             resources_dir: Optional[str] = None, base_dir: Optional[str] = None,
             font_dirs: Optional[Sequence[str]] = None, limits: LimitsSpec = None,
             **options) -> Tree:
    """Load and resolve an SVG document.

    Parameters
    ----------
    source : str, os.PathLike, bytes or binary file object
        The document (see the module docstring).
    dpi : float
        Resolution for absolute units (``in``, ``mm``, ``pt`` ...).
    fonts : raster.FontOptions, dict or None
        The fonts of text: None uses the system's fonts (see
        :class:`raster.FontOptions`: font folders and files, no system
        fonts, generic family overrides, the default family).
    resources_dir : str or None
        Directory external files may be read from.
    base_dir : str or None
        Directory relative references resolve against (default: the
        source file's directory).
    limits : raster.limits.Limits, mapping, 'unlimited' or None
        Budgets for this call (see the module docstring).
    **options
        Further fields of :class:`raster.parser.Options` (``font_size``,
        ``languages``, ``tolerance``, ``max_elements``, ``max_use_depth``,
        ``extra_css``, ``allow_files_under``).  ``font_dirs`` is the
        deprecated spelling of ``fonts=FontOptions(dirs=..., system=False)``.

    Returns
    -------
    raster.tree.Tree

    Raises
    ------
    raster.errors.SVGError
        Unreadable XML, not an SVG document, invalid size or ``dpi``.
    raster.errors.InputLimitError
        A document beyond ``max_input_bytes`` or ``max_xml_elements``
        (also an :class:`~raster.errors.SVGError`).
    raster.errors.RasterIOError
        The file cannot be read, or ``source`` is a URL other than
        ``file:`` (also an :class:`OSError`).

    Warns
    -----
    raster.errors.RasterWarning
        Content ignored or unsupported, or left out over a budget (once
        per kind).
    """
    with _limits.applied(limits):
        return _load_svg(source, dpi, fonts, font_dirs, resources_dir, base_dir, options)


def _load_svg(source, dpi, fonts, font_dirs, resources_dir, base_dir, options):
    d = check_dpi(dpi)
    fopts = font_options(fonts, font_dirs)
    src, sbase = _source_and_base(source)
    root = load_document(src)
    if 'languages' in options:
        options['languages'] = tuple(options['languages'])
    opts = Options(dpi=d, fonts=fopts, resources_dir=resources_dir,
                   base_dir=base_dir if base_dir is not None else sbase, **options)
    return build_tree(root, opts)


def check_dpi(dpi) -> float:
    """``dpi`` as a positive finite float.

    Raises
    ------
    raster.errors.SVGError
        Anything else.
    """
    try:
        d = float(dpi)
    except (TypeError, ValueError):
        d = math.nan
    if not (math.isfinite(d) and d > 0):
        raise SVGError('dpi must be a positive number, got %r' % (dpi,))
    return d


def parse_background(bg: Background) -> Optional[Tuple[float, float, float, float]]:
    """Straight RGBA floats in [0, 1] of a background: a CSS colour string
    (``'white'``, ``'#ff000080'``), 3 or 4 floats in [0, 1], or None
    (transparent, returned as None).

    Raises
    ------
    raster.errors.SVGError
        Anything else.

    >>> parse_background('red'), parse_background((0, 0, 1))
    ((1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0))
    """
    if bg is None:
        return None
    if isinstance(bg, str):
        c = parse_color(bg)
        if c is None or c is CURRENT_COLOR:
            raise SVGError('invalid background colour %r' % (bg,))
        return tuple(float(v) for v in c)
    try:
        c = tuple(float(v) for v in bg)
    except (TypeError, ValueError):
        raise SVGError('background must be a CSS colour or 4 floats, got %r' % (bg,)) from None
    if len(c) == 3:
        c = c + (1.0,)
    if len(c) != 4 or not all(0.0 <= v <= 1.0 for v in c):
        raise SVGError('background must be 4 floats in [0, 1], got %r' % (bg,))
    return c


def render(source: Source, width: Optional[int] = None, height: Optional[int] = None, *,
           zoom: Optional[float] = None, dpi: float = 96, background: Background = None,
           id: Optional[str] = None, fonts: Optional[FontOptions] = None,
           resources_dir: Optional[str] = None, premultiplied: bool = False,
           tolerance: float = DEFAULT_TOLERANCE, crop: bool = False,
           font_dirs: Optional[Sequence[str]] = None,
           languages: Sequence[str] = ('en',), limits: LimitsSpec = None,
           window: Optional[Tuple[int, int, int, int]] = None) -> np.ndarray:
    """Render an SVG document to an RGBA array.

    Parameters
    ----------
    source : str, os.PathLike, bytes or binary file object
        The document.
    width, height : int or None
        Output size in pixels; only one keeps the aspect ratio, both stretch;
        neither: the natural size (rounded up).
    zoom : float or None
        Scale of the natural size (instead of width/height).
    dpi : float
        Resolution for absolute units.
    background : str, tuple or None
        A CSS colour (``'white'``, ``'#ff000080'``) or straight RGBA floats;
        None: transparent.
    id : str or None
        Render only the element with this id (with its ancestors'
        transforms).
    crop : bool
        With ``id``: the image is the element's drawn box (strokes, markers,
        filters included) rather than the page.
    fonts, resources_dir :
        See :func:`load_svg` (``font_dirs`` too, deprecated).
    premultiplied : bool
        Return premultiplied colours (default: straight alpha).
    tolerance : float
        Flattening tolerance in device pixels.
    languages : sequence of str
        The user's languages for ``systemLanguage`` (language tags; see
        :class:`raster.parser.Options`).
    window : (x0, y0, x1, y1) ints or None
        Only this rectangle of the output (columns x0 to x1 - 1, rows y0
        to y1 - 1), equal to that part of the whole image; the whole output
        may then exceed the ``max_pixels`` budget (see
        :func:`raster.renderer.render_tree`).  To render many windows of
        one document, load it once (:func:`load_svg`) and call
        :func:`raster.renderer.render_tree` with ``window`` on the tree.
    limits : raster.limits.Limits, mapping, 'unlimited' or None
        Budgets for this call (see the module docstring): an element over
        one is left out with a warning.

    Returns
    -------
    (H, W, 4) uint8 ndarray
        RGBA, row 0 at the top (``(y1 - y0, x1 - x0, 4)`` with a window).

    Raises
    ------
    raster.errors.SVGError
        Bad document, unknown ``id`` or bad background colour.
    raster.errors.CanvasError
        Zero, negative or non-finite size or zoom, or an output above
        ``max_pixels`` (:mod:`raster.limits`).
    raster.errors.InputLimitError
        A document beyond ``max_input_bytes`` or ``max_xml_elements``.

    >>> img = render(b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="2">'
    ...              b'<rect width="2" height="2" fill="blue"/></svg>')
    >>> img.shape, img[0, 0].tolist(), img[0, 3].tolist()
    ((2, 4, 4), [0, 0, 255, 255], [0, 0, 0, 0])
    """
    bg = parse_background(background)
    with _limits.applied(limits):
        tree = load_svg(source, dpi=dpi, fonts=font_options(fonts, font_dirs),
                        resources_dir=resources_dir,
                        languages=tuple(languages))
        canvas = render_tree(tree, width=width, height=height, zoom=zoom, background=bg,
                             node_id=id, tolerance=tolerance, crop=crop, dtype=np.uint8,
                             window=window)
    return canvas.to_rgba8(premultiplied=bool(premultiplied))


def render_image(source: Source, width: Optional[int] = None, height: Optional[int] = None,
                 **kwargs) -> 'PIL.Image.Image':  # noqa: F821
    """:func:`render` as a straight-alpha RGBA :class:`PIL.Image.Image`
    (same arguments; ``premultiplied`` is not accepted)."""
    from PIL import Image
    if 'premultiplied' in kwargs:
        raise TypeError('render_image() always returns straight alpha')
    return Image.fromarray(render(source, width, height, **kwargs), 'RGBA')
