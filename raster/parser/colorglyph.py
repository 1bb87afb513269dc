"""Colour glyphs as render tree nodes.

:func:`color_glyph_node` turns the description of a colour glyph
(:mod:`raster.fonts.color`: layers in font units, y up) into one
:class:`~raster.tree.Group` whose transform maps glyph space to the text's
user space.  Nothing new is asked of the renderer:

* a fill layer is a :class:`~raster.tree.PathNode` filled with a
  :class:`~raster.tree.SolidPaint`, :class:`~raster.tree.LinearGradient`,
  :class:`~raster.tree.RadialGradient` (COLRv1's two circles are the focal
  and the end circle) or :class:`~raster.tree.SweepGradient`; colour lines
  with stops outside [0, 1] have their geometry rescaled to the stops;
* a clip layer is a Group with a :class:`~raster.tree.ClipPath`;
* composite modes: ``src_over`` and ``dest_over`` are drawing orders,
  ``src`` and ``dest`` one side, ``clear`` nothing, the blend modes an
  isolated Group whose source has a :class:`~raster.tree.BlendMode`, and
  the Porter-Duff operators (``src_in``, ``dest_out``, ``xor``, ``plus``,
  ...) a filter: the other side as an ``feImage`` and an ``feComposite``
  (in sRGB) within the glyph's clip box;
* a bitmap glyph (sbix, CBDT) is an :class:`~raster.tree.ImageNode` of its
  decoded PNG;
* an SVG glyph is its document parsed like an SVG image (self-contained:
  no files) and the node of its ``glyph<id>`` element, or the whole
  document, drawn with y down.

Palette index 0xFFFF (the foreground) takes the text's fill colour when
it is a solid colour, else black.
"""

import dataclasses

from ..errors import RasterError
from ..geometry.transform import IDENTITY, Affine
from ..fonts.color import BitmapGlyph, ClipLayer, CompositeLayer, FillLayer, SvgGlyph
from ..tree import BlendMode, ClipPath, Fill, Group, ImageNode, PathNode, SolidPaint
from ..tree.servers import GradientStop, LinearGradient, RadialGradient, SpreadMethod, SweepGradient
from ..tree import filter as tf
from .imageload import ImageError, decode_raster, load_svg_data

__all__ = ['color_glyph_node']

_BLACK = (0.0, 0.0, 0.0, 1.0)
_FLIP = Affine.scale(1.0, -1.0)

_BLENDS = {'screen': BlendMode.SCREEN, 'overlay': BlendMode.OVERLAY,
           'darken': BlendMode.DARKEN, 'lighten': BlendMode.LIGHTEN,
           'color_dodge': BlendMode.COLOR_DODGE, 'color_burn': BlendMode.COLOR_BURN,
           'hard_light': BlendMode.HARD_LIGHT, 'soft_light': BlendMode.SOFT_LIGHT,
           'difference': BlendMode.DIFFERENCE, 'exclusion': BlendMode.EXCLUSION,
           'multiply': BlendMode.MULTIPLY, 'hsl_hue': BlendMode.HUE,
           'hsl_saturation': BlendMode.SATURATION, 'hsl_color': BlendMode.COLOR,
           'hsl_luminosity': BlendMode.LUMINOSITY}
# Porter-Duff modes: (feComposite operator, the filtered side is the source)
_PORTER_DUFF = {'src_in': ('in', True), 'dest_in': ('in', False), 'src_out': ('out', True),
                'dest_out': ('out', False), 'src_atop': ('atop', True),
                'dest_atop': ('atop', False), 'xor': ('xor', True), 'plus': ('arithmetic', True)}


def color_glyph_node(font, desc, matrix, foreground, cache):
    """The Group drawing colour glyph ``desc`` (a tuple of layers from
    :meth:`raster.fonts.color.ColorFont.glyph`) of ``font``.

    Parameters
    ----------
    font : raster.fonts.Font
    desc : tuple
    matrix : Affine
        Glyph space (font units, y up) -> the text's user space.
    foreground : tuple of 4 floats
        Straight RGBA of palette index 0xFFFF.
    cache : raster.parser.context.Cache
        The document's cache (SVG glyph documents are parsed once per
        document).

    Returns
    -------
    Group or None
        None when nothing is drawn.
    """
    kids = _layers(font, desc, foreground, cache)
    if not kids:
        return None
    return Group(transform=matrix, children=kids)


def _layers(font, layers, fg, cache):
    out = []
    for layer in layers:
        if isinstance(layer, FillLayer):
            if not len(layer.path.verbs):
                continue
            paint, opacity = _paint(layer.brush, fg)
            if paint is not None:
                out.append(PathNode(path=layer.path, fill=Fill(paint, opacity)))
        elif isinstance(layer, ClipLayer):
            inner = _layers(font, layer.layers, fg, cache)
            if inner and len(layer.path.verbs):
                clip = ClipPath(root=Group(children=[PathNode(path=layer.path,
                                                              fill=Fill(SolidPaint(_BLACK)))]))
                out.append(Group(clip_path=clip, children=inner))
        elif isinstance(layer, CompositeLayer):
            out.extend(_composite(font, layer, fg, cache))
        elif isinstance(layer, BitmapGlyph):
            node = _bitmap(layer, cache)
            if node is not None:
                out.append(node)
        elif isinstance(layer, SvgGlyph):
            node = _svg(font, layer, cache)
            if node is not None:
                out.append(node)
    return out


def _composite(font, layer, fg, cache):
    src = _layers(font, layer.source, fg, cache)
    back = _layers(font, layer.backdrop, fg, cache)
    mode = layer.mode
    if mode == 'clear':
        return []
    if mode == 'src':
        return src
    if mode == 'dest':
        return back
    if mode == 'src_over':
        return back + src
    if mode == 'dest_over':
        return src + back
    blend = _BLENDS.get(mode)
    if blend is not None:
        if not src:
            return back
        return [Group(isolate=True, children=back + [Group(blend_mode=blend, children=src)])]
    op, source_filtered = _PORTER_DUFF.get(mode, ('over', True))
    drawn, other = (src, back) if source_filtered else (back, src)
    if not drawn:
        return []
    x0, y0, x1, y1 = layer.box
    if not (x1 > x0 and y1 > y0):
        return back + src
    k = (0.0, 1.0, 1.0, 0.0) if op == 'arithmetic' else (0.0, 0.0, 0.0, 0.0)
    prims = [tf.Image(result='other', linear=False, root=Group(children=other)),
             tf.Composite(inputs=(tf.Source.GRAPHIC, tf.Result('other')), linear=False,
                          operator=tf.CompositeOperator(op), k=k)]
    region = (x0, y0, x1 - x0, y1 - y0)
    return [Group(filters=(tf.Filter(region, prims),), children=drawn)]


def _rgba(stop, fg):
    c = fg if stop.color is None else stop.color
    return (c[0], c[1], c[2], c[3] * stop.alpha)


def _paint(brush, fg):
    """(paint, opacity) of a brush; (None, 0) when it paints nothing."""
    stops = brush.stops
    if brush.kind == 'solid' or len(stops) == 1:
        c = _rgba(stops[0], fg)
        return (SolidPaint(c), 1.0) if c[3] > 0 else (None, 0.0)
    lo, hi = stops[0].offset, stops[-1].offset
    if hi <= lo:
        return SolidPaint(_rgba(stops[-1], fg)), 1.0
    span = hi - lo
    gstops = tuple(GradientStop((s.offset - lo) / span, _rgba(s, fg)) for s in stops)
    spread = SpreadMethod(brush.extend)
    g = brush.geometry

    def at(a, b, t):
        return a + (b - a) * t
    if brush.kind == 'linear':
        x0, y0, x1, y1 = g
        return LinearGradient(at(x0, x1, lo), at(y0, y1, lo), at(x0, x1, hi), at(y0, y1, hi),
                              gstops, brush.transform, spread), 1.0
    if brush.kind == 'radial':
        x0, y0, r0, x1, y1, r1 = g
        return RadialGradient(cx=at(x0, x1, hi), cy=at(y0, y1, hi), r=max(at(r0, r1, hi), 0.0),
                              fx=at(x0, x1, lo), fy=at(y0, y1, lo), fr=max(at(r0, r1, lo), 0.0),
                              stops=gstops, transform=brush.transform, spread=spread), 1.0
    cx, cy, a0, a1 = g
    return SweepGradient(cx, cy, at(a0, a1, lo), at(a0, a1, hi), gstops, brush.transform,
                         spread), 1.0


def _bitmap(layer, cache):
    memo = cache.table('color_bitmaps')
    key = layer.data
    pix = memo.get(key)
    if pix is None:
        try:
            pix = decode_raster(layer.data, 'png')
            pix.setflags(write=False)
        except ImageError as e:
            cache.warn('color-bitmap', 'bitmap glyph not drawn: %s' % e)
            pix = False
        memo[key] = pix
    if pix is False:
        return None
    h, w = pix.shape[:2]
    top = -(layer.y + layer.height)          # y down in the flipped group
    m = Affine.translate(layer.x, top) @ Affine.scale(layer.width / w, layer.height / h)
    img = ImageNode(view_rect=(layer.x, top, layer.width, layer.height), transform=m,
                    pixels=pix, smooth=True)
    return Group(transform=_FLIP, children=[img])


def _svg(font, layer, cache):
    memo = cache.table('color_svg')
    key = (font.face.path, font.face.index, layer.index)
    tree = memo.get(key)
    if tree is None:
        try:
            tree = load_svg_data(layer.data, cache)
        except (ImageError, RasterError) as e:
            cache.warn('color-svg', 'SVG glyph not drawn: %s' % e)
            tree = False
        memo[key] = tree
    if tree is False:
        return None
    if layer.element_id is None:
        # the document's own user space: not the viewport the parser gives a
        # document without a size
        node = dataclasses.replace(tree.root, transform=IDENTITY)
    else:
        node = tree.ids.get(layer.element_id)
    if node is None:
        return None
    return Group(transform=_FLIP, children=[node])
