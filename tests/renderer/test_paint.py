"""Tests of raster.renderer.paint: gradient colours, raster image resampling and
image sampling.

Gradients are checked against an independent float64 evaluation (the
projection onto the gradient vector, the two-point conical equation solved
per pixel, np.interp between stops); the colour lookup table against the
exact interpolation (within 1/255); images against a float64 bilinear /
nearest reference with clamped edges and against analytic pictures
(flips, quarter turns, uniform images with no dark fringe)."""

import math
import zlib

import numpy as np
import pytest
from hypothesis import given, settings, strategies as hs

from raster.pixels.canvas import Canvas
from raster.geometry.path import Path
from raster.pixels.scan import Mask
from raster.renderer import paint
from raster.renderer.paint import (color_lut, draw_pixels, gradient_colors, resample_window, sample,
                              stop_colors)
from raster.tree import GradientStop, ImageNode, LinearGradient, RadialGradient
from raster.geometry.transform import Affine

LEVEL = 1.0 / 255.0
SQUARE = Path.polygon([(0, 0), (10, 0), (10, 10), (0, 10)])


# ---------------------------------------------------------------------------
# references (float64, straightforward)
# ---------------------------------------------------------------------------

def ref_stop_colors(s, offs, cols):
    """Premultiplied (..., 4) float64 colours, offsets strictly increasing."""
    s = np.asarray(s, np.float64)
    out = np.stack([np.interp(s, offs, cols[:, k]) for k in range(4)], -1)
    out[..., :3] *= out[..., 3:4]
    return out


def ref_spread(s, mode):
    if mode == 'pad':
        return np.clip(s, 0, 1)
    if mode == 'repeat':
        return s - np.floor(s)
    m = np.mod(s, 2.0)
    return np.where(m > 1, 2 - m, m)


def ref_radial(p, x, y):
    """Largest s whose circle (centre focal + s (centre - focal), radius
    fr + s (r - fr) >= 0) passes through (x, y); NaN where there is none
    (outside the cone of a focal circle not inside the end circle: the
    gradient leaves such points transparent, SVG 2 and canvas)."""
    cdx, cdy, dr = p.cx - p.fx, p.cy - p.fy, p.r - p.fr
    px, py = x - p.fx, y - p.fy
    a = cdx ** 2 + cdy ** 2 - dr ** 2
    b = px * cdx + py * cdy + p.fr * dr
    c = px ** 2 + py ** 2 - p.fr ** 2
    disc = b * b - a * c
    sq = np.sqrt(np.maximum(disc, 0))
    roots = np.stack([(b + sq) / a, (b - sq) / a])
    ok = p.fr + roots * dr >= 0
    best = np.where(ok, roots, -np.inf).max(axis=0)
    return np.where((disc >= 0) & np.isfinite(best), best, np.nan)


def ref_gradient(p, mask, t):
    """Premultiplied float64 colours of a userSpaceOnUse gradient times the
    coverage, evaluated per pixel in float64."""
    h, w = mask.data.shape
    jj, ii = np.meshgrid(np.arange(w) + mask.x0 + 0.5, np.arange(h) + mask.y0 + 0.5)
    inv = (t @ p.transform).inverse()
    pts = inv.apply(np.stack([jj.ravel(), ii.ravel()], -1))
    x, y = pts[:, 0].reshape(h, w), pts[:, 1].reshape(h, w)
    if isinstance(p, LinearGradient):
        dx, dy = p.x2 - p.x1, p.y2 - p.y1
        s = ((x - p.x1) * dx + (y - p.y1) * dy) / (dx * dx + dy * dy)
    else:
        s = ref_radial(p, x, y)
    offs = np.array([st.offset for st in p.stops])
    cols = np.array([st.color for st in p.stops])
    inside = ~np.isnan(s)
    col = ref_stop_colors(ref_spread(np.where(inside, s, 0.0), p.spread), offs, cols)
    return col * (mask.data * inside)[..., None]


def ref_sample(img, u, v, smooth, wrap):
    """Bilinear / nearest in float64, one pixel at a time (small inputs)."""
    ih, iw = img.shape[:2]
    out = np.zeros(u.shape + (4,))

    def px(r, c):
        if wrap:
            return img[r % ih, c % iw]
        return img[min(max(r, 0), ih - 1), min(max(c, 0), iw - 1)]

    for idx in np.ndindex(u.shape):
        uu, vv = u[idx], v[idx]
        if not smooth:
            out[idx] = px(int(math.floor(vv)), int(math.floor(uu)))
            continue
        fu, fv = uu - 0.5, vv - 0.5
        c0, r0 = int(math.floor(fu)), int(math.floor(fv))
        au, av = fu - c0, fv - r0
        top = px(r0, c0) * (1 - au) + px(r0, c0 + 1) * au
        bot = px(r0 + 1, c0) * (1 - au) + px(r0 + 1, c0 + 1) * au
        out[idx] = top * (1 - av) + bot * av
    return out


def premul8(pix):
    """Premultiplied float64 in [0, 1] of straight uint8 RGBA, rounded to
    8 bits (the bilinear path works on these)."""
    p = pix.astype(np.int64)
    out = p.copy()
    out[..., :3] = (p[..., :3] * p[..., 3:4] + 127) // 255
    return out / 255.0


def premul(pix):
    """Premultiplied float64 in [0, 1] of straight uint8 RGBA, unrounded
    (the nearest path picks straight pixels and premultiplies in float)."""
    p = pix / 255.0
    p[..., :3] *= p[..., 3:4]
    return p


def random_stops(rng, k, hard=False):
    offs = np.sort(rng.random(k))
    if hard and k > 2:
        offs[1] = offs[2]
    return [GradientStop(float(o), tuple(rng.random(4))) for o in offs]


# ---------------------------------------------------------------------------
# stop colours and the lookup table
# ---------------------------------------------------------------------------

@given(hs.integers(0, 2 ** 31), hs.integers(2, 6))
@settings(max_examples=60, deadline=None)
def test_lookup_table_is_within_one_level_of_exact(seed, k):
    rng = np.random.default_rng(seed)
    offs = np.sort(rng.random(k))
    offs[0], offs[-1] = rng.choice([0.0, offs[0]]), rng.choice([1.0, offs[-1]])
    cols = rng.random((k, 4))
    lut = color_lut(offs, cols)
    s = rng.random(20000).astype(np.float32)
    s[:k] = offs                                    # the stops themselves too
    exact = ref_stop_colors(s, offs, cols)
    if lut is None:
        # only when a ramp is too steep for the largest table
        span = np.diff(offs).min()
        assert span < 255 * 2 / paint._LUT_MAX
        return
    assert lut.dtype == np.float32 and paint._LUT_MIN <= len(lut) <= paint._LUT_MAX
    got = stop_colors(s, offs, cols, exact=False)
    assert np.abs(got - exact).max() <= LEVEL


def test_steep_ramps_get_bigger_tables_then_exact():
    cols = np.array([[0, 0, 0, 1], [0.4, 0.4, 0.4, 1.0], [0, 0, 0, 1]])
    sizes = [len(color_lut(np.array([0.0, d, 1.0]), cols)) for d in (0.5, 0.1, 0.05)]
    assert sizes[0] == paint._LUT_MIN and sizes[0] < sizes[1] < sizes[2]
    offs = np.array([0.0, 0.5, 0.501])
    assert color_lut(offs, cols) is None
    s = np.linspace(0.49, 0.502, 1001, dtype=np.float32)
    got = stop_colors(s, offs, cols)                       # falls back to exact
    assert np.abs(got - ref_stop_colors(s, offs, cols)).max() < 1e-5
    with pytest.raises(ValueError):
        stop_colors(s, offs, cols, exact=False)


@given(hs.integers(0, 2 ** 31))
@settings(max_examples=40, deadline=None)
def test_two_stops_are_exact_with_coverage(seed):
    """One ramp (any offsets, translucent colours) is evaluated in closed
    form: to float32 rounding (magnified by the ramp's steepness, since
    (s - o0) / (o1 - o0) is computed in float32), also times a coverage,
    and to float64 rounding in float64."""
    rng = np.random.default_rng(seed)
    offs = np.sort(rng.random(2))
    offs[0] *= rng.choice([0.0, 1.0])
    cols = rng.random((2, 4))
    s = rng.random(5000)
    s[:4] = (0.0, offs[0], offs[1], 1.0)
    cover = rng.random(5000).astype(np.float32)
    # the reference at the float32 positions (a steep ramp magnifies the
    # rounding of s itself)
    s = s.astype(np.float32).astype(np.float64)
    ref = ref_stop_colors(s, offs, cols)
    steep = np.abs(cols[1] - cols[0]).max() / max(offs[1] - offs[0], 1e-12)
    tol = 2e-6 + 4 * np.finfo(np.float32).eps * steep
    got = stop_colors(s.astype(np.float32), offs, cols)
    assert got.dtype == np.float32 and np.abs(got - ref).max() < tol
    got = stop_colors(s.astype(np.float32), offs, cols, cover)
    assert np.abs(got - ref * cover[:, None]).max() < tol
    got = stop_colors(s, offs, cols, cover)
    assert got.dtype == np.float64 and np.abs(got - ref * cover[:, None]).max() < 1e-7


def test_hard_stop_jumps_exactly_at_the_shared_offset():
    red, blue, green, white = (1, 0, 0, 1), (0, 0, 1, 1), (0, 0.5, 0, 1), (1, 1, 1, 1)
    offs = np.array([0.0, 0.4, 0.4, 1.0])
    cols = np.array([red, blue, green, white], np.float64)
    assert color_lut(offs, cols) is None                   # a jump: exact path
    s = np.array([0.0, 0.2, np.nextafter(np.float32(0.4), 0), 0.4, 0.7, 1.0], np.float32)
    got = stop_colors(s, offs, cols)
    assert np.allclose(got[0], red) and np.allclose(got[1], (0.5, 0, 0.5, 1))
    assert np.allclose(got[2], blue, atol=1e-6)            # just before: the first
    assert np.allclose(got[3], green)                      # at the offset: the last
    assert np.allclose(got[4], (0.5, 0.75, 0.5, 1)) and np.allclose(got[5], white)
    # repeated first offset: s at it takes the first stop's colour (pad)
    got = stop_colors(np.array([0.0, 0.5], np.float32), np.array([0.0, 0.0, 1.0]),
                      np.array([red, blue, white], np.float64))
    assert np.allclose(got[0], red) and np.allclose(got[1], (0.5, 0.5, 1, 1))
    # repeated offsets of one colour do not jump: the table is fine
    assert color_lut(np.array([0.0, 0.5, 0.5, 1.0]),
                     np.array([red, blue, blue, white], np.float64)) is not None


def test_colours_interpolate_straight_then_premultiply():
    cols = np.array([[1, 0, 0, 1], [0, 0, 1, 0]], np.float64)   # red to transparent blue
    got = stop_colors(np.array([0.5], np.float32), np.array([0.0, 1.0]), cols)
    assert np.allclose(got[0], (0.25, 0, 0.25, 0.5), atol=LEVEL)


# ---------------------------------------------------------------------------
# gradient_colors
# ---------------------------------------------------------------------------

def random_gradient(rng, kind, spread, hard=False):
    stops = random_stops(rng, int(rng.integers(2, 6)), hard)
    tr = Affine(*(rng.normal(size=4) * 0.5 + [1, 0, 0, 1]), *rng.normal(size=2) * 5) \
        if rng.random() < 0.5 else Affine()
    if kind == 'linear':
        x1, y1, x2, y2 = rng.random(4) * 60
        return LinearGradient(x1, y1, x2, y2, stops, transform=tr, spread=spread)
    cx, cy, r = rng.random() * 60, rng.random() * 60, rng.random() * 40 + 2
    fx, fy, fr = cx, cy, 0.0
    if kind in ('focal', 'focal-fr'):
        ang, d = rng.random() * 2 * np.pi, rng.random() * 0.95 * r
        fx, fy = cx + d * np.cos(ang), cy + d * np.sin(ang)
    if kind == 'focal-fr':
        fr = rng.random() * 0.8 * r
    if kind == 'outside':
        fx, fy = cx + 1.5 * r, cy
    return RadialGradient(cx, cy, r, fx, fy, stops, fr, transform=tr, spread=spread)


@pytest.mark.parametrize('kind', ['linear', 'centred', 'focal', 'focal-fr', 'outside'])
@pytest.mark.parametrize('spread', ['pad', 'reflect', 'repeat'])
@pytest.mark.parametrize('sparse', [False, True])
def test_gradient_matches_float64_reference(kind, spread, sparse):
    # str hashes change from process to process: seed from the names' bytes
    rng = np.random.default_rng(zlib.crc32(repr((kind, spread, sparse)).encode()))
    for _ in range(6):
        p = random_gradient(rng, kind, spread)
        h, w = rng.integers(5, 70, 2)
        data = rng.random((h, w)).astype(np.float32)
        if sparse:
            data[data < 0.9] = 0                   # ~10 % nonzero: pixel by pixel
        else:
            data[data < 0.05] = 0
        mask = Mask(data, int(rng.integers(-5, 30)), int(rng.integers(-5, 30)))
        t = Affine.scale(rng.random() * 3 + 0.3)
        got = gradient_colors(p, mask, t)
        assert got.dtype == np.float32 and got.shape == (h, w, 4)
        ref = ref_gradient(p, mask, t)
        diff = np.abs(got - ref).max(axis=-1)
        # float32 geometry may move s by a hair: allow a stray pixel where
        # the parameter sits on a spread fold or the edge of the cone
        assert (diff > 1.5 * LEVEL).mean() <= 0.002, (p, diff.max())


@pytest.mark.parametrize('kind', ['linear', 'focal', 'outside'])
def test_sparse_and_dense_paths_agree(kind, monkeypatch):
    rng = np.random.default_rng(7)
    p = random_gradient(rng, kind, 'reflect', hard=True)
    data = rng.random((40, 50)).astype(np.float32)
    data[data < 0.85] = 0
    mask = Mask(data, 3, 4)
    t = Affine.scale(1.7)
    monkeypatch.setattr(paint, '_SPARSE', 0.0)
    dense = gradient_colors(p, mask, t)
    monkeypatch.setattr(paint, '_SPARSE', 1.0)
    sparse = gradient_colors(p, mask, t)
    assert np.all(sparse[data == 0] == 0)
    assert np.abs(dense - sparse).max() <= LEVEL


@pytest.mark.parametrize('spread', ['pad', 'reflect', 'repeat'])
def test_focal_point_outside_the_end_circle_leaves_outside_the_cone_transparent(spread):
    """End circle centred (0, 0), radius 1; focal point (3, 0): the cone's
    tangents from the focal point touch the circle at 19.47 degrees from
    the axis.  Points in the cone (towards the circle) are painted, points
    beside it, and behind the focal point, are transparent."""
    stops = [GradientStop(0.0, (1, 0, 0, 1)), GradientStop(1.0, (0, 0, 1, 1))]
    p = RadialGradient(0.0, 0.0, 1.0, 3.0, 0.0, stops, 0.0, spread=spread)
    mask = Mask(np.ones((80, 80), np.float32), -40, -40)
    got = gradient_colors(p, mask, Affine.scale(10.0))        # 10 px per unit

    def at(x, y):                                             # user units
        return got[int(y * 10) + 40, int(x * 10) + 40]
    half = math.degrees(math.asin(1 / 3))
    for ang in (0.0, 0.5 * half, 0.9 * half):                 # inside the cone
        d = 1.5
        x, y = 3 - d * math.cos(math.radians(ang)), d * math.sin(math.radians(ang))
        assert at(x, y)[3] == pytest.approx(1.0)
    for ang in (1.2 * half, 60.0, 120.0):                     # beside it
        d = 1.5
        x, y = 3 - d * math.cos(math.radians(ang)), d * math.sin(math.radians(ang))
        assert at(x, y)[3] == 0.0
    assert at(3.5, 0.05)[3] == 0.0                            # behind the apex
    assert at(-0.5, 0.0)[3] == pytest.approx(1.0)             # through the circle


def test_linear_gradient_analytic_ramp_and_spreads():
    """Black to white along x over device [10, 20]: pad, reflect, repeat."""
    stops = [GradientStop(0.0, (0, 0, 0, 1)), GradientStop(1.0, (1, 1, 1, 1))]
    mask = Mask(np.ones((2, 40), np.float32), 0, 0)
    x = np.arange(40) + 0.5
    s = (x - 10) / 10
    expect = {'pad': np.clip(s, 0, 1), 'repeat': s - np.floor(s),
              'reflect': np.abs(np.mod(s + 1, 2) - 1)}
    for spread, e in expect.items():
        p = LinearGradient(10, 0, 20, 0, stops, spread=spread)
        got = gradient_colors(p, mask, Affine())
        assert np.abs(got[0, :, 0] - e).max() <= LEVEL, spread
        assert np.all(got[..., 3] == 1) and np.array_equal(got[0], got[1])


def test_centred_radial_is_distance_over_radius():
    stops = [GradientStop(0.0, (1, 1, 1, 1)), GradientStop(1.0, (0, 0, 0, 1))]
    p = RadialGradient(20, 20, 16, 20, 20, stops)
    mask = Mask(np.ones((40, 40), np.float32), 0, 0)
    got = gradient_colors(p, mask, Affine())
    jj, ii = np.meshgrid(np.arange(40) + 0.5, np.arange(40) + 0.5)
    d = np.clip(np.hypot(jj - 20, ii - 20) / 16, 0, 1)
    assert np.abs(got[..., 0] - (1 - d)).max() <= LEVEL


def test_object_bounding_box_units_resolve_to_the_box():
    """objectBoundingBox units are resolved by the parser: the gradient
    vector (0, 0) -> (1, 0) of the box x 4..14 runs over x 4..14."""
    from raster.parser.servers import GradientServer, in_space
    stops = [GradientStop(0.0, (0, 0, 0, 1)), GradientStop(1.0, (1, 1, 1, 1))]
    server = GradientServer(LinearGradient(0, 0, 1, 0, stops), obb=True)
    p = in_space(server, Affine(), (4.0, 0.0, 10.0, 3.0))
    mask = Mask(np.ones((3, 20), np.float32), 0, 0)
    got = gradient_colors(p, mask, Affine())
    assert np.abs(got[1, :, 0] - np.clip((np.arange(20) + 0.5 - 4) / 10, 0, 1)).max() <= LEVEL
    assert in_space(server, Affine(), (4.0, 0.0, 10.0, 0.0)) is None   # no height: nothing


def test_single_stop_degenerate_vectors_and_empty_masks():
    one = [GradientStop(0.3, (1, 0, 0, 0.5))]
    two = [GradientStop(0.0, (1, 0, 0, 1)), GradientStop(1.0, (0, 0, 1, 0.5))]
    cov = np.full((3, 4), 0.5, np.float32)
    mask = Mask(cov, 0, 0)
    got = gradient_colors(LinearGradient(0, 0, 1, 0, one), mask, Affine())
    assert np.allclose(got, (0.25, 0, 0, 0.25))
    # zero-length vector / zero radius: the last stop
    got = gradient_colors(LinearGradient(1, 1, 1, 1, two), mask, Affine())
    assert np.allclose(got, (0, 0, 0.25, 0.25))
    got = gradient_colors(RadialGradient(1, 1, 0, 1, 1, two, 0.0), mask, Affine())
    assert np.allclose(got, (0, 0, 0.25, 0.25))
    empty = Mask(np.zeros((3, 4), np.float32), 0, 0)
    assert gradient_colors(LinearGradient(0, 0, 1, 0, two), empty, Affine()) is None
    assert gradient_colors(LinearGradient(0, 0, 1, 0, []), mask, Affine()) is None


def test_far_from_origin_keeps_float32_precision():
    """A window far out in device space with a gradient in big user
    coordinates: the separable terms are centred on the window."""
    stops = [GradientStop(0.0, (0, 0, 0, 1)), GradientStop(1.0, (1, 1, 1, 1))]
    p = RadialGradient(30000, 30000, 40, 30010, 30000, stops, 0.0)
    mask = Mask(np.ones((90, 90), np.float32), 29955, 29955)
    got = gradient_colors(p, mask, Affine())
    ref = ref_gradient(p, mask, Affine())
    assert np.abs(got - ref).max() <= 1.5 * LEVEL


# ---------------------------------------------------------------------------
# raster images
# ---------------------------------------------------------------------------

def random_image(rng, h, w, opaque=False):
    pix = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
    if opaque:
        pix[..., 3] = 255
    return pix


def window_coords(inv, x0, y0, w, h):
    jj, ii = np.meshgrid(np.arange(w) + x0 + 0.5, np.arange(h) + y0 + 0.5)
    uv = inv.apply(np.stack([jj.ravel(), ii.ravel()], -1))
    return uv[:, 0].reshape(h, w), uv[:, 1].reshape(h, w)


def test_identity_reproduces_premultiplied_pixels_exactly():
    rng = np.random.default_rng(1)
    pix = random_image(rng, 9, 13)
    for f, ref in (('nearest', premul(pix)), ('bilinear', premul8(pix))):
        got = resample_window(pix, Affine(), 0, 0, 13, 9, f)
        assert got.dtype == np.float32 and got.shape == (9, 13, 4)
        assert np.abs(got - ref).max() < 1e-6
        # an integer shift and a window crop
        got = resample_window(pix, Affine.translate(-3, -2), 5, 4, 6, 5, f)
        assert np.abs(got - ref[2:7, 2:8]).max() < 1e-6


def test_nearest_integer_upscale_is_pixel_replication():
    rng = np.random.default_rng(2)
    pix = random_image(rng, 5, 7)
    got = resample_window(pix, Affine.scale(1 / 3, 1 / 2), 0, 0, 21, 10, 'nearest')
    expect = np.repeat(np.repeat(premul(pix), 2, axis=0), 3, axis=1)
    assert np.abs(got - expect).max() < 1e-6


@pytest.mark.parametrize('name, t', [
    ('up', Affine(2.7, 0, 0, 3.1, 4.3, -2.2)),
    ('down', Affine(0.45, 0, 0, 0.6, 1.5, 2.0)),
    ('aniso', Affine(4.0, 0, 0, 0.7, 0, 0)),
    ('rotate', Affine.translate(20, 3) @ Affine.rotate(33) @ Affine.scale(1.8)),
    ('skew', Affine(2.0, 0.4, 0.9, 1.6, 1, 1)),
])
@pytest.mark.parametrize('f', ['bilinear', 'nearest'])
def test_resampling_matches_reference_with_clamped_edges(name, t, f):
    """Image -> device transform ``t``; the window reaches past the image on
    every side, where the edge pixels extend."""
    rng = np.random.default_rng(3)
    pix = random_image(rng, 11, 14)
    inv = t.inverse()
    corners = t.apply(np.array([[0, 0], [14, 0], [14, 11], [0, 11]], float))
    x0, y0 = (np.floor(corners.min(axis=0)) - 1).astype(int)
    x1, y1 = (np.ceil(corners.max(axis=0)) + 1).astype(int)
    w, h = x1 - x0, y1 - y0
    got = resample_window(pix, inv, x0, y0, w, h, f)
    u, v = window_coords(inv, x0, y0, w, h)
    ref = ref_sample(premul8(pix) if f == 'bilinear' else premul(pix), u, v, f == 'bilinear',
                     False)
    # inside the image rectangle grown by a device pixel (what draw_pixels
    # covers): 8-bit results, and nearest picks may differ where a centre
    # falls on a pixel boundary up to rounding
    near = (u > -1.5) & (u < 15.5) & (v > -1.5) & (v < 12.5)
    diff = np.abs(got - ref).max(axis=-1)[near]
    if f == 'bilinear':
        assert diff.max() <= 2 * LEVEL
    else:
        assert (diff > 1e-6).mean() < 0.01


def test_flips_and_quarter_turns_mirror_the_plain_result():
    rng = np.random.default_rng(4)
    pix = random_image(rng, 6, 9)
    w, h = 27, 18                                    # 3x scale, image fills the window
    plain = resample_window(pix, Affine.scale(1 / 3), 0, 0, w, h, 'bilinear')
    fx = resample_window(pix, (Affine(-3, 0, 0, 3, w, 0)).inverse(), 0, 0, w, h, 'bilinear')
    fy = resample_window(pix, (Affine(3, 0, 0, -3, 0, h)).inverse(), 0, 0, w, h, 'bilinear')
    assert np.array_equal(fx, plain[:, ::-1]) and np.array_equal(fy, plain[::-1])
    # a quarter turn: device (x, y) = (h - 3 v, 3 u); the window is h x w
    # (the two resampling passes run in the other order: 8-bit rounding
    # in between may differ by a level)
    quarter = resample_window(pix, Affine(0, 3, -3, 0, h, 0).inverse(), 0, 0, h, w, 'bilinear')
    assert np.abs(quarter - np.rot90(plain, -1)).max() <= 1.01 * LEVEL


def test_downscale_samples_at_pixel_centres_like_resvg():
    """Columns 1 mod 3 white, others black, drawn a third as wide: every
    device pixel centre lands on a white column (no area averaging)."""
    pix = np.zeros((4, 30, 4), np.uint8)
    pix[..., 3] = 255
    pix[:, 1::3, :3] = 255
    got = resample_window(pix, Affine.scale(3, 1), 0, 0, 10, 4, 'bilinear')
    assert np.all(got == 1)


def test_window_far_inside_a_big_image_converts_only_what_it_reads(monkeypatch):
    seen = []
    orig = paint._premultiply8

    def spy(rgba):
        seen.append(rgba.shape)
        return orig(rgba)

    monkeypatch.setattr(paint, '_premultiply8', spy)
    pix = np.zeros((2000, 3000, 4), np.uint8)
    pix[..., 3] = 128
    got = resample_window(pix, Affine.scale(0.5), 1000, 1000, 8, 6, 'bilinear')
    assert got.shape == (6, 8, 4)
    assert seen and seen[0][0] * seen[0][1] < 100


@pytest.mark.parametrize('t', [
    Affine(3.3, 0, 0, 2.1, 0.4, 0.7),
    Affine.translate(15, 2) @ Affine.rotate(27) @ Affine.scale(2.2, 1.3),
    Affine(0.23, 0, 0, 0.31, 0.6, 0.2),
    Affine(-1.7, 0, 0, 1.9, 40, 0.5),
])
@pytest.mark.parametrize('smooth', [True, False])
def test_uniform_image_has_no_dark_fringe(t, smooth):
    """A uniform translucent image: wherever anything is drawn, the straight
    colour is the image's; only the alpha fades at the anti-aliased edges."""
    pix = np.empty((10, 16, 4), np.uint8)
    pix[:] = (200, 40, 90, 180)
    c = Canvas(60, 50)
    draw_pixels(ImageNode(pixels=pix, transform=t, smooth=smooth), Affine(), c, 0.05)
    d = c.data
    a = d[..., 3]
    on = a > 2 / 255
    assert on.sum() >= 12
    straight = d[on][:, :3] / a[on][:, None]
    assert np.abs(straight * 255 - (200, 40, 90)).max() <= 1.5 * 255 / 180 * 2
    assert a.max() <= 180 / 255 + 1e-6
    # exact-area coverage: the total alpha is the image area times its alpha
    area = abs(t.a * t.d - t.b * t.c) * 16 * 10
    assert abs(a.sum() - area * 180 / 255) <= 0.01 * area


def test_clip_rectangle_is_anti_aliased_and_intersected():
    pix = np.full((10, 10, 4), 255, np.uint8)
    node = ImageNode(pixels=pix, transform=Affine.scale(2), clip=(0.5, 0.25, 4.0, 5.5))
    c = Canvas(30, 30)
    draw_pixels(node, Affine(), c, 0.05)
    a = c.data[..., 3]
    assert abs(a.sum() - 4.0 * 5.5) < 1e-3
    assert a[0, 1] == pytest.approx(0.75) and a[3, 0] == pytest.approx(0.5)


def _overlap_ref(lo, hi, n):
    """(n,) float64 length of [lo, hi] inside each unit pixel interval."""
    k = np.arange(n, dtype=np.float64)
    return np.clip(np.minimum(k + 1, hi) - np.maximum(k, lo), 0, 1)


def _draw_alpha(node, t, size, general=False):
    c = Canvas(*size)
    if general:     # force the box-sized path_coverage mask
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(paint, '_device_rect', lambda pts, t: None)
            draw_pixels(node, t, c, 0.05)
    else:
        draw_pixels(node, t, c, 0.05)
    return c.data[..., 3].astype(np.float64)


AXIS_ALIGNED = [
    Affine(2.37, 0, 0, 1.61, 3.29, 4.71),       # fractional position and scale
    Affine(-2.37, 0, 0, 1.61, 40.29, 4.71),     # flipped in x
    Affine(1.3, 0, 0, -2.9, 5.5, 37.13),        # flipped in y
    Affine(0, 1.7, 2.3, 0, 0.61, 1.37),         # axes swapped (quarter turn + flip)
    Affine(0, -1.7, 2.3, 0, 1.61, 30.37),       # a quarter turn
    Affine(0.31, 0, 0, 0.27, 10.6, 9.9),        # smaller than a pixel per image pixel
    Affine(3.0, 0, 0, 2.0, -6.5, -3.25),        # partly off the canvas
]


@pytest.mark.parametrize('t', AXIS_ALIGNED)
@pytest.mark.parametrize('clip', [None, (1.3, 0.6, 7.45, 6.2), (-3, -3, 40, 40)])
def test_axis_aligned_coverage_equals_path_coverage(t, clip):
    """The separable coverage of an axis-aligned image (and clip) rectangle
    is the exact-area coverage path_coverage gives it, up to float32
    rounding, over the same window."""
    rng = np.random.default_rng(11)
    pix = rng.integers(0, 256, (9, 13, 4), dtype=np.uint8)
    pix[..., 3] = 255
    node = ImageNode(pixels=pix, transform=Affine(), clip=clip, smooth=False)
    fast = _draw_alpha(node, t, (48, 44))
    slow = _draw_alpha(node, t, (48, 44), general=True)
    assert fast.any()
    np.testing.assert_allclose(fast, slow, rtol=4e-7, atol=1e-7)


@pytest.mark.parametrize('flip', [(1, 1), (-1, 1), (1, -1), (-1, -1)])
def test_clipped_image_alpha_is_the_area_of_the_intersection(flip):
    """An opaque image under a user-space transform with flips, clipped by
    a rectangle: each pixel's alpha is the area of the pixel inside both
    rectangles, the product of the x and y overlaps of their intersection."""
    sx, sy = 1.75 * flip[0], 1.4 * flip[1]
    ex, ey = (3.3 if sx > 0 else 3.3 + 1.75 * 12), (2.6 if sy > 0 else 2.6 + 1.4 * 10)
    t = Affine(sx, 0, 0, sy, ex, ey)
    pix = np.full((10, 12, 4), 255, np.uint8)
    clip = (2.2, 1.7, 7.3, 5.9)         # image pixels, before t
    node = ImageNode(pixels=pix, transform=Affine(), clip=clip)
    a = _draw_alpha(node, t, (30, 24))
    # the device rectangles: image [0, 12] x [0, 10] and the clip, mapped by t
    xs = sorted([ex, ex + sx * 12]), sorted([ex + sx * 2.2, ex + sx * 9.5])
    ys = sorted([ey, ey + sy * 10]), sorted([ey + sy * 1.7, ey + sy * 7.6])
    x0, x1 = max(xs[0][0], xs[1][0]), min(xs[0][1], xs[1][1])
    y0, y1 = max(ys[0][0], ys[1][0]), min(ys[0][1], ys[1][1])
    ref = _overlap_ref(y0, y1, 24)[:, None] * _overlap_ref(x0, x1, 30)[None, :]
    np.testing.assert_allclose(a, ref, atol=2e-6)
    assert abs(a.sum() - 7.3 * 5.9 * 1.75 * 1.4) < 1e-4


def test_image_rectangle_without_area_draws_nothing():
    pix = np.full((4, 4, 4), 255, np.uint8)
    c = Canvas(20, 20)
    draw_pixels(ImageNode(pixels=pix, transform=Affine(), clip=(1, 1, 0, 2)),
                Affine.scale(2), c, 0.05)
    draw_pixels(ImageNode(pixels=pix, transform=Affine(), clip=(12, 1, 3, 3)),
                Affine.scale(2), c, 0.05)     # the clip lies off the canvas
    assert not c.data.any()


# ---------------------------------------------------------------------------
# sample (the pattern path)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize('smooth', [True, False])
@pytest.mark.parametrize('wrap', [True, False])
def test_sample_matches_reference(smooth, wrap):
    rng = np.random.default_rng(5)
    for ih, iw in [(1, 1), (1, 5), (7, 4), (9, 13)]:
        img = rng.random((ih, iw, 4)).astype(np.float32)
        u = rng.normal(size=(6, 7)) * 12
        v = rng.normal(size=(6, 7)) * 12
        got = sample(img, u, v, smooth=smooth, wrap=wrap)
        assert got.dtype == np.float32 and got.shape == (6, 7, 4)
        assert np.abs(got - ref_sample(img, u, v, smooth, wrap)).max() < 1e-5


def test_sample_wraps_exactly_at_multiples_of_the_size():
    img = np.arange(5 * 4, dtype=np.float32).reshape(1, 5, 4)
    u = np.array([-10.0, -5.0, 0.0, 5.0, 10.0, 4.999999, -0.000001, 9.5])
    got = sample(img, u, np.full_like(u, 0.5), smooth=False, wrap=True)
    assert got[:, 0].tolist() == [0, 0, 0, 0, 0, 16, 16, 16]
    got = sample(img, u + 0.5, np.full_like(u, 0.5), smooth=True, wrap=True)
    assert np.allclose(got[:5, 0], 0) and np.allclose(got[7, 0], 8)   # 9.5 + .5: halfway 4 | 0


# ---------------------------------------------------------------------------
# sweep gradients
# ---------------------------------------------------------------------------

@pytest.mark.parametrize('transform', [Affine(), Affine.rotate(30, 20, 20),
                                       Affine.translate(3, -2) @ Affine.scale(1, -1)])
@pytest.mark.parametrize('spread', ['pad', 'repeat', 'reflect'])
def test_sweep_gradient_against_atan2(transform, spread):
    """The offset at a pixel centre is (atan2 angle in [0, 360) - start) /
    (end - start) in gradient space (the pixel mapped back through the
    transform), spread, then interpolated between the stops."""
    from raster.tree import SweepGradient
    stops = [GradientStop(0.0, (1, 0, 0, 1)), GradientStop(1.0, (0, 0, 1, 1))]
    p = SweepGradient(20, 20, 45.0, 225.0, stops, transform=transform, spread=spread)
    mask = Mask(np.ones((40, 40), np.float32), 0, 0)
    got = gradient_colors(p, mask, Affine())
    jj, ii = np.meshgrid(np.arange(40) + 0.5, np.arange(40) + 0.5)
    q = transform.inverse().apply(np.stack([jj.ravel(), ii.ravel()], 1))
    ang = np.degrees(np.arctan2(q[:, 1] - 20, q[:, 0] - 20)) % 360
    s = (ang - 45.0) / 180.0
    s = {'pad': np.clip(s, 0, 1), 'repeat': np.mod(s, 1),
         'reflect': np.abs(np.mod(s + 1, 2) - 1)}[spread].reshape(40, 40)
    # away from the seams (the angle wraps at 0 degrees; repeat jumps at
    # 225 degrees): 1 level
    far = np.abs(((ang.reshape(40, 40) + 180) % 360) - 180) > 2
    far &= np.abs(ang.reshape(40, 40) - 225) > 2 if spread == 'repeat' else far
    far &= np.hypot(*(q - 20).T).reshape(40, 40) > 2
    assert np.abs(got[..., 0] - (1 - s))[far].max() <= 2 * LEVEL
    assert np.abs(got[..., 2] - s)[far].max() <= 2 * LEVEL


def test_sweep_gradient_of_no_angle_is_its_last_stop():
    from raster.tree import SweepGradient
    stops = [GradientStop(0.0, (1, 0, 0, 1)), GradientStop(1.0, (0, 0, 1, 1))]
    mask = Mask(np.ones((4, 4), np.float32), 0, 0)
    got = gradient_colors(SweepGradient(2, 2, 90, 90, stops), mask, Affine())
    assert np.allclose(got, (0, 0, 1, 1))
