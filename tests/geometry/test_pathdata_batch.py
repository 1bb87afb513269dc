"""parse_paths (many path data strings in one vectorized pass) against
parse_path one string at a time."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.errors import PathError
from raster.geometry.pathdata import parse_path, parse_paths

_ARGS = {'M': 2, 'L': 2, 'H': 1, 'V': 1, 'C': 6, 'S': 4, 'Q': 4, 'T': 2, 'A': 7, 'Z': 0}


@st.composite
def data_strings(draw):
    """Path data, mostly valid; sometimes truncated, junk or blank."""
    n = draw(st.integers(0, 12))
    first = draw(st.sampled_from('Mm'))
    parts = ['%s%d,%d' % (first, draw(st.integers(-50, 50)), draw(st.integers(-50, 50)))]
    for _ in range(n):
        c = draw(st.sampled_from('MLHVCSQTZA'))
        if draw(st.booleans()):
            c = c.lower()
        k = _ARGS[c.upper()]
        nums = [draw(st.integers(-40, 40)) for _ in range(k * draw(st.integers(1, 2)))]
        if c in 'Aa':
            for g in range(0, len(nums), 7):
                nums[g], nums[g + 1] = abs(nums[g]) + 1, abs(nums[g + 1]) + 1
                nums[g + 3], nums[g + 4] = nums[g + 3] & 1, nums[g + 4] & 1
        parts.append(c + ' '.join(map(str, nums)))
    d = ' '.join(parts)
    how = draw(st.sampled_from(['ok', 'ok', 'ok', 'cut', 'junk', 'blank', 'comma']))
    if how == 'cut':
        d = d[:draw(st.integers(0, len(d)))]
    elif how == 'junk':
        i = draw(st.integers(0, len(d)))
        d = d[:i] + draw(st.sampled_from(['x', '#', '|', ',,', '1e999'])) + d[i:]
    elif how == 'blank':
        d = draw(st.sampled_from(['', ' ', '\n']))
    elif how == 'comma':
        d = d + ','
    return d


def _same(a, b):
    return (a.verbs.tolist() == b.verbs.tolist() and a.points.shape == b.points.shape
            and np.allclose(a.points, b.points, rtol=1e-12, atol=1e-9))


@settings(max_examples=120, deadline=None)
@given(st.lists(data_strings(), min_size=0, max_size=8), st.sampled_from([0.01, 0.5]))
def test_batch_equals_one_by_one(ds, tol):
    got = parse_paths(ds, tol)
    assert len(got) == len(ds)
    for d, p in zip(ds, got):
        assert _same(p, parse_path(d, tol, strict=False)), d


def test_relative_moveto_starts_every_path_absolute():
    # in a concatenation 'm' would be relative to the previous path's end
    a, b = parse_paths(['M 10 10 l 5 5', 'm 1 2 l 1 1 z m 1 1 h 1'])
    assert b.to_svg() == 'M 1 2 L 2 3 Z M 2 3 L 3 3'
    assert a.to_svg() == 'M 10 10 L 15 15'


def test_smooth_curves_do_not_reflect_across_paths():
    # S after C reflects; S at the start of the next path has no previous C
    a, b = parse_paths(['M0 0 C 1 1 2 1 3 0', 'M0 0 S 2 1 3 0'])
    assert b.points[1].tolist() == [0.0, 0.0]       # first control = current point


def test_invalid_strings_keep_their_valid_prefix():
    got = parse_paths(['M0 0 L10 0 L', 'L 1 1', 'M 0 0 L 5 5', 'M0 0 L 1e999 0'])
    assert got[0].to_svg() == 'M 0 0 L 10 0'
    assert len(got[1]) == 0
    assert got[2].to_svg() == 'M 0 0 L 5 5'
    assert got[3].to_svg() == 'M 0 0'


def test_many_map_like_paths_agree_with_parse_path():
    # a "map": many closed polygons of relative lines and cubics (seeded)
    rng = np.random.default_rng(3)
    ds = []
    for _ in range(300):
        parts = ['M%.3f,%.3f' % tuple(rng.uniform(0, 1000, 2))]
        for _ in range(int(rng.integers(1, 40))):
            if rng.random() < 0.5:
                parts.append('l%.3f%+.3f' % tuple(rng.normal(0, 3, 2)))
            else:
                parts.append('c' + ','.join('%.3f' % v for v in rng.normal(0, 3, 6)))
        parts.append('z')
        ds.append(''.join(parts))
    got = parse_paths(ds)
    for d, p in zip(ds, got):
        assert _same(p, parse_path(d, strict=False))


def test_arcs_follow_the_tolerance():
    # a semicircle of radius 100: a finer tolerance gives more cubic pieces
    d = 'M 0 0 A 100 100 0 0 1 200 0'
    coarse, fine = parse_paths([d, d], 1.0)[0], parse_paths([d, d], 1e-5)[0]
    assert len(fine.verbs) > len(coarse.verbs)
    assert _same(fine, parse_path(d, 1e-5))


def test_bad_input_raises_path_error():
    with pytest.raises(PathError):
        parse_paths(['M0 0', 5])
    with pytest.raises(PathError):
        parse_paths(['M0 0'], 0.0)
    assert parse_paths([]) == []


@settings(max_examples=60, deadline=None)
@given(st.lists(data_strings(), min_size=1, max_size=8))
def test_batch_of_long_data_equals_one_by_one(ds):
    # enough data for the vectorized lexer (when no string needs the
    # regular expression one): same paths either way
    from raster.geometry import pathdata as svgpath
    k = svgpath.FAST_LEX_CHARS // max(1, sum(map(len, ds))) + 1
    ds = (ds * k)[:200]
    got = parse_paths(ds, 0.1)
    for d, p in zip(ds, got):
        assert _same(p, parse_path(d, 0.1, strict=False)), d


@settings(max_examples=80, deadline=None)
@given(st.lists(data_strings(), max_size=12), st.integers(1, 60), st.integers(1, 80))
def test_lexing_in_chunks_changes_nothing(ds, chunk, fast_from):
    from raster.geometry import pathdata as svgpath
    d = '|'.join(ds)
    nums, kinds = svgpath._split(svgpath._mark(d))
    want = np.array(nums, np.float64) if nums else np.zeros(0)
    saved = svgpath._LEX_CHUNK, svgpath.FAST_LEX_CHARS
    try:
        svgpath._LEX_CHUNK, svgpath.FAST_LEX_CHARS = chunk, fast_from
        k, v = svgpath._lex_values(d)
    finally:
        svgpath._LEX_CHUNK, svgpath.FAST_LEX_CHARS = saved
    assert k == kinds and v.tobytes() == want.tobytes()
