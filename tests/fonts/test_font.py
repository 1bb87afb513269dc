"""Tests of raster.fonts on the resvg suite's fonts: CSS matching, shaping,
outlines and their caches."""
import os
import shutil
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.fonts import DEFAULT_FAMILY, Font, FontDB, FontError, parse_font_family
from raster.errors import RasterError, RasterWarning

from _shared import SUITE_FONTS as FONTS

#: The generic mapping of resvg's test harness; the suite's fonts hold
#: these families, and the built-in preference lists find them too.
GENERIC_FAMILIES = {'serif': 'Noto Serif', 'sans-serif': 'Noto Sans', 'cursive': 'Yellowtail',
                    'fantasy': 'Sedgwick Ave Display', 'monospace': 'Noto Mono'}


@pytest.fixture(scope='module')
def db():
    return FontDB([FONTS])


def test_parse_font_family_quotes_and_spaces():
    assert parse_font_family('"Noto  Sans" , Times   New Roman,serif') == \
        ['Noto  Sans', 'Times New Roman', 'serif']
    assert parse_font_family("'a, b', c") == ['a, b', 'c']
    assert parse_font_family('') == []
    assert parse_font_family(' , ,') == []


@given(st.lists(st.text(alphabet='abcXYZ -', min_size=1, max_size=8), min_size=1, max_size=4))
@settings(max_examples=100, deadline=None)
def test_parse_font_family_roundtrip_quoted(names):
    names = [' '.join(n.split()) for n in names]
    names = [n for n in names if n]
    value = ', '.join('"%s"' % n for n in names)
    assert parse_font_family(value) == names


def test_empty_and_missing_dirs_give_the_bundled_font(tmp_path):
    from raster.fonts import BUNDLED_FONT
    for db in (FontDB([]), FontDB([str(tmp_path / 'nope')]), FontDB([str(tmp_path)])):
        assert db.bundled_only
        assert [f.path for f in db.faces] == [BUNDLED_FONT]
        assert db.match(['serif']).path == BUNDLED_FONT


def test_corrupt_font_file_warns_and_is_skipped(tmp_path):
    (tmp_path / 'bad.ttf').write_bytes(b'not a font at all')
    with pytest.warns(RasterWarning, match='bad.ttf'):
        db = FontDB([str(tmp_path)])
    assert db.bundled_only


def test_generic_families_map_as_resvg_harness(db):
    for generic, fam in GENERIC_FAMILIES.items():
        face = db.match([generic])
        assert face is not None and fam in face.families, generic


def test_default_family_falls_back_to_serif(db):
    assert DEFAULT_FAMILY == 'Times New Roman'
    face = db.match(['No Such Family'])
    assert 'Noto Serif' in face.families
    assert 'Noto Serif' in db.match([]).families


def test_first_available_family_wins(db):
    assert 'Noto Sans' in db.match(['Nope', 'Noto Sans', 'Noto Serif']).families
    assert 'Noto Sans' in db.match(['noto sans']).families     # case-insensitive


@pytest.mark.parametrize('weight, expect', [
    (100, 100), (200, 100), (300, 300), (400, 400), (500, 400),    # 500 -> 400 next
    (600, 700), (700, 700), (800, 900), (900, 900), (350, 300),
])
def test_css_weight_matching(db, weight, expect):
    face = db.match(['Noto Sans'], weight=weight)
    assert face.weight == expect


def test_style_matching(db):
    assert db.match(['Noto Sans'], style='italic').style == 'italic'
    assert db.match(['Noto Sans'], style='oblique').style == 'italic'   # oblique -> italic
    assert db.match(['Noto Sans'], style='normal').style == 'normal'
    # a family without italics still matches
    assert 'Noto Serif' in db.match(['Noto Serif'], style='italic').families


def test_scan_is_cached(db):
    again = FontDB([FONTS])
    assert again.faces == db.faces


def test_shaping_advances_match_hmtx(db):
    """HarfBuzz advances of 'Hello World' in Noto Sans equal the hmtx
    advances (no kerning pairs between these letters change them... so
    compare the kerned sum with the GPOS-free sum within the kern total)."""
    from fontTools.ttLib import TTFont
    face = db.match(['Noto Sans'])
    font = Font.load(face)
    text = 'Hilmn'          # no kerning pairs among these letters
    shaped = font.shape(text)
    tt = TTFont(face.path)
    cmap = tt.getBestCmap()
    expect = [tt['hmtx'][cmap[ord(c)]][0] for c in text]
    assert [g[2] for g in shaped] == expect
    assert [g[1] for g in shaped] == list(range(len(text)))
    assert font.upem == 1000


def test_cff_outlines(db):
    face = [f for f in db.faces if f.path.endswith('.otf')][0]
    font = Font.load(face)
    assert 'CFF ' in font.tt
    gid = font.shape('A')[0][0]
    assert gid != 0
    p = font.outline(gid)
    assert len(p.verbs) > 4 and p.verbs[0] == 0


def test_outline_of_H_box(db):
    """The glyph 'H' of Noto Sans lies within its advance and above the
    baseline up to the cap height (font units, y up)."""
    font = Font.load(db.match(['Noto Sans']))
    gid, _, adv, _, _, _ = font.shape('H')[0]
    pts = font.outline(gid).points
    assert pts[:, 0].min() >= 0 and pts[:, 0].max() <= adv
    assert pts[:, 1].min() == 0
    assert abs(pts[:, 1].max() - font.cap_height) < 1


def test_load_missing_file_raises_font_error():
    from raster.fonts import FontFace
    with pytest.raises(FontError):
        Font.load(FontFace('/nonexistent/x.ttf', 0, ('X',)))
    assert issubclass(FontError, RasterError)


def test_variable_font_variant(db):
    """Roboto Flex is variable: heavier weights widen 'H'; values are
    clamped to the axis range; a static font and the default location
    give the font itself."""
    font = Font.load(db.match(['Roboto Flex']))
    lo, dflt, hi = font.axes['wght']
    assert (lo, dflt, hi) == (100.0, 400.0, 1000.0)
    assert font.variant({'wght': dflt}) is font
    assert font.variant({'nope': 3}) is font
    bold = font.variant({'wght': 900})
    assert bold is font.variant({'wght': 900.0})          # cached
    assert font.variant({'wght': 5000}) is font.variant({'wght': 1000})
    gid = font.shape('H')[0][0]
    assert bold.shape('H')[0][2] > font.shape('H')[0][2]
    w_reg = np.ptp(font.outline(gid).points[:, 0])
    w_bold = np.ptp(bold.outline(gid).points[:, 0])
    assert w_bold > w_reg
    static = Font.load(db.match(['Noto Sans']))
    assert static.axes == {} and static.variant({'wght': 700}) is static


# -- caches: shaping, packed outlines, matching ---------------------------------

def test_shape_arrays_match_shape_and_are_cached(db):
    font = Font.load(db.match(['Noto Sans']))
    r = font.shape_arrays('Wave office')
    assert font.shape_arrays('Wave office') is r                   # cached
    assert font.shape_arrays('Wave office', {'kern': False}) is not r
    rows = list(zip(r.gid.tolist(), r.cluster.tolist(), *r.pos.astype(int).T.tolist()))
    assert rows == font.shape('Wave office')
    assert not r.gid.flags.writeable and not r.pos.flags.writeable
    assert r.ordered == (len(r.gid) == len('Wave office'))
    # kerning off changes the advance of 'Wa' (a kerned pair in Noto Sans)
    assert r.pos[0, 0] != font.shape_arrays('Wave office', {'kern': False}).pos[0, 0]


def test_shape_cache_is_bounded(db, monkeypatch):
    import raster.fonts as F
    monkeypatch.setattr(F.font, '_SHAPE_LIMIT', 8)
    font = Font.load(db.match(['Noto Serif']))
    font._shaped.clear()
    words = ['w%d' % i for i in range(50)]
    for w in words:
        font.shape_arrays(w)
        assert len(font._shaped) <= 9
    for w in words[::7]:    # evicted entries come back equal
        a, b = font.shape_arrays(w), font._shape(w, None)
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x, y)


def _outline_by_pen(font, gid):
    """One glyph drawn on its own (by HarfBuzz), not through the packed
    outline arrays: (verbs, points)."""
    return font._draw_glyph(gid)


@pytest.mark.parametrize('family', ['Noto Sans', 'Noto Serif', 'CFF Outlines and SBIX', 'Amiri'])
def test_outlines_gather_equals_per_glyph_outlines(db, family):
    font = Font.load(db.match([family]))
    rng = np.random.default_rng(5)
    n = font.num_glyphs
    for size in (1, 3, 40):         # short runs are cached, long ones are not
        gids = rng.integers(0, n, size)
        verbs, points, npts = font.outlines(gids)
        ref = [_outline_by_pen(font, int(g)) for g in gids]
        assert npts.tolist() == [len(p) for _, p in ref]
        np.testing.assert_array_equal(verbs, np.concatenate([v for v, _ in ref]))
        np.testing.assert_array_equal(points, np.concatenate([p for _, p in ref]).reshape(-1, 2))
        again = font.outlines(gids)
        np.testing.assert_array_equal(again[1], points)
    # a glyph id the font does not have: an empty outline
    verbs, points, npts = font.outlines([n + 5, -1])
    assert len(verbs) == 0 and npts.tolist() == [0, 0]
    assert len(font.outline(n + 5).verbs) == 0


def test_outline_atlas_and_run_cache_are_bounded(db, monkeypatch):
    import raster.fonts as F
    monkeypatch.setattr(F.font, '_ATLAS_MAX_POINTS', 500)
    monkeypatch.setattr(F.font, '_RUN_LIMIT', 4)
    font = Font(db.match(['Noto Sans']))        # a fresh font: empty caches
    rng = np.random.default_rng(11)
    atlas = font._atlas
    for _ in range(60):
        gids = rng.integers(0, font.num_glyphs, 3)
        verbs, points, npts = font.outlines(gids)
        ref = [_outline_by_pen(font, int(g)) for g in gids]
        np.testing.assert_array_equal(points, np.concatenate([p for _, p in ref]).reshape(-1, 2))
        assert len(atlas.runs) <= 4
        # the atlas starts over beyond the bound: at most one gather more
        assert atlas.np <= 500 + sum(len(p) for _, p in ref)


def test_match_cache_is_bounded_and_agrees(db, monkeypatch):
    import raster.fonts as F
    monkeypatch.setattr(F.matching, '_MATCH_LIMIT', 5)
    fresh = FontDB([FONTS])
    for w in range(100, 1000, 50):
        for style in ('normal', 'italic'):
            face = fresh.match(['Noto Sans'], w, style)
            assert face == fresh._match(('Noto Sans',), w, style, 5)
            assert fresh.match(['Noto Sans'], w, style) == face
            assert len(fresh._matches) <= 6


# -- loading: mapped files, collections, bad files --------------------------------

def test_font_file_is_mapped_not_copied():
    """HarfBuzz maps the file: its blob is the file's bytes, and a
    second Font of the same file shares the page cache's pages (the blob
    of a memory font is a copy of the registered bytes)."""
    from raster.fonts import FontFace
    from raster.fonts.font import _font_blob
    path = os.path.join(FONTS, 'NotoSans-Regular.ttf')
    blob = _font_blob(path)
    with open(path, 'rb') as fh:
        assert blob.data == fh.read()
    maps = open('/proc/self/maps').read() if os.path.exists('/proc/self/maps') else None
    if maps is not None:
        assert path in maps
    font = Font(FontFace(path, 0, ('Noto Sans',)))
    assert font.shape('Hi') == Font.load(FontFace(path, 0, ('Noto Sans',))).shape('Hi')


def test_collection_faces_load_by_index(tmp_path):
    from fontTools.ttLib import TTCollection, TTFont
    from raster.fonts import FontFace
    names = ['NotoSans-Regular.ttf', 'NotoSerif-Regular.ttf']
    ttc = TTCollection()
    ttc.fonts = [TTFont(os.path.join(FONTS, n)) for n in names]
    ttc.save(str(tmp_path / 'two.ttc'))
    for index, name in enumerate(names):
        alone = Font(FontFace(os.path.join(FONTS, name), 0, ('x',)))
        inside = Font(FontFace(str(tmp_path / 'two.ttc'), index, ('x',)))
        assert inside.shape('Wave') == alone.shape('Wave')
        assert (inside.num_glyphs, inside.ascender, inside.x_height) == \
            (alone.num_glyphs, alone.ascender, alone.x_height)
        gid = alone.shape('g')[0][0]
        np.testing.assert_array_equal(inside.outline(gid).points, alone.outline(gid).points)
    with pytest.raises(FontError, match='no face 5'):
        Font(FontFace(str(tmp_path / 'two.ttc'), 5, ('x',)))


@pytest.mark.parametrize('data, message', [
    (b'', 'too short'),
    (b'not a font at all', 'not a font'),
    (b'\x00\x01\x00\x00\x00\x05' + bytes(20), 'table directory'),
])
def test_bad_font_files_raise_font_error(tmp_path, data, message):
    from raster.fonts import FontFace
    (tmp_path / 'bad.ttf').write_bytes(data)
    with pytest.raises(FontError, match=message):
        Font(FontFace(str(tmp_path / 'bad.ttf'), 0, ('x',)))


@pytest.mark.parametrize('tag, message', [(b'head', "no 'head' table"), (b'maxp', 'no glyphs')])
def test_font_without_head_or_maxp_raises_font_error(tmp_path, tag, message):
    """The table renamed in the directory (the file stays a valid sfnt)."""
    import struct
    from raster.fonts import BUNDLED_FONT, FontFace
    with open(BUNDLED_FONT, 'rb') as fh:
        data = bytearray(fh.read())
    (num,) = struct.unpack_from('>H', data, 4)
    tags = [bytes(data[12 + 16 * k:16 + 16 * k]) for k in range(num)]
    k = tags.index(tag)
    data[12 + 16 * k:16 + 16 * k] = b'zz' + tag[2:]
    path = tmp_path / 'renamed.ttf'
    path.write_bytes(bytes(data))
    with pytest.raises(FontError, match=message):
        Font(FontFace(str(path), 0, ('x',)))
