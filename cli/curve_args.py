"""Argument parsing shared by ``curve`` and ``curve surface``: the usage
error, number and point lists, the plot size."""

import argparse
import math
import re

import numpy as np

__all__ = ['UsageError', 'Parser', 'number', 'parse_numbers', 'parse_points', 'plot_size']


class UsageError(Exception):
    """Bad command-line input (exit status 2)."""


class Parser(argparse.ArgumentParser):
    """An argument parser that raises :class:`UsageError` instead of
    exiting."""

    def error(self, message):
        raise UsageError(message)


def number(text, what):
    """A finite float from ``text`` or :class:`UsageError` naming ``what``."""
    try:
        v = float(text)
    except ValueError:
        raise UsageError('cannot parse %s %r as a number' % (what, text)) from None
    if not math.isfinite(v):
        raise UsageError('%s must be finite, got %r' % (what, text))
    return v


def parse_numbers(text, what='value'):
    """'0,0.25,1' -> [0.0, 0.25, 1.0]."""
    parts = [p for p in re.split(r'[,\s]+', text.strip()) if p]
    if not parts:
        raise UsageError('no %s given' % what)
    return [number(p, what) for p in parts]


def parse_points(text, what='points'):
    """'1,1 2,3 4,3' -> (N, D) float64 array (D the same for every point)."""
    groups = [g for g in re.split(r'[\s;]+', text.strip()) if g]
    if not groups:
        raise UsageError('no %s given' % what)
    pts = []
    for g in groups:
        coords = [c for c in g.split(',') if c != '']
        pts.append([number(c, 'coordinate') for c in coords])
    dims = {len(p) for p in pts}
    if len(dims) != 1:
        raise UsageError('all %s must have the same number of coordinates' % what)
    return np.array(pts, dtype=np.float64)


def plot_size(args):
    """The ``--size`` option as an int in [100, 4000]."""
    size = number(args.size, 'size')
    if size != int(size) or not 100 <= size <= 4000:
        raise UsageError('--size must be an integer between 100 and 4000')
    return int(size)
