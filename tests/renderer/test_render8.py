"""Rendering onto an 8-bit canvas (``render_tree(..., dtype='uint8')``, what
``raster.render`` and ``rasterize`` use): the same picture as the float32
canvas within a level or two, in a fraction of the memory (layers, masks
and clip paths follow the canvas's storage or use one channel)."""

import glob
import os
import tracemalloc

import numpy as np
import pytest

import raster
from raster.svg import load_svg
from raster.renderer import render_tree

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = sorted(glob.glob(os.path.join(HERE, '..', '..', 'golden', 'cases', '*.svg')))


@pytest.mark.parametrize('path', CASES, ids=[os.path.basename(p)[:-4] for p in CASES])
def test_golden_cases_within_two_levels_of_float(path):
    tree = load_svg(path)
    a = render_tree(tree).to_rgba8(premultiplied=True).astype(int)
    b = render_tree(tree, dtype='uint8')
    assert b.data.dtype == np.uint8
    d = np.abs(a - b.to_rgba8(premultiplied=True))
    assert d.max() <= 2


def test_render_returns_the_8bit_picture():
    doc = (b'<svg xmlns="http://www.w3.org/2000/svg" width="30" height="20">'
           b'<rect width="30" height="20" fill="#336699" opacity="0.5"/></svg>')
    img = raster.render(doc)
    assert np.array_equal(img, render_tree(load_svg(doc), dtype='uint8').to_rgba8())
    # premultiplied 0x33 * 0.5 = 25.5 -> 26 levels, demultiplied 26 * 255 / 128 = 51.8
    assert img[5, 5].tolist() == [52, 0x66, 0x99, 128]
    exact = render_tree(load_svg(doc)).to_rgba8()
    assert np.abs(exact.astype(int) - img).max() == 1


LAYERED = '''<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">
<clipPath id="c"><circle cx="50%%" cy="50%%" r="45%%"/></clipPath>
<mask id="m"><rect width="100%%" height="100%%" fill="#ccc"/></mask>
<g clip-path="url(#c)" opacity="0.8"><g mask="url(#m)">
<rect width="100%%" height="100%%" fill="red"/><rect width="50%%" height="100%%" fill="blue"/>
</g></g></svg>'''


def peak_bytes(fn):
    fn()                                        # (warm: imports, caches)
    tracemalloc.start()
    try:
        out = fn()
        return out, tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_layers_masks_and_clips_take_a_quarter_of_the_memory():
    """Full-size group layers with a clip path and a mask, one inside the
    other: the 8-bit render's peak is under a third of the float32
    render's, at most 6 arrays of 4 bytes a pixel (the canvas, two layers,
    the mask's content, the coverage of a rectangle drawn into it and the
    fill's flags of that coverage), where float32 layers alone would take
    16 bytes a pixel each."""
    n = 600
    tree = load_svg((LAYERED % (n, n)).encode())
    c, peak8 = peak_bytes(lambda: render_tree(tree, dtype='uint8'))
    f, peak32 = peak_bytes(lambda: render_tree(tree))
    assert peak8 < peak32 / 3
    assert peak8 < 24 * n * n
    # (premultiplied: where the alpha is a level or two, straight colours
    # of the two differ by much more, as any demultiplied 8-bit colour)
    assert np.abs(f.to_rgba8(True).astype(int) - c.to_rgba8(True)).max() <= 2


SHADOW = '''<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">
<filter id="b" x="-10%%" y="-10%%" width="120%%" height="120%%"><feGaussianBlur stdDeviation="6"/></filter>
<rect x="20%%" y="20%%" width="60%%" height="60%%" fill="%s" filter="url(#b)"/></svg>'''


@pytest.mark.parametrize('colour', ['black', '#3366cc'])
def test_a_blurred_one_colour_layer_is_filtered_from_its_alpha(monkeypatch, colour):
    """An 8-bit layer painted in one colour (a shadow) is filtered from its
    alpha channel, never read as float32 RGBA (16 bytes a pixel): the same
    picture as the float32 render within two levels."""
    from raster.pixels.canvas import Canvas
    n = 300
    tree = load_svg((SHADOW % (n, n, colour)).encode())
    f = render_tree(tree)
    reads = []
    real = Canvas.read

    def read(self, *a):
        reads.append((self.dtype, self.width, self.height))
        return real(self, *a)
    monkeypatch.setattr(Canvas, 'read', read)
    c = render_tree(tree, dtype='uint8')
    assert reads == []
    assert np.abs(f.to_rgba8(True).astype(int) - c.to_rgba8(True)).max() <= 2
    assert c.data[n // 2, n // 2, 3] == 255 and c.data[2, 2, 3] == 0
    # a layer of two colours is read once
    doc = (SHADOW % (n, n, colour)).replace(
        '<rect x', '<g filter="url(#b)"><rect width="50%" height="50%" fill="red"/><rect x'
    ).replace(' filter="url(#b)"/></svg>', '/></g></svg>')
    reads.clear()
    render_tree(load_svg(doc.encode()), dtype='uint8')
    assert len(reads) == 1 and reads[0][0] == np.uint8
