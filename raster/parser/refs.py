"""References between elements: ``href`` targets, ``url(#id)`` property
values, ``href`` chains of paint servers and filters, ``use`` cycles, and
``use`` references into other local SVG documents.

A ``use`` may name an element of another SVG file (``lib.svg#id``; the
file alone names its root ``svg``): the file is read under the rules of
image files (relative to the document, only below the allowed
directories, never from inside an SVG image; see
:mod:`raster.parser.imageload`), and its elements are converted with that
document's own style sheets and ids (SVG 1.1: selectors match the
referenced elements in their document).  Other references to other
documents are not followed (one warning); a missing target or one of the
wrong kind is ignored, as resvg does.
"""

import dataclasses
import os

from .context import SVG_NS, XLINK_HREF
from .style import local_name
from .values import parse_url

__all__ = ['href_target', 'reference', 'href_chain', 'is_recursive', 'external_target',
           'instance_size']

_USE = '{%s}use' % SVG_NS


def _href(el):
    href = el.get('href')
    if href is None:
        href = el.get(XLINK_HREF)
    return None if href is None else href.strip()


def href_target(el, cache, warn=True):
    """The element ``el``'s ``href`` (or ``xlink:href``) names in this
    document, or None (a reference to another document warns once unless
    ``warn`` is False)."""
    href = _href(el)
    if href is None:
        return None
    if not href.startswith('#'):
        if href and warn:
            cache.warn('external', 'references to other documents are not supported')
        return None
    return cache.by_id.get(href[1:])


#: Memo tables shared by a document and the documents it references.
_SHARED = ('documents', 'document_caches', 'external_active')


def external_target(el, cache):
    """``(element, cache)``: the element of another local SVG document that
    ``el``'s ``href`` names (``lib.svg#id``, or ``lib.svg`` for its root)
    and that document's :class:`~raster.parser.context.Cache`; None when the
    reference is local, absent or cannot be followed (one warning: a
    refused or missing file, not SVG, no such id)."""
    href = _href(el)
    if not href or href.startswith('#'):
        return None
    file, _, frag = href.partition('#')
    scheme = file.split(':', 1)[0].lower() if ':' in file else ''
    if len(scheme) > 1 and scheme != 'file':
        cache.warn('external', 'references to other documents are only followed to local '
                               'files: %s' % href[:60])
        return None
    from .imageload import ImageError, fetch_document, image_source
    opts = cache.options
    # (imported here: documents without such references never load it)
    from .imageload import ImageError, fetch_document, image_source
    try:
        real, root = fetch_document(file, opts, cache.table('documents'))
    except ImageError as e:
        cache.warn(('external', str(e)), 'use reference not followed: %s' % e)
        return None
    subs = cache.table('document_caches')
    sub = subs.get(real)
    if sub is None:
        roots = image_source(opts).allowed
        sub_opts = dataclasses.replace(
            opts, base_dir=os.path.dirname(real),
            allow_files_under=roots[0] if roots else None,
            resources_dir=roots[1] if len(roots) > 1 else opts.resources_dir)
        sub = cache.open_document(root, sub_opts)
        for name in _SHARED:
            sub.memo[name] = cache.table(name)
        sub.warned = cache.warned
        subs[real] = sub
    tgt = sub.by_id.get(frag) if frag else sub.root
    if tgt is None:
        cache.warn(('external-id', href), 'use reference not followed: no element %r in %s'
                   % (frag, os.path.basename(real)))
        return None
    return tgt, sub


def reference(value, kind, prop, cache):
    """The element of local name ``kind`` that a ``url(#id)`` value of
    property ``prop`` references, or None.  Remembered per document (the
    ids do not change): thousands of elements may share one value."""
    memo = cache.table('references')
    key = (value, kind, prop)
    tgt = memo.get(key, memo)
    if tgt is not memo:
        return tgt
    u = parse_url(value)
    if u is None:
        cache.warn(prop + '-syntax', 'unsupported %s value %r ignored' % (prop, value))
        tgt = None
    else:
        tgt = cache.by_id.get(u[0])
        if tgt is not None and local_name(tgt) != kind:
            tgt = None
    if len(memo) < 65536:
        memo[key] = tgt
    return tgt


def href_chain(el, kinds, cache):
    """``el`` and the elements it references through ``href`` while they
    are of one of the local names ``kinds`` (cycles cut)."""
    chain = [el]
    seen = {el}
    while True:
        nxt = href_target(chain[-1], cache)
        if nxt is None or nxt in seen or local_name(nxt) not in kinds:
            return chain
        chain.append(nxt)
        seen.add(nxt)


def is_recursive(use, cache):
    """True when instantiating ``use`` would (directly or through other
    ``use`` elements) instantiate itself, or nest deeper than the use depth
    limit.  Memoized per element."""
    memo = cache.table('use_recursive')
    gray = 'gray'
    max_depth = cache.options.max_use_depth

    def visit(u, depth):
        v = memo.get(u)
        if v is gray:
            return True
        if v is not None:
            return v
        if depth > max_depth:
            return True
        memo[u] = gray
        res = False
        tgt = href_target(u, cache, warn=False)
        if tgt is not None:
            anc = u
            while anc is not None:
                if anc is tgt:
                    res = True
                    break
                anc = anc.getparent()
            if not res:
                for u2 in tgt.iter(_USE):
                    if visit(u2, depth + 1):
                        res = True
                        break
        memo[u] = res
        return res

    try:
        return visit(use, 0)
    finally:
        del visit       # it calls itself through its closure: break the cycle


#: Sizes above this are all "too many" (keeps the arithmetic small).
_SIZE_CAP = 10 ** 15

#: Properties that give an element a layer worth counting (the expensive
#: group effects: resolved per copy, composited per copy); a container's
#: opacity below 1 counts too.
LAYER_PROPS = ('clip-path', 'mask', 'filter', 'mix-blend-mode', 'isolation')


def instance_size(el, cache):
    """Estimated ``(nodes, layers)`` that converting ``el`` builds: the
    elements of its subtree, each ``use`` in it counting its target again
    (an upper estimate: hidden and non-rendered elements count too), and
    those of them with a clip path, mask, filter, blend mode or isolation
    (:data:`LAYER_PROPS`) or, for containers, an opacity below 1.  A cycle
    counts nothing (it is refused when converted).  Memoized per element,
    linear in the document; no recursion (use chains may be deep).

    The cost model of ``use`` fan-outs (``max_elements`` and
    ``max_layers`` of :mod:`raster.limits`): a ``use`` whose content
    cannot fit in what is left of the budgets is left out before any of it
    is built."""
    memo = cache.table('instance_size')
    v = memo.get(el)
    if v is not None and v is not _GRAY:
        return v
    styles = cache.styles
    stack = [(el, None)]
    while stack:
        e, kids = stack.pop()
        if kids is None:
            if e in memo:
                continue
            memo[e] = _GRAY
            kids = [c for c in e if isinstance(c.tag, str)]
            if e.tag == _USE:
                t = href_target(e, cache, warn=False)      # (local targets only)
                if t is not None:
                    kids.append(t)
            stack.append((e, kids))
            stack.extend((c, None) for c in kids if c not in memo)
        else:
            st = styles.get(e)
            n, lay = 1, 1 if st and _layered(e, st) else 0
            for c in kids:
                m = memo.get(c)
                if m is not None and m is not _GRAY:
                    n += m[0]
                    lay += m[1]
            memo[e] = (min(n, _SIZE_CAP), min(lay, _SIZE_CAP))
    return memo[el]


_GRAY = (0, 0)
_CONTAINERS = frozenset('{%s}%s' % (SVG_NS, n) for n in ('g', 'a', 'switch', 'svg', 'use',
                                                           'symbol'))


def _layered(el, style):
    """Whether ``el`` (declared ``style``) counts against ``max_layers``:
    a group effect, or a container's opacity below 1 (a leaf's opacity is
    folded into its paint)."""
    if any(p in style for p in LAYER_PROPS):
        return True
    o = style.get('opacity')
    if o is None or el.tag not in _CONTAINERS:
        return False
    try:
        return float(o.strip().rstrip('%')) < (100.0 if o.strip().endswith('%') else 1.0)
    except ValueError:
        return False
