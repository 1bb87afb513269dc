"""raster.parser.textlayout: bidi levels and visual runs, Unicode
properties, batched affines, and the layout rules on the suite's fonts."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.parser import textlayout as L


@given(st.lists(st.integers(0, 5), min_size=1, max_size=40))
@settings(max_examples=200, deadline=None)
def test_visual_runs_cover_every_character_once(levels):
    lv = np.array(levels)
    runs = L.visual_runs(lv)
    covered = sorted(i for a, b, _ in runs for i in range(a, b))
    assert covered == list(range(len(levels)))
    for a, b, rtl in runs:
        assert len(set(levels[a:b])) == 1 and rtl == bool(levels[a] % 2)


def test_visual_order_of_mixed_text_by_rule_l2():
    # L L R R EN(2) R L: the digits inside the RTL run keep their order
    runs = L.visual_runs(np.array([0, 0, 1, 1, 2, 1, 0]))
    order = [i for a, b, rtl in runs for i in (range(b - 1, a - 1, -1) if rtl else range(a, b))]
    assert order == [0, 1, 5, 4, 3, 2, 6]


def test_bidi_levels_of_hebrew_and_digits():
    lv = L.bidi_levels('ab \u05d0\u05d1 12 cd')
    assert lv.tolist() == [0, 0, 0, 1, 1, 1, 2, 2, 0, 0, 0]
    assert not L.bidi_levels('plain text').any()


def test_upright_and_joining_properties():
    assert L.is_upright([0x4E2D, 0xAC00, 0x3042, 0xFF21]).all()         # Han, Hangul, kana, fullwidth A
    assert not L.is_upright([ord('A'), ord('1'), 0x3001, 0x30FC]).any()   # Latin, 、 and ー turn
    assert L.joins_letters([0x0627, 0x0915]).all()
    assert not L.joins_letters([ord('a'), 0x05D0, 0x4E2D]).any()


@given(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.floats(-360, 360))
@settings(max_examples=100, deadline=None)
def test_affines_compose_like_point_maps(tx, ty, deg):
    p = np.array([3.0, -2.0, 1.0])
    m = L.compose(L.translate(tx, ty), L.rotate(deg), L.scale(2.0, 0.5))
    r = np.radians(deg)
    x, y = 6.0, -1.0
    want = [tx + np.cos(r) * x - np.sin(r) * y, ty + np.sin(r) * x + np.cos(r) * y, 1.0]
    np.testing.assert_allclose(m @ p, want, atol=1e-9)
    a = L.affines(m[None])[0]
    np.testing.assert_allclose([a[0] * 3 + a[2] * -2 + a[4], a[1] * 3 + a[3] * -2 + a[5]],
                               want[:2], atol=1e-9)
