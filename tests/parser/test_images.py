"""Tests of raster.parser.imageload: the SVG <image> element.

Decoding (PNG incl. 16-bit / palette / grey+alpha, JPEG, GIF, WebP) checked
pixel for pixel at 1:1 scale, preserveAspectRatio placements against
analytic rectangles, file access rules (relative paths, allowed
directories, symlinks, network URLs), broken data, nested and
self-referencing SVG images, limits, and the resvg suite's
structure/image cases compared with their reference renders."""

import base64
import io
import os
import struct
import urllib.parse
import warnings
import zlib

import numpy as np
import pytest

from raster import limits
from hypothesis import given, settings, strategies as hs
from PIL import Image

import raster
from raster.errors import RasterWarning
from raster.parser import imageload as image_mod
from raster.svg import load_svg
from raster.parser.imageload import (ImageError, ImageSource, decode_raster, fetch_image,
                              parse_data_uri, sniff)
from raster.tree import Group, ImageNode, walk
from raster.testing import compare_images

from _shared import SUITE_ROOT as SUITE, SUITE_TESTS
RED, BLUE, GREEN = (255, 0, 0, 255), (0, 0, 255, 255), (0, 128, 0, 255)


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------

def encode(arr_or_img, fmt='PNG', **kw):
    im = arr_or_img if isinstance(arr_or_img, Image.Image) else Image.fromarray(arr_or_img)
    buf = io.BytesIO()
    im.save(buf, fmt, **kw)
    return buf.getvalue()


def data_uri(data, mime='image/png'):
    return 'data:%s;base64,%s' % (mime, base64.b64encode(data).decode())


def doc(body, w=10, h=10, extra=''):
    return ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"'
            ' width="%s" height="%s" %s>%s</svg>' % (w, h, extra, body)).encode()


def render_quiet(src, **kw):
    with warnings.catch_warnings(record=True) as ws:
        warnings.simplefilter('always')
        out = raster.render(src, **kw)
    return out, [str(w.message) for w in ws if issubclass(w.category, RasterWarning)]


def tree_quiet(src, **kw):
    with warnings.catch_warnings(record=True) as ws:
        warnings.simplefilter('always')
        t = load_svg(src, **kw)
    return t, [str(w.message) for w in ws if issubclass(w.category, RasterWarning)]


def images(tree):
    return [(n, t) for n, t in walk(tree.root) if isinstance(n, ImageNode)]


def image_doc(href, w, h, attrs='', dw=None, dh=None):
    """A document of size dw x dh (default w x h) with one image at 0,0."""
    return doc('<image href="%s" %s/>' % (href, attrs), dw or w, dh or h)


def random_rgba(rng, h, w, alpha=True):
    a = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
    if alpha:
        a[..., 3] = rng.choice([0, 255], (h, w))
        a[a[..., 3] == 0] = 0          # fully transparent pixels have no colour
    else:
        a[..., 3] = 255
    return a


# ---------------------------------------------------------------------------
# data URIs and sniffing
# ---------------------------------------------------------------------------

def test_parse_data_uri_base64_with_whitespace_and_no_padding():
    payload = bytes(range(50))
    b64 = base64.b64encode(payload).decode().rstrip('=')
    wrapped = '\n  '.join(b64[i:i + 10] for i in range(0, len(b64), 10))
    assert parse_data_uri('data:image/png;base64,\n ' + wrapped) == ('image/png', payload)


def test_parse_data_uri_percent_encoded_and_params():
    svg = '<svg xmlns="http://www.w3.org/2000/svg"/>'
    href = 'data:image/svg+xml;charset=utf-8,' + urllib.parse.quote(svg)
    assert parse_data_uri(href) == ('image/svg+xml', svg.encode())


def test_parse_data_uri_without_comma_raises():
    with pytest.raises(ImageError):
        parse_data_uri('data:image/png;base64')


def test_sniff_signatures():
    rng = np.random.default_rng(1)
    a = random_rgba(rng, 3, 3, alpha=False)[..., :3]
    assert sniff(encode(a, 'PNG')) == 'png'
    assert sniff(encode(a, 'JPEG')) == 'jpeg'
    assert sniff(encode(a, 'GIF')) == 'gif'
    assert sniff(encode(a, 'WEBP', lossless=True)) == 'webp'
    assert sniff(b'\xef\xbb\xbf  <?xml version="1.0"?><svg/>') == 'svg'
    assert sniff(b'\x1f\x8b\x08\x00') == 'svg'
    assert sniff(b'hello') is None
    assert sniff(b'') is None


def test_declared_type_is_not_trusted():
    """A PNG declared as image/jpeg (and an SVG with no type) still works."""
    png = encode(np.full((2, 2, 3), 200, np.uint8))
    out, ws = render_quiet(image_doc(data_uri(png, 'image/jpeg'), 2, 2))
    assert not ws and (out[..., :3] == 200).all()
    svg = doc('<rect width="4" height="4" fill="blue"/>', 4, 4)
    out, ws = render_quiet(image_doc(data_uri(svg, ''), 4, 4))
    assert not ws and (out == BLUE).all()


# ---------------------------------------------------------------------------
# decoding: exact pixels at 1:1 scale
# ---------------------------------------------------------------------------

@pytest.mark.parametrize('fmt,kw', [('PNG', {}), ('WEBP', {'lossless': True})])
def test_lossless_rgba_exact_at_one_to_one(fmt, kw):
    rng = np.random.default_rng(7)
    a = random_rgba(rng, 5, 7)
    uri = data_uri(encode(a, fmt, **kw))
    out, ws = render_quiet(image_doc(uri, 7, 5, 'image-rendering="pixelated"'))
    assert not ws
    np.testing.assert_array_equal(out, a)


def test_png_partial_alpha_round_trips_within_one_level():
    rng = np.random.default_rng(8)
    a = rng.integers(0, 256, (4, 6, 4), dtype=np.uint8)
    a[..., 3] = rng.integers(128, 256, (4, 6))
    out, _ = render_quiet(image_doc(data_uri(encode(a)), 6, 4, 'image-rendering="pixelated"'))
    assert np.abs(out.astype(int) - a.astype(int)).max() <= 1


def test_jpeg_matches_pillow_decode():
    rng = np.random.default_rng(9)
    a = rng.integers(0, 256, (8, 8, 3), dtype=np.uint8)
    jpg = encode(a, 'JPEG', quality=90)
    ref = np.asarray(Image.open(io.BytesIO(jpg)).convert('RGBA'))
    out, ws = render_quiet(image_doc(data_uri(jpg, 'image/jpeg'), 8, 8,
                                     'image-rendering="optimizeSpeed"'))
    assert not ws
    np.testing.assert_array_equal(out, ref)


def test_jpeg_exif_orientation_is_ignored_like_resvg():
    a = np.zeros((2, 4, 3), np.uint8)
    a[:, :2] = (255, 0, 0)
    a[:, 2:] = (0, 0, 255)
    ex = Image.Exif()
    ex[0x0112] = 6          # "rotate 90 CW" when honoured
    pix = decode_raster(encode(a, 'JPEG', exif=ex.tobytes(), quality=100))
    assert pix.shape == (2, 4, 4)
    assert pix[0, 0, 0] > 200 and pix[0, 3, 2] > 200


def test_gif_first_frame_with_transparency():
    f1 = Image.new('P', (3, 2))
    f1.putpalette([255, 0, 0, 0, 0, 255, 0, 255, 0])
    f1.putdata([0, 1, 2, 0, 1, 2])
    f2 = Image.new('P', (3, 2))
    f2.putpalette([0, 255, 0] * 3)
    f2.putdata([0] * 6)
    buf = io.BytesIO()
    f1.save(buf, 'GIF', save_all=True, append_images=[f2], transparency=2, duration=100)
    out, ws = render_quiet(image_doc(data_uri(buf.getvalue(), 'image/gif'), 3, 2,
                                     'image-rendering="pixelated"'))
    assert not ws
    np.testing.assert_array_equal(out[0], [RED, BLUE, (0, 0, 0, 0)])


def test_png_16bit_grey_is_scaled_not_clipped():
    g = np.array([[0, 257 * 128, 65535, 257 * 3]], np.uint16)
    pix = decode_raster(encode(Image.fromarray(g)))
    assert pix[0, :, 0].tolist() == [0, 128, 255, 3]
    assert (pix[..., 3] == 255).all()


def test_png_palette_and_grey_transparency():
    p = Image.new('P', (2, 1))
    p.putpalette([255, 0, 0, 0, 255, 0])
    p.putdata([0, 1])
    assert decode_raster(encode(p, transparency=0)).tolist() == [[[255, 0, 0, 0],
                                                                   [0, 255, 0, 255]]]
    la = np.array([[[10, 20], [30, 255]]], np.uint8)
    assert decode_raster(encode(Image.fromarray(la, 'LA'))).tolist() == [[[10, 10, 10, 20],
                                                                           [30, 30, 30, 255]]]


def test_pixels_are_shared_and_read_only():
    uri = data_uri(encode(np.zeros((2, 2, 3), np.uint8)))
    t, _ = tree_quiet(doc('<image href="%s"/><image x="3" href="%s"/>' % (uri, uri)))
    (a, _), (b, _) = images(t)
    assert a.pixels is b.pixels
    assert not a.pixels.flags.writeable


@pytest.mark.parametrize('dx,dy', [(0, 0), (3, 2), (1, 5)])
def test_integer_translation_shifts_pixels_exactly(dx, dy):
    rng = np.random.default_rng(11)
    a = random_rgba(rng, 3, 4)
    uri = data_uri(encode(a))
    out, _ = render_quiet(doc('<image transform="translate(%d %d)" image-rendering="pixelated" '
                              'href="%s"/>' % (dx, dy, uri), 12, 12))
    np.testing.assert_array_equal(out[dy:dy + 3, dx:dx + 4], a)
    mask = np.ones((12, 12), bool)
    mask[dy:dy + 3, dx:dx + 4] = False
    assert (out[mask] == 0).all()


def test_scaled_nearest_neighbour_is_blocky():
    a = np.array([[RED, BLUE]], np.uint8)
    uri = data_uri(encode(a))
    out, _ = render_quiet(image_doc(uri, 40, 20, 'width="40" height="20" '
                                    'image-rendering="crisp-edges"'))
    assert (out[:, :20] == RED).all() and (out[:, 20:] == BLUE).all()
    smooth, _ = render_quiet(image_doc(uri, 40, 20, 'width="40" height="20"'))
    mid = smooth[10, 18:22, 0].astype(int)
    assert 0 < mid[1] < 255 and mid[0] > mid[3]      # bilinear ramp across the seam


@pytest.mark.parametrize('rendering', ['auto', 'pixelated'])
def test_mirrored_image_is_the_mirror_of_the_image(rendering):
    """scale(-1, 1) and scale(1, -1) about the image centre: the render is
    the plain render mirrored (magnified 2.5 times, both filters)."""
    rng = np.random.default_rng(12)
    uri = data_uri(encode(random_rgba(rng, 6, 8, alpha=False)))
    attrs = 'width="20" height="15" preserveAspectRatio="none" image-rendering="%s"' % rendering
    plain, _ = render_quiet(image_doc(uri, 20, 15, attrs))
    fx, _ = render_quiet(image_doc(uri, 20, 15, attrs + ' transform="matrix(-1 0 0 1 20 0)"'))
    fy, _ = render_quiet(image_doc(uri, 20, 15, attrs + ' transform="matrix(1 0 0 -1 0 15)"'))
    np.testing.assert_array_equal(fx, plain[:, ::-1])
    np.testing.assert_array_equal(fy, plain[::-1])


@pytest.mark.parametrize('transform', ['rotate(17 20 20)', 'translate(3.3 4.6) scale(3.7 2.1)',
                                       'translate(30 5) scale(-0.35 0.3)'])
def test_transformed_uniform_image_keeps_its_colour_to_the_edges(transform):
    """Edge pixels of a resampled image extend outwards: the anti-aliased
    border of a uniform image only fades, it never darkens."""
    a = np.zeros((9, 12, 4), np.uint8)
    a[:] = (40, 200, 120, 255)
    uri = data_uri(encode(a))
    out, _ = render_quiet(doc('<image x="5" y="6" transform="%s" href="%s"/>'
                              % (transform, uri), 40, 40))
    on = out[..., 3] > 0
    assert on.sum() > 5
    # an 8-bit premultiplied pixel of alpha a (levels) holds its colour c as
    # c a / 255 and a, each to half a level: demultiplied, c is known to
    # (c + 255) / (2 a) levels, at most 255 / a
    alpha = out[on][:, 3:].astype(float)
    err = np.abs(out[on][:, :3].astype(int) - (40, 200, 120))
    assert (err <= 2 + 255 / alpha).all()
    assert (err[alpha[:, 0] == 255] <= 2).all()


def test_image_rendering_flags():
    uri = data_uri(encode(np.zeros((1, 1, 3), np.uint8)))
    body = ''.join('<image image-rendering="%s" href="%s"/>' % (v, uri)
                   for v in ('auto', 'optimizeQuality', 'optimizeSpeed', 'pixelated',
                             'crisp-edges', 'smooth', 'high-quality'))
    body += '<g style="image-rendering: pixelated"><image href="%s"/></g>' % uri
    t, _ = tree_quiet(doc(body))
    assert [n.smooth for n, _ in images(t)] == [True, True, False, False, False, True, True,
                                                False]


# ---------------------------------------------------------------------------
# geometry: sizes and preserveAspectRatio
# ---------------------------------------------------------------------------

def two_colour_uri():
    """A 4x2 image: columns 0-1 red, 2-3 blue."""
    a = np.zeros((2, 4, 4), np.uint8)
    a[:, :2] = RED
    a[:, 2:] = BLUE
    return data_uri(encode(a))


@pytest.mark.parametrize('ax', ['Min', 'Mid', 'Max'])
@pytest.mark.parametrize('ay', ['Min', 'Mid', 'Max'])
def test_meet_places_analytic_rectangle(ax, ay):
    """A 4x2 image in a 40x40 viewport at (10, 10): scale 10, a 40x20 band
    at y = 10 + {0, 10, 20} (the x alignment has no room to act)."""
    par = 'x%sY%s meet' % (ax, ay)
    src = doc('<image x="10" y="10" width="40" height="40" preserveAspectRatio="%s" '
              'image-rendering="pixelated" href="%s"/>' % (par, two_colour_uri()), 60, 60)
    out, _ = render_quiet(src)
    y0 = 10 + {'Min': 0, 'Mid': 10, 'Max': 20}[ay]
    alpha = out[..., 3]
    assert (alpha[y0:y0 + 20, 10:50] == 255).all()
    assert alpha.sum() == 255 * 40 * 20
    assert (out[y0:y0 + 20, 10:30] == RED).all() and (out[y0:y0 + 20, 30:50] == BLUE).all()
    t, _ = tree_quiet(src)
    (n, _), = images(t)
    assert n.clip is None and n.view_rect == (10, 10, 40, 40)
    assert (n.transform.a, n.transform.d, n.transform.e, n.transform.f) == (10, 10, 10, y0)


@pytest.mark.parametrize('ax,colours', [('Min', (RED, RED)), ('Mid', (RED, BLUE)),
                                        ('Max', (BLUE, BLUE))])
@pytest.mark.parametrize('ay', ['Min', 'Mid', 'Max'])
def test_slice_covers_viewport_and_clips(ax, ay, colours):
    """Slice: scale 20, the 80x40 image is cut to the viewport; which
    columns show depends on the x alignment only."""
    par = 'x%sY%s slice' % (ax, ay)
    src = doc('<image x="10" y="10" width="40" height="40" preserveAspectRatio="%s" '
              'image-rendering="pixelated" href="%s"/>' % (par, two_colour_uri()), 60, 60)
    out, _ = render_quiet(src)
    assert out[..., 3].sum() == 255 * 40 * 40
    assert (out[10:50, 10:30] == colours[0]).all() and (out[10:50, 30:50] == colours[1]).all()
    t, _ = tree_quiet(src)
    (n, _), = images(t)
    assert n.clip == (10, 10, 40, 40)


def test_none_stretches_to_viewport():
    src = doc('<image x="5" y="5" width="20" height="30" preserveAspectRatio="none" '
              'image-rendering="pixelated" href="%s"/>' % two_colour_uri(), 30, 40)
    out, _ = render_quiet(src)
    assert (out[5:35, 5:15] == RED).all() and (out[5:35, 15:25] == BLUE).all()
    assert out[..., 3].sum() == 255 * 20 * 30


@pytest.mark.parametrize('attrs,size', [('', (4, 2)), ('width="8"', (8, 4)),
                                        ('height="6"', (12, 6)),
                                        ('width="auto" height="auto"', (4, 2)),
                                        ('width="50%"', (10, 5))])
def test_auto_sizes_keep_the_intrinsic_aspect_ratio(attrs, size):
    t, _ = tree_quiet(doc('<image %s href="%s"/>' % (attrs, two_colour_uri()), 20, 20))
    (n, _), = images(t)
    assert n.view_rect[2:] == pytest.approx(size)


def test_svg_image_natural_size_is_used_for_auto():
    inner = doc('<rect width="30" height="10" fill="blue"/>', 30, 10)
    t, _ = tree_quiet(doc('<image y="2" height="5" href="%s"/>' % data_uri(inner, ''), 40, 40))
    (n, _), = images(t)
    assert n.view_rect == pytest.approx((0, 2, 15, 5))
    assert n.tree is not None and n.pixels is None


@pytest.mark.parametrize('attrs', ['width="0"', 'height="0"', 'width="-3"', 'display="none"',
                                   'visibility="hidden"', 'opacity="0"',
                                   'transform="scale(0)"', 'requiredExtensions="x"'])
def test_not_rendered_without_a_warning(attrs):
    t, ws = tree_quiet(doc('<image %s href="%s"/>' % (attrs, two_colour_uri())))
    assert images(t) == [] and ws == []


def test_zero_size_does_not_even_look_at_the_file():
    t, ws = tree_quiet(doc('<image width="0" height="5" href="no/such/file.png"/>'))
    assert ws == []


def test_opacity_is_folded_into_the_node_unless_a_layer_is_needed():
    uri = two_colour_uri()
    t, _ = tree_quiet(doc('<image opacity="0.5" href="%s"/>' % uri))
    assert isinstance(t.root.children[0], ImageNode)
    assert t.root.children[0].opacity == 0.5
    out, _ = render_quiet(doc('<image opacity="0.5" image-rendering="pixelated" href="%s"/>'
                              % uri))
    assert out[0, 0].tolist() == [255, 0, 0, 128]
    body = ('<clipPath id="c" clipPathUnits="objectBoundingBox"><rect width=".5" height="1"/>'
            '</clipPath><image clip-path="url(#c)" opacity="0.5" href="%s"/>' % uri)
    t, _ = tree_quiet(doc(body))
    g = t.root.children[0]
    assert isinstance(g, Group) and g.opacity == 0.5 and g.clip_path is not None
    out, _ = render_quiet(doc(body.replace('href=', 'image-rendering="pixelated" href=')))
    assert out[0, 1, 3] == 128 and out[0, 2, 3] == 0     # bbox units: the image's viewport


def test_href_wins_over_xlink_href():
    red = data_uri(encode(np.array([[RED]], np.uint8)))
    blue = data_uri(encode(np.array([[BLUE]], np.uint8)))
    out, _ = render_quiet(doc('<image href="%s" xlink:href="%s"/>' % (blue, red), 1, 1))
    assert out[0, 0].tolist() == list(BLUE)


def test_image_through_use_and_switch():
    uri = two_colour_uri()
    body = ('<defs><image id="i" href="%s"/></defs><use href="#i" x="2" y="3"/>'
            '<switch><image systemLanguage="xx" href="%s"/><image x="10" href="%s"/></switch>'
            % (uri, uri, uri))
    t, _ = tree_quiet(doc(body, 20, 20))
    origins = sorted(tuple(tr.apply(np.array([n.view_rect[:2]], float))[0].tolist())
                     for n, tr in images(t))
    assert origins == [(2.0, 3.0), (10.0, 0.0)]


@settings(max_examples=40, deadline=None)
@given(iw=hs.integers(1, 9), ih=hs.integers(1, 9),
       x=hs.floats(-50, 50), y=hs.floats(-50, 50),
       w=hs.floats(0.5, 100), h=hs.floats(0.5, 100),
       ax=hs.sampled_from(['Min', 'Mid', 'Max']), ay=hs.sampled_from(['Min', 'Mid', 'Max']),
       mode=hs.sampled_from(['meet', 'slice', 'none']))
def test_placement_properties(iw, ih, x, y, w, h, ax, ay, mode):
    """meet: the image lies inside the viewport touching both sides of one
    axis; slice: it covers the viewport and the clip is the viewport; none:
    it is the viewport."""
    uri = data_uri(encode(np.zeros((ih, iw, 3), np.uint8)))
    par = 'none' if mode == 'none' else 'x%sY%s %s' % (ax, ay, mode)
    t, _ = tree_quiet(doc('<image x="%r" y="%r" width="%r" height="%r" '
                          'preserveAspectRatio="%s" href="%s"/>' % (x, y, w, h, par, uri)))
    (n, _), = images(t)
    (x0, y0), (x1, y1) = n.transform.apply(np.array([[0.0, 0.0], [iw, ih]]))
    eps = 1e-9 * (1 + abs(x) + abs(y) + w + h)
    if mode == 'none':
        assert (x0, y0, x1, y1) == pytest.approx((x, y, x + w, y + h))
    elif mode == 'meet':
        assert x0 >= x - eps and y0 >= y - eps and x1 <= x + w + eps and y1 <= y + h + eps
        assert (abs(x1 - x0 - w) < eps) or (abs(y1 - y0 - h) < eps)
        assert (x1 - x0) * ih == pytest.approx((y1 - y0) * iw)
    else:
        assert x0 <= x + eps and y0 <= y + eps and x1 >= x + w - eps and y1 >= y + h - eps
        assert n.clip == pytest.approx((x, y, w, h))


# ---------------------------------------------------------------------------
# files and security
# ---------------------------------------------------------------------------

def write_png(path, colour=RED, size=(2, 2)):
    Image.new('RGBA', size, colour).save(path)


def test_relative_file_in_document_dir_and_below(tmp_path):
    (tmp_path / 'sub').mkdir()
    write_png(tmp_path / 'a.png', RED)
    write_png(tmp_path / 'sub' / 'b.png', BLUE)
    svg = tmp_path / 'doc.svg'
    svg.write_bytes(doc('<image href="a.png"/><image x="2" xlink:href="sub/b.png"/>', 4, 2))
    out, ws = render_quiet(str(svg))
    assert ws == []
    assert (out[:, :2] == RED).all() and (out[:, 2:] == BLUE).all()


def test_file_outside_the_document_dir_is_refused(tmp_path):
    (tmp_path / 'd').mkdir()
    write_png(tmp_path / 'outside.png')
    svg = tmp_path / 'd' / 'doc.svg'
    svg.write_bytes(doc('<image href="../outside.png"/><image x="2" href="%s"/>'
                        % (tmp_path / 'outside.png'), 4, 2))
    out, ws = render_quiet(str(svg))
    assert (out == 0).all()
    assert len(ws) == 2 and all('outside the allowed directories' in w for w in ws)
    # allowed once the directory is given as resources_dir (the CLI's --allow-dir)
    out, ws = render_quiet(str(svg), resources_dir=str(tmp_path))
    assert ws == [] and (out == RED).all()


def test_symlink_escaping_the_document_dir_is_refused(tmp_path):
    (tmp_path / 'd').mkdir()
    write_png(tmp_path / 'secret.png')
    os.symlink(tmp_path / 'secret.png', tmp_path / 'd' / 'link.png')
    svg = tmp_path / 'd' / 'doc.svg'
    svg.write_bytes(doc('<image href="link.png"/>', 2, 2))
    out, ws = render_quiet(str(svg))
    assert (out == 0).all() and any('outside the allowed' in w for w in ws)


def test_bytes_document_resolves_against_resources_dir(tmp_path):
    write_png(tmp_path / 'a.png', BLUE)
    src = doc('<image href="a.png"/>', 2, 2)
    out, ws = render_quiet(src)
    assert (out == 0).all() and any('no base directory' in w for w in ws)
    out, ws = render_quiet(src, resources_dir=str(tmp_path))
    assert ws == [] and (out == BLUE).all()


def test_missing_file_warns(tmp_path):
    svg = tmp_path / 'doc.svg'
    svg.write_bytes(doc('<image href="nope.png"/>', 2, 2))
    out, ws = render_quiet(str(svg))
    assert (out == 0).all() and len(ws) == 1 and 'not found' in ws[0]


@pytest.mark.parametrize('href', ['http://example.com/a.png', 'https://example.com/a.png',
                                  'HTTPS://example.com/a.svg', 'ftp://example.com/a.png',
                                  '//example.com/a.png', '\\\\server\\share\\a.png',
                                  'javascript:alert(1)',
                                  'file://otherhost/etc/a.png'])
def test_network_and_other_urls_are_refused(tmp_path, href):
    svg = tmp_path / 'doc.svg'
    svg.write_bytes(doc('<image width="2" height="2" href="%s"/>' % href, 2, 2))
    t, ws = tree_quiet(str(svg))
    assert images(t) == [] and len(ws) == 1
    if href.lower().startswith(('http', 'ftp', '//', '\\\\')):
        assert 'network image reference not fetched' in ws[0]


def test_file_url_inside_allowed_dir(tmp_path):
    write_png(tmp_path / 'a.png', BLUE)
    svg = tmp_path / 'doc.svg'
    svg.write_bytes(doc('<image href="%s"/>' % (tmp_path / 'a.png').as_uri(), 2, 2))
    out, ws = render_quiet(str(svg))
    assert ws == [] and (out == BLUE).all()


# ---------------------------------------------------------------------------
# broken data and limits
# ---------------------------------------------------------------------------

def fake_png_header(w, h):
    def chunk(kind, data):
        return (struct.pack('>I', len(data)) + kind + data
                + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff))
    ihdr = struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr)
            + chunk(b'IDAT', zlib.compress(b'\0' * 16)) + chunk(b'IEND', b''))


@pytest.mark.parametrize('href', [
    'data:image/png;base64,AAAA',
    'data:image/png;base64,' + base64.b64encode(encode(np.zeros((8, 8, 3), np.uint8))[:40])
    .decode(),
    'data:image/png;base64,' + base64.b64encode(fake_png_header(100000, 100000)).decode(),
    'data:image/png;base64',
    'data:text/plain,hello',
    'data:image/svg+xml,%3Csvg',
    'data:image/svg+xml,' + urllib.parse.quote('<html/>'),
])
def test_broken_or_unusable_data_warns_once_and_draws_nothing(href):
    t, ws = tree_quiet(doc('<image width="5" height="5" href="%s"/>' % href))
    assert images(t) == [] and len(ws) == 1


def test_pixel_limit():
    uri = data_uri(encode(np.zeros((4, 4, 3), np.uint8)))
    with limits.applied(max_image_pixels=15):
        t, ws = tree_quiet(doc('<image href="%s"/>' % uri))
    assert images(t) == [] and 'exceeds the limit' in ws[0] and 'max_image_pixels' in ws[0]
    t, ws = tree_quiet(doc('<image href="%s"/>' % uri))
    assert len(images(t)) == 1


def test_image_byte_limit():
    uri = data_uri(encode(np.zeros((4, 4, 3), np.uint8)))
    with limits.applied(max_image_bytes=20):
        t, ws = tree_quiet(doc('<image href="%s"/>' % uri))
    assert images(t) == [] and 'max_image_bytes' in ws[0]


@pytest.mark.parametrize('magic', [b'\x89PNG\r\n\x1a\n', b'\xff\xd8\xff', b'GIF89a',
                                   b'RIFF\0\0\0\0WEBP'])
def test_unidentified_image_message_has_no_object_repr(magic):
    # Pillow says "cannot identify image file <_io.BytesIO object at 0x...>"
    uri = 'data:image/png;base64,' + base64.b64encode(magic).decode()
    t, ws = tree_quiet(doc('<image width="5" height="5" href="%s"/>' % uri))
    assert images(t) == [] and len(ws) == 1
    assert 'cannot decode' in ws[0] and ' at 0x' not in ws[0] and 'BytesIO' not in ws[0]


def test_decompression_bomb_header_is_refused_before_decoding():
    with pytest.raises(ImageError, match='exceeds the'):
        decode_raster(fake_png_header(100000, 100000))


@settings(max_examples=50, deadline=None)
@given(hs.binary(max_size=64), hs.sampled_from([b'', b'\x89PNG\r\n\x1a\n', b'\xff\xd8\xff',
                                                 b'GIF89a', b'RIFF\0\0\0\0WEBP', b'<svg',
                                                 b'\x1f\x8b']))
def test_random_bytes_never_raise(tail, head):
    t, ws = tree_quiet(doc('<image width="4" height="4" href="%s"/>'
                           % data_uri(head + tail)))
    assert len(images(t)) <= 1


# ---------------------------------------------------------------------------
# SVG images
# ---------------------------------------------------------------------------

def test_embedded_svg_image_renders_at_viewport():
    inner = doc('<rect width="10" height="5" fill="blue"/><rect y="5" width="10" height="5" '
                'fill="red"/>', 10, 10)
    out, ws = render_quiet(doc('<image x="4" y="4" width="20" height="20" href="%s"/>'
                               % data_uri(inner, 'image/svg+xml'), 28, 28))
    assert ws == []
    assert (out[4:14, 4:24] == BLUE).all() and (out[14:24, 4:24] == RED).all()
    assert out[..., 3].sum() == 255 * 400


def test_svg_image_content_is_clipped_to_its_natural_box():
    inner = doc('<rect x="-5" y="-5" width="20" height="20" fill="blue"/>', 10, 10)
    out, _ = render_quiet(doc('<image x="5" y="5" href="%s"/>' % data_uri(inner), 20, 20))
    assert out[..., 3].sum() == 255 * 100 and (out[5:15, 5:15] == BLUE).all()


def test_gzipped_svg_image():
    inner = doc('<rect width="4" height="4" fill="blue"/>', 4, 4)
    out, ws = render_quiet(image_doc(data_uri(__import__('gzip').compress(inner),
                                              'image/svg+xml'), 4, 4))
    assert ws == [] and (out == BLUE).all()


def test_raster_image_inside_svg_image():
    png = data_uri(encode(np.array([[RED]], np.uint8)))
    inner = doc('<image width="4" height="4" href="%s"/>' % png, 4, 4)
    out, ws = render_quiet(image_doc(data_uri(inner, 'image/svg+xml'), 4, 4))
    assert ws == [] and (out == RED).all()


def test_svg_image_nesting_depth_is_limited():
    uri = data_uri(encode(np.array([[BLUE]], np.uint8)))
    for _ in range(image_mod.MAX_IMAGE_DEPTH + 2):
        uri = data_uri(doc('<image width="4" height="4" href="%s"/>' % uri, 4, 4), '')
    out, ws = render_quiet(image_doc(uri, 4, 4))
    assert (out == 0).all() and any('nested deeper' in w for w in ws)
    uri = data_uri(encode(np.array([[BLUE]], np.uint8)))
    for _ in range(image_mod.MAX_IMAGE_DEPTH):
        uri = data_uri(doc('<image width="4" height="4" href="%s"/>' % uri, 4, 4), '')
    out, ws = render_quiet(image_doc(uri, 4, 4))
    assert ws == [] and (out == BLUE).all()


def test_self_referencing_svg_image_terminates(tmp_path):
    svg = tmp_path / 'self.svg'
    svg.write_bytes(doc('<rect width="2" height="2" fill="blue"/>'
                        '<image x="2" y="2" width="8" height="8" href="self.svg"/>', 10, 10))
    out, ws = render_quiet(str(svg))
    # the document, and itself once inside; the third level is refused
    assert (out[0:2, 0:2] == BLUE).all()
    assert (out[2:4, 2:4, 2] > 0).all()
    assert (out[4:10, 4:10, 3] == 0).all()
    assert any('inside an SVG image refused' in w for w in ws)


def test_chain_of_svg_files_terminates(tmp_path):
    (tmp_path / 'a.svg').write_bytes(doc('<image width="10" height="10" href="b.svg"/>'))
    (tmp_path / 'b.svg').write_bytes(doc('<rect width="10" height="10" fill="red"/>'
                                         '<image width="10" height="10" href="a.svg"/>'))
    out, ws = render_quiet(str(tmp_path / 'a.svg'))
    assert (out == RED).all() and len(ws) == 1


def test_load_image_api(tmp_path):
    write_png(tmp_path / 'a.png', GREEN, (3, 2))
    src = ImageSource(str(tmp_path), (os.path.realpath(str(tmp_path)),), True)
    kind, pix = fetch_image('a.png', src)
    assert kind == 'png' and pix.shape == (2, 3, 4) and pix[0, 0].tolist() == list(GREEN)
    with pytest.raises(ImageError, match='network image reference not fetched'):
        fetch_image('https://example.com/a.png', src)
    with pytest.raises(ImageError, match='outside'):
        fetch_image('a.png', ImageSource(str(tmp_path), (), True))


# ---------------------------------------------------------------------------
# the resvg suite
# ---------------------------------------------------------------------------

SUITE_CASES = [
    'structure/image/' + n for n in (
        'embedded-16bit-png', 'embedded-jpeg-as-image-jpeg', 'embedded-jpeg-as-image-jpg',
        'embedded-png-luma', 'embedded-png', 'embedded-svg-without-mime', 'embedded-svg',
        'embedded-svgz', 'embedded-webp', 'external-gif', 'external-jpeg', 'external-png',
        'external-svg-with-transform', 'external-svg', 'external-svgz', 'external-webp',
        'float-size', 'image-with-float-size-scaling', 'nested-external-png',
        'no-height-non-square', 'no-height-on-svg', 'no-height', 'no-width-and-height',
        'no-width-on-svg', 'no-width', 'preserveAspectRatio=none-on-svg',
        'preserveAspectRatio=none', 'preserveAspectRatio=xMaxYMax-meet-on-svg',
        'preserveAspectRatio=xMaxYMax-meet', 'preserveAspectRatio=xMaxYMax-slice-on-svg',
        'preserveAspectRatio=xMaxYMax-slice', 'preserveAspectRatio=xMidYMid-meet-on-svg',
        'preserveAspectRatio=xMidYMid-meet', 'preserveAspectRatio=xMidYMid-slice-on-svg',
        'preserveAspectRatio=xMidYMid-slice', 'preserveAspectRatio=xMinYMin-meet-on-svg',
        'preserveAspectRatio=xMinYMin-meet', 'preserveAspectRatio=xMinYMin-slice-on-svg',
        'preserveAspectRatio=xMinYMin-slice', 'raster-image-and-size-with-odd-numbers',
        'recursive-1', 'recursive-2', 'url-to-png', 'zero-height', 'zero-width')
] + ['painting/image-rendering/' + n for n in ('high-quality', 'optimizeSpeed-on-SVG',
                                               'optimizeSpeed')]


@pytest.mark.parametrize('case', SUITE_CASES)
def test_resvg_suite_case(case):
    svg = os.path.join(SUITE_TESTS, case + '.svg')
    expected = np.asarray(Image.open(os.path.join(SUITE_TESTS, case + '.png')).convert('RGBA'))
    actual, _ = render_quiet(svg, width=300, resources_dir=os.path.join(SUITE, 'resources'))
    cmp = compare_images(expected, actual)
    assert cmp.passed, cmp.reason


def test_suite_list_covers_the_image_directory():
    names = {n[:-4] for n in os.listdir(os.path.join(SUITE_TESTS, 'structure', 'image'))
             if n.endswith('.svg')}
    assert {'structure/image/' + n for n in names} <= set(SUITE_CASES)


# ---------------------------------------------------------------------------
# tolerance of SVG images
# ---------------------------------------------------------------------------

def circle_error(tree, centre, radius):
    """Largest radial error (document px) of the circle inside the SVG image,
    sampled on its cubics; and the number of cubics."""
    from raster.tree import PathNode
    (img, t_img), = images(tree)
    (node, t_in), = [(n, t) for n, t in walk(img.tree.root) if isinstance(n, PathNode)]
    ctrl = node.path.segments().ctrl                        # (S, 4, 2) cubics
    u = np.linspace(0, 1, 65)[:, None, None]
    b = ((1 - u) ** 3 * ctrl[:, 0] + 3 * (1 - u) ** 2 * u * ctrl[:, 1]
         + 3 * (1 - u) * u ** 2 * ctrl[:, 2] + u ** 3 * ctrl[:, 3]).reshape(-1, 2)
    pts = (t_img @ img.transform @ t_in).apply(b)
    return np.abs(np.hypot(*(pts - centre).T) - radius).max(), len(ctrl)


@pytest.mark.parametrize('tol', [0.5, 0.1, 0.02])
def test_scaled_up_svg_image_honours_tolerance(tol):
    """A unit circle in a 2x2 SVG image drawn 10000 times larger: the
    circle's cubics stay within `tolerance` document pixels of the true
    circle of radius 10000 (four plain quarter cubics would be 2.7 px off)."""
    inner = doc('<circle cx="1" cy="1" r="1" fill="blue"/>', 2, 2)
    src = doc('<image width="20000" height="20000" href="%s"/>' % data_uri(inner), 20000, 20000)
    t, ws = tree_quiet(src, tolerance=tol)
    err, n = circle_error(t, (10000.0, 10000.0), 10000.0)
    assert ws == [] and err <= tol and n > 4


def test_unscaled_svg_image_is_built_once():
    inner = doc('<circle cx="1" cy="1" r="1" fill="blue"/>', 2, 2)
    uri = data_uri(inner)
    t, _ = tree_quiet(doc('<image width="2" height="2" href="%s"/>'
                          '<image x="3" width="1" height="1" href="%s"/>' % (uri, uri)))
    (a, _), (b, _) = images(t)
    assert a.tree is b.tree
