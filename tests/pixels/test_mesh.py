"""Golden-style tests of raster.pixels.mesh (SVG 2 mesh gradients).

No other renderer draws mesh gradients, so the references are computed here
from the specification's equations by dense sampling: every patch is
sampled on a (u, v) grid fine enough that samples lie less than half a
pixel apart, each sample is mapped by the Coons formula ``S = S_C + S_D -
S_B`` (written out below from the four boundary cubics) and coloured by
bilinear or bicubic interpolation (the bicubic derivative rules re-read
from SVG 2 here, scalar by scalar); a pixel takes the sample that lands in
it with the highest priority (later patch, then larger v, then larger u).
Renders and references are compared with raster.testing.compare_images,
the criterion of the conformance suite.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.pixels.canvas import Canvas
from raster.errors import LimitError
from raster.pixels import mesh as M
from raster.testing import compare_images


# -- the reference ---------------------------------------------------------------
def cubic(c, t):
    c = np.asarray(c, float)
    t = t[:, None]
    return ((1 - t) ** 3 * c[0] + 3 * t * (1 - t) ** 2 * c[1] + 3 * t ** 2 * (1 - t) * c[2]
            + t ** 3 * c[3])


def coons(b, u, v):
    """SVG 2: C1 top, C2 bottom, D1 left, D2 right; S = S_C + S_D - S_B."""
    C1, C2 = b[[0, 1, 2, 3]], b[[9, 8, 7, 6]]
    D1, D2 = b[[0, 11, 10, 9]], b[[3, 4, 5, 6]]
    uu, vv = u[:, None], v[:, None]
    sc = (1 - vv) * cubic(C1, u) + vv * cubic(C2, u)
    sd = (1 - uu) * cubic(D1, v) + uu * cubic(D2, v)
    sb = ((1 - vv) * ((1 - uu) * b[0] + uu * b[3]) + vv * ((1 - uu) * b[9] + uu * b[6]))
    return sc + sd - sb


def spec_slopes(p, c):
    """SVG 2 monotone derivatives along one line of corners (one channel)."""
    n = len(p) - 1
    d = [0.0] * (n + 1)
    sec = []
    for k in range(n):
        dist = math.hypot(*(np.asarray(p[k + 1]) - np.asarray(p[k])))
        sec.append(0.0 if dist == 0 else (c[k + 1] - c[k]) / dist)
    if n == 1:
        return [sec[0], sec[0]]
    for k in range(1, n):
        a, b = sec[k - 1], sec[k]
        x = (a + b) / 2
        if a * b < 0:
            x = 0.0
        else:
            if abs(x) > abs(3 * a):
                x = 3 * a
            if abs(x) > abs(3 * b):
                x = 3 * b
        d[k] = x
    d[0] = 2 * sec[0] - d[1]
    d[n] = 2 * sec[n - 1] - d[n - 1]
    return d


def hermite_cubic(f0, f1, d0, d1, t):
    return ((2 * t ** 3 - 3 * t ** 2 + 1) * f0 + (-2 * t ** 3 + 3 * t ** 2) * f1
            + (t ** 3 - 2 * t ** 2 + t) * d0 + (t ** 3 - t ** 2) * d1)


def reference_colours(patches, colors, interpolation, shape):
    """A function (patch, u, v) -> (N, 4) straight colours."""
    if interpolation == 'bilinear':
        def colour(k, u, v):
            c = colors[k]
            uu, vv = u[:, None], v[:, None]
            return ((1 - uu) * (1 - vv) * c[0] + uu * (1 - vv) * c[1] + uu * vv * c[2]
                    + (1 - uu) * vv * c[3])
        return colour
    rows, cols = shape
    G = np.zeros((rows + 1, cols + 1, 2))
    C = np.zeros((rows + 1, cols + 1, 4))
    for r in range(rows):
        for q in range(cols):
            b, c = patches[r * cols + q], colors[r * cols + q]
            for (dr, dq), (pi, ci) in (((0, 0), (0, 0)), ((0, 1), (3, 1)), ((1, 1), (6, 2)),
                                       ((1, 0), (9, 3))):
                G[r + dr, q + dq], C[r + dr, q + dq] = b[pi], c[ci]
    DX = np.zeros_like(C)
    DY = np.zeros_like(C)
    for ch in range(4):
        for r in range(rows + 1):
            DX[r, :, ch] = spec_slopes(G[r], C[r, :, ch])
        for q in range(cols + 1):
            DY[:, q, ch] = spec_slopes(G[:, q], C[:, q, ch])

    def colour(k, u, v):
        r, q = divmod(k, cols)
        lu0 = np.linalg.norm(G[r, q + 1] - G[r, q])
        lu1 = np.linalg.norm(G[r + 1, q + 1] - G[r + 1, q])
        lv0 = np.linalg.norm(G[r + 1, q] - G[r, q])
        lv1 = np.linalg.norm(G[r + 1, q + 1] - G[r, q + 1])
        out = np.zeros((len(u), 4))
        for ch in range(4):
            f = lambda a, b: C[r + b, q + a, ch]                          # noqa: E731
            fu = lambda a, b: DX[r + b, q + a, ch] * (lu0 if b == 0 else lu1)  # noqa: E731
            fv = lambda a, b: DY[r + b, q + a, ch] * (lv0 if a == 0 else lv1)  # noqa: E731
            # bicubic Hermite with zero cross derivatives: the tensor product of
            # the Hermite cubics in u (values and u-slopes along v = 0 and 1)
            # and in v
            h = [lambda t: 2 * t ** 3 - 3 * t ** 2 + 1, lambda t: -2 * t ** 3 + 3 * t ** 2,
                 lambda t: t ** 3 - 2 * t ** 2 + t, lambda t: t ** 3 - t ** 2]
            G4 = np.array([[f(0, 0), f(0, 1), fv(0, 0), fv(0, 1)],
                           [f(1, 0), f(1, 1), fv(1, 0), fv(1, 1)],
                           [fu(0, 0), fu(0, 1), 0.0, 0.0],
                           [fu(1, 0), fu(1, 1), 0.0, 0.0]])
            Hu = np.stack([hf(u) for hf in h], 1)
            Hv = np.stack([hf(v) for hf in h], 1)
            out[:, ch] = np.einsum('ka,ab,kb->k', Hu, G4, Hv)
        return out
    return colour


def reference(patches, colors, window, interpolation='bilinear', shape=None, spacing=0.28,
              radius=0.2, flip=False):
    """Dense-sampling reference: (h, w, 4) uint8 straight RGBA.

    Samples lie at most ``spacing`` apart in device space (so every covered
    point is within ``spacing / sqrt 2`` of one); a pixel takes, among the
    samples within ``radius`` of its centre, the one of the highest
    priority.  ``flip`` puts the smaller v on top instead (to show that the
    comparison can tell)."""
    patches = np.asarray(patches, float)
    colors = np.asarray(colors, float)
    x0, y0, w, h = window
    colour = reference_colours(patches, colors, interpolation, shape)
    best = np.full(h * w, -1)
    rgba = np.zeros((h * w, 4))
    for k, b in enumerate(patches):
        s = np.linspace(0, 1, 101)
        U, V = np.meshgrid(s, s, indexing='ij')
        pts = coons(b, U.ravel(), V.ravel()).reshape(101, 101, 2)
        step = max(np.linalg.norm(np.diff(pts, axis=0), axis=2).max(),
                   np.linalg.norm(np.diff(pts, axis=1), axis=2).max()) * 100
        N = int(math.ceil(1.15 * step / spacing)) + 2
        s = np.linspace(0, 1, N)
        U, V = (a.ravel() for a in np.meshgrid(s, s, indexing='ij'))
        xy = coons(b, U, V)
        col = np.round(xy[:, 0] - x0 - 0.5).astype(np.int64)
        row = np.round(xy[:, 1] - y0 - 0.5).astype(np.int64)
        near = np.hypot(xy[:, 0] - (x0 + col + 0.5), xy[:, 1] - (y0 + row + 0.5)) <= radius
        ok = near & (col >= 0) & (col < w) & (row >= 0) & (row < h)
        pix = row[ok] * w + col[ok]
        # priority within the patch: larger v, then larger u (sorted
        # ascending, the last sample of a pixel wins); later patches
        # overwrite earlier ones
        Uo, Vo = U[ok], V[ok]
        order = np.lexsort((Uo, -Vo if flip else Vo))
        pix, Us, Vs = pix[order], Uo[order], Vo[order]
        srt = np.argsort(pix, kind='stable')
        ps = pix[srt]
        last_idx = srt[np.r_[ps[1:] != ps[:-1], True]] if len(ps) else srt
        rgba[pix[last_idx]] = colour(k, Us[last_idx], Vs[last_idx])
        best[pix[last_idx]] = k
    straight = np.clip(rgba, 0, 1)
    straight[best < 0] = 0
    pre = straight.copy()
    pre[:, :3] *= pre[:, 3:]
    c = Canvas(w, h)
    c.composite(pre.reshape(h, w, 4).astype(np.float32))
    return c.to_rgba8()


def ours(patches, colors, window, interpolation='bilinear', shape=None, tolerance=0.1):
    px = M.mesh_gradient(patches, colors, window, interpolation, shape, tolerance)
    c = Canvas(window[2], window[3])
    c.composite(px)
    return c.to_rgba8()


# -- test meshes -------------------------------------------------------------------
def cub(a, rel):
    a = np.asarray(a, float)
    return [a, a + rel[0], a + rel[1], a + rel[2]]


def svg2_example():
    """The annotated 2 x 2 mesh of SVG 2 (x = y = 50), colours as given."""
    A = np.array([50.0, 50.0])
    t = cub(A, [[25, -25], [75, 25], [100, 0]])
    r = cub(A + [100, 0], [[25, 25], [-25, 75], [0, 100]])
    b = cub(A + [100, 100], [[-25, 25], [-75, -25], [-100, 0]])
    lf = cub(A + [0, 100], [[-25, -25], [25, -75], [0, -100]])
    sh = lambda pts, d: [p + d for p in pts]                       # noqa: E731
    p1 = t[:3] + r[:3] + b[:3] + lf[:3]
    p2 = sh(t, [100, 0])[:3] + sh(r, [100, 0])[:3] + sh(b, [100, 0])[:3] + r[::-1][:3]
    p3 = b[::-1][:3] + sh(r, [0, 100])[:3] + sh(b, [0, 100])[:3] + sh(lf, [0, 100])[:3]
    p4 = (sh(b, [100, 0])[::-1][:3] + sh(r, [100, 100])[:3] + sh(b, [100, 100])[:3]
          + sh(r, [0, 100])[::-1][:3])
    lb, pu, rd = [0.68, 0.85, 0.9, 1.0], [0.5, 0.0, 0.5, 1.0], [1.0, 0.0, 0.0, 1.0]
    cols = [[lb, pu, rd, pu], [pu, lb, pu, rd], [pu, rd, pu, lb], [rd, pu, lb, pu]]
    return np.array([p1, p2, p3, p4]), np.array(cols)


def test_spec_example_bilinear():
    P, C = svg2_example()
    r = compare_images(ours(P, C, (0, 0, 300, 300)), reference(P, C, (0, 0, 300, 300)))
    assert r.passed, r


def test_spec_example_bicubic_and_the_test_can_fail():
    P, C = svg2_example()
    win = (0, 0, 300, 300)
    ref = reference(P, C, win, 'bicubic', (2, 2))
    got = ours(P, C, win, 'bicubic', (2, 2))
    r = compare_images(got, ref)
    assert r.passed, r
    # the bilinear render is visibly different from the bicubic reference
    assert not compare_images(ours(P, C, win), ref).passed


def test_folded_patch_larger_v_on_top():
    # the left and right edges run down to y = 140 and back up to the
    # bottom edge at y = 40: every column is folded, the strip 40 < y < 110
    # is covered twice, and the part with the larger v (going back up,
    # bluer) must be on top
    b = np.array([[10, 10], [40, 10], [70, 10], [100, 10], [100, 140], [100, 140], [100, 40],
                  [70, 40], [40, 40], [10, 40], [10, 140], [10, 140]], float)
    C = np.array([[[1, 0, 0, 1], [1, 0, 0, 1], [0, 0, 1, 1], [0, 0, 1, 1]]], float)
    win = (0, 0, 110, 125)
    got = ours([b], C, win)
    r = compare_images(got, reference([b], C, win))
    assert r.passed, r
    # with the smaller v on top the strip would look different
    flipped = reference([b], C, win, spacing=0.6, radius=0.5, flip=True)
    assert compare_images(got, flipped).bad_pct > 20


def test_later_patches_paint_over_earlier():
    sq = lambda x, y, s: np.array([[x, y], [x + s / 3, y], [x + 2 * s / 3, y], [x + s, y],  # noqa
                                   [x + s, y + s / 3], [x + s, y + 2 * s / 3], [x + s, y + s],
                                   [x + 2 * s / 3, y + s], [x + s / 3, y + s], [x, y + s],
                                   [x, y + 2 * s / 3], [x, y + s / 3]], float)
    P = np.stack([sq(5, 5, 60), sq(35, 35, 60)])
    red, green = [1, 0, 0, 1], [0, 1, 0, 1]
    C = np.array([[red] * 4, [green] * 4], float)
    px = M.mesh_gradient(P, C, (0, 0, 100, 100))
    assert px[50, 50].tolist() == [0, 1, 0, 1]              # overlap: the later (green)
    assert px[20, 20].tolist() == [1, 0, 0, 1]
    assert px[2, 2].tolist() == [0, 0, 0, 0]                 # uncovered: transparent
    r = compare_images(ours(P[::-1], C[::-1], (0, 0, 100, 100)),
                       reference(P[::-1], C[::-1], (0, 0, 100, 100)))
    assert r.passed, r


def conic_mesh():
    """1 x 4 mesh simulating a conic gradient: each patch a quarter disc
    with a zero-length bottom edge at the centre (SVG 2 example)."""
    c = np.array([100.0, 100.0])
    R, k = 80.0, 0.5522847498
    patches, cols = [], []
    hues = [[1, 0, 0, 1], [1, 1, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [1, 0, 0, 1]]
    for q in range(4):
        a0, a1 = q * math.pi / 2, (q + 1) * math.pi / 2
        p0 = c + R * np.array([math.cos(a0), math.sin(a0)])
        p3 = c + R * np.array([math.cos(a1), math.sin(a1)])
        t0 = R * k * np.array([-math.sin(a0), math.cos(a0)])
        t1 = R * k * np.array([-math.sin(a1), math.cos(a1)])
        top = [p0, p0 + t0, p3 - t1, p3]
        right = list(np.linspace(p3, c, 4))
        bottom = [c, c, c, c]
        left = list(np.linspace(c, p0, 4))
        patches.append(top[:3] + right[:3] + bottom[:3] + left[:3])
        cols.append([hues[q], hues[q + 1], hues[q + 1], hues[q]])
    return np.array(patches), np.array(cols, float)


def test_conic_gradient_with_collapsed_edges():
    P, C = conic_mesh()
    win = (0, 0, 200, 200)
    r = compare_images(ours(P, C, win), reference(P, C, win))
    assert r.passed, r


def test_transparency_and_window_offset():
    P, C = svg2_example()
    C = C.copy()
    C[..., 3] = [[1.0, 0.2, 0.6, 0.0], [0.2, 1.0, 0.0, 0.6], [0.2, 0.6, 0.0, 1.0],
                 [0.6, 0.0, 1.0, 0.2]]
    win = (120, 20, 170, 140)             # partly outside the mesh
    for kind in ('bilinear', 'bicubic'):
        r = compare_images(ours(P, C, win, kind, (2, 2)), reference(P, C, win, kind, (2, 2)))
        assert r.passed, (kind, r)
    px = M.mesh_gradient(P, C, win)
    assert px.dtype == np.float32 and px.shape == (140, 170, 4)
    assert np.all(px[..., :3] <= px[..., 3:] + 1e-6)          # premultiplied


def test_bicubic_slopes_follow_the_spec_rules():
    p = [[0, 0], [1, 0], [2, 0], [3, 0], [4, 0]]
    c = [0.0, 1.0, 0.5, 0.5, 2.0]
    got = M.bicubic_slopes([p], [[[x] for x in c]])[0, :, 0]
    np.testing.assert_allclose(got, spec_slopes(p, c))
    # an extremum gets slope 0, a flat secant limits the neighbour to 0
    assert got[1] == 0 and got[2] == 0 and got[3] == 0
    # a linear ramp keeps its slope everywhere (bicubic reproduces it)
    lin = M.bicubic_slopes([p], [[[0.25 * k] for k in range(5)]])[0, :, 0]
    np.testing.assert_allclose(lin, 0.25)


def test_bicubic_reproduces_a_linear_ramp():
    P, _ = svg2_example()
    g, _ = M.corner_grid(P, np.zeros((4, 4, 4)), (2, 2))
    # colours linear in the corner's x: bicubic equals bilinear on a
    # rectangular grid with straight edges
    sq = []
    for r in range(2):
        for q in range(2):
            x, y = 10 + 50 * q, 10 + 50 * r
            sq.append([[x, y], [x + 50 / 3, y], [x + 100 / 3, y], [x + 50, y],
                       [x + 50, y + 50 / 3], [x + 50, y + 100 / 3], [x + 50, y + 50],
                       [x + 100 / 3, y + 50], [x + 50 / 3, y + 50], [x, y + 50],
                       [x, y + 100 / 3], [x, y + 50 / 3]])
    sq = np.array(sq, float)
    C = np.zeros((4, 4, 4))
    C[..., 3] = 1
    for k, b in enumerate(sq):
        C[k, :, 0] = (b[[0, 3, 6, 9], 0] - 10) / 100
    a = M.mesh_gradient(sq, C, (0, 0, 120, 120), 'bicubic', (2, 2))
    b = M.mesh_gradient(sq, C, (0, 0, 120, 120), 'bilinear')
    np.testing.assert_allclose(a, b, atol=2e-6)


@settings(max_examples=8, deadline=None)
@given(st.integers(0, 2 ** 31), st.floats(0.05, 1.0))
def test_tolerance_is_honoured(seed, tol):
    # colours encode the parameters: r = u, g = v exactly (bilinear); every
    # painted pixel must show a patch point within `tol` of its centre, and
    # every centre deeper than `tol` inside the boundary must be painted
    # (the boundary has winding number 1, so the patch covers its inside;
    # it may also bulge out of it near sharp corners -- painting there is
    # right, and the first check covers it)
    rng = np.random.default_rng(seed)
    s = 40.0
    base = np.array([[0, 0], [1, 0], [2, 0], [3, 0], [3, 1], [3, 2], [3, 3], [2, 3], [1, 3],
                     [0, 3], [0, 2], [0, 1]], float) * (s / 3) + 5
    b = base + rng.uniform(-0.18 * s, 0.18 * s, size=base.shape) * (np.arange(12) % 3 != 0)[:, None]
    b[[0, 3, 6, 9]] += rng.uniform(-0.1 * s, 0.1 * s, size=(4, 2))
    C = np.array([[[0, 0, 0, 1], [1, 0, 0, 1], [1, 1, 0, 1], [0, 1, 0, 1]]], float)
    W = 60
    px = M.mesh_gradient([b], C, (0, 0, W, W), tolerance=tol).astype(np.float64)
    painted = px[..., 3] > 0
    rows, cols = np.nonzero(painted)
    u, v = px[rows, cols, 0], px[rows, cols, 1]
    pts = coons(b, u, v)
    centre = np.stack([cols + 0.5, rows + 0.5], 1)
    err = np.linalg.norm(pts - centre, axis=1)
    assert err.max() <= tol + 1e-3
    # boundary polyline, distances and inside test of every centre
    t = np.linspace(0, 1, 200)
    poly = np.concatenate([cubic(b[[0, 1, 2, 3]], t), cubic(b[[3, 4, 5, 6]], t),
                           cubic(b[[6, 7, 8, 9]], t), cubic(b[[9, 10, 11, 0]], t)])
    yy, xx = np.mgrid[0:W, 0:W] + 0.5
    q = np.stack([xx.ravel(), yy.ravel()], 1)
    a, c = poly, np.roll(poly, -1, axis=0)
    d = c - a
    ll = np.maximum((d * d).sum(1), 1e-300)
    sp = np.clip(((q[:, None] - a) * d).sum(2) / ll, 0, 1)
    dist = np.linalg.norm(q[:, None] - (a + sp[..., None] * d), axis=2).min(1)
    cross = ((a[:, 1] > q[:, None, 1]) != (c[:, 1] > q[:, None, 1])) & (
        q[:, None, 0] < a[:, 0] + (q[:, None, 1] - a[:, 1]) * d[:, 0] / np.where(d[:, 1] == 0, 1, d[:, 1]))
    inside = cross.sum(1) % 2 == 1
    deep = (inside & (dist > tol + 0.02)).reshape(W, W)
    assert painted[deep].all()
    assert deep.sum() > 300


def test_zoomed_in_mesh_work_is_bounded():
    # a patch 10^6 px across seen through a 64 x 64 window: pieces outside
    # the window are dropped, so the cell count stays small
    P, C = svg2_example()
    big = (P - 100) * 1e4 + 100
    nets = M.P.mesh_patch_nets(big)
    pid, box, pn, nu, nv = M.mesh_cells(nets, 0.05, (100, 100, 64, 64))
    assert int((nu * nv).sum()) < 200_000
    px = M.mesh_gradient(big, C, (100, 100, 64, 64))
    assert (px[..., 3] > 0).all()


def test_errors():
    P, C = svg2_example()
    with pytest.raises(M.MeshError, match='shape'):
        M.mesh_gradient(P[:, :11], C, (0, 0, 10, 10))
    with pytest.raises(M.MeshError):
        M.mesh_gradient(P, C[:3], (0, 0, 10, 10))
    with pytest.raises(M.MeshError, match='needs the mesh shape'):
        M.mesh_gradient(P, C, (0, 0, 10, 10), 'bicubic')
    with pytest.raises(M.MeshError, match='does not hold'):
        M.mesh_gradient(P, C, (0, 0, 10, 10), 'bicubic', (3, 2))
    with pytest.raises(M.MeshError, match='bilinear or bicubic'):
        M.mesh_gradient(P, C, (0, 0, 10, 10), 'linear')
    with pytest.raises(M.MeshError, match='window'):
        M.mesh_gradient(P, C, (0, 0, 0, 10))
    with pytest.raises(M.MeshError, match='tolerance'):
        M.mesh_gradient(P, C, (0, 0, 10, 10), tolerance=0)
    bad = P.copy()
    bad[0, 0, 0] = np.nan
    with pytest.raises(M.MeshError, match='finite'):
        M.mesh_gradient(bad, C, (0, 0, 10, 10))
    with pytest.raises(LimitError, match='cells|pieces'):      # bounded work
        M.mesh_gradient(P * 50, C, (0, 0, 4000, 4000), tolerance=1e-5)
    with pytest.raises(LimitError, match='window'):
        M.mesh_gradient(P, C, (0, 0, 20_000, 20_000))
