"""A small CSS parser, selector matcher and the SVG style cascade.

What is supported
-----------------
* Stylesheets: comments, ``<!--``/``-->`` tokens, rules
  ``selector-list { name: value; name: value !important }``, at-rules
  (``@media``, ``@import``, ``@font-face``, ... with or without a block)
  skipped as a whole, invalid declarations skipped one by one, a rule with an
  invalid selector dropped.
* Selectors: type (matches the element's local name, case-sensitive as in
  XML), ``*``, ``.class``, ``#id``, attribute selectors ``[a]``, ``[a=v]``,
  ``[a~=v]``, ``[a|=v]``, ``[a^=v]``, ``[a$=v]``, ``[a*=v]`` (value quoted or
  not, optional ``i`` flag), combinators descendant (whitespace), child
  ``>``, adjacent sibling ``+`` and general sibling ``~``, the pseudo-classes
  ``:root``, ``:first-child``, ``:last-child``, ``:only-child``,
  ``:nth-child(an+b)``, ``:nth-last-child()``, ``:first-of-type``,
  ``:last-of-type``, ``:only-of-type``, ``:nth-of-type()``,
  ``:nth-last-of-type()`` (``odd``, ``even``, ``an+b``; no ``of S``),
  ``:empty`` (no element children and no text), ``:lang(ranges)`` (the
  nearest ``xml:lang`` or ``lang`` of the element or an ancestor, equal to a
  range or beginning with it and ``-``) and ``:not(selector list)``.  Any
  other pseudo-class or pseudo-element parses but never matches; a bad
  ``an+b`` or ``:not()`` argument drops the rule.
* Specificity ``(ids, classes + attributes + pseudo-classes, types)`` with
  source order breaking ties.

The cascade (:func:`declared_styles`), lowest priority first:

1. presentation attributes (see :data:`raster.parser.properties.PRESENTATION_ATTRIBUTES`);
2. normal stylesheet declarations, by specificity then source order;
3. normal declarations of the ``style`` attribute;
4. ``!important`` stylesheet declarations, by specificity then order;
5. ``!important`` declarations of the ``style`` attribute.

Only properties of :data:`raster.parser.properties.PROPERTIES` are kept (a
``height`` in CSS is ignored, as resvg does for SVG 1.1 geometry).  The
shorthands ``marker`` and ``font`` are expanded.  Values are trimmed strings;
``inherit`` (and ``initial``/``unset``) are kept as is for the tree builder to
resolve.  A ``transform`` entry can only come from CSS (the attribute is not a
presentation attribute), so it is CSS syntax: parse it with
``raster.parser.values.parse_transform(value, css=True)``; it replaces the
element's ``transform`` attribute.

Cost: rules are indexed by the id, first class or type of their rightmost
compound, so an element is only tested against rules that can match it; with
no ``<style>`` at all only attributes are read.  Matching caches results per
(element, compound) during a pass, so descendant and sibling combinators stay
linear on deep trees.  The tests (candidate rules summed over the elements)
are counted before any is made: beyond ``max_css_matches``
(:mod:`raster.limits`) the stylesheets are ignored with one
:class:`~raster.errors.RasterWarning` (presentation attributes and
``style`` attributes still apply).

>>> from lxml import etree
>>> root = etree.fromstring(
...     '<svg xmlns="http://www.w3.org/2000/svg"><style>rect{fill:green}'
...     '.a{fill:blue}</style><rect class="a" fill="red" stroke="black"/></svg>')
>>> styles = declared_styles(root)
>>> sorted(styles[root[1]].items())
[('fill', 'blue'), ('stroke', 'black')]
"""

import functools
import re
import warnings
from typing import NamedTuple

from .._regex import lazy
from .. import limits
from ..errors import RasterWarning, SVGError
from .properties import PROPERTIES, PRESENTATION_ATTRIBUTES

__all__ = ['CSSError', 'Declaration', 'Rule', 'Selector', 'parse_stylesheet', 'font_face_rules',
           'parse_declarations', 'parse_selector', 'parse_selector_list', 'declared_styles',
           'select', 'SVG_NS']

SVG_NS = 'http://www.w3.org/2000/svg'


class CSSError(SVGError, ValueError):
    """Invalid selector syntax (raised by :func:`parse_selector_list` and
    :func:`select` only; stylesheets skip what they cannot parse)."""


class Declaration(NamedTuple):
    """``name: value [!important]`` with `name` lower-cased, `value` trimmed."""
    name: str
    value: str
    important: bool


# --------------------------------------------------------------------------
# tokenizing helpers
# --------------------------------------------------------------------------

_STRING_OR_COMMENT_RE = lazy(globals(), '_STRING_OR_COMMENT_RE', 
    r'"(?:[^"\\\n]|\\.)*"|\'(?:[^\'\\\n]|\\.)*\'|/\*.*?(?:\*/|\Z)', re.S)


def _strip_comments(text):
    """Remove comments (not inside strings) and the CDO/CDC tokens."""
    if '/*' in text:
        text = _STRING_OR_COMMENT_RE.sub(
            lambda m: ' ' if m.group(0).startswith('/*') else m.group(0), text)
    if '<!--' in text or '-->' in text:
        text = text.replace('<!--', ' ').replace('-->', ' ')
    return text


#: Per set of stop characters, a pattern finding the next character that
#: matters to :func:`_scan_to` (a quote, a bracket or a stop).
_SCAN_RES = {}


def _scan_to(text, pos, stops):
    """Index of the first character of `stops` at nesting depth 0 (outside
    strings, parentheses and brackets) from `pos`, or ``len(text)``."""
    find = _SCAN_RES.get(stops)
    if find is None:
        find = _SCAN_RES[stops] = re.compile('[%s]' % re.escape('"\'()[]' + stops)).search
    n = len(text)
    depth = 0
    while True:
        m = find(text, pos)
        if m is None:
            return n
        pos = m.start()
        ch = text[pos]
        if ch == '"' or ch == "'":
            end = text.find(ch, pos + 1)
            while end != -1 and text[end - 1] == '\\':
                end = text.find(ch, end + 1)
            if end == -1:
                return n
            pos = end + 1
            continue
        if depth == 0 and ch in stops:
            return pos
        if ch in '([':
            depth += 1
        elif ch in ')]':
            depth = max(depth - 1, 0)
        pos += 1


def _skip_block(text, pos):
    """`pos` is at '{': return the index after the matching '}'."""
    n = len(text)
    depth = 0
    while pos < n:
        ch = text[pos]
        if ch == '"' or ch == "'":
            end = text.find(ch, pos + 1)
            pos = n if end == -1 else end + 1
            continue
        if ch == '{':
            depth += 1
        elif ch == '}':
            depth -= 1
            if depth == 0:
                return pos + 1
        pos += 1
    return n


# --------------------------------------------------------------------------
# declarations
# --------------------------------------------------------------------------

_IMPORTANT_RE = lazy(globals(), '_IMPORTANT_RE', r'!\s*important\s*$', re.I)
_PROP_NAME_RE = lazy(globals(), '_PROP_NAME_RE', r'-?[_a-zA-Z][_a-zA-Z0-9-]*')


def _split_decls(text):
    out = []
    pos, n = 0, len(text)
    while pos < n:
        end = _scan_to(text, pos, ';')
        out.append(text[pos:end])
        pos = end + 1
    return out


@functools.lru_cache(maxsize=4096)
def _parse_declarations(text):
    out = []
    if '"' in text or "'" in text or '(' in text or '/*' in text or '<!--' in text:
        chunks = _split_decls(_strip_comments(text))
    else:
        chunks = text.split(';')
    for chunk in chunks:
        name, colon, value = chunk.partition(':')
        if not colon:
            continue
        name = name.strip().lower()
        if not _PROP_NAME_RE.fullmatch(name):
            continue
        important = False
        m = _IMPORTANT_RE.search(value)
        if m is not None:
            important = True
            value = value[:m.start()]
        value = value.strip()
        if not value or '!' in value:
            continue
        out.extend(_expand(name, value, important))
    return tuple(out)


def parse_declarations(text):
    """Parse a declaration list (a ``style`` attribute or a rule body).

    Shorthands (``marker``, ``font``) are expanded into their longhands;
    declarations without a colon, with an empty value or a stray ``!`` are
    skipped.

    Parameters
    ----------
    text : str

    Returns
    -------
    tuple of Declaration

    >>> for d in parse_declarations('fill: red !important; ; bogus; Stroke :blue'):
    ...     print(d)
    Declaration(name='fill', value='red', important=True)
    Declaration(name='stroke', value='blue', important=False)
    """
    if not isinstance(text, str):
        raise CSSError('declarations must be a string, got %s' % type(text).__name__)
    return _parse_declarations(text)


_FONT_STYLE = {'italic', 'oblique'}
_FONT_VARIANT = {'small-caps'}
_FONT_WEIGHT = {'bold', 'bolder', 'lighter', '100', '200', '300', '400', '500',
                '600', '700', '800', '900'}
_FONT_STRETCH = {'ultra-condensed', 'extra-condensed', 'condensed',
                 'semi-condensed', 'semi-expanded', 'expanded',
                 'extra-expanded', 'ultra-expanded'}
_FONT_SIZE_KW = {'xx-small', 'x-small', 'small', 'medium', 'large', 'x-large',
                 'xx-large', 'xxx-large', 'larger', 'smaller'}
_SIZE_RE = lazy(globals(), '_SIZE_RE', r'(?:[+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?'
                      r'(?:[a-zA-Z]+|%)?)$')


def _expand_font(value, important):
    """The CSS ``font`` shorthand: ``[style || variant || weight ||
    stretch] size[/line-height] family``; ``None`` if not of that form
    (system fonts such as ``caption`` are not supported)."""
    if value.lower() == 'inherit':
        return [Declaration(n, 'inherit', important) for n in _FONT_LONGHANDS]
    words = []
    pos, n = 0, len(value)
    # split on whitespace outside quotes until the family starts
    while pos < n:
        while pos < n and value[pos].isspace():
            pos += 1
        end = pos
        while end < n and not value[end].isspace() and value[end] not in '"\'':
            end += 1
        words.append((value[pos:end], pos))
        if end < n and value[end] in '"\'':
            break
        pos = end
    got = {}
    for i, (w, start) in enumerate(words):
        low = w.lower()
        size = None
        if '/' in w:
            size, lh = w.split('/', 1)
        else:
            size, lh = w, None
        if size and (size.lower() in _FONT_SIZE_KW or _SIZE_RE.match(size)) and \
                'font-size' not in got and (lh is not None or low not in _FONT_WEIGHT):
            got['font-size'] = size
            if lh is not None:
                if not lh:
                    return None
                got['line-height'] = lh
            family = value[start + len(w):].strip()
            if lh is None and family.startswith('/'):
                return None
            if not family:
                return None
            got['font-family'] = family
            break
        if low == 'normal':
            continue
        if low in _FONT_STYLE and 'font-style' not in got:
            got['font-style'] = w
        elif low in _FONT_VARIANT and 'font-variant' not in got:
            got['font-variant'] = w
        elif low in _FONT_WEIGHT and 'font-weight' not in got:
            got['font-weight'] = w
        elif low in _FONT_STRETCH and 'font-stretch' not in got:
            got['font-stretch'] = w
        else:
            return None
    if 'font-family' not in got:
        return None
    return [Declaration(name, got.get(name, PROPERTIES[name].initial
                                      if name in ('font-size', 'font-family')
                                      else 'normal'), important)
            for name in _FONT_LONGHANDS] + \
        [Declaration(name, PROPERTIES[name].initial, important) for name in _FONT_RESETS]


_FONT_LONGHANDS = ('font-style', 'font-variant', 'font-weight', 'font-stretch',
                   'font-size', 'line-height', 'font-family')
# reset to their initial values by the shorthand without being settable in it
# (CSS Fonts 4, section 2.8)
_FONT_RESETS = ('font-kerning', 'font-feature-settings', 'font-variation-settings')


def _expand(name, value, important):
    if name == 'marker':
        return [Declaration(n, value, important)
                for n in ('marker-start', 'marker-mid', 'marker-end')]
    if name == 'font':
        d = _expand_font(value, important)
        return d if d is not None else []
    return [Declaration(name, value, important)]


# --------------------------------------------------------------------------
# selectors
# --------------------------------------------------------------------------

_IDENT = r'-?(?:[_a-zA-Z]|[^\x00-\x7f]|\\.)(?:[_a-zA-Z0-9-]|[^\x00-\x7f]|\\.)*'
_IDENT_RE = lazy(globals(), '_IDENT_RE', _IDENT)
_ATTR_RE = lazy(globals(), '_ATTR_RE', 
    r'\[\s*(' + _IDENT + r')\s*(?:([~|^$*]?=)\s*(?:(' + _IDENT + r')|"((?:[^"\\]|\\.)*)"'
    r'|\'((?:[^\'\\]|\\.)*)\')\s*(?:([iIsS])\s*)?)?\]')
_ESC_RE = lazy(globals(), '_ESC_RE', r'\\(.)', re.S)
_NAME_RE = lazy(globals(), '_NAME_RE', r'(?:[_a-zA-Z0-9-]|[^\x00-\x7f]|\\.)+')


def _unescape(s):
    return _ESC_RE.sub(r'\1', s) if '\\' in s else s


class _Compound:
    """A compound selector: tag, id, classes, attribute tests, pseudo-classes."""

    __slots__ = ('tag', 'id', 'classes', 'attrs', 'pseudos', 'never')

    def __init__(self):
        self.tag = None        # None = any
        self.id = None
        self.classes = ()
        self.attrs = ()        # (name, op, value, case_insensitive)
        self.pseudos = ()      # (kind, argument): see _PSEUDO_TESTS
        self.never = False     # an unsupported pseudo-class

    def specificity(self):
        b = len(self.classes) + len(self.attrs) + self.never
        a = c = 0
        for kind, arg in self.pseudos:
            if kind == 'not':        # the most specific selector of its list
                sa, sb, sc = max(s.specificity for s in arg)
                a, b, c = a + sa, b + sb, c + sc
            else:
                b += 1
        return (a + (1 if self.id is not None else 0), b,
                c + (1 if self.tag is not None else 0))

    def matches(self, el, local, memo=None):
        if self.never:
            return False
        if self.tag is not None and self.tag != local:
            return False
        if self.id is not None and el.get('id') != self.id:
            return False
        if self.classes:
            cls = el.get('class')
            if cls is None:
                return False
            have = cls.split()
            for c in self.classes:
                if c not in have:
                    return False
        for name, op, val, ci in self.attrs:
            v = el.get(name)
            if v is None:
                return False
            if op is None:
                continue
            if ci:
                v, val = v.lower(), val.lower()
            if op == '=':
                ok = v == val
            elif op == '~=':
                ok = bool(val) and val in v.split()
            elif op == '|=':
                ok = v == val or v.startswith(val + '-')
            elif op == '^=':
                ok = bool(val) and v.startswith(val)
            elif op == '$=':
                ok = bool(val) and v.endswith(val)
            else:  # '*='
                ok = bool(val) and val in v
            if not ok:
                return False
        for kind, arg in self.pseudos:
            if not _PSEUDO_TESTS[kind](el, arg, memo):
                return False
        return True


# --- structural pseudo-classes (Selectors level 4, without ``of S``) -------

_NTH_RE = lazy(globals(), '_NTH_RE', r'^([+-]?)(\d*)n\s*(?:([+-])\s*(\d+))?$', re.I)


def _parse_nth(text):
    """``an+b`` of ``:nth-child()``: ``odd``, ``even``, an integer,
    ``[+-][a]n[ [+-] b]``; return ``(a, b)``."""
    t = text.strip().lower()
    if t == 'odd':
        return 2, 1
    if t == 'even':
        return 2, 0
    if re.fullmatch(r'[+-]?\d+', t):
        return 0, int(t)
    m = _NTH_RE.match(t)
    if m is None:
        raise CSSError('bad an+b argument %r' % text)
    sign, a, bsign, b = m.groups()
    a = int(a) if a else 1
    if sign == '-':
        a = -a
    b = int(b) if b else 0
    if bsign == '-':
        b = -b
    return a, b


def _nth_ok(ab, pos):
    """Whether the 1-based position ``pos`` is ``a*n + b`` for some n >= 0."""
    a, b = ab
    if a == 0:
        return pos == b
    n, r = divmod(pos - b, a)
    return r == 0 and n >= 0


def _positions(el, memo):
    """``(position, count, type position, type count)`` of ``el`` among
    its parent's element children (1-based), computed once per parent
    when ``memo`` is given (linear in the number of siblings)."""
    parent = el.getparent()
    if parent is None:
        return 1, 1, 1, 1
    table = memo.get(('pos', parent)) if memo is not None else None
    if table is None:
        table = {}
        kids = [k for k in parent if isinstance(k.tag, str)]
        by_type = {}
        for k in kids:
            by_type.setdefault(k.tag, []).append(k)
        n = len(kids)
        for i, k in enumerate(kids):
            table[k] = [i + 1, n, 0, 0]
        for group in by_type.values():
            m = len(group)
            for i, k in enumerate(group):
                t = table[k]
                t[2], t[3] = i + 1, m
        if memo is not None:
            memo[('pos', parent)] = table
    return table[el]


def _lang_of(el):
    while el is not None:
        v = el.get('{http://www.w3.org/XML/1998/namespace}lang')
        if v is None:
            v = el.get('lang')
        if v is not None:
            return v.strip().lower()
        el = el.getparent()
    return None


def _lang_test(el, ranges, memo):
    lang = _lang_of(el)
    if lang is None:
        return False
    return any(lang == r or lang.startswith(r + '-') or r == '*' for r in ranges)


def _empty_test(el, arg, memo):
    if el.text:
        return False
    for k in el:
        if isinstance(k.tag, str) or k.tail:
            return False
    return True


def _not_test(el, sels, memo):
    for s in sels:
        sub = None
        if memo is not None and s._backtracks:      # one memo per inner selector
            sub = memo.get(('not', s))
            if sub is None:
                sub = memo[('not', s)] = {}
        if s.matches(el, sub):
            return False
    return True


_PSEUDO_TESTS = {
    'root': lambda el, arg, memo: el.getparent() is None,
    'first-child': lambda el, arg, memo: _prev_element(el) is None,
    'last-child': lambda el, arg, memo: _next_element(el) is None,
    'only-child': lambda el, arg, memo: _prev_element(el) is None and _next_element(el) is None,
    'nth-child': lambda el, ab, memo: _nth_ok(ab, _positions(el, memo)[0]),
    'nth-last-child': lambda el, ab, memo: _nth_ok(ab, _nth_last(_positions(el, memo), 0)),
    'first-of-type': lambda el, arg, memo: _positions(el, memo)[2] == 1,
    'last-of-type': lambda el, arg, memo: (lambda p: p[2] == p[3])(_positions(el, memo)),
    'only-of-type': lambda el, arg, memo: _positions(el, memo)[3] == 1,
    'nth-of-type': lambda el, ab, memo: _nth_ok(ab, _positions(el, memo)[2]),
    'nth-last-of-type': lambda el, ab, memo: _nth_ok(ab, _nth_last(_positions(el, memo), 2)),
    'empty': _empty_test,
    'lang': _lang_test,
    'not': _not_test,
}

# pseudo-classes taking an ``an+b`` argument, without an argument, and the
# ones that need the sibling positions (and so a matching memo)
_NTH_PSEUDOS = frozenset({'nth-child', 'nth-last-child', 'nth-of-type', 'nth-last-of-type'})
_PLAIN_PSEUDOS = frozenset({'root', 'first-child', 'last-child', 'only-child', 'first-of-type',
                            'last-of-type', 'only-of-type', 'empty'})
_POSITIONAL = _NTH_PSEUDOS | {'first-of-type', 'last-of-type', 'only-of-type', 'not'}


def _nth_last(p, i):
    return p[i + 1] - p[i] + 1


def _local(el):
    tag = el.tag
    return tag.rpartition('}')[2] if tag[0] == '{' else tag


def _prev_element(el):
    p = el.getprevious()
    while p is not None and not isinstance(p.tag, str):
        p = p.getprevious()
    return p


def _next_element(el):
    p = el.getnext()
    while p is not None and not isinstance(p.tag, str):
        p = p.getnext()
    return p


class Selector:
    """One complex selector (no commas).

    Attributes
    ----------
    text : str
        The source text.
    specificity : (int, int, int)
    """

    __slots__ = ('text', 'parts', 'specificity', '_backtracks')

    # _backtracks counts descendant and general-sibling combinators, plus
    # one for pseudo-classes that read sibling positions: a selector with
    # any gets a matching memo for a whole pass

    def __init__(self, text, parts):
        # parts: [compound, (combinator, compound), ...] read right to left:
        # parts[0] is the rightmost compound (the subject).
        self.text = text
        self.parts = parts
        a = b = c = 0
        for p in parts:
            comp = p if isinstance(p, _Compound) else p[1]
            sa, sb, sc = comp.specificity()
            a, b, c = a + sa, b + sb, c + sc
        self.specificity = (a, b, c)
        # number of descendant / general-sibling combinators
        self._backtracks = sum(1 for p in parts[1:] if p[0] in ' ~') + any(
            k in _POSITIONAL for p in parts
            for k, _ in (p if isinstance(p, _Compound) else p[1]).pseudos)

    def __repr__(self):
        return 'Selector(%r)' % self.text

    @property
    def key(self):
        """Index key of the subject compound: ``('id', v)``, ``('class',
        v)``, ``('tag', v)`` or ``('*', None)``."""
        c = self.parts[0]
        if c.id is not None:
            return ('id', c.id)
        if c.classes:
            return ('class', c.classes[0])
        if c.tag is not None:
            return ('tag', c.tag)
        return ('*', None)

    def matches(self, el, memo=None):
        """Whether lxml element `el` matches this selector.

        Parameters
        ----------
        el : lxml element
        memo : dict, optional
            A cache private to this selector and one unchanged document.
            Passing the same dict for every element of a pass makes matching
            linear in the number of elements and compounds (no exponential
            backtracking over ancestors or siblings).

        >>> from lxml import etree
        >>> r = etree.fromstring('<svg><g><rect/></g></svg>')
        >>> rect = r[0][0]
        >>> parse_selector('svg rect').matches(rect), parse_selector('svg > rect').matches(rect)
        (True, False)
        """
        if not isinstance(el.tag, str):
            return False
        if memo is None and self._backtracks:
            memo = {}
        return self._match(el, 0, memo)

    def _match(self, el, i, memo):
        """Whether `el` matches part `i` and everything left of it."""
        if memo is not None:
            key = (el, i)
            r = memo.get(key)
            if r is None:
                r = memo[key] = self._match1(el, i, memo)
            return r
        return self._match1(el, i, memo)

    def _match1(self, el, i, memo):
        parts = self.parts
        comp = parts[i] if i == 0 else parts[i][1]
        if not comp.matches(el, _local(el), memo):
            return False
        if i + 1 == len(parts):
            return True
        comb = parts[i + 1][0]
        if comb == '>':
            p = el.getparent()
            return p is not None and self._match(p, i + 1, memo)
        if comb == '+':
            p = _prev_element(el)
            return p is not None and self._match(p, i + 1, memo)
        step = _parent if comb == ' ' else _prev_element
        return self._any_along(step(el), step, i + 1, memo)

    def _any_along(self, node, step, j, memo):
        """Whether `node` or a node reached from it by repeated `step`
        (ancestors or previous siblings) matches part `j` onward."""
        if memo is None:
            while node is not None:
                if self._match(node, j, memo):
                    return True
                node = step(node)
            return False
        tag = 'a' if step is _parent else 's'
        walked = []
        result = False
        while node is not None:
            key = (tag, node, j)
            r = memo.get(key)
            if r is not None:
                result = r
                break
            walked.append(node)
            if self._match(node, j, memo):
                result = True
                break
            node = step(node)
        for n in walked:
            memo[(tag, n, j)] = result
        return result


def _parent(el):
    return el.getparent()


def _parse_compound(text, pos):
    """Parse a compound selector at `pos`; return (compound, new pos)."""
    comp = _Compound()
    n = len(text)
    start = pos
    classes, attrs, pseudos = [], [], []
    if pos < n and text[pos] == '*':
        pos += 1
    else:
        m = _IDENT_RE.match(text, pos)
        if m is not None:
            comp.tag = _unescape(m.group(0))
            pos = m.end()
    while pos < n:
        ch = text[pos]
        if ch == '#':
            m = _IDENT_RE.match(text, pos + 1)
            if m is None:
                m = _NAME_RE.match(text, pos + 1)  # lenient: '#1a' accepted
                if m is None:
                    raise CSSError('bad id selector in %r' % text)
            if comp.id is not None and comp.id != _unescape(m.group(0)):
                comp.never = True
            comp.id = _unescape(m.group(0))
            pos = m.end()
        elif ch == '.':
            m = _IDENT_RE.match(text, pos + 1)
            if m is None:
                raise CSSError('bad class selector in %r' % text)
            classes.append(_unescape(m.group(0)))
            pos = m.end()
        elif ch == '[':
            m = _ATTR_RE.match(text, pos)
            if m is None:
                raise CSSError('bad attribute selector in %r' % text)
            name, op = _unescape(m.group(1)), m.group(2)
            val = next((g for g in m.group(3, 4, 5) if g is not None), None)
            if op is not None:
                val = _unescape(val)
            attrs.append((name, op, val, (m.group(6) or '').lower() == 'i'))
            pos = m.end()
        elif ch == ':':
            double = text.startswith('::', pos)
            pos += 2 if double else 1
            m = _IDENT_RE.match(text, pos)
            if m is None:
                raise CSSError('bad pseudo-class in %r' % text)
            name = m.group(0).lower()
            pos = m.end()
            if pos < n and text[pos] == '(':
                end = _scan_to(text, pos + 1, ')')
                if end >= n:
                    raise CSSError('unclosed pseudo-class argument in %r' % text)
                arg = text[pos + 1:end]
                pos = end + 1
                if double:
                    comp.never = True
                elif name in _NTH_PSEUDOS:
                    pseudos.append((name, _parse_nth(arg)))
                elif name == 'not':
                    pseudos.append(('not', parse_selector_list(arg.strip())))
                elif name == 'lang':
                    ranges = tuple(r.strip().strip('"\'').lower() for r in arg.split(','))
                    if not all(ranges):
                        raise CSSError('bad :lang() argument in %r' % text)
                    pseudos.append(('lang', ranges))
                else:
                    comp.never = True
            elif name in _PLAIN_PSEUDOS and not double:
                pseudos.append((name, None))
            else:
                comp.never = True
        else:
            break
    if pos == start:
        raise CSSError('expected a selector at %r' % text[start:start + 20])
    comp.classes = tuple(classes)
    comp.attrs = tuple(attrs)
    comp.pseudos = tuple(pseudos)
    return comp, pos


_COMB_RE = lazy(globals(), '_COMB_RE', r'\s*([>+~])\s*|\s+')


def _parse_complex(text):
    text = text.strip()
    if not text:
        raise CSSError('empty selector')
    comps, combs = [], []
    pos, n = 0, len(text)
    while True:
        comp, pos = _parse_compound(text, pos)
        comps.append(comp)
        if pos >= n:
            break
        m = _COMB_RE.match(text, pos)
        if m is None:
            raise CSSError('unexpected %r in selector %r' % (text[pos], text))
        combs.append(m.group(1) or ' ')
        pos = m.end()
        if pos >= n:
            raise CSSError('selector %r ends with a combinator' % text)
    parts = [comps[-1]]
    for i in range(len(comps) - 2, -1, -1):
        parts.append((combs[i], comps[i]))
    return Selector(text, parts)


@functools.lru_cache(maxsize=1024)
def parse_selector_list(text):
    """Parse a comma-separated selector list.

    Raises
    ------
    CSSError
        If any selector is invalid (CSS then drops the whole rule).

    >>> [s.specificity for s in parse_selector_list('#a .b, svg > rect:first-child')]
    [(1, 1, 0), (0, 1, 2)]
    """
    if not isinstance(text, str):
        raise CSSError('selector must be a string')
    out = []
    pos, n = 0, len(text)
    while pos <= n:
        end = _scan_to(text, pos, ',')
        out.append(_parse_complex(text[pos:end]))
        pos = end + 1
    return tuple(out)


def parse_selector(text):
    """Parse a single complex selector (helper for doctests and tests)."""
    sels = parse_selector_list(text)
    if len(sels) != 1:
        raise CSSError('expected one selector, got %d' % len(sels))
    return sels[0]


# --------------------------------------------------------------------------
# stylesheets
# --------------------------------------------------------------------------

class Rule(NamedTuple):
    """One selector with its declarations; `order` is the source position of
    the rule (shared by the selectors of one selector list)."""
    selector: Selector
    declarations: tuple
    order: int


_IMPORT_RE = lazy(globals(), '_IMPORT_RE', 
    r'@import\s*(?:url\(\s*(?:"((?:[^"\\]|\\.)*)"|\'((?:[^\'\\]|\\.)*)\'|([^)\s"\']*))\s*\)'
    r'|"((?:[^"\\]|\\.)*)"|\'((?:[^\'\\]|\\.)*)\')\s*(.*)$', re.I | re.S)


def parse_import(rule):
    """The target and media list of an ``@import`` rule (its text up to,
    not including, the ``;``): ``(href, media)``, or None when it is not a
    well-formed import.  ``media`` is the lower-cased, trimmed rest.

    >>> parse_import('@import url("a b.css") screen'), parse_import("@import 'x.css'")
    (('a b.css', 'screen'), ('x.css', ''))
    """
    m = _IMPORT_RE.match(rule.strip())
    if m is None:
        return None
    href = next(g for g in m.groups()[:5] if g is not None)
    return _unescape(href), m.group(6).strip().lower()


def media_applies(media):
    """Whether a media query list applies to a static picture: empty,
    or one of its queries is ``all`` or ``screen`` (optionally with
    ``only``).  Queries with features (``screen and (...)``) are not
    evaluated and do not apply."""
    if not media:
        return True
    for q in media.split(','):
        words = q.split()
        if words[:1] == ['only']:
            words = words[1:]
        if words in (['all'], ['screen']):
            return True
    return False


def parse_stylesheet(text, start_order=0, load=None):
    """Parse a stylesheet into rules, one per selector.

    At-rules are skipped with their blocks; rules whose selector does not
    parse are dropped; bad declarations are skipped.  ``@import`` rules
    before the first rule are followed when ``load`` is given and their
    media list applies (:func:`media_applies`): the imported sheet's rules
    come where the import stands, before the rules that follow it.

    Parameters
    ----------
    text : str
    start_order : int
        Order number of the first rule (to chain several sheets).
    load : callable, optional
        ``load(href)`` -> ``(text, load)`` of the imported sheet (``load``
        for its own imports, relative to it), or None when it is not
        used.  The caller bounds depth, cycles and what may be read.

    Returns
    -------
    list of Rule

    >>> [(r.selector.text, r.declarations[0].value)
    ...  for r in parse_stylesheet('@media print { a { fill: red } } a, b { fill: green }')]
    [('a', 'green'), ('b', 'green')]
    """
    if not isinstance(text, str):
        raise CSSError('stylesheet must be a string')
    text = _strip_comments(text)
    rules = []
    order = start_order
    pos, n = 0, len(text)
    imports_allowed = True      # @import only before any other rule
    while pos < n:
        while pos < n and text[pos].isspace():
            pos += 1
        if pos >= n:
            break
        if text[pos] == '@':
            end = _scan_to(text, pos, ';{}')
            if end < n and text[end] == '{':
                pos = _skip_block(text, end)
                imports_allowed = False
                continue
            head = text[pos:end]
            pos = end + 1
            if head[:7].lower() == '@import':
                ref = parse_import(head) if imports_allowed and load is not None else None
                if ref is not None and media_applies(ref[1]):
                    got = load(ref[0])
                    if got is not None:
                        sub = parse_stylesheet(got[0], order, got[1])
                        rules.extend(sub)
                        if sub:
                            order = sub[-1].order + 1
            elif head[:8].lower() != '@charset':
                imports_allowed = False
            continue
        imports_allowed = False
        if text[pos] == '}':  # stray closing brace
            pos += 1
            continue
        brace = _scan_to(text, pos, '{}')
        if brace >= n:
            break
        if text[brace] == '}':
            pos = brace + 1
            continue
        prelude = text[pos:brace]
        close = _scan_to(text, brace + 1, '}')
        body = text[brace + 1:close]
        pos = close + 1
        try:
            selectors = parse_selector_list(prelude.strip())
        except CSSError:
            continue
        decls = parse_declarations(body)
        for sel in selectors:
            rules.append(Rule(sel, decls, order))
        order += 1
    return rules


def select(root, selector):
    """All elements under `root` (inclusive, document order) matching
    `selector` (a selector list string).

    >>> from lxml import etree
    >>> r = etree.fromstring('<svg><rect id="a"/><circle/><rect/></svg>')
    >>> [e.get('id') for e in select(r, 'circle + rect, #a')]
    ['a', None]
    """
    sels = parse_selector_list(selector)
    memos = [{} if s._backtracks else None for s in sels]
    return [el for el in root.iter() if isinstance(el.tag, str)
            and any(s.matches(el, m) for s, m in zip(sels, memos))]


# --------------------------------------------------------------------------
# cascade
# --------------------------------------------------------------------------

def _is_style_element(el):
    tag = el.tag
    if tag != 'style' and tag != '{%s}style' % SVG_NS:
        return False
    t = el.get('type')
    return t is None or t.strip() == '' or t.strip().lower() == 'text/css'


class _Index:
    def __init__(self, rules):
        self.by_id, self.by_class, self.by_tag = {}, {}, {}
        self.universal = []
        for r in rules:
            kind, val = r.selector.key
            if kind == '*':
                self.universal.append(r)
            else:
                d = {'id': self.by_id, 'class': self.by_class, 'tag': self.by_tag}[kind]
                d.setdefault(val, []).append(r)

    def candidates(self, el, local):
        """The rules that may match ``el`` (local name ``local``), in no
        particular order (the caller sorts what matches)."""
        if not self.by_id and not self.by_class:      # only reads the tag
            t = self.by_tag.get(local)
            if not self.universal:
                return t or ()
            return self.universal + t if t else self.universal
        out = list(self.universal)
        i = el.get('id')
        if i is not None and i in self.by_id:
            out.extend(self.by_id[i])
        c = el.get('class')
        if c is not None and self.by_class:
            seen = set()
            for name in c.split():
                if name in self.by_class and name not in seen:
                    seen.add(name)
                    out.extend(self.by_class[name])
        t = self.by_tag.get(local)
        if t:
            out.extend(t)
        return out


def _etree_element():
    from lxml import etree
    return etree.Element


def _sort_declarations(decls, props, normal, important):
    """Put the declarations of known ``props`` into ``normal`` or, when
    ``!important``, into ``important`` (made when first needed); return
    ``important``."""
    for decl in decls:
        if decl.name in props:
            if decl.important:
                if important is None:
                    important = {}
                important[decl.name] = decl.value
            else:
                normal[decl.name] = decl.value
    return important


def _candidate_count(index, elements, limit):
    """Selector tests the cascade would make (the candidate rules of every
    element), counted without testing any; stops past ``limit``."""
    uni, by_id, by_class, by_tag = (len(index.universal), index.by_id, index.by_class,
                                    index.by_tag)
    total = 0
    for el in elements:
        n = uni
        tag = el.tag
        t = by_tag.get(tag.rpartition('}')[2] if tag[0] == '{' else tag)
        if t:
            n += len(t)
        if by_id:
            i = el.get('id')
            if i is not None and i in by_id:
                n += len(by_id[i])
        if by_class:
            c = el.get('class')
            if c is not None:
                for name in set(c.split()):
                    r = by_class.get(name)
                    if r:
                        n += len(r)
        total += n
        if total > limit:
            break
    return total


def declared_styles(root, extra_css='', found=None, load=None):
    """The cascaded (declared) style of every element of a document.

    Parameters
    ----------
    root : lxml element
        The document root (usually ``<svg>``); every element of its tree is
        styled.
    extra_css : str
        An additional author stylesheet, applied after the document's
        ``<style>`` elements (so it wins ties).
    found : dict, optional
        Attribute name -> list: each list gets, in document order, the
        elements that have that (non-presentation) attribute.  The tree
        builder learns ids and conditional attributes this way, without a
        second pass over the document.
    load : callable, optional
        Follows ``@import`` rules of the document's style sheets (see
        :func:`parse_stylesheet`); without it imports are skipped.

    Returns
    -------
    dict
        lxml element -> ``{property: value string}``, for every element of
        the tree (comments and processing instructions excluded).  Only known
        properties appear; values are trimmed, ``inherit`` is kept.

    Notes
    -----
    ``<style>`` elements with no ``type``, an empty one or ``text/css`` are
    used, wherever they are in the tree; CDATA sections are plain text.
    """
    if not hasattr(root, 'iter') or not isinstance(getattr(root, 'tag', None), str):
        if hasattr(root, 'getroot'):
            root = root.getroot()
        else:
            raise CSSError('declared_styles needs an lxml element, got %s'
                           % type(root).__name__)
    elements = list(root.iter(_etree_element()))
    rules = []
    for el in root.iter('{%s}style' % SVG_NS, 'style'):
        if _is_style_element(el):
            rules.extend(parse_stylesheet(''.join(el.itertext()),
                                          rules[-1].order + 1 if rules else 0, load))
    if extra_css:
        rules.extend(parse_stylesheet(extra_css, (rules[-1].order if rules else 0) + 1_000_000))
    index = _Index(rules) if rules else None
    # the cost model (raster.limits max_css_matches): every element is
    # tested against its candidate rules; count the tests before making any
    limit = limits.current().max_css_matches
    if index is not None and len(rules) * len(elements) > limit:
        n = _candidate_count(index, elements, limit)
        if n > limit:
            warnings.warn('stylesheets ignored: the cascade needs more than %d selector tests '
                          '(max_css_matches)' % limit, RasterWarning, stacklevel=3)
            rules, index = [], None
    # one matching cache per selector with descendant/sibling combinators,
    # shared by all elements of this pass (see Selector.matches)
    memos = {id(r.selector): {} for r in rules if r.selector._backtracks}
    props = PROPERTIES
    pres = PRESENTATION_ATTRIBUTES
    out = {}
    for el in elements:
        d = {}
        style = None
        # names first: values such as path data are never copied out
        keys = el.keys()
        if keys:
            get = el.get
            for k in keys:
                if k in pres:
                    d[k] = get(k).strip()
                elif k == 'style':
                    style = get(k)
                elif found is not None and k in found:
                    found[k].append(el)
        important = None
        if index is not None:
            tag = el.tag
            local = tag.rpartition('}')[2] if tag[0] == '{' else tag
            cands = index.candidates(el, local)
            matched = [r for r in cands
                       if r.selector.matches(el, memos.get(id(r.selector)))] if cands else None
            if matched:
                if len(matched) > 1:
                    matched.sort(key=lambda r: (r.selector.specificity, r.order))
                for r in matched:
                    important = _sort_declarations(r.declarations, props, d, important)
        # precedence: sheet < style attribute < sheet !important < style !important
        simp = _sort_declarations(_parse_declarations(style), props, d, None) if style else None
        if important:
            d.update(important)
        if simp:
            d.update(simp)
        out[el] = d
    return out


# --------------------------------------------------------------------------
# @font-face
# --------------------------------------------------------------------------

def font_face_rules(root):
    """The ``@font-face`` rules of a document's ``<style>`` elements, in
    document order: a list of ``{descriptor: value}`` dicts (names lower
    case, values trimmed, later declarations winning).  Only top-level
    rules are found (not inside ``@media``); the text layout resolves them
    (:mod:`raster.parser.fontface`).

    >>> from lxml import etree
    >>> root = etree.fromstring('<svg xmlns="http://www.w3.org/2000/svg"><style>'
    ...     '@font-face { font-family: "A B"; src: url(a.woff2) format("woff2") }'
    ...     'text { fill: red }</style></svg>')
    >>> font_face_rules(root)
    [{'font-family': '"A B"', 'src': 'url(a.woff2) format("woff2")'}]
    """
    out = []
    for el in root.iter('{%s}style' % SVG_NS, 'style'):
        if not _is_style_element(el):
            continue
        text = ''.join(el.itertext())
        if '@font-face' not in text.lower():
            continue
        text = _strip_comments(text)
        pos, n = 0, len(text)
        while pos < n:
            at = text.find('@', pos)
            if at < 0:
                break
            end = _scan_to(text, at, ';{}')
            if end >= n or text[end] != '{':
                pos = end + 1
                continue
            close = _skip_block(text, end)
            if text[at + 1:end].strip().lower() == 'font-face':
                body = text[end + 1:close - 1]
                out.append({d.name: d.value for d in _parse_declarations(body)})
            pos = close
    return out
