"""Code point sets and the CSS unicode-range descriptor (CSS Fonts 4,
section 4.5): single code points, ranges, wildcards, lists, and the
invalid values that drop the descriptor."""
import numpy as np
import pytest
from hypothesis import given, strategies as st

from raster.fonts.ranges import (MAX_CODE_POINT, in_ranges, intersect_ranges, merge_ranges,
                                 parse_unicode_range)


@pytest.mark.parametrize('value, expected', [
    ('U+26', (0x26, 0x26)),
    ('u+26', (0x26, 0x26)),
    ('U+0-7F', (0, 0x7F)),
    ('U+0025-00FF', (0x25, 0xFF)),
    ('U+4??', (0x400, 0x4FF)),
    ('U+???', (0, 0xFFF)),
    ('U+10????', (0x100000, 0x10FFFF)),
    ('U+10FFFF', (MAX_CODE_POINT, MAX_CODE_POINT)),
    ('U+0025-00FF, U+4??', (0x25, 0xFF, 0x400, 0x4FF)),
    (' U+4?? ,U+26 ', (0x26, 0x26, 0x400, 0x4FF)),          # sorted, spaces around items
    ('U+30-39, U+35-45, U+46', (0x30, 0x46)),                 # overlapping and adjacent merge
    ('U+000041', (0x41, 0x41)),                               # six digits
])
def test_valid_values(value, expected):
    assert parse_unicode_range(value) == expected


@pytest.mark.parametrize('value', [
    '',                     # no item
    'U+26,',                # an empty item
    'U+00FF-0025',          # start after end
    'U+110000',             # beyond U+10FFFF
    'U+10FFFF-110000',
    'U+11????',             # a wildcard reaching past U+10FFFF
    'U+4?4',                # ? only at the end
    'U+4??-4FF',            # a wildcard is not a range start
    'U+0-?',
    'U+1234567',            # seven digits
    'U+???????',
    'U+',
    'U+ 26',                # no space after U+
    '26',
    'U-26',
    'U+G0',
    'U+26 U+27',            # items are separated by commas
    'U+0041, U+00FF-0025',  # one invalid item drops the whole value
])
def test_invalid_values_drop_the_descriptor(value):
    assert parse_unicode_range(value) is None


@given(st.lists(st.tuples(st.integers(0, 0x2FF), st.integers(0, 0x2FF)), min_size=1,
                max_size=6))
def test_parsed_set_is_the_union_of_its_items(pairs):
    """Any list of valid items means exactly the code points some item
    covers (checked point by point against a Python set)."""
    pairs = [(min(a, b), max(a, b)) for a, b in pairs]
    value = ', '.join('U+%X-%X' % p if p[0] != p[1] else 'U+%X' % p[0] for p in pairs)
    ranges = parse_unicode_range(value)
    want = set()
    for a, b in pairs:
        want.update(range(a, b + 1))
    cps = np.arange(0, 0x301)
    got = set(cps[in_ranges(ranges, cps)].tolist())
    assert got == want
    flat = np.asarray(ranges)
    assert (np.diff(flat) > 0)[1::2].all()       # disjoint, not adjacent, increasing
    assert (flat[1::2] >= flat[0::2]).all()


@given(st.lists(st.integers(0, 500), min_size=2, max_size=12),
       st.lists(st.integers(0, 500), min_size=2, max_size=6))
def test_intersection_is_the_common_code_points(a, b):
    a = merge_ranges([(min(x, y), max(x, y)) for x, y in zip(a[0::2], a[1::2])])
    b = merge_ranges([(min(x, y), max(x, y)) for x, y in zip(b[0::2], b[1::2])])
    cps = np.arange(0, 502)
    both = set(cps[in_ranges(a, cps) & in_ranges(b, cps)].tolist())
    r = intersect_ranges(a, b)
    got = set(cps[in_ranges(r, cps)].tolist()) if len(r) else set()
    assert got == both


def test_in_ranges_at_the_bounds():
    r = (0x25, 0xFF, 0x400, 0x4FF)
    cps = [0x24, 0x25, 0xFF, 0x100, 0x3FF, 0x400, 0x4FF, 0x500, 0]
    assert in_ranges(r, cps).tolist() == [False, True, True, False, False, True, True, False,
                                          False]
