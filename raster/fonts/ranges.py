"""Sets of code points as flat sorted inclusive ranges, and the CSS
``unicode-range`` descriptor (CSS Fonts 4, section 4.5) that gives them.

A set is a tuple (or (2K,) int64 array) ``lo0, hi0, lo1, hi1, ...`` of
disjoint ranges in increasing order, each inclusive; the empty tuple of a
:class:`~raster.fonts.FontFace` means "every code point".

>>> parse_unicode_range('U+0025-00FF, u+4??, U+26')
(37, 255, 1024, 1279)
>>> parse_unicode_range('U+00FF-0025') is None       # start after end: invalid
True
"""

import re

import numpy as np

__all__ = ['MAX_CODE_POINT', 'parse_unicode_range', 'in_ranges', 'intersect_ranges',
           'merge_ranges']

#: The largest Unicode code point.
MAX_CODE_POINT = 0x10FFFF

_ITEM = re.compile(r'[uU]\+([0-9a-fA-F?]{1,6})(?:-([0-9a-fA-F]{1,6}))?')
_WILD = re.compile(r'[0-9a-fA-F]*\?+')


def parse_unicode_range(value):
    """The code points of a ``unicode-range`` value, or None when it is
    invalid (the descriptor is then ignored, as CSS drops an invalid
    declaration).

    Parameters
    ----------
    value : str
        A comma-separated list of ``<urange>`` items: ``U+26`` (one code
        point), ``U+0-7F`` (a range), ``U+4??`` (a wildcard: the ``?``
        digits run over 0..F); ``U`` in either case, one to six hex
        digits.

    Returns
    -------
    tuple of int or None
        Flat sorted inclusive ranges (merged: overlapping and adjacent
        items join).  None when an item does not parse, a range starts
        after it ends or reaches past U+10FFFF, or the list is empty.
    """
    if not isinstance(value, str):
        return None
    items = value.split(',')
    out = []
    for item in items:
        m = _ITEM.fullmatch(item.strip())
        if m is None:
            return None
        first, second = m.group(1), m.group(2)
        if '?' in first:
            if second is not None or not _WILD.fullmatch(first):
                return None
            lo, hi = int(first.replace('?', '0'), 16), int(first.replace('?', 'F'), 16)
        else:
            lo = int(first, 16)
            hi = lo if second is None else int(second, 16)
        if lo > hi or hi > MAX_CODE_POINT:
            return None
        out.append((lo, hi))
    return merge_ranges(out)


def merge_ranges(pairs):
    """Flat sorted ranges of ``(lo, hi)`` inclusive pairs in any order
    (overlapping and adjacent pairs joined), as a tuple of int."""
    out = []
    for lo, hi in sorted(pairs):
        if out and lo <= out[-1] + 1:
            out[-1] = max(out[-1], hi)
        else:
            out.extend((lo, hi))
    return tuple(int(v) for v in out)


def in_ranges(ranges, cps):
    """Which code points lie in a set.

    Parameters
    ----------
    ranges : sequence of int
        Flat sorted inclusive ranges (non-empty).
    cps : sequence of int
        Code points, shape (N,).

    Returns
    -------
    (N,) bool ndarray
    """
    r = np.asarray(ranges, np.int64)
    c = np.asarray(cps, np.int64)
    i = np.searchsorted(r, c, 'right')
    # inside a range: after an odd number of bounds, or on a range's end
    return (i % 2 == 1) | ((i > 0) & (r[np.maximum(i - 1, 0)] == c))


def intersect_ranges(a, b):
    """The code points in both of two sets (flat sorted inclusive
    ranges), as a (2K,) int64 ndarray."""
    a = np.asarray(a, np.int64).reshape(-1, 2)
    b = np.asarray(b, np.int64).reshape(-1, 2)
    if not len(a) or not len(b):
        return np.zeros(0, np.int64)
    # every pair of ranges, clipped to each other (b is short: a few items)
    lo = np.maximum(a[:, None, 0], b[None, :, 0]).ravel()
    hi = np.minimum(a[:, None, 1], b[None, :, 1]).ravel()
    keep = lo <= hi
    lo, hi = lo[keep], hi[keep]
    order = np.argsort(lo, kind='stable')
    return np.asarray(merge_ranges(zip(lo[order].tolist(), hi[order].tolist())), np.int64)
