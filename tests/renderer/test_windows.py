"""Windows of a render (render_tree(window=...), raster.render(window=)):
a window equals that part of the whole image -- bit for bit for paths,
gradients, patterns, clip paths, masks, groups and most filters, within one
level of 255 where a blur's or the scan's float sums round differently at
another layer origin -- including effects that reach across the window's
border (blurs, offsets, shadows, morphology, feTile, lighting)."""

import math
import os

import numpy as np
import pytest

import raster
from raster.errors import CanvasError
from raster.renderer import MAX_WINDOWED_PIXELS, check_window, render_tree
from raster.renderer.filters import filter_margin
from raster.geometry.transform import Affine
from raster.svg import load_svg
from raster.tree import filter as F

from _shared import CORPUS, SUITE_TESTS

SVG = '<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">%s</svg>'

CASES = {
    'paths': '<rect x="10" y="10" width="100" height="60" fill="#336699" stroke="red" '
             'stroke-width="7"/><circle cx="100" cy="80" r="37" fill="green" opacity="0.6"/>'
             '<path d="M5 115 L155 5" stroke="black" stroke-width="0.5"/>',
    'part-covering': '<rect width="40" height="40" fill="orange"/>'
                     '<rect x="80" y="0" width="80" height="70" fill="#336699"/>'
                     '<rect x="0" y="50" width="160" height="70" fill="#993366" opacity="0.8"/>'
                     '<circle cx="80" cy="60" r="30" fill="green"/>',
    'gradient': '<defs><linearGradient id="g" x1="0" x2="1"><stop offset="0" stop-color="red"/>'
                '<stop offset="1" stop-color="blue"/></linearGradient><radialGradient id="r">'
                '<stop offset="0" stop-color="yellow"/><stop offset="1" stop-color="purple" '
                'stop-opacity="0.2"/></radialGradient></defs>'
                '<rect width="160" height="60" fill="url(#g)"/>'
                '<ellipse cx="80" cy="80" rx="70" ry="35" fill="url(#r)"/>',
    'pattern': '<defs><pattern id="p" width="13" height="9" patternUnits="userSpaceOnUse" '
               'patternTransform="rotate(20)"><circle cx="5" cy="4" r="4" fill="teal"/>'
               '</pattern></defs><rect x="3" y="3" width="150" height="110" fill="url(#p)"/>',
    'clip-mask': '<defs><clipPath id="c"><circle cx="80" cy="60" r="50"/></clipPath>'
                 '<mask id="m"><rect width="160" height="120" fill="white"/>'
                 '<circle cx="60" cy="50" r="25" fill="black"/></mask></defs>'
                 '<g clip-path="url(#c)" mask="url(#m)"><rect width="160" height="120" '
                 'fill="orange"/><path d="M0 0 L160 120" stroke="navy" stroke-width="9"/></g>',
    'blur': '<defs><filter id="f" x="-50%" y="-50%" width="200%" height="200%">'
            '<feGaussianBlur stdDeviation="6"/></filter></defs>'
            '<rect x="30" y="30" width="70" height="50" fill="crimson" filter="url(#f)"/>',
    'small-blur': '<defs><filter id="f"><feGaussianBlur stdDeviation="1.2 0.6"/></filter></defs>'
                  '<circle cx="80" cy="60" r="30" fill="blue" filter="url(#f)"/>',
    'shadow-offset': '<defs><filter id="f" x="-30%" y="-30%" width="180%" height="180%">'
                     '<feDropShadow dx="9" dy="-7" stdDeviation="3"/>'
                     '<feOffset dx="-11" dy="5"/></filter></defs>'
                     '<text x="20" y="70" font-size="40" fill="gold" filter="url(#f)">Ab</text>'
                     '<rect x="90" y="40" width="40" height="40" fill="purple" '
                     'filter="url(#f)"/>',
    'morphology': '<defs><filter id="f"><feMorphology radius="4 2" operator="dilate"/>'
                  '</filter></defs><path d="M20 20 L140 100 M20 100 L140 20" stroke="black" '
                  'stroke-width="3" filter="url(#f)"/>',
    'tile': '<defs><filter id="f" x="0" y="0" width="1" height="1">'
            '<feFlood flood-color="green" x="10" y="10" width="23" height="17" result="a"/>'
            '<feOffset dx="5" dy="3"/><feTile/></filter></defs>'
            '<rect x="5" y="5" width="150" height="110" filter="url(#f)"/>',
    'lighting': '<defs><radialGradient id="g" r="0.5"><stop offset="0.4" stop-color="white"/>'
                '<stop offset="1" stop-color="white" stop-opacity="0"/></radialGradient>'
                '<filter id="d" color-interpolation-filters="sRGB"><feDiffuseLighting '
                'surfaceScale="10"><feDistantLight azimuth="45" elevation="45"/>'
                '</feDiffuseLighting></filter><filter id="s"><feSpecularLighting '
                'in="SourceAlpha" surfaceScale="7" specularExponent="8" '
                'lighting-color="seagreen"><feSpotLight x="110" y="90" z="25" pointsAtX="60" '
                'pointsAtY="40" specularExponent="3" limitingConeAngle="40"/>'
                '</feSpecularLighting></filter></defs>'
                '<rect x="10" y="10" width="70" height="100" fill="url(#g)" filter="url(#d)"/>'
                '<ellipse cx="115" cy="60" rx="40" ry="50" fill="url(#g)" filter="url(#s)"/>',
    'nested': '<defs><filter id="f" x="-40%" y="-40%" width="180%" height="180%">'
              '<feGaussianBlur stdDeviation="3"/></filter></defs>'
              '<g opacity="0.7" filter="url(#f)"><g filter="url(#f)">'
              '<rect x="40" y="30" width="60" height="50" fill="teal"/></g>'
              '<circle cx="110" cy="80" r="20" fill="red"/></g>',
}


def windows(w, h, rng, n=3):
    """Cuts of a w x h image into a grid of random windows."""
    xs = sorted(set([0, w] + [int(v) for v in rng.integers(1, w, n)]))
    ys = sorted(set([0, h] + [int(v) for v in rng.integers(1, h, n)]))
    return [(x0, y0, x1, y1) for y0, y1 in zip(ys, ys[1:]) for x0, x1 in zip(xs, xs[1:])]


def assert_windows_equal(tree, tol, seed=0, **kw):
    full = render_tree(tree, dtype='uint8', **kw).to_rgba8()
    h, w = full.shape[:2]
    worst = 0
    for win in windows(w, h, np.random.default_rng(seed)):
        x0, y0, x1, y1 = win
        part = render_tree(tree, dtype='uint8', window=win, **kw).to_rgba8()
        assert part.shape == (y1 - y0, x1 - x0, 4)
        worst = max(worst, int(np.abs(part.astype(int) - full[y0:y1, x0:x1]).max()))
    assert worst <= tol, worst
    return full


@pytest.mark.parametrize('name', sorted(CASES))
def test_windows_equal_the_whole_render(name):
    tree = load_svg((SVG % CASES[name]).encode())
    full = assert_windows_equal(tree, 1, seed=len(name))
    assert full[..., 3].any()                    # the case draws something


@pytest.mark.parametrize('name', ['blur', 'shadow-offset', 'pattern', 'clip-mask', 'lighting'])
def test_windows_equal_the_whole_render_scaled(name):
    tree = load_svg((SVG % CASES[name]).encode())
    assert_windows_equal(tree, 1, seed=3, width=397)


def test_lighting_windows_of_the_resvg_suite_equal_the_whole_render():
    # feDiffuseLighting / feSpecularLighting with every light source: the
    # surface normal at a window's edge comes from the neighbouring pixels
    # (the layer reaches past the window) and the bump map's gradient
    # colours are those of the whole render (each pixel's paint position
    # rounded once), so surfaceScale has no rounding difference to magnify
    import glob
    files = sorted(f for d in ('feDiffuseLighting', 'feSpecularLighting', 'feDistantLight',
                               'fePointLight', 'feSpotLight')
                   for f in glob.glob(os.path.join(SUITE_TESTS, 'filters', d, '*.svg')))
    assert len(files) > 30
    drawn = 0
    for f in files:
        try:
            tree = load_svg(f)
        except raster.errors.RasterError:
            continue
        full = assert_windows_equal(tree, 1, seed=len(f))
        drawn += bool(full[..., 3].any())
    assert drawn > 30


def test_blur_windows_are_exact_where_the_window_is_far_from_content():
    # a window of a region the blur does not reach is transparent, and a
    # window that only the blur's tail reaches still gets that tail
    tree = load_svg((SVG % CASES['blur']).encode())
    full = render_tree(tree, dtype='uint8').to_rgba8()
    tail = render_tree(tree, dtype='uint8', window=(101, 30, 120, 80)).to_rgba8()
    assert tail[..., 3].any()
    assert np.array_equal(tail, full[30:80, 101:120])


@pytest.mark.parametrize('name', ['tango_paper_sheet_inkscape.svg',
                                  'tango_input_keyboard_inkscape.svg'])
def test_corpus_windows_are_exact(name):
    # Inkscape's blurred shadows and gradients: strips and tiles of 600 px
    # renders equal the whole render bit for bit
    tree = load_svg(os.path.join(CORPUS, name))
    assert_windows_equal(tree, 0, seed=1, width=600)


def test_corpus_windows_of_curved_strokes_equal_the_whole_render():
    # the tiger's curved fills and strokes: every outline is flattened and
    # stroked in the whole output's pixels whatever the window (a window
    # moves the edges by whole pixels only), so windows equal the whole
    # render within one level (a sum of coverage started at another column)
    tree = load_svg(os.path.join(CORPUS, 'tiger.svg'))
    assert_windows_equal(tree, 1, seed=1, width=600)
    assert_windows_equal(tree, 1, seed=5, width=457)


def test_flattening_is_done_in_the_whole_outputs_pixels(monkeypatch):
    # the transforms the renderer flattens with are those of the whole
    # render, never translated by the window's corner
    from raster.renderer import batch
    seen = {'whole': set(), 'window': set()}
    real = batch.flatten_joined

    def spy(paths, transforms, *a, **k):
        seen[mode].update(tuple(t) for t in (transforms or ()) if t is not None)
        return real(paths, transforms, *a, **k)
    monkeypatch.setattr(batch, 'flatten_joined', spy)
    tree = load_svg((SVG % CASES['paths']).encode())
    mode = 'whole'
    render_tree(tree, dtype='uint8')
    mode = 'window'
    render_tree(tree, dtype='uint8', window=(37, 21, 141, 97))
    assert seen['window'] and seen['window'] <= seen['whole']


def test_render_window_front_door():
    doc = (SVG % CASES['blur']).encode()
    full = raster.render(doc)
    part = raster.render(doc, window=(20, 10, 90, 70))
    assert np.array_equal(part, full[10:70, 20:90])


def test_a_window_of_an_output_beyond_max_pixels():
    # a 40000 x 30000 output (1200 M pixels) is refused whole but its
    # windows render, equal to the same place of a smaller render scaled
    doc = (SVG % '<rect x="40" y="30" width="80" height="60" fill="blue"/>').encode()
    tree = load_svg(doc)
    with pytest.raises(CanvasError):
        render_tree(tree, width=40000)
    px = render_tree(tree, width=40000, dtype='uint8',
                     window=(9990, 7490, 10010, 7510)).to_rgba8()
    # the rectangle's corner (40, 30) is at (10000, 7500) at 250x: inside
    # below-right of it, outside above-left
    assert px[15, 15].tolist() == [0, 0, 255, 255] and px[5, 5, 3] == 0
    assert 40000 * 30000 <= MAX_WINDOWED_PIXELS


@pytest.mark.parametrize('win', [(0, 0, 0, 5), (0, 0, 161, 10), (-1, 0, 5, 5), (3, 2, 1, 9),
                                 (0, 0, 1.5, 2), 'abcd', (1, 2, 3)])
def test_bad_windows_are_refused(win):
    with pytest.raises(CanvasError):
        check_window(win, 160, 120)
    with pytest.raises(CanvasError):
        raster.render((SVG % '').encode(), window=win)


def test_filter_margin_bounds_each_primitive():
    t = Affine.scale(3.0, 2.0)
    blur = F.Filter(region=None, primitives=[F.GaussianBlur(std_dev=(2.0, 5.0))])
    assert filter_margin([blur], t) == 4 * 10.0 + 4
    off = F.Filter(region=None, primitives=[F.Offset(dx=-4.0, dy=1.5)])
    assert filter_margin([off], t) == 12.0 + 3.0 + 1
    # chains add up; lists of filters too
    assert filter_margin([blur, off], t) == filter_margin([blur], t) + filter_margin([off], t)
    assert filter_margin([F.Filter(region=None, primitives=[F.Tile()])], t) is None
    wrap = F.ConvolveMatrix(kernel=np.ones((3, 3)), edge_mode=F.EdgeMode.WRAP)
    assert filter_margin([F.Filter(region=None, primitives=[wrap])], t) is None
    assert filter_margin([F.Filter(region=None, primitives=[F.Flood()])], t) == 0.0


def test_paths_outside_the_canvas_cover_nothing():
    # the culling of paths whose device box misses the canvas: a shape
    # wholly left of, above, and beside the window changes nothing
    inside = '<rect x="60" y="40" width="30" height="30" fill="red"/>'
    outside = ('<rect x="-300" y="40" width="100" height="30" fill="blue"/>'
               '<path d="M-50 -50 L-10 -50 L-10 -10 Z" fill="green" stroke="black"/>'
               '<rect x="500" y="500" width="10" height="10" fill="black"/>')
    a = raster.render((SVG % inside).encode())
    b = raster.render((SVG % (outside + inside)).encode())
    assert np.array_equal(a, b)
    win = raster.render((SVG % (outside + inside)).encode(), window=(55, 35, 95, 75))
    assert np.array_equal(win, a[35:75, 55:95])


def test_an_edge_store_keeps_outlines_across_windows_with_the_same_pixels():
    # tiles of the tiger drawn row by row with one EdgeStore: the outlines
    # crossing several tiles are flattened once (the store answers for
    # them) and the tiles still equal the whole render
    from raster.renderer import EdgeStore
    tree = load_svg(os.path.join(CORPUS, 'tiger.svg'))
    full = render_tree(tree, dtype='uint8', width=500).to_rgba8()
    store = EdgeStore()
    h, w = full.shape[:2]
    for y0 in range(0, h, 128):
        for x0 in range(0, w, 128):
            win = (x0, y0, min(w, x0 + 128), min(h, y0 + 128))
            part = render_tree(tree, dtype='uint8', width=500, window=win,
                               store=store).to_rgba8()
            assert np.array_equal(part, full[win[1]:win[3], win[0]:win[2]]), win
    assert store.hits > 50


def test_an_edge_store_serves_one_tree():
    # a store given another tree (or output size) forgets what it held
    from raster.renderer import EdgeStore
    a = load_svg((SVG % CASES['paths']).encode())
    b = load_svg((SVG % CASES['gradient']).encode())
    store = EdgeStore()
    render_tree(a, dtype='uint8', window=(0, 0, 160, 40), store=store)
    assert len(store) > 0
    want = render_tree(b, dtype='uint8').to_rgba8()[40:]
    got = render_tree(b, dtype='uint8', window=(0, 40, 160, 120), store=store).to_rgba8()
    assert np.array_equal(got, want)
    store.bind(a, Affine.scale(2.0), 0.05, 0)
    assert len(store) == 0


def _svg_image_doc(preserve='xMidYMid meet'):
    # an SVG document drawn as an image: curves, a blur reaching past the
    # window, a clipped group and a mask inside, the image placed off the
    # pixel grid, scaled and clipped to its viewport
    import base64
    inner = ('<svg xmlns="http://www.w3.org/2000/svg" width="50" height="40" '
             'viewBox="0 0 50 40"><defs><filter id="b" x="-50%" y="-50%" width="200%" '
             'height="200%"><feGaussianBlur stdDeviation="2.5"/></filter>'
             '<clipPath id="c"><circle cx="25" cy="20" r="15"/></clipPath>'
             '<mask id="m"><rect width="50" height="40" fill="white"/>'
             '<circle cx="30" cy="15" r="6" fill="black"/></mask></defs>'
             '<rect width="50" height="40" fill="#eef"/>'
             '<ellipse cx="18" cy="22" rx="12" ry="9" fill="crimson" filter="url(#b)"/>'
             '<g clip-path="url(#c)" mask="url(#m)"><path d="M0 40 C 20 -10 30 50 50 0" '
             'stroke="navy" stroke-width="4" fill="none"/></g></svg>')
    href = 'data:image/svg+xml;base64,' + base64.b64encode(inner.encode()).decode()
    return (SVG % ('<image x="13.3" y="9.7" width="117" height="93" '
                   'preserveAspectRatio="%s" href="%s"/>' % (preserve, href))).encode()


@pytest.mark.parametrize('preserve', ['xMidYMid meet', 'xMinYMin slice', 'none'])
def test_windows_of_a_nested_svg_image_equal_the_whole_render(preserve):
    tree = load_svg(_svg_image_doc(preserve))
    full = assert_windows_equal(tree, 1, seed=7, width=331)
    assert full[..., 3].any()
    # a window that cuts through the image and its blur
    part = render_tree(tree, dtype='uint8', width=331, window=(61, 47, 140, 130)).to_rgba8()
    assert np.abs(part.astype(int) - full[47:130, 61:140]).max() <= 1


def test_an_edge_store_holds_at_most_its_edges():
    # a store too small for any outline keeps none and changes no pixel
    from raster.renderer import EdgeStore
    tree = load_svg(os.path.join(CORPUS, 'tiger.svg'))
    full = render_tree(tree, dtype='uint8', width=300).to_rgba8()
    small, big = EdgeStore(max_edges=5), EdgeStore()
    for y0 in range(0, full.shape[0], 60):
        win = (0, y0, 300, min(full.shape[0], y0 + 60))
        for st in (small, big):
            part = render_tree(tree, dtype='uint8', width=300, window=win, store=st).to_rgba8()
            assert np.array_equal(part, full[win[1]:win[3]])
    assert len(small) == 0 and small.hits == 0 and big.hits > 0


def _long_paths_document(seed=0):
    """A stroke of 600 quadratics wandering all over the image, a filled 500-gon with a
    hairline and a dashed curve, each crossing the whole 240 x 200 image."""
    rng = np.random.default_rng(seed)
    # a random walk of small steps, folded back into the image
    p = np.cumsum(rng.normal(0, 4, (1201, 2)), axis=0) + (120, 100)
    p = 10 + np.abs((p - 10) % 440 - 220) * (1, 180 / 220)
    d = 'M %.2f %.2f ' % tuple(p[0]) + ' '.join(
        'Q %.2f %.2f %.2f %.2f' % (tuple(p[i]) + tuple(p[i + 1])) for i in range(1, 1201, 2))
    a = np.linspace(0, 2 * np.pi, 500, endpoint=False)
    r = 90 + 8 * np.sin(7 * a)
    poly = ' '.join('%.2f,%.2f' % (120 + r[i] * np.cos(a[i]), 100 + r[i] * 0.9 * np.sin(a[i]))
                    for i in range(500))
    body = ('<polygon points="%s" fill="#8ac" stroke="#024" stroke-width="0.4"/>' % poly
            + '<path d="%s" fill="none" stroke="#a40" stroke-width="3" stroke-linejoin="round"/>'
            % d + '<path d="M 5 100 C 80 -60 160 260 235 100" fill="none" stroke="black" '
            'stroke-width="4" stroke-dasharray="9 5" stroke-linecap="square"/>')
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="240" height="200">%s</svg>'
            % body).encode()


def test_a_window_outlines_only_the_segments_near_it(monkeypatch):
    # a strip flattens and strokes the segments that can reach it (the
    # others cut away: raster.geometry.culling), and draws the pixels of
    # the whole render
    from raster.renderer import batch
    verbs = []
    real_join, real_many = batch.flatten_joined, batch.stroke_many

    def join(paths, transforms, *a, **k):
        if transforms is not None:          # (not the stroke outlines)
            verbs.append(sum(len(p.verbs) for p in paths))
        return real_join(paths, transforms, *a, **k)

    def many(paths, *a, **k):
        verbs.append(sum(len(p.verbs) for p in paths))
        return real_many(paths, *a, **k)
    monkeypatch.setattr(batch, 'flatten_joined', join)
    monkeypatch.setattr(batch, 'stroke_many', many)
    tree = load_svg(_long_paths_document())
    full = render_tree(tree, dtype='uint8').to_rgba8()
    whole = sum(verbs)
    for win in [(0, y, 240, y + 25) for y in range(0, 200, 25)] + [(60, 50, 120, 90)]:
        del verbs[:]
        part = render_tree(tree, dtype='uint8', window=win).to_rgba8()
        assert np.array_equal(part, full[win[1]:win[3], win[0]:win[2]]), win
        assert sum(verbs) < 0.6 * whole, (win, sum(verbs), whole)


def test_strips_with_an_edge_store_cut_only_above_them():
    # with a store, outlines are kept for the windows below: a strip's cut
    # leaves everything from its top down, and the strips still equal the
    # whole render
    from raster.renderer import EdgeStore
    tree = load_svg(_long_paths_document(1))
    full = render_tree(tree, dtype='uint8').to_rgba8()
    store = EdgeStore()
    for y in range(0, 200, 40):
        part = render_tree(tree, dtype='uint8', window=(0, y, 240, y + 40),
                           store=store).to_rgba8()
        assert np.array_equal(part, full[y:y + 40]), y
    assert store.hits > 0
