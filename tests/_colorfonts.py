"""Small synthetic colour fonts for tests (built with fontTools).

Every font has units per em 1000, ascender 800, descender -200 and these
glyphs (advance 1000):

* ``sq``: the square [0, 1000] x [0, 1000] (y up);
* ``lo``: the lower half [0, 1000] x [0, 500];
* ``left``: the left half [0, 500] x [0, 1000];
* ``A`` (U+0041) .. ``Z``: base glyphs given colour by the caller (their
  own outline is the square);
* ``space``.

:func:`colr_font` writes a COLR/CPAL font: ``paints`` maps a base glyph
(``'A'`` ...) to a COLRv1 paint (fontTools' dict form) or a COLRv0 layer
list ``[(glyph, palette index), ...]``.  :func:`svg_font` writes one with
an SVG table.
"""

import gzip

from fontTools.colorLib.builder import buildCOLR, buildCPAL
from fontTools.fontBuilder import FontBuilder
from fontTools.pens.ttGlyphPen import TTGlyphPen
from fontTools.ttLib import newTable
from fontTools.ttLib.tables.otTables import PaintFormat

LETTERS = [chr(c) for c in range(ord('A'), ord('Z') + 1)]
GLYPHS = ['.notdef', 'space', 'sq', 'lo', 'left'] + LETTERS


def _rect(x0, y0, x1, y1):
    pen = TTGlyphPen(None)
    pen.moveTo((x0, y0))
    pen.lineTo((x0, y1))
    pen.lineTo((x1, y1))
    pen.lineTo((x1, y0))
    pen.closePath()
    return pen.glyph()


def _base(family):
    fb = FontBuilder(1000, isTTF=True)
    fb.setupGlyphOrder(GLYPHS)
    cmap = {ord(c): c for c in LETTERS}
    cmap[32] = 'space'
    fb.setupCharacterMap(cmap)
    glyphs = {g: _rect(0, 0, 1000, 1000) for g in GLYPHS}
    glyphs['.notdef'] = _rect(100, 0, 900, 800)
    glyphs['space'] = TTGlyphPen(None).glyph()
    glyphs['lo'] = _rect(0, 0, 1000, 500)
    glyphs['left'] = _rect(0, 0, 500, 1000)
    fb.setupGlyf(glyphs)
    fb.setupHorizontalMetrics({g: (1000, 0) for g in GLYPHS})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupNameTable({'familyName': family, 'styleName': 'Regular'})
    fb.setupOS2(sTypoAscender=800, sTypoDescender=-200, usWinAscent=800, usWinDescent=200)
    fb.setupPost()
    return fb


def colr_font(path, paints, palette=((1, 0, 0, 1), (0, 0, 1, 1), (0, 1, 0, 1)),
              family='Test Colour', clip_boxes=None):
    """Write a COLR font to ``path`` (see the module docstring);
    ``palette``: RGBA floats of palette 0."""
    fb = _base(family)
    font = fb.font
    font['COLR'] = buildCOLR(paints, glyphMap=font.getReverseGlyphMap(), clipBoxes=clip_boxes)
    font['CPAL'] = buildCPAL([list(palette)])
    fb.save(str(path))
    return str(path)


def svg_font(path, docs, family='Test SVG', compress=False):
    """Write a font with an SVG table: ``docs`` is a list of (SVG text,
    first glyph name, last glyph name)."""
    fb = _base(family)
    font = fb.font
    order = font.getGlyphOrder()
    table = newTable('SVG ')
    table.docList = []
    for text, first, last in docs:
        from fontTools.ttLib.tables.S_V_G_ import SVGDocument
        table.docList.append(SVGDocument(text, order.index(first), order.index(last), compress))
    font['SVG '] = table
    fb.save(str(path))
    return str(path)


class _Raw:
    """A table written as the given bytes."""
    def __init__(self, data):
        self.data = data

    def compile(self, font):
        return self.data

    def ensureDecompiled(self, recurse=False):
        pass


def raw_svg_font(path, doc, first, last, family='Test SVG'):
    """Write a font whose SVG table holds the bytes ``doc`` as they are (a
    gzip stream, say) for glyphs ``first`` .. ``last``."""
    import struct
    fb = _base(family)
    font = fb.font
    order = font.getGlyphOrder()
    index = struct.pack('>HHHII', 1, order.index(first), order.index(last), 14, len(doc))
    font['SVG '] = _Raw(struct.pack('>HII', 0, 10, 0) + index + doc)
    fb.save(str(path))
    return str(path)


def solid(index, alpha=1.0):
    return {'Format': PaintFormat.PaintSolid, 'PaletteIndex': index, 'Alpha': alpha}


def glyph(name, paint):
    return {'Format': PaintFormat.PaintGlyph, 'Glyph': name, 'Paint': paint}


def stops(*pairs, extend='pad'):
    """A colour line of (offset, palette index) pairs."""
    return {'Extend': extend, 'ColorStop': [{'StopOffset': o, 'PaletteIndex': i, 'Alpha': 1.0}
                                           for o, i in pairs]}


def gzip_bomb(size):
    """Gzip bytes inflating to ``size`` bytes of spaces after an SVG start."""
    return gzip.compress(b'<svg xmlns="http://www.w3.org/2000/svg">' + b' ' * size + b'</svg>')


#: The sequences of :func:`emoji_font`: (characters, ligature glyph).
SEQUENCES = (('\U0001F468\u200D\U0001F469', 'family'),        # ZWJ sequence
             ('\U0001F44B\U0001F3FD', 'wave_tone'),           # skin tone modifier
             ('\U0001F1EB\U0001F1F7', 'flag_fr'))             # regional indicators


def emoji_font(path, family='Test Emoji'):
    """Write a COLR emoji font: single characters of :data:`SEQUENCES` are
    blue squares, each sequence's ligature (GSUB ``ccmp``) a red square;
    advance 1000 for every glyph but the ZWJ and the skin tone modifier
    when they stay alone (0)."""
    from fontTools.feaLib.builder import addOpenTypeFeaturesFromString
    chars = sorted({c for seq, _ in SEQUENCES for c in seq})
    names = {c: 'u%04X' % ord(c) for c in chars}
    ligs = [name for _, name in SEQUENCES]
    order = ['.notdef'] + [names[c] for c in chars] + ligs
    fb = FontBuilder(1000, isTTF=True)
    fb.setupGlyphOrder(order)
    fb.setupCharacterMap({ord(c): names[c] for c in chars})
    fb.setupGlyf({g: _rect(0, 0, 1000, 1000) for g in order})
    zero = {names['\u200D'], names['\U0001F3FD']}
    fb.setupHorizontalMetrics({g: (0 if g in zero else 1000, 0) for g in order})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupNameTable({'familyName': family, 'styleName': 'Regular'})
    fb.setupOS2(sTypoAscender=800, sTypoDescender=-200, usWinAscent=800, usWinDescent=200)
    fb.setupPost()
    font = fb.font
    rules = ''.join('  sub %s by %s;\n' % (' '.join(names[c] for c in seq), name)
                    for seq, name in SEQUENCES)
    addOpenTypeFeaturesFromString(font, 'feature ccmp {\n%s} ccmp;\n' % rules)
    paints = {names[c]: [(names[c], 1)] for c in chars if c not in '\u200D\U0001F3FD'}
    paints.update({name: [(name, 0)] for name in ligs})
    font['COLR'] = buildCOLR(paints, glyphMap=font.getReverseGlyphMap())
    font['CPAL'] = buildCPAL([[(1, 0, 0, 1), (0, 0, 1, 1)]])
    fb.save(str(path))
    return str(path)
