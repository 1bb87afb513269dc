"""SVG 2 mesh gradients end to end: ``meshgradient`` documents rendered by
raster against references computed here by dense sampling of the Coons
patch equations (no other renderer draws mesh gradients).

The reference: for every patch, in document order, the boundary curves
(written out here, independently of the parser) are sampled on a dense
(u, v) grid, each sample is the Coons point
``S = (1-v) C0(u) + v C1(u) + (1-u) D0(v) + u D1(v) - B(u, v)`` with its
bilinearly interpolated corner colour, and the pixel it falls in takes that
colour (later samples and patches on top).  Compared under the suite's
criterion (raster.testing.compare_images).
"""

import os
import warnings

import numpy as np
import pytest

import raster
from raster.parser import build_tree
from raster.parser.document import load_document
from raster.testing import compare_images
from raster.tree import MeshGradient, MeshInterpolation, PathNode, walk

HERE = os.path.dirname(os.path.abspath(__file__))
MESH = os.path.join(HERE, '..', '..', 'golden', 'mesh')


def _bez(p, t):
    """Cubic Bezier points: p (4, 2), t (N,) -> (N, 2)."""
    t = t[:, None]
    s = 1 - t
    return s ** 3 * p[0] + 3 * s * s * t * p[1] + 3 * s * t * t * p[2] + t ** 3 * p[3]


def _line(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.array([a, a + (b - a) / 3, a + (b - a) * 2 / 3, b])


def reference(patches, width, height, transform=None):
    """Dense-sampling reference image (H, W, 4) uint8 straight RGBA.

    ``patches``: list of (top, right, bottom, left, colours) with the four
    edges as (4, 2) control points in the usual directions (top and bottom
    left to right, left and right top to bottom) and colours the straight
    RGBA at the corners top-left, top-right, bottom-right, bottom-left."""
    img = np.zeros((height, width, 4))
    for top, right, bottom, left, cols in patches:
        ctrl = np.concatenate([top, right, bottom, left])
        if transform is not None:
            ctrl = transform.apply(ctrl)
        top, right, bottom, left = ctrl[0:4], ctrl[4:8], ctrl[8:12], ctrl[12:16]
        span = np.abs(ctrl.max(0) - ctrl.min(0)).max()
        n = int(span * 4) + 8
        u = np.linspace(0, 1, n)
        U, V = np.meshgrid(u, u)                 # row = v, column = u
        uu, vv = U.ravel(), V.ravel()
        C0, C1 = _bez(top, uu), _bez(bottom, uu)
        D0, D1 = _bez(left, vv), _bez(right, vv)
        P00, P10, P11, P01 = top[0], top[3], bottom[3], bottom[0]
        B = ((1 - uu) * (1 - vv))[:, None] * P00 + (uu * (1 - vv))[:, None] * P10 + \
            ((1 - uu) * vv)[:, None] * P01 + (uu * vv)[:, None] * P11
        S = (1 - vv)[:, None] * C0 + vv[:, None] * C1 + (1 - uu)[:, None] * D0 + \
            uu[:, None] * D1 - B
        c = np.asarray(cols, float)
        col = ((1 - uu) * (1 - vv))[:, None] * c[0] + (uu * (1 - vv))[:, None] * c[1] + \
            (uu * vv)[:, None] * c[2] + ((1 - uu) * vv)[:, None] * c[3]
        ix, iy = np.floor(S[:, 0]).astype(int), np.floor(S[:, 1]).astype(int)
        ok = (ix >= 0) & (ix < width) & (iy >= 0) & (iy < height)
        img[iy[ok], ix[ok]] = col[ok]            # later samples on top
    return np.round(np.clip(img, 0, 1) * 255).astype(np.uint8)


def _check(svg, ref, **kw):
    got = raster.render(svg, **kw)
    cmp = compare_images(ref, got)
    assert cmp.passed, cmp.reason
    return got


BLUE, LIME, YELLOW = (0, 0, 1, 1), (0, 1, 0, 1), (1, 1, 0, 1)


def test_two_by_two_mesh_of_lines():
    """golden/mesh/mesh-2x2-lines.svg: corners blue, lime, yellow (top row),
    lime, yellow, blue (middle), yellow, blue, lime (bottom)."""
    grid = [[(20, 20), (120, 20), (220, 20)], [(20, 120), (120, 120), (220, 120)],
            [(20, 220), (120, 220), (220, 220)]]
    cols = [[BLUE, LIME, YELLOW], [LIME, YELLOW, BLUE], [YELLOW, BLUE, LIME]]
    patches = []
    for r in range(2):
        for c in range(2):
            tl, tr = grid[r][c], grid[r][c + 1]
            bl, br = grid[r + 1][c], grid[r + 1][c + 1]
            patches.append((_line(tl, tr), _line(tr, br), _line(bl, br), _line(tl, bl),
                            (cols[r][c], cols[r][c + 1], cols[r + 1][c + 1], cols[r + 1][c])))
    ref = reference(patches, 240, 240)
    got = _check(os.path.join(MESH, 'mesh-2x2-lines.svg'), ref)
    assert np.abs(got[120, 120].astype(int) - (255, 255, 0, 255)).max() <= 4   # shared corner
    assert got[5, 5, 3] == 0                                       # outside the mesh


def test_a_wrong_reference_fails():
    """The comparison has teeth: the 2x2 mesh against its reference with two
    corner colours swapped fails."""
    grid = [(20, 20), (220, 20), (220, 220), (20, 220)]
    ref = reference([(_line(grid[0], grid[1]), _line(grid[1], grid[2]),
                      _line(grid[3], grid[2]), _line(grid[0], grid[3]),
                      (BLUE, YELLOW, LIME, YELLOW))], 240, 240)
    got = raster.render(os.path.join(MESH, 'mesh-2x2-lines.svg'))
    assert not compare_images(ref, got).passed


def test_curved_patch_in_bounding_box_units_with_a_transform():
    """golden/mesh/mesh-curved-obb.svg: one curved patch in the units of the
    rect's box (10, 10, 180, 140), rotated 5 degrees about the box centre;
    stop-opacity 0.5 at the top-right corner."""
    from raster.geometry.transform import Affine
    top = np.array([[0.1, 0.1], [0.4, -0.1], [0.6, 0.3], [0.9, 0.1]])
    right = np.array([[0.9, 0.1], [1.0, 0.4], [0.8, 0.6], [0.9, 0.9]])
    bottom = np.array([[0.1, 0.9], [0.4, 0.7], [0.6, 0.95], [0.9, 0.9]])
    left = np.array([[0.1, 0.1], [0.0, 0.4], [0.2, 0.6], [0.1, 0.9]])
    cols = ((1, 0, 0, 1), (1, 0.843, 0, 0.5), (0, 0, 1, 1), (0, 1, 0, 1))
    box = Affine(180, 0, 0, 140, 10, 10) @ Affine.rotate(5, 0.5, 0.5)
    ref = reference([(top, right, bottom, left, cols)], 200, 160, transform=box)
    got = _check(os.path.join(MESH, 'mesh-curved-obb.svg'), ref)
    assert got[12, 180, 3] == 0                  # inside the rect, outside the patch


def test_inkscape_document_renders():
    """golden/mesh/mesh-inkscape.svg, written the way Inkscape writes
    meshes (style attributes, namespaces, mm units, a path in a translated
    layer), renders without warnings and matches its reference."""
    def wave(p0, d):
        p0 = np.asarray(p0, float)
        return np.array([p0, p0 + (25, -10), p0 + (50, 10), p0 + (75, 0)]) if d == 'h' else \
            np.array([p0, p0 + (5, 25), p0 + (-5, 50), p0 + (0, 75)])
    orange, white, blue = (1, 0.4, 0, 1), (1, 1, 1, 1), (0, 0.4, 1, 1)
    green, purple = (0, 2 / 3, 4 / 15, 1), (2 / 3, 0, 8 / 15, 1)
    p1 = (wave((30, 30), 'h'), wave((105, 30), 'v'), wave((30, 105), 'h'), wave((30, 30), 'v'),
          (orange, white, blue, white))
    p2 = (wave((105, 30), 'h'), wave((180, 30), 'v'), wave((105, 105), 'h'),
          wave((105, 30), 'v'), (white, green, purple, blue))
    from raster.geometry.transform import Affine
    scale = 96 / 25.4                            # viewBox in mm, drawn at 96 dpi
    t = Affine.scale(scale) @ Affine.translate(2, 3)
    w, h = round(210 * scale), round(148 * scale)
    ref = reference([p1, p2], w, h, transform=t)
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        got = _check(os.path.join(MESH, 'mesh-inkscape.svg'), ref)
    assert got.shape == (h, w, 4)


def _doc(stops_rows, extra=''):
    rows = ''.join('<meshrow>%s</meshrow>' % ''.join(
        '<meshpatch>%s</meshpatch>' % ''.join(
            '<stop %s/>' % s for s in patch) for patch in row) for row in stops_rows)
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
            '<meshgradient id="m" gradientUnits="userSpaceOnUse" x="10" y="10"%s>%s'
            '</meshgradient><rect width="100" height="100" fill="url(#m) lime"/></svg>'
            % (extra, rows)).encode()


def _mesh_of(doc):
    t = build_tree(load_document(doc))
    (n,) = [n for n, _ in walk(t.root) if isinstance(n, PathNode)]
    return n.fill.paint


def test_the_tree_holds_the_patches_in_user_space():
    p = _mesh_of(_doc([[['stop-color="red" path="l 50,0"', 'stop-color="blue" path="L 60,50"',
                         'stop-color="lime" path="l -50,0"', 'stop-color="black" path="l 0,-40"']]],
                      ' type="bicubic" gradientTransform="translate(5 0)"'))
    assert isinstance(p, MeshGradient) and p.shape == (1, 1)
    assert p.interpolation is MeshInterpolation.BICUBIC
    assert p.patches.shape == (1, 12, 2) and p.colors.shape == (1, 4, 4)
    corners = p.patches[0, [0, 3, 6, 9]]
    assert corners.tolist() == [[10, 10], [60, 10], [60, 50], [10, 50]]
    assert p.colors[0, :, :3].tolist() == [[1, 0, 0], [0, 0, 1], [0, 1, 0], [0, 0, 0]]
    # the last edge leaves out its end point: the patch closes on its start
    assert p.patches[0, 11].tolist() == pytest.approx([10, 50 - 40 * 2 / 3])
    assert p.transform.e == 5


@pytest.mark.parametrize('stops', [
    [['stop-color="red" path="l 50,0"', 'path="l 0,50"']],                      # too few stops
    [['stop-color="red" path="q 1,2 3,4"', 'path="l 0,50"', 'path="l -50,0"',
      'path="l 0,-50"']],                                                          # not l/c
    [['path="l 50"', 'path="l 0,50"', 'path="l -50,0"', 'path="l 0,-50"']],     # odd numbers
])
def test_a_malformed_mesh_paints_the_fallback(stops):
    img = raster.render(_doc([stops]))
    assert img[50, 50].tolist() == [0, 255, 0, 255]                 # fill="url(#m) lime"


def test_shared_corner_colour_comes_from_the_first_patch():
    """A stop colour given again for a shared corner is ignored."""
    p = _mesh_of(_doc([[['stop-color="red" path="l 40,0"', 'stop-color="blue" path="l 0,40"',
                         'stop-color="red" path="l -40,0"', 'stop-color="red" path="l 0,-40"'],
                        ['stop-color="yellow" path="l 40,0"', 'stop-color="red" path="l 0,40"',
                         'stop-color="red" path="l -40,0"']]]))
    assert p.shape == (1, 2)
    # the second patch's top-left corner is the first's top-right: blue
    assert p.colors[1, 0, :3].tolist() == [0, 0, 1]
