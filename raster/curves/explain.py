r"""Worked solutions: the derivations the course exercises ask for, written
out with the numbers of a given curve.

:func:`explain` returns text in one of three formats (``'plain'``,
``'markdown'`` with ``$...$`` math, ``'latex'`` body text).  What it derives
depends on the curve:

* Bezier curves: the blending functions of the degree written out, the
  parametric equation with the control points substituted, each requested
  ``t`` substituted with its arithmetic, the table of points and the
  polynomial form (and tangents, with ``tangent=True``);
* Hermite curves: the general cubic, the four end conditions, the Hermite
  basis matrix obtained by solving them, the blending functions, then the
  substitution as for Bezier curves;
* natural and clamped cubic splines: the tridiagonal system of the second
  derivatives with the numbers filled in, its solution, and the cubic of
  every interval;
* the other families (cardinal, Kochanek-Bartels, B-spline, Beta-spline,
  rational Bezier, NURBS): their blending functions' values at each ``t``
  and the weighted sums;
* every curve with joints: the derivatives on both sides of each joint and
  the continuity they give.

The document is built from a few block types (:class:`Doc`), so the three
formats say the same thing.

>>> from raster.curves import Bezier
>>> text = explain(Bezier([[2, 6], [6, 8], [9, 12]]), [0.8])
>>> 'P(0.8) = (7.76, 10.48)' in text
True
"""

import math
from typing import Sequence

import numpy as np

from .checks import CurveError

__all__ = ['explain', 'Doc', 'FORMATS']

FORMATS = ('plain', 'markdown', 'latex')


def num(v: float, digits: int = 6) -> str:
    """A number for the reader: up to ``digits`` significant digits, no
    trailing zeros, no ``-0``."""
    v = float(v)
    if not math.isfinite(v):
        return 'inf' if v > 0 else ('-inf' if v < 0 else 'nan')
    if abs(v) < 1e-12:
        return '0'
    s = '%.*g' % (digits, v)
    if 'e' in s:
        m, e = s.split('e')
        return '%se%d' % (m, int(e))
    return s


def _pt(p):
    return '(' + ', '.join(num(x) for x in p) + ')'


class M:
    """A piece of mathematics with a plain-text and a LaTeX spelling."""

    def __init__(self, plain, latex=None):
        self.plain = plain
        self.latex = plain if latex is None else latex


class Doc:
    """A document of blocks: ``('h', text)``, ``('p', parts)`` (strings and
    :class:`M`), ``('eq', [M, ...])`` (displayed lines) and ``('table',
    header, rows)``."""

    def __init__(self):
        self.blocks = []

    def h(self, text):
        self.blocks.append(('h', text))

    def p(self, *parts):
        self.blocks.append(('p', list(parts)))

    def eq(self, *lines):
        self.blocks.append(('eq', [x if isinstance(x, M) else M(x) for x in lines]))

    def table(self, header, rows):
        self.blocks.append(('table', header, rows))

    def render(self, fmt='plain'):
        """The document as text in ``fmt`` (one of :data:`FORMATS`)."""
        if fmt not in FORMATS:
            raise CurveError('format must be one of %s, got %r' % (', '.join(FORMATS), fmt))
        out = []
        for b in self.blocks:
            kind = b[0]
            if kind == 'h':
                out.append({'plain': '%s\n%s' % (b[1], '-' * len(b[1])),
                            'markdown': '### %s' % b[1],
                            'latex': '\\subsection*{%s}' % _tex_text(b[1])}[fmt])
            elif kind == 'p':
                out.append(''.join(self._inline(x, fmt) for x in b[1]))
            elif kind == 'eq':
                if fmt == 'plain':
                    out.append('\n'.join('    ' + m.plain.replace('\n', '\n    ') for m in b[1]))
                elif fmt == 'markdown':
                    out.append('$$\n\\begin{aligned}\n%s\n\\end{aligned}\n$$'
                               % ' \\\\\n'.join(_align(m.latex) for m in b[1]))
                else:
                    out.append('\\begin{align*}\n%s\n\\end{align*}'
                               % ' \\\\\n'.join(_align(m.latex) for m in b[1]))
            else:
                out.append(self._table(b[1], b[2], fmt))
        return '\n\n'.join(out) + '\n'

    @staticmethod
    def _inline(x, fmt):
        if isinstance(x, M):
            return x.plain if fmt == 'plain' else '$%s$' % x.latex
        return x if fmt != 'latex' else _tex_text(x)

    def _table(self, header, rows, fmt):
        cells = [[self._inline(x, fmt) for x in header]] + [[str(v) for v in r] for r in rows]
        if fmt == 'plain':
            wid = [max(len(c[i]) for c in cells) for i in range(len(header))]
            lines = ['  '.join(c[i].rjust(wid[i]) for i in range(len(c))) for c in cells]
            lines.insert(1, '  '.join('-' * w for w in wid))
            return '\n'.join('    ' + ln for ln in lines)
        if fmt == 'markdown':
            lines = ['| ' + ' | '.join(c) + ' |' for c in cells]
            lines.insert(1, '|' + '|'.join('---:' for _ in header) + '|')
            return '\n'.join(lines)
        body = ' \\\\\n'.join(' & '.join(c) for c in cells[1:])
        return ('\\begin{tabular}{%s}\n%s \\\\\n\\hline\n%s \\\\\n\\end{tabular}'
                % ('r' * len(header), ' & '.join(cells[0]), body))


def _tex_text(s):
    for a, b in (('\\', '\\textbackslash{}'), ('&', '\\&'), ('%', '\\%'), ('#', '\\#'),
                 ('_', '\\_'), ('^', '\\^{}')):
        s = s.replace(a, b)
    return s


def _align(latex):
    """Put the alignment mark before the first '=' of a displayed line."""
    i = latex.find('=')
    return latex if i < 0 else latex[:i] + '&' + latex[i:]


# -- polynomials in words ---------------------------------------------------------
def _poly(coef, var='t'):
    """(plain, latex) of sum coef[k] var^k."""
    terms = []
    for k, c in enumerate(coef):
        if abs(c) < 1e-12 * max(1.0, float(np.abs(coef).max())):
            continue
        mag = num(abs(c))
        if k == 0:
            body_p = body_l = mag
        else:
            pw_p = var if k == 1 else '%s^%d' % (var, k)
            pw_l = var if k == 1 else '%s^{%d}' % (var, k)
            body_p = pw_p if mag == '1' else '%s%s' % (mag, pw_p)
            body_l = pw_l if mag == '1' else '%s%s' % (mag, pw_l)
        terms.append(('-' if c < 0 else '+', body_p, body_l))
    if not terms:
        return '0', '0'
    p = ('-' if terms[0][0] == '-' else '') + terms[0][1]
    latex = ('-' if terms[0][0] == '-' else '') + terms[0][2]
    for s, bp, bl in terms[1:]:
        p += ' %s %s' % (s, bp)
        latex += ' %s %s' % (s, bl)
    return p, latex


def _bern_symbolic(n, i, var='t'):
    """(plain, latex) of C(n,i) t^i (1-t)^(n-i) in simplest form."""
    c = math.comb(n, i)
    parts_p, parts_l = [], []
    if c != 1:
        parts_p.append(str(c))
        parts_l.append(str(c))
    if i == 1:
        parts_p.append(var)
        parts_l.append(var)
    elif i > 1:
        parts_p.append('%s^%d' % (var, i))
        parts_l.append('%s^{%d}' % (var, i))
    j = n - i
    if j == 1:
        parts_p.append('(1-%s)' % var)
        parts_l.append('(1-%s)' % var)
    elif j > 1:
        parts_p.append('(1-%s)^%d' % (var, j))
        parts_l.append('(1-%s)^{%d}' % (var, j))
    if not parts_p:
        return '1', '1'
    return ''.join(parts_p), ''.join(parts_l)


def _bern_numeric(n, i, t):
    """(plain, latex, value) of C(n,i) t^i (1-t)^(n-i) with t substituted."""
    c = math.comb(n, i)
    s = num(1 - t)
    tt = num(t)
    fp, fl = [], []
    if c != 1:
        fp.append(str(c))
        fl.append(str(c))
    for base, e in ((tt, i), (s, n - i)):
        if e == 0:
            continue
        fp.append('(%s)' % base if e == 1 else '(%s)^%d' % (base, e))
        fl.append('(%s)' % base if e == 1 else '(%s)^{%d}' % (base, e))
    val = c * t ** i * (1 - t) ** (n - i)
    if not fp:
        return '1', '1', val
    return '*'.join(fp), ' \\cdot '.join(fl), val


def _weighted_sum(weights, values, label):
    """``label = w0(v0) + w1(v1) + ... = a + b + ... = result``."""
    prods = [w * v for w, v in zip(weights, values)]

    def chain(items):
        out = ''
        for k, (mag, neg) in enumerate(items):
            out += ('-' if neg else '') + mag if k == 0 else (' - ' if neg else ' + ') + mag
        return out

    s1 = chain([('%s(%s)' % (num(abs(w)), num(v)), w < 0) for w, v in zip(weights, values)])
    l1 = chain([('%s \\cdot %s' % (num(abs(w)), _paren(num(v))), w < 0)
                for w, v in zip(weights, values)])
    s2 = chain([(num(abs(p)), p < 0) for p in prods])
    tot = float(sum(prods))
    return M('%s = %s = %s = %s' % (label[0], s1, s2, num(tot)),
             '%s = %s = %s = %s' % (label[1], l1, s2, num(tot))), tot


def _paren(s):
    return '(%s)' % s if s.startswith('-') else s


# -- the explanations ---------------------------------------------------------------
def _names(k):
    return ['P%d' % i for i in range(k)], ['P_{%d}' % i for i in range(k)]


def _control_list(points, names):
    return ', '.join('%s%s' % (n, _pt(p)) for n, p in zip(names, points))


def _axes(D):
    return ['x', 'y', 'z', 'w'][:D] if D <= 4 else ['x%d' % i for i in range(D)]


def _bezier(doc, curve, ts, tangent):
    P = curve.ctrl
    n, D = curve.degree, curve.dim
    names_p, names_l = _names(n + 1)
    ax = _axes(D)
    doc.h('Bezier curve of degree %d' % n)
    doc.p('%d control points: %s.' % (n + 1, _control_list(P, names_p)))
    doc.p('The curve is ', M('P(t) = sum_{i=0}^{%d} B_{%d,i}(t) P_i' % (n, n),
                               'P(t) = \\sum_{i=0}^{%d} B_{%d,i}(t)\\,P_i' % (n, n)),
          ', 0 <= t <= 1, with the blending functions (Bernstein polynomials) ',
          M('B_{n,i}(t) = C(n,i) t^i (1-t)^(n-i)', 'B_{n,i}(t) = \\binom{n}{i} t^i (1-t)^{n-i}'),
          ', ', M('C(n,i) = n! / (i! (n-i)!)', '\\binom{n}{i} = \\frac{n!}{i!\\,(n-i)!}'), '.')
    doc.h('Blending functions for n = %d' % n)
    lines = []
    for i in range(n + 1):
        bp, bl = _bern_symbolic(n, i)
        lines.append(M('B_%d,%d(t) = %d!/(%d! %d!) t^%d (1-t)^%d = %s'
                       % (n, i, n, i, n - i, i, n - i, bp),
                       'B_{%d,%d}(t) = \\frac{%d!}{%d!\\,%d!} t^{%d} (1-t)^{%d} = %s'
                       % (n, i, n, i, n - i, i, n - i, bl)))
    doc.eq(*lines)
    bp = [(_bern_symbolic(n, i)) for i in range(n + 1)]
    doc.p('So the parametric equation is')
    doc.eq(M('P(t) = ' + ' + '.join('%s %s' % (b[0], names_p[i]) for i, b in enumerate(bp)),
             'P(t) = ' + ' + '.join('%s\\,%s' % (b[1], names_l[i]) for i, b in enumerate(bp))))
    rows = []
    for d, a in enumerate(ax):
        tp, tl = [], []
        for i in range(n + 1):
            c = math.comb(n, i) * P[i, d]
            if c == 0:
                continue
            sym = _bern_symbolic(n, i)
            bare = [x[len(str(math.comb(n, i))):] if math.comb(n, i) != 1 else x for x in sym]
            mag = num(abs(c))
            tp.append(('-' if c < 0 else '+', (mag if mag != '1' or not bare[0] else '') + bare[0]))
            tl.append(('-' if c < 0 else '+', (mag if mag != '1' or not bare[1] else '') + bare[1]))
        if not tp:
            tp = tl = [('+', '0')]
        rows.append(M('%s(t) = ' % a + ('-' if tp[0][0] == '-' else '') + tp[0][1]
                      + ''.join(' %s %s' % x for x in tp[1:]),
                      '%s(t) = ' % a + ('-' if tl[0][0] == '-' else '') + tl[0][1]
                      + ''.join(' %s %s' % x for x in tl[1:])))
    doc.eq(*rows)
    _substitute(doc, ts, ax, P, lambda t: [_bern_numeric(n, i, t) for i in range(n + 1)],
                ['B_%d,%d' % (n, i) for i in range(n + 1)],
                ['B_{%d,%d}' % (n, i) for i in range(n + 1)])
    coef = curve.power_coeffs()
    doc.h('Polynomial form')
    doc.eq(*[M('%s(t) = %s' % (a, _poly(coef[:, d])[0]), '%s(t) = %s' % (a, _poly(coef[:, d])[1]))
             for d, a in enumerate(ax)])
    if tangent:
        _bezier_tangent(doc, curve, ts, ax)


def _substitute(doc, ts, ax, P, basis, names_p, names_l, point='P', var='t', one_minus=True,
                table_rows=None, offset=0.0):
    """The substitution of every t: blending values (``basis(t)`` gives
    (plain, latex, value) per function), weighted sums, table."""
    if not len(ts):
        return
    doc.h('Substituting the parameter values')
    table = []
    for t in ts:
        vals = basis(t)
        lines = [M('1 - %s = %s' % (var, num(1 - t)))] if one_minus else []
        w = []
        for i, (sp, sl, v) in enumerate(vals):
            lines.append(M('%s(%s) = %s = %s' % (names_p[i], num(t), sp, num(v)),
                           '%s(%s) = %s = %s' % (names_l[i], num(t), sl, num(v))))
            w.append(v)
        res = []
        for d, a in enumerate(ax):
            m, tot = _weighted_sum(w, P[:, d], ('%s(%s)' % (a, num(t)), '%s(%s)' % (a, num(t))))
            lines.append(m)
            res.append(tot)
        lines.append(M('%s(%s) = %s' % (point, num(t), _pt(res)),
                       '%s(%s) = %s' % (point, num(t), _pt(res))))
        if offset:
            doc.p('At ', M('t = %s' % num(t + offset)), ', ', M('%s = %s' % (var, num(t))), ':')
        else:
            doc.p('At ', M('%s = %s' % (var, num(t))), ':')
        doc.eq(*lines)
        table.append([num(t + offset)] + [num(v) for v in res])
    if table_rows is not None:
        table_rows.extend(table)
        return
    doc.h('Points on the curve')
    doc.table([M(var)] + [M('%s(%s)' % (a, var)) for a in ax], table)


def _bezier_tangent(doc, curve, ts, ax):
    n = curve.degree
    d = curve.deriv()
    doc.h('Tangent')
    doc.p('Differentiating the blending functions gives the hodograph ',
          M("P'(t) = %d sum_{i=0}^{%d} B_{%d,i}(t) (P_{i+1} - P_i)" % (n, n - 1, n - 1),
            "P'(t) = %d \\sum_{i=0}^{%d} B_{%d,i}(t)\\,(P_{i+1} - P_i)" % (n, n - 1, n - 1)),
          ', a Bezier curve of degree %d with control points %s.'
          % (n - 1, ', '.join(_pt(p) for p in d.ctrl)))
    rows = []
    for t in ts:
        v = np.atleast_2d(curve.tangent(t))[0]
        slope = v[1] / v[0] if len(v) > 1 and v[0] != 0 else float('inf')
        rows.append([num(t)] + [num(x) for x in v] + ([num(slope)] if len(v) > 1 else []))
    doc.table([M('t')] + [M("%s'(t)" % a, "%s'(t)" % a) for a in ax]
              + ([M('dy/dx', '\\frac{dy}{dx}')] if len(ax) > 1 else []), rows)


def _hermite(doc, curve, ts, derive=True):
    from .hermite import HERMITE_MATRIX
    D = curve.points.shape[1]
    ax = _axes(D)
    if not derive:
        doc.p('Blending functions: ', M('h00 = 2u^3 - 3u^2 + 1, h01 = -2u^3 + 3u^2, '
                                        'h10 = u^3 - 2u^2 + u, h11 = u^3 - u^2'),
              ' (the Hermite basis).')
        _hermite_segments(doc, curve, ts, ax)
        return
    doc.h('Hermite cubic: derivation of the basis matrix')
    doc.p('A parametric cubic and its derivative, 0 <= t <= 1:')
    doc.eq(M('P(t) = a3 t^3 + a2 t^2 + a1 t + a0', 'P(t) = a_3 t^3 + a_2 t^2 + a_1 t + a_0'),
           M("P'(t) = 3 a3 t^2 + 2 a2 t + a1", "P'(t) = 3 a_3 t^2 + 2 a_2 t + a_1"))
    doc.p('The four end conditions (end points and end tangents):')
    doc.eq(M('P(0) = a0', 'P(0) = a_0'),
           M('P(1) = a3 + a2 + a1 + a0', 'P(1) = a_3 + a_2 + a_1 + a_0'),
           M("P'(0) = a1", "P'(0) = a_1"),
           M("P'(1) = 3 a3 + 2 a2 + a1", "P'(1) = 3a_3 + 2a_2 + a_1"))
    doc.p('In matrix form ', M("[P(0) P(1) P'(0) P'(1)]^T = C [a3 a2 a1 a0]^T",
                              "[P(0)\\;P(1)\\;P'(0)\\;P'(1)]^T = C\\,[a_3\\;a_2\\;a_1\\;a_0]^T"),
          ' with')
    C = np.array([[0, 0, 0, 1], [1, 1, 1, 1], [0, 0, 1, 0], [3, 2, 1, 0]], float)
    doc.eq(_matrix('C', C))
    doc.p('Solving (the first and third rows give a0 and a1 at once; the second and fourth '
          'then give a2 and a3):')
    doc.eq(M('a0 = P(0)', 'a_0 = P(0)'), M("a1 = P'(0)", "a_1 = P'(0)"),
           M("a2 = -3 P(0) + 3 P(1) - 2 P'(0) - P'(1)", "a_2 = -3P(0) + 3P(1) - 2P'(0) - P'(1)"),
           M("a3 = 2 P(0) - 2 P(1) + P'(0) + P'(1)", "a_3 = 2P(0) - 2P(1) + P'(0) + P'(1)"))
    doc.p('so ', M('[a3 a2 a1 a0]^T = M_H [P(0) P(1) P\'(0) P\'(1)]^T',
                   "[a_3\\;a_2\\;a_1\\;a_0]^T = M_H\\,[P(0)\\;P(1)\\;P'(0)\\;P'(1)]^T"),
          ' with the Hermite matrix ', M('M_H = C^-1', 'M_H = C^{-1}'), ':')
    doc.eq(_matrix('M_H', HERMITE_MATRIX))
    doc.p('Collecting the terms of each end condition gives the blending functions:')
    doc.eq(M("P(t) = (2t^3 - 3t^2 + 1) P(0) + (-2t^3 + 3t^2) P(1) + (t^3 - 2t^2 + t) P'(0) "
             "+ (t^3 - t^2) P'(1)",
             "P(t) = (2t^3 - 3t^2 + 1)P(0) + (-2t^3 + 3t^2)P(1) + (t^3 - 2t^2 + t)P'(0) "
             "+ (t^3 - t^2)P'(1)"))
    _hermite_segments(doc, curve, ts, ax)


def _hermite_segments(doc, curve, ts, ax):
    from .hermite import HERMITE_MATRIX
    S = len(curve.points) - 1
    rows = []
    for s in range(S):
        p0, p1 = curve.points[s], curve.points[s + 1]
        t0, t1 = curve.out_tangents[s], curve.in_tangents[s]
        g = np.stack([p0, p1, t0, t1])
        coef = (HERMITE_MATRIX @ g)[::-1]
        title = 'With the given data' if S == 1 else 'Segment %d (t in [%d, %d])' % (s, s, s + 1)
        doc.h(title)
        doc.p("P(0) = %s, P(1) = %s, P'(0) = %s, P'(1) = %s."
              % (_pt(p0), _pt(p1), _pt(t0), _pt(t1)))
        var = 't' if S == 1 else 'u'
        if S > 1:
            doc.p('Local parameter u = %s.' % ('t' if s == 0 else 't - %d' % s))
        doc.eq(*[M('%s(%s) = %s' % (a, var, _poly(coef[:, d], var)[0]),
                   '%s(%s) = %s' % (a, var, _poly(coef[:, d], var)[1]))
                 for d, a in enumerate(ax)])
        loc = [t - s for t in ts if (s <= t < s + 1) or (s == S - 1 and t == S)]
        if loc:
            _substitute(doc, loc, ax, g, _hermite_values, _HNAMES,
                        ['h_{00}', 'h_{01}', 'h_{10}', 'h_{11}'], var=var, one_minus=False,
                        table_rows=rows, offset=float(s))
    if rows:
        doc.h('Points on the curve')
        doc.table([M('t')] + [M('%s(t)' % a) for a in ax], rows)


_HNAMES = ['h00', 'h01', 'h10', 'h11']
_HPOLY = [('2u^3 - 3u^2 + 1', [1, 0, -3, 2]), ('-2u^3 + 3u^2', [0, 0, 3, -2]),
          ('u^3 - 2u^2 + u', [0, 1, -2, 1]), ('u^3 - u^2', [0, 0, -1, 1])]


def _hermite_values(t):
    """(plain, latex, value) of the four Hermite blending functions at t,
    with t substituted term by term."""
    out = []
    for _, c in _HPOLY:
        tp, tl = [], []
        for k in (3, 2, 1, 0):
            ck = c[k]
            if ck == 0:
                continue
            sign = '-' if ck < 0 else '+'
            mag = '' if abs(ck) == 1 and k else str(abs(ck))
            if k == 0:
                fp = fl = str(abs(ck))
            else:
                fp = '%s(%s)%s' % (mag, num(t), '^%d' % k if k > 1 else '')
                fl = '%s(%s)%s' % (mag, num(t), '^{%d}' % k if k > 1 else '')
            tp.append((sign, fp))
            tl.append((sign, fl))
        sp = ('-' if tp[0][0] == '-' else '') + tp[0][1] + ''.join(' %s %s' % x for x in tp[1:])
        sl = ('-' if tl[0][0] == '-' else '') + tl[0][1] + ''.join(' %s %s' % x for x in tl[1:])
        out.append((sp, sl, sum(ck * t ** k for k, ck in enumerate(c))))
    return out


def _matrix(name, A):
    cells = [[num(v) for v in r] for r in A]
    wid = max(len(c) for r in cells for c in r)
    pad = ' ' * (len(name) + 3)
    lines = ['| %s |' % ' '.join(c.rjust(wid) for c in r) for r in cells]
    plain = '\n'.join((name + ' = ' if i == 0 else pad) + ln for i, ln in enumerate(lines))
    latex = '%s = \\begin{bmatrix} %s \\end{bmatrix}' % (
        name, ' \\\\ '.join(' & '.join(r) for r in cells))
    return M(plain, latex)


def _natural(doc, curve, ts):
    from .natural import FunctionSpline, second_derivatives
    func = isinstance(curve, FunctionSpline)
    if func:
        x = curve.points[:, 0]
        Y = curve.points[:, 1:]
        ends = None if curve.end_slopes is None else np.array(curve.end_slopes)[:, None]
        names, var = ['y'], 'x'
    else:
        x = curve.params
        Y = curve.points
        ends = curve.end_tangents
        names, var = _axes(Y.shape[1]), 't'
    Mv = second_derivatives(x, Y, None if ends is None else (ends[0], ends[1]))
    n = len(x) - 1
    h = np.diff(x)
    doc.h('Cubic spline interpolation')
    if func:
        doc.p('Data points: %s.' % ', '.join('(%s, %s)' % (num(a), num(b))
                                            for a, b in zip(x, Y[:, 0])))
    else:
        doc.p('Points %s at the parameters t = %s (%s parameterization); each coordinate is '
              'a cubic spline of t.' % (', '.join(_pt(p) for p in Y),
                                        ', '.join(num(v) for v in x), curve.parameterization))
    doc.p('On each interval the spline is a cubic; with ',
          M('h_i = %s_{i+1} - %s_i' % (var, var)), ' and the second derivatives ',
          M("M_i = S''(%s_i)" % var), ' at the points, values, slopes and second '
          'derivatives of neighbouring cubics agree when')
    doc.eq(M('h_{i-1} M_{i-1} + 2(h_{i-1} + h_i) M_i + h_i M_{i+1} = 6((y_{i+1} - y_i)/h_i '
             '- (y_i - y_{i-1})/h_{i-1}),  i = 1..%d' % (n - 1),
             'h_{i-1} M_{i-1} + 2(h_{i-1} + h_i) M_i + h_i M_{i+1} = 6\\left(\\frac{y_{i+1} '
             '- y_i}{h_i} - \\frac{y_i - y_{i-1}}{h_{i-1}}\\right), \\quad i = 1, \\dots, %d'
             % (n - 1)))
    if ends is None:
        doc.p('Natural ends: ', M('M_0 = M_%d = 0' % n, 'M_0 = M_{%d} = 0' % n), '.')
    else:
        doc.p("Clamped ends with given end slopes s_0 = y'(%s_0), s_n = y'(%s_n):" % (var, var))
        doc.eq(M('2 h_0 M_0 + h_0 M_1 = 6((y_1 - y_0)/h_0 - s_0)',
                 '2h_0 M_0 + h_0 M_1 = 6\\left(\\frac{y_1 - y_0}{h_0} - s_0\\right)'),
               M('h_{n-1} M_{n-1} + 2 h_{n-1} M_n = 6(s_n - (y_n - y_{n-1})/h_{n-1})',
                 'h_{n-1} M_{n-1} + 2h_{n-1} M_n = 6\\left(s_n - \\frac{y_n - y_{n-1}}'
                 '{h_{n-1}}\\right)'))
    doc.p('Here h = %s.' % ', '.join(num(v) for v in h))
    for d, name in enumerate(names):
        y = Y[:, d]
        if len(names) > 1:
            doc.h('Coordinate %s' % name)
        lines = []

        def row(terms, rhs):
            tp = ' + '.join('%s M%d' % (num(c), k) for c, k in terms if c != 0)
            tl = ' + '.join('%s M_{%d}' % (num(c), k) for c, k in terms if c != 0)
            return M('%s = %s' % (tp, num(rhs)), '%s = %s' % (tl, num(rhs)))

        if ends is not None:
            lines.append(row([(2 * h[0], 0), (h[0], 1)],
                             6 * ((y[1] - y[0]) / h[0] - ends[0][d])))
        for i in range(1, n):
            rhs = 6 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1])
            lines.append(row([(h[i - 1], i - 1), (2 * (h[i - 1] + h[i]), i), (h[i], i + 1)], rhs))
        if ends is not None:
            lines.append(row([(h[-1], n - 1), (2 * h[-1], n)],
                             6 * (ends[1][d] - (y[n] - y[n - 1]) / h[-1])))
        if lines:
            doc.p('The tridiagonal system%s:' % ('' if ends is not None
                                                 else ' (with M0 = M%d = 0)' % n))
            doc.eq(*lines)
        m = Mv[:, d]
        doc.p('Its solution: ', M(', '.join('M%d = %s' % (i, num(v)) for i, v in enumerate(m)),
                                  ', '.join('M_{%d} = %s' % (i, num(v)) for i, v in enumerate(m))),
              '.')
        doc.p('The cubic on interval i is ',
              M('S_i(%s) = a_i + b_i (%s - %s_i) + c_i (%s - %s_i)^2 + d_i (%s - %s_i)^3'
                % ((var,) * 7)), ' with ',
              M('a_i = y_i, b_i = (y_{i+1} - y_i)/h_i - h_i (2 M_i + M_{i+1})/6, '
                'c_i = M_i/2, d_i = (M_{i+1} - M_i)/(6 h_i)',
                'a_i = y_i,\\ b_i = \\frac{y_{i+1} - y_i}{h_i} - \\frac{h_i(2M_i + '
                'M_{i+1})}{6},\\ c_i = \\frac{M_i}{2},\\ d_i = \\frac{M_{i+1} - M_i}{6h_i}'),
              ':')
        rows = []
        for i in range(n):
            b = (y[i + 1] - y[i]) / h[i] - h[i] * (2 * m[i] + m[i + 1]) / 6
            rows.append(['%s .. %s' % (num(x[i]), num(x[i + 1])), num(y[i]), num(b),
                         num(m[i] / 2), num((m[i + 1] - m[i]) / (6 * h[i]))])
        doc.table([M('interval'), M('a_i'), M('b_i'), M('c_i'), M('d_i')], rows)
    if len(ts):
        doc.h('Values')
        pts = np.atleast_2d(curve.eval(np.asarray(ts, float)))
        if func:
            doc.table([M('x'), M('y(x)')], [[num(t), num(p[1])] for t, p in zip(ts, pts)])
        else:
            doc.table([M('t')] + [M('%s(t)' % a) for a in names],
                      [[num(t)] + [num(v) for v in p] for t, p in zip(ts, pts)])


def _generic(doc, curve, ts, title, terms, note=None):
    """Blending values and weighted sums: ``terms(t)`` gives the names,
    values and points of the blending functions that act at ``t``."""
    P = np.asarray(curve.control_points())
    ax = _axes(P.shape[1])
    doc.h(title)
    doc.p('Control points: %s.' % _control_list(P, _names(len(P))[0]))
    if note:
        doc.p(note)
    if not len(ts):
        return
    doc.h('Substituting the parameter values')
    table = []
    for t in ts:
        names, wts, pts = terms(t)
        pt = np.atleast_1d(curve.eval(t))
        doc.p('At ', M('t = %s' % num(t)), ':')
        lines = [M(', '.join('%s = %s' % (nm[0], num(v)) for nm, v in zip(names, wts)),
                   ',\\ '.join('%s = %s' % (nm[1], num(v)) for nm, v in zip(names, wts)))]
        keep = [i for i, v in enumerate(wts) if abs(v) > 1e-15]
        for d, a in enumerate(ax):
            m, _ = _weighted_sum([wts[i] for i in keep], [pts[i][d] for i in keep],
                                 ('%s(%s)' % (a, num(t)),) * 2)
            lines.append(m)
        lines.append(M('P(%s) = %s' % (num(t), _pt(pt))))
        doc.eq(*lines)
        table.append([num(t)] + [num(v) for v in pt])
    doc.h('Points on the curve')
    doc.table([M('t')] + [M('%s(t)' % a) for a in ax], table)


def _all_points(curve, fn, label):
    """Blending terms over all control points (B-splines, rational)."""
    P = np.asarray(curve.control_points())

    def terms(t):
        w = np.atleast_2d(fn(t))[0]
        return ([('%s%d' % (label[0], i), '%s_{%d}' % (label[1], i)) for i in range(len(w))],
                w, P)
    return terms


def _beta_terms(curve):
    def terms(t):
        s = int(np.clip(np.floor(t), 0, len(curve.ctrl) - 4))
        w = np.atleast_2d(curve.blending(t))[0]
        names = [('b%d' % r, 'b_{%d}' % r) for r in (-2, -1, 0, 1)]
        return names, w, curve.ctrl[s:s + 4]
    return terms


def _tangent_rule(doc, curve):
    """How a cardinal / Kochanek-Bartels spline gets its Hermite tangents."""
    from .kochanek import KochanekBartels
    if isinstance(curve, KochanekBartels):
        doc.p('Kochanek-Bartels tangents at key P_i (tension T, continuity C, bias B):')
        doc.eq(M("D_out = (1-T)(1+B)(1-C)/2 (P_i - P_{i-1}) + (1-T)(1-B)(1+C)/2 (P_{i+1} - P_i)",
                 "D^{out}_i = \\tfrac{(1-T)(1+B)(1-C)}{2}(P_i - P_{i-1}) + "
                 "\\tfrac{(1-T)(1-B)(1+C)}{2}(P_{i+1} - P_i)"),
               M("D_in  = (1-T)(1+B)(1+C)/2 (P_i - P_{i-1}) + (1-T)(1-B)(1-C)/2 (P_{i+1} - P_i)",
                 "D^{in}_i = \\tfrac{(1-T)(1+B)(1+C)}{2}(P_i - P_{i-1}) + "
                 "\\tfrac{(1-T)(1-B)(1-C)}{2}(P_{i+1} - P_i)"))
    else:
        doc.p('Cardinal tangents at key P_i with tension c = %s: ' % num(curve.tension),
              M('T_i = (1 - c) (P_{i+1} - P_{i-1}) / 2',
                'T_i = (1-c)\\,\\frac{P_{i+1} - P_{i-1}}{2}'),
              ' (c = 0: Catmull-Rom).')
    doc.p('Ends: %s.' % {'duplicate': 'the missing neighbours of the end keys are the end keys',
                         'interior': 'the first and last points only steer the end tangents',
                         'closed': 'neighbours wrap around (closed loop)'}[curve.ends])
    rows = []
    for s in range(len(curve.points) - 1):
        rows.append([str(s), _pt(curve.points[s]), _pt(curve.out_tangents[s]),
                     _pt(curve.points[s + 1]), _pt(curve.in_tangents[s])])
    doc.table([M('segment'), M('P(0)'), M("P'(0)"), M('P(1)'), M("P'(1)")], rows)
    doc.p('Each segment is then the Hermite cubic of its end points and tangents:')


def _continuity(doc, curve, tolerance=1e-9):
    joints = curve.continuity(tolerance) if hasattr(curve, 'continuity') else []
    if not joints:
        return
    pb = curve
    doc.h('Continuity at the joints')
    doc.p('At a joint where segment A ends and segment B starts: C0 when the positions agree, '
          'C1 when also the first derivatives agree, C2 when also the second ones do; G1 '
          'when the unit tangents agree, G2 when also the curvature vectors agree.')
    for j in joints:
        seg = _joint_derivs(pb, j.index)
        lines = []
        if seg is not None:
            (a0, a1, a2), (b0, b1, b2) = seg
            lines += [M('A(%s) = %s,  B(%s) = %s' % (num(j.t), _pt(a0), num(j.t), _pt(b0))),
                      M("A'(%s) = %s,  B'(%s) = %s" % (num(j.t), _pt(a1), num(j.t), _pt(b1))),
                      M("A''(%s) = %s,  B''(%s) = %s" % (num(j.t), _pt(a2), num(j.t), _pt(b2)))]
        cs = 'C%d' % j.C if j.C >= 0 else 'not C0'
        gs = 'G%d' % j.G if j.G >= 0 else 'not G0'
        lines.append(M('joint %d at t = %s: %s, %s (gap %s, tangent angle %s deg, '
                       'curvature jump %s)'
                       % (j.index, num(j.t), cs, gs, num(j.gap), num(np.degrees(j.angle)),
                          num(j.curvature_jump))))
        doc.eq(*lines)


def _joint_derivs(curve, k):
    """Derivatives (global parameter) at the end of segment k and the start
    of segment k+1 (wrapping for closed curves)."""
    if hasattr(curve, 'end_derivatives'):
        st, en = curve.end_derivatives()
    elif hasattr(curve, 'to_rational_beziers'):
        st, en = curve.to_rational_beziers().end_derivatives()
    else:
        pb = curve.to_beziers()
        ds = [pb] + [pb.deriv(i) for i in (1, 2)]
        st = np.stack([d.ctrl[:, 0] for d in ds], 1)
        en = np.stack([d.ctrl[:, -1] for d in ds], 1)
    S = len(st)
    return en[k], st[(k + 1) % S]


def explain(curve, params: Sequence[float] = (), fmt: str = 'plain', tangent: bool = False,
            continuity: bool = True) -> str:
    """The worked solution for ``curve`` at the parameters ``params``.

    Parameters
    ----------
    curve : a curve of :mod:`raster.curves`
    params : sequence of float
        Parameter values to substitute (x values for a function spline).
    fmt : {'plain', 'markdown', 'latex'}
    tangent : bool
        Also derive the tangents (Bezier curves).
    continuity : bool
        Add the joint analysis when the curve has joints.

    Returns
    -------
    str

    Raises
    ------
    CurveError
        Unknown format, parameters outside the domain.
    """
    from .bezier import Bezier
    from .hermite import HermiteSpline
    from .natural import FunctionSpline, NaturalSpline
    from .cardinal import CardinalSpline
    from .kochanek import KochanekBartels
    from .bspline import BSpline
    from .beta import BetaSpline
    from .rational import RationalBezier
    from .nurbs import NURBS
    if fmt not in FORMATS:
        raise CurveError('format must be one of %s, got %r' % (', '.join(FORMATS), fmt))
    ts = [float(t) for t in np.asarray(params, dtype=np.float64).reshape(-1)]
    if ts:
        curve.eval(np.asarray(ts))                 # domain errors first
    doc = Doc()
    if isinstance(curve, Bezier):
        _bezier(doc, curve, ts, tangent)
    elif isinstance(curve, (CardinalSpline, KochanekBartels)):
        doc.h('%s spline through %d keys' % (
            'Kochanek-Bartels' if isinstance(curve, KochanekBartels) else 'Cardinal',
            len(curve.points)))
        _tangent_rule(doc, curve)
        _hermite(doc, curve, ts, derive=False)
    elif isinstance(curve, HermiteSpline):
        _hermite(doc, curve, ts)
    elif isinstance(curve, (FunctionSpline, NaturalSpline)):
        _natural(doc, curve, ts)
    elif isinstance(curve, BSpline):
        _generic(doc, curve, ts, 'B-spline of degree %d' % curve.degree,
                 _all_points(curve, curve.basis, ('N', 'N')),
                 'Knots %s; C(t) = sum N_i,%d(t) P_i with the Cox-de Boor basis functions.'
                 % (', '.join(num(k) for k in curve.knots), curve.degree))
    elif isinstance(curve, BetaSpline):
        _generic(doc, curve, ts, 'Beta-spline (beta1 = %s, beta2 = %s)'
                 % (num(curve.beta1), num(curve.beta2)), _beta_terms(curve),
                 'Segment s = floor(t) blends V_s .. V_s+3 with b-2 .. b1 at u = t - s.')
    elif isinstance(curve, RationalBezier):
        _generic(doc, curve, ts, 'Rational Bezier curve of degree %d' % curve.degree,
                 _all_points(curve, curve.blending, ('R', 'R')),
                 'Weights %s; R_i(t) = w_i B_%d,i(t) / sum_j w_j B_%d,j(t).'
                 % (', '.join(num(w) for w in curve.weights), curve.degree, curve.degree))
    elif isinstance(curve, NURBS):
        _generic(doc, curve, ts, 'NURBS of degree %d' % curve.degree,
                 _all_points(curve, curve.basis, ('R', 'R')),
                 'Weights %s, knots %s; R_i(t) = w_i N_i(t) / sum_j w_j N_j(t).'
                 % (', '.join(num(w) for w in curve.control_weights()),
                    ', '.join(num(k) for k in curve.knots)))
    else:
        raise CurveError('no explanation for %s' % type(curve).__name__)
    if continuity:
        _continuity(doc, curve)
    return doc.render(fmt)

