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

import gzip
import io
import os
import re
import zlib

from lxml import etree

from ..errors import SVGError
from ..sources import read_file, read_stream

__all__ = ['load_document', 'chain_attr', 'SVG_NS', 'XLINK_NS', 'MAX_DOCUMENT_BYTES']

SVG_NS = 'http://www.w3.org/2000/svg'
XLINK_NS = 'http://www.w3.org/1999/xlink'

#: Default cap on the (decompressed) document size in bytes.
MAX_DOCUMENT_BYTES = 200 * 1024 * 1024

_GZIP_MAGIC = b'\x1f\x8b'


def _parser():
    return etree.XMLParser(resolve_entities='internal', no_network=True, load_dtd=False,
                           dtd_validation=False, remove_comments=True, remove_pis=True,
                           huge_tree=False, recover=False)


def _read_source(source, max_bytes):
    """Raw bytes of the document (still possibly gzip-compressed)."""
    if isinstance(source, (bytes, bytearray, memoryview)):
        return bytes(source)
    if isinstance(source, str):
        if source.lstrip().startswith('<'):
            return source.encode('utf-8')
        return _read_file(source, max_bytes)
    if isinstance(source, os.PathLike):
        return _read_file(os.fspath(source), max_bytes)
    read = getattr(source, 'read', None)
    if read is None:
        raise SVGError('cannot read an SVG document from %s' % type(source).__name__)
    data = read_stream(source, max_bytes)
    if isinstance(data, str):
        data = data.encode('utf-8')
    if not isinstance(data, (bytes, bytearray)):
        raise SVGError('file object returned %s, not bytes' % type(data).__name__)
    if len(data) > max_bytes:
        raise SVGError('document is larger than %d bytes' % max_bytes)
    return bytes(data)


def _read_file(path, max_bytes):
    return read_file(path, max_bytes)      # file: URLs read, other URLs refused


def _gunzip(data, max_bytes):
    """Decompress gzip data, refusing output beyond ``max_bytes``."""
    d = zlib.decompressobj(16 + zlib.MAX_WBITS)
    try:
        out = d.decompress(data, max_bytes + 1)
    except zlib.error as e:
        raise SVGError('corrupt gzip data: %s' % e) from None
    if len(out) > max_bytes or d.unconsumed_tail:
        raise SVGError('decompressed document is larger than %d bytes' % max_bytes)
    if not d.eof:
        raise SVGError('corrupt gzip data: truncated stream')
    return out


def load_document(source, *, max_bytes=MAX_DOCUMENT_BYTES):
    """Parse an SVG document.

    Parameters
    ----------
    source : str, os.PathLike, bytes or binary file object
        A file path, the document as bytes, the document as XML text (a
        ``str`` whose first non-blank character is ``<``) or an object with
        ``read()``.  Gzip data (magic bytes ``1f 8b``, e.g. ``.svgz``) is
        decompressed.
    max_bytes : int
        Largest accepted document size, compressed and decompressed.

    Returns
    -------
    lxml.etree._Element
        The root ``{http://www.w3.org/2000/svg}svg`` element.

    Raises
    ------
    raster.errors.SVGError
        XML syntax errors (with the line), entity expansion refused, a root
        that is not ``svg``, a document above ``max_bytes``.
    raster.errors.RasterIOError
        A path that cannot be read, or a URL other than ``file:`` (also an
        :class:`OSError`).
    """
    data = _read_source(source, max_bytes)
    if data[:2] == _GZIP_MAGIC:
        data = _gunzip(data, max_bytes)
    if not data.strip():
        raise SVGError('empty document')
    try:
        try:
            root = etree.fromstring(data, _parser())
        except etree.XMLSyntaxError as e:
            data2 = _xlink_in_entities(data, e)
            if data2 is None:
                raise
            root = etree.fromstring(data2, _parser())
    except etree.XMLSyntaxError as e:
        msg = str(e.msg if getattr(e, 'msg', None) else e).splitlines()[0]
        # lxml appends ", line L, column C" to some messages
        msg = msg.split(', line ')[0].rstrip('.')
        line = e.lineno if getattr(e, 'lineno', None) else None
        if line:
            raise SVGError('XML error at line %d: %s' % (line, msg)) from None
        raise SVGError('XML error: %s' % msg) from None
    except ValueError as e:    # e.g. str with an encoding declaration
        raise SVGError('XML error: %s' % str(e).splitlines()[0]) from None
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


_XLINK_HREF_IN_DTD = re.compile(rb'(\s)xlink:href(\s*=)')


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
