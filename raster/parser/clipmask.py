"""``clipPath`` and ``mask`` elements to :class:`raster.tree.ClipPath` and
:class:`raster.tree.Mask` for the content they apply to.

Units: ``clipPathUnits``, ``maskUnits`` and ``maskContentUnits`` of
``objectBoundingBox`` are resolved against the content's box here, so the
tree holds clip paths and masks in the clipped element's user space.  A
recursive reference is ignored (one warning), as resvg does; a clip path
or mask that leaves nothing visible is :data:`EMPTY`.
"""

from ..geometry.transform import IDENTITY, Affine
from ..tree import ClipPath, Group, Mask, MaskType
from .boxes import object_box
from .context import SVG_NS, State
from .convert import convert, convert_children
from .refs import href_target, reference
from .style import doc_style, length, length_context, local_name, transform_of
from .values import LengthContext, parse_length, parse_url

__all__ = ['EMPTY', 'clip_property', 'build_clip', 'build_mask', 'cut_masks']

#: A clip path or mask that leaves nothing visible.
EMPTY = object()

_SHAPES = frozenset(['rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon', 'path'])
_MASK = '{%s}mask' % SVG_NS


def clip_property(own, kids, state, cache):
    """The ClipPath of the ``clip-path`` value in ``own`` for content
    ``kids``: None (none, or a reference that is ignored) or :data:`EMPTY`
    (nothing is visible)."""
    v = own.get('clip-path')
    if v is None or v.strip() == 'none':
        return None
    ref = reference(v, 'clipPath', 'clip-path', cache)
    return None if ref is None else build_clip(ref, kids, state, cache)


def build_clip(cp, kids, state, cache):
    """A clipPath element to a ClipPath for content ``kids``; None when the
    reference is ignored (recursion), :data:`EMPTY` when nothing is left.

    A clip path in user space units with no clip path of its own does not
    depend on the content: it is built once per viewport, CTM and ``use``
    depth and shared (documents that clip each line of text to its row
    refer to a few clip paths thousands of times)."""
    if cp in cache.active:
        cache.warn('clip-recursive', 'recursive clip-path reference ignored')
        return None
    if cp.get('clipPathUnits') == 'objectBoundingBox':
        return _build_clip(cp, kids, state, cache)
    own = doc_style(cp, cache)[1]
    v = own.get('clip-path')
    if v is not None and v.strip() != 'none':
        return _build_clip(cp, kids, state, cache)
    memo = cache.table('clip_paths')
    key = (cp, state.vw, state.vh, state.ctm, state.use_depth)
    r = memo.get(key, memo)
    if r is memo:
        r = memo[key] = _build_clip(cp, kids, state, cache)
    return r


def _build_clip(cp, kids, state, cache):
    with cache.referencing(cp):
        inh, own = doc_style(cp, cache)
        ctx = length_context(inh, state, cache)
        t = transform_of(cp, own, ctx)
        if t is None:
            return EMPTY
        if cp.get('clipPathUnits') == 'objectBoundingBox':
            box = object_box(kids)
            if box is None or box[2] <= 0 or box[3] <= 0:
                return EMPTY
            t = t @ Affine(box[2], 0, 0, box[3], box[0], box[1])
        sub = State(inh, own, state.vw, state.vh, state.ctm @ t, state.use_depth, True)
        nodes = []
        for ch in cp:
            name = local_name(ch)
            if name in _SHAPES or name == 'text':
                convert(ch, sub, cache, nodes)
            elif name == 'use':
                tgt = href_target(ch, cache)
                if tgt is not None and local_name(tgt) in _SHAPES:
                    convert(ch, sub, cache, nodes)
        nested = clip_property(own, kids, state, cache)
        if nested is EMPTY:
            return EMPTY
        if not nodes:
            return EMPTY
        return ClipPath(root=Group(children=nodes), transform=t, clip_path=nested,
                        id=cp.get('id') or '')


def build_mask(mk, kids, state, cache):
    """A mask element to a Mask for content ``kids`` (None: reference
    ignored; :data:`EMPTY`: nothing is visible)."""
    if mk in cache.active:
        cache.warn('mask-recursive', 'recursive mask reference ignored')
        return None
    with cache.referencing(mk):
        inh, own = doc_style(mk, cache)
        box = None
        obb = mk.get('maskUnits') != 'userSpaceOnUse'
        cobb = mk.get('maskContentUnits') == 'objectBoundingBox'
        if obb or cobb:
            box = object_box(kids)
            if box is None or box[2] <= 0 or box[3] <= 0:
                return EMPTY
        if obb:
            lctx = LengthContext(font_size=inh['_fs'], width=1.0, height=1.0,
                                 dpi=cache.options.dpi)
        else:
            lctx = length_context(inh, state, cache)
        x = length(mk, 'x', 'x', lctx, None)
        y = length(mk, 'y', 'y', lctx, None)
        w = length(mk, 'width', 'x', lctx, None)
        h = length(mk, 'height', 'y', lctx, None)
        x = parse_length('-10%', 'x', lctx) if x is None else x
        y = parse_length('-10%', 'y', lctx) if y is None else y
        w = parse_length('120%', 'x', lctx) if w is None else w
        h = parse_length('120%', 'y', lctx) if h is None else h
        if obb:
            x, y, w, h = box[0] + x * box[2], box[1] + y * box[3], w * box[2], h * box[3]
        if not (w > 0 and h > 0):
            return EMPTY
        ct = IDENTITY
        if cobb:
            ct = Affine(box[2], 0, 0, box[3], box[0], box[1])
        sub = State(inh, own, state.vw, state.vh, state.ctm @ ct, state.use_depth)
        nodes = []
        convert_children(mk, sub, cache, nodes)
        if not ct.is_identity and nodes:
            nodes = [Group(transform=ct, children=nodes)]
        nested = None
        v = own.get('mask')
        if v is not None and v.strip() != 'none':
            ref = reference(v, 'mask', 'mask', cache)
            # a chain of mask-on-mask references that comes back is
            # dropped as a whole (resvg)
            seen = set()
            r = ref
            while r is not None and r not in seen:
                if r is mk or r in cache.active:
                    ref = None
                    cache.warn('mask-recursive', 'recursive mask reference ignored')
                    break
                seen.add(r)
                rv = doc_style(r, cache)[1].get('mask')
                r = reference(rv, 'mask', 'mask', cache) \
                    if rv and rv.strip() != 'none' else None
            if ref is not None:
                nested = build_mask(ref, kids, state, cache)
                if nested is EMPTY:
                    return EMPTY
        if not nodes:
            return EMPTY
        kind = MaskType.ALPHA if own.get('mask-type') == 'alpha' else MaskType.LUMINANCE
        return Mask(rect=(x, y, w, h), root=Group(children=nodes), kind=kind, mask=nested,
                    id=mk.get('id') or '')


def cut_masks(cache):
    """Elements inside ``mask`` elements whose ``mask`` property is dropped
    to break a cycle, decided once per document as resvg does: for every
    mask M in document order, a descendant that references M itself loses
    its ``mask``; one that references another mask N keeps it, and the
    descendants of N that reference M lose theirs.  (Which link of a cycle
    to cut is not specified; this order matches resvg's output.)"""
    memo = cache.table('cut_masks')
    cut = memo.get('cut')
    if cut is not None:
        return cut
    cut = memo['cut'] = set()
    masks = list(cache.root.iter(_MASK))
    if not masks:
        return cut

    def target(e):
        if e in cut:
            return None
        decl = cache.styles.get(e)
        v = decl.get('mask') if decl else None
        if not v or v.strip() == 'none':
            return None
        u = parse_url(v)
        t = cache.by_id.get(u[0]) if u is not None else None
        return t if t is not None and local_name(t) == 'mask' else None
    for m in masks:
        for e in m.iter():
            if e is m or not isinstance(e.tag, str):
                continue
            n = target(e)
            if n is None:
                continue
            if n is m:
                cut.add(e)
                continue
            for f in n.iter():
                if f is not n and isinstance(f.tag, str) and target(f) is m:
                    cut.add(f)
    return cut
