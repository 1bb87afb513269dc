"""References between elements: ``href`` targets, ``url(#id)`` property
values, ``href`` chains of paint servers and filters, ``use`` cycles.

References to other documents are not followed (one warning); a missing
target or one of the wrong kind is ignored, as resvg does.
"""

from .context import SVG_NS, XLINK_HREF
from .style import local_name
from .values import parse_url

__all__ = ['href_target', 'reference', 'href_chain', 'is_recursive', 'instance_size']

_USE = '{%s}use' % SVG_NS


def href_target(el, cache):
    """The element ``el``'s ``href`` (or ``xlink:href``) names in this
    document, or None."""
    href = el.get('href')
    if href is None:
        href = el.get(XLINK_HREF)
    if href is None:
        return None
    href = href.strip()
    if not href.startswith('#'):
        if href:
            cache.warn('external', 'references to other documents are not supported')
        return None
    return cache.by_id.get(href[1:])


def reference(value, kind, prop, cache):
    """The element of local name ``kind`` that a ``url(#id)`` value of
    property ``prop`` references, or None."""
    u = parse_url(value)
    if u is None:
        cache.warn(prop + '-syntax', 'unsupported %s value %r ignored' % (prop, value))
        return None
    tgt = cache.by_id.get(u[0])
    if tgt is None or local_name(tgt) != kind:
        return None
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
        tgt = href_target(u, cache)
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

    return visit(use, 0)


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
                t = href_target(e, cache)
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
