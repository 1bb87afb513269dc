"""Canvas.fill_many composites a sequence of solid fills with the pixels
of filling them one by one (bit for bit)."""

import numpy as np
import pytest

from raster.errors import CanvasError
from raster.pixels import canvas as canvas_mod
from raster.pixels.canvas import Canvas
from raster.pixels.scan import Mask


def random_fills(seed, w, h, n=300, big=False):
    """Overlapping masks (some partly or wholly off the canvas) with
    zero, full and partial coverage, opaque and translucent paints."""
    rng = np.random.default_rng(seed)
    fills = []
    for _ in range(n):
        mh = int(rng.integers(1, 100 if big else 30))
        mw = int(rng.integers(1, 100 if big else 30))
        k = rng.random((mh, mw)).astype(np.float32)
        k[k < 0.3] = 0.0
        k[k > 0.6] = 1.0
        x0, y0 = int(rng.integers(-20, w + 5)), int(rng.integers(-20, h + 5))
        color = tuple(rng.random(3 if rng.random() < 0.7 else 4).tolist())
        opacity = 1.0 if rng.random() < 0.6 else float(rng.random())
        fills.append((Mask(k, x0, y0), color, opacity))
    return fills


def one_by_one(c, fills):
    for f in fills:
        c.fill(*f)


@pytest.mark.parametrize('dtype', [np.float32, np.uint8])
@pytest.mark.parametrize('seed', range(4))
@pytest.mark.parametrize('big', [False, True])
def test_equals_one_by_one(dtype, seed, big):
    fills = random_fills(seed, 120, 90, big=big)
    a = Canvas(120, 90, (0.2, 0.5, 0.7, 0.6), dtype=dtype)
    b = Canvas(120, 90, (0.2, 0.5, 0.7, 0.6), dtype=dtype)
    a.fill_many(fills)
    one_by_one(b, fills)
    assert np.array_equal(a.data, b.data)


@pytest.mark.parametrize('dtype', [np.float32, np.uint8])
def test_deep_overlaps_keep_their_order(dtype):
    # the same pixels covered by many translucent masks of different
    # colours: the result depends on the order at every pixel
    rng = np.random.default_rng(7)
    fills = [(Mask(np.full((5, 6), 0.5, np.float32), 3 + i % 2, 2), tuple(rng.random(3)), 0.7)
             for i in range(300)]
    a, b = Canvas(12, 10, dtype=dtype), Canvas(12, 10, dtype=dtype)
    a.fill_many(fills)
    one_by_one(b, fills)
    assert np.array_equal(a.data, b.data)
    c = Canvas(12, 10, dtype=dtype)
    c.fill_many(fills[::-1])
    assert not np.array_equal(a.data, c.data)


@pytest.mark.parametrize('dtype', [np.float32, np.uint8])
def test_groups_and_large_masks_keep_their_order(dtype, monkeypatch):
    # small groups, large masks (filled one by one, the opaque copy of
    # fill's dense path included) between batched ones
    monkeypatch.setattr(canvas_mod, 'MANY_GROUP_PIXELS', 2000)
    monkeypatch.setattr(canvas_mod, 'MANY_MASK_PIXELS', 1500)
    fills = random_fills(11, 150, 120, n=200, big=True)
    a = Canvas(150, 120, (1, 1, 1), dtype=dtype)
    b = Canvas(150, 120, (1, 1, 1), dtype=dtype)
    a.fill_many(fills)
    one_by_one(b, fills)
    assert np.array_equal(a.data, b.data)


@pytest.mark.parametrize('dtype', [np.float32, np.uint8])
def test_dense_opaque_masks_in_a_group(dtype, monkeypatch):
    # masks above fill's small size, opaque and dense, batched: fill copies
    # the colour where they cover fully, the batch must too
    monkeypatch.setattr(canvas_mod, 'MANY_MASK_PIXELS', 1 << 16)
    rng = np.random.default_rng(3)
    fills = []
    for i in range(20):
        k = np.ones((70, 80), np.float32)
        k[:, :3] = rng.random((70, 3)).astype(np.float32)
        fills.append((Mask(k, int(rng.integers(0, 60)), int(rng.integers(0, 40))),
                      tuple(rng.random(3)), 1.0))
    a = Canvas(140, 110, (0.3, 0.3, 0.3, 0.5), dtype=dtype)
    b = Canvas(140, 110, (0.3, 0.3, 0.3, 0.5), dtype=dtype)
    a.fill_many(fills)
    one_by_one(b, fills)
    assert np.array_equal(a.data, b.data)


def test_nothing_and_none():
    c = Canvas(4, 4, (0, 0, 1))
    before = c.data.copy()
    c.fill_many([])
    c.fill_many([(None, (1, 0, 0), 1.0), (Mask(np.ones((2, 2), np.float32), 9, 9), (1, 0, 0), 1.0),
                 (Mask(np.ones((2, 2), np.float32), 0, 0), (1, 0, 0), 0.0)])
    assert np.array_equal(c.data, before)


def test_an_invalid_colour_raises_after_the_fills_before_it():
    m = Mask(np.ones((2, 2), np.float32), 0, 0)
    a, b = Canvas(3, 3), Canvas(3, 3)
    with pytest.raises(CanvasError):
        a.fill_many([(m, (1, 0, 0), 0.5), (Mask(np.ones((1, 1), np.float32), 2, 2), (0, 1, 0), 1.0),
                     (m, (1, 0), 1.0), (m, (0, 0, 1), 1.0)])
    b.fill(m, (1, 0, 0), 0.5)
    b.fill(Mask(np.ones((1, 1), np.float32), 2, 2), (0, 1, 0), 1.0)
    assert np.array_equal(a.data, b.data)
