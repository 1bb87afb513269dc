"""raster.geometry.rows: row gathers and scatters through complex views
equal ordinary fancy indexing bit for bit; and the exact fast paths of
the flattener that use the same idea (cubic blossoms, cubic ranges)."""

import numpy as np

from raster.geometry import bezier
from raster.geometry.bezier import bernstein_range
from raster.geometry.flattening import _cubic_range0
from raster.geometry.rows import pairs, put_rows, take_rows


def test_take_and_put_rows_equal_fancy_indexing():
    rng = np.random.default_rng(3)
    a = rng.normal(size=(500, 2))
    a[7] = [np.nan, -0.0]
    idx = rng.integers(0, 500, 300)
    mask = rng.random(500) < 0.4
    for sel in (idx, mask):
        got = take_rows(a, sel)
        assert got.shape == a[sel].shape
        assert got.tobytes() == a[sel].tobytes()
    out1, out2 = np.zeros((500, 2)), np.zeros((500, 2))
    u = np.unique(idx)
    vals = rng.normal(size=(len(u), 2))
    out1[u] = vals
    put_rows(out2, u, vals)
    assert out1.tobytes() == out2.tobytes()


def test_rows_fall_back_for_other_layouts():
    a = np.arange(12.0).reshape(6, 2)[::2]          # not contiguous
    assert pairs(a) is None
    assert take_rows(a, np.array([2, 0])).tolist() == [[8.0, 9.0], [0.0, 1.0]]
    out = np.zeros((3, 2))
    put_rows(out, np.array([0, 2]), np.array([5.0, 6.0]))   # broadcast row
    assert out.tolist() == [[5.0, 6.0], [0.0, 0.0], [5.0, 6.0]]


def test_cubic_blossom_is_the_generic_one_bit_for_bit():
    rng = np.random.default_rng(4)
    m = 2000
    P = rng.normal(size=(4, 2, m)) * 10.0 ** rng.integers(-3, 4, size=(1, 1, m))
    a, b = rng.uniform(0, 1, m), rng.uniform(0, 1, m)
    a[:10], b[10:20], a[20:30], b[30:40] = 0.0, 1.0, 1.0, 0.0
    want = bezier._blossom_terms(P, a, b)
    got = bezier._blossom_loops(P, a, b)
    assert got.tobytes() == want.tobytes()


def test_cubic_range0_equals_bernstein_range():
    rng = np.random.default_rng(5)
    for trial in range(40):
        m = 500
        c1 = rng.normal(size=m) * 10.0 ** rng.integers(-8, 8)
        c2 = rng.normal(size=m) * 10.0 ** rng.integers(-8, 8)
        sel = rng.random(m) < 0.2
        c2[sel] = c1[sel]
        c1[rng.random(m) < 0.1] = 0.0
        c2[rng.random(m) < 0.1] = 0.0
        sel = rng.random(m) < 0.05
        c2[sel] = 2 * c1[sel]
        for end in (0.0, 1.0):
            c = np.zeros((4, m))
            c[1], c[2], c[3] = c1, c2, end
            lo, hi = bernstein_range(c, normalize=False)
            glo, ghi = _cubic_range0(c1, c2, end)
            assert np.array_equal(lo, glo) and np.array_equal(hi, ghi)
