"""Glyph outlines drawn by HarfBuzz (:meth:`raster.fonts.Font.outlines`)
against fontTools' glyph sets drawn into a PathBuilder, on the resvg
suite's fonts (TrueType quadratics, composites, a variable font at other
locations) and on CFF and CFF2 fonts made from the bundled Noto Sans
(cubics).

Where the two differ, they draw the same closed contours:

* HarfBuzz starts a TrueType contour whose first two points are off-curve
  at their midpoint, fontTools at the contour's first on-curve point;
* HarfBuzz moves every TrueType glyph so that its ``xMin`` (as ``glyf``
  stores it) is at the ``hmtx`` left side bearing, fontTools moves simple
  glyphs only: composite glyphs whose ``hmtx`` disagrees with ``glyf``
  differ by that amount;
* HarfBuzz draws no contour of a lone point (fontTools: a move and a
  close);
* HarfBuzz computes in single precision: variation deltas and component
  scales are within ``VAR_TOL`` font units of fontTools' doubles.
"""
import io
import os

import numpy as np
import pytest
from fontTools.fontBuilder import FontBuilder
from fontTools.pens.recordingPen import DecomposingRecordingPen
from fontTools.pens.t2CharStringPen import T2CharStringPen
from fontTools.ttLib import TTFont

from raster.fonts import BUNDLED_FONT, Font, FontFace
from raster.geometry.path import CLOSE, LINE, MOVE, QUAD, CUBIC
from raster.geometry.pens import PathBuilder

from _shared import SUITE_FONTS

#: Font units: single-precision arithmetic of HarfBuzz (component scales
#: at the default location, variation deltas elsewhere).
STATIC_TOL = 1e-3
VAR_TOL = 0.05
NPTS = {LINE: 1, QUAD: 2, CUBIC: 3}

#: Fonts whose contours all start where fontTools starts them: the
#: outlines are equal verb for verb.
SAME_START = ['NotoSans-Regular.ttf', 'NotoSans-Bold.ttf', 'NotoSans-Italic.ttf',
              'NotoSans-Black.ttf', 'NotoSerif-Regular.ttf', 'NotoZnamennyMusicalNotation-Regular.ttf',
              'NotoSansDevanagari-Regular.ttf', 'NotoSansMalayalam-Regular.ttf',
              'SourceSansPro-Regular.ttf', 'RobotoFlex.subset.ttf']
#: Fonts with contours that start elsewhere, and composites with an lsb
#: unlike their xMin.
OTHER = ['Amiri-Regular.ttf', 'MPLUS1p-Regular.ttf', 'SedgwickAveDisplay-Regular.ttf',
         'Yellowtail-Regular.ttf', 'TwitterColorEmoji.subset.ttf', 'CFF-and-SBIX.otf',
         'NotoColorEmojiCOLR.subset.ttf', 'NotoMono-Regular.ttf']


def _font(path):
    return Font(FontFace(path, 0, ('Test',)))


def _fonttools(tt, location=None):
    """draw(gid) -> (verbs, points) through fontTools' glyph set, composite
    glyphs moved by lsb - xMin as HarfBuzz moves them."""
    gs = tt.getGlyphSet(location=location)
    order = tt.getGlyphOrder()
    glyf = tt['glyf'] if 'glyf' in tt else None

    def draw(gid):
        rec = DecomposingRecordingPen(gs)
        gs[order[gid]].draw(rec)
        b = PathBuilder()
        rec.replay(b)
        p = b.path()
        shift = 0.0
        if glyf is not None and location is None:
            g = glyf[order[gid]]
            if g.isComposite():
                shift = tt['hmtx'][order[gid]][1] - g.xMin
        return p.verbs, p.points + [shift, 0.0]
    return draw


def _contours(verbs, points):
    """[(closed, segments)]: each segment (verb, (n, 2) points ending at its
    end point), a closed contour's closing line made explicit; contours
    of one point left out (HarfBuzz draws none)."""
    out = []
    i = 0
    for v in verbs.tolist():
        if v == MOVE:
            out.append([False, points[i], []])
            i += 1
        elif v == CLOSE:
            c = out[-1]
            c[0] = True
            last = c[2][-1][1][-1] if c[2] else c[1]
            if (last != c[1]).any():
                c[2].append((LINE, c[1][None]))
        else:
            out[-1][2].append((v, points[i:i + NPTS[v]]))
            i += NPTS[v]
    return [(closed, segs) for closed, _, segs in out if segs]


def _same_contours(a, b, tol):
    """The outlines ``a`` and ``b`` ((verbs, points) each) draw the same
    contours in the same order, closed ones possibly from another start."""
    ca, cb = _contours(*a), _contours(*b)
    if len(ca) != len(cb):
        return False
    for (closed, sa), (closed_b, sb) in zip(ca, cb):
        if closed != closed_b or len(sa) != len(sb):
            return False
        va = [v for v, _ in sa]
        pa = np.concatenate([p for _, p in sa]) if sa else np.zeros((0, 2))
        for k in (range(len(sb)) if closed else [0]):
            rot = sb[k:] + sb[:k]
            if [v for v, _ in rot] != va:
                continue
            if np.abs(np.concatenate([p for _, p in rot]) - pa).max(initial=0) <= tol:
                break
        else:
            return False
    return True


def _sample(n, count, seed):
    if n <= count:
        return range(n)
    return sorted(np.random.default_rng(seed).choice(n, count, replace=False).tolist())


@pytest.mark.parametrize('name', SAME_START)
def test_truetype_outlines_equal_fonttools(name):
    """Verb for verb, point for point (quadratics with implied on-curve
    points, composites); the closing line is the close's, as fontTools'."""
    path = os.path.join(SUITE_FONTS, name)
    font = _font(path)
    ref = _fonttools(TTFont(path, lazy=True))
    for gid in _sample(font.num_glyphs, 400, 1):
        verbs, points, _ = font.outlines([gid])
        rv, rp = ref(gid)
        assert verbs.tolist() == rv.tolist(), gid
        np.testing.assert_allclose(points, rp, rtol=0, atol=STATIC_TOL, err_msg=str(gid))


@pytest.mark.parametrize('name', OTHER)
def test_outlines_draw_fonttools_contours(name):
    path = os.path.join(SUITE_FONTS, name)
    font = _font(path)
    ref = _fonttools(TTFont(path, lazy=True))
    for gid in _sample(font.num_glyphs, 400, 2):
        verbs, points, _ = font.outlines([gid])
        assert _same_contours((verbs, points), ref(gid), STATIC_TOL), gid


@pytest.mark.parametrize('location', [{'wght': 900}, {'wght': 150, 'wdth': 40},
                                      {'opsz': 100, 'GRAD': -100, 'slnt': -10}])
def test_variable_outlines_equal_fonttools(location):
    path = os.path.join(SUITE_FONTS, 'RobotoFlex.subset.ttf')
    font = _font(path).variant(location)
    assert font.location == location
    ref = _fonttools(TTFont(path, lazy=True), location)
    moved = 0
    for gid in range(font.num_glyphs):
        verbs, points, _ = font.outlines([gid])
        rv, rp = ref(gid)
        assert _same_contours((verbs, points), (rv, rp), VAR_TOL), gid
        moved += len(points) and not np.array_equal(points, font._base.outlines([gid])[1])
    assert moved > font.num_glyphs // 2         # the location changes the outlines


def _cff_font(path, cff2=False):
    """The bundled Noto Sans with its quadratics made cubic, as a CFF (or
    CFF2) font written to ``path``; returns the fontTools source font."""
    src = TTFont(BUNDLED_FONT)
    order = src.getGlyphOrder()
    gs = src.getGlyphSet()
    charstrings = {}
    for name in order:
        pen = T2CharStringPen(None if cff2 else gs[name].width, gs, CFF2=cff2)
        gs[name].draw(pen)
        charstrings[name] = pen.getCharString()
    fb = FontBuilder(src['head'].unitsPerEm, isTTF=False)
    fb.setupGlyphOrder(order)
    fb.setupCharacterMap(src.getBestCmap())
    if cff2:
        fb.setupCFF2(charstrings)
    else:
        fb.setupCFF('TestCFF', {'FullName': 'Test CFF'}, charstrings, {})
    fb.setupHorizontalMetrics({n: src['hmtx'][n] for n in order})
    fb.setupHorizontalHeader(ascent=src['hhea'].ascent, descent=src['hhea'].descent)
    fb.setupNameTable({'familyName': 'Test CFF', 'styleName': 'Regular'})
    fb.setupOS2(sTypoAscender=src['OS/2'].sTypoAscender, sxHeight=src['OS/2'].sxHeight,
                sCapHeight=src['OS/2'].sCapHeight)
    fb.setupPost()
    fb.save(str(path))
    return src


@pytest.mark.parametrize('cff2', [False, True])
def test_cff_outlines_equal_fonttools(tmp_path, cff2):
    """Cubics: every glyph verb for verb and point for point; the font's
    metrics and character map are the source font's."""
    path = tmp_path / 'cff.otf'
    src = _cff_font(path, cff2)
    tt = TTFont(str(path), lazy=True)
    assert ('CFF2' if cff2 else 'CFF ') in tt and 'glyf' not in tt
    font = _font(str(path))
    ref = _fonttools(tt)
    cubics = 0
    for gid in range(font.num_glyphs):
        verbs, points, _ = font.outlines([gid])
        rv, rp = ref(gid)
        assert verbs.tolist() == rv.tolist(), gid
        np.testing.assert_array_equal(points, rp)
        cubics += int((verbs == CUBIC).sum())
    assert cubics > 100
    plain = _font(BUNDLED_FONT)
    assert font.num_glyphs == plain.num_glyphs == len(src.getGlyphOrder())
    assert (font.cap_height, font.x_height, font.ascender) == \
        (plain.cap_height, plain.x_height, plain.ascender)
    assert [font.has_char(c) for c in 'Az~\u00e9'] == [plain.has_char(c) for c in 'Az~\u00e9']
