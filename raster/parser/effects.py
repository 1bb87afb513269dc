"""Group effects, decided in one place: what an element does to its
content as a group (opacity, ``mix-blend-mode``, ``isolation``,
``clip-path``, ``mask``, ``filter``), and the Group that carries them.

:func:`effects` resolves them for an element whose content is known (clip
paths, masks and filters with ``objectBoundingBox`` units need the
content's box); :func:`wrap` and :func:`emit` put the content in a Group
when something needs one.
"""

import dataclasses

from ..geometry.pathdata import rect_path
from ..tree import BlendMode, ClipPath, Fill, Group, ImageNode, PathNode, SolidPaint
from .refs import reference
from .style import BLACK, opacity

__all__ = ['Effects', 'NO_EFFECTS', 'effects', 'wrap', 'emit', 'clip_rect', 'ghost']


@dataclasses.dataclass(frozen=True, slots=True)
class Effects:
    """What an element does to its content as a group; ``ok`` False: the
    element is not rendered at all."""
    opacity: float = 1.0
    blend: BlendMode = BlendMode.NORMAL
    isolate: bool = False
    clip: object = None
    mask: object = None
    filters: tuple = ()
    ok: bool = True
    #: Needs a layer for something other than opacity (derived).
    composited: bool = dataclasses.field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, 'composited', (
            self.clip is not None or self.mask is not None or self.blend != BlendMode.NORMAL
            or self.isolate or bool(self.filters)))

    @property
    def trivial(self):
        """Changes nothing: no Group is needed (but for a transform or id)."""
        return self.opacity >= 1.0 and not self.composited

    def group(self, id, transform, children):
        """A Group with these effects."""
        return Group(id=id, transform=transform, opacity=self.opacity, clip_path=self.clip,
                     mask=self.mask, filters=tuple(self.filters), blend_mode=self.blend,
                     isolate=self.isolate, children=children)


NO_EFFECTS = Effects()
NOT_DRAWN = Effects(ok=False)
# properties that make Effects more than an opacity
_EFFECT_PROPS = frozenset(['clip-path', 'mask', 'filter', 'mix-blend-mode', 'isolation'])
_BLEND = {m.value: m for m in BlendMode}


def effects(el, own, state, cache, kids, t=None):
    """Group effects of element ``el`` with own style ``own`` whose content
    is ``kids`` (nodes in its user space; ``t`` its transform, in
    ``state``).  ``ok`` is False when the element is not rendered: an empty
    clip path, an objectBoundingBox clip or mask of an empty box, an
    invalid filter reference."""
    if not own:
        return NO_EFFECTS
    for k in own:
        if k in _EFFECT_PROPS:
            break
    else:       # at most an opacity (ignored inside a clip path)
        o = own.get('opacity')
        if o is None or state.clip:
            return NO_EFFECTS
        memo = cache.table('opacity_effects')
        e = memo.get(o)
        if e is None:
            e = memo[o] = Effects(opacity=opacity(o))
        return e
    # the layer budget (raster.limits max_layers); use copies pay ahead
    if not cache.prepaid and not cache.spend('layers', 1, 'element with a clip path, mask, '
                                             'filter or blend mode'):
        return NOT_DRAWN
    # clip paths, masks and filters load with the first element that has one
    from .clipmask import EMPTY, build_mask, clip_property, cut_masks
    mask = None
    if t is not None and not t.is_identity and ('clip-path' in own or 'mask' in own):
        state = state.sub(transform=t)
    clip = clip_property(own, kids, state, cache)
    if clip is EMPTY:
        return NOT_DRAWN
    if state.clip:
        return Effects(clip=clip)
    v = own.get('mask')
    if v is not None and v.strip() != 'none' and el not in cut_masks(cache):
        mask = reference(v, 'mask', 'mask', cache)
        if mask is not None:
            mask = build_mask(mask, kids, state, cache)
            if mask is EMPTY:
                return NOT_DRAWN
    v = own.get('filter')
    filters = None
    if v is not None and v.strip() != 'none':
        from .filters import resolve_filter_property
        filters = resolve_filter_property(el, v, kids, state, cache)
        if filters is None:         # invalid reference, empty filter: not rendered
            return NOT_DRAWN
    blend = _BLEND.get(own.get('mix-blend-mode', 'normal'), BlendMode.NORMAL)
    return Effects(opacity=opacity(own.get('opacity')), blend=blend,
                   isolate=own.get('isolation') == 'isolate', clip=clip, mask=mask,
                   filters=tuple(filters or ()))


def wrap(el, own, t, kids, state, cache, clip=None, keep=False):
    """The nodes to add to the parent for content ``kids`` of ``el``: the
    content itself, or a Group when the element changes something (or has
    an id, or ``keep``).  ``clip`` is a viewport clip (nested svg,
    symbol)."""
    if not kids and own.get('filter', 'none').strip() == 'none':
        return []       # (a filter can draw for an empty element: feFlood)
    e = effects(el, own, state, cache, kids, t)
    if not e.ok:
        return []
    if e.opacity <= 0.0:
        # invisible but rendered: it still counts in its parent's box
        g = ghost(kids)
        return [Group(transform=t, children=g)] if g else []
    if clip is not None:
        if e.clip is not None:      # viewport clip inside the element's clip path
            kids = [Group(clip_path=clip, children=kids)]
        else:
            e = dataclasses.replace(e, clip=clip)
    kids, e = _fold_opacity(kids, e)
    if (e.opacity < 1.0 and not e.composited and not cache.prepaid
            and not cache.spend('layers', 1, 'group with opacity')):
        return []                   # the layer budget (raster.limits max_layers)
    i = el.get('id') or ''
    if not keep and not i and t.is_identity and e.trivial:
        return kids
    g = e.group(i, t, kids)
    cache.note_id(el, g)
    return [g]


def emit(node, t, e, cache, parent):
    """Append a leaf node to ``parent``, inside a Group when its transform
    ``t`` or its effects ``e`` need one (the Group then stands for the
    node's id)."""
    if t.is_identity and e.trivial:
        parent.append(node)
        return
    g = e.group(node.id, t, [node])
    if node.id:
        cache.tree_ids[node.id] = g
    parent.append(g)


def ghost(nodes):
    """Unpainted copies of ``nodes`` that keep only their geometry and
    transforms (images become their viewport rectangles): what an element
    that is rendered but invisible (``opacity: 0``, no fill and no stroke)
    adds to its parent's object bounding box, which ignores opacity and
    paint (SVG 2; resvg counts such elements too).  The renderer draws
    nothing for them."""
    out = []
    for n in nodes:
        if isinstance(n, Group):
            kids = ghost(n.children)
            if kids:
                out.append(Group(transform=n.transform, children=kids))
        elif isinstance(n, PathNode):
            if n.path is not None and len(n.path.verbs):
                out.append(n if n.fill is None and n.stroke is None and n.markers is None
                           else PathNode(path=n.path))
        elif isinstance(n, ImageNode):
            out.append(PathNode(path=rect_path(*n.view_rect)))
    return out


def clip_rect(x, y, w, h):
    """A ClipPath of the rectangle (x, y, w, h) (viewport clips)."""
    rect = PathNode(path=rect_path(x, y, w, h), fill=Fill(SolidPaint(BLACK)))
    return ClipPath(root=Group(children=[rect]))


def _fold_opacity(kids, e):
    """Group opacity over a single path painted once (fill or stroke, no
    markers) equals that paint's own opacity times the group's: fold it in
    and spare the renderer a layer.  Returns ``(kids, effects)``."""
    if e.opacity >= 1.0 or e.composited or len(kids) != 1 or not isinstance(kids[0], PathNode):
        return kids, e
    n = kids[0]
    if n.markers is not None or (n.fill is None) == (n.stroke is None):
        return kids, e
    if n.fill is not None:
        n = dataclasses.replace(n, fill=dataclasses.replace(n.fill,
                                                            opacity=n.fill.opacity * e.opacity))
    else:
        n = dataclasses.replace(n, stroke=dataclasses.replace(
            n.stroke, opacity=n.stroke.opacity * e.opacity))
    return [n], dataclasses.replace(e, opacity=1.0)
