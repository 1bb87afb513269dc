"""CairoSVG-compatible entry points: code written for ``cairosvg.svg2png``
runs on raster by changing the import.

>>> import raster
>>> png = raster.svg2png(b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="2">'
...                      b'<rect width="2" height="2" fill="blue"/></svg>', scale=2)
>>> png[:8] == b'\\x89PNG\\r\\n\\x1a\\n', png[16:24].hex()     # IHDR: 8 x 4 px
(True, '0000000800000004')

The parameters mean what they mean in CairoSVG 2.x:

* the document is ``bytestring`` (bytes or str), else ``file_obj``, else
  ``url`` -- taken in that order when several are given;
* the output size is the document's size times ``scale``; ``output_width``
  / ``output_height`` replace it (one of them keeps the aspect ratio, and
  ``scale`` is then ignored); both fit the document into that box by its
  ``preserveAspectRatio`` (centred, not stretched, by default); sizes are
  rounded to whole pixels half to even, as CairoSVG does;
* ``parent_width`` / ``parent_height`` are the size of the box the
  document sits in: percentages in the root's ``width`` / ``height``
  (and a missing one, which means 100 %) resolve against them;
* ``dpi`` converts absolute units (``in``, ``mm``, ``pt`` ...); the PNG
  records no resolution (CairoSVG's does not either);
* ``background_color`` is any CSS colour painted under the document;
* ``unsafe=False`` reads no file but the document itself: images come from
  ``data:`` URIs only (CairoSVG likewise); ``unsafe=True`` lets images
  come from local files anywhere.

Differences: ``url`` is a local path or a ``file:`` URL only -- raster
never fetches from the network (a :class:`~raster.errors.RasterIOError`
otherwise) -- and errors are :class:`~raster.errors.RasterError` s
(CairoSVG raises ``ValueError``, ``TypeError`` or parser errors).  Internal
XML entities are expanded with libxml2's amplification guard whether or
not ``unsafe`` is set; ``unsafe`` lifts raster's budgets
(:mod:`raster.limits`), as it lets CairoSVG read very large files.
``negate_colors`` and ``invert_images`` are not supported.
"""

from __future__ import annotations

import math
import os
import re
from typing import BinaryIO

from .errors import CanvasError, RasterIOError, SVGError

__all__ = ['svg2png']

_PERCENT = re.compile(r'\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)%\s*$')


def _number(name, value, positive=True):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise CanvasError('%s must be a number, got %r' % (name, value)) from None
    if not math.isfinite(v) or (positive and v <= 0):
        raise CanvasError('%s must be positive and finite, got %r' % (name, value))
    return v


def _document(bytestring, file_obj, url):
    """(source for load_document, path of the document or None)."""
    if bytestring is not None:
        if isinstance(bytestring, str):
            bytestring = bytestring.encode('utf-8')
        if not isinstance(bytestring, (bytes, bytearray, memoryview)):
            raise SVGError('bytestring must be bytes or str, got %s' % type(bytestring).__name__)
        return bytes(bytestring), None
    if file_obj is not None:
        name = getattr(file_obj, 'name', None)
        path = name if isinstance(name, str) and os.path.isfile(name) else None
        return file_obj, path
    if url is not None:
        from .sources import local_path
        path = local_path(url)
        return path, path
    raise SVGError('no input: give one of bytestring, file_obj or url')


def _root_size_against_parent(root, vb, parent_width, parent_height):
    """Resolve percentages of the root's width/height (absent: 100 %)
    against the parent box, in place.  Without a parent size a percentage
    (or an absent side) is CairoSVG's zero, which means the viewBox size
    when there is one (not raster's aspect ratio from the other side)."""
    for i, (attr, parent) in enumerate((('width', parent_width), ('height', parent_height))):
        m = _PERCENT.match(root.get(attr, '100%'))
        if m is None:
            continue
        if parent is not None:
            root.set(attr, repr(float(m.group(1)) * _number('parent_' + attr, parent) / 100.0))
        elif vb is not None:
            root.set(attr, repr(vb[2 + i]))


def _output_box(w, h, scale, output_width, output_height):
    """CairoSVG's output size (unrounded floats) of a document of natural
    size ``w`` x ``h``."""
    ow = _number('output_width', output_width) if output_width else None
    oh = _number('output_height', output_height) if output_height else None
    if ow and oh:
        return ow, oh
    if ow:
        return ow, h * ow / w
    if oh:
        return w * oh / h, oh
    s = _number('scale', scale)
    return w * s, h * s


def svg2png(bytestring: bytes | str | None = None, *, url: str | os.PathLike | None = None,
            file_obj: BinaryIO | None = None,
            write_to: str | os.PathLike | BinaryIO | None = None, dpi: float = 96,
            parent_width: float | None = None, parent_height: float | None = None,
            scale: float = 1, unsafe: bool = False, background_color: str | None = None,
            output_width: float | None = None,
            output_height: float | None = None, fonts=None, limits=None) -> bytes | None:
    """Render an SVG document to PNG, with CairoSVG's ``svg2png`` arguments.

    Parameters
    ----------
    bytestring : bytes or str, optional
        The document.
    url : str or os.PathLike, optional
        A local path or ``file:`` URL of the document.
    file_obj : binary file object, optional
        The document, read with ``read()``; its ``name``, when it is a file,
        is the base of relative references.
    write_to : str, os.PathLike or writable binary file object, optional
        Where to write the PNG; None: return it.
    dpi : float
        Pixels per inch for absolute units.
    parent_width, parent_height : float, optional
        Size in px of the box the document sits in (see the module
        docstring).
    scale : float
        Factor of the natural size (ignored with an output size).
    unsafe : bool
        Allow images from local files (default: ``data:`` URIs only) and,
        as CairoSVG's ``unsafe`` allows very large files, lift every budget
        of :mod:`raster.limits` unless ``limits`` is given.
    background_color : str, optional
        A CSS colour under the document (default transparent).
    output_width, output_height : float, optional
        Output size in px (see the module docstring).
    fonts : raster.FontOptions or dict, optional
        The fonts of text (default: the system's fonts), as for
        :func:`raster.render`; not a CairoSVG argument.
    limits : raster.limits.Limits, mapping or 'unlimited', optional
        The budgets for this call (default: those in force, or none with
        ``unsafe``); raster's own addition.

    Returns
    -------
    bytes or None
        The PNG (8-bit RGBA, straight alpha) when ``write_to`` is None.

    Raises
    ------
    raster.errors.RasterIOError
        A URL other than ``file:``, a document that cannot be read, or
        ``write_to`` that cannot be written (also :class:`OSError`).
    raster.errors.SVGError
        No input, a bad document, a bad ``dpi`` or colour.
    raster.errors.CanvasError
        A size or scale that is not positive and finite, or an output that
        rounds to 0 pixels or exceeds :mod:`raster.limits`.
    """
    from . import limits as budgets
    if limits is None and unsafe:
        limits = budgets.UNLIMITED
    with budgets.applied(limits):
        return _svg2png(bytestring, url, file_obj, write_to, dpi, parent_width, parent_height,
                        scale, unsafe, background_color, output_width, output_height, fonts)


def _svg2png(bytestring, url, file_obj, write_to, dpi, parent_width, parent_height, scale,
             unsafe, background_color, output_width, output_height, fonts):
    from .pixels.encode import encode
    from .svg import check_dpi, font_options, parse_background
    from .parser import build_tree
    from .parser.document import load_document
    from .renderer import render_tree
    from .tree import Fill, Group, PathNode, SolidPaint, Tree
    from .geometry.pathdata import parse_path
    from .parser.values import (DEFAULT_ASPECT_RATIO, parse_preserve_aspect_ratio,
                                parse_viewbox, viewbox_transform)

    bg = parse_background(background_color)
    d = check_dpi(dpi)
    source, path = _document(bytestring, file_obj, url)
    root = load_document(source)
    vb = parse_viewbox(root.get('viewBox')) if root.get('viewBox') is not None else None
    _root_size_against_parent(root, vb, parent_width, parent_height)
    if unsafe:
        base = os.path.dirname(os.path.abspath(path)) if path else os.getcwd()
        files = dict(base_dir=base, resources_dir=os.path.abspath(os.sep))
    else:
        files = dict(base_dir=None, resources_dir=None)     # data: URIs only
    tree = build_tree(root, dpi=d, fonts=font_options(fonts), **files)
    w, h = tree.width, tree.height
    W, H = _output_box(w, h, scale, output_width, output_height)
    Wi, Hi = int(round(W)), int(round(H))
    if Wi < 1 or Hi < 1:
        raise CanvasError('output size %g x %g rounds to zero pixels' % (W, H))
    # the document box (its viewBox, else its natural size) fitted into the
    # output box by the root's preserveAspectRatio, as CairoSVG does
    box = vb or (0.0, 0.0, w, h)
    par = parse_preserve_aspect_ratio(root.get('preserveAspectRatio', '')) or DEFAULT_ASPECT_RATIO
    fit = viewbox_transform(box, par, W, H) @ viewbox_transform(box, par, w, h).inverse()
    kids = [Group(transform=fit, children=[tree.root])]
    if bg is not None:
        # painted over the unrounded output box only, as CairoSVG paints it
        # (a fractional last row or column is partly covered)
        rect = parse_path('M0 0H%rV%rH0Z' % (W, H))
        kids.insert(0, PathNode(path=rect, fill=Fill(SolidPaint(bg))))
    out = Tree(width=float(Wi), height=float(Hi), root=Group(children=kids), ids=tree.ids)
    png = encode(render_tree(out, dtype='uint8').to_rgba8(), 'png')
    if write_to is None:
        return png
    if hasattr(write_to, 'write'):
        write_to.write(png)
        return None
    target = os.fspath(write_to)
    try:
        with open(target, 'wb') as f:
            f.write(png)
    except OSError as e:
        raise RasterIOError(e.errno, e.strerror or str(e), target) from e
    return None
