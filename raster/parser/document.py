"""Load an SVG document into an lxml element tree, safely.

:func:`load_document` accepts a path, ``bytes``, XML text or a binary file
object, transparently decompresses gzip (``.svgz``) with a size cap, and
parses with a hardened parser:

* no network access, no external DTD or external entities;
* internal DTD entities *are* expanded (SVG test suites use them for
  attribute values and even whole elements), but libxml2's entity
  amplification guard refuses "billion laughs" documents quickly;
* comments and processing instructions are dropped.

The root must be an ``svg`` element in the SVG namespace.  A root ``<svg>``
with no namespace at all is accepted as SVG (resvg renders such files): its
un-namespaced elements are moved into the SVG namespace.

Errors are :class:`raster.errors.SVGError` with a one-line message.

>>> root = load_document(b'<svg xmlns="http://www.w3.org/2000/svg" width="4"/>')
>>> root.tag, root.get('width')
('{http://www.w3.org/2000/svg}svg', '4')
>>> load_document('<html/>')
Traceback (most recent call last):
...
raster.errors.SVGError: not an SVG document: root element is <html>
"""

import os
import re
import zlib

from lxml import etree

from .._regex import lazy
from .. import limits
from ..errors import InputLimitError, SVGError
from ..sources import CHUNK, file_chunks, stream_chunks, too_large

__all__ = ['load_document', 'chain_attr', 'SVG_NS', 'XLINK_NS', 'MAX_DOCUMENT_BYTES']

SVG_NS = 'http://www.w3.org/2000/svg'
XLINK_NS = 'http://www.w3.org/1999/xlink'

#: Default cap on the (decompressed) document size in bytes
#: (:attr:`raster.limits.Limits.max_input_bytes`).
MAX_DOCUMENT_BYTES = limits.DEFAULT.max_input_bytes

_GZIP_MAGIC = b'\x1f\x8b'

# libxml2's limit on one text node or attribute value without its huge mode
_LIBXML2_TEXT = 10_000_000


def _parser(huge=False):
    return etree.XMLPullParser(events=('start',), resolve_entities='internal',
                               no_network=True, load_dtd=False, dtd_validation=False,
                               remove_comments=True, remove_pis=True, huge_tree=huge,
                               recover=False)


def _raw_chunks(source, max_bytes):
    """The document's bytes (still possibly gzip-compressed), in pieces
    read as they are consumed, at most ``max_bytes`` in all."""
    if isinstance(source, (bytes, bytearray, memoryview)):
        data = memoryview(source).cast('B')
        if len(data) > max_bytes:
            raise too_large(max_bytes)
        for i in range(0, len(data), CHUNK):
            yield bytes(data[i:i + CHUNK])
        return
    if isinstance(source, str):
        if source.lstrip().startswith('<'):
            yield from _raw_chunks(source.encode('utf-8'), max_bytes)
            return
        yield from file_chunks(source, max_bytes)      # file: URLs read, other URLs refused
        return
    if isinstance(source, os.PathLike):
        yield from file_chunks(os.fspath(source), max_bytes)
        return
    if getattr(source, 'read', None) is None:
        raise SVGError('cannot read an SVG document from %s' % type(source).__name__)
    for data in stream_chunks(source, max_bytes):
        if isinstance(data, str):
            data = data.encode('utf-8')
        if not isinstance(data, (bytes, bytearray)):
            raise SVGError('file object returned %s, not bytes' % type(data).__name__)
        yield bytes(data)


def _chunks(source, max_bytes):
    """The document's bytes, gunzipped when they start with the gzip magic,
    refusing more than ``max_bytes`` compressed or decompressed."""
    raw = _raw_chunks(source, max_bytes)
    first = b''
    for first in raw:
        if first:
            break
    if first[:2] != _GZIP_MAGIC or len(first) < 2:
        if first:
            yield first
        yield from raw
        return
    d = zlib.decompressobj(16 + zlib.MAX_WBITS)
    total = 0
    for piece in _chain(first, raw):
        while piece:
            try:
                out = d.decompress(piece, CHUNK)
            except zlib.error as e:
                raise SVGError('corrupt gzip data: %s' % e) from None
            total += len(out)
            if total > max_bytes:
                raise too_large(max_bytes, 'decompressed document')
            if out:
                yield out
            if d.eof:
                return
            piece = d.unconsumed_tail
    if not d.eof:
        raise SVGError('corrupt gzip data: truncated stream')


def _chain(first, rest):
    yield first
    yield from rest


def _parse(pieces, lim, keep):
    """Feed ``pieces`` to a hardened pull parser, counting elements against
    ``lim.max_xml_elements``; the pieces are appended to ``keep`` (for the
    one retry of :func:`_xlink_in_entities`).  Returns the root element (or
    None for an empty document)."""
    parser = _parser(huge=lim.max_xml_text_bytes > _LIBXML2_TEXT)
    max_el = lim.max_xml_elements
    n = 0
    seen = False
    for piece in pieces:
        if keep is not None:
            keep.append(piece)
        if not seen:
            if not piece.strip():
                continue
            seen = True
        parser.feed(piece)
        for _ in parser.read_events():
            n += 1
        if n > max_el:
            raise InputLimitError('document has more than %d elements (max_xml_elements)'
                                  % max_el)
    if not seen:
        raise SVGError('empty document')
    root = parser.close()
    for _ in parser.read_events():
        n += 1
    if n > max_el:
        raise InputLimitError('document has more than %d elements (max_xml_elements)' % max_el)
    return root


def load_document(source, *, max_bytes=None):
    """Parse an SVG document.

    The document is read, decompressed and parsed a piece at a time, so a
    document beyond a budget (:mod:`raster.limits`: ``max_input_bytes``,
    ``max_xml_elements``) fails before it is read in full.

    Parameters
    ----------
    source : str, os.PathLike, bytes or binary file object
        A file path, the document as bytes, the document as XML text (a
        ``str`` whose first non-blank character is ``<``) or an object with
        ``read()``.  Gzip data (magic bytes ``1f 8b``, e.g. ``.svgz``) is
        decompressed.
    max_bytes : int or None
        Largest accepted document size, compressed and decompressed
        (default: :attr:`raster.limits.Limits.max_input_bytes`).

    Returns
    -------
    lxml.etree._Element
        The root ``{http://www.w3.org/2000/svg}svg`` element.

    Raises
    ------
    raster.errors.SVGError
        XML syntax errors (with the line), entity expansion refused, a root
        that is not ``svg``.
    raster.errors.InputLimitError
        A document above ``max_bytes`` or with more than
        ``max_xml_elements`` elements (also an :class:`SVGError`).
    raster.errors.RasterIOError
        A path that cannot be read, or a URL other than ``file:`` (also an
        :class:`OSError`).
    """
    lim = limits.current()
    if max_bytes is None:
        max_bytes = lim.max_input_bytes
    keep = []
    try:
        try:
            root = _parse(_chunks(source, max_bytes), lim, keep)
        except etree.XMLSyntaxError as e:
            data = b''.join(keep)
            data2 = _xlink_in_entities(data, e)
            if data2 is None:
                raise
            del keep[:], data
            root = _parse(_chain(data2, ()), lim, None)
    except etree.XMLSyntaxError as e:
        msg = str(e.msg if getattr(e, 'msg', None) else e).splitlines()[0]
        # lxml appends ", line L, column C" to some messages
        msg = msg.split(', line ')[0].rstrip('.')
        line = e.lineno if getattr(e, 'lineno', None) else None
        msg = _huge_hint(msg)
        if line:
            raise SVGError('XML error at line %d: %s' % (line, msg)) from None
        raise SVGError('XML error: %s' % msg) from None
    except ValueError as e:    # e.g. str with an encoding declaration
        raise SVGError('XML error: %s' % str(e).splitlines()[0]) from None
    del keep
    if root is None:
        raise SVGError('empty document')
    tag = root.tag
    if tag == 'svg':
        _adopt_svg_namespace(root)
    elif tag != '{%s}svg' % SVG_NS:
        local = etree.QName(tag).localname if isinstance(tag, str) else '?'
        raise SVGError('not an SVG document: root element is <%s>' % local)
    elif root.getroottree().docinfo.internalDTD is not None:
        # libxml2 parses the replacement text of an internal entity without
        # the namespace declarations in scope: elements that came from an
        # entity reference have no namespace.  Give them their parent's.
        _adopt_svg_namespace(root, only_under_svg=True)
    return root


_HUGE_ADVICE = lazy(globals(), '_HUGE_ADVICE', r',?\s*(?:try|use) XML_PARSE_HUGE(?: option)?',
                    re.I)


def _huge_hint(msg):
    """libxml2's advice to use its huge mode, said in our terms."""
    if not _HUGE_ADVICE.search(msg):
        return msg
    return _HUGE_ADVICE.sub('', msg).rstrip(' ,:') + \
        ' (libxml2\'s limit: raise max_xml_text_bytes above 10 MB)'


_XLINK_HREF_IN_DTD = lazy(globals(), '_XLINK_HREF_IN_DTD', rb'(\s)xlink:href(\s*=)')


def _xlink_in_entities(data, err):
    """The document with ``xlink:href`` inside its internal DTD subset
    rewritten to plain ``href`` (SVG 2's equivalent), or None.

    libxml2 parses the replacement text of an internal entity without the
    namespace declarations of the place where it is used, so an entity
    holding ``<use xlink:href=...>`` is a namespace error although the root
    declares ``xlink`` (resvg renders such files).  Only this error is
    retried; the retry uses the same hardened parser and limits."""
    msg = str(getattr(err, 'msg', '') or err)
    if 'Namespace prefix xlink' not in msg:
        return None
    i = data.find(b'<!DOCTYPE')
    if i < 0:
        return None
    j = data.find(b']>', i)
    if j < 0:
        return None
    sub = _XLINK_HREF_IN_DTD.sub(rb'\1href\2', data[i:j])
    if sub == data[i:j]:
        return None
    return data[:i] + sub + data[j:]


def _adopt_svg_namespace(root, only_under_svg=False):
    """Move un-namespaced elements into the SVG namespace (all of them, or
    only those whose parent is an SVG element)."""
    pre = '{%s}' % SVG_NS
    for el in root.iter():
        t = el.tag
        if isinstance(t, str) and t[:1] != '{':
            if only_under_svg:
                p = el.getparent()
                if p is None or not p.tag.startswith(pre):
                    continue
            el.tag = pre + t


def chain_attr(chain, name, tag=None):
    """The first value of attribute ``name`` along an href chain of elements
    (the referencing element first), among elements with tag ``tag`` when
    given; None when no element has it."""
    for e in chain:
        if tag is not None and e.tag != tag:
            continue
        v = e.get(name)
        if v is not None:
            return v
    return None
