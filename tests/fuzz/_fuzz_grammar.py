"""Grammars of the fuzzers: SVG path data, CSS and whole SVG documents.

Each generator is a plain function of a :class:`random.Random`, so the same
grammar serves hypothesis (``st.randoms()``: shrinkable choices), seeded
samples (``random.Random(seed)``) and atheris (a generator seeded by the
fuzzer's bytes).  The values mix the ordinary with the hostile: zero,
negative, huge (``1e308``), tiny (``1e-9``), non-finite spellings, long
digit strings, percentages and units; references go to a small pool of ids
so that they resolve, and so that cycles and fan-outs happen.

Documents are built to paint: every one has a visible shape of moderate
size among the random content (``test_fuzz.py`` checks that a sample
draws pixels).
"""

import base64
import random
import struct
import zlib

NS = 'xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"'
IDS = ('a', 'b', 'c', 'd', 'e', 'f')

_NUMBERS = ('0', '1', '-1', '0.5', '.5', '-.5', '10', '100', '37.25', '1e3', '1e-3', '-0',
            '1e9', '-1e9', '1e38', '1e-9', '1e308', '-1e308', '1e-320', '3e400', '1E5', '+2',
            '6666666666666666661610', '0.000000000000000000001', '00012', '1.', '4e+2')
_BAD_NUMBERS = ('nan', 'inf', '-inf', 'NaN', '1e', '--1', '.', '', 'x', '1..2', '0x10')
_UNITS = ('', '', '', 'px', '%', 'em', 'ex', 'in', 'cm', 'mm', 'pt', 'pc', 'vw', 'Q')
_COLORS = ('red', 'green', 'blue', '#000', '#ff000080', 'rgb(10, 200, 30)', 'none',
           'currentColor', 'transparent', 'hsl(120, 50%, 50%)', 'rgba(0,0,255,.5)',
           'context-fill', 'bogus', '#12', 'rgb(1e308, -5, nan)')


def number(r, bad=0.05):
    """A number as SVG text (sometimes malformed)."""
    x = r.random()
    if x < bad:
        return r.choice(_BAD_NUMBERS)
    if x < 0.45:
        return r.choice(_NUMBERS)
    if x < 0.8:
        return '%g' % r.uniform(-100, 200)
    return str(r.randint(-10, 300))


def length(r):
    return number(r, 0.03) + r.choice(_UNITS)


def paint(r):
    if r.random() < 0.35:
        return 'url(#%s)' % r.choice(IDS) + r.choice(('', '', ' red', ' none'))
    return r.choice(_COLORS)


# -- path data ------------------------------------------------------------------------

_COMMANDS = 'MLHVCSQTAZmlhvcsqtaz'
_ARGS = {'M': 2, 'L': 2, 'H': 1, 'V': 1, 'C': 6, 'S': 4, 'Q': 4, 'T': 2, 'A': 7, 'Z': 0}


def path_data(r, n=None):
    """SVG path data: mostly valid commands with odd spacing and numbers,
    sometimes junk."""
    n = r.randint(0, 12) if n is None else n
    out = [r.choice(('M', 'm', 'M', 'L', ''))]
    if out[0]:
        out.append(' '.join(number(r) for _ in range(2)))
    for _ in range(n):
        c = r.choice(_COMMANDS)
        out.append(c)
        k = _ARGS[c.upper()] * r.choice((1, 1, 1, 2))
        args = []
        for i in range(k):
            if c in 'Aa' and i % 7 in (3, 4):
                args.append(r.choice(('0', '1', '1', '0', '2', '-1')))
            else:
                args.append(number(r))
        sep = r.choice((' ', ',', ' , ', '', '\n'))
        out.append(sep.join(args) if sep or not args else ' '.join(args))
        if r.random() < 0.03:
            out.append(r.choice(('#', ')', 'é', '\0', '  ', ',,')))
    return r.choice((' ', '', '\t')).join(out)


# -- CSS ------------------------------------------------------------------------------

_PROPS = ('fill', 'stroke', 'stroke-width', 'opacity', 'fill-opacity', 'display',
          'visibility', 'transform', 'stroke-dasharray', 'font-size', 'font', 'marker',
          'mix-blend-mode', 'filter', 'clip-path', 'mask', 'color', 'unknown-prop', 'x', 'r')
_TYPES = ('rect', 'circle', 'path', 'g', 'svg', 'text', 'use', '*', 'ellipse', 'polygon')


def selector(r, depth=0):
    parts = []
    for _ in range(r.randint(1, 3)):
        c = r.random()
        if c < 0.3:
            parts.append(r.choice(_TYPES))
        elif c < 0.6:
            parts.append('.c%d' % r.randint(0, 4))
        elif c < 0.75:
            parts.append('#' + r.choice(IDS))
        elif c < 0.9:
            parts.append('[%s%s]' % (r.choice(('fill', 'class', 'id', 'x')),
                                     r.choice(('', '=red', '~="c1"', '|=a', '^=c', '$="1"',
                                               '*=c i'))))
        else:
            parts.append(r.choice((':first-child', ':hover', '::before', ':not(.c1)',
                                   ':nth-child(2n+1)', '[', ')', '"')))
    s = ''.join(parts)
    if depth < 2 and r.random() < 0.4:
        s += r.choice((' ', ' > ', ' + ', ' ~ ', '>')) + selector(r, depth + 1)
    return s


def declaration(r):
    p = r.choice(_PROPS)
    if p in ('fill', 'stroke', 'color'):
        v = paint(r)
    elif p == 'transform':
        v = transform(r)
    elif p in ('display', 'visibility'):
        v = r.choice(('none', 'inline', 'hidden', 'collapse', 'bogus'))
    elif p in ('filter', 'clip-path', 'mask', 'marker'):
        v = r.choice(('url(#%s)' % r.choice(IDS), 'none', 'blur(2px)', 'drop-shadow(1px 1px)',
                      'invert(1)', 'url(', 'blur(1e9px)'))
    else:
        v = length(r)
    return '%s:%s%s' % (p, v, r.choice(('', '', ' !important', ' ! important')))


def stylesheet(r):
    """A stylesheet: rules, at-rules, comments and junk."""
    out = []
    for _ in range(r.randint(0, 8)):
        c = r.random()
        if c < 0.7:
            sels = ', '.join(selector(r) for _ in range(r.randint(1, 3)))
            decls = ';'.join(declaration(r) for _ in range(r.randint(0, 4)))
            out.append('%s{%s}' % (sels, decls))
        elif c < 0.8:
            out.append(r.choice(('@media print { rect { fill: red } }', '@import "x.css";',
                                 '@font-face { font-family: x; src: url(x.ttf) }',
                                 '@charset "utf-8";', '@unknown { { } }')))
        elif c < 0.9:
            out.append(r.choice(('/* comment */', '<!--', '-->', '/* unclosed')))
        else:
            out.append(r.choice(('}', '{', '"', "'", 'rect{fill:red', ';;', '\\')))
    return '\n'.join(out)


# -- documents -------------------------------------------------------------------------

def transform(r):
    out = []
    for _ in range(r.randint(1, 3)):
        k = r.choice(('translate', 'scale', 'rotate', 'skewX', 'skewY', 'matrix'))
        n = {'translate': 2, 'scale': r.choice((1, 2)), 'rotate': r.choice((1, 3)),
             'skewX': 1, 'skewY': 1, 'matrix': 6}[k]
        out.append('%s(%s)' % (k, ' '.join(number(r, 0.02) for _ in range(n))))
    return ' '.join(out)


def _png(r):
    """A tiny PNG, sometimes broken."""
    w, h = r.randint(1, 4), r.randint(1, 4)
    raw = b''.join(b'\0' + bytes(r.randrange(256) for _ in range(4 * w)) for _ in range(h))

    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    data = (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
    if r.random() < 0.3:
        data = data[:r.randint(0, len(data))]
    return 'data:image/png;base64,' + base64.b64encode(data).decode()


def _attrs(r, names):
    return ''.join(' %s="%s"' % (k, v) for k, v in names if r.random() < 0.7)


def _presentation(r):
    out = []
    if r.random() < 0.6:
        out.append(('fill', paint(r)))
    if r.random() < 0.4:
        out.append(('stroke', paint(r)))
        out.append(('stroke-width', length(r)))
    if r.random() < 0.15:
        out.append(('stroke-dasharray', ' '.join(number(r) for _ in range(r.randint(1, 4)))))
    if r.random() < 0.2:
        out.append(('opacity', r.choice(('0.5', '1', '0', '-1', '2', '50%'))))
    if r.random() < 0.2:
        out.append(('transform', transform(r)))
    if r.random() < 0.15:
        out.append(('class', 'c%d' % r.randint(0, 4)))
    for prop in ('clip-path', 'mask', 'filter', 'marker-start', 'marker-mid', 'marker-end'):
        if r.random() < 0.06:
            out.append((prop, 'url(#%s)' % r.choice(IDS)))
    if r.random() < 0.05:
        out.append(('style', ';'.join(declaration(r) for _ in range(2))))
    if r.random() < 0.25:
        out.append(('id', r.choice(IDS)))
    return ''.join(' %s="%s"' % kv for kv in out)


def _shape(r):
    k = r.choice(('rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon', 'path', 'path'))
    p = _presentation(r)
    if k == 'rect':
        a = _attrs(r, [('x', length(r)), ('y', length(r)), ('width', length(r)),
                       ('height', length(r)), ('rx', length(r)), ('ry', length(r))])
    elif k == 'circle':
        a = _attrs(r, [('cx', length(r)), ('cy', length(r)), ('r', length(r))])
    elif k == 'ellipse':
        a = _attrs(r, [('cx', length(r)), ('cy', length(r)), ('rx', length(r)),
                       ('ry', length(r))])
    elif k == 'line':
        a = _attrs(r, [('x1', length(r)), ('y1', length(r)), ('x2', length(r)),
                       ('y2', length(r))])
    elif k in ('polyline', 'polygon'):
        a = ' points="%s"' % ' '.join(number(r) for _ in range(2 * r.randint(0, 6)))
    else:
        a = ' d="%s"' % path_data(r)
    return '<%s%s%s/>' % (k, a, p)


def _primitive(r):
    k = r.choice(('feGaussianBlur', 'feOffset', 'feFlood', 'feColorMatrix', 'feMorphology',
                  'feTurbulence', 'feConvolveMatrix', 'feComposite', 'feBlend', 'feTile',
                  'feMerge', 'feDropShadow', 'feDiffuseLighting', 'feSpecularLighting',
                  'feDisplacementMap', 'feComponentTransfer', 'feImage', 'feBogus'))
    a = {'feGaussianBlur': [('stdDeviation', number(r))],
         'feOffset': [('dx', number(r)), ('dy', number(r))],
         'feFlood': [('flood-color', paint(r)), ('flood-opacity', number(r))],
         'feColorMatrix': [('type', r.choice(('matrix', 'saturate', 'hueRotate',
                                               'luminanceToAlpha'))),
                           ('values', ' '.join(number(r) for _ in range(r.choice((1, 20)))))],
         'feMorphology': [('radius', number(r)), ('operator', r.choice(('erode', 'dilate')))],
         'feTurbulence': [('baseFrequency', number(r)), ('numOctaves', number(r)),
                          ('type', r.choice(('turbulence', 'fractalNoise'))),
                          ('seed', number(r))],
         'feConvolveMatrix': [('order', r.choice(('3', '2 2', '1000', '0', '-1', '3 3'))),
                              ('kernelMatrix', ' '.join(number(r) for _ in range(9)))],
         'feComposite': [('operator', r.choice(('over', 'in', 'arithmetic', 'xor'))),
                         ('k1', number(r)), ('k2', number(r)), ('in2', 'SourceAlpha')],
         'feBlend': [('mode', r.choice(('multiply', 'screen', 'bogus'))), ('in2', 'r1')],
         'feDropShadow': [('stdDeviation', number(r)), ('dx', number(r))],
         'feDisplacementMap': [('scale', number(r)), ('in2', 'SourceGraphic')],
         'feImage': [('href', '#' + r.choice(IDS))]}.get(k, [])
    a.append(('result', r.choice(('r1', 'r2', ''))))
    if r.random() < 0.3:
        a += [('x', length(r)), ('width', length(r))]
    inner = ''
    if k in ('feDiffuseLighting', 'feSpecularLighting'):
        inner = r.choice(('<feDistantLight azimuth="%s" elevation="%s"/>' % (number(r), number(r)),
                          '<fePointLight x="%s" y="%s" z="%s"/>' % (number(r), number(r),
                                                                  number(r)),
                          '<feSpotLight x="1" y="1" z="%s" limitingConeAngle="%s"/>'
                          % (number(r), number(r)), ''))
    elif k == 'feMerge':
        inner = '<feMergeNode in="SourceGraphic"/><feMergeNode in="r1"/>'
    elif k == 'feComponentTransfer':
        inner = '<feFuncA type="table" tableValues="%s"/>' % ' '.join(number(r) for _ in range(3))
    return '<%s%s>%s</%s>' % (k, ''.join(' %s="%s"' % kv for kv in a), inner, k)


def _server(r, depth):
    """A paint server, clip path, mask, filter, marker or symbol with an id."""
    i = r.choice(IDS)
    k = r.choice(('linearGradient', 'radialGradient', 'pattern', 'clipPath', 'mask', 'filter',
                  'marker', 'symbol'))
    href = ' href="#%s"' % r.choice(IDS) if r.random() < 0.2 else ''
    if k in ('linearGradient', 'radialGradient'):
        stops = ''.join('<stop offset="%s" stop-color="%s"/>' % (number(r), paint(r))
                        for _ in range(r.randint(0, 3)))
        a = _attrs(r, [('gradientUnits', r.choice(('userSpaceOnUse', 'objectBoundingBox'))),
                       ('spreadMethod', r.choice(('pad', 'reflect', 'repeat'))),
                       ('x2', length(r)), ('r', length(r)),
                       ('gradientTransform', transform(r))])
        return '<%s id="%s"%s%s>%s</%s>' % (k, i, a, href, stops, k)
    if k == 'filter':
        prims = ''.join(_primitive(r) for _ in range(r.randint(0, 3)))
        a = _attrs(r, [('x', length(r)), ('width', length(r)),
                       ('filterUnits', r.choice(('userSpaceOnUse', 'objectBoundingBox'))),
                       ('primitiveUnits', r.choice(('userSpaceOnUse', 'objectBoundingBox')))])
        return '<filter id="%s"%s%s>%s</filter>' % (i, a, href, prims)
    content = ''.join(_element(r, depth + 1) for _ in range(r.randint(0, 3)))
    a = _attrs(r, [('width', length(r)), ('height', length(r)), ('x', length(r)),
                   ('viewBox', ' '.join(number(r, 0.02) for _ in range(4))),
                   ('patternUnits', r.choice(('userSpaceOnUse', 'objectBoundingBox'))),
                   ('maskUnits', 'userSpaceOnUse'), ('markerWidth', length(r)),
                   ('orient', r.choice(('auto', '45', 'auto-start-reverse'))),
                   ('clipPathUnits', 'objectBoundingBox'), ('clip-path', 'url(#%s)' % i)])
    return '<%s id="%s"%s%s>%s</%s>' % (k, i, a, href if k == 'pattern' else '', content, k)


def _element(r, depth=0):
    c = r.random()
    if depth > 4 or c < 0.45:
        return _shape(r)
    if c < 0.6:
        kids = ''.join(_element(r, depth + 1) for _ in range(r.randint(0, 4)))
        tag = r.choice(('g', 'g', 'a', 'switch', 'svg'))
        extra = (_attrs(r, [('width', length(r)), ('height', length(r)),
                            ('viewBox', ' '.join(number(r, 0.02) for _ in range(4)))])
                 if tag == 'svg' else '')
        return '<%s%s%s>%s</%s>' % (tag, extra, _presentation(r), kids, tag)
    if c < 0.72:
        return '<use href="#%s"%s%s/>' % (r.choice(IDS), _attrs(r, [('x', length(r)),
                                                                   ('width', length(r))]),
                                         _presentation(r))
    if c < 0.85:
        return '<defs>%s</defs>' % ''.join(_server(r, depth) for _ in range(r.randint(1, 3)))
    if c < 0.92:
        return '<text x="%s" y="%s"%s>%s<tspan dx="%s">%s</tspan></text>' % (
            length(r), length(r), _presentation(r), r.choice(('Hi', 'abc', '', 'ي', '\u00e9')),
            number(r), r.choice(('x', 'text', '')))
    if c < 0.96:
        return '<image width="%s" height="%s" href="%s"%s/>' % (
            length(r), length(r), _png(r), _presentation(r))
    return '<style>%s</style>' % stylesheet(r).replace('<', ' ').replace('&', ' ')


def document(r):
    """An SVG document (text) of at most a few dozen elements that paints:
    random content around a visible shape of moderate size."""
    w, h = r.choice((('64', '64'), ('64', '48'), ('100%', '64'), ('64', '1e-3'), ('0', '10'),
                     ('64', '64'), ('64', '64')))
    vb = (' viewBox="%s"' % ' '.join(number(r, 0.02) for _ in range(4))
          if r.random() < 0.25 else '')
    before = ''.join(_element(r) for _ in range(r.randint(0, 5)))
    after = ''.join(_element(r) for _ in range(r.randint(0, 3)))
    visible = '<rect x="%d" y="%d" width="%d" height="%d" fill="%s"/>' % (
        r.randint(0, 20), r.randint(0, 20), r.randint(10, 40), r.randint(10, 40),
        r.choice(('red', 'blue', 'black', '#0a0')))
    return '<svg %s width="%s" height="%s"%s>%s%s%s</svg>' % (NS, w, h, vb, before, visible,
                                                              after)


def seeded(fn, data):
    """``fn`` driven by a generator seeded with ``data`` (bytes or int)."""
    return fn(random.Random(data))
