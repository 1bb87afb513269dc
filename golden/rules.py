"""Golden cases that pin down the rules of issue 14 (conformance that
generalises): several cases per rule, the edge cases as well as the plain
one.  make_cases.py writes them next to the others.

CASES maps a name to ``(title, desc, body)``: the standard 200x200 head
with a ``<desc>`` saying what the rule is, then ``body``.  DOCS maps a
name to a whole document (for rules about the root element).

References come from resvg (regenerate.py) where resvg follows the rule.
Where it does not, the case's ``<desc>`` says why, and EQUIVALENT gives a
document drawing what the rule asks for without the feature in question;
regenerate.py renders that equivalent (golden/equivalent/NAME.svg) with
resvg as the case's reference.
"""

import urllib.parse

NS = 'xmlns="http://www.w3.org/2000/svg"'


def svg_uri(doc):
    """A ``data:image/svg+xml`` URI of the document ``doc`` (percent-encoded)."""
    return 'data:image/svg+xml;utf8,' + urllib.parse.quote(doc, safe='=:/;,.-')


def _sub(attrs, body=None):
    """A small SVG image document with root attributes ``attrs``: a 40x20
    panel (teal), a circle and a square, all inside (0, 0, 40, 20)."""
    if body is None:
        body = ('<rect width="40" height="20" fill="#2a9d8f"/><circle cx="10" cy="10" r="8" '
                'fill="#e76f51"/><rect x="28" y="5" width="8" height="10" fill="#264653"/>')
    return '<svg %s %s>%s</svg>' % (NS, attrs, body)


def _img(attrs, sub):
    return '<image %s href="%s"/>' % (attrs, svg_uri(sub))


def _frame(x, y, w, h):
    """A thin outline of the box an image is expected to fill."""
    return ('<rect x="%g" y="%g" width="%g" height="%g" fill="none" stroke="#bbb" '
            'stroke-dasharray="3 3"/>' % (x, y, w, h))


CASES = {
    # --- SVG images: intrinsic size (SVG 2 / CSS sizing of replaced elements) ----
    'image-svg-intrinsic-viewbox': (
        'SVG image without width/height: the size of the referenced viewBox',
        'The image element has no width and height (auto), the referenced document only '
        'a viewBox of 40x20: its intrinsic size is 40x20, drawn at (20, 20) unscaled.',
        _img('x="20" y="20"', _sub('viewBox="0 0 40 20"')) + _frame(20, 20, 40, 20)),
    'image-svg-intrinsic-width-only': (
        'SVG image whose root has only a width: the height follows the viewBox ratio',
        'The referenced root has width="80" and viewBox="0 0 40 20" but no height: its '
        'intrinsic height comes from the 2:1 ratio (40), not from a 100% default.',
        _img('x="20" y="20"', _sub('width="80" viewBox="0 0 40 20"')) + _frame(20, 20, 80, 40)),
    'image-svg-intrinsic-height-only': (
        'SVG image whose root has only a height: the width follows the viewBox ratio',
        'The referenced root has height="60" and a 2:1 viewBox: 120x60.',
        _img('x="20" y="20"', _sub('height="60" viewBox="0 0 40 20"')) + _frame(20, 20, 120, 60)),
    'image-svg-intrinsic-auto': (
        'width and height auto, on the image and on the referenced root',
        'auto on the image element is its intrinsic size; auto on the referenced root is '
        'as if absent (the viewBox size, then the ratio for a missing side).  Top: both '
        'auto (40x20); bottom: width="100" height="auto" on the root (100x50).',
        _img('x="20" y="20" width="auto" height="auto"', _sub('width="auto" height="auto" viewBox="0 0 40 20"'))
        + _img('x="20" y="80" width="auto"', _sub('width="100" height="auto" viewBox="0 0 40 20"'))
        + _frame(20, 20, 40, 20) + _frame(20, 80, 100, 50)),
    'image-svg-one-side-given': (
        'image with only a width or only a height: the other from the intrinsic ratio',
        'width="160" alone on the image: height 80 (the 2:1 ratio of a root with only a '
        'width); height="50" alone: width 100.',
        _img('x="20" y="20" width="160"', _sub('width="80" viewBox="0 0 40 20"'))
        + _img('x="20" y="120" height="50"', _sub('viewBox="0 0 40 20"'))
        + _frame(20, 20, 160, 80) + _frame(20, 120, 100, 50)),
    'image-svg-par-none-intrinsic': (
        'preserveAspectRatio none stretches the intrinsic box of an SVG image',
        'The referenced root has only a width and a viewBox (intrinsic 80x40); the image '
        'box is 160x100 with preserveAspectRatio="none": the whole 2:1 picture is '
        'stretched to the box, circle into an ellipse.',
        _img('x="20" y="20" width="160" height="100" preserveAspectRatio="none"',
             _sub('width="80" viewBox="0 0 40 20"')) + _frame(20, 20, 160, 100)),
    'image-svg-slice-intrinsic': (
        'preserveAspectRatio slice with an SVG image sized by its ratio',
        'Intrinsic 2:1 (root width only), image box 100x100, xMaxYMid slice: scaled to '
        'height 100, its right part shown, clipped to the box.',
        _img('x="50" y="50" width="100" height="100" preserveAspectRatio="xMaxYMid slice"',
             _sub('width="80" viewBox="0 0 40 20"')) + _frame(50, 50, 100, 100)),
    'image-svg-intrinsic-no-viewbox': (
        'SVG image with neither size nor viewBox: sized by its content',
        'The referenced root has no width, height or viewBox; its content reaches '
        '(70, 40) from the origin, which stays where it is: the image is 70x40 with '
        'the content at its own coordinates (not moved to the corner).  Below: only a '
        'height (60), the width from the content (70).',
        _img('x="20" y="20"', _sub('', '<rect x="30" y="10" width="40" height="30" fill="#2a9d8f"/>'
                                   '<circle cx="40" cy="25" r="8" fill="#e76f51"/>'))
        + _img('x="20" y="100" width="auto"', _sub('height="60"', '<rect x="30" y="10" width="40" '
                                                   'height="30" fill="#2a9d8f"/>'))
        + _frame(20, 20, 70, 40) + _frame(20, 100, 70, 60)),
}

DOCS = {
    # --- the root element's size --------------------------------------------------
    'structure-root-width-only': (
        '<svg %s width="200" viewBox="0 0 100 50">\n  <title>root with a width and a viewBox '
        'but no height</title>\n  <desc>The missing height follows the viewBox ratio: the '
        'document is 200x100 (CSS sizing with an intrinsic ratio), not 200 by 100%% of a '
        'default.</desc>\n  <rect x="0.5" y="0.5" width="99" height="49" fill="none" '
        'stroke="#777"/>\n  <circle cx="25" cy="25" r="20" fill="#e76f51"/><rect x="60" y="10" '
        'width="30" height="30" fill="#264653"/>\n</svg>\n' % NS),
    'structure-root-height-auto': (
        '<svg %s width="150" height="auto" viewBox="0 0 100 50">\n  <title>root with '
        'height auto</title>\n  <desc>height="auto" is as if absent: 150 wide, 75 high by the '
        'viewBox ratio (an error before).</desc>\n  <rect x="0.5" y="0.5" width="99" '
        'height="49" fill="none" stroke="#777"/>\n  <circle cx="25" cy="25" r="20" '
        'fill="#e76f51"/><rect x="60" y="10" width="30" height="30" fill="#264653"/>\n</svg>\n'
        % NS),
    'structure-root-auto-no-viewbox': (
        '<svg %s width="auto" height="auto">\n  <title>root with auto size and no '
        'viewBox</title>\n  <desc>No size and no viewBox: the document reaches the far edges '
        'of its content from the origin (160x120); the content is not moved.</desc>\n  '
        '<rect x="40" y="30" width="120" height="90" fill="#2a9d8f"/>\n  <circle cx="100" '
        'cy="75" r="30" fill="#e76f51"/>\n</svg>\n' % NS),
}

EQUIVALENT = {}
