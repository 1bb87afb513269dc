"""Shared test geometry (imported by the test modules as ``_geometry``)."""

from raster.geometry.pens import PathBuilder

#: Control-point distance of a quarter-circle cubic: radial error 2.7e-4 r.
KAPPA = 0.5522847498


def kappa_circle(cx, cy, r):
    """The usual SVG circle: four cubic quarter arcs starting at (cx + r, cy),
    in the positive-angle direction (clockwise on screen)."""
    k = KAPPA * r
    b = PathBuilder()
    b.moveTo((cx + r, cy))
    b.curveTo((cx + r, cy + k), (cx + k, cy + r), (cx, cy + r))
    b.curveTo((cx - k, cy + r), (cx - r, cy + k), (cx - r, cy))
    b.curveTo((cx - r, cy - k), (cx - k, cy - r), (cx, cy - r))
    b.curveTo((cx + k, cy - r), (cx + r, cy - k), (cx + r, cy))
    b.closePath()
    return b.path()
