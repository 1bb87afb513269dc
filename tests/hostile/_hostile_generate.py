"""Hostile inputs too large to keep in the repository, made on demand
(by tests/hostile/test_hostile.py).

Each function takes the directory to write into and returns the path of
the document it made, or ``(path, extra command-line arguments)``.
``tests/hostile/expected.json`` names them as ``"gen:<function>"``; the
``cases/`` directory holds the small inputs.
"""

import base64
import io
import os
import struct

NS = 'xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"'
#: What the rest of every document draws: a red square at the top left
#: (the test checks it is there when the case expects "drawn").
MARK = '<rect width="20" height="20" fill="red"/>'

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _write(d, name, text):
    p = os.path.join(d, name)
    with open(p, 'w' if isinstance(text, str) else 'wb') as f:
        f.write(text)
    return p


def convolve_order_1000(d):
    """feConvolveMatrix order="1000": a 10**6-entry kernel (2 MB)."""
    k = ' '.join(['1'] * 10 ** 6)
    return _write(d, 'convolve.svg', '<svg %s width="200" height="200"><filter id="f">'
                  '<feConvolveMatrix order="1000" kernelMatrix="%s"/></filter>'
                  '<rect width="200" height="200" fill="blue" filter="url(#f)"/>%s</svg>'
                  % (NS, k, MARK))


def use_opacity_copies(d):
    """10**4 use copies of a group with opacity (a layer each)."""
    uses = ''.join('<use href="#l" x="%d" y="%d"/>' % (i % 100, i // 100)
                   for i in range(10 ** 4))
    return _write(d, 'use_opacity.svg', '<svg %s width="200" height="200"><defs><g id="l" '
                  'opacity="0.5"><rect width="100" height="100" fill="blue"/><rect x="50" y="50" '
                  'width="100" height="100" fill="green"/></g></defs>%s%s</svg>'
                  % (NS, uses, MARK))


def use_blur_copies(d):
    """10**4 use copies of a blurred rectangle (a filter each)."""
    uses = ''.join('<use href="#r" x="%d" y="%d"/>' % (i % 100, i // 100)
                   for i in range(10 ** 4))
    return _write(d, 'use_blur.svg', '<svg %s width="200" height="200"><defs><filter id="b">'
                  '<feGaussianBlur stdDeviation="5"/></filter><rect id="r" width="100" '
                  'height="100" fill="blue" filter="url(#b)"/></defs>%s%s</svg>'
                  % (NS, uses, MARK))


def long_path(d):
    """One path of 3.75 million segments (7.5 MB of path data)."""
    return _write(d, 'long_path.svg', '<svg %s width="200" height="200"><path d="M0 0%s"/>%s'
                  '</svg>' % (NS, 'h1v1' * 1_875_000, MARK))


def path_at_the_limit(d):
    """One path of 998,000 segments in 1,996,004 bytes of data without a
    separator (``h1v1...``): just under the default max_path_bytes, so it
    is parsed and drawn."""
    return _write(d, 'path_at_the_limit.svg', '<svg %s width="200" height="200"><path '
                  'd="M0 0%s" fill="blue"/>%s</svg>' % (NS, 'h1v1' * 499_000, MARK))


def many_elements(d):
    """300,000 rects (8.4 MB): more elements than max_xml_elements."""
    return _write(d, 'many.svg', '<svg %s width="200" height="200">%s%s</svg>'
                  % (NS, MARK, '<rect width="1" height="1"/>' * 300_000))


def css_rules(d):
    """20,000 rules with a descendant combinator over 4,000 elements."""
    css = ''.join('svg .r{fill:#%03x}' % (i % 4096) for i in range(20_000))
    body = ''.join('<rect class="r" x="%d" y="%d" width="1" height="1"/>' % (i % 63, 30 + i // 63)
                   for i in range(4_000))
    return _write(d, 'css.svg', '<svg %s width="200" height="200"><style>%s</style>%s%s</svg>'
                  % (NS, css, body, MARK))


def big_image(d):
    """A 12 MB data: URI (a PNG of noise), above libxml2's 10 MB text limit."""
    import numpy as np
    from PIL import Image
    a = np.random.default_rng(1).integers(0, 256, (1800, 1800, 3), dtype=np.uint8)
    buf = io.BytesIO()
    Image.fromarray(a).save(buf, 'PNG', compress_level=1)
    uri = 'data:image/png;base64,' + base64.b64encode(buf.getvalue()).decode()
    return _write(d, 'big_image.svg', '<svg %s width="100" height="100"><image width="100" '
                  'height="100" href="%s"/>%s</svg>' % (NS, uri, MARK))


def broken_font(d):
    """A font directory with a copy of the bundled Noto Sans whose ``hhea``
    claims fewer horizontal metrics than ``hmtx`` holds (fontTools would log
    "too much 'hmtx' table data") and whose ``head`` magic is zeroed: the
    text is shaped and drawn (by HarfBuzz, which reads it as is) without a
    message."""
    src = os.path.join(ROOT, 'raster', 'fonts', 'NotoSans-Regular-ASCII.ttf')
    with open(src, 'rb') as f:
        buf = bytearray(f.read())
    for i in range(struct.unpack('>H', buf[4:6])[0]):
        off = 12 + 16 * i
        tag = bytes(buf[off:off + 4])
        o = struct.unpack('>I', buf[off + 8:off + 12])[0]
        if tag == b'hhea':
            n = struct.unpack('>H', buf[o + 34:o + 36])[0]
            buf[o + 34:o + 36] = struct.pack('>H', n - 10)
        elif tag == b'head':
            buf[o + 12:o + 16] = b'\0\0\0\0'
    fonts = os.path.join(d, 'fonts')
    os.makedirs(fonts, exist_ok=True)
    _write(fonts, 'Broken.ttf', bytes(buf))
    doc = _write(d, 'text.svg', '<svg %s width="200" height="100"><text x="10" y="50" '
                 'font-family="Noto Sans" font-size="20">Hello</text>%s</svg>' % (NS, MARK))
    return doc, ['--font-dir', fonts]
