"""raster.fonts.color: colour glyph descriptions of COLRv0, COLRv1, SVG,
sbix and CBDT fonts (synthetic fonts from tests/_colorfonts.py and the
suite's colour fonts)."""
import math
import os

import numpy as np
import pytest
from fontTools.ttLib.tables.otTables import PaintFormat

from raster.fonts import Font, FontDB
from raster.fonts.color import (BitmapGlyph, ClipLayer, CompositeLayer, FillLayer, SvgGlyph,
                                _linear_points, _paint_transform)

from _colorfonts import colr_font, glyph, gzip_bomb, raw_svg_font, solid, stops, svg_font
from _shared import SUITE_FONTS


def load(path):
    db = FontDB(files=[path])
    return Font.load(db.faces[0])


def gid(font, name):
    return font.tt.getGlyphID(name)


def desc(font, name):
    return font.color.glyph(gid(font, name))


def test_colrv0_layers_in_order_with_palette_colours(tmp_path):
    f = load(colr_font(tmp_path / 'v0.ttf', {'A': [('lo', 0), ('left', 1)]}))
    d = desc(f, 'A')
    assert [type(x) for x in d] == [FillLayer, FillLayer]
    assert d[0].path == f.outline(gid(f, 'lo')) and d[1].path == f.outline(gid(f, 'left'))
    assert d[0].brush.stops[0].color == (1, 0, 0, 1)
    assert d[1].brush.stops[0].color == (0, 0, 1, 1)
    assert f.color.mask.sum() == 1 and f.color.mask[gid(f, 'A')]


def test_plain_glyphs_have_no_description(tmp_path):
    f = load(colr_font(tmp_path / 'v0.ttf', {'A': [('lo', 0)]}))
    assert desc(f, 'B') is None and desc(f, 'sq') is None


def test_font_without_colour_tables_has_no_colour():
    f = load(os.path.join(SUITE_FONTS, 'NotoSans-Regular.ttf'))
    assert f.color is None


def test_translate_applies_to_the_glyph_outline(tmp_path):
    paint = {'Format': PaintFormat.PaintTranslate, 'dx': 100, 'dy': -50,
             'Paint': glyph('lo', solid(0))}
    f = load(colr_font(tmp_path / 't.ttf', {'A': paint}))
    (layer,) = desc(f, 'A')
    np.testing.assert_allclose(layer.path.points, f.outline(gid(f, 'lo')).points + [100, -50])


def test_transform_inside_a_glyph_moves_the_brush_only(tmp_path):
    inner = {'Format': PaintFormat.PaintScale, 'scaleX': 1.5, 'scaleY': 0.5,
             'Paint': {'Format': PaintFormat.PaintLinearGradient,
                       'ColorLine': stops((0, 0), (1, 1)),
                       'x0': 0, 'y0': 0, 'x1': 100, 'y1': 0, 'x2': 0, 'y2': 100}}
    f = load(colr_font(tmp_path / 't.ttf', {'A': glyph('sq', inner)}))
    (layer,) = desc(f, 'A')
    assert layer.path == f.outline(gid(f, 'sq'))
    b = layer.brush
    assert b.kind == 'linear' and b.geometry == (0, 0, 100, 0)
    assert tuple(b.transform) == (1.5, 0, 0, 0.5, 0, 0)


@pytest.mark.parametrize('fmt, fields, point, expect', [
    (PaintFormat.PaintRotate, {'angle': 90}, (1, 0), (0, 1)),            # counter-clockwise
    (PaintFormat.PaintRotateAroundCenter, {'angle': 180, 'centerX': 10, 'centerY': 0},
     (0, 0), (20, 0)),
    (PaintFormat.PaintScaleAroundCenter, {'scaleX': 1.5, 'scaleY': 0.5, 'centerX': 1,
                                          'centerY': 1}, (3, 3), (4, 2)),
    (PaintFormat.PaintScaleUniform, {'scale': 0.25}, (4, -8), (1, -2)),
    # FreeType's skew: x' = x - tan(xSkew) y, y' = tan(ySkew) x + y
    (PaintFormat.PaintSkew, {'xSkewAngle': 45, 'ySkewAngle': 0}, (0, 1), (-1, 1)),
    (PaintFormat.PaintSkew, {'xSkewAngle': 0, 'ySkewAngle': 45}, (1, 0), (1, 1)),
])
def test_paint_transforms(tmp_path, fmt, fields, point, expect):
    paint = dict(fields, Format=fmt, Paint=glyph('sq', solid(0)))
    f = load(colr_font(tmp_path / 't.ttf', {'A': paint}))
    t = _paint_transform(f.color._colr1[gid(f, 'A')])
    np.testing.assert_allclose(t.apply(np.array([point], float))[0], expect, atol=1e-9)


def test_linear_gradient_colour_line_is_perpendicular_to_the_rotation_line():
    """p0 = origin, p2 on the y axis: the gradient only varies along x, so
    p1 = (100, 100) is projected to (100, 0)."""
    assert _linear_points(0, 0, 100, 100, 0, 100) == (0, 0, 100, 0)
    # p2 on p0p1's normal: p1 unchanged
    assert _linear_points(0, 0, 100, 0, 0, 50) == (0, 0, 100, 0)
    # degenerate p2 = p0: p1 as given
    assert _linear_points(5, 5, 10, 20, 5, 5) == (5, 5, 10, 20)


def test_brush_without_glyph_fills_the_clip_box(tmp_path):
    paint = {'Format': PaintFormat.PaintColrLayers, 'Layers': [solid(2)]}
    f = load(colr_font(tmp_path / 't.ttf', {'A': paint}, clip_boxes={'A': (10, 20, 300, 400)}))
    (layer,) = desc(f, 'A')
    lo, hi = layer.path.points.min(0), layer.path.points.max(0)
    assert tuple(lo) == (10, 20) and tuple(hi) == (300, 400)
    assert layer.brush.stops[0].color == (0, 1, 0, 1)


def test_glyph_around_a_composite_is_a_clip(tmp_path):
    comp = {'Format': PaintFormat.PaintComposite, 'CompositeMode': 'SRC_IN',
            'SourcePaint': glyph('lo', solid(0)), 'BackdropPaint': glyph('left', solid(1))}
    f = load(colr_font(tmp_path / 't.ttf', {'A': glyph('sq', comp)}))
    (clip,) = desc(f, 'A')
    assert isinstance(clip, ClipLayer) and clip.path == f.outline(gid(f, 'sq'))
    (c,) = clip.layers
    assert isinstance(c, CompositeLayer) and c.mode == 'src_in'
    assert c.source[0].path == f.outline(gid(f, 'lo'))


def test_colr_glyph_reference_and_foreground(tmp_path):
    paints = {'B': glyph('lo', solid(0xFFFF, 0.5)),
              'A': {'Format': PaintFormat.PaintColrGlyph, 'Glyph': 'B'}}
    f = load(colr_font(tmp_path / 't.ttf', paints))
    (layer,) = desc(f, 'A')
    s = layer.brush.stops[0]
    assert s.color is None and s.alpha == 0.5       # the text's colour, half transparent


def test_colr_glyph_cycle_is_refused(tmp_path):
    paints = {'A': {'Format': PaintFormat.PaintColrGlyph, 'Glyph': 'B'},
              'B': {'Format': PaintFormat.PaintColrGlyph, 'Glyph': 'A'}}
    f = load(colr_font(tmp_path / 't.ttf', paints))
    assert desc(f, 'A') is None and desc(f, 'B') is None


def test_sweep_and_radial_brushes(tmp_path):
    sweep = {'Format': PaintFormat.PaintSweepGradient, 'ColorLine': stops((0, 0), (1, 1)),
             'centerX': 500, 'centerY': 500, 'startAngle': 0, 'endAngle': 90}
    radial = {'Format': PaintFormat.PaintRadialGradient, 'ColorLine': stops((0, 0), (1, 1)),
              'x0': 100, 'y0': 200, 'r0': 10, 'x1': 300, 'y1': 400, 'r1': 50}
    f = load(colr_font(tmp_path / 't.ttf', {'A': glyph('sq', sweep), 'B': glyph('sq', radial)}))
    (s,) = desc(f, 'A')
    (r,) = desc(f, 'B')
    assert s.brush.kind == 'sweep' and s.brush.geometry == (500, 500, 0, 90)
    assert r.brush.kind == 'radial' and r.brush.geometry == (100, 200, 10, 300, 400, 50)


def test_svg_documents_whole_and_by_glyph_id(tmp_path):
    one = '<svg xmlns="http://www.w3.org/2000/svg"><rect width="10" height="10"/></svg>'
    many = ('<svg xmlns="http://www.w3.org/2000/svg"><g id="glyph6"/><g id="glyph7"/></svg>')
    f = load(svg_font(tmp_path / 's.ttf', [(one, 'A', 'A'), (many, 'B', 'C')]))
    (a,) = desc(f, 'A')
    (b,) = desc(f, 'B')
    assert isinstance(a, SvgGlyph) and a.element_id is None and a.data == one.encode()
    assert b.element_id == 'glyph%d' % gid(f, 'B') and b.data == many.encode()


def test_compressed_svg_document_is_inflated(tmp_path):
    one = '<svg xmlns="http://www.w3.org/2000/svg"><rect width="10" height="10"/></svg>'
    f = load(svg_font(tmp_path / 's.ttf', [(one, 'A', 'A')], compress=True))
    (a,) = desc(f, 'A')
    assert a.data == one.encode()


def test_svg_gzip_bomb_is_not_inflated_beyond_the_bound(tmp_path, monkeypatch):
    from raster.fonts import color
    monkeypatch.setattr(color, 'MAX_SVG_BYTES', 10000)
    f = load(raw_svg_font(tmp_path / 'bomb.ttf', gzip_bomb(10 ** 6), 'A', 'A'))
    assert f.color.mask[gid(f, 'A')]
    assert desc(f, 'A') is None             # refused: the outline is drawn instead


def test_cbdt_bitmap_placement():
    """Noto Color Emoji's U+1F600 bitmap: 136 x 128 px at 109 ppem,
    BearingX 0, BearingY 101 (2048 units per em): its top edge is 101 px
    above the baseline."""
    f = load(os.path.join(SUITE_FONTS, 'NotoColorEmojiCBDT.subset.ttf'))
    (b,) = f.color.glyph(f.tt.getGlyphID('u1F600'))
    s = 2048 / 109
    assert isinstance(b, BitmapGlyph) and b.data[:4] == b'\x89PNG'
    assert b.x == 0 and b.width == pytest.approx(136 * s) and b.height == pytest.approx(128 * s)
    assert b.y + b.height == pytest.approx(101 * s)


def test_sbix_bitmap_placement_follows_the_outline_box():
    """CFF-and-SBIX's 'A': 512 ppem strike, origin offset 0, outline box
    from y = -174: the bitmap's lower-left corner is at (0, -174) (usvg's
    rule)."""
    f = load(os.path.join(SUITE_FONTS, 'CFF-and-SBIX.otf'))
    (b,) = f.color.glyph(f.tt.getGlyphID('A'))
    assert isinstance(b, BitmapGlyph)
    assert (b.x, b.y) == (0, -174)
    assert b.width == pytest.approx(b.height) and b.width > 0


def test_colrv1_suite_font_has_gradients():
    f = load(os.path.join(SUITE_FONTS, 'NotoColorEmojiCOLR.subset.ttf'))
    kinds = set()

    def visit(layers):
        for x in layers:
            if isinstance(x, FillLayer):
                kinds.add(x.brush.kind)
            elif isinstance(x, ClipLayer):
                visit(x.layers)
    for g in np.flatnonzero(f.color.mask).tolist():
        visit(f.color.glyph(g))
    assert {'solid', 'linear', 'radial'} <= kinds
    assert not math.isnan(f.color.clip_box(1)[0])
