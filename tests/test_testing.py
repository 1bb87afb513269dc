"""raster.testing against the project's conformance scorer (score.py).

score.py is loaded by path from ../shared/conformance (always present in CI);
its functions are the oracle, ours must agree exactly on every image pair.
"""

import importlib.util
import os

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.testing import (CRITERION, Comparison, ComparisonError, compare_images,
                            diff_strip, premultiply8, range_diff)

SCORE_PY = os.path.join(os.path.dirname(__file__), '..', '..', 'shared', 'conformance', 'score.py')


def _load_score():
    spec = importlib.util.spec_from_file_location('_conformance_score', SCORE_PY)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


score = _load_score()


def oracle(ref, act):
    """score.py's verdict: (status, bad_pct, fine_bad_pct, max_diff)."""
    rec = {'ref_size': [ref.shape[1], ref.shape[0]], 'out_size': [act.shape[1], act.shape[0]]}
    if ref.shape != act.shape:
        rec['size_mismatch'] = True
        score.judge(rec, score.DEFAULT_CRITERION)
        return rec['status'], None, None, None
    m = score.compare(ref, act)
    m.pop('_maps')
    rec.update(m)
    score.judge(rec, score.DEFAULT_CRITERION)
    return rec['status'], rec['bad_pct'], rec['fine_bad_pct'], rec['max_diff']


def check_agrees(ref, act):
    ours = compare_images(ref, act)
    st_, bad, fine, mx = oracle(ref, act)
    assert ours.passed == (st_ == 'pass')
    if bad is not None:
        assert ours.bad_pct == bad
        assert ours.fine_bad_pct == fine
        assert ours.max_diff == mx
    return ours


def test_criterion_constants_match_scorer():
    assert CRITERION == score.DEFAULT_CRITERION


# -- building blocks ----------------------------------------------------------

def test_premultiply_matches_scorer_on_all_values():
    c, a = np.meshgrid(np.arange(256), np.arange(256), indexing='ij')
    img = np.stack([c, 255 - c, c // 2, a], -1).astype(np.uint8)
    assert np.array_equal(premultiply8(img).astype(np.int32), score.premultiply(img))


@pytest.mark.parametrize('r', [1, 2, 3])
def test_range_diff_matches_scorer(r):
    rng = np.random.default_rng(10 + r)
    for shape in [(1, 1), (1, 7), (6, 1), (9, 13), (30, 17)]:
        p = rng.integers(0, 256, shape + (4,), dtype=np.uint8)
        q = rng.integers(0, 256, shape + (4,), dtype=np.uint8)
        assert np.array_equal(range_diff(p, q, r), score.range_diff(p, q, r))


def test_range_diff_symmetric():
    rng = np.random.default_rng(3)
    p = rng.integers(0, 256, (12, 12, 4), dtype=np.uint8)
    q = rng.integers(0, 256, (12, 12, 4), dtype=np.uint8)
    assert np.array_equal(range_diff(p, q, 2), range_diff(q, p, 2))


# -- structured pairs ------------------------------------------------------------

def square(h=60, w=80, x0=20, y0=15, size=25, color=(0, 128, 255, 255)):
    img = np.zeros((h, w, 4), np.uint8)
    img[y0:y0 + size, x0:x0 + size] = color
    return img


def test_identical_images_pass():
    img = square()
    r = check_agrees(img, img.copy())
    assert r.passed and r.max_diff == 0 and r.reason is None


@pytest.mark.parametrize('dx,dy', [(1, 0), (0, 1), (-1, 1), (1, -1)])
def test_shifted_edges_pass(dx, dy):
    """A square moved by 1 px costs nothing beyond either window."""
    a = square()
    b = np.roll(np.roll(a, dy, 0), dx, 1)
    r = check_agrees(a, b)
    assert r.passed
    assert r.maps[1].max() == 0 and r.maps[2].max() == 0


@pytest.mark.parametrize('dx,dy', [(2, 0), (0, -2), (2, 2)])
def test_two_pixel_shift_clean_for_coarse_window(dx, dy):
    a = square()
    b = np.roll(np.roll(a, dy, 0), dx, 1)
    r = check_agrees(a, b)
    assert r.maps[2].max() == 0 and r.maps[1].max() == 255


def test_shift_by_two_fails_fine_check_on_large_edges():
    """A 2-px shift is invisible to the 5x5 window but not to the 3x3 one."""
    a = np.zeros((100, 100, 4), np.uint8)
    for k in range(0, 100, 6):
        a[:, k:k + 3] = 255                          # many vertical stripes
    b = np.roll(a, 2, 1)
    r = check_agrees(a, b)
    assert not r.passed and r.bad_pct == 0.0 and r.fine_bad_pct > CRITERION['F2']


def test_recoloured_block_fails():
    a = square()
    b = square(color=(255, 0, 0, 255))
    r = check_agrees(a, b)
    assert not r.passed and r.max_diff == 255 and 'beyond 2px' in r.reason


def test_missing_content_fails():
    a = square()
    r = check_agrees(a, np.zeros_like(a))
    assert not r.passed


def test_transparent_pixels_compare_premultiplied():
    """Different colours under alpha 0 are the same premultiplied pixel."""
    a = np.zeros((10, 10, 4), np.uint8)
    b = a.copy()
    b[..., :3] = 200
    r = check_agrees(a, b)
    assert r.passed and r.max_diff == 0


@pytest.mark.parametrize('n_bad', [0, 1, 2, 3, 4, 5, 8])
def test_coarse_threshold_boundary(n_bad):
    """100x100 image: 0.05 % is exactly 5 pixels -- 5 may fail, 6 may not."""
    a = np.full((100, 100, 4), 255, np.uint8)
    b = a.copy()
    # isolated single-pixel defects far apart, each costing 25 (> T = 24)
    for k in range(n_bad):
        b[10 + 10 * (k % 8), 10 + 10 * (k // 8), :3] = 255 - 25
    r = check_agrees(a, b)
    assert r.passed == (n_bad <= 5)


@pytest.mark.parametrize('cost', [23, 24, 25, 32, 33])
def test_threshold_values(cost):
    """A flat block of cost exactly T is tolerated, T + 1 is not."""
    a = np.full((40, 40, 4), 255, np.uint8)
    b = a.copy()
    b[10:30, 10:30, 0] = 255 - cost
    r = check_agrees(a, b)
    assert r.passed == (cost <= 24)


@pytest.mark.parametrize('rows,pct,expect', [(70, 1.39, True), (75, 1.49, True),
                                             (76, 1.51, False), (100, 2.0, False)])
def test_fine_threshold_boundary(rows, pct, expect):
    """An edge moved by 2 px fails the 3x3 window on two columns (one per
    direction, less the corner): 2 * rows - 1 pixels of 10000, allowed up to F2 = 1.5 %."""
    a = np.zeros((100, 100, 4), np.uint8)
    a[:rows, 30:] = 255
    b = np.zeros_like(a)
    b[:rows, 28:] = 255
    r = check_agrees(a, b)
    assert r.bad_pct == 0.0
    assert r.fine_bad_pct == pct      # the last row's corner costs only once
    assert r.passed == expect


def test_size_mismatch_fails():
    a = np.zeros((10, 12, 4), np.uint8)
    b = np.zeros((12, 10, 4), np.uint8)
    r = check_agrees(a, b)
    assert not r.passed and r.maps is None and r.reason == 'size 10x12 != expected 12x10'


def test_bad_input_raises_documented_error():
    with pytest.raises(ComparisonError):
        compare_images(np.zeros((4, 4, 3), np.uint8), np.zeros((4, 4, 3), np.uint8))
    with pytest.raises(ComparisonError):
        compare_images(np.zeros((4, 4, 4), np.float32), np.zeros((4, 4, 4), np.uint8))


def test_accepts_pil_images():
    from PIL import Image
    a = square()
    r = compare_images(Image.fromarray(a), Image.fromarray(a))
    assert r.passed


# -- random pairs (hypothesis) ---------------------------------------------------

@settings(max_examples=120, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), h=st.integers(1, 24), w=st.integers(1, 24),
       mode=st.sampled_from(['noise', 'sparse', 'blocks', 'alpha']))
def test_random_pairs_agree_with_scorer(seed, h, w, mode):
    rng = np.random.default_rng(seed)
    a = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
    if mode == 'noise':
        b = np.clip(a.astype(int) + rng.integers(-40, 41, a.shape), 0, 255).astype(np.uint8)
    elif mode == 'sparse':
        b = a.copy()
        m = rng.random((h, w)) < 0.05
        b[m] = rng.integers(0, 256, (int(m.sum()), 4), dtype=np.uint8)
    elif mode == 'blocks':
        a = np.repeat(np.repeat(rng.integers(0, 256, (4, 4, 4), dtype=np.uint8), 8, 0), 8, 1)[:h, :w]
        b = np.roll(a, int(rng.integers(-2, 3)), int(rng.integers(0, 2)))
    else:
        b = a.copy()
        b[..., 3] = rng.integers(0, 256, (h, w), dtype=np.uint8)
    check_agrees(a, b)


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), k=st.integers(0, 40), cost=st.integers(20, 40))
def test_near_threshold_pairs_agree_with_scorer(seed, k, cost):
    """White 60x60 images with k single-pixel defects of cost near T/T2."""
    rng = np.random.default_rng(seed)
    a = np.full((60, 60, 4), 255, np.uint8)
    b = a.copy()
    ys = rng.integers(0, 60, k)
    xs = rng.integers(0, 60, k)
    b[ys, xs, rng.integers(0, 3)] = 255 - cost
    check_agrees(a, b)


# -- diff strip --------------------------------------------------------------------

def test_diff_strip_layout_and_colours():
    a = square()
    b = square(color=(255, 0, 0, 255))
    r = compare_images(a, b)
    s = diff_strip(a, b, r)
    h, w = a.shape[:2]
    assert s.shape == (h, 3 * w + 8, 3) and s.dtype == np.uint8
    assert tuple(s[0, 0]) == (255, 255, 255)                 # transparent over white
    assert tuple(s[20, 25]) == (0, 128, 255)                 # expected panel
    assert tuple(s[20, 2 * (w + 4) + 25]) == (255, 0, 0)     # actual panel
    assert tuple(s[20, w + 4 + 25]) == (230, 0, 0)           # diff panel: coarse failure
    assert tuple(s[0, w + 1]) == (96, 96, 96)                # gap


def test_diff_strip_size_mismatch_and_missing_actual():
    a = square()
    b = np.zeros((10, 10, 4), np.uint8)
    s = diff_strip(a, b, compare_images(a, b))
    assert s.shape == (60, 3 * 80 + 8, 3)
    s2 = diff_strip(a, None, None)
    assert s2.shape == (60, 248, 3)
    assert tuple(s2[30, 100]) == (230, 0, 0)
