"""Device boxes of paths (raster.renderer.bounds): the box of the path's
control box mapped by the CTM, the same for every kind of transform."""

import numpy as np
from hypothesis import given, settings, strategies as st

from raster.geometry.path import Path
from raster.geometry.transform import Affine
from raster.renderer.bounds import device_area, device_box

coord = st.floats(-1e4, 1e4, allow_nan=False)
factor = st.floats(-50, 50, allow_nan=False)


def corners_box(path, t):
    """The box of the four mapped corners of the control box (numpy)."""
    x0, y0, x1, y1 = path.control_box()
    c = t.apply(np.array([[x0, y0], [x1, y0], [x0, y1], [x1, y1]]))
    return (*c.min(0), *c.max(0))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(coord, coord), min_size=1, max_size=6), factor, factor, factor,
       factor, coord, coord, st.booleans())
def test_device_box_is_the_box_of_the_mapped_corners(pts, a, b, c, d, e, f, axis_aligned):
    # scales and translations (flips included) take a shorter path than
    # rotations and skews: both give the mapped corners' box
    if axis_aligned:
        b = c = 0.0
    path = Path.polygon(pts)
    t = Affine(a, b, c, d, e, f)
    got = device_box(path, t)
    want = corners_box(path, t)
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-9)
    assert got[0] <= got[2] and got[1] <= got[3]


def test_device_box_of_flips_and_a_known_area():
    # the square (1, 2)-(3, 5) mirrored in both axes, then moved
    path = Path.polygon([(1, 2), (3, 2), (3, 5), (1, 5)])
    assert device_box(path, Affine(-2, 0, 0, -1, 10, 20)) == (4.0, 15.0, 8.0, 18.0)
    assert device_box(path, Affine(0, 1, 1, 0, 0, 0)) == (2.0, 1.0, 5.0, 3.0)   # swap axes
    # its 4 x 3 device box grown by 1 px, on a 100 x 100 canvas
    assert device_area(path, Affine(-2, 0, 0, -1, 10, 20), (100, 100)) == 6.0 * 5.0
