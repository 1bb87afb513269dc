"""SVG and CSS micro-syntaxes: colours, paints, lengths, number lists, angles,
transform lists, ``transform-origin``, ``viewBox`` and ``preserveAspectRatio``.

Every parser here is a pure function of its string argument (and of a
:class:`LengthContext` for lengths).  An invalid value returns ``None``: SVG
says an attribute with an invalid value is treated as if it were absent, and
the tree builder does exactly that.  Only a wrong *type* of argument (not a
string) raises, with :class:`ValueSyntaxError`.

Coordinates follow SVG: user units, x to the right, y downward.

>>> parse_color('#0a0')
(0.0, 0.6666666666666666, 0.0, 1.0)
>>> parse_length('2in')
192.0
>>> parse_transform('translate(10) scale(2)')
Affine(2, 0, 0, 2, 10, 0)
"""

import functools
import math
import re
from typing import NamedTuple, Optional

from .._regex import lazy
from ..errors import SVGError
from ..geometry.transform import Affine

__all__ = [
    'ValueSyntaxError', 'CURRENT_COLOR', 'Paint', 'PAINT_NONE',
    'LengthContext', 'NAMED_COLORS',
    'parse_color', 'parse_paint', 'parse_number', 'parse_number_list',
    'parse_length', 'parse_length_list', 'parse_angle', 'parse_transform',
    'parse_transform_origin', 'parse_viewbox', 'resolve_viewbox', 'ZERO_VIEWBOX',
    'parse_preserve_aspect_ratio',
    'viewbox_transform', 'parse_url', 'DEFAULT_ASPECT_RATIO',
    'parse_opacity', 'parse_font_size', 'FONT_SIZE_KEYWORDS', 'PAINT_CURRENT',
    'DEFAULT_CONTEXT',
]


class ValueSyntaxError(SVGError, ValueError):
    """A micro-syntax parser was given something that is not a string."""


def _check_str(s, what):
    if not isinstance(s, str):
        raise ValueSyntaxError('%s must be a string, got %s' % (what, type(s).__name__))


# --------------------------------------------------------------------------
# numbers
# --------------------------------------------------------------------------

#: An SVG/CSS number: optional sign, digits with optional fraction (or a bare
#: fraction), optional exponent.  The exponent needs digits, so ``1em`` is the
#: number 1 followed by the unit ``em``.
NUMBER = r'[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?'
_NUM_RE = lazy(globals(), '_NUM_RE', NUMBER)
_NUM_FULL = lazy(globals(), '_NUM_FULL', r'\s*(' + NUMBER + r')\s*')
_WS = ' \t\r\n\f'


def parse_number(s):
    """Parse one number, surrounding whitespace allowed.

    Returns
    -------
    float or None
        ``None`` when `s` is not exactly one finite number.

    >>> parse_number(' -1.5e2 '), parse_number('1px'), parse_number('.5')
    (-150.0, None, 0.5)
    """
    _check_str(s, 'number')
    m = _NUM_FULL.fullmatch(s)
    if m is None:
        return None
    v = float(m.group(1))
    return v if math.isfinite(v) else None


def _valid_prefix(s):
    """The numbers of the longest valid prefix of the list `s` (slow path,
    only used on invalid input with ``strict=False``)."""
    pos, n = 0, len(s)
    out = []
    while True:
        while pos < n and s[pos] in _WS:
            pos += 1
        m = _NUM_RE.match(s, pos)
        if m is None:
            return out
        out.append(m.group(0))
        pos = m.end()
        while pos < n and s[pos] in _WS:
            pos += 1
        if pos < n and s[pos] == ',':
            pos += 1


def parse_number_list(s, strict=True):
    """Parse a list of numbers separated by commas and/or whitespace (as in
    ``viewBox``, ``points``, ``stroke-dasharray`` without units).

    As SVG allows, no separator is needed where the next number starts with a
    sign or a dot: ``'1-2.5.5'`` is ``[1, -2.5, 0.5]``.

    Parameters
    ----------
    s : str
    strict : bool
        When true, any syntax error gives ``None``.  When false, the numbers
        before the first error are returned (what SVG asks for ``points``).

    Returns
    -------
    list of float, or None
        An empty or blank string gives ``[]``.

    >>> parse_number_list('0 0, 10,20 -5-5')
    [0.0, 0.0, 10.0, 20.0, -5.0, -5.0]
    >>> parse_number_list('1,,2') is None, parse_number_list('1 2 x', strict=False)
    (True, [1.0, 2.0])
    """
    _check_str(s, 'number list')
    # fast path (C speed): plain numbers separated by whitespace/commas
    if not s.translate(_DROP_LIST_CHARS) and _commas_ok(s):
        try:
            vals = [float(x) for x in s.replace(',', ' ').split()]
        except ValueError:  # '1-2', '.5.5', '1e' ...: use the full grammar
            pass
        else:
            if all(map(math.isfinite, vals)):
                return vals
            return None
    nums = _NUM_RE.findall(s)
    # Replace every number with 'N' and drop whitespace: a valid list is then
    # 'N' runs separated by at most one comma, with no comma at either end.
    skeleton = _NUM_RE.sub('N', s).translate(_DROP_WS)
    ok = (skeleton == '' or (
        not skeleton.strip('N,') and skeleton[0] == 'N' and skeleton[-1] == 'N'
        and ',,' not in skeleton))
    if ok:
        vals = [float(x) for x in nums]
    elif strict:
        return None
    else:
        vals = [float(x) for x in _valid_prefix(s)]
    if not all(math.isfinite(v) for v in vals):
        return None
    return vals


_DROP_WS = str.maketrans('', '', _WS)
_DROP_LIST_CHARS = str.maketrans('', '', _WS + '0123456789.eE+-,')


def _commas_ok(s):
    # no comma at either end, no two commas with only whitespace between
    t = s.translate(_DROP_WS)
    return not (t.startswith(',') or t.endswith(',') or ',,' in t)


# --------------------------------------------------------------------------
# colours
# --------------------------------------------------------------------------

class _CurrentColor:
    """The ``currentColor`` keyword: resolved by the tree builder from the
    ``color`` property."""

    _inst = None

    def __new__(cls):
        if cls._inst is None:
            cls._inst = super().__new__(cls)
        return cls._inst

    def __repr__(self):
        return 'CURRENT_COLOR'

    def __reduce__(self):
        return (_CurrentColor, ())


#: Sentinel returned by :func:`parse_color` for ``currentColor``.
CURRENT_COLOR = _CurrentColor()

_NAMED = """
aliceblue f0f8ff antiquewhite faebd7 aqua 00ffff aquamarine 7fffd4 azure f0ffff
beige f5f5dc bisque ffe4c4 black 000000 blanchedalmond ffebcd blue 0000ff
blueviolet 8a2be2 brown a52a2a burlywood deb887 cadetblue 5f9ea0
chartreuse 7fff00 chocolate d2691e coral ff7f50 cornflowerblue 6495ed
cornsilk fff8dc crimson dc143c cyan 00ffff darkblue 00008b darkcyan 008b8b
darkgoldenrod b8860b darkgray a9a9a9 darkgreen 006400 darkgrey a9a9a9
darkkhaki bdb76b darkmagenta 8b008b darkolivegreen 556b2f darkorange ff8c00
darkorchid 9932cc darkred 8b0000 darksalmon e9967a darkseagreen 8fbc8f
darkslateblue 483d8b darkslategray 2f4f4f darkslategrey 2f4f4f
darkturquoise 00ced1 darkviolet 9400d3 deeppink ff1493 deepskyblue 00bfff
dimgray 696969 dimgrey 696969 dodgerblue 1e90ff firebrick b22222
floralwhite fffaf0 forestgreen 228b22 fuchsia ff00ff gainsboro dcdcdc
ghostwhite f8f8ff gold ffd700 goldenrod daa520 gray 808080 grey 808080
green 008000 greenyellow adff2f honeydew f0fff0 hotpink ff69b4
indianred cd5c5c indigo 4b0082 ivory fffff0 khaki f0e68c lavender e6e6fa
lavenderblush fff0f5 lawngreen 7cfc00 lemonchiffon fffacd lightblue add8e6
lightcoral f08080 lightcyan e0ffff lightgoldenrodyellow fafad2
lightgray d3d3d3 lightgreen 90ee90 lightgrey d3d3d3 lightpink ffb6c1
lightsalmon ffa07a lightseagreen 20b2aa lightskyblue 87cefa
lightslategray 778899 lightslategrey 778899 lightsteelblue b0c4de
lightyellow ffffe0 lime 00ff00 limegreen 32cd32 linen faf0e6 magenta ff00ff
maroon 800000 mediumaquamarine 66cdaa mediumblue 0000cd mediumorchid ba55d3
mediumpurple 9370db mediumseagreen 3cb371 mediumslateblue 7b68ee
mediumspringgreen 00fa9a mediumturquoise 48d1cc mediumvioletred c71585
midnightblue 191970 mintcream f5fffa mistyrose ffe4e1 moccasin ffe4b5
navajowhite ffdead navy 000080 oldlace fdf5e6 olive 808000 olivedrab 6b8e23
orange ffa500 orangered ff4500 orchid da70d6 palegoldenrod eee8aa
palegreen 98fb98 paleturquoise afeeee palevioletred db7093
papayawhip ffefd5 peachpuff ffdab9 peru cd853f pink ffc0cb plum dda0dd
powderblue b0e0e6 purple 800080 rebeccapurple 663399 red ff0000 rosybrown bc8f8f royalblue 4169e1
saddlebrown 8b4513 salmon fa8072 sandybrown f4a460 seagreen 2e8b57
seashell fff5ee sienna a0522d silver c0c0c0 skyblue 87ceeb slateblue 6a5acd
slategray 708090 slategrey 708090 snow fffafa springgreen 00ff7f
steelblue 4682b4 tan d2b48c teal 008080 thistle d8bfd8 tomato ff6347
turquoise 40e0d0 violet ee82ee wheat f5deb3 white ffffff whitesmoke f5f5f5
yellow ffff00 yellowgreen 9acd32
""".split()

#: The 147 SVG 1.1 named colours plus CSS 4 ``rebeccapurple`` (lower-case
#: name -> ``(r, g, b)`` bytes).
NAMED_COLORS = {
    _NAMED[i]: (int(_NAMED[i + 1][0:2], 16), int(_NAMED[i + 1][2:4], 16),
                int(_NAMED[i + 1][4:6], 16))
    for i in range(0, len(_NAMED), 2)
}
del _NAMED

_HEX_RE = lazy(globals(), '_HEX_RE', r'#([0-9a-fA-F]+)')
_FUNC_RE = lazy(globals(), '_FUNC_RE', r'([a-zA-Z]+)\s*\((.*)\)', re.S)
_ARG_RE = lazy(globals(), '_ARG_RE', r'(' + NUMBER + r')(%|deg|rad|grad|turn)?', re.I)


def _clamp01(v):
    return 0.0 if v < 0.0 else 1.0 if v > 1.0 else v


def _split_args(body):
    """Split the arguments of a colour function: ``a, b, c[, d]`` (legacy) or
    ``a b c [/ d]`` (modern).  Returns (list of (value, unit), legacy) or
    None."""
    body = body.strip()
    legacy = ',' in body
    if legacy:
        if '/' in body:
            return None
        parts = [p.strip() for p in body.split(',')]
        if len(parts) not in (3, 4):
            return None
    else:
        alpha = None
        if '/' in body:
            body, alpha = body.split('/', 1)
            alpha = alpha.strip()
        parts = body.split()
        if len(parts) != 3:
            return None
        if alpha is not None:
            parts.append(alpha)
    out = []
    for p in parts:
        m = _ARG_RE.fullmatch(p)
        if m is None:
            return None
        v = float(m.group(1))
        if not math.isfinite(v):
            return None
        out.append((v, (m.group(2) or '').lower()))
    return out, legacy


def _alpha(arg):
    v, unit = arg
    if unit == '%':
        v /= 100.0
    elif unit:
        return None
    return _clamp01(v)


def _hsl_to_rgb(h, s, l):
    """CSS Color 4 formula; `h` in degrees, `s` and `l` in [0, 1].  Exact for
    hues that are multiples of 30 degrees."""
    h = h % 360.0
    a = s * min(l, 1.0 - l)

    def f(n):
        k = (n + h / 30.0) % 12.0
        return l - a * max(-1.0, min(k - 3.0, 9.0 - k, 1.0))
    return f(0), f(8), f(4)


@functools.lru_cache(maxsize=4096)
def _parse_color(s):
    t = s.strip(_WS)
    if not t:
        return None
    low = t.lower()
    if low == 'currentcolor':
        return CURRENT_COLOR
    if low == 'transparent':
        return (0.0, 0.0, 0.0, 0.0)
    rgb = NAMED_COLORS.get(low)
    if rgb is not None:
        return (rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0, 1.0)
    if t[0] == '#':
        m = _HEX_RE.fullmatch(t)
        if m is None:
            return None
        h = m.group(1)
        if len(h) in (3, 4):
            vals = [int(c, 16) * 17 for c in h]
        elif len(h) in (6, 8):
            vals = [int(h[i:i + 2], 16) for i in range(0, len(h), 2)]
        else:
            return None
        if len(vals) == 3:
            vals.append(255)
        return tuple(v / 255.0 for v in vals)
    m = _FUNC_RE.fullmatch(t)
    if m is None:
        return None
    name = m.group(1).lower()
    split = _split_args(m.group(2))
    if split is None:
        return None
    args, legacy = split
    a = 1.0
    if len(args) == 4:
        if legacy and args[3][1]:
            return None  # resvg: no percentage alpha in the comma syntax
        a = _alpha(args[3])
        if a is None:
            return None
    if name in ('rgb', 'rgba'):
        if legacy and len({u == '%' for _, u in args[:3]}) != 1:
            return None  # numbers and percentages mixed
        out = []
        for v, unit in args[:3]:
            if unit == '%':
                v = v / 100.0
            elif unit:
                return None
            else:
                v = v / 255.0
            out.append(_clamp01(v))
        return (out[0], out[1], out[2], a)
    if name in ('hsl', 'hsla'):
        (h, hu), (s_, su), (l_, lu) = args[:3]
        scale = {'': 1.0, 'deg': 1.0, 'rad': 180.0 / math.pi,
                 'grad': 0.9, 'turn': 360.0}.get(hu)
        if scale is None or su not in ('%', '') or lu not in ('%', ''):
            return None
        r, g, b = _hsl_to_rgb(h * scale, _clamp01(s_ / 100.0), _clamp01(l_ / 100.0))
        return (_clamp01(r), _clamp01(g), _clamp01(b), a)
    return None


def parse_color(s):
    """Parse a CSS/SVG colour.

    Accepts the 147 SVG named colours, ``rebeccapurple`` and ``transparent``
    (case-insensitive), ``#rgb``, ``#rgba``, ``#rrggbb``, ``#rrggbbaa``,
    ``rgb()``/``rgba()`` with numbers (0..255) or percentages, ``hsl()``/``hsla()`` with the hue
    unitless (degrees) or in ``deg``/``rad``/``grad``/``turn``; either the
    comma syntax with an optional fourth alpha argument, or the space syntax
    with an optional ``/ alpha``.  Out-of-range components are clamped.

    Following resvg (its ``painting/fill`` tests), the comma syntax does not
    mix numbers and percentages in ``rgb()`` and takes alpha as a number only
    (``rgba(0, 127, 0, 50%)`` is invalid); the space syntax takes
    ``/ 50%``.  SVG 1.1 ``icc-color(...)`` suffixes are invalid (SVG 2 dropped
    them; resvg ignores such a paint).  CSS system colours (``ButtonFace``
    ...) are not supported and give ``None``.

    Parameters
    ----------
    s : str

    Returns
    -------
    tuple of 4 floats in [0, 1], CURRENT_COLOR, or None
        Non-premultiplied sRGB ``(r, g, b, a)``; :data:`CURRENT_COLOR` for
        ``currentColor``; ``None`` if `s` is not a colour.

    >>> parse_color('rgb(300 -5 50%)'), parse_color('rgb(300, -5, 50%)')
    ((1.0, 0.0, 0.5, 1.0), None)
    >>> parse_color('hsl(120, 100%, 50%)')
    (0.0, 1.0, 0.0, 1.0)
    >>> parse_color('currentcolor'), parse_color('ButtonFace')
    (CURRENT_COLOR, None)
    """
    _check_str(s, 'colour')
    return _parse_color(s)


# --------------------------------------------------------------------------
# paint
# --------------------------------------------------------------------------

class Paint(NamedTuple):
    """A parsed ``fill``/``stroke`` value.

    Attributes
    ----------
    kind : str
        ``'none'``, ``'color'``, ``'current'`` (currentColor), ``'url'``,
        ``'context-fill'`` or ``'context-stroke'``.
    color : tuple of 4 floats or None
        ``(r, g, b, a)`` for ``kind == 'color'``.
    url : str or None
        The referenced id (without ``#``) for ``kind == 'url'``.  A reference
        to another document keeps its full text.
    fallback : Paint or None
        For ``kind == 'url'``: the paint used when the reference cannot be
        used (``None`` when no fallback was given).
    """
    kind: str
    color: Optional[tuple] = None
    url: Optional[str] = None
    fallback: Optional['Paint'] = None


PAINT_NONE = Paint('none')
PAINT_CURRENT = Paint('current')

_URL_RE = lazy(globals(), '_URL_RE',
               r'url\(\s*(?:"([^"]*)"|\'([^\']*)\'|([^)\s]*))\s*\)', re.I)


def parse_url(s):
    """Parse a ``url(#id)`` FuncIRI (quotes allowed).

    Returns
    -------
    (str, str) or None
        The id without its leading ``#`` and the remaining text (stripped).

    >>> parse_url('url( "#a b" ) red')
    ('a b', 'red')
    """
    _check_str(s, 'url')
    t = s.strip(_WS)
    m = _URL_RE.match(t)
    if m is None:
        return None
    ref = next(g for g in m.groups() if g is not None).strip(_WS)
    if ref.startswith('#'):
        ref = ref[1:]
    if not ref:
        return None
    return ref, t[m.end():].strip(_WS)


@functools.lru_cache(maxsize=1024)
def _parse_paint(s):
    t = s.strip(_WS)
    low = t.lower()
    if low == 'none':
        return PAINT_NONE
    if low in ('context-fill', 'context-stroke'):
        return Paint(low)
    if low.startswith('url('):
        u = parse_url(t)
        if u is None:
            return None
        ref, rest = u
        fallback = None
        if rest:
            fallback = _parse_paint(rest)
            if fallback is None or fallback.kind not in ('none', 'color', 'current'):
                return None
        return Paint('url', url=ref, fallback=fallback)
    c = _parse_color(t)
    if c is None:
        return None
    if c is CURRENT_COLOR:
        return PAINT_CURRENT
    return Paint('color', color=c)


def parse_paint(s):
    """Parse an SVG paint (``fill``, ``stroke``).

    Returns
    -------
    Paint or None
        ``None`` when the value is invalid.  ``inherit`` is not handled here.

    >>> p = parse_paint('url(#g) none')
    >>> p.kind, p.url, p.fallback.kind
    ('url', 'g', 'none')
    >>> parse_paint('red').color
    (1.0, 0.0, 0.0, 1.0)
    """
    _check_str(s, 'paint')
    return _parse_paint(s)


# --------------------------------------------------------------------------
# lengths and angles
# --------------------------------------------------------------------------

class LengthContext(NamedTuple):
    """What relative lengths resolve against.

    Attributes
    ----------
    font_size : float
        Computed font size in user units (``em``; ``ex`` is half of it).
        resvg's default is 12.
    width, height : float
        Viewport size in user units, for percentages.
    dpi : float
        Pixels per inch for absolute units (CSS: 96).
    """
    font_size: float = 12.0
    width: float = 100.0
    height: float = 100.0
    dpi: float = 96.0


DEFAULT_CONTEXT = LengthContext()

#: The characters of a unitless number without spaces (see parse_length).
_PLAIN_CHARS = '0123456789.+-eE'
_LEN_RE = lazy(globals(), '_LEN_RE', r'\s*(' + NUMBER + r')([a-zA-Z]*|%)\s*')
_ABS_UNITS = {'': 1.0, 'px': 1.0, 'in': None, 'cm': 1 / 2.54, 'mm': 1 / 25.4,
              'pt': 1 / 72, 'pc': 1 / 6}
# CSS's `Q` (quarter-millimetre) unit is not an SVG length unit: resvg
# rejects it (resvg suite shapes/rect/q-values), and so do we.


def _resolve(v, unit, axis, ctx):
    unit = unit.lower()
    if unit == '' or unit == 'px':
        return v
    if unit in _ABS_UNITS:
        f = _ABS_UNITS[unit]
        return v * ctx.dpi * (1.0 if f is None else f)
    if unit == 'em':
        return v * ctx.font_size
    if unit == 'ex':
        return v * ctx.font_size / 2.0
    if unit == '%':
        if axis == 'x':
            ref = ctx.width
        elif axis == 'y':
            ref = ctx.height
        else:
            try:
                ref = math.sqrt((ctx.width ** 2 + ctx.height ** 2) / 2.0)
            except OverflowError:           # a huge viewport: the same, without squares
                ref = math.hypot(ctx.width, ctx.height) / math.sqrt(2.0)
        return v * ref / 100.0
    return None


def parse_length(s, axis='x', ctx=None):
    """Parse a length and convert it to user units.

    Units: none/``px`` (1), ``in`` (dpi), ``cm``, ``mm``, ``Q``, ``pt``
    (dpi/72), ``pc`` (dpi/6), ``em`` (font size), ``ex`` (half the font
    size), ``%`` of the viewport width (``axis='x'``), height (``'y'``) or
    diagonal/sqrt(2) (``'other'``).  Units are case-insensitive.

    Parameters
    ----------
    s : str
    axis : {'x', 'y', 'other'}
    ctx : LengthContext, optional

    Returns
    -------
    float or None
        ``None`` for invalid syntax, an unknown unit or a non-finite value.

    >>> parse_length('50%', 'y', LengthContext(width=200, height=100))
    50.0
    >>> parse_length('3pt'), parse_length('1em'), parse_length('1 px')
    (4.0, 12.0, None)
    """
    _check_str(s, 'length')
    if s and not s.strip(_PLAIN_CHARS):
        # digits, '.', signs and exponents alone: float() accepts such a
        # string exactly when it is an SVG number, and it has no unit
        try:
            v = float(s)
        except ValueError:
            return None
        return v if math.isfinite(v) else None
    if ctx is None:
        ctx = DEFAULT_CONTEXT
    m = _LEN_RE.fullmatch(s)
    if m is None:
        return None
    v = _resolve(float(m.group(1)), m.group(2), axis, ctx)
    if v is None or not math.isfinite(v):
        return None
    return v


_LEN_ITEM_RE = lazy(globals(), '_LEN_ITEM_RE', r'(' + NUMBER + r')([a-zA-Z]+|%)?')


def parse_length_list(s, axis='other', ctx=None):
    """Parse a comma/whitespace separated list of lengths (e.g.
    ``stroke-dasharray="5mm, 2%"``), each converted to user units.

    Returns
    -------
    list of float, or None on any error; ``[]`` for a blank string.

    >>> parse_length_list('1 2px,1in')
    [1.0, 2.0, 96.0]
    """
    _check_str(s, 'length list')
    if ctx is None:
        ctx = DEFAULT_CONTEXT
    items = _LEN_ITEM_RE.findall(s)
    skeleton = _LEN_ITEM_RE.sub('N', s).translate(_DROP_WS)
    if skeleton and (skeleton.strip('N,') or skeleton[0] != 'N'
                     or skeleton[-1] != 'N' or ',,' in skeleton):
        return None
    out = []
    for num, unit in items:
        v = _resolve(float(num), unit or '', axis, ctx)
        if v is None or not math.isfinite(v):
            return None
        out.append(v)
    return out


_OPACITY_RE = lazy(globals(), '_OPACITY_RE', r'\s*(' + NUMBER + r')(%?)\s*')


def parse_opacity(s):
    """Parse an opacity (``opacity``, ``fill-opacity``, ``stop-opacity``
    ...): a number or a percentage, clamped to [0, 1].

    Returns
    -------
    float or None
        ``None`` for anything else (``'0.1mm'``), as resvg treats it: the
        property is then absent.

    >>> parse_opacity('50%'), parse_opacity('1.5'), parse_opacity('0.1mm')
    (0.5, 1.0, None)
    """
    _check_str(s, 'opacity')
    m = _OPACITY_RE.fullmatch(s)
    if m is None:
        return None
    v = float(m.group(1))
    if m.group(2):
        v /= 100.0
    if not math.isfinite(v):
        return None
    return _clamp01(v)


#: Steps of the absolute font-size keywords from ``medium``; each step
#: scales by 1.2 (measured on resvg's ``text/font-size/named-value`` test).
FONT_SIZE_KEYWORDS = {'xx-small': -3, 'x-small': -2, 'small': -1, 'medium': 0,
                      'large': 1, 'x-large': 2, 'xx-large': 3}


def parse_font_size(s, parent_size=12.0, ctx=None, medium=12.0):
    """Parse a ``font-size`` value into user units.

    Parameters
    ----------
    s : str
    parent_size : float
        The parent's computed font size: ``em``, ``ex`` (half) and ``%``
        refer to it, ``larger``/``smaller`` multiply/divide it by 1.2.
    ctx : LengthContext, optional
        For absolute units (only ``dpi`` is used).
    medium : float
        Size of the ``medium`` keyword; the other absolute keywords are
        ``medium * 1.2**k``, ``k`` from -3 (``xx-small``) to 3 (``xx-large``).

    Returns
    -------
    float or None
        ``None`` when invalid or negative.

    >>> round(parse_font_size('large'), 9), parse_font_size('200%', 10)
    (14.4, 20.0)
    >>> parse_font_size('smaller', 12)
    10.0
    """
    _check_str(s, 'font-size')
    t = s.strip(_WS).lower()
    k = FONT_SIZE_KEYWORDS.get(t)
    if k is not None:
        return medium * 1.2 ** k if k >= 0 else medium / 1.2 ** -k
    if t == 'larger':
        return parent_size * 1.2
    if t == 'smaller':
        return parent_size / 1.2
    base = DEFAULT_CONTEXT if ctx is None else ctx
    c = LengthContext(font_size=parent_size, width=parent_size, height=parent_size,
                      dpi=base.dpi)
    v = parse_length(s, 'x', c)
    if v is None or v < 0:
        return None
    return v


_ANGLE_RE = lazy(globals(), '_ANGLE_RE', r'\s*(' + NUMBER + r')(deg|rad|grad|turn)?\s*',
                 re.I)
_ANGLE_UNITS = {'': 1.0, 'deg': 1.0, 'rad': 180 / math.pi, 'grad': 0.9, 'turn': 360.0}


def parse_angle(s):
    """Parse an angle (unitless = degrees, ``deg``, ``rad``, ``grad``,
    ``turn``) and return it in degrees, or ``None``.

    >>> parse_angle('0.25turn'), parse_angle('100grad'), parse_angle('90')
    (90.0, 90.0, 90.0)
    """
    _check_str(s, 'angle')
    m = _ANGLE_RE.fullmatch(s)
    if m is None:
        return None
    v = float(m.group(1)) * _ANGLE_UNITS[(m.group(2) or '').lower()]
    return v if math.isfinite(v) else None


# --------------------------------------------------------------------------
# transforms
# --------------------------------------------------------------------------

_TF_RE = lazy(globals(), '_TF_RE', r'[ \t\r\n]*(matrix|translate|scale|rotate|skewX|skewY)'
              r'[ \t\r\n]*\(([^()]*)\)[ \t\r\n]*')
_TF_NARGS = {'matrix': (6,), 'translate': (1, 2), 'scale': (1, 2),
             'rotate': (1, 3), 'skewX': (1,), 'skewY': (1,)}


def _tf_one(name, args):
    if name == 'matrix':
        return Affine(*args)
    if name == 'translate':
        return Affine.translate(args[0], args[1] if len(args) > 1 else 0.0)
    if name == 'scale':
        return Affine.scale(args[0], args[1] if len(args) > 1 else None)
    if name == 'rotate':
        if len(args) == 3:
            return Affine.rotate(args[0], args[1], args[2])
        return Affine.rotate(args[0])
    if name == 'skewX':
        return Affine.skew_x(args[0])
    return Affine.skew_y(args[0])


_CSS_TF_RE = lazy(globals(), '_CSS_TF_RE',
                  r'[ \t\r\n]*([a-zA-Z]+)[ \t\r\n]*\(([^()]*)\)[ \t\r\n]*')
_ANGLE_FUNCS = {'rotate', 'skew', 'skewx', 'skewy'}
_LENGTH_FUNCS = {'translate', 'translatex', 'translatey'}
_CSS_NARGS = {'matrix': (6,), 'translate': (1, 2), 'translatex': (1,),
              'translatey': (1,), 'scale': (1, 2), 'scalex': (1,), 'scaley': (1,),
              'rotate': (1, 3), 'skew': (1, 2), 'skewx': (1,), 'skewy': (1,)}


def _css_tf_args(name, body):
    """Arguments of a CSS transform function, converted to numbers (angles
    to degrees, lengths to px); ``None`` when invalid."""
    items = _LEN_ITEM_RE.findall(body)
    skeleton = _LEN_ITEM_RE.sub('N', body).translate(_DROP_WS)
    if not skeleton or skeleton.strip('N,') or skeleton[0] != 'N' or \
            skeleton[-1] != 'N' or ',,' in skeleton:
        return None
    out = []
    for i, (num, unit) in enumerate(items):
        v = float(num)
        unit = unit.lower()
        if name in _ANGLE_FUNCS and i == 0 or name in ('skew',):
            f = _ANGLE_UNITS.get(unit)
            if f is None:
                return None
            v *= f
        elif name in _LENGTH_FUNCS or (name == 'rotate' and i > 0):
            if unit == '%' or unit in ('em', 'ex'):
                return None
            v = _resolve(v, unit, 'x', DEFAULT_CONTEXT)
            if v is None:
                return None
        elif name in ('scale', 'scalex', 'scaley') and unit == '%':
            v /= 100.0
        elif unit:
            return None
        if not math.isfinite(v):
            return None
        out.append(v)
    return out


def _css_tf_one(name, a):
    if name == 'translate':
        return Affine.translate(a[0], a[1] if len(a) > 1 else 0.0)
    if name == 'translatex':
        return Affine.translate(a[0], 0.0)
    if name == 'translatey':
        return Affine.translate(0.0, a[0])
    if name == 'scale':
        return Affine.scale(a[0], a[1] if len(a) > 1 else None)
    if name == 'scalex':
        return Affine.scale(a[0], 1.0)
    if name == 'scaley':
        return Affine.scale(1.0, a[0])
    if name == 'skew':
        return Affine(1, math.tan(math.radians(a[1])) if len(a) > 1 else 0.0,
                      math.tan(math.radians(a[0])), 1, 0, 0)
    return _tf_one({'skewx': 'skewX', 'skewy': 'skewY'}.get(name, name), a)


# The one-function lists that real documents are full of (chart and map
# generators emit ``translate(x,y)`` per element): parsed without building
# intermediate transforms.  Anything else takes the general path below.
_TF_SIMPLE_RE = lazy(globals(), '_TF_SIMPLE_RE', r'[ \t\r\n]*(translate|scale|matrix)[ \t\r\n]*'
                     r'\(([^()]*)\)[ \t\r\n]*')


# ``translate(x[ y])`` with plain separators: one regular expression
# reads it all (a subset of what the paths below accept, same values).
_TF_TRANSLATE_RE = lazy(
    globals(), '_TF_TRANSLATE_RE',
    r'[ \t\r\n]*translate[ \t\r\n]*\([ \t\r\n\f]*(' + NUMBER + r')'
    r'(?:(?:[ \t\r\n\f]+,?|,)[ \t\r\n\f]*(' + NUMBER + r'))?[ \t\r\n\f]*\)[ \t\r\n]*')


def _simple_transform(s):
    """``translate``/``scale``/``matrix`` alone (same arguments as the
    general path accepts), or None when ``s`` is not that form."""
    m = _TF_TRANSLATE_RE.fullmatch(s)
    if m is not None:
        x, y = m.group(1, 2)
        x = float(x)
        y = 0.0 if y is None else float(y)
        if math.isfinite(x) and math.isfinite(y):
            return Affine(1.0, 0.0, 0.0, 1.0, x, y)
    m = _TF_SIMPLE_RE.fullmatch(s)
    if m is None:
        return None
    name = m.group(1)
    args = parse_number_list(m.group(2))
    if args is None:
        return None
    n = len(args)
    if name == 'translate' and (n == 1 or n == 2):
        return Affine(1.0, 0.0, 0.0, 1.0, args[0], args[1] if n == 2 else 0.0)
    if name == 'scale' and (n == 1 or n == 2):
        return Affine(args[0], 0.0, 0.0, args[-1], 0.0, 0.0)
    if name == 'matrix' and n == 6:
        return Affine(*args)
    return None


@functools.lru_cache(maxsize=8192)
def _parse_transform(s, css):
    if not css:
        try:
            t = _simple_transform(s)
        except Exception:     # non-finite values: the general path decides
            t = None
        if t is not None:
            return t
    return _transform_list(s, css)


def _transform_list(s, css):
    """The general transform-list parser behind :func:`parse_transform`."""
    if css and s.strip(_WS).lower() == 'none':
        return Affine()
    pos, n = 0, len(s)
    out = Affine()
    need_more = False
    regex = _CSS_TF_RE if css else _TF_RE
    while True:
        m = regex.match(s, pos)
        if m is None:
            break
        if css:
            name = m.group(1).lower()
            if name not in _CSS_NARGS:
                return None
            args = _css_tf_args(name, m.group(2))
            if args is None or len(args) not in _CSS_NARGS[name]:
                return None
        else:
            name = m.group(1)
            args = parse_number_list(m.group(2))
            if args is None or len(args) not in _TF_NARGS[name]:
                return None
        try:
            out = out @ (_css_tf_one(name, args) if css else _tf_one(name, args))
        except Exception:  # non-finite results (overflow)
            return None
        pos = m.end()
        need_more = False
        if pos < n and s[pos] == ',':
            pos += 1
            need_more = True
    if need_more or s[pos:].strip(_WS):
        return None
    return out


def parse_transform(s, css=False):
    """Parse an SVG transform list, or a CSS ``transform`` value.

    SVG syntax (``css=False``): ``matrix(a b c d e f)``, ``translate(tx
    [ty])``, ``scale(sx [sy])``, ``rotate(deg [cx cy])``, ``skewX(deg)``,
    ``skewY(deg)``; arguments and functions separated by commas and/or
    whitespace (or nothing between functions); names are case-sensitive.

    CSS syntax (``css=True``, for a ``transform`` that came from a style
    sheet or ``style`` attribute): also ``none``, ``translateX/Y``,
    ``scaleX/Y``, ``skew(ax [, ay])``, case-insensitive names; angles may
    carry ``deg``/``rad``/``grad``/``turn`` and translations absolute length
    units (``px``, ``in``, ``mm`` ...; percentages are refused since there is
    no reference box); unitless values are accepted as in SVG.

    Either way the list composes left to right: the rightmost function
    applies first.

    Returns
    -------
    Affine or None
        Identity for an empty/blank string; ``None`` on any syntax error, in
        which case the whole attribute is ignored (resvg does the same).  A
        singular result (``matrix(0 0 0 0 0 0)``) is returned as is: the tree
        builder does not render such an element.

    >>> parse_transform('rotate(90, 10, 10)')
    Affine(0, 1, -1, 0, 20, 0)
    >>> parse_transform('scale(2) foo(1)') is None
    True
    >>> parse_transform('translateX(1in) rotate(0.25turn)', css=True)
    Affine(0, 1, -1, 0, 96, 0)
    """
    _check_str(s, 'transform')
    return _parse_transform(s, bool(css))


_KW_X = {'left': 0.0, 'center': 50.0, 'right': 100.0}
_KW_Y = {'top': 0.0, 'center': 50.0, 'bottom': 100.0}


def parse_transform_origin(s, ctx=None, box=None):
    """Parse ``transform-origin`` into a point in user units.

    The reference box (CSS Transforms 1, ``transform-box``) is the viewport
    by default (``view-box``: at the user-space origin, ``ctx.width`` x
    ``ctx.height``); ``box`` ``(x, y, w, h)`` gives another one (the
    ``fill-box`` or ``stroke-box`` of the element): percentages and
    keywords are fractions of its size and every offset starts at its
    corner ``(x, y)``.

    One or two values (a third, the z offset, is accepted and ignored): each a
    length, a percentage of the viewport (``ctx.width``/``ctx.height``) or a
    keyword ``left``/``center``/``right``/``top``/``bottom``; x first, except
    that two keywords may come in either order (``bottom right``).  A single value sets x (or y for
    ``top``/``bottom``); the other coordinate is ``center``.

    Returns
    -------
    (float, float) or None

    >>> parse_transform_origin('right bottom', LengthContext(width=200, height=100))
    (200.0, 100.0)
    >>> parse_transform_origin('25% top', LengthContext(width=200, height=100))
    (50.0, 0.0)
    """
    _check_str(s, 'transform-origin')
    if ctx is None:
        ctx = DEFAULT_CONTEXT
    parts = s.split()
    if not 1 <= len(parts) <= 3:
        return None
    if len(parts) == 3:
        if parse_length(parts[2], 'other', ctx) is None or parts[2].endswith('%'):
            return None
        parts = parts[:2]
    if len(parts) == 1:
        if parts[0].lower() in ('top', 'bottom'):
            parts = ['center', parts[0]]
        else:
            parts = [parts[0], 'center']
    a, b = parts[0].lower(), parts[1].lower()
    # swap when the first is a y keyword or the second an x keyword
    if a in ('top', 'bottom') or b in ('left', 'right'):
        if a in ('left', 'right') or b in ('top', 'bottom') or \
                a not in _KW_Y or b not in _KW_X:
            return None  # e.g. 'top 10px': only keyword pairs may swap
        a, b = b, a
        parts = parts[::-1]

    bx, by, bw, bh = (0.0, 0.0, ctx.width, ctx.height) if box is None else box

    def one(word, raw, kw, axis):
        size = bw if axis == 'x' else bh
        if word in kw:
            return kw[word] * size / 100.0
        if word in _KW_X or word in _KW_Y:
            return None
        if box is not None and raw.endswith('%'):
            try:
                v = float(raw[:-1])
            except ValueError:
                return None
            return v * size / 100.0 if math.isfinite(v) else None
        return parse_length(raw, axis, ctx)
    x = one(a, parts[0], _KW_X, 'x')
    y = one(b, parts[1], _KW_Y, 'y')
    if x is None or y is None:
        return None
    return (bx + x, by + y)


# --------------------------------------------------------------------------
# viewBox and preserveAspectRatio
# --------------------------------------------------------------------------

def parse_viewbox(s):
    """Parse ``viewBox="min-x min-y width height"``.

    Returns
    -------
    (float, float, float, float) or None
        ``None`` on a syntax error, a wrong count, or a width or height that
        is zero or negative (see :func:`resolve_viewbox` for what each
        means to an element).

    >>> parse_viewbox('0,0 100 50'), parse_viewbox('0 0 0 10')
    ((0.0, 0.0, 100.0, 50.0), None)
    """
    v = parse_number_list(s)
    if v is None or len(v) != 4 or v[2] <= 0 or v[3] <= 0:
        return None
    return tuple(v)


#: What :func:`resolve_viewbox` returns for a viewBox with a zero side.
ZERO_VIEWBOX = 'zero'


def resolve_viewbox(s):
    """What a ``viewBox`` attribute value (or None when absent) does to its
    element.

    Returns
    -------
    (float, float, float, float), None or ZERO_VIEWBOX
        The box; None when absent or invalid -- a syntax error, a count
        other than four, a negative width or height: SVG 2 says such a
        value invalidates the attribute, so the element is drawn as if it
        had none (resvg does the same); :data:`ZERO_VIEWBOX` when the width
        or height is zero, which disables rendering of the element (SVG 1.1
        and 2; resvg draws it as if it had no viewBox).

    >>> resolve_viewbox('0 0 10 5'), resolve_viewbox('0 0 -10 5'), resolve_viewbox('0 0 0 5')
    ((0.0, 0.0, 10.0, 5.0), None, 'zero')
    """
    if s is None:
        return None
    v = parse_number_list(s)
    if v is None or len(v) != 4 or v[2] < 0 or v[3] < 0:
        return None
    if v[2] == 0 or v[3] == 0:
        return ZERO_VIEWBOX
    return tuple(v)


_ALIGNS = frozenset(['none', 'xMinYMin', 'xMidYMin', 'xMaxYMin', 'xMinYMid',
                     'xMidYMid', 'xMaxYMid', 'xMinYMax', 'xMidYMax', 'xMaxYMax'])

#: The initial ``preserveAspectRatio``.
DEFAULT_ASPECT_RATIO = ('xMidYMid', 'meet')


def parse_preserve_aspect_ratio(s):
    """Parse ``preserveAspectRatio="[defer] <align> [meet | slice]"``.

    Keywords are case-sensitive.  ``defer`` is accepted and dropped.

    Returns
    -------
    (str, str) or None
        ``(align, 'meet' | 'slice')``; ``None`` when invalid (use
        :data:`DEFAULT_ASPECT_RATIO`).

    >>> parse_preserve_aspect_ratio(' xMinYMax slice ')
    ('xMinYMax', 'slice')
    """
    _check_str(s, 'preserveAspectRatio')
    parts = s.split()
    if parts and parts[0] == 'defer':
        parts = parts[1:]
    if not 1 <= len(parts) <= 2 or parts[0] not in _ALIGNS:
        return None
    mos = parts[1] if len(parts) == 2 else 'meet'
    if mos not in ('meet', 'slice'):
        return None
    return (parts[0], mos)


def viewbox_transform(viewbox, par, width, height, x=0.0, y=0.0):
    """The transform from viewBox coordinates to a viewport.

    Implements SVG's algorithm: with ``align='none'`` x and y scale
    independently to fill the viewport; otherwise one uniform scale, the
    smaller (``meet``: all visible) or the larger (``slice``: viewport
    covered) of the two, and the box is aligned at the min/mid/max of each
    axis.

    Parameters
    ----------
    viewbox : (minx, miny, w, h) floats, w and h > 0
    par : (align, meet_or_slice) or None (default ``xMidYMid meet``)
    width, height : float
        Viewport size in user units of the parent.
    x, y : float
        Viewport origin.

    Returns
    -------
    Affine

    Raises
    ------
    ValueSyntaxError
        For a viewBox size that is not positive or an unknown `par`.

    >>> viewbox_transform((0, 0, 100, 50), ('xMidYMid', 'meet'), 200, 200)
    Affine(2, 0, 0, 2, 0, 50)
    """
    minx, miny, vw, vh = (float(v) for v in viewbox)
    if not (vw > 0 and vh > 0):
        raise ValueSyntaxError('viewBox width and height must be positive')
    align, mos = par if par is not None else DEFAULT_ASPECT_RATIO
    if align not in _ALIGNS or mos not in ('meet', 'slice'):
        raise ValueSyntaxError('bad preserveAspectRatio %r' % (par,))
    sx, sy = width / vw, height / vh
    if align == 'none':
        return Affine(sx, 0, 0, sy, x - minx * sx, y - miny * sy)
    s = min(sx, sy) if mos == 'meet' else max(sx, sy)
    tx = x - minx * s
    ty = y - miny * s
    ax, ay = align[1:4], align[5:8]
    if ax == 'Mid':
        tx += (width - vw * s) / 2.0
    elif ax == 'Max':
        tx += width - vw * s
    if ay == 'Mid':
        ty += (height - vh * s) / 2.0
    elif ay == 'Max':
        ty += height - vh * s
    return Affine(s, 0, 0, s, tx, ty)
