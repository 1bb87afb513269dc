"""The parser: an SVG document to a resolved :class:`raster.tree.Tree`.

Layers inside (each module imports only those above it in this list):

* :mod:`.document` (safe XML loading: entity limits, svgz),
  :mod:`.css` (the cascade), :mod:`.values` (micro-syntaxes),
  :mod:`.properties` (the property table);
* :mod:`.context` (:class:`Options`, per-subtree ``State``, per-document
  ``Cache``), :mod:`.style` (computed style, lengths, transforms,
  conditions), :mod:`.refs` (references), :mod:`.boxes` (content boxes);
* :mod:`.convert`: the dispatcher every converter calls for children;
* one converter module per element family, each with the signature
  ``convert(el, state, cache, parent)``: :mod:`.structure` (``g``,
  ``a``, ``switch``, ``svg``, ``use``/``symbol``, the root), :mod:`.shapes`
  (basic shapes, ``path``), :mod:`.paint` (paint servers),
  :mod:`.clipmask`, :mod:`.markers`, :mod:`.images` (with
  :mod:`.imageload`), :mod:`.text`, :mod:`.filters`; :mod:`.effects`
  decides every group effect in one place.

The parser never imports the renderer: the tree is the only contract.

>>> root = load_document(b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10">'
...                      b'<rect width="5" height="5" fill="red"/></svg>')
>>> tree = build_tree(root)
>>> tree.width, tree.height, tree.root.children[0].fill.paint.color
(20.0, 10.0, (1.0, 0.0, 0.0, 1.0))
"""

import dataclasses
import math
from typing import Optional

import numpy as np

from .. import limits
from ..errors import SVGError
from ..tree import Tree
from .context import Cache, Options
from .css import declared_styles
from .document import load_document
from .shapes import SHAPES, convert_shape
from .structure import convert_group, convert_root, convert_svg, convert_switch, convert_use

__all__ = ['Options', 'build_tree', 'parse', 'load_document', 'CONVERTERS']


def convert_text(el, state, cache, parent):
    """``text``: :func:`raster.parser.text.convert_text`, loaded with the
    first text element (with it fonts, fontTools and HarfBuzz)."""
    from .text import convert_text as convert
    convert(el, state, cache, parent)


def convert_image(el, state, cache, parent):
    """``image``: :func:`raster.parser.images.convert_image`, loaded with
    the first image (with it the image decoders and Pillow)."""
    from .images import convert_image as convert
    convert(el, state, cache, parent)


#: Element local name -> converter ``convert(el, state, cache, parent)``.
#: Elements not listed are never rendered directly (``defs``, ``symbol``,
#: paint servers, ``clipPath``, ``mask``, ``marker``, ``filter``, ...) or
#: unknown.  Families that need heavy modules (text, images) are entered
#: as small functions importing their module on first use, so a document
#: without them never loads it.
CONVERTERS = dict({name: convert_shape for name in SHAPES},
                  g=convert_group, a=convert_group, switch=convert_switch, svg=convert_svg,
                  use=convert_use, text=convert_text, image=convert_image)


def parse(source, options: Optional[Options] = None) -> Tree:
    """Load an SVG document (see :func:`~raster.parser.document.load_document`
    for the accepted sources) and resolve it into a Tree."""
    return build_tree(load_document(source), options)


def build_tree(root, options: Optional[Options] = None, image_cache: Optional[dict] = None,
               **fields) -> Tree:
    """Resolve a loaded SVG document into a render :class:`~raster.tree.Tree`.

    Parameters
    ----------
    root : lxml element
        The root ``svg`` element (see :func:`load_document`).
    options : Options or None
        How to parse (default ``Options()``).
    image_cache : dict or None
        Decoded images to share (SVG images pass their document's).
    **fields
        Fields of :class:`Options` replacing those of ``options``
        (``build_tree(root, tolerance=0.05)``).

    Returns
    -------
    raster.tree.Tree
        ``width``/``height``: natural size in px; ``root``: a Group whose
        transform maps user space to document px; ``ids``: id -> first
        node built for that id.

    Raises
    ------
    raster.errors.SVGError
        The root is not ``svg``, the document size is zero, negative or
        invalid, or the tolerance is not a positive number.

    Warns
    -----
    raster.errors.RasterWarning
        Once per kind of unsupported or ignored content.
    """
    if options is None:
        options = Options()
    if fields:
        if 'languages' in fields:
            fields['languages'] = tuple(fields['languages'])
        options = dataclasses.replace(options, **fields)
    lim = limits.current()
    if options.max_elements is None or options.max_use_depth is None:
        me, md = options.max_elements, options.max_use_depth
        options = dataclasses.replace(options,
                                      max_elements=lim.max_elements if me is None else me,
                                      max_use_depth=lim.max_use_depth if md is None else md)
    tag = root.tag
    if not (isinstance(tag, str) and tag == '{http://www.w3.org/2000/svg}svg'):
        raise SVGError('not an SVG document: root element is not <svg>')
    tol = options.tolerance
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
        raise SVGError('tolerance must be a positive number, got %r' % (tol,))
    # (the library leaves Python's garbage collector as the application set
    # it; the commands pause it while they run: raster_cli._common.run)
    # hostile numbers overflow in transforms and boxes: the results are
    # checked where they are used (State.check, finite paths), not warned about
    with np.errstate(over='ignore', invalid='ignore', divide='ignore'):
        cache = _document_cache(root, options, {} if image_cache is None else image_cache, lim)
        try:
            tree = convert_root(root, cache)
        finally:
            deep = cache.memo.get('too-deep')
            cache.release()
    if deep:
        cache.warn('nesting', 'element <%s> nested too deeply: not rendered' % deep['tag'])
    return tree


def _import_loader(options):
    """The ``load`` of :func:`raster.parser.css.declared_styles` for a
    document parsed with ``options``: local style sheets read by
    :func:`raster.parser.imageload.fetch_stylesheet`, chains at most
    ``MAX_IMPORT_DEPTH`` deep, at most ``MAX_IMPORTS`` sheets, a sheet
    importing itself (directly or not) skipped; each refusal one warning."""
    count = [0]

    def loader(base_dir, chain):
        def load(href):
            # (imported here: a document without @import loads none of it)
            import warnings
            from ..errors import RasterWarning
            from .imageload import MAX_IMPORT_DEPTH, MAX_IMPORTS, ImageError, fetch_stylesheet
            if len(chain) >= MAX_IMPORT_DEPTH or count[0] >= MAX_IMPORTS:
                warnings.warn('style sheet not imported: more than %d imports or %d levels: %s'
                              % (MAX_IMPORTS, MAX_IMPORT_DEPTH, href[:60]), RasterWarning,
                              stacklevel=2)
                return None
            try:
                real, text, base = fetch_stylesheet(href, base_dir, options)
            except ImageError as e:
                warnings.warn('style sheet not imported: %s' % e, RasterWarning, stacklevel=2)
                return None
            if real is not None and real in chain:
                warnings.warn('style sheet not imported: import cycle through %s' % href[:60],
                              RasterWarning, stacklevel=2)
                return None
            count[0] += 1
            return text, loader(base, chain + ((real,) if real else ()))
        return load
    return loader(None, ())


def _document_cache(root, options, image_cache, lim):
    """The :class:`Cache` of a loaded document: its cascade, ids and
    conditional elements, under the budgets ``lim``."""
    found = {'id': [], 'requiredExtensions': [], 'systemLanguage': []}
    styles = declared_styles(root, options.extra_css, found, _import_loader(options))
    by_id = {}
    for el in found['id']:
        i = el.get('id')
        if i not in by_id:
            by_id[i] = el

    def open_document(other_root, other_options):
        return _document_cache(other_root, other_options, image_cache, lim)
    return Cache(options=options, root=root, styles=styles, by_id=by_id,
                 conditional=set(found['requiredExtensions']) | set(found['systemLanguage']),
                 converters=CONVERTERS, parse_nested=build_tree, image_cache=image_cache,
                 open_document=open_document, limits=lim)
