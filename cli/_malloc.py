"""Allocator tuning for large numpy temporaries (glibc only).

Rendering makes many numpy temporaries of tens of megabytes.  glibc's
malloc serves blocks above its mmap threshold (128 kB, rising to at most
32 MB as such blocks are freed) with fresh ``mmap`` calls and unmaps them on
``free``, so every such temporary costs a page fault per 4 kB page touched:
on the corpus benchmark's world map at 2000 px that was 70,000-100,000 page
faults and 0.2-0.9 s of system time per render.  :func:`tune` raises the
mmap threshold and the trim threshold so freed blocks stay in the heap and
are reused: later renders in the same process then fault almost no pages
(the first one still grows the heap).

The cost: memory freed after a render is kept by the process (up to
``_TRIM`` bytes above the heap top) instead of being returned to the
system.  Set the environment variable ``RASTER_MALLOC_TUNING=0`` to leave
the allocator alone.  Elsewhere than Linux with glibc this does nothing.
"""

import ctypes
import os
import sys

__all__ = ['tune']

_M_TRIM_THRESHOLD, _M_TOP_PAD, _M_MMAP_THRESHOLD = -1, -2, -3
_MMAP = 1 << 30          # blocks above 1 GB still get their own mapping
_TRIM = 1 << 30          # free memory kept at the heap top before trimming
_PAD = 64 << 20          # heap growth step

_done = False


def tune():
    """Tune glibc's malloc once per process (see the module docstring).
    Returns True when the settings were applied."""
    global _done
    if _done:
        return False
    _done = True
    if os.environ.get('RASTER_MALLOC_TUNING', '1') == '0' or not sys.platform.startswith('linux'):
        return False
    try:
        libc = ctypes.CDLL('libc.so.6')
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    ok = mallopt(_M_MMAP_THRESHOLD, _MMAP) == 1
    ok = mallopt(_M_TRIM_THRESHOLD, _TRIM) == 1 and ok
    ok = mallopt(_M_TOP_PAD, _PAD) == 1 and ok
    return ok
