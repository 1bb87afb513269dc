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


# --- markers with a viewBox, markers drawing images -----------------------------
# A polyline with three vertices on y = 60 (marker-start/mid/end, orient 0,
# stroke-width 4), so every instance is translate(vertex) @ scale @ translate(-ref).
_MK_PATH = ('<polyline points="40,60 100,60 160,60" fill="none" stroke="#264653" '
            'stroke-width="4" marker-start="url(#m)" marker-mid="url(#m)" marker-end="url(#m)"/>')
_MK_PATH2 = _MK_PATH.replace('40,60 100,60 160,60', '40,150 100,150 160,150')
_VERTS = ((40, 60), (100, 60), (160, 60))


def _instances(content, scale, ref, clip=None, verts=_VERTS, cid='c'):
    """What a marker draws, written out: ``content`` at each vertex under
    translate(vertex) scale(scale) translate(-ref), clipped to ``clip``
    (x, y, w, h in content coordinates) when given."""
    out = ''
    if clip is not None:
        out += ('<clipPath id="%s"><rect x="%g" y="%g" width="%g" height="%g"/></clipPath>'
                % ((cid,) + tuple(clip)))
    for vx, vy in verts:
        out += '<g transform="translate(%g %g) scale(%g) translate(%g %g)"%s>%s</g>' % (
            vx, vy, scale, -ref[0], -ref[1],
            ' clip-path="url(#%s)"' % cid if clip is not None else '', content)
    return out


_MK_WIDE = ('<rect x="-4" y="2" width="18" height="6" fill="#2a9d8f"/>'
            '<path d="M0 0 L10 5 L0 10z" fill="#e76f51"/>')
_MK_WIDER = ('<rect x="-8" y="2" width="26" height="6" fill="#2a9d8f"/>'
             '<path d="M0 0 L10 5 L0 10z" fill="#e76f51"/>')
_MK_SQUARE = ('<rect width="10" height="10" fill="#2a9d8f"/><circle cx="5" cy="5" r="4" '
              'fill="#e76f51"/><rect x="4" y="0" width="2" height="10" fill="#264653"/>')
_PNG = ('data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAQAAAADCAYAAAC09K7GAAAAKUlEQVR4nGN4'
        'Zun2/+Ovd/9X3Lrz37V67n8GZM4zS7f/DMicj7/e/QcAllEj4JIVAnkAAAAASUVORK5CYII=')

CASES.update({
    'marker-viewbox-viewport-clip': (
        'marker viewBox meet: the clip is the marker viewport, not the viewBox',
        'viewBox 0 0 10 10 into markerWidth 8 x markerHeight 4 (meet, scale 0.4, centred): '
        'the viewport spans x -5..15 of the viewBox coordinates, so overflow: hidden clips '
        'there (SVG 1.1 and 2: a marker clips at the bounds of its viewport).  Top: a bar '
        'from -4 to 14 is whole; bottom: one from -8 to 18 is cut at -5 and 15.  resvg clips '
        'at the viewBox (0..10); the reference draws the instances out (golden/equivalent).',
        '<defs><marker id="m" viewBox="0 0 10 10" markerWidth="8" markerHeight="4" refX="5" '
        'refY="5">%s</marker><marker id="n" viewBox="0 0 10 10" markerWidth="8" '
        'markerHeight="4" refX="5" refY="5">%s</marker></defs>%s%s'
        % (_MK_WIDE, _MK_WIDER, _MK_PATH, _MK_PATH2.replace('#m', '#n'))),
    'marker-viewbox-slice': (
        'marker viewBox with slice: the viewport cuts the viewBox',
        'viewBox 0 0 10 10 into 8 x 4 with xMidYMid slice: scale 0.8, the viewport shows '
        'the band y 2.5..7.5 of the viewBox; the reference point (5, 5) sits on each vertex.  '
        'resvg clips at the whole viewBox; the reference draws the instances out.',
        '<defs><marker id="m" viewBox="0 0 10 10" markerWidth="8" markerHeight="4" refX="5" '
        'refY="5" preserveAspectRatio="xMidYMid slice">%s</marker></defs>%s'
        % (_MK_SQUARE, _MK_PATH)),
    'marker-viewbox-none-and-offset': (
        'marker viewBox: preserveAspectRatio none, and a viewBox not at the origin',
        'Top: viewBox 0 0 10 10 stretched into 8 x 4 (none): scale 3.2 x 1.6 of the stroke '
        'width.  Bottom: viewBox -5 -5 20 20 into 6 x 6 with refX/refY 5: the reference point '
        'is in viewBox coordinates; the alignment offset cancels out.',
        '<defs><marker id="m" viewBox="0 0 10 10" markerWidth="8" markerHeight="4" refX="5" '
        'refY="5" preserveAspectRatio="none">%s</marker><marker id="n" viewBox="-5 -5 20 20" '
        'markerWidth="6" markerHeight="6" refX="5" refY="5">%s</marker></defs>%s%s'
        % (_MK_SQUARE, _MK_SQUARE, _MK_PATH, _MK_PATH2.replace('#m', '#n'))),
    'marker-viewbox-ref-keywords': (
        'refX/refY keywords resolve against the marker viewBox',
        'refX="right" refY="center" with viewBox 5 5 10 10: the reference point is (15, 10), '
        'the right middle of the viewBox (SVG 2).  resvg reads the keywords as 0; the '
        'reference is the same marker with refX="15" refY="10".',
        '<defs><marker id="m" viewBox="5 5 10 10" markerWidth="6" markerHeight="6" '
        'refX="right" refY="center" orient="auto">%s</marker></defs>%s'
        % (_MK_SQUARE.replace('<rect width', '<rect x="5" y="5" width').replace(
            'cx="5" cy="5"', 'cx="10" cy="10"').replace('x="4" y="0"', 'x="9" y="5"'),
           _MK_PATH)),
    'marker-viewbox-invalid': (
        'an invalid marker viewBox is ignored, a zero-sized one disables the marker',
        'Top: viewBox="0 0 10 -10" (negative height) invalidates the attribute (SVG 2): the '
        'marker is drawn as if it had none.  Bottom: viewBox="0 0 0 10" disables rendering of '
        'the marker (SVG 1.1 and 2): no markers, only the line.  resvg draws the second as if '
        'it had no viewBox; the reference leaves it out.',
        '<defs><marker id="m" viewBox="0 0 10 -10" markerWidth="3" markerHeight="3" '
        'refX="1.5" refY="1.5"><rect width="3" height="3" fill="#2a9d8f"/></marker><marker '
        'id="n" viewBox="0 0 0 10" markerWidth="3" markerHeight="3"><rect width="3" height="3" '
        'fill="#e76f51"/></marker></defs>%s%s' % (_MK_PATH, _MK_PATH2.replace('#m', '#n'))),
    'marker-image-raster': (
        'a marker whose content is a raster image',
        'An image in the marker content is drawn like any content: scaled by the stroke '
        'width, turned by orient="auto" along a curve, clipped to the viewport (the image '
        'is larger than markerWidth x markerHeight on the second path).',
        '<defs><marker id="m" markerWidth="8" markerHeight="6" refX="4" refY="3" '
        'orient="auto"><image width="8" height="6" preserveAspectRatio="none" href="%s"/>'
        '</marker><marker id="n" markerWidth="6" markerHeight="6" refX="3" refY="3">'
        '<image x="-2" y="-2" width="10" height="10" image-rendering="optimizeSpeed" '
        'href="%s"/></marker></defs><path d="M30 80 C 70 20, 130 140, 170 80" fill="none" '
        'stroke="#264653" stroke-width="3" marker-start="url(#m)" marker-end="url(#m)"/>%s'
        % (_PNG, _PNG, _MK_PATH2.replace('#m', '#n'))),
    'marker-image-svg': (
        'a marker whose content is an SVG image, in a marker with a viewBox',
        'The SVG image (viewBox 0 0 10 10, a circle and a bar) fills the 100 x 100 viewBox of '
        'the marker, mapped into 6 x 6 stroke widths; orient auto-start-reverse.',
        '<defs><marker id="m" viewBox="0 0 100 100" markerWidth="6" markerHeight="6" refX="50" '
        'refY="50" orient="auto-start-reverse"><image width="100" height="100" href="%s"/>'
        '</marker></defs><path d="M40 100 L100 60 L160 100" fill="none" stroke="#264653" '
        'stroke-width="4" marker-start="url(#m)" marker-mid="url(#m)" marker-end="url(#m)"/>'
        % svg_uri(_sub('viewBox="0 0 10 10"', '<circle cx="5" cy="5" r="5" fill="#e76f51"/>'
                       '<rect x="4" y="1" width="2" height="8" fill="#264653"/>'))),
})

EQUIVALENT.update({
    'marker-viewbox-viewport-clip': (
        'equivalent: the marker instances written out',
        _MK_PATH.replace(' marker-start="url(#m)" marker-mid="url(#m)" marker-end="url(#m)"', '')
        + _MK_PATH2.replace(' marker-start="url(#m)" marker-mid="url(#m)" marker-end="url(#m)"', '')
        + _instances(_MK_WIDE, 1.6, (5, 5), (-5, 0, 20, 10), cid='c1')
        + _instances(_MK_WIDER, 1.6, (5, 5), (-5, 0, 20, 10),
                     verts=((40, 150), (100, 150), (160, 150)), cid='c2')),
    'marker-viewbox-slice': (
        'equivalent: the marker instances written out',
        _MK_PATH.replace(' marker-start="url(#m)" marker-mid="url(#m)" marker-end="url(#m)"', '')
        + _instances(_MK_SQUARE, 3.2, (5, 5), (0, 2.5, 10, 5))),
    'marker-viewbox-invalid': (
        'equivalent: the first marker without its viewBox, the second left out',
        '<defs><marker id="m" markerWidth="3" markerHeight="3" refX="1.5" refY="1.5"><rect '
        'width="3" height="3" fill="#2a9d8f"/></marker></defs>%s%s'
        % (_MK_PATH, _MK_PATH2.replace(
            ' marker-start="url(#m)" marker-mid="url(#m)" marker-end="url(#m)"', ''))),
})
EQUIVALENT['marker-viewbox-ref-keywords'] = (
    'equivalent: the reference point as numbers',
    CASES['marker-viewbox-ref-keywords'][2].replace('refX="right" refY="center"',
                                                     'refX="15" refY="10"'))


# --- patterns that cannot paint: the fallback colour ----------------------------
_P_OBB = ('<pattern id="p" width="0.25" height="0.25"><rect width="10" height="10" '
          'fill="#264653"/></pattern>')
_P_USER = ('<pattern id="u" width="20" height="20" patternUnits="userSpaceOnUse"><rect '
           'width="10" height="10" fill="#264653"/></pattern>')
_SQ = '<rect x="20" y="20" width="160" height="160" fill="%s"/>'

CASES.update({
    'pattern-obb-zero-box-fallback': (
        'objectBoundingBox pattern and gradient on shapes without area: the fallback',
        'A horizontal and a vertical line have bounding boxes of zero height or width, so '
        'objectBoundingBox units cannot be resolved and the paint server is unusable: the '
        'stroke takes the fallback colour of url() (a colour, currentColor), and paints '
        'nothing without one (the third line).  The same for a gradient (bottom).',
        '<defs>%s<linearGradient id="g"><stop offset="0" stop-color="red"/><stop offset="1" '
        'stop-color="blue"/></linearGradient></defs>'
        '<line x1="20" y1="40" x2="180" y2="40" stroke="url(#p) #2a9d8f" stroke-width="16"/>'
        '<line x1="40" y1="60" x2="40" y2="140" stroke="url(#p) currentColor" color="#e76f51" '
        'stroke-width="16"/><line x1="60" y1="80" x2="180" y2="80" stroke="url(#p)" '
        'stroke-width="16"/><path d="M60 160 H180" stroke="url(#g) #264653" stroke-width="16"/>'
        '<rect x="80" y="100" width="80" height="30" fill="url(#p) red"/>' % _P_OBB),
    'pattern-empty-fallback': (
        'a pattern without content paints the fallback colour',
        'Left: a pattern element without children; right: one that inherits nothing to draw '
        'through href (its template has no children either).  Neither can paint, so fill and '
        'stroke take the fallback colours; the pattern with content (bottom) paints itself.',
        '<defs><pattern id="e" width="20" height="20" patternUnits="userSpaceOnUse"/>'
        '<pattern id="f" href="#e" width="30"/>%s</defs>'
        '<rect x="20" y="20" width="70" height="100" fill="url(#e) #2a9d8f"/>'
        '<rect x="110" y="20" width="70" height="100" fill="url(#f) #e9c46a" '
        'stroke="url(#e) #e76f51" stroke-width="6"/>'
        '<rect x="20" y="140" width="160" height="40" fill="url(#u) red"/>' % _P_USER),
    'pattern-zero-size-fallback': (
        'a pattern tile of zero or negative size paints the fallback colour',
        'width="0", height="-20" and an objectBoundingBox height of 0: the tile is empty '
        '(SVG: a value of zero disables rendering, a negative one is an error), the paint '
        'server unusable, the fallback colour is painted.',
        '<defs><pattern id="a" width="0" height="20" patternUnits="userSpaceOnUse"><rect '
        'width="10" height="10"/></pattern><pattern id="b" width="20" height="-20" '
        'patternUnits="userSpaceOnUse"><rect width="10" height="10"/></pattern><pattern id="c" '
        'width="0.5" height="0"><rect width="10" height="10"/></pattern></defs>'
        '<rect x="20" y="20" width="50" height="160" fill="url(#a) #2a9d8f"/>'
        '<rect x="75" y="20" width="50" height="160" fill="url(#b) #e9c46a"/>'
        '<rect x="130" y="20" width="50" height="160" fill="url(#c) #e76f51"/>'),
    'pattern-invisible-content-transparent': (
        'a pattern whose content draws nothing is transparent, not the fallback',
        'The patterns have content (an empty group; a rectangle with fill none), so they are '
        'valid and paint a transparent tile: the fallback colour (red) must not show.',
        '<defs><pattern id="a" width="20" height="20" patternUnits="userSpaceOnUse"><g/>'
        '</pattern><pattern id="b" width="20" height="20" patternUnits="userSpaceOnUse"><rect '
        'width="10" height="10" fill="none"/></pattern></defs>'
        '<rect x="20" y="20" width="160" height="160" fill="#e9c46a"/>'
        '<rect x="40" y="40" width="50" height="120" fill="url(#a) red"/>'
        '<rect x="110" y="40" width="50" height="120" fill="url(#b) red"/>'),
    'pattern-content-obb-zero-box-fallback': (
        'objectBoundingBox pattern content on a shape without area: the fallback',
        'The tile is in user space but patternContentUnits="objectBoundingBox": the content '
        'cannot be placed on a line whose box has zero height, so the pattern cannot paint '
        'and the fallback colour is used, as for patternUnits.  resvg paints nothing here; '
        'the reference is the lines stroked with the fallback colour.',
        '<defs><pattern id="p" width="20" height="20" patternUnits="userSpaceOnUse" '
        'patternContentUnits="objectBoundingBox"><rect width="0.5" height="0.5" '
        'fill="#264653"/></pattern></defs>'
        '<line x1="20" y1="60" x2="180" y2="60" stroke="url(#p) #2a9d8f" stroke-width="20"/>'
        '<line x1="100" y1="90" x2="100" y2="180" stroke="url(#p) #e76f51" stroke-width="20"/>'),
    'pattern-zero-viewbox-fallback': (
        'a pattern with a zero-sized viewBox paints the fallback colour',
        'viewBox="0 0 0 10" disables rendering of the pattern (SVG 1.1 and 2), which leaves '
        'the fill to the fallback colour.  resvg ignores the viewBox and tiles the content; '
        'the reference is the rectangle filled with the fallback colour.',
        '<defs><pattern id="p" width="20" height="20" patternUnits="userSpaceOnUse" '
        'viewBox="0 0 0 10"><rect width="10" height="10" fill="#264653"/></pattern></defs>'
        + _SQ % 'url(#p) #2a9d8f'),
})

EQUIVALENT.update({
    'pattern-content-obb-zero-box-fallback': (
        'equivalent: the fallback colours',
        '<line x1="20" y1="60" x2="180" y2="60" stroke="#2a9d8f" stroke-width="20"/>'
        '<line x1="100" y1="90" x2="100" y2="180" stroke="#e76f51" stroke-width="20"/>'),
    'pattern-zero-viewbox-fallback': ('equivalent: the fallback colour', _SQ % '#2a9d8f'),
})


# --- what counts in an object bounding box; display none on the root -----------
_OBB_CLIP = ('<clipPath id="c" clipPathUnits="objectBoundingBox"><circle cx="0.5" cy="0.5" '
             'r="0.5"/></clipPath>')
_INNER = '<rect x="50" y="70" width="100" height="100" fill="#e76f51"/>'


def _clipped(invisible, inner=_INNER, effect='clip-path="url(#c)"'):
    return '<defs>%s</defs><g %s>%s%s</g>' % (_OBB_CLIP, effect, invisible, inner)


CASES.update({
    'bbox-invisible-opacity-zero': (
        'an opacity 0 child still counts in the bounding box of a clipped group',
        'The group is clipped by a circle in objectBoundingBox units.  Its first child '
        '(20..180) has opacity 0: it paints nothing but is rendered, and the bounding box is '
        'geometry whatever the opacity (SVG 2), so the circle is centred on (100, 100) with '
        'radius 80 and cuts the visible square only at its lower corners.',
        _clipped('<rect x="20" y="20" width="160" height="160" opacity="0"/>')),
    'bbox-invisible-no-paint': (
        'children without fill or stroke count in the bounding box',
        'Left: fill="none" and no stroke; right: a url() to a missing paint server without '
        'fallback.  Both paint nothing and both count: each clip circle is the box of the '
        'invisible outer rectangle.',
        _clipped('<rect x="10" y="20" width="85" height="160" fill="none"/>',
                 '<rect x="20" y="60" width="65" height="100" fill="#e76f51"/>')
        + _clipped('<rect x="105" y="20" width="85" height="160" fill="url(#missing)"/>',
                   '<rect x="115" y="60" width="65" height="100" fill="#2a9d8f"/>')),
    'bbox-invisible-group-use-image': (
        'invisible groups, use instances and images count in the bounding box',
        'Three clipped groups, each with an invisible first child: a rotated group with '
        'opacity 0 (its box is that of the rotated square, 29..171), a use with opacity 0, '
        'and an image with opacity 0 (its box is its viewport).',
        '<defs>%s<rect id="r" x="120" y="10" width="70" height="70"/></defs>'
        '<g clip-path="url(#c)"><g opacity="0" transform="rotate(45 100 100)"><rect x="50" '
        'y="50" width="100" height="100"/></g><rect x="60" y="90" width="80" height="80" '
        'fill="#e76f51"/></g>'
        '<g clip-path="url(#c)"><use href="#r" opacity="0"/><rect x="140" y="30" width="50" '
        'height="50" fill="#2a9d8f"/></g>'
        '<g clip-path="url(#c)"><image x="10" y="120" width="70" height="70" opacity="0" '
        'preserveAspectRatio="none" href="%s"/><rect x="10" y="140" width="50" height="50" '
        'fill="#264653"/></g>' % (_OBB_CLIP, _PNG)),
    'bbox-image-viewport': (
        'the bounding box of an image is its viewport, not the drawn picture',
        'A 4x3 image in a 160x160 viewport (meet: drawn 160x120) inside a group clipped by a '
        'circle in objectBoundingBox units: the box is the viewport (x, y, width, height; '
        'SVG 2 "the positioning rectangle is used as the bounding box"), so the circle has '
        'radius 80 around (100, 100).  resvg uses the drawn 160x120; the reference clips by '
        'that circle in user space.',
        _clipped('<image x="20" y="20" width="160" height="160" href="%s"/>' % _PNG, '')),
    'bbox-invisible-mask-filter': (
        'invisible children size objectBoundingBox masks and filter regions too',
        'Left: a mask in objectBoundingBox content units; right: a filter region of exactly '
        'the box (x=0 y=0 width=1 height=1) with a flood.  The opacity 0 rectangles make the '
        'boxes 10..95 and 105..190 across.',
        '<defs><mask id="m" maskContentUnits="objectBoundingBox"><circle cx="0.5" cy="0.5" '
        'r="0.5" fill="white"/></mask><filter id="f" x="0" y="0" width="1" height="1">'
        '<feFlood flood-color="#2a9d8f" flood-opacity="0.6"/></filter></defs>'
        '<g mask="url(#m)"><rect x="10" y="20" width="85" height="160" opacity="0"/><rect '
        'x="20" y="60" width="65" height="100" fill="#e76f51"/></g>'
        '<g filter="url(#f)"><rect x="105" y="20" width="85" height="160" opacity="0"/><rect '
        'x="115" y="60" width="65" height="100" fill="#e76f51"/></g>'),
})

EQUIVALENT['bbox-image-viewport'] = (
    'equivalent: the image clipped by the circle of its viewport',
    '<defs><clipPath id="c"><circle cx="100" cy="100" r="80"/></clipPath></defs>'
    '<g clip-path="url(#c)"><image x="20" y="20" width="160" height="160" href="%s"/></g>' % _PNG)

DOCS.update({
    'structure-root-display-none': (
        '<svg %s width="200" height="100" viewBox="0 0 100 50" display="none" '
        'style="background-color: #e9c46a">\n  <title>display none on the root element</title>\n'
        '  <desc>display="none" on the root svg: nothing is rendered, not even the '
        'background, and the document keeps its size (200x100, transparent).</desc>\n  '
        '<rect width="100" height="50" fill="#e76f51"/>\n</svg>\n' % NS),
    'structure-root-display-none-css': (
        '<svg %s width="120" height="80">\n  <title>display none on the root element from '
        'a style sheet</title>\n  <desc>The same through CSS (svg { display: none }): a '
        'transparent 120x80 document.</desc>\n  <style>svg { display: none }</style>\n  '
        '<rect width="120" height="80" fill="#e76f51"/>\n</svg>\n' % NS),
})


# --- filters ---------------------------------------------------------------------
_FR = '<rect x="40" y="40" width="100" height="100" fill="#e76f51" filter="%s"/>'
_DOT = '<circle cx="90" cy="90" r="15" fill="#264653"/>'
_SHIFT = '<filter id="s"><feOffset dx="20" dy="20"/></filter>'

CASES.update({
    'filter-list-invalid-url': (
        'a filter list with an unusable url: left out, the rest applies',
        'Top left: url(#s) url(#missing) applies the offset and leaves the missing reference '
        'out; top right: blur(3px) url(#missing) blurs; bottom left: url(#missing) '
        'grayscale(1) turns grey; bottom right: url(#missing) alone, nothing usable left: '
        'the element is not rendered (only the dot).',
        '<defs>%s</defs>' % _SHIFT
        + '<g transform="translate(-14 -14) scale(0.6)">%s%s</g>' % (_FR % 'url(#s) url(#missing)', _DOT)
        + '<g transform="translate(86 -14) scale(0.6)">%s%s</g>' % (_FR % 'blur(3px) url(#missing)', _DOT)
        + '<g transform="translate(-14 86) scale(0.6)">%s%s</g>' % (_FR % 'url(#missing) grayscale(1)', _DOT)
        + '<g transform="translate(86 86) scale(0.6)">%s%s</g>' % (_FR % 'url(#missing)', _DOT)),
    'filter-list-syntax-error': (
        'a filter value with a syntax error is ignored as a whole',
        'Left: url(#s),url(#s) (filter lists are separated by spaces only); right: url() (no '
        'reference).  Both values are invalid, so the elements are drawn unfiltered.',
        '<defs>%s</defs>' % _SHIFT
        + '<g transform="translate(-20 20) scale(0.6)">%s%s</g>' % (_FR % 'url(#s),url(#s)', _DOT)
        + '<g transform="translate(80 20) scale(0.6)">%s%s</g>' % (_FR % 'url()', _DOT)),
    'filter-spotlight-exponent-zero': (
        'feSpotLight specularExponent 0 is a flat cone',
        'The spot light points straight down the middle; with specularExponent="0" every '
        'direction inside the 55 degree cone gets the full light (pow(x, 0) = 1): a disc of '
        'even light with a hard edge (top).  specularExponent="-2" is invalid and means the '
        'initial 1, a light fading off the axis (bottom).',
        '<filter id="a" x="0" y="0" width="1" height="1"><feDiffuseLighting surfaceScale="0">'
        '<feSpotLight x="100" y="50" z="30" pointsAtX="100" pointsAtY="50" pointsAtZ="0" '
        'specularExponent="0" limitingConeAngle="55"/></feDiffuseLighting></filter>'
        '<filter id="b" x="0" y="0" width="1" height="1"><feDiffuseLighting surfaceScale="0">'
        '<feSpotLight x="100" y="150" z="30" pointsAtX="100" pointsAtY="150" pointsAtZ="0" '
        'specularExponent="-2" limitingConeAngle="55"/></feDiffuseLighting></filter>'
        '<rect x="20" y="10" width="160" height="80" filter="url(#a)"/>'
        '<rect x="20" y="110" width="160" height="80" filter="url(#b)"/>'),
    'filter-feimage-self-reference': (
        'feImage that references the filtered element itself',
        "The rectangle's filter has an feImage of the rectangle: drawing it would never end, "
        'so the rectangle ignores its filter and is drawn plainly (resvg does the same).  The '
        "circle's feImage references the rectangle, which is drawn through no filter there "
        "either, shifted to the circle's filter region.",
        '<defs><filter id="f"><feImage href="#r"/></filter><filter id="g" x="0" y="0" '
        'width="1" height="1"><feImage href="#r"/></filter></defs>'
        '<rect id="r" x="30" y="30" width="60" height="60" fill="#e76f51" filter="url(#f)"/>'
        '<circle cx="140" cy="140" r="40" fill="#2a9d8f" filter="url(#g)"/>'),
    'filter-flood-obb-subregion-defaults': (
        'feFlood subregion in objectBoundingBox primitive units: missing values are the box',
        'primitiveUnits="objectBoundingBox": an feFlood with only width="0.5" floods the left '
        'half of the bounding box (x, y, height default to 0, 0, 100 % of the box, as resvg '
        'does), here under a rotation: the flood is the device box of that half, within the '
        'filter region.',
        '<filter id="f" primitiveUnits="objectBoundingBox"><feFlood flood-color="#2a9d8f" '
        'width="0.5"/></filter><rect x="50" y="50" width="100" height="100" '
        'filter="url(#f)"/><rect x="50" y="50" width="100" height="100" fill="none" '
        'stroke="#264653" transform="rotate(20 100 100)"/><rect x="50" y="50" width="100" '
        'height="100" fill="#e76f51" fill-opacity="0.5" filter="url(#f)" '
        'transform="rotate(20 100 100)"/>'),
    'filter-turbulence-transforms': (
        'feTurbulence under scale, rotation and skew',
        'Under a scale the noise scales with the element (exact); under rotation and skew the '
        'filter works on the device axes at the scale of the CTM rows, as blur radii and '
        "offsets do (resvg's approximation: the noise is not turned).",
        '<filter id="f" filterUnits="userSpaceOnUse" x="0" y="0" width="60" height="60">'
        '<feTurbulence baseFrequency="0.06" numOctaves="2" seed="3"/></filter>'
        '<rect width="60" height="60" filter="url(#f)" transform="translate(15 15) scale(1.3)"/>'
        '<rect width="60" height="60" filter="url(#f)" transform="translate(130 10) rotate(30)"/>'
        '<rect width="60" height="60" filter="url(#f)" transform="translate(30 110) skewX(20) '
        'scale(1.2 1)"/>'),
})


# --- radial gradients: a focal circle not inside the end circle -----------------
_RS = ('<stop offset="0" stop-color="#e76f51"/><stop offset="0.5" stop-color="#e9c46a"/>'
       '<stop offset="1" stop-color="#264653"/>')


def _radial(attrs, x=20, y=20, w=160, h=160, gid='g'):
    return ('<defs><radialGradient id="%s" %s>%s</radialGradient></defs><rect x="%g" y="%g" '
            'width="%g" height="%g" fill="url(#%s)" stroke="#999"/>' % (gid, attrs, _RS, x, y,
                                                                          w, h, gid))


CASES.update({
    'gradient-radial-focal-outside-cone': (
        'radial gradient with the focal point outside the end circle: a cone',
        'fx="1.2" (right of the circle of radius 0.5 around the centre): the circles from the '
        'focal point to the end circle make a cone; inside it the gradient runs from the '
        'focal point (red) to the circle and past it (pad: the last colour); outside the cone '
        'nothing is painted, the grey outline of the rectangle shows through (SVG 2, canvas).  '
        'No moving of the focal point into the circle (SVG 1.1).',
        _radial('fx="1.2" fy="0.5"', 20, 20, 160, 75)
        + _radial('fx="0.5" fy="1.6" r="0.3"', 20, 105, 160, 75, 'h')),
    'gradient-radial-focal-outside-spread': (
        'the cone of an outside focal point with reflect and repeat',
        'Inside the cone the parameter is reflected or repeated as usual; outside it stays '
        'unpainted whatever the spread method.',
        _radial('fx="1.3" fy="0.3" r="0.35" spreadMethod="reflect"', 20, 20, 160, 75)
        + _radial('fx="1.3" fy="0.7" r="0.35" spreadMethod="repeat"', 20, 105, 160, 75, 'h')),
    'gradient-radial-focal-circle-overlap': (
        'a focal circle (fr) reaching out of the end circle',
        'Top: fx="0.9" fr="0.2" with r="0.5": the focal circle crosses the end circle, so the '
        'gradient is a cone again and the corners beside it stay unpainted.  Bottom: a focal '
        'circle inside the end circle (fx="0.6" fr="0.2"): the whole rectangle is painted.',
        _radial('fx="0.9" fy="0.5" fr="0.2"', 20, 20, 160, 75)
        + _radial('fx="0.6" fy="0.5" fr="0.2"', 20, 105, 160, 75, 'h')),
})


# --- use that points into another local SVG file (golden/cases/lib/) -------------

CASES.update({
    'use-external-element': (
        'use of an element of another local SVG file, styled by that file',
        'lib/shapes.svg#star takes the fill of its class and the stroke of its id from the '
        'style sheet of lib/shapes.svg; lib/shapes.svg#bar is filled with that file’s '
        'gradient #g (orange to yellow), not with the #g of this document (blue); '
        'lib/shapes.svg#chain uses more.svg#dot in turn (relative to lib/).',
        '<defs><linearGradient id="g"><stop offset="0" stop-color="blue"/><stop offset="1" '
        'stop-color="navy"/></linearGradient></defs>'
        '<use href="lib/shapes.svg#star" x="20" y="20"/>'
        '<use href="lib/shapes.svg#bar" x="110" y="30"/>'
        '<rect x="20" y="110" width="60" height="24" fill="url(#g)"/>'
        '<use href="lib/shapes.svg#chain" x="130" y="120"/>'),
    'use-external-inherit-symbol-root': (
        'external use content inherits from the use; symbols and whole files',
        'lib/shapes.svg#pair has no fill of its own: it inherits the use element’s '
        '(dark blue).  lib/shapes.svg#sym is a symbol sized by the use (80 x 80); '
        'lib/shapes.svg without a fragment is the file’s root svg, a viewport of the use’s '
        'size (60 x 60 here, its viewBox 0 0 60 60).',
        '<use href="lib/shapes.svg#pair" x="20" y="20" fill="#264653"/>'
        '<use href="lib/shapes.svg#sym" x="100" y="20" width="80" height="80"/>'
        '<use href="lib/shapes.svg" x="30" y="110" width="60" height="60"/>'),
    'use-external-refused': (
        'external use references that are not followed',
        'Nothing but the frame is drawn: a file outside the allowed directories '
        '(../mesh/, above the document’s directory), an id the file does not have, a use '
        'cycle through two files, a network URL, and a data URI.',
        '<use href="../mesh/mesh-2x2-lines.svg#m"/>'
        '<use href="lib/shapes.svg#nothing"/>'
        '<use href="lib/shapes.svg#loop"/>'
        '<use href="https://example.com/shapes.svg#star"/>'
        '<use href="data:image/svg+xml,%3Csvg xmlns=%27http://www.w3.org/2000/svg%27%3E%3Crect '
        'id=%27r%27 width=%27100%27 height=%27100%27/%3E%3C/svg%3E#r"/>'),
})

EQUIVALENT.update({
    'use-external-element': (
        'equivalent: the used elements copied in',
        '<defs><linearGradient id="g2"><stop offset="0" stop-color="#e76f51"/><stop offset="1" '
        'stop-color="#e9c46a"/></linearGradient><linearGradient id="g"><stop offset="0" '
        'stop-color="blue"/><stop offset="1" stop-color="navy"/></linearGradient></defs>'
        '<path transform="translate(20 20)" fill="#2a9d8f" stroke="#264653" stroke-width="3" '
        'd="M30 3 L37 21 L57 21 L41 33 L47 53 L30 41 L13 53 L19 33 L3 21 L23 21 Z"/>'
        '<rect x="110" y="30" width="60" height="24" fill="url(#g2)"/>'
        '<rect x="20" y="110" width="60" height="24" fill="url(#g)"/>'
        '<circle cx="140" cy="130" r="10" fill="#e76f51"/>'),
    'use-external-inherit-symbol-root': (
        'equivalent: the used elements copied in',
        '<defs><linearGradient id="g"><stop offset="0" stop-color="#e76f51"/><stop offset="1" '
        'stop-color="#e9c46a"/></linearGradient></defs>'
        '<g transform="translate(20 20)" fill="#264653"><circle cx="12" cy="12" r="10"/>'
        '<rect x="28" width="60" height="24" fill="url(#g)" transform="scale(0.5)"/></g>'
        '<svg x="100" y="20" width="80" height="80" viewBox="0 0 10 10"><circle cx="5" cy="5" '
        'r="5" fill="#264653"/><rect x="3" y="3" width="4" height="4" fill="#e9c46a"/></svg>'
        '<svg x="30" y="110" width="60" height="60" viewBox="0 0 60 60"><rect width="60" '
        'height="60" fill="#e9c46a"/><circle cx="30" cy="30" r="20" fill="#e76f51"/></svg>'),
    'use-external-refused': ('equivalent: nothing drawn', ''),
})

CASES['filter-offset-whole-pixels'] = (
    'feOffset and feDropShadow move by whole device pixels, truncated',
    'Offsets of 7.5 and -3.7 px (dx="7.5" dy="-3.7"; a drop shadow of dx="2.6") move the '
    'content 7, -3 and 2 whole pixels: the fraction is dropped toward zero, as resvg does '
    '(an approximation: the exact result would resample), and feTile repeats the shifted '
    'tile with that phase.',
    '<filter id="o" x="0" y="0" width="1" height="1"><feOffset dx="7.5" dy="-3.7"/></filter>'
    '<filter id="t" filterUnits="userSpaceOnUse" x="100" y="20" width="80" height="80">'
    '<feFlood flood-color="#264653" x="104" y="24" width="10" height="10"/><feOffset dx="5.5" '
    'dy="2.5"/><feTile/></filter><filter id="d" filterUnits="userSpaceOnUse" x="0" y="110" '
    'width="200" height="90"><feDropShadow dx="2.6" dy="2.6" stdDeviation="0" '
    'flood-color="#264653"/></filter>'
    '<rect x="20" y="20" width="60" height="60" fill="#e76f51" filter="url(#o)"/>'
    '<rect x="100" y="20" width="80" height="80" filter="url(#t)"/>'
    '<rect x="30.5" y="120.5" width="60" height="60" fill="#2a9d8f" filter="url(#d)"/>')


# --- CSS selectors (Selectors 4 structural pseudo-classes, :lang, :not) -------
# resvg's CSS engine knows :first-child (and little else of these): the
# references are equivalents with the colours written out.

def _row(y, n=8, attrs='', start=0):
    return ''.join('<rect x="%d" y="%d" width="18" height="18"%s/>' % (10 + 22 * i, y, attrs)
                   for i in range(start, n))


CASES.update({
    'css-nth-child': (
        ':nth-child(an+b), :nth-last-child, :first-child, :last-child',
        'Eight squares in one group: odd positions teal, 3n+2 orange (5 is both: the later '
        'rule wins at equal specificity), the second from the end outlined, the first and '
        'last half transparent.  Second row: -n+3 (the first three) dark, even yellow; a '
        'comment between siblings does not count.',
        '<style>#row rect { fill: #ccc } #row > rect:nth-child(odd) { fill: #2a9d8f } '
        '#row > rect:nth-child(3n+2) { fill: #e76f51 } #row > :nth-last-child(2) { stroke: '
        '#264653; stroke-width: 4 } #row > rect:first-child, #row > rect:last-child { '
        'fill-opacity: 0.5 } #r2 > * { fill: #ccc } #r2 > :nth-child(-n+3) { fill: #264653 } '
        '#r2 > :NTH-CHILD( even ) { fill: #e9c46a }</style>'
        '<g id="row">' + _row(30) + '</g>'
        '<g id="r2">' + _row(80, 3) + '<!-- a comment -->' + _row(80, 8, start=3) + '</g>'),
    'css-of-type': (
        ':first-of-type, :last-of-type, :nth-of-type, :only-of-type',
        'Children rect, circle, rect, circle, rect, ellipse: the first of each type teal, '
        'the last of each type outlined, the second rect orange, the only ellipse yellow '
        '(a later rule than :first-of-type).',
        '<style>#types > * { fill: #ccc } #types > :first-of-type { fill: #2a9d8f } '
        '#types > :last-of-type { stroke: #264653; stroke-width: 3 } #types > '
        'rect:nth-of-type(2) { fill: #e76f51 } #types > :only-of-type { fill: #e9c46a }</style>'
        '<g id="types"><rect x="10" y="60" width="18" height="18"/><!-- c -->'
        '<circle cx="49" cy="69" r="9"/><rect x="62" y="60" width="18" height="18"/>'
        '<circle cx="101" cy="69" r="9"/><rect x="114" y="60" width="18" height="18"/>'
        '<ellipse cx="153" cy="69" rx="12" ry="8"/></g>'),
    'css-empty-root-not-only-child': (
        ':empty, :root, :not(), :only-child',
        'Top: a rect without children teal (:empty), one with a title orange.  Then a rect '
        'that is a child of the root dark (:root > rect.top), one in a group not.  Then '
        ':only-child yellow (one circle in its group; two in the other stay grey).  Bottom: '
        'rect:not(.a, #b) teal, the .a and #b rects stay grey.',
        '<style>#e > rect:empty { fill: #2a9d8f } #e > rect:not(:empty) { fill: #e76f51 } '
        ':root > rect.top { fill: #264653 } g.solo > :only-child, g.duo > :only-child { fill: '
        '#e9c46a } #e2 > rect:not(.a, #b) { fill: #2a9d8f }</style>'
        '<g id="e"><rect x="20" y="20" width="30" height="30"/><rect x="60" y="20" width="30" '
        'height="30"><title>not empty</title></rect></g>'
        '<rect class="top" x="20" y="70" width="30" height="30" fill="#ccc"/>'
        '<g><rect class="top" x="60" y="70" width="30" height="30" fill="#ccc"/></g>'
        '<g class="solo"><circle cx="125" cy="85" r="15" fill="#ccc"/></g>'
        '<g class="duo"><circle cx="160" cy="40" r="12" fill="#ccc"/><circle cx="160" cy="85" '
        'r="12" fill="#ccc"/></g>'
        '<g id="e2"><rect class="a" x="20" y="130" width="30" height="30" fill="#ccc"/>'
        '<rect id="b" x="60" y="130" width="30" height="30" fill="#ccc"/>'
        '<rect x="100" y="130" width="30" height="30" fill="#ccc"/></g>'),
    'css-lang': (
        ':lang() matches the nearest xml:lang or lang, and its subtags',
        ':lang(de) orange, :lang(en) teal: a rect in a group of xml:lang="de-CH", one '
        'in a group of lang="en", one of xml:lang="de" inside an English group (its own wins), '
        'one of xml:lang="fr" (grey), one with no language anywhere (grey), and '
        ':lang("en-US", x) with a quoted range (dark).',
        '<style>#L rect { fill: #ccc } #L rect:lang(de) { fill: #e76f51 } #L rect:lang(en) { '
        'fill: #2a9d8f } #L rect:lang("en-US", x) { fill: #264653 }</style>'
        '<g id="L"><g xml:lang="de-CH"><rect x="20" y="20" width="40" height="40"/></g>'
        '<g lang="en"><rect x="80" y="20" width="40" height="40"/>'
        '<rect xml:lang="de" x="140" y="20" width="40" height="40"/></g>'
        '<rect xml:lang="fr" x="20" y="80" width="40" height="40"/>'
        '<rect x="80" y="80" width="40" height="40"/>'
        '<g xml:lang="en-us"><rect x="140" y="80" width="40" height="40"/></g></g>'),
    'css-import': (
        '@import of local style sheets',
        'lib/import-main.css (url() form) imports lib/import-nested.css before its own rules '
        '(teal wins over the nested red for .i1; .i2 orange from the nested sheet; '
        'lib/import-nested.css importing import-main.css again is a cycle, skipped).  A '
        'screen import applies (.i3 dark), a print import does not (.i4 stays grey), an '
        'import after a rule is ignored (.i5 stays grey).',
        '<style>@import url(lib/import-main.css); @import "lib/import-screen.css" screen; '
        '@import \'lib/import-print.css\' print;</style>'
        '<style>rect { stroke: #777 } @import "lib/import-late.css";</style>'
        '<rect class="i1" x="20" y="20" width="40" height="40" fill="#ccc"/>'
        '<rect class="i2" x="80" y="20" width="40" height="40" fill="#ccc"/>'
        '<rect class="i3" x="140" y="20" width="40" height="40" fill="#ccc"/>'
        '<rect class="i4" x="20" y="80" width="40" height="40" fill="#ccc"/>'
        '<rect class="i5" x="80" y="80" width="40" height="40" fill="#ccc"/>'),
})


def _rect(x, y, fill, extra=''):
    return '<rect x="%g" y="%g" width="18" height="18" fill="%s"%s/>' % (x, y, fill, extra)


_X = [10 + 22 * i for i in range(8)]
EQUIVALENT.update({
    'css-nth-child': (
        'equivalent: the colours written out',
        _rect(_X[0], 30, '#2a9d8f', ' fill-opacity="0.5"') + _rect(_X[1], 30, '#e76f51')
        + _rect(_X[2], 30, '#2a9d8f') + _rect(_X[3], 30, '#ccc') + _rect(_X[4], 30, '#e76f51')
        + _rect(_X[5], 30, '#ccc') + _rect(_X[6], 30, '#2a9d8f', ' stroke="#264653" stroke-width="4"')
        + _rect(_X[7], 30, '#e76f51', ' fill-opacity="0.5"')
        + ''.join(_rect(_X[i], 80, '#e9c46a' if i % 2 else '#264653' if i < 3 else '#ccc')
                  for i in range(8))),
    'css-of-type': (
        'equivalent: the colours written out',
        '<rect x="10" y="60" width="18" height="18" fill="#2a9d8f"/>'
        '<circle cx="49" cy="69" r="9" fill="#2a9d8f"/>'
        '<rect x="62" y="60" width="18" height="18" fill="#e76f51"/>'
        '<circle cx="101" cy="69" r="9" fill="#ccc" stroke="#264653" stroke-width="3"/>'
        '<rect x="114" y="60" width="18" height="18" fill="#ccc" stroke="#264653" stroke-width="3"/>'
        '<ellipse cx="153" cy="69" rx="12" ry="8" fill="#e9c46a" stroke="#264653" '
        'stroke-width="3"/>'),
    'css-empty-root-not-only-child': (
        'equivalent: the colours written out',
        '<rect x="20" y="20" width="30" height="30" fill="#2a9d8f"/>'
        '<rect x="60" y="20" width="30" height="30" fill="#e76f51"/>'
        '<rect x="20" y="70" width="30" height="30" fill="#264653"/>'
        '<rect x="60" y="70" width="30" height="30" fill="#ccc"/>'
        '<circle cx="125" cy="85" r="15" fill="#e9c46a"/>'
        '<circle cx="160" cy="40" r="12" fill="#ccc"/><circle cx="160" cy="85" r="12" fill="#ccc"/>'
        '<rect x="20" y="130" width="30" height="30" fill="#ccc"/>'
        '<rect x="60" y="130" width="30" height="30" fill="#ccc"/>'
        '<rect x="100" y="130" width="30" height="30" fill="#2a9d8f"/>'),
    'css-lang': (
        'equivalent: the colours written out',
        '<rect x="20" y="20" width="40" height="40" fill="#e76f51"/>'
        '<rect x="80" y="20" width="40" height="40" fill="#2a9d8f"/>'
        '<rect x="140" y="20" width="40" height="40" fill="#e76f51"/>'
        '<rect x="20" y="80" width="40" height="40" fill="#ccc"/>'
        '<rect x="80" y="80" width="40" height="40" fill="#ccc"/>'
        '<rect x="140" y="80" width="40" height="40" fill="#264653"/>'),
    'css-import': (
        'equivalent: the imported rules applied by hand',
        '<g stroke="#777"><rect x="20" y="20" width="40" height="40" fill="#2a9d8f"/>'
        '<rect x="80" y="20" width="40" height="40" fill="#e76f51"/>'
        '<rect x="140" y="20" width="40" height="40" fill="#264653"/>'
        '<rect x="20" y="80" width="40" height="40" fill="#ccc"/>'
        '<rect x="80" y="80" width="40" height="40" fill="#ccc"/></g>'),
})

#: style sheets the css-import case reads (written by make_cases.py into lib/)
CSS_FILES = {
    'import-main.css': '@import "import-nested.css";\n.i1 { fill: #2a9d8f }\n',
    'import-nested.css': '@import url("import-main.css");\n.i1 { fill: red }\n'
                         '.i2 { fill: #e76f51 }\n',
    'import-screen.css': '.i3 { fill: #264653 }\n',
    'import-print.css': '.i4 { fill: red }\n',
    'import-late.css': '.i5 { fill: red }\n',
}


# --- shape-rendering crispEdges / optimizeSpeed ------------------------------
# resvg turns anti-aliasing off for the path: a stroke thinner than a pixel is
# outlined at its own width and filled at full opacity where it covers pixel
# centres (no one-pixel hairline at a fraction of the opacity), so a thin
# slanted line breaks into runs; a centre on a right or bottom edge is inside.

CASES.update({
    'crisp-thin-strokes': (
        'crispEdges on strokes thinner than a pixel',
        'Strokes of 0.4 and 0.3 px with shape-rendering crispEdges are aliased at full '
        'opacity: horizontal lines whose band covers a row of pixel centres are solid '
        '(y = 20.3 +- 0.2 reaches the centre 20.5 on its bottom edge), slanted lines and a '
        'thin circle break where they miss the centres; a 1 px line is one column.',
        '<g shape-rendering="crispEdges" fill="none" stroke="#264653">'
        '<path d="M20 20.3 H180" stroke-width="0.4"/><path d="M20 30.5 H180" stroke-width="0.4"/>'
        '<path d="M20 40 L180 60" stroke-width="0.4"/><path d="M20 50 L180 190" stroke-width="0.3"/>'
        '<path d="M20.5 70 V190" stroke-width="1"/>'
        '<circle cx="110" cy="120" r="40" stroke-width="0.5"/></g>'),
    'crisp-fills-on-pixel-centres': (
        'crispEdges fills whose edges pass through pixel centres',
        'Aliased fills cover the pixels whose centres are inside; a centre exactly on a left '
        'or top edge is outside, on a right or bottom edge inside (resvg rounds edge ends to '
        'the nearest pixel boundary).  Rectangles with edges on centres, a triangle, a '
        'circle.',
        '<g shape-rendering="crispEdges"><rect x="20.5" y="20.5" width="40" height="30" '
        'fill="#2a9d8f"/><rect x="70.3" y="20.6" width="30.4" height="20.2" fill="#e76f51"/>'
        '<rect x="110.5" y="20" width="60" height="40.5" fill="#264653"/>'
        '<path d="M20.5 80.5 L90.5 80.5 L20.5 150.5 Z" fill="#e9c46a"/>'
        '<circle cx="140" cy="120" r="30.5" fill="#2a9d8f"/></g>'),
    'optimizespeed-thin-strokes': (
        'optimizeSpeed turns anti-aliasing off as crispEdges does',
        'shape-rendering optimizeSpeed on a 0.4 px stroke and a filled ellipse: aliased at '
        'full opacity, inherited from the group; geometricPrecision next to it stays '
        'anti-aliased.',
        '<g shape-rendering="optimizeSpeed"><path d="M20 30.5 H180 M20 40 L180 70" '
        'fill="none" stroke="#264653" stroke-width="0.4"/><ellipse cx="60" cy="120" rx="40" '
        'ry="25" fill="#e76f51"/></g><g shape-rendering="geometricPrecision"><path d="M20 '
        '170.5 H180" stroke="#264653" stroke-width="0.4"/><ellipse cx="150" cy="120" rx="40" '
        'ry="25" fill="#e76f51"/></g>'),
})


# --- stroke caps and joins where control points coincide with end points -------

CASES.update({
    'stroke-coincident-controls-caps': (
        'caps of curves whose first or last control points coincide with an end',
        'The tangent at an end comes from the next distinct control point: C with both '
        'first controls on the start (square caps along the chord to the end), C with the '
        'last control on the end (butt caps), a dashed curve of that kind.',
        '<path d="M30 30 C30 30 30 30 90 60" fill="none" stroke="#264653" stroke-width="20" '
        'stroke-linecap="square"/><path d="M120 30 C120 30 180 90 180 90" fill="none" '
        'stroke="#264653" stroke-width="20"/><path d="M20 190 C20 190 60 150 60 150" '
        'fill="none" stroke="#e9c46a" stroke-width="10" stroke-dasharray="20 8" '
        'stroke-linecap="square"/><path d="M110 190 Q110 190 190 140" fill="none" '
        'stroke="#2a9d8f" stroke-width="12" stroke-linecap="square"/>'),
    'stroke-coincident-controls-joins': (
        'joins at curves whose controls coincide with the join point',
        'Miter joins between a curve whose last control is its end and a line, two '
        'quadratics with controls on their ends, and a degenerate cubic (all points equal) '
        'between two curves, which adds no join of its own.',
        '<path d="M30 170 C 90 170 120 100 120 100 L 180 160" fill="none" stroke="#e76f51" '
        'stroke-width="20"/><path d="M20 110 Q 60 110 60 110 Q60 110 100 60" fill="none" '
        'stroke="#264653" stroke-width="18"/><path d="M120 60 C 150 50 160 80 160 80 C 160 '
        '80 160 80 160 80 C 160 80 170 60 190 50" fill="none" stroke="#2a9d8f" '
        'stroke-width="14"/>'),
})


# --- zero-length subpaths: dots when stroked, nothing when dashed ---------------

_ZERO = ('<path d="M40 40 Z M100 40 Z M160 40 L160 40 M20 150 L180 150" fill="none" '
         'stroke="#264653" stroke-width="24" %s/>')

CASES.update({
    'stroke-zero-length-subpath-dots': (
        'zero-length subpaths stroked with round and square caps',
        'A subpath without length ("M x y Z", "M x y L x y") draws a dot with round caps and '
        'a square (axis-aligned) with square caps; butt caps draw nothing.',
        _ZERO % 'stroke-linecap="round"' + '<g transform="translate(0 50)">'
        + _ZERO % 'stroke-linecap="square"' + '</g>'
        + '<path d="M40 190 Z" stroke="#e76f51" stroke-width="24"/>'),
    'stroke-zero-length-subpath-dashed': (
        'zero-length subpaths of a dashed stroke draw nothing',
        'Dashing follows each subpath along its length; a subpath without length has none '
        'to dash, so it draws no dot, with round or square caps, whatever the dash offset '
        '(as Skia and resvg do); the line below is dashed as usual.',
        _ZERO % 'stroke-linecap="round" stroke-dasharray="30 10"'
        + '<g transform="translate(0 30)">'
        + _ZERO % 'stroke-linecap="round" stroke-dasharray="30 10" stroke-dashoffset="4"'
        + '</g>'),
    'stroke-zero-length-subpath-dashed-square': (
        'zero-length subpaths of a dashed stroke with square caps and an offset',
        'As for round caps: with stroke-dashoffset placing a dash across the start of every '
        'subpath, the zero-length ones still draw nothing.',
        _ZERO % 'stroke-linecap="square" stroke-dasharray="12 6" stroke-dashoffset="3"'
        + '<g transform="translate(0 30)">'
        + _ZERO % 'stroke-linecap="square" stroke-dasharray="12 6" stroke-dashoffset="-20"'
        + '</g>'),
})


# --- transform-origin and transform-box ------------------------------------------

CASES.update({
    'transform-origin-keywords-lengths': (
        'transform-origin with keywords, percentages and lengths (view-box)',
        'The reference box is the viewport (transform-box view-box, the default): "center" '
        'is (100, 100), "right 25%" (200, 50), "30px 40" a length pair, "bottom left" '
        'keywords in either order, a CSS transform with its origin from a style sheet.',
        '<style>.css { transform: rotate(-20deg); transform-origin: 150px 150px }</style>'
        '<rect x="20" y="20" width="40" height="30" fill="#2a9d8f" transform="rotate(15)" '
        'transform-origin="center"/><rect x="120" y="20" width="50" height="30" '
        'fill="#e76f51" transform="scale(0.8)" transform-origin="right 25%"/><rect x="20" '
        'y="80" width="50" height="30" fill="#264653" transform="rotate(20)" '
        'transform-origin="30px 40"/><rect x="90" y="80" width="40" height="30" '
        'fill="#e9c46a" transform="scale(0.7)" transform-origin="bottom left"/><rect '
        'class="css" x="120" y="130" width="50" height="40" fill="#2a9d8f"/>'),
    'transform-box-fill-box': (
        'transform-box fill-box: the origin in the element’s own box',
        'With transform-box: fill-box (a property: set from CSS), percentages and keywords '
        'of transform-origin refer to the element’s bounding box and lengths start at its '
        'corner: each square turns about its own centre, a group scales about the centre of '
        'its content, an offset of 10px 5px from the corner.  resvg ignores transform-box, '
        'so the reference is the same drawing with the origins written into the transforms.',
        '<style>.fb { transform-box: fill-box } .cb { transform-box: content-box } .sb { '
        'transform-box: stroke-box }</style><rect x="20" y="20" width="40" height="40" '
        'fill="#ccc"/><rect class="fb" x="20" y="20" width="40" height="40" fill="#264653" '
        'transform="rotate(30)" transform-origin="center"/><rect class="cb" x="120" y="20" '
        'width="60" height="40" fill="#e76f51" transform="scale(0.5)" transform-origin="right '
        'bottom"/><g class="fb" transform="rotate(45)" transform-origin="50% 50%"><rect '
        'x="20" y="110" width="30" height="30" fill="#2a9d8f"/><rect x="50" y="140" width="30" '
        'height="30" fill="#e9c46a"/></g><rect class="sb" x="120" y="120" width="40" '
        'height="40" fill="none" stroke="#264653" stroke-width="20" transform="scale(0.5)" '
        'transform-origin="0 0"/><rect class="fb" x="100" y="80" width="40" height="20" '
        'fill="#2a9d8f" transform="rotate(90)" transform-origin="10px 5px"/>'),
})

EQUIVALENT.update({
    'transform-box-fill-box': (
        'equivalent: the origins written into the transforms',
        '<rect x="20" y="20" width="40" height="40" fill="#ccc"/><rect x="20" y="20" '
        'width="40" height="40" fill="#264653" transform="rotate(30 40 40)"/><rect x="120" '
        'y="20" width="60" height="40" fill="#e76f51" transform="translate(180 60) scale(0.5) '
        'translate(-180 -60)"/><g transform="rotate(45 50 140)"><rect x="20" y="110" '
        'width="30" height="30" fill="#2a9d8f"/><rect x="50" y="140" width="30" height="30" '
        'fill="#e9c46a"/></g><rect x="120" y="120" width="40" height="40" fill="none" '
        'stroke="#264653" stroke-width="20" transform="translate(110 110) scale(0.5) '
        'translate(-110 -110)"/><rect x="100" y="80" width="40" height="20" fill="#2a9d8f" '
        'transform="rotate(90 110 85)"/>'),
})

# -- issue 10: spaces at the end of a child element, text after a textPath ----------------------
_ARC = '<defs><path id="arc" d="M 20 120 C 40 60 100 60 120 110"/></defs>' \
    '<use href="#arc" fill="none" stroke="#bbb"/>'
CASES.update({
    'text-space-after-textpath': (
        'a space ending a textPath starts the next chunk',
        'The characters of the textPath end with a space and the text after it starts with '
        'one: the later space is kept (usvg and Chrome), so the space is not on the path and '
        'the green word starts one space after the last glyph on the path.',
        _ARC + '<text font-family="Noto Sans" font-size="22"><textPath href="#arc">Arc '
        '</textPath> <tspan fill="green">next</tspan></text>'),
    'text-after-textpath-past-its-end': (
        'text after a textPath continues from the last glyph on the path',
        'Glyphs past the end of the path are not drawn; the text after the textPath starts '
        'after the last glyph drawn (its point on the path plus its advance), on that '
        'point\'s baseline.',
        _ARC + '<text font-family="Noto Sans" font-size="22"><textPath href="#arc">'
        'Far too long for the arc</textPath><tspan fill="green">end</tspan></text>'),
    'text-space-after-tspan': (
        'a space ending a tspan before a space goes to the text after it',
        'In "a <tspan>b </tspan> c" the tspan loses its space and the text keeps its own: '
        'the tspan\'s underline and larger size end with b, and the space is the text\'s '
        '(its font size), as usvg resolves it.',
        '<text x="12" y="110" font-family="Noto Sans" font-size="20">one '
        '<tspan font-size="34" text-decoration="underline" fill="#e76f51">two </tspan> '
        'three</text>'),
    'text-invalid-textpath-separates-spaces': (
        'the characters of an invalid textPath still take part in whitespace',
        'The textPath has no path, so it draws nothing; its characters still count in the '
        'whitespace processing, so the spaces on both sides of it are both kept.',
        '<text x="100" y="110" font-family="Noto Sans" font-size="24" text-anchor="middle">'
        'Some <textPath>long</textPath> text|</text>'),
})
CASES['text-textpath-tiny-path-scaled-up'] = (
    'text on a tiny path scaled up 100 times',
    'The path and the text are a hundred times smaller than the drawing and scaled up by the '
    'group: the glyphs sit on the curve and turn with it as closely as on a large path (the '
    'path is followed within a fraction of a device pixel, not of its own units).',
    '<g transform="scale(100)"><path id="tiny" d="M 0.2 0.9 C 0.45 0.3 1.2 1.5 1.8 0.8" '
    'fill="none" stroke="#bbb" stroke-width="0.01"/><text font-family="Noto Sans" '
    'font-size="0.22" fill="#264653"><textPath href="#tiny">Tiny but smooth text</textPath>'
    '</text></g>')
