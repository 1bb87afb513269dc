"""The dispatcher: one element to tree nodes through the converter of its
family.

Every converter has the signature ``convert(el, state, cache, parent)``
(see :mod:`raster.parser.context`); the table mapping element names to
converters is :data:`raster.parser.CONVERTERS`, held by the cache.  What
applies to every element is decided here, once: elements outside the SVG
namespace and elements that are never rendered directly (``defs``,
gradients, ``clipPath`` ...) are skipped; ``display: none`` and failed
conditional processing attributes hide the element and its content; each
element counts against :attr:`Options.max_elements`; an element whose
numbers overflow when combined (``1e308`` scales ...), that is over a
budget of :mod:`raster.limits` or nested deeper than Python's stack allows
is left out with one warning while the rest of the document is
converted.
"""

from ..errors import RasterError
from .context import SVG_NS
from .style import is_displayed, passes_conditions

__all__ = ['convert', 'convert_children']

_P = '{%s}' % SVG_NS
_PLEN = len(_P)


def convert_children(el, state, cache, parent):
    """Convert the SVG children of ``el`` in ``state`` into ``parent``."""
    for ch in el:
        tag = ch.tag
        if isinstance(tag, str) and tag.startswith(_P):
            convert(ch, state, cache, parent)


def convert(el, state, cache, parent):
    """Convert element ``el`` (rendered in ``state``) and append its nodes
    to ``parent`` (a list of tree nodes)."""
    tag = el.tag
    if not (isinstance(tag, str) and tag.startswith(_P)):
        return
    fn = cache.converters.get(tag[_PLEN:])
    if fn is None:          # never rendered directly, or unknown
        return
    if not is_displayed(el, cache):
        return
    if el in cache.conditional and not passes_conditions(el, cache):
        return
    if not cache.tick():
        return
    mark = len(parent)
    try:
        fn(el, state, cache, parent)
    except RasterError as e:
        # numbers that overflow when combined: the element is left out,
        # the rest of the document still renders
        del parent[mark:]
        cache.warn('element-error', 'element <%s> not rendered: %s' % (tag[_PLEN:], e))
    except RecursionError:
        # nesting deeper than Python's stack allows: this element is left
        # out; the warning is issued once the stack has unwound (see
        # raster.parser.build_tree), a warning here could overflow again
        del parent[mark:]
        cache.table('too-deep').setdefault('tag', tag[_PLEN:])
