"""Surface plots: the camera, painter's order, shading, SVG output."""

import io

import numpy as np
import pytest
import resvg_py
from PIL import Image

from raster.curves import BezierSurface, CurveError
from raster.curves.surfaceplot import SURFACE_COLORS, SurfacePlot, camera

DOME = BezierSurface([[[0, 0, 0], [0, 1, 0], [0, 2, 0]], [[1, 0, 0], [1, 1, 2], [1, 2, 0]],
                      [[2, 0, 0], [2, 1, 0], [2, 2, 0]]])


def test_camera_projections():
    c = np.array([1.0, 2.0, 3.0])
    ortho, (r, u, f) = camera(c, 2.0, 30, 40, False)
    np.testing.assert_allclose([r @ u, r @ f, u @ f], 0, atol=1e-15)
    assert u[2] > 0                                      # z is up on the screen
    # orthographic: points along the view direction project to one point,
    # their depths grow along it
    line = c + np.outer([-1, 0, 2], f)
    p, d = ortho(line)
    np.testing.assert_allclose(p - p[0], 0, atol=1e-12)
    assert np.all(np.diff(d) > 0)
    persp, _ = camera(c, 2.0, 30, 40, True)
    # perspective: an offset seen from farther away looks smaller
    near, far = c + r - 2 * f, c + r + 2 * f
    (pn, _), (pf, _) = persp(near), persp(far)
    pc, _ = persp(c)
    assert np.linalg.norm(pn - persp(c - 2 * f)[0]) > np.linalg.norm(pf - persp(c + 2 * f)[0])
    assert np.isfinite(pc).all()


def test_top_view_shades_the_front_and_hides_nothing_it_should_not():
    # seen from above the dome (z up) shows its upper side; with the net's
    # orientation S_u x S_v points up, so every quad is a front face
    plot = SurfacePlot(DOME, None, 400, 'ortho', azimuth=-90, elevation=89.9, isolines=1)
    img = plot.render()[..., :3].astype(float)
    fills = [st['color'] for k, p, st in plot.layers if k == 'fill' and len(st['color']) == 3]
    front = np.array(SURFACE_COLORS['front'])
    shaded = [c for c in fills if np.allclose(np.array(c) / max(max(c), 1e-9),
                                              front / front.max(), atol=0.02)]
    assert len(shaded) >= 32 * 32
    # the middle of the image is surface colour, bluish
    h, w = img.shape[:2]
    m = img[h // 2 - 20:h // 2 + 20, w // 2 - 20:w // 2 + 20].reshape(-1, 3).mean(0)
    assert m[2] > m[0] + 30


def test_painter_order_back_to_front():
    plot = SurfacePlot(DOME, [[0.5, 0.5]], 400, 'both', azimuth=-60, elevation=30)
    assert len(plot.paint_depths) == 2
    for d in plot.paint_depths:
        assert len(d) == 32 * 32 and np.all(np.diff(d) <= 0)     # far to near


@pytest.mark.parametrize('view', ['perspective', 'both'])
def test_svg_matches_the_png(view):
    plot = SurfacePlot(DOME, [[0.5, 0.5], [0, 1]], 500, view)
    ours = plot.render().astype(float)
    ref = np.asarray(Image.open(io.BytesIO(bytes(resvg_py.svg_to_bytes(
        svg_string=plot.to_svg())))).convert('RGBA')).astype(float)
    assert ref.shape == ours.shape
    assert np.abs(ours - ref).mean() < 1.0


def test_bad_views():
    with pytest.raises(CurveError, match='view'):
        SurfacePlot(DOME, None, 400, 'fisheye')
    with pytest.raises(CurveError, match='width'):
        SurfacePlot(DOME, None, 50)
