"""``curve``: evaluate, tabulate and plot parametric curves from the command
line.

Examples::

    curve bezier "1,1 2,3 4,3 6,4" --at 0,0.25,0.5,0.75,1
    curve bezier "1,1 2,3 4,3 6,4" --step 0.2 --explain --plot p.png --plot-blend
    curve bezier "1,1 2,3 4,3 6,4" --step 0.2 --tangent --json
    curve hermite "0,0 1,0" --tangents "0,3 0,-3" --poly
    curve catmull-rom "0,0 1,2 3,2 4,0" --continuity --plot cr.png
    curve kochanek-bartels "0,0 1,2 3,2 4,0" --tension 0.2 --continuity 0.5 --bias 0
    curve bspline "0,0 1,2 3,2 4,0 5,1" --degree 2 --knots 0,0,0,1,2,3,3,3 --at 0.5,2.5
    curve beta "0,0 1,2 3,2 4,0 5,1" --bias 2 --tension 1 --blend
    curve natural "0,0 1,1 2,0 3,1" --function --at 0.5,1.5
    curve rational-bezier "1,0 1,1 0,1" --weights 1,0.70710678,1 --at 0.5
    curve nurbs "0,0 1,2 3,2 4,0 5,1" --weights 1,2,1,2,1 --degree 2 --knots 0,0,0,1,3,4,4,4
    curve arc "0,0" --radius 2 --angles 0,90 --at-angle 30,60
    curve surface "0,0,0 1,0,1 2,0,0 ; 0,1,1 1,1,2 2,1,1 ; 0,2,0 1,2,1 2,2,0" --at "0.5,0.5;0,1"

``surface`` takes a control net: rows separated by ``;`` (row ``i`` runs
along ``u``, the points of a row along ``v``), or a JSON file with
``{"points": [[[x, y, z], ...], ...], "weights": ..., "degree": [p, q],
"knots": [[...], [...]]}``.  The degrees come from the net (a Bezier
patch) unless ``--degree p[,q]`` or ``--knots "u knots;v knots"`` make it
a B-spline surface; ``--weights "w w ; w w"`` (rows like the net) make it
rational.
Points are separated by spaces (or semicolons); coordinates by commas; all
points have 2 or 3 coordinates (3-D curves are plotted projected onto x, y).
Without ``--at`` or ``--step`` the domain is sampled at 11 even steps.

``--continuity`` without a value reports the continuity at every joint; for
``kochanek-bartels`` a value (``--continuity 0.5``) sets the KB continuity
parameter instead (use ``--joints`` for the report).

Usage and input errors print one line on stderr and exit with status 2.
"""

import json
import math
import os
import re
import sys

import numpy as np

from raster_cli.curve_args import (UsageError, Parser as _Parser, number as _number,
                                   parse_numbers, parse_points, plot_size)
from raster_cli.curve_surface import run_surface

__all__ = ['main', 'build_parser', 'build_curve', 'parse_numbers', 'parse_points', 'UsageError',
           'FAMILIES']
from ._common import add_version

FAMILIES = ('bezier', 'hermite', 'cardinal', 'catmull-rom', 'kochanek-bartels', 'bspline',
            'beta', 'natural', 'rational-bezier', 'nurbs', 'arc', 'surface')


def _per_key(text, what):
    v = parse_numbers(text, what)
    return v[0] if len(v) == 1 else v


def build_parser():
    p = _Parser(prog='curve', description='Evaluate, explain and plot parametric curves '
                '(Bezier, Hermite, cardinal, Catmull-Rom, Kochanek-Bartels, B-spline, '
                'Beta-spline, natural cubic spline, rational Bezier, NURBS, circle and ellipse '
                'arcs) and surfaces (Bezier, B-spline, NURBS).')
    p.add_argument('family', choices=FAMILIES, help='curve family')
    p.add_argument('points', help='control points / keys, e.g. "1,1 2,3 4,3 6,4"')
    g = p.add_argument_group('sampling')
    g.add_argument('--at', help='comma-separated parameter values (x values with --function)')
    g.add_argument('--step', help='sample the domain evenly with this step')
    g.add_argument('--at-angle', help='arc: parametric angles in degrees, comma-separated')
    o = p.add_argument_group('output')
    o.add_argument('--poly', action='store_true', help='print the polynomial form')
    o.add_argument('--tangent', action='store_true', help='add tangents and slopes dy/dx')
    o.add_argument('--blend', action='store_true', help='print blending-function values')
    o.add_argument('--json', action='store_true', help='print JSON instead of tables')
    o.add_argument('--explain', action='store_true',
                   help='print the worked solution (derivation, substitution, table)')
    o.add_argument('--format', default='plain', choices=('plain', 'markdown', 'latex'),
                   help='format of --explain (default plain)')
    o.add_argument('--plot', metavar='OUT', help='draw the curve to OUT.png or OUT.svg')
    o.add_argument('--size', default='640', help='plot width in pixels, 100-4000 (default 640)')
    o.add_argument('--plot-blend', action='store_true',
                   help='add a panel with the blending functions over t')
    o.add_argument('--plot-tangents', action='store_true',
                   help='draw tangent arrows at the sample points')
    o.add_argument('--no-axes', action='store_true', help='plot without axes and grid')
    o.add_argument('--no-labels', action='store_true',
                   help='plot without coordinate labels')
    o.add_argument('--title', help='plot title')
    o.add_argument('--view', default='perspective', choices=('perspective', 'ortho', 'both'),
                   help='surface plot projection (default perspective)')
    o.add_argument('--azimuth', default='-60', help='surface plot: view azimuth in degrees')
    o.add_argument('--elevation', default='30', help='surface plot: view elevation in degrees')
    o.add_argument('--continuity', nargs='?', const=True, default=None,
                   help='report joint continuity (kochanek-bartels: with a value, the '
                   'continuity parameter)')
    o.add_argument('--joints', action='store_true', help='report joint continuity')
    o.add_argument('--tolerance', default='1e-9',
                   help='relative tolerance of the continuity report (default 1e-9)')
    s = p.add_argument_group('shape')
    s.add_argument('--tangents', help='hermite: end tangents "tx0,ty0 tx1,ty1" (one per point)')
    s.add_argument('--tension', help='cardinal, kochanek-bartels (per key allowed), '
                   'beta (beta2, default 0)')
    s.add_argument('--bias', help='kochanek-bartels (per key allowed), beta (beta1, default 1)')
    s.add_argument('--ends', default='duplicate', choices=('duplicate', 'interior', 'closed'),
                   help='cardinal/catmull-rom/kochanek-bartels end handling')
    s.add_argument('--degree', default=None, help='bspline/nurbs degree (default 3); surface: '
                   'p or p,q (a B-spline surface)')
    s.add_argument('--knots', help='bspline/nurbs knot vector k0,k1,... (default clamped '
                   'uniform on [0, 1]); surface: "u knots;v knots"')
    s.add_argument('--weights', help='rational-bezier/nurbs: weights w0,w1,...; surface: rows '
                   '"w w ; w w"')
    s.add_argument('--radius', help='arc: radius r, or semi-axes rx,ry (an ellipse)')
    s.add_argument('--angles', default=None, help='arc: start,sweep in degrees (default 0,360)')
    s.add_argument('--rotation', default=None, help='arc: ellipse rotation in degrees')
    s.add_argument('--closed', action='store_true', help='bspline/beta: closed (periodic) curve')
    s.add_argument('--function', action='store_true',
                   help='natural: points are (x, y) samples of a function y(x)')
    s.add_argument('--param', default='chord', choices=('uniform', 'chord', 'centripetal'),
                   help='natural (parametric): parameterization (default chord)')
    s.add_argument('--end-tangents', help='natural: clamped end tangents "a b" (slopes with '
                   '--function, vectors "tx0,ty0 tx1,ty1" otherwise)')
    add_version(p)
    return p


# -- building curves -----------------------------------------------------------
def _unused(args, allowed):
    names = {'tangents': '--tangents', 'tension': '--tension', 'bias': '--bias',
             'knots': '--knots', 'end_tangents': '--end-tangents', 'weights': '--weights',
             'radius': '--radius', 'angles': '--angles', 'rotation': '--rotation',
             'degree': '--degree', 'at_angle': '--at-angle'}
    for attr, flag in names.items():
        if getattr(args, attr) is not None and attr not in allowed:
            raise UsageError('%s does not apply to %s' % (flag, args.family))
    if args.continuity not in (None, True) and args.family != 'kochanek-bartels':
        raise UsageError('--continuity takes no value for %s' % args.family)


def _degree(text, default=3):
    if text is None:
        return default
    deg = _number(text, 'degree')
    if deg != int(deg) or deg < 0:
        raise UsageError('--degree must be a non-negative integer, got %r' % text)
    return int(deg)


def _weights(args, n):
    if args.weights is None:
        return None
    w = parse_numbers(args.weights, 'weight')
    if len(w) != n:
        raise UsageError('need one weight per control point (%d), got %d' % (n, len(w)))
    return w


def build_curve(args):
    """The curve object described by the parsed arguments."""
    from raster import curves as C
    fam = args.family
    pts = parse_points(args.points)
    if pts.shape[1] not in (2, 3):
        raise UsageError('points must have 2 or 3 coordinates, got %d' % pts.shape[1])
    if fam == 'bezier':
        _unused(args, ())
        if len(pts) < 2:
            raise UsageError('a Bezier curve needs at least 2 control points, got %d' % len(pts))
        return C.Bezier(pts)
    if fam == 'hermite':
        _unused(args, ('tangents',))
        if args.tangents is None:
            raise UsageError('hermite needs --tangents "tx0,ty0 tx1,ty1"')
        tans = parse_points(args.tangents, 'tangents')
        if tans.shape != pts.shape:
            raise UsageError('need one tangent per point (%d of dimension %d), got %d of %d'
                             % (len(pts), pts.shape[1], len(tans), tans.shape[1]))
        if len(pts) == 2:
            return C.Hermite(pts[0], pts[1], tans[0], tans[1])
        if len(pts) < 2:
            raise UsageError('hermite needs at least 2 points')
        return C.HermiteSpline(pts, tans[:-1], tans[1:])
    if fam in ('cardinal', 'catmull-rom'):
        _unused(args, ('tension',) if fam == 'cardinal' else ())
        tension = _number(args.tension, 'tension') if args.tension is not None else 0.0
        return C.CardinalSpline(pts, tension, args.ends)
    if fam == 'kochanek-bartels':
        _unused(args, ('tension', 'bias'))
        kw = {}
        if args.tension is not None:
            kw['tension'] = _per_key(args.tension, 'tension')
        if args.bias is not None:
            kw['bias'] = _per_key(args.bias, 'bias')
        if args.continuity not in (None, True):
            kw['continuity'] = _per_key(args.continuity, 'continuity')
        return C.KochanekBartels(pts, ends=args.ends, **kw)
    if fam == 'bspline':
        _unused(args, ('knots', 'degree'))
        knots = parse_numbers(args.knots, 'knot') if args.knots is not None else None
        return C.BSpline(pts, _degree(args.degree), knots, closed=args.closed)
    if fam == 'rational-bezier':
        _unused(args, ('weights',))
        if len(pts) < 2:
            raise UsageError('a rational Bezier curve needs at least 2 control points')
        w = _weights(args, len(pts))
        return C.RationalBezier(pts, w)
    if fam == 'nurbs':
        _unused(args, ('weights', 'knots', 'degree'))
        knots = parse_numbers(args.knots, 'knot') if args.knots is not None else None
        return C.NURBS(pts, _weights(args, len(pts)), _degree(args.degree), knots,
                       closed=args.closed)
    if fam == 'arc':
        _unused(args, ('radius', 'angles', 'rotation', 'at_angle'))
        if pts.shape != (1, 2):
            raise UsageError('arc takes one 2-D centre point "cx,cy"')
        if args.radius is None:
            raise UsageError('arc needs --radius r (or rx,ry)')
        r = parse_numbers(args.radius, 'radius')
        if len(r) not in (1, 2):
            raise UsageError('--radius takes r or rx,ry')
        ang = parse_numbers(args.angles, 'angle') if args.angles is not None else [0.0, 360.0]
        if len(ang) != 2:
            raise UsageError('--angles takes start,sweep in degrees')
        rot = _number(args.rotation, 'rotation') if args.rotation is not None else 0.0
        rx, ry = (r[0], r[0]) if len(r) == 1 else r
        return C.ellipse_arc(pts[0], rx, ry, math.radians(rot), math.radians(ang[0]),
                             math.radians(ang[1]))
    if fam == 'beta':
        _unused(args, ('tension', 'bias'))
        b1 = _number(args.bias, 'bias') if args.bias is not None else 1.0
        b2 = _number(args.tension, 'tension') if args.tension is not None else 0.0
        return C.BetaSpline(pts, b1, b2, closed=args.closed)
    # natural
    _unused(args, ('end_tangents',))
    if args.function:
        if pts.shape[1] != 2:
            raise UsageError('--function needs x,y samples')
        ends = None
        if args.end_tangents is not None:
            ends = parse_numbers(args.end_tangents, 'end slope')
            if len(ends) != 2:
                raise UsageError('--end-tangents needs two slopes with --function')
        return C.FunctionSpline(pts[:, 0], pts[:, 1], ends)
    ends = None
    if args.end_tangents is not None:
        ends = parse_points(args.end_tangents, 'end tangents')
        if ends.shape != (2, pts.shape[1]):
            raise UsageError('--end-tangents needs two vectors of dimension %d' % pts.shape[1])
    return C.NaturalSpline(pts, args.param, ends)


def sample_params(args, curve):
    lo, hi = curve.domain
    if args.at is not None and args.step is not None:
        raise UsageError('use either --at or --step')
    if args.at is not None:
        return np.array(parse_numbers(args.at, 'parameter')) + 0.0     # no -0
    if getattr(args, 'at_angle', None) is not None:
        if args.family != 'arc':
            raise UsageError('--at-angle applies to arc only')
        if args.step is not None or args.at is not None:
            raise UsageError('use one of --at, --step and --at-angle')
        ang = np.radians(parse_numbers(args.at_angle, 'angle'))
        return np.atleast_1d(curve.param_at_angle(ang))
    if args.step is not None:
        h = _number(args.step, 'step')
        if h <= 0:
            raise UsageError('--step must be positive')
        n = int(math.floor((hi - lo) / h + 1e-9)) + 1
        if n > 1_000_000:
            raise UsageError('--step %g gives too many samples (%d)' % (h, n))
        return lo + h * np.arange(n)
    return np.linspace(lo, hi, 11)


# -- derived data --------------------------------------------------------------
def blending(curve, t):
    """(names, (M, K) values) of the family's blending functions at t."""
    from raster import curves as C
    if isinstance(curve, C.Bezier):
        return ['B%d,%d' % (curve.degree, i) for i in range(curve.degree + 1)], curve.blending(t)
    if isinstance(curve, C.BSpline):
        N = len(curve.ctrl)
        return ['N%d,%d' % (i, curve.degree) for i in range(N)], curve.basis(t)
    if isinstance(curve, C.BetaSpline):
        return ['b-2', 'b-1', 'b0', 'b1'], curve.blending(t)
    if isinstance(curve, C.CardinalSpline):
        return ['P(i-1)', 'P(i)', 'P(i+1)', 'P(i+2)'], curve.blending(t)
    if isinstance(curve, C.HermiteSpline):
        lo, hi = curve.domain
        ta = np.asarray(t, dtype=np.float64)
        if np.any(ta < lo) or np.any(ta > hi):
            curve.eval(ta)          # raises the domain error
        u = ta - np.clip(np.floor(ta), 0, len(curve.points) - 2)
        return ['h00', 'h01', 'h10', 'h11'], C.hermite_blend(u)
    if isinstance(curve, C.RationalBezier):
        return ['R%d,%d' % (curve.degree, i) for i in range(curve.degree + 1)], curve.blending(t)
    if isinstance(curve, C.NURBS):
        return ['R%d,%d' % (i, curve.degree) for i in range(len(curve.control_weights()))], \
            curve.basis(t)
    raise UsageError('%s splines have no blending functions (global interpolation)'
                     % type(curve).__name__)


def _fmt_poly(coef, var='u'):
    terms = []
    for k, c in enumerate(coef):
        if abs(c) < 1e-13 * max(1.0, np.abs(coef).max()):
            continue
        mono = '' if k == 0 else (var if k == 1 else '%s^%d' % (var, k))
        mag = abs(c)
        num = '%.10g' % mag
        body = num if not mono else (mono if num == '1' else '%s*%s' % (num, mono))
        terms.append(('-' if c < 0 else '+', body))
    if not terms:
        return '0'
    out = ('-' if terms[0][0] == '-' else '') + terms[0][1]
    for sgn, body in terms[1:]:
        out += ' %s %s' % (sgn, body)
    return out


def _rational_chain(curve):
    """The PiecewiseRational form of a rational family, or None."""
    from raster import curves as C
    if isinstance(curve, C.RationalBezier):
        return curve.to_chain()
    if isinstance(curve, C.NURBS):
        return curve.to_rational_beziers()
    if isinstance(curve, C.PiecewiseRational):
        return curve
    return None


def polynomials(curve):
    """List of (segment, (a, b), (n+1, D) power coefficients in the local
    parameter u = (t - a) / (b - a)); for rational curves the coefficients
    of the numerator and, as the last column, the denominator."""
    from raster.curves import bernstein_matrix
    rc = _rational_chain(curve)
    if rc is not None:
        h = rc.homogeneous()
        m = bernstein_matrix(h.degree)
        return [(s, (float(h.breaks[s]), float(h.breaks[s + 1])), m @ h.ctrl[s])
                for s in range(len(h))]
    pb = curve.to_beziers()
    m = bernstein_matrix(pb.degree)
    return [(s, (float(pb.breaks[s]), float(pb.breaks[s + 1])), m @ pb.ctrl[s])
            for s in range(len(pb))]


def _jnum(v):
    v = float(v)
    return v if math.isfinite(v) else None


def compute(args, curve):
    from raster.curves import FunctionSpline
    t = sample_params(args, curve)
    pts = np.atleast_2d(curve.eval(t))
    res = {'t': t, 'points': pts}
    if args.tangent:
        res['tangents'] = np.atleast_2d(curve.tangent(t))
        d = res['tangents']
        with np.errstate(divide='ignore', invalid='ignore'):
            res['slopes'] = d[:, 1] / d[:, 0]
    if args.blend:
        res['blend_names'], res['blend'] = blending(curve, t)
    if args.poly:
        res['poly'] = polynomials(curve)
    if args.joints or args.continuity is True:
        tol = _number(args.tolerance, 'tolerance')
        res['joints'] = curve.continuity(tol)
    res['function'] = isinstance(curve, FunctionSpline)
    if args.explain:
        from raster.curves.explain import explain
        res['explanation'] = explain(curve, t, args.format, tangent=args.tangent)
    return res


def _pieces(curve):
    rc = _rational_chain(curve)
    return rc if rc is not None else curve.to_beziers()


def describe(args, curve):
    pb = _pieces(curve)
    lo, hi = curve.domain
    pts = curve.control_points() if _rational_chain(curve) is not None else (
        curve.points if hasattr(curve, 'points') else curve.ctrl)
    kind = 'rational Bezier' if _rational_chain(curve) is not None else 'Bezier'
    return ('%s: %d points (%d-D), %d %s segment%s of degree %d, %s in [%g, %g]'
            % (args.family, len(pts), pts.shape[1], len(pb), kind, '' if len(pb) == 1 else 's',
               pb.degree, 'x' if args.function and args.family == 'natural' else 't', lo, hi))


def print_text(args, curve, res, out):
    from raster.curves import format_joints
    print(describe(args, curve), file=out)
    D = res['points'].shape[1]
    var = 'x' if res['function'] else 't'
    axes = ['x', 'y', 'z'][:D]
    cols = [var] + ([] if res['function'] else axes)
    if res['function']:
        cols.append('y')
    if args.tangent:
        cols += ['d' + a for a in axes] + ['dy/dx']
    if args.blend:
        cols += res['blend_names']
    print(' '.join('%12s' % c for c in cols), file=out)
    for m, tv in enumerate(res['t']):
        row = [tv] + (res['points'][m].tolist() if not res['function']
                      else [res['points'][m, 1]])
        if args.tangent:
            row += res['tangents'][m].tolist() + [res['slopes'][m]]
        if args.blend:
            row += res['blend'][m].tolist()
        print(' '.join('%12.6g' % v for v in row), file=out)
    if args.poly:
        print('polynomial form (u = (t - a) / (b - a) on each segment [a, b]):'
              if len(res['poly']) > 1 or res['poly'][0][1] != (0.0, 1.0)
              else 'polynomial form (u = t):', file=out)
        for s, (a, b), coef in res['poly']:
            if len(res['poly']) > 1:
                print('segment %d, [%g, %g]:' % (s, a, b), file=out)
            rational = _rational_chain(curve) is not None
            names = ['%s*w' % a for a in axes] + ['w'] if rational else axes
            for d, name in enumerate(names[:coef.shape[1]]):
                print('  %s(u) = %s' % (name, _fmt_poly(coef[:, d])), file=out)
            if rational:
                print('  (the point is (x*w, y*w, ...) / w)', file=out)
    if 'joints' in res:
        print(format_joints(res['joints']), file=out)


def to_json(args, curve, res):
    rc = _rational_chain(curve)
    pts = curve.control_points() if rc is not None else (
        curve.points if hasattr(curve, 'points') else curve.ctrl)
    lo, hi = curve.domain
    pb = _pieces(curve)
    obj = {'curve': args.family, 'dimension': int(res['points'].shape[1]),
           'degree': int(getattr(curve, 'degree', pb.degree)), 'segments': len(pb),
           'domain': [lo, hi], 'control_points': pts.tolist(), 'points': []}
    if rc is not None:
        from raster import curves as C
        if isinstance(curve, C.NURBS):
            obj['weights'] = curve.control_weights().tolist()
            obj['knots'] = curve.knots.tolist()
        elif isinstance(curve, C.RationalBezier):
            obj['weights'] = curve.weights.tolist()
        else:
            obj['weights'] = curve.weights.tolist()
            obj['control_points'] = curve.ctrl.tolist()
    for m, tv in enumerate(res['t']):
        item = {'t': float(tv), 'point': res['points'][m].tolist()}
        if args.tangent:
            item['tangent'] = res['tangents'][m].tolist()
            item['slope'] = _jnum(res['slopes'][m])
        if args.blend:
            item['blend'] = res['blend'][m].tolist()
        obj['points'].append(item)
    if args.blend:
        obj['blend_names'] = res['blend_names']
    if args.poly:
        if rc is not None:
            obj['polynomial'] = [{'segment': s, 'interval': [a, b],
                                  'numerator': coef[:, :-1].T.tolist(),
                                  'denominator': coef[:, -1].tolist()}
                                 for s, (a, b), coef in res['poly']]
        else:
            obj['polynomial'] = [{'segment': s, 'interval': [a, b],
                                  'coefficients': coef.T.tolist()}
                                 for s, (a, b), coef in res['poly']]
    if 'explanation' in res:
        obj['explanation'] = res['explanation']
    if 'joints' in res:
        obj['joints'] = [{'index': j.index, 't': j.t, 'C': j.C, 'G': j.G, 'gap': j.gap,
                          'angle': _jnum(j.angle), 'curvature_jump': _jnum(j.curvature_jump)}
                         for j in res['joints']]
    if args.plot:
        obj['plot'] = args.plot
    # one key per line, values compact
    return '{\n' + ',\n'.join(' %s: %s' % (json.dumps(k), json.dumps(v))
                              for k, v in obj.items()) + '\n}'


def _no_surface_options(args):
    if args.view != 'perspective' or args.azimuth != '-60' or args.elevation != '30':
        raise UsageError('--view, --azimuth and --elevation apply to surface only')
    if args.plot_blend and not args.plot:
        raise UsageError('--plot-blend needs --plot')


def main(argv=None):
    """Entry point; returns the exit status (0 ok, 1 output failure, 2 bad
    input)."""
    from raster.errors import RasterError
    from ._common import install_warnings
    install_warnings('curve')
    parser = build_parser()
    if argv is None:
        argv = sys.argv[1:]
    # values such as "-1,2 3,4" or "-0.5,1" must not be taken for options:
    # a leading space keeps argparse from seeing a dash (parsing strips it)
    argv = [' ' + a if re.match(r'-[\d.]', a) else a for a in argv]
    try:
        args = parser.parse_args(argv)
        if args.family == 'surface':
            run_surface(args, sys.stdout)
            return 0
        _no_surface_options(args)
        curve = build_curve(args)
        res = compute(args, curve)
        if args.plot:
            from raster.curves.plot import plot_curve
            plot_curve(curve, args.plot, params=res['t'], width=plot_size(args),
                       label_var='x' if res['function'] else 't', axes=not args.no_axes,
                       labels=not args.no_labels, tangents=args.plot_tangents,
                       blend=args.plot_blend, title=args.title)
        if args.json:
            print(to_json(args, curve, res))
        elif args.explain:
            sys.stdout.write(res['explanation'])
        else:
            print_text(args, curve, res, sys.stdout)
    except (UsageError, RasterError) as e:
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        print('curve: error: %s' % msg, file=sys.stderr)
        return 2
    except BrokenPipeError:             # e.g. piped into head: stop quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except OSError as e:
        print('curve: error: %s' % e, file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
