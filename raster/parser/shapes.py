"""Basic shapes and ``path``: geometry, fill, stroke and markers.

Geometry: lengths in user units, SVG's prefix-on-error rule for path data,
arcs converted to cubics :data:`ARC_SAFETY` times finer than the
tolerance divided by the element's scale.  Path data without arcs is
parsed for the whole document in one vectorized pass
(:func:`raster.geometry.pathdata.parse_paths`) and shared by every element with the
same ``d`` (paths are immutable), as are basic shapes with the same
attributes.  What a computed style says about painting (paints that do
not depend on the shape, stroke parameters, paint order, antialiasing)
is worked out once per style.

An invisible shape (``visibility: hidden``, ``opacity: 0``, no fill and
no stroke) paints nothing but still counts in its parent's object bounding
box (SVG 2: the box is geometry, whatever the paint and opacity; resvg
agrees), so it is kept unpainted.  Inside a ``clipPath`` a shape is filled black with its
``clip-rule``.
"""

import math

from ..errors import LimitError, RasterError
from ..geometry.bounds import bbox as exact_bbox
from ..geometry.stroking import LineCap, LineJoin, StrokeStyle
from ..geometry.pathdata import (circle_path, ellipse_path, line_path, parse_path, parse_paths,
                       polyline_path, rect_path)
from ..tree import Fill, FillRule, Group, PathNode, SolidPaint, Stroke
from .context import SVG_NS
from .effects import NO_EFFECTS, effects
from .paint import paint
from .style import (BLACK, length, length_context, opacity, origin_box, paint_order, style_of,
                    transform_of)
from .values import parse_length, parse_length_list, parse_number, parse_paint

__all__ = ['convert_shape', 'geometry', 'fill_and_stroke', 'ARC_SAFETY', 'SHAPES']

#: Arcs are made this much finer than the tolerance, so zooming in stays smooth:
#: at 0.01 a circle drawn 20x its natural size is still within the renderer's
#: accuracy target (8/255; 0.1 gave 27/255 there), for about 1.5x the cubics.
ARC_SAFETY = 0.01
SHAPES = frozenset(['rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon', 'path'])
_P = '{%s}' % SVG_NS
_PLEN = len(_P)
_PATH = _P + 'path'
# the attributes that define each basic shape
_GEOMETRY_ATTRS = {'rect': ('x', 'y', 'width', 'height', 'rx', 'ry'), 'circle': ('cx', 'cy', 'r'),
                   'ellipse': ('cx', 'cy', 'rx', 'ry'), 'line': ('x1', 'y1', 'x2', 'y2'),
                   'polyline': ('points',), 'polygon': ('points',)}
# arcs are re-flattened for marker placement with a tolerance so large that
# only the "at most 90 degrees per piece" rule splits them (as resvg does)
_PLACEMENT_TOL = 1e9
_JOINS = frozenset(m.value for m in LineJoin)
_CAPS = frozenset(m.value for m in LineCap)


def convert_shape(el, state, cache, parent):
    """A basic shape or ``path`` element to a PathNode (with markers)."""
    name = el.tag[_PLEN:]
    inh, own = style_of(el, state.inh, state.own, cache)
    ctx = length_context(inh, state, cache)
    t = transform_of(el, own, ctx)
    if t is None:
        return
    _, hidden, has_markers, order, antialias, paints, _ = _shape_style(inh, ctx, cache)
    clip_mode = state.clip
    if hidden and clip_mode:
        return
    ident = t.is_identity
    try:
        if not ident:
            state.check(t)     # an overflowing CTM: the element is left out
        path = _shape_path(el, name, ctx, state, t, cache)
    except LimitError as e:     # a budget of raster.limits: left out, one warning
        cache.warn('path-limit', 'element <%s> not rendered: %s' % (name, e))
        return
    except RasterError:
        return
    if path is None or len(path.verbs) == 0:
        return
    if hidden:
        fill = stroke = None
    elif paints is not None and not clip_mode:     # (fill_and_stroke, inlined)
        fp, fop, rule, sp, params = paints
        fill = None if fp is None else Fill(fp, fop, rule)
        stroke = None if sp is None else Stroke(sp, params[0], params[1])
    else:
        fill, stroke = fill_and_stroke(inh, ctx, path, state, cache)
    kind = origin_box(el, own)
    if kind is not None:
        # transform-box fill-box / stroke-box: the origin is placed in the
        # shape's own box (the stroke box as the fill box widened by half
        # the stroke width)
        try:
            x0, y0, x1, y1 = exact_bbox(path)
        except RasterError:
            return
        pad = 0.5 * stroke.style.width if kind == 'stroke' and stroke is not None else 0.0
        t = transform_of(el, own, ctx, (x0 - pad, y0 - pad, x1 - x0 + 2 * pad, y1 - y0 + 2 * pad))
        if t is None:
            return
        ident = t.is_identity
        try:
            if not ident:
                state.check(t)
        except RasterError:
            return
    markers = None
    if has_markers and not hidden and not clip_mode:
        from .markers import build_markers      # (loaded with the first marker)
        placement = _placement_path(el, name, path, ctx, cache)
        markers = build_markers(el, name, path, placement, inh, ctx, state.sub(transform=t),
                                cache, fill, stroke)
    # a shape that paints nothing (fill and stroke none, visibility hidden,
    # opacity 0) is kept unpainted: it counts in its parent's bounding box
    i = el.get('id') or ''
    node = PathNode(id=i, path=path, fill=fill, stroke=stroke, paint_order=order,
                    markers=markers, antialias=antialias)
    e = effects(el, own, state, cache, [node], t) if own else NO_EFFECTS
    if e is not NO_EFFECTS:
        if not e.ok:
            return
        if e.opacity <= 0.0:
            node = PathNode(path=path)
            e = NO_EFFECTS
        elif e.opacity < 1.0 and not e.composited and markers is None \
                and (fill is None) != (stroke is None):
            # group opacity over one paint: folded into it (the Fill or
            # Stroke was made for this node alone, so it is updated in place)
            if fill is not None:
                fill.opacity = fill.opacity * e.opacity
            else:
                stroke.opacity = stroke.opacity * e.opacity
            e = NO_EFFECTS
    if i and i not in cache.tree_ids:
        cache.tree_ids[i] = node
    if ident and (e is NO_EFFECTS or e.trivial):
        parent.append(node)
    else:
        g = (Group(id=i, transform=t, children=[node]) if e is NO_EFFECTS
             else e.group(i, t, [node]))
        if i:
            cache.tree_ids[i] = g
        parent.append(g)


def _shape_path(el, name, ctx, state, t, cache):
    """The Path of a shape element under transform ``t`` in ``state``."""
    tol = cache.options.tolerance
    if name == 'path':
        paths = _element_paths(cache)
        path = paths.get(el)
        if path is not None:
            return path
        d = el.get('d')
        if not d:
            return None
        if 'a' in d or 'A' in d:
            return path_data(d, arc_tolerance(state, t, cache), cache)
        return path_data(d, tol, cache)
    if name == 'line' or name == 'polyline' or name == 'polygon':
        pass                    # no curves: the tolerance is not used
    elif not (name == 'rect' and el.get('rx') is None and el.get('ry') is None):
        tol = arc_tolerance(state, t, cache)
    return geometry(el, name, ctx, tol, cache)


def arc_tolerance(state, t, cache):
    """Tolerance for arcs of an element with transform ``t`` in ``state``
    (memoized in the state for translations)."""
    if t.is_translation:
        tol = state.arc_tol
        if tol is None:
            tol = state.arc_tol = _arc_tolerance(state.scale(), cache)
        return tol
    return _arc_tolerance((state.ctm @ t).max_scale(), cache)


def _arc_tolerance(s, cache):
    tol = cache.options.tolerance * ARC_SAFETY
    if s > 0 and math.isfinite(s):
        tol = tol / s
    return min(max(tol, 1e-9), 1e9)


def path_data(d, tol, cache):
    """``parse_path(d, tol, strict=False)``, memoized per document (data
    without arcs does not depend on the tolerance: one key)."""
    key = (d, tol) if ('a' in d or 'A' in d) else d
    memo = cache.table('path_data')
    _element_paths(cache)
    p = memo.get(key)
    if p is None:
        check_path_size(d, cache)
        p = parse_path(d, tol, strict=False)
        if len(memo) < 65536:
            memo[key] = p
    return p


def check_path_size(data, cache):
    """The cost model of path data (``d``, ``points``): parsing holds a
    few hundred bytes per segment for a while, so data longer than
    ``max_path_bytes`` (:mod:`raster.limits`) is refused before it is
    parsed (:class:`~raster.errors.LimitError`: the element is left out)."""
    lim = cache.limits.max_path_bytes
    if len(data) > lim:
        raise LimitError('path data of %d bytes, more than max_path_bytes %d'
                         % (len(data), lim))


#: Characters of path data parsed in one vectorized pass (see _element_paths).
_PATHS_CHARS = 1 << 18
def _element_paths(cache):
    """``{path element: Path}`` for the document's arc-free path data,
    parsed in one vectorized pass on first use (a map with thousands of
    ``path`` elements would otherwise pay the per-string overhead
    thousands of times)."""
    paths = cache.memo.get('element_paths')
    if paths is not None:
        return paths
    memo = cache.table('path_data')
    ds = {}
    els = []
    lim = cache.limits.max_path_bytes
    for el in cache.root.iter(_PATH):
        d = el.get('d')
        if d and 'a' not in d and 'A' not in d and len(d) <= lim:
            els.append((el, d))
            if d not in memo:
                ds[d] = None
                if len(ds) >= 65536:
                    break
    if len(ds) >= 32:
        # in passes of about _PATHS_CHARS characters: a pass's temporaries are
        # some tens of bytes per character of path data
        ds = list(ds)
        i = 0
        while i < len(ds):
            j, n = i, 0
            while j < len(ds) and (j == i or n + len(ds[j]) <= _PATHS_CHARS):
                n += len(ds[j])
                j += 1
            part = ds[i:j]
            i = j
            try:
                parsed = parse_paths(part, cache.options.tolerance)
            except RasterError:
                continue            # one of them overflows: parsed one by one later
            memo.update(zip(part, parsed))
    paths = cache.memo['element_paths'] = {el: memo[d] for el, d in els if d in memo}
    return paths


def geometry(el, name, ctx, tol, cache):
    """The Path of a basic shape or ``path`` element (None when it has no
    valid geometry); lengths resolve against ``ctx``, curves within
    ``tol``.  Basic shapes are memoized on their attribute strings."""
    if name == 'path':
        d = el.get('d')
        if not d:
            return None
        return path_data(d, tol, cache)
    key = (name, ctx, tol) + tuple(map(el.get, _GEOMETRY_ATTRS.get(name, ('points',))))
    if name in ('polyline', 'polygon') and key[-1]:
        check_path_size(key[-1], cache)
    memo = cache.table('shape_geometry')
    p = memo.get(key, memo)
    if p is memo:
        p = _shape_geometry(el, name, ctx, tol)
        if len(memo) < 65536:
            memo[key] = p
    return p


def _shape_geometry(el, name, ctx, tol):
    L = length
    if name == 'rect':
        w = L(el, 'width', 'x', ctx, None)
        h = L(el, 'height', 'y', ctx, None)
        if w is None or h is None or w <= 0 or h <= 0:
            return None
        rx = L(el, 'rx', 'x', ctx, None)
        ry = L(el, 'ry', 'y', ctx, None)
        if rx is not None and rx < 0:
            rx = None
        if ry is not None and ry < 0:
            ry = None
        return rect_path(L(el, 'x', 'x', ctx), L(el, 'y', 'y', ctx), w, h, rx, ry, tol)
    if name == 'circle':
        r = L(el, 'r', 'other', ctx, None)
        if r is None or r <= 0:
            return None
        return circle_path(L(el, 'cx', 'x', ctx), L(el, 'cy', 'y', ctx), r, tol)
    if name == 'ellipse':
        rx = L(el, 'rx', 'x', ctx, None)
        ry = L(el, 'ry', 'y', ctx, None)
        # a negative radius is invalid: treated as auto (resvg)
        rx = None if rx is not None and rx < 0 else rx
        ry = None if ry is not None and ry < 0 else ry
        if rx is None and ry is None:
            return None
        return ellipse_path(L(el, 'cx', 'x', ctx), L(el, 'cy', 'y', ctx), rx, ry, tol)
    if name == 'line':
        return line_path(L(el, 'x1', 'x', ctx), L(el, 'y1', 'y', ctx),
                         L(el, 'x2', 'x', ctx), L(el, 'y2', 'y', ctx))
    pts = el.get('points')
    if not pts:
        return None
    return polyline_path(pts, closed=(name == 'polygon'))


def _placement_path(el, name, path, ctx, cache):
    """The path whose vertices carry markers: arcs (path arcs, rounded
    corners, ellipses) split only into pieces of at most 90 degrees."""
    if name in ('line', 'polyline', 'polygon'):
        return path
    if name == 'path':
        d = el.get('d') or ''
        if 'a' not in d and 'A' not in d:
            return path
    if name == 'rect' and el.get('rx') is None and el.get('ry') is None:
        return path
    try:
        p = geometry(el, name, ctx, _PLACEMENT_TOL, cache)
    except RasterError:
        return path
    return path if p is None else p


# -- painting -----------------------------------------------------------------------

def _shape_style(inh, ctx, cache):
    """What a shape's computed style ``inh`` (lengths against ``ctx``) says
    about its painting, worked out once per style: ``(inh, hidden, has
    markers, paint order, antialias, static paints, ctx)`` (see
    :func:`_static_paints`)."""
    memo = cache.table('shape_style')
    key = (id(inh), id(ctx))
    r = memo.get(key)
    if r is None or r[0] is not inh or r[6] is not ctx:
        vis = inh.get('visibility', 'visible')
        sr = inh.get('shape-rendering', 'auto')
        r = (inh, vis == 'hidden' or vis == 'collapse',
             inh.get('marker-start', 'none') != 'none'
             or inh.get('marker-mid', 'none') != 'none'
             or inh.get('marker-end', 'none') != 'none',
             paint_order(inh.get('paint-order')),
             sr != 'crispEdges' and sr != 'optimizeSpeed',
             _static_paints(inh, ctx, cache), ctx)
        if len(memo) < 65536:
            memo[key] = r     # (keeps inh, ctx alive: their ids stay unique)
    return r


def _rule(v):
    return FillRule.EVENODD if v == 'evenodd' else FillRule.NONZERO


def fill_and_stroke(inh, ctx, path, state, cache, box=None):
    """The resolved ``(Fill or None, Stroke or None)`` of a shape or text
    run with computed style ``inh`` and geometry ``path`` (for
    objectBoundingBox paints, unless ``box`` (x0, y0, x1, y1) gives the
    bounding box: text); inside a clip path, a black fill with the
    clip-rule."""
    if state.clip:
        return Fill(SolidPaint(BLACK), 1.0, _rule(inh.get('clip-rule', 'nonzero'))), None
    # colours and 'none' depend on the style alone: resolved once per style
    spec = _shape_style(inh, ctx, cache)[5]
    if spec is not None:
        fp, fop, rule, sp, params = spec
        return (None if fp is None else Fill(fp, fop, rule),
                None if sp is None else Stroke(sp, params[0], params[1]))
    fill = stroke = None
    fp = paint(inh.get('fill', 'black'), inh, ctx, state, cache, path, box)
    if fp is not None:
        fill = Fill(fp, opacity(inh.get('fill-opacity')), _rule(inh.get('fill-rule', 'nonzero')))
    sv = inh.get('stroke')
    if sv is not None:
        sp = paint(sv, inh, ctx, state, cache, path, box)
        if sp is not None:
            params = _stroke_params(inh, ctx, cache)
            if params is not False:
                stroke = Stroke(sp, params[0], params[1])
    return fill, stroke


def _static_paints(inh, ctx, cache):
    """``(fill paint, fill opacity, fill rule, stroke paint, stroke
    parameters)`` of computed style ``inh`` when neither paint depends on
    the shape or the context (colours, ``currentColor``, ``none``, invalid
    values); None otherwise (references, context paints).  A paint is None
    when not painted."""
    fv = inh.get('fill', 'black')
    sv = inh.get('stroke')
    for v in (fv, sv):
        p = parse_paint(v) if v is not None else None
        if p is not None and p.kind not in ('none', 'color', 'current'):
            return None
    fp = paint(fv, inh, ctx, None, cache)
    sp = paint(sv, inh, ctx, None, cache) if sv is not None else None
    params = _stroke_params(inh, ctx, cache) if sp is not None else False
    if params is False:
        sp = None
    return (fp, opacity(inh.get('fill-opacity')), _rule(inh.get('fill-rule', 'nonzero')), sp,
            params)


def _stroke_params(inh, ctx, cache):
    """``(StrokeStyle, stroke-opacity)`` of a computed style, or False when
    the stroke is not drawn; memoized on the stroke properties."""
    key = (inh.get('stroke-width'), inh.get('stroke-linejoin'), inh.get('stroke-linecap'),
           inh.get('stroke-miterlimit'), inh.get('stroke-dasharray'),
           inh.get('stroke-dashoffset'), inh.get('stroke-opacity'), ctx)
    memo = cache.table('stroke_params')
    params = memo.get(key)
    if params is None:
        params = _compute_stroke_params(inh, ctx)
        if len(memo) < 4096:
            memo[key] = params
    return params


def _compute_stroke_params(inh, ctx):
    w = 1.0
    s = inh.get('stroke-width')
    if s is not None:
        v = parse_length(s, 'other', ctx)
        if v is not None:
            w = v
    if not w > 0:
        return False
    join = inh.get('stroke-linejoin', 'miter')
    cap = inh.get('stroke-linecap', 'butt')
    ml = parse_number(inh.get('stroke-miterlimit', '4'))
    if ml is None or ml < 1:
        ml = 4.0
    dash = None
    da = inh.get('stroke-dasharray')
    if da is not None and da.strip() != 'none':
        vals = parse_length_list(da, 'other', ctx)
        if vals and all(v >= 0 for v in vals) and sum(vals) > 0:
            if len(vals) % 2:
                vals = vals * 2
            dash = tuple(vals)
    off = 0.0
    do = inh.get('stroke-dashoffset')
    if do is not None:
        v = parse_length(do, 'other', ctx)
        if v is not None:
            off = v
    style = StrokeStyle(width=w, join=join if join in _JOINS else LineJoin.MITER,
                        cap=cap if cap in _CAPS else LineCap.BUTT, miterlimit=ml, dash=dash,
                        dash_offset=off)
    return style, opacity(inh.get('stroke-opacity'))
