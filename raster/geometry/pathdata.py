"""SVG path data and SVG basic shapes to :class:`raster.Path`.

Coordinates are user units, x right and y down, as in SVG.  Elliptical arcs
are converted to cubic Beziers within ``tolerance`` (path units: a caller
that knows its device transform divides its device tolerance by the
transform's scale); quadratic segments (``Q``/``T``) stay quadratic.

>>> p = parse_path('M10 10 h 20 v 20 q -10 10 -20 0 z')
>>> p.to_svg()
'M 10 10 L 30 10 L 30 30 Q 20 40 10 30 Z'

How it works: one regular-expression pass splits the data into numbers and
everything else (arc flags are marked first, since ``"00"`` in flag position
is two flags); the rest becomes one byte per token (``'#'`` a number), and a
second regular expression checks the whole command grammar at once.  Long
data without exponents is tokenized by numpy instead, numbers and values
included, with the same result bit for bit (:func:`_lex_fast`): a map's
megabytes of path data would spend most of their time in the regular
expression.  Only invalid data takes the slower path that locates the
first error.  The geometry (relative coordinates, ``S``/``T`` reflections,
arcs) is then computed by numpy over all commands at once for long paths
(the longest in parts of :data:`_BUILD_TOKENS` tokens, each continuing
from where the previous stopped, so that the temporaries stay bounded),
or by a plain loop over commands for short ones, where numpy's per-call
overhead would dominate (:data:`SMALL_PATH_TOKENS`); the two agree
(tested).

Basic shapes (:func:`rect_path`, :func:`circle_path`, :func:`ellipse_path`,
:func:`line_path`, :func:`polyline_path`) follow the equivalent paths of
SVG 2, whose start point and direction matter for markers and dashes.

Errors: with ``strict=True`` a malformed string raises
:class:`~raster.errors.PathError` naming the character position; with
``strict=False`` the path is kept up to the last complete command, which is
what SVG renderers draw.

>>> parse_path('M0 0 L10 0 L', strict=False).to_svg()
'M 0 0 L 10 0'
"""

from __future__ import annotations

import functools
import math
import re
import sys

from typing import List, NamedTuple, Optional, Sequence, TYPE_CHECKING

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

from .._regex import lazy
from ..errors import LimitError, PathError
from .path import CLOSE, CUBIC, LINE, MOVE, QUAD, Path

__all__ = ['parse_path', 'parse_paths', 'arc_to_cubics', 'parse_points', 'rect_path',
           'circle_path', 'ellipse_path', 'line_path', 'polyline_path']

#: Most cubic pieces one elliptical arc may be split into; beyond this
#: (a radius astronomically larger than the tolerance) :class:`LimitError`.
MAX_ARC_PIECES = 100_000

# -- lexical grammar -----------------------------------------------------------
_WS = ' \t\n\r\f'
_WSP = '[ \\t\\n\\r\\f]'
_NUM = r'[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?'
# comma-wsp, possibly empty; written so that a run of whitespace can be
# matched one way only (no quadratic backtracking on long blank runs)
_SEP = _WSP + '*(?:,' + _WSP + '*)?'
_NUM_SPLIT = lazy(globals(), '_NUM_SPLIT', '(' + _NUM + ')')
_NUM_RE = lazy(globals(), '_NUM_RE', _NUM)
_TOKEN_RE = lazy(globals(), '_TOKEN_RE', _NUM + '|[^ \\t\\n\\r\\f]')
_CMD_LETTERS = 'MmZzLlHhVvCcSsQqTtAa'


def _atomic(name):
    # a number that the regex engine may not shorten by backtracking (SVG
    # numbers are read greedily); lookahead + backreference works on 3.10
    return '(?=(?P<%s>%s))(?P=%s)' % (name, _NUM, name)


# an arc command up to the next command letter; inside it, the three numbers
# before each pair of flags, and the two numbers after them
_ARC_CMD_RE = lazy(globals(), '_ARC_CMD_RE', '[Aa][^%s]*' % _CMD_LETTERS)
_ARC_FLAGS_RE = lazy(globals(), '_ARC_FLAGS_RE',
                     _SEP + _atomic('a') + _SEP + _atomic('b') + _SEP + _atomic('c') + _SEP
                     + '(?P<f1>[01])(?:' + _SEP + '(?P<f2>[01]))?')
_ARC_TAIL_RE = lazy(globals(), '_ARC_TAIL_RE', _SEP + _atomic('x') + _SEP + _atomic('y'))
_POINTS_RE = lazy(globals(), '_POINTS_RE',
                  _WSP + '*(?:' + _atomic('n') + '(?:' + _SEP + _atomic('m') + ')*)?')

# -- token-level grammar ---------------------------------------------------------
# The data is reduced to one byte per token: '#' a number, b'\x00' / b'\x01'
# an arc flag, ',' a comma, a command letter, anything else is junk.
_GROUP = {'M': '##', 'L': '##', 'T': '##', 'H': '#', 'V': '#', 'C': '######',
          'S': '####', 'Q': '####', 'A': '###ff##', 'Z': ''}
_GROUP.update({k.lower(): v for k, v in _GROUP.items()})
# Possessive repeats (Python 3.11+) accept the same language; they only stop
# the engine from keeping backtracking state, which made matching a
# megabyte-long path superlinear.  Before 3.11.5 a possessive repeat of a
# group holding an alternation could match wrongly (CPython gh-106052): those
# versions use plain repeats.
POSSESSIVE = sys.version_info >= (3, 11, 5)


def _validity_source(possessive, body=False):
    p = b'+' if possessive else b''
    cmd = (rb'(?:[MmLlTt](?:##)+%s|[HhVv]#+%s|[Cc](?:######)+%s|[SsQq](?:####)+%s'
           rb'|[Aa](?:###[\x00\x01][\x00\x01]##)+%s|[Zz])' % ((p,) * 5))
    if body:            # commands after the first (see _grammar_ok)
        return cmd + rb'*' + p
    return rb'(?:[Mm](?:##)+' + p + cmd + rb'*' + p + rb')?'


def validity_regex(possessive=POSSESSIVE):
    """The regex of valid token strings (see :func:`_is_valid`), with
    possessive or plain repeats (both accept the same language)."""
    return re.compile(_validity_source(possessive))


_VALID = lazy(globals(), '_VALID', _validity_source(POSSESSIVE))
_VALID_BODY = lazy(globals(), '_VALID_BODY', _validity_source(POSSESSIVE, body=True))
_LETTER = lazy(globals(), '_LETTER', b'[%s]' % _CMD_LETTERS.encode())

#: Tokens per piece of the grammar check (:func:`_grammar_ok`).
_VALID_TOKENS = 1 << 16


def _grammar_ok(kinds):
    """Whether the token string (without commas) is valid path data:
    ``_VALID.fullmatch(kinds)``, checked a piece of about
    :data:`_VALID_TOKENS` tokens at a time, each cut before a command
    letter (valid data is a sequence of commands, each starting at a
    letter: the first piece must be valid data, every other one a sequence
    of commands).  Without possessive repeats (Python before 3.11.5) the
    regex engine keeps some 100 bytes of backtracking state a command:
    84 MB for 2 MB of ``M0 0Z`` in one match."""
    n = len(kinds)
    if n <= _VALID_TOKENS:
        return _VALID.fullmatch(kinds) is not None
    lo, rx = 0, _VALID
    while lo < n:
        m = _LETTER.search(kinds, lo + _VALID_TOKENS) if n - lo > _VALID_TOKENS else None
        hi = n if m is None else m.start()
        if rx.fullmatch(kinds, lo, hi) is None:
            return False
        lo, rx = hi, _VALID_BODY
    return True


_CMD_SPAN = lazy(globals(), '_CMD_SPAN',
                 b'([%s])([^%s]*)' % (_CMD_LETTERS.encode(), _CMD_LETTERS.encode()))
_COMMA_AFTER_BAD = lazy(globals(), '_COMMA_AFTER_BAD', rb'(?<![#\x00\x01]),')
_COMMA_BEFORE_BAD = lazy(globals(), '_COMMA_BEFORE_BAD', rb',(?![#\x00\x01])')
# token string -> 'N' (number or flag), ',' (comma) or 'x' (anything else)
_COMMA_VIEW = bytes(78 if i in (0, 1, 35) else 44 if i == 44 else 120 for i in range(256))

# per command letter (byte value): tokens per group, and the offsets of the
# end point's x and y among them
_ARITY = np.zeros(128, np.int64)
_EX = np.zeros(128, np.int64)
_EY = np.zeros(128, np.int64)
for _c, _n, _ex, _ey in (('M', 2, 0, 1), ('L', 2, 0, 1), ('T', 2, 0, 1),
                         ('H', 1, 0, 0), ('V', 1, 0, 0), ('C', 6, 4, 5),
                         ('S', 4, 2, 3), ('Q', 4, 2, 3), ('A', 7, 5, 6),
                         ('Z', 0, 0, 0)):
    for _l in (_c, _c.lower()):
        _ARITY[ord(_l)] = _n
        _EX[ord(_l)] = _ex
        _EY[ord(_l)] = _ey
_M, _L, _H, _V, _C, _S, _Q, _T, _A, _Z = (ord(c) for c in 'MLHVCSQTAZ')
_SET, _ADD, _CLOSE = 0, 1, 2


def _check_tolerance(tolerance):
    try:
        tol = float(tolerance)
    except (TypeError, ValueError):
        raise PathError('tolerance must be a number, got %r' % (tolerance,)) from None
    if not (math.isfinite(tol) and tol > 0):
        raise PathError('tolerance must be a positive finite number, got %r' % (tolerance,))
    return tol


# -- parse_path ------------------------------------------------------------------------
def parse_path(d: str, tolerance: float = 0.01, strict: bool = True) -> Path:
    """Parse SVG path data into a :class:`~raster.geometry.path.Path`.

    Parameters
    ----------
    d : str
        SVG path data (the ``d`` attribute): commands ``M m L l H h V v C c
        S s Q q T t A a Z z`` with SVG number syntax (``"1.5.5"`` is two
        numbers, ``"-1-2"`` too; arc flags need no separator).
    tolerance : float, optional
        Largest distance, in path units, between an elliptical arc and the
        cubic Beziers that replace it.  Must be positive and finite.
    strict : bool, optional
        ``True``: malformed data raises :class:`~raster.errors.PathError`
        (``"path data error at 12: expected number"``, 12 being the
        0-based character index).  ``False``: return the path up to the last
        complete command before the error (SVG's rendering rule); data that
        does not start with ``M``/``m`` gives an empty path.

    Returns
    -------
    Path
        ``M`` becomes ``MOVE``; ``L H V`` ``LINE``; ``C S`` ``CUBIC``; ``Q T``
        ``QUAD``; ``A`` one or more ``CUBIC`` (``LINE`` for a zero radius,
        nothing when its end points coincide); ``Z`` ``CLOSE``.  Drawing
        after ``Z`` starts a new contour at the closed contour's first point.
        Zero-length segments and lone ``M Z`` contours are kept.

    Raises
    ------
    PathError
        Malformed data (strict mode), a number too large for float64, a
        coordinate that overflows, or a bad ``tolerance``.
    LimitError
        An arc needs more than :data:`MAX_ARC_PIECES` cubic pieces.

    Examples
    --------
    >>> parse_path('m1 2 3 4').to_svg()
    'M 1 2 L 4 6'
    >>> parse_path('M0 0 C1 1 2 1 3 0 S5 -1 6 0').points[-3:].tolist()
    [[4.0, -1.0], [5.0, -1.0], [6.0, 0.0]]
    >>> try:
    ...     parse_path('M0 0 L1 1 2')
    ... except PathError as e:
    ...     print(e)
    path data error at 11: expected number
    >>> len(parse_path('   '))
    0
    """
    tol = _check_tolerance(tolerance)
    if not isinstance(d, str):
        raise PathError('path data must be a string, got %s' % type(d).__name__)
    d2 = _mark(d)
    # (long data in chunks; short data by either lexer, as floats)
    fast = None
    if len(d2) > _LEX_CHUNK:
        fast = _lex_marked(d2)
    elif len(d2) >= FAST_LEX_CHARS:
        fast = _lex_fast(d2)
    if fast is not None:
        kb, vals = fast             # (the values stay one float64 array)
    else:
        nums, kb = _split(d2)
        vals = list(map(float, nums))
    kinds = kb.replace(b',', b'') if b',' in kb else kb
    if _is_valid(kb, kinds, vals):
        return _build(kinds, vals, tol)
    vals = np.asarray(vals, dtype=np.float64)
    at, what = _first_error(kb, kinds, vals)
    if strict:
        pos = _char_position(d2, at)
        if what is None:
            what = ('unexpected character %r' % d[pos] if pos < len(d)
                    else 'unexpected end of data')
        raise PathError('path data error at %d: %s' % (pos, what))
    cut = at - kb.count(b',', 0, at)              # token index without commas
    end = _VALID.match(kinds, 0, cut).end()
    return _build(kinds[:end], vals[:kinds.count(b'#', 0, end)], tol)


def parse_paths(ds: Sequence[str], tolerance: float = 0.01) -> List[Path]:
    """Parse many path data strings at once, as SVG renders them.

    The result equals ``[parse_path(d, tolerance, strict=False) for d in
    ds]``, but the strings are tokenized by one regular-expression pass and
    built by one vectorized pass, which is several times faster for a
    document with thousands of short paths (a map).  Malformed strings are
    handed to :func:`parse_path` one by one.

    Parameters
    ----------
    ds : sequence of str
        Path data strings.
    tolerance : float, optional
        Arc tolerance in path units, as for :func:`parse_path`.

    Returns
    -------
    list of Path
        One per string, in order.

    Raises
    ------
    PathError
        A string that is not a ``str``, a bad ``tolerance``, coordinates
        that overflow.
    LimitError
        An arc needs more than :data:`MAX_ARC_PIECES` cubic pieces.

    >>> [p.to_svg() for p in parse_paths(['M0 0 L1 1', 'm2 2 h1 z', 'M0 0 L'])]
    ['M 0 0 L 1 1', 'M 2 2 L 3 2 Z', 'M 0 0']
    """
    tol = _check_tolerance(tolerance)
    ds = list(ds)
    for d in ds:
        if not isinstance(d, str):
            raise PathError('path data must be a string, got %s' % type(d).__name__)
    out = [None] * len(ds)
    batch = [i for i, d in enumerate(ds) if '|' not in d]    # '|' separates pieces
    pieces = []
    if len(batch) > 1:
        kb, vals = _lex_values('|'.join([ds[i] for i in batch]))
        if np.isfinite(vals).all():
            pieces = kb.split(b'|')
    if len(pieces) == len(batch) and pieces:
        counts = [p.count(35) for p in pieces]
        kinds = [p.replace(b',', b'') if 44 in p else p for p in pieces]
        # all pieces valid <=> the concatenation is valid, given that every
        # piece starts with a moveto (no command group can span two pieces)
        whole = b''.join(kinds)
        if (all(k[:1] in (b'M', b'm') for k in kinds)
                and not (len(whole) != len(kb) - len(pieces) + 1
                         and _bad_commas(kb))
                and _grammar_ok(whole)):
            good = list(range(len(batch)))
        else:
            good = [j for j, (p, k) in enumerate(zip(pieces, kinds))
                    if k and (len(k) == len(p) or not _bad_commas(p))
                    and _grammar_ok(k)]
            if len(good) > 1:
                off = np.cumsum(counts) - counts
                vals = np.concatenate([vals[off[j]:off[j] + counts[j]] for j in good])
                whole = b''.join([kinds[j] for j in good])
        if len(good) > 1:
            lens = np.array([len(kinds[j]) for j in good], np.int64)
            starts = np.cumsum(lens) - lens
            try:
                with np.errstate(over='ignore', invalid='ignore'):
                    paths = _build_vector(whole, vals, tol, starts)
            except PathError:            # an overflow somewhere: one by one
                paths = ()
            for j, p in zip(good, paths):
                out[batch[j]] = p
    for i, d in enumerate(ds):
        if out[i] is None:
            out[i] = parse_path(d, tol, strict=False)
    return out


def _bad_commas(kb):
    """Whether token string ``kb`` has a comma that does not sit between
    two numbers or flags (what ``_COMMA_AFTER_BAD`` and
    ``_COMMA_BEFORE_BAD`` find, by byte translation and substring
    search instead of a regular expression scan)."""
    t = kb.translate(_COMMA_VIEW)
    return (t[:1] == b',' or t[-1:] == b',' or b',,' in t or b'x,' in t
            or b',x' in t)


def _is_valid(kb, kinds, vals):
    """Fast check of the whole token string (commas, command grammar,
    finite numbers); the slow search for the first error runs only when this
    fails."""
    if len(kinds) != len(kb) and _bad_commas(kb):
        return False
    if not _grammar_ok(kinds):
        return False
    if isinstance(vals, np.ndarray):
        return bool(np.isfinite(vals).all())
    return not vals or max(map(abs, vals)) < math.inf


def _lex(d):
    """Return ``(d2, numbers, kinds)``: ``d2`` is ``d`` with arc flags
    replaced by the marker characters ``\\x00``/``\\x01`` (same length),
    ``numbers`` the number strings in order and ``kinds`` one byte per token
    (whitespace dropped)."""
    d = _mark(d)
    nums, kinds = _split(d)
    return d, nums, kinds


def _split(d):
    """Regular-expression lexer of marked data: ``(numbers, kinds)``."""
    parts = _NUM_SPLIT.split(d)
    kinds = '#'.join(parts[0::2]).encode('ascii', 'replace').translate(None, _WS.encode())
    return parts[1::2], kinds


def _lex_values(d):
    """``(kinds, values)``: :func:`_lex`'s kinds and its numbers as a
    float64 array (by :func:`_lex_fast` when it applies)."""
    return _lex_marked(_mark(d))


def _lex_marked(d):
    """:func:`_lex_values` of data already passed through :func:`_mark`.

    Long data is lexed in chunks of about :data:`_LEX_CHUNK` characters
    (the lexers' temporaries are several arrays per character: tens of MB
    for a megabyte at once).  A chunk ends at a ``'|'`` (a one-character
    junk token: it is dropped, and the chunks' kinds are joined by it),
    just after a space or comma, or just before a command letter (data
    without separators, ``h1h1...``); no token spans such a cut and either
    lexer reads the next character as at the start of data, so the result
    is the same as in one piece."""
    kinds, vals = [], []
    pos, n = 0, len(d)
    while pos <= n:
        m = _CUT.search(d, pos + _LEX_CHUNK) if n - pos > _LEX_CHUNK else None
        sep = b''
        nxt = None if m is None else m.start() + 1
        if m is None:
            end = n
        elif d[m.start()] == '|':                   # dropped: the kinds join by it
            end, sep = m.start(), b'|'
        elif d[m.start()] in _CMD_LETTERS:          # a letter: starts the next chunk
            end = nxt = m.start()
        else:                                       # a space or comma: kept
            end = m.start() + 1
        part = d[pos:end] if pos or end < n else d
        r = _lex_fast(part) if len(part) >= FAST_LEX_CHARS else None
        if r is None:
            nums, k = _split(part)
            r = k, (np.array(nums, dtype=np.float64) if nums else np.zeros(0))
        kinds.append(r[0])
        kinds.append(sep)
        vals.append(r[1])
        if m is None:
            break
        pos = nxt
    if len(vals) == 1:
        return kinds[0], vals[0]
    return b''.join(kinds), np.concatenate(vals)


#: Where :func:`_lex_marked` may end a chunk.
_CUT = re.compile('[|,%s%s]' % (_WS, _CMD_LETTERS))


#: Characters per chunk of :func:`_lex_marked` (a chunk ends at the next
#: ``'|'``, space, comma or command letter after that many).
_LEX_CHUNK = 1 << 18


def _mark(d):
    """``d`` with the token marker characters made junk and arc flags
    marked (see :func:`_lex`)."""
    if '#' in d or '\x00' in d or '\x01' in d:
        # characters used internally as token markers are junk in the input
        d = d.replace('#', '\ufffd').replace('\x00', '\ufffd').replace('\x01', '\ufffd')
    if 'A' in d or 'a' in d:
        d = _ARC_CMD_RE.sub(_mark_flags, d)
    return d


#: Data at least this long is tokenized by the vectorized lexer
#: (:func:`_lex_fast`) when it applies; shorter data by the regular
#: expression, whose cost grows with the length but starts lower.
FAST_LEX_CHARS = 2048

# character classes of the vectorized lexer
_CL_DIGIT, _CL_DOT, _CL_SIGN, _CL_OTHER, _CL_SPACE = range(5)
_CLASS = np.full(256, _CL_OTHER, np.uint8)
_CLASS[np.frombuffer(b'0123456789', np.uint8)] = _CL_DIGIT
_CLASS[ord('.')] = _CL_DOT
_CLASS[np.frombuffer(b'+-', np.uint8)] = _CL_SIGN
_CLASS[np.frombuffer(_WS.encode(), np.uint8)] = _CL_SPACE
_POW10 = 10.0 ** np.arange(23)        # exact in float64


def _lex_fast(d):
    """Vectorized :func:`_lex` for data without exponents.

    Returns ``(kinds, values)`` equal to ``_lex(d)``'s kinds and
    ``np.array(numbers, float)``, or ``None`` when ``d`` needs the regular
    expression lexer: non-ASCII text, an ``e``/``E``, a ``.`` not followed
    by a digit or a sign followed by neither digit nor ``.`` (junk,
    ambiguous or unusual number spellings).

    Without those, SVG's greedy number grammar ``sign? (digits ('.'
    digits?)? | '.' digits)`` splits a run of digits, dots and signs at
    every sign, at a run's start, and at every dot after the first of a
    number ("1.5.5" is "1.5", ".5").  Values are ``mantissa / 10**k`` with
    an integer mantissa of at most 15 digits and ``k <= 22``: both exact
    in float64, so the division is correctly rounded and equals
    ``float(text)`` bit for bit; longer numbers go through ``float``.

    Parameters
    ----------
    d : str
        Path data already passed through :func:`_mark`.

    Returns
    -------
    kinds : bytes
        One byte per token, ``'#'`` for a number (whitespace dropped).
    values : (N,) float64 ndarray
        The N numbers in order.
    """
    if not d or not d.isascii():
        return None
    b = d.encode('ascii')
    if b'e' in b or b'E' in b:
        return None
    # (np.take and index arrays: several times faster than fancy or
    # boolean indexing on megabytes of data)
    a = np.frombuffer(b, np.uint8)
    n = len(a)
    c = np.take(_CLASS, a)
    isD = c == _CL_DIGIT
    isP = c == _CL_DOT
    isS = c == _CL_SIGN
    if (isP[-1] or isS[-1] or (isP[:-1] & ~isD[1:]).any()
            or (isS[:-1] & (c[1:] > _CL_DOT)).any()):
        return None
    # number starts: every sign; a digit after other text or space; a dot
    # after other text or space, or after digits that follow another dot
    st = isS.copy()
    st[0] |= isD[0]
    st[1:] |= isD[1:] & (c[:-1] >= _CL_OTHER)
    q = np.flatnonzero(~isD)                    # non-digits in order
    cq = np.take(c, q)
    pq = np.flatnonzero(cq == _CL_DOT)          # the dots among them
    qp = np.take(q, pq)                         # positions of the dots
    if len(pq):
        prev_q = np.take(q, pq - 1)             # the non-digit before each dot
        prev_c = np.take(cq, pq - 1)
        if pq[0] == 0:                          # none: as if other text at -1
            prev_q[0], prev_c[0] = -1, _CL_OTHER
        np.put(st, qp, np.where(qp - prev_q > 1, prev_c == _CL_DOT, prev_c >= _CL_OTHER))
    # a number ends where the next starts or at the first character that is
    # neither digit nor dot
    dp = isD | isP
    endm = np.empty(n + 1, bool)
    endm[0] = False
    endm[1:n] = (dp[:-1] | isS[:-1]) & (st[1:] | ~dp[1:])
    endm[n] = dp[-1]
    sp = np.flatnonzero(st)
    end = np.flatnonzero(endm)
    keep = np.flatnonzero(st | (c == _CL_OTHER))
    kinds = np.take(np.where(st, np.uint8(35), a), keep).tobytes()
    if not len(sp):
        return kinds, np.zeros(0)
    sign = np.take(isS, sp)
    hasp = np.zeros(len(sp), bool)
    nfrac = np.zeros(len(sp), np.int64)
    if len(pq):
        tp = np.take(np.cumsum(st, dtype=np.int32), qp) - 1
        hasp[tp] = True
        nfrac[tp] = end[tp] - qp - 1
    ndig = end - sp - sign - hasp
    last = np.cumsum(ndig)                      # digits up to each number's end
    digits = np.take(a, np.flatnonzero(isD)) - 48
    # power of ten of every digit within its number's integer mantissa
    k = np.repeat(last, ndig) - np.arange(1, len(digits) + 1)
    mant = np.add.reduceat(digits * np.take(_POW10, k, mode='clip'), last - ndig)
    vals = mant / np.take(_POW10, nfrac, mode='clip')
    np.negative(vals, out=vals, where=np.take(a, sp) == 45)
    for t in np.flatnonzero((ndig > 15) | (nfrac > 22)).tolist():
        vals[t] = float(b[sp[t]:end[t]])
    return kinds, vals


def _mark_flags(m):
    """Replace the flag characters of one arc command by marker characters,
    so that ``"00"`` in flag position reads as two flags, not a number."""
    text = m.group()
    marks = []
    pos = 1
    while True:
        f = _ARC_FLAGS_RE.match(text, pos)
        if f is None:
            break
        marks.append(f.start('f1'))
        if f.group('f2') is None:
            break
        marks.append(f.start('f2'))
        t = _ARC_TAIL_RE.match(text, f.end())
        if t is None:
            break
        pos = t.end()
    if not marks:
        return text
    chars = list(text)
    for i in marks:
        chars[i] = '\x00' if chars[i] == '0' else '\x01'
    return ''.join(chars)


def _first_error(kb, kinds, vals):
    """Index into ``kb`` (tokens with commas) of the first error, and a
    message (``None``: unexpected character)."""
    errors = []
    m = _COMMA_AFTER_BAD.search(kb)
    if m:
        errors.append((m.start(), 'unexpected comma'))
    m = _COMMA_BEFORE_BAD.search(kb)
    if m:
        errors.append((m.start() + 1, _expected('#', kb, m.start() + 1)))
    nonfinite = np.flatnonzero(~np.isfinite(vals))
    if len(nonfinite):
        k = _nth(kinds, b'#', int(nonfinite[0]))
        errors.append((_with_commas(kb, k), 'number out of range'))
    k, what = _structure_error(kinds)
    if k is not None:
        errors.append((_with_commas(kb, k), what))
    if not errors:                                # defensive: never expected
        errors.append((len(kb), 'invalid path data'))
    return min(errors, key=lambda e: e[0])


def _structure_error(kinds):
    """First token of ``kinds`` (no commas) that breaks the command grammar."""
    n = len(kinds)
    if n == 0:
        return None, None
    if kinds[0] not in b'Mm':
        return 0, _expected('M', kinds, 0)
    e = _VALID.match(kinds).end()
    if e == n:
        return None, None
    c = chr(kinds[e])
    if c in _GROUP and c not in 'Zz':
        cmd, start = c, e + 1                    # a command without arguments
    else:
        j = max(kinds.rfind(ch.encode(), 0, e) for ch in _CMD_LETTERS)
        cmd, start = chr(kinds[j]), e             # inside an incomplete group
    pattern = _GROUP[cmd]
    if not pattern:
        return e, _expected('cmd', kinds, e)
    for i, want in enumerate(pattern):
        k = start + i
        ok = k < n and (kinds[k] == 35 if want == '#' else kinds[k] in (0, 1))
        if not ok:
            return k, _expected(want, kinds, k)
    return e, None                                # not reached for valid input


def _expected(want, toks, k):
    """Message for token ``k`` of ``toks`` where ``want`` was expected, or
    ``None`` when the token is junk (the caller names the character)."""
    if k < len(toks):
        t = toks[k]
        if not (t in (0, 1) or chr(t) in '#,' + _CMD_LETTERS):
            return None
    return {'#': 'expected number', 'f': 'expected arc flag (0 or 1)',
            'M': 'expected moveto (M or m)', 'cmd': 'expected command'}[want]


def _nth(s, byte, n):
    """Index of the ``n``-th (0-based) occurrence of ``byte`` in ``s``."""
    hits = np.flatnonzero(np.frombuffer(s, np.uint8) == byte[0])
    return int(hits[n])


def _with_commas(kb, k):
    """Map token index ``k`` of the comma-free kinds to an index in ``kb``."""
    if b',' not in kb:
        return k
    keep = np.flatnonzero(np.frombuffer(kb, np.uint8) != 44)
    return int(keep[k]) if k < len(keep) else len(kb)


def _char_position(d2, k):
    """Character index of token ``k`` (``len(d2)`` past the last token)."""
    for i, m in enumerate(_TOKEN_RE.finditer(d2)):
        if i == k:
            return m.start()
    return len(d2)


#: Paths with fewer tokens than this are built by a plain loop over their
#: commands (numpy's per-call overhead dominates on short paths); longer
#: ones by the vectorized builder.  Both give the same path (tested).
SMALL_PATH_TOKENS = 2000


def _build(kinds, vals, tol):
    """Path from a validated token string and its numbers (a list of
    floats or a float64 array)."""
    if len(kinds) < SMALL_PATH_TOKENS:
        return _build_loop(kinds, vals.tolist() if isinstance(vals, np.ndarray) else vals, tol)
    with np.errstate(over='ignore', invalid='ignore'):   # overflow: checked at the end
        return _build_vector(kinds, np.asarray(vals, dtype=np.float64), tol)


def _build_loop(kinds, vals, tol):
    """Command-by-command builder (reference semantics, used for short
    paths)."""
    v = vals                                # list of floats
    verbs, pts = [], []                     # pts: flat x, y list
    k = 0                                   # next number in v
    x = y = sx = sy = 0.0                   # current point, contour start
    qx = qy = cx = cy = 0.0                 # last quadratic / cubic control
    last = 0                                # previous command (upper case)
    for letter, args in _CMD_SPAN.findall(kinds):
        c = letter[0]
        up = c & 0xDF
        if up == _Z:
            if last != _Z:
                verbs.append(CLOSE)
            x, y, last = sx, sy, _Z
            continue
        rel = c >= 97
        for g in range(len(args) // int(_ARITY[c])):
            if last == _Z and not (up == _M and g == 0):
                verbs.append(MOVE)          # drawing after Z: implicit move
                pts += (x, y)
            ox, oy = (x, y) if rel else (0.0, 0.0)
            if up == _M or up == _L:
                x, y = ox + v[k], oy + v[k + 1]
                k += 2
                if up == _M and g == 0:
                    verbs.append(MOVE)
                    sx, sy, last = x, y, _M
                else:
                    verbs.append(LINE)
                    last = _L
                pts += (x, y)
            elif up == _H or up == _V:
                if up == _H:
                    x = ox + v[k]
                else:
                    y = oy + v[k]
                k += 1
                verbs.append(LINE)
                pts += (x, y)
                last = up
            elif up == _C or up == _S:
                if up == _C:
                    c1 = (ox + v[k], oy + v[k + 1])
                    k += 2
                elif last == _C or last == _S:
                    c1 = (2 * x - cx, 2 * y - cy)
                else:
                    c1 = (x, y)
                cx, cy = ox + v[k], oy + v[k + 1]
                x, y = ox + v[k + 2], oy + v[k + 3]
                k += 4
                verbs.append(CUBIC)
                pts += (c1[0], c1[1], cx, cy, x, y)
                last = up
            elif up == _Q or up == _T:
                if up == _Q:
                    qx, qy = ox + v[k], oy + v[k + 1]
                    k += 2
                elif last == _Q or last == _T:
                    qx, qy = 2 * x - qx, 2 * y - qy
                else:
                    qx, qy = x, y
                x, y = ox + v[k], oy + v[k + 1]
                k += 2
                verbs.append(QUAD)
                pts += (qx, qy, x, y)
                last = up
            else:                           # elliptical arc
                f = args[7 * g + 3: 7 * g + 5]
                ex, ey = ox + v[k + 3], oy + v[k + 4]
                ctrl = _arc_scalar(x, y, v[k], v[k + 1], v[k + 2], f[0], f[1], ex, ey, tol)
                k += 5
                x, y, last = ex, ey, _A
                if ctrl is None:            # same end points: omitted
                    continue
                if ctrl:
                    verbs += [CUBIC] * (len(ctrl) // 6)
                    pts += ctrl
                else:                       # zero radius: straight line
                    verbs.append(LINE)
                    pts += (x, y)
    verbs = np.array(verbs, np.uint8)
    points = np.array(pts, np.float64).reshape(-1, 2)
    if not np.isfinite(points).all():
        raise PathError('path coordinates overflow float64')
    return Path(verbs, points, _checked=True)


def _resolve(mode, val, is_move, before=None):
    """One coordinate of the current point after every command.

    ``mode`` is ``_SET`` (absolute value), ``_ADD`` (relative) or ``_CLOSE``
    (back to the start of the contour, i.e. the latest move).  Runs of
    relative commands are cumulative sums from the last set/close; a close
    refers to the position of an earlier move, which may itself hang off an
    earlier close: those chains are resolved by pointer jumping (log n
    rounds).  ``before``: ``(cur, start)``, the coordinate of the current
    point and of the contour's start before the first command (a later part
    of a long path, see :func:`_build_vector`): a relative first command
    starts from ``cur``, a close before any move goes back to ``start``."""
    if before is not None:
        # as if the commands followed a move to `start` and a line to `cur`
        cur, start = before
        r = _resolve(np.concatenate([[_SET, _SET], mode]), np.concatenate([[start, cur], val]),
                     np.concatenate([[True, False], is_move]))
        return r[2:]
    n = len(mode)
    bound = mode != _ADD
    seg = np.cumsum(bound) - 1
    starts = np.flatnonzero(bound)
    cs = np.cumsum(np.where(bound, 0.0, val))
    local = cs - cs[starts][seg]
    smode = mode[starts]
    base = np.where(smode == _SET, val[starts], 0.0)
    close = smode == _CLOSE
    if close.any():
        last_move = np.maximum.accumulate(np.where(is_move, np.arange(n), 0))
        m = last_move[starts[close]]
        ref = np.full(len(starts), -1, np.int64)
        ref[close] = seg[m]
        base[close] = local[m]
        act = np.flatnonzero(ref >= 0)
        while len(act):
            r = ref[act]
            base[act] = base[act] + base[r]
            ref[act] = ref[r]
            act = act[ref[act] >= 0]
    return base[seg] + local


#: Tokens the vectorized builder takes per pass (:func:`_build_vector`):
#: its per-command temporaries, some 300 bytes a command, stay a few
#: tens of MB for the longest path data.
_BUILD_TOKENS = 1 << 16


class _Carry(NamedTuple):
    """What a part of a path leaves the next (:func:`_build_vector`): the
    current point, the contour's start, the last command's kind (upper
    case; 0 before any) and its control point (the second one of a
    ``C``/``S``, the one of a ``Q``/``T``)."""
    x: float = 0.0
    y: float = 0.0
    sx: float = 0.0
    sy: float = 0.0
    kind: int = 0
    cx: float = 0.0
    cy: float = 0.0


def _build_vector(kinds, vals, tol, starts=None):
    """Vectorized builder: all commands at once (used for long paths).

    With ``starts`` (token offsets into ``kinds`` where independent paths
    begin, each with a moveto), return one Path per piece instead: many
    paths built by one pass (:func:`parse_paths`).

    Token strings longer than :data:`_BUILD_TOKENS` are built in parts of
    about that many tokens, cut between command groups (a part that starts
    inside a run of implicit repeats gets the run's letter, ``M`` becoming
    ``L``), each starting from the state the previous one left
    (:class:`_Carry`): the result is that of one pass, but for the last
    bits of relative coordinates, whose cumulative sums then run per part."""
    if not kinds:
        return Path.empty()
    carry = _Carry()
    verbs, points, vstarts, pstarts = [], [], [], []
    nv = nverb = npt = 0
    for lo, hi, lead in _parts(kinds, _BUILD_TOKENS):
        part = lead + kinds[lo:hi] if lead else (kinds if hi - lo == len(kinds) else kinds[lo:hi])
        k = kinds.count(b'#', lo, hi)
        local = None
        if starts is not None:
            local = starts[(starts >= lo) & (starts < hi)] - lo + len(lead)
        v, pts, carry, sv, sp = _build_part(part, vals[nv:nv + k], tol, carry, lo == 0, local)
        nv += k
        verbs.append(v)
        points.append(pts)
        if starts is not None:
            vstarts.append(sv + nverb)
            pstarts.append(sp + npt)
        nverb += len(v)
        npt += len(pts)
    iverb = verbs[0] if len(verbs) == 1 else np.concatenate(verbs)
    pts = points[0] if len(points) == 1 else np.concatenate(points)
    if not np.isfinite(pts).all():
        raise PathError('path coordinates overflow float64')
    if starts is None:
        return Path(iverb, pts, _checked=True)
    v0 = np.append(np.concatenate(vstarts), nverb).tolist()
    p0 = np.append(np.concatenate(pstarts), npt).tolist()
    return [Path(iverb[v0[k]:v0[k + 1]], pts[p0[k]:p0[k + 1]], _checked=True)
            for k in range(len(v0) - 1)]


def _parts(kinds, size):
    """Cut a validated token string (without commas) into parts of about
    ``size`` tokens between command groups: ``(lo, hi, lead)`` in order,
    the part being ``lead + kinds[lo:hi]``, where ``lead`` is the letter of
    a run of implicit repeats that the cut fell into (``b''`` otherwise)."""
    n = len(kinds)
    codes = np.frombuffer(kinds, np.uint8)
    lo, lead = 0, b''
    while n - lo > size:
        hi = lo + size
        let = np.flatnonzero(codes[lo + 1:hi + 1] >= 65)
        if len(let):                            # end before the last letter
            cut = lo + 1 + int(let[-1])
            yield lo, cut, lead
            lo, lead = cut, b''
            continue
        # inside one run of groups: end at a group boundary.  The run's
        # letter is the part's lead or its first token
        letter = lead if lead else kinds[lo:lo + 1]
        first = lo if lead else lo + 1         # where the part's groups start
        a = int(_ARITY[letter[0]])
        cut = first + (hi - first) // a * a
        yield lo, cut, lead
        lo, lead = cut, {b'M': b'L', b'm': b'l'}.get(letter, letter)
    yield lo, n, lead


def _build_part(kinds, vals, tol, carry, first, starts=None):
    """:func:`_build_vector` of one part: ``(verbs, points, carry, v0, p0)``
    (the part's verbs and points, the state it leaves, and with ``starts``
    the verb and point offsets of the pieces starting in it).  ``first``:
    the part starts the path (its leading ``m`` is absolute)."""
    codes = np.frombuffer(kinds, np.uint8)
    cmd_at = np.flatnonzero(codes >= 65)
    letters = codes[cmd_at]
    arity = _ARITY[letters]
    ntok = np.diff(cmd_at, append=len(codes)) - 1
    ngroups = np.where(arity > 0, ntok // np.maximum(arity, 1), 1)
    first_group = np.cumsum(ngroups) - ngroups
    cmd = np.repeat(np.arange(len(letters)), ngroups)
    j = np.arange(len(cmd)) - first_group[cmd]
    letter = letters[cmd]
    tok = cmd_at[cmd] + 1 + j * arity[cmd]         # first argument token
    rel = letter >= 97
    kind = letter & 0xDF                           # upper case
    kind[(kind == _M) & (j > 0)] = _L              # implicit lineto after moveto

    tokval = np.zeros(len(codes) + 8)
    tokval[:len(codes)][codes == 35] = vals
    if b'A' in kinds or b'a' in kinds:
        isflag = codes < 2
        tokval[:len(codes)][isflag] = codes[isflag]

    # end point of every command
    ex = tokval[tok + _EX[kind]]
    ey = tokval[tok + _EY[kind]]
    mx = np.where(rel, _ADD, _SET)
    my = mx.copy()
    isV, isH, isZ = kind == _V, kind == _H, kind == _Z
    mx[isV] = _ADD
    ex[isV] = 0.0
    my[isH] = _ADD
    ey[isH] = 0.0
    mx[isZ] = _CLOSE
    my[isZ] = _CLOSE
    if first:
        mx[0] = my[0] = _SET                       # a leading 'm' is absolute
    if starts is not None:
        g0 = first_group[np.searchsorted(cmd_at, starts)]  # first group of every piece
        mx[g0] = my[g0] = _SET
    is_move = kind == _M
    pos = np.empty((len(kind), 2))
    pos[:, 0] = _resolve(mx, ex, is_move, None if first else (carry.x, carry.sx))
    pos[:, 1] = _resolve(my, ey, is_move, None if first else (carry.y, carry.sy))
    prev = np.empty_like(pos)
    prev[0] = carry.x, carry.y
    prev[1:] = pos[:-1]
    prevkind = np.empty_like(kind)
    prevkind[0] = carry.kind
    prevkind[1:] = kind[:-1]

    def args(idx, npts):
        """(len(idx), npts, 2) absolute points from the first 2 * npts
        arguments of commands ``idx`` (relative ones offset by the
        current point; absolute ones untouched, so -0.0 stays)."""
        p = tokval[tok[idx][:, None] + np.arange(2 * npts)].reshape(-1, npts, 2)
        np.add(p, prev[idx][:, None, :], out=p, where=rel[idx][:, None, None])
        return p

    # Z after Z closes nothing; drawing after Z starts with a move
    drop = isZ & (prevkind == _Z)
    need_move = (prevkind == _Z) & ~isZ & ~is_move
    own = np.ones(len(kind), np.int64)
    own[drop] = 0

    isA = kind == _A
    arcs = None
    if isA.any():
        ai = np.flatnonzero(isA)
        arcs = ai, _arc_batch(prev[ai], pos[ai], tokval[tok[ai]], tokval[tok[ai] + 1],
                              tokval[tok[ai] + 2], tokval[tok[ai] + 3],
                              tokval[tok[ai] + 4], tol)
        own[ai] = arcs[1][1]

    nitem = own + need_move
    item_at = np.cumsum(nitem) - nitem
    at = item_at + need_move                        # index of the command's own item
    total = int(nitem.sum())
    iverb = np.empty(total, np.uint8)
    ipts = np.zeros((total, 3, 2))
    inpt = np.zeros(total, np.int64)

    mi = item_at[need_move]
    iverb[mi] = MOVE
    ipts[mi, 0] = prev[need_move]
    inpt[mi] = 1

    simple = is_move | (kind == _L) | isH | isV
    k = at[simple]
    iverb[k] = np.where(is_move[simple], MOVE, LINE)
    ipts[k, 0] = pos[simple]
    inpt[k] = 1

    keepz = isZ & ~drop
    iverb[at[keepz]] = CLOSE

    # control points (C/S: the second; Q/T: the only one), with the one
    # carried from the previous part in front
    ctrl = np.zeros((len(kind) + 1, 2))
    ctrl[0] = carry.cx, carry.cy
    isC, isS = kind == _C, kind == _S
    if isC.any() or isS.any():
        ci = np.flatnonzero(isC)
        k = at[ci]
        iverb[k] = CUBIC
        inpt[k] = 3
        a = args(ci, 2)
        ipts[k, :2] = a
        ctrl[ci + 1] = a[:, 1]
        ipts[k, 2] = pos[ci]
        si = np.flatnonzero(isS)
        if len(si):
            ctrl[si + 1] = args(si, 1)[:, 0]
            pk = prevkind[si]
            smooth = (pk == _C) | (pk == _S)
            c1 = prev[si].copy()
            c1[smooth] = 2 * prev[si][smooth] - ctrl[si][smooth]
            k = at[si]
            iverb[k] = CUBIC
            inpt[k] = 3
            ipts[k, 0] = c1
            ipts[k, 1] = ctrl[si + 1]
            ipts[k, 2] = pos[si]

    isQ, isT = kind == _Q, kind == _T
    if isQ.any() or isT.any():
        qi = np.flatnonzero(isQ)
        ctrl[qi + 1] = args(qi, 1)[:, 0]
        ti = np.flatnonzero(isT)
        if len(ti):
            ctrl[ti + 1] = _t_controls(ti, prev, prevkind, ctrl)
        qt = np.flatnonzero(isQ | isT)
        k = at[qt]
        iverb[k] = QUAD
        inpt[k] = 2
        ipts[k, 0] = ctrl[qt + 1]
        ipts[k, 1] = pos[qt]

    if arcs is not None:
        ai, (akind, acount, actrl) = arcs
        li = ai[akind == 1]
        k = at[li]
        iverb[k] = LINE
        inpt[k] = 1
        ipts[k, 0] = pos[li]
        cub = akind == 2
        if cub.any():
            n = acount[cub]
            k = np.repeat(at[ai[cub]], n) + (np.arange(int(n.sum()))
                                              - np.repeat(np.cumsum(n) - n, n))
            iverb[k] = CUBIC
            inpt[k] = 3
            ipts[k] = actrl

    points = ipts[np.arange(3) < inpt[:, None]]
    moves = np.flatnonzero(is_move)
    sx, sy = pos[moves[-1]] if len(moves) else (carry.sx, carry.sy)
    last = len(kind) - 1
    out = _Carry(float(pos[last, 0]), float(pos[last, 1]), float(sx), float(sy),
                 int(kind[last]), float(ctrl[last + 1, 0]), float(ctrl[last + 1, 1]))
    if starts is None:
        return iverb, points, out, None, None
    v0 = item_at[g0]
    p0 = (np.cumsum(inpt) - inpt)[v0]
    return iverb, points, out, v0, p0


def _t_controls(ti, prev, prevkind, ctrl):
    """Control points of the ``T`` commands at indices ``ti``; ``ctrl[i +
    1]`` is the control point of command ``i`` (``ctrl[0]``: the one before
    the first command).

    Each reflects the previous control point about the current point when
    the previous command was ``Q``/``T``, else it is the current point.  In
    a run of ``T`` commands ``c[k] = 2 P[k] - c[k-1]``; with
    ``u[k] = (-1)**k c[k]`` that becomes ``u[k] = u[k-1] + 2 (-1)**k P[k]``,
    a cumulative sum per run (a run at the first command continues the
    previous part's, from its control point)."""
    P = prev[ti]
    pk = prevkind[ti]
    start = pk != _T
    start[0] |= ti[0] == 0
    r = P.copy()                                   # reflected point at a run start
    fromq = start & ((pk == _Q) | (pk == _T))
    r[fromq] = ctrl[ti[fromq]]
    sgn = np.where(ti % 2 == 0, 1.0, -1.0)[:, None]
    term = 2 * sgn * P
    cs = np.cumsum(term, axis=0)
    run = np.cumsum(start) - 1
    s = np.flatnonzero(start)
    base = -sgn[s] * r[s] - (cs[s] - term[s])
    return sgn * (cs + base[run])


# -- elliptical arcs ---------------------------------------------------------------------
def _arc_error(theta):
    """Radial error of the standard cubic approximation (control arms
    ``4/3 tan(theta/4)``) of a unit-circle arc of ``theta`` radians:
    ``(2/27) sin(theta/4)**6 / cos(theta/4)**2``.  For theta <= pi/2 the
    true maximum is within 0.01% of this (measured); callers add 1%."""
    q = theta / 4
    return (2.0 / 27.0) * np.sin(q) ** 6 / np.cos(q) ** 2


def _pieces(sweep, radius, tol):
    """Number of cubic pieces for arcs of ``sweep`` radians (absolute) on
    ellipses whose larger radius is ``radius``: at most 90 degrees each and
    radial error at most ``tol``."""
    n = np.maximum(np.ceil(sweep / (np.pi / 2) - 1e-9), 1.0)
    with np.errstate(divide='ignore', over='ignore', invalid='ignore'):
        theta = 4.0 * (13.5 / 1.01 * tol / radius) ** (1.0 / 6.0)   # small-angle inverse
        n = np.maximum(n, np.ceil(sweep / theta))
    n = np.where(np.isfinite(n), n, float(MAX_ARC_PIECES + 1))
    if np.any(n > MAX_ARC_PIECES):
        raise LimitError('elliptical arc needs more than %d cubic pieces at '
                         'tolerance %g' % (MAX_ARC_PIECES, tol))
    for _ in range(8):                             # the estimate is close: fix up
        bad = 1.01 * _arc_error(sweep / n) * radius > tol
        if not bad.any():
            break
        n[bad] += 1
    return n.astype(np.int64)


def _arc_batch(p0, p1, rx, ry, phi_deg, large, sweep, tol):
    """Convert N SVG arcs (endpoint form) at once.

    Returns ``kind`` ((N,) 0: omitted, 1: straight line, 2: cubics),
    ``count`` ((N,) pieces per arc; 1 for lines) and ``ctrl`` ((K, 3, 2)
    control points of all cubic pieces, arc by arc)."""
    rx, ry = np.abs(rx), np.abs(ry)
    same = np.all(p0 == p1, axis=1)
    line = ~same & ((rx == 0) | (ry == 0))
    arc = ~same & ~line
    ctrl = np.zeros((0, 3, 2))
    count = line.astype(np.int64)
    if arc.any():
        i = np.flatnonzero(arc)
        ok, n, ctrl = _arc_cubics(p0[i], p1[i], rx[i], ry[i], phi_deg[i],
                                  large[i] != 0, sweep[i] != 0, tol)
        line[i[~ok]] = True                        # radius too large to matter
        arc[i[~ok]] = False
        count[i] = np.where(ok, n, 1)
    kind = np.where(same, 0, np.where(line, 1, 2))
    return kind, count, ctrl


def _arc_cubics(p0, p1, rx, ry, phi_deg, large, sweep, tol):
    """Centre parameterization (SVG implementation notes, F.6.5/F.6.6)
    computed in the unit-circle frame of each ellipse, then cubic pieces.

    Returns ``ok`` ((N,) False where the chord is negligible against the
    radii, to be drawn as a line), ``n`` ((N,) pieces) and ``ctrl``
    ((sum n over ok, 3, 2))."""
    phi = np.radians(np.mod(phi_deg, 360.0))
    co, si = np.cos(phi), np.sin(phi)
    h = (p0 - p1) * 0.5
    X = (co * h[:, 0] + si * h[:, 1]) / rx          # half chord in unit frame
    Y = (-si * h[:, 0] + co * h[:, 1]) / ry
    lam = X * X + Y * Y
    ok = (lam > 0) & np.isfinite(lam)
    scale = np.sqrt(np.where(lam > 1, lam, 1.0))    # radii too small: scale up
    rx, ry, X, Y = rx * scale, ry * scale, X / scale, Y / scale
    lam = np.where(ok, X * X + Y * Y, 1.0)
    # radicand of F.6.5.2 in the unit frame; exactly 0 once radii were scaled
    s = np.where(scale > 1, 0.0, np.sqrt(np.maximum(0.0, (1.0 - lam) / lam)))
    s = np.where(large != sweep, s, -s)
    ucx, ucy = s * Y, -s * X                        # centre in unit frame
    t1 = np.arctan2(Y - ucy, X - ucx)
    dt = np.mod(np.arctan2(-Y - ucy, -X - ucx) - t1, 2 * np.pi)
    dt = np.where(sweep, dt, dt - 2 * np.pi)
    n = np.zeros(len(p0), np.int64)
    n[ok] = _pieces(np.abs(dt[ok]), np.maximum(rx, ry)[ok], tol)
    sel = np.flatnonzero(ok)
    n_sel = n[sel]
    a = np.repeat(sel, n_sel)                        # arc of every piece
    jj = np.arange(len(a)) - np.repeat(np.cumsum(n_sel) - n_sel, n_sel)
    step = (dt / np.maximum(n, 1))[a]
    a0 = t1[a] + step * jj
    a1 = t1[a] + step * (jj + 1)
    k = (4.0 / 3.0) * np.tan(step / 4)
    c0, s0, c1, s1 = np.cos(a0), np.sin(a0), np.cos(a1), np.sin(a1)
    ux = np.stack([c0 - k * s0, c1 + k * s1, c1], 1) + ucx[a][:, None]
    uy = np.stack([s0 + k * c0, s1 - k * c1, s1], 1) + ucy[a][:, None]
    ex, ey = ux * rx[a][:, None], uy * ry[a][:, None]
    mid = (p0 + p1)[a] * 0.5
    ctrl = np.empty((len(a), 3, 2))
    ctrl[:, :, 0] = co[a][:, None] * ex - si[a][:, None] * ey + mid[:, 0:1]
    ctrl[:, :, 1] = si[a][:, None] * ex + co[a][:, None] * ey + mid[:, 1:2]
    if len(a):
        ctrl[np.cumsum(n_sel) - 1, 2] = p1[sel]      # end exactly on p1
    return ok, n, ctrl


def _piece_count(sweep, radius, tol):
    """Scalar :func:`_pieces` (pure Python: no numpy call overhead)."""
    n = max(math.ceil(sweep / (math.pi / 2) - 1e-9), 1)
    theta = 4.0 * (13.5 / 1.01 * tol / radius) ** (1.0 / 6.0)
    if theta == 0 or sweep / theta > MAX_ARC_PIECES:
        raise LimitError('elliptical arc needs more than %d cubic pieces at '
                         'tolerance %g' % (MAX_ARC_PIECES, tol))
    n = max(n, math.ceil(sweep / theta))
    for _ in range(8):
        q = sweep / n / 4
        if 1.01 * (2.0 / 27.0) * math.sin(q) ** 6 / math.cos(q) ** 2 * radius <= tol:
            break
        n += 1
    return n


def _arc_scalar(x0, y0, rx, ry, phi_deg, large, sweep, x1, y1, tol):
    """One arc, same mathematics as :func:`_arc_cubics` in plain Python.

    Returns ``None`` (end points equal: omit the arc), ``[]`` (zero radius,
    or a chord negligible against the radii: a straight line) or the flat
    list ``[x, y, ...]`` of the control points of its cubic pieces."""
    if x0 == x1 and y0 == y1:
        return None
    rx, ry = abs(rx), abs(ry)
    if rx == 0 or ry == 0:
        return []
    phi = math.radians(phi_deg % 360.0)
    co, si = math.cos(phi), math.sin(phi)
    hx, hy = (x0 - x1) * 0.5, (y0 - y1) * 0.5
    X = (co * hx + si * hy) / rx
    Y = (-si * hx + co * hy) / ry
    lam = X * X + Y * Y
    if not (lam > 0 and math.isfinite(lam)):
        return []
    if lam > 1:
        scale = math.sqrt(lam)
        rx, ry, X, Y, s = rx * scale, ry * scale, X / scale, Y / scale, 0.0
    else:
        s = math.sqrt(max(0.0, (1.0 - lam) / lam))
        if bool(large) == bool(sweep):
            s = -s
    ucx, ucy = s * Y, -s * X
    t1 = math.atan2(Y - ucy, X - ucx)
    dt = (math.atan2(-Y - ucy, -X - ucx) - t1) % (2 * math.pi)
    if not sweep:
        dt -= 2 * math.pi
    n = _piece_count(abs(dt), max(rx, ry), tol)
    step = dt / n
    k = (4.0 / 3.0) * math.tan(step / 4)
    mx, my = (x0 + x1) * 0.5, (y0 + y1) * 0.5
    out = []
    c1, s1 = math.cos(t1), math.sin(t1)
    for j in range(n):
        c0, s0 = c1, s1
        a1 = t1 + step * (j + 1)
        c1, s1 = math.cos(a1), math.sin(a1)
        for ux, uy in ((c0 - k * s0, s0 + k * c0), (c1 + k * s1, s1 - k * c1), (c1, s1)):
            ex, ey = (ux + ucx) * rx, (uy + ucy) * ry
            out += (co * ex - si * ey + mx, si * ex + co * ey + my)
    out[-2:] = (x1, y1)                             # end exactly on p1
    return out


def _finite(name, *vals):
    out = []
    for v in vals:
        if type(v) is float and math.isfinite(v):     # (the common case, quickly)
            out.append(v)
            continue
        try:
            f = float(v)
        except (TypeError, ValueError):
            raise PathError('%s must be numbers, got %r' % (name, v)) from None
        if not math.isfinite(f):
            raise PathError('%s must be finite, got %r' % (name, v))
        out.append(f)
    return out


def arc_to_cubics(p0: ArrayLike, rx: float, ry: float, phi_deg: float, large_arc: bool,
                  sweep: bool, p1: ArrayLike, tolerance: float = 0.01) -> np.ndarray:
    """Cubic Beziers of an SVG elliptical arc given in endpoint form.

    Follows the SVG implementation notes: negative radii use their absolute
    value, radii too small to reach ``p1`` are scaled up uniformly, the
    x-axis rotation is in degrees, ``sweep`` true means the positive-angle
    direction (clockwise on screen, y down).

    Parameters
    ----------
    p0, p1 : pair of float
        Start and end point.
    rx, ry, phi_deg : float
        Radii and x-axis rotation in degrees.
    large_arc, sweep : bool
        The SVG flags.
    tolerance : float, optional
        Largest distance between the arc and the cubics, in path units.  No
        piece spans more than 90 degrees.

    Returns
    -------
    (K, 3, 2) float64 ndarray
        Control points of each piece after its start point; piece ``i``
        starts at ``p0`` (``i == 0``) or at the end of piece ``i-1``, and the
        last piece ends exactly at ``p1``.  ``K == 0`` when ``p0 == p1`` (the
        arc is omitted); a zero radius gives one cubic along the straight
        line.

    Examples
    --------
    >>> c = arc_to_cubics((0, 0), 5, 5, 0, False, True, (10, 0))
    >>> c.shape
    (2, 3, 2)
    >>> c[0, 2].round(12).tolist()   # sweep 1 passes above the chord (y down)
    [5.0, -5.0]
    """
    tol = _check_tolerance(tolerance)
    x0, y0, x1, y1 = _finite('arc end points', p0[0], p0[1], p1[0], p1[1])
    rx, ry, phi = _finite('arc radii and rotation', rx, ry, phi_deg)
    ctrl = _arc_scalar(x0, y0, rx, ry, phi, bool(large_arc), bool(sweep), x1, y1, tol)
    if ctrl is None:
        return np.zeros((0, 3, 2))
    if not ctrl:
        a, b = np.array([x0, y0]), np.array([x1, y1])
        return np.array([[a + (b - a) / 3, a + (b - a) * (2 / 3), b]])
    return np.array(ctrl).reshape(-1, 3, 2)


# -- basic shapes ----------------------------------------------------------------------
# All shape functions raise PathError for non-numeric or non-finite geometry
# and for a tolerance that is not a positive finite number.
_QUADRANT = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])


def _quarters(centres, rx, ry, quadrants, tol):
    """Cubics of quarter-ellipse arcs, each from angle ``q * 90`` to
    ``(q + 1) * 90`` degrees (positive direction) about its centre.

    ``centres`` is one centre (2,) for all quarters or one a quarter
    (Q, 2).  Returns (Q * n, 3, 2) control points, quarter by quarter;
    quarter end points are exact."""
    n = _quarter_pieces(max(rx, ry), tol)
    out = _unit_quarters(n, tuple(quadrants)) * np.array([rx, ry])
    c = np.asarray(centres, dtype=np.float64)
    out += c if c.ndim == 1 else np.repeat(c, n, axis=0)[:, None, :]
    return out, n


@functools.lru_cache(maxsize=1024)
def _quarter_pieces(radius, tol):
    """Pieces of a quarter arc of ``radius`` within ``tol`` (memoized:
    documents repeat their radii and tolerances)."""
    return _piece_count(np.pi / 2, radius, tol)


@functools.lru_cache(maxsize=64)
def _unit_quarters(n, quadrants):
    """The unit circle's part of :func:`_quarters` for ``n`` pieces a
    quarter: (Q * n, 3, 2) control points, the quarters' ends exact (the
    same for every circle, ellipse and rounded corner drawn in that many
    pieces; read-only and cached, so a document of many small circles
    builds them once)."""
    q = np.repeat(np.asarray(quadrants), n)
    j = np.tile(np.arange(n), len(quadrants))
    step = (np.pi / 2) / n
    a0 = q * (np.pi / 2) + j * step
    a1 = a0 + step
    k = (4.0 / 3.0) * math.tan(step / 4)
    c0, s0, c1, s1 = np.cos(a0), np.sin(a0), np.cos(a1), np.sin(a1)
    last = j == n - 1
    end = _QUADRANT[(q + 1) % 4]
    c1 = np.where(last, end[:, 0], c1)
    s1 = np.where(last, end[:, 1], s1)
    first = j == 0
    c0 = np.where(first, _QUADRANT[q][:, 0], c0)
    s0 = np.where(first, _QUADRANT[q][:, 1], s0)
    u = np.empty((len(q), 3, 2))
    u[:, :, 0] = np.stack([c0 - k * s0, c1 + k * s1, c1], 1)
    u[:, :, 1] = np.stack([s0 + k * c0, s1 - k * c1, s1], 1)
    u.flags.writeable = False
    return u


def _auto_radii(rx, ry):
    if rx is None and ry is None:
        return 0.0, 0.0
    if rx is None:
        rx = ry
    if ry is None:
        ry = rx
    return _finite('radii', rx, ry)


def rect_path(x: float, y: float, w: float, h: float, rx: Optional[float] = None,
              ry: Optional[float] = None, tolerance: float = 0.01) -> Path:
    """Path of an SVG ``<rect>`` (SVG 2 equivalent path).

    Square corners: ``M x,y H x+w V y+h H x Z`` (the closing edge is drawn
    by ``Z``).  Rounded corners start at ``(x+rx, y)`` and go right
    (clockwise on screen): line, quarter arc, line, quarter arc, ... ,
    ``Z``; lines of zero length are kept.

    Parameters
    ----------
    x, y, w, h : float
        Position and size; ``w <= 0`` or ``h <= 0`` gives an empty path.
    rx, ry : float or None, optional
        Corner radii.  ``None`` is SVG's ``auto``: one given sets the other.
        Each is then clamped to half the width/height; a negative radius
        counts as 0.
    tolerance : float, optional
        Largest distance (path units) between a corner arc and its cubics.

    Returns
    -------
    Path

    Examples
    --------
    >>> rect_path(0, 0, 10, 5).to_svg()
    'M 0 0 L 10 0 L 10 5 L 0 5 Z'
    >>> p = rect_path(0, 0, 10, 6, rx=2)
    >>> p.points[0].tolist(), p.verbs.tolist()[:3]
    ([2.0, 0.0], [0, 1, 3])
    """
    _check_tolerance(tolerance)
    x, y, w, h = _finite('rect geometry', x, y, w, h)
    if w <= 0 or h <= 0:
        return Path.empty()
    rx, ry = _auto_radii(rx, ry)
    rx = min(max(rx, 0.0), w / 2)
    ry = min(max(ry, 0.0), h / 2)
    if rx == 0 or ry == 0:
        pts = np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]])
        return Path(np.array([MOVE, LINE, LINE, LINE, CLOSE], np.uint8), pts, _checked=True)
    x0, x1, y0, y1 = x + rx, x + w - rx, y + ry, y + h - ry
    arcs, n = _quarters([[x1, y0], [x1, y1], [x0, y1], [x0, y0]], rx, ry, [3, 0, 1, 2],
                        _check_tolerance(tolerance))
    arcs = arcs.reshape(4, n, 3, 2)
    lines = [[x1, y], [x + w, y1], [x0, y + h], [x, y0]]
    pts = [np.array([[x0, y]])]
    for i in range(4):
        pts.append(np.array([lines[i]]))
        pts.append(arcs[i].reshape(-1, 2))
    pts = np.concatenate(pts)
    ends = np.arange(1, 5) * (1 + 3 * n)             # exact corner-arc ends
    pts[ends] = [[x + w, y0], [x1, y + h], [x, y1], [x0, y]]
    corner = [LINE] + [CUBIC] * n
    verbs = np.array([MOVE] + corner * 4 + [CLOSE], np.uint8)
    return Path(verbs, pts, _checked=True)


def ellipse_path(cx: float, cy: float, rx: Optional[float] = None, ry: Optional[float] = None,
                 tolerance: float = 0.01) -> Path:
    """Path of an SVG ``<ellipse>``: starts at ``(cx+rx, cy)``, four quarter
    arcs in the positive-angle direction (clockwise on screen, through
    ``(cx, cy+ry)`` first), then ``Z``.

    Parameters
    ----------
    cx, cy : float
        Centre.
    rx, ry : float or None, optional
        Radii; ``None`` is SVG's ``auto`` (the other radius).  A radius
        ``<= 0`` (or both ``None``) gives an empty path.
    tolerance : float, optional
        Largest distance (path units) between the ellipse and the cubics;
        each quarter is split into equal pieces as needed.

    Returns
    -------
    Path

    Examples
    --------
    >>> p = ellipse_path(0, 0, 4, 2)
    >>> p.points[[0, 3, 6, 9, 12]].tolist()
    [[4.0, 0.0], [0.0, 2.0], [-4.0, 0.0], [0.0, -2.0], [4.0, 0.0]]
    """
    tol = _check_tolerance(tolerance)
    cx, cy = _finite('ellipse centre', cx, cy)
    rx, ry = _auto_radii(rx, ry)
    if rx <= 0 or ry <= 0:
        return Path.empty()
    n = _quarter_pieces(max(rx, ry), tol)
    verbs, unit = _unit_ellipse(n)
    pts = unit * np.array((rx, ry))
    pts += np.array((cx, cy))
    return Path(verbs, pts, _checked=True)


@functools.lru_cache(maxsize=64)
def _unit_ellipse(n):
    """The verbs and points of :func:`ellipse_path` for the unit circle
    with ``n`` pieces a quarter: the start ``(1, 0)`` and the four quarters
    of :func:`_unit_quarters` (read-only, shared by those paths: a Path's
    arrays never change)."""
    v = np.array([MOVE] + [CUBIC] * (4 * n) + [CLOSE], np.uint8)
    v.flags.writeable = False
    u = np.concatenate([[[1.0, 0.0]], _unit_quarters(n, (0, 1, 2, 3)).reshape(-1, 2)])
    u.flags.writeable = False
    return v, u


def circle_path(cx: float, cy: float, r: float, tolerance: float = 0.01) -> Path:
    """Path of an SVG ``<circle>``: :func:`ellipse_path` with ``rx = ry = r``
    (empty for ``r <= 0``).

    Examples
    --------
    >>> circle_path(0, 0, 1).verbs.tolist()
    [0, 3, 3, 3, 3, 4]
    """
    (r,) = _finite('circle radius', r)
    return ellipse_path(cx, cy, r, r, tolerance)


def line_path(x1: float, y1: float, x2: float, y2: float, tolerance: float = 0.01) -> Path:
    """Path of an SVG ``<line>``: ``M x1,y1 L x2,y2`` (kept when of zero
    length, for caps).  ``tolerance`` is accepted for uniformity.

    Examples
    --------
    >>> line_path(0, 0, 3, 4).to_svg()
    'M 0 0 L 3 4'
    """
    _check_tolerance(tolerance)
    pts = np.array([_finite('line end points', x1, y1, x2, y2)]).reshape(2, 2)
    return Path(np.array([MOVE, LINE], np.uint8), pts, _checked=True)


def parse_points(s: str) -> np.ndarray:
    """Parse an SVG ``points`` attribute.

    Parameters
    ----------
    s : str
        Numbers in SVG syntax with comma/whitespace separators.  Parsing
        stops at the first error or non-finite number (the pairs before it
        are kept); an odd count drops the last number.

    Returns
    -------
    (N, 2) float64 ndarray

    Examples
    --------
    >>> parse_points('0,0 10-5 20 .5 7').tolist()
    [[0.0, 0.0], [10.0, -5.0], [20.0, 0.5]]
    >>> parse_points('1 2 3 4 x 5 6').shape
    (2, 2)
    """
    if not isinstance(s, str):
        raise PathError('points must be a string, got %s' % type(s).__name__)
    end = _POINTS_RE.match(s).end()
    vals = np.array(_NUM_RE.findall(s, 0, end), dtype=np.float64)
    bad = np.flatnonzero(~np.isfinite(vals))
    if len(bad):
        vals = vals[:bad[0]]
    return vals[:len(vals) // 2 * 2].reshape(-1, 2)


def polyline_path(points: ArrayLike, closed: bool = False, tolerance: float = 0.01) -> Path:
    """Path of an SVG ``<polyline>`` (``closed=True``: ``<polygon>``):
    ``M`` to the first point, ``L`` to the others, ``Z`` when closed.

    Parameters
    ----------
    points : (N, 2) array_like or str
        The vertices, or an SVG ``points`` string (see :func:`parse_points`).
    closed : bool, optional
    tolerance : float, optional
        Accepted for uniformity (nothing is approximated).

    Returns
    -------
    Path
        Empty when there are no points.

    Examples
    --------
    >>> polyline_path('0,0 10,0 10,10', closed=True).to_svg()
    'M 0 0 L 10 0 L 10 10 Z'
    """
    _check_tolerance(tolerance)
    if isinstance(points, str):
        pts = parse_points(points)
    else:
        try:
            pts = np.array(points, dtype=np.float64)
        except (TypeError, ValueError):
            raise PathError('points must be an (N, 2) array of numbers') from None
        if pts.size == 0:
            pts = pts.reshape(0, 2)
        if pts.ndim != 2 or pts.shape[1] != 2:
            raise PathError('points must have shape (N, 2), got %s' % (pts.shape,))
        if not np.isfinite(pts).all():
            raise PathError('points must be finite')
    if len(pts) == 0:
        return Path.empty()
    verbs = np.full(len(pts) + bool(closed), LINE, np.uint8)
    verbs[0] = MOVE
    if closed:
        verbs[-1] = CLOSE
    return Path(verbs, pts.copy(), _checked=True)
