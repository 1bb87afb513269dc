"""``curve surface``: points and unit normals of Bezier, B-spline and NURBS
surfaces, and surface plots (part of :mod:`raster_cli.curve`).

The net is rows separated by ``;`` (row ``i`` along ``u``, the points of a
row along ``v``): ``"x,y,z x,y,z ; x,y,z x,y,z"``, or the name of a JSON
file holding ``{"points": [[[x, y, z], ...], ...]}`` with optional
``"weights"`` (rows like the points), ``"degree"`` (``p`` or ``[p, q]``)
and ``"knots"`` (``[u knots, v knots]``).  Without ``--degree``,
``--knots`` or weights the net is one Bezier patch of degree ``(rows - 1,
columns - 1)``.
"""

import json
import math
import os
import re

import numpy as np

from raster_cli.curve_args import UsageError, number, parse_numbers, parse_points, plot_size

#: Largest JSON net file read (bytes).
MAX_NET_FILE = 16 << 20


def _rows(text, what):
    rows = [r for r in text.split(';') if r.strip()]
    if not rows:
        raise UsageError('no %s given' % what)
    return rows


def parse_net(text):
    """'x,y,z x,y,z ; x,y,z x,y,z' -> (rows, cols, D) float64."""
    rows = [parse_points(r, what) for r, what in ((r, 'net points') for r in _rows(text, 'net'))]
    if len({r.shape for r in rows}) != 1:
        raise UsageError('every row of the net needs the same number of points of the same '
                         'dimension')
    net = np.stack(rows)
    if net.shape[2] not in (2, 3):
        raise UsageError('net points must have 2 or 3 coordinates, got %d' % net.shape[2])
    return net


def parse_weights(text, shape):
    rows = [parse_numbers(r, 'weight') for r in _rows(text, 'weights')]
    w = np.array(rows, dtype=np.float64) if len({len(r) for r in rows}) == 1 else None
    if w is None or w.shape != shape:
        raise UsageError('--weights needs %d rows of %d weights (like the net)' % shape)
    return w


def parse_uv(text):
    """'0.5,0.5;0,1' -> (M, 2) float64."""
    out = []
    for pair in _rows(text, '(u, v) pairs'):
        v = parse_numbers(pair, 'parameter')
        if len(v) != 2:
            raise UsageError('--at takes u,v pairs separated by ";", got %r' % pair.strip())
        out.append(v)
    return np.array(out) + 0.0


def _load_json(path):
    try:
        if os.path.getsize(path) > MAX_NET_FILE:
            raise UsageError('net file %s is larger than %d bytes' % (path, MAX_NET_FILE))
        with open(path, encoding='utf-8') as f:
            obj = json.load(f)
    except json.JSONDecodeError as e:
        raise UsageError('cannot read %s: %s' % (path, str(e).splitlines()[0])) from None
    if not isinstance(obj, dict) or 'points' not in obj:
        raise UsageError('the JSON net needs an object with "points"')
    try:
        net = np.array(obj['points'], dtype=np.float64)
    except (TypeError, ValueError):
        raise UsageError('"points" must be rows of points of equal length') from None
    if net.ndim != 3 or net.shape[2] not in (2, 3):
        raise UsageError('"points" must be rows of 2-D or 3-D points')
    return net, obj


def build_surface(args):
    """The surface described by the arguments."""
    from raster import curves as C
    from raster.curves.surface import NURBSSurface
    text = args.points.strip()
    spec = {}
    if text.lower().endswith('.json') or (os.path.isfile(text) and not re.search(r'\d,', text)):
        net, spec = _load_json(text)
    else:
        net = parse_net(text)
    for flag in ('tangents', 'tension', 'bias', 'end_tangents', 'radius', 'angles', 'rotation',
                 'at_angle'):
        if getattr(args, flag, None) is not None:
            raise UsageError('--%s does not apply to surface' % flag.replace('_', '-'))
    if args.step is not None:
        raise UsageError('--step does not apply to surface; use --at "u,v;u,v"')
    weights = spec.get('weights')
    if args.weights is not None:
        weights = parse_weights(args.weights, net.shape[:2])
    degree = spec.get('degree')
    if args.degree is not None:
        d = parse_numbers(args.degree, 'degree')
        if len(d) not in (1, 2) or any(x != int(x) or x < 0 for x in d):
            raise UsageError('--degree takes p or p,q (non-negative integers)')
        degree = [int(x) for x in d]
    knots = spec.get('knots')
    if args.knots is not None:
        parts = args.knots.split(';')
        if len(parts) != 2:
            raise UsageError('--knots takes "u knots;v knots" for a surface')
        knots = [parse_numbers(k, 'knot') if k.strip() else None for k in parts]
    if degree is None and knots is None and weights is None:
        return C.BezierSurface(net), 'bezier'
    if degree is None:
        degree = (min(3, net.shape[0] - 1), min(3, net.shape[1] - 1)) if knots is None else None
        if degree is None:
            degree = tuple(len(k) - n - 1 if k is not None else min(3, n - 1)
                           for k, n in zip(knots, net.shape[:2]))
    if isinstance(degree, int) or (isinstance(degree, (list, tuple)) and len(degree) == 1):
        degree = int(degree[0] if isinstance(degree, (list, tuple)) else degree)
        degree = (degree, degree)
    knots = tuple(knots) if knots is not None else (None, None)
    if weights is not None:
        return NURBSSurface(net, tuple(degree), knots, np.asarray(weights, float)), 'nurbs'
    return C.BSplineSurface(net, tuple(degree), knots), 'bspline'


def run_surface(args, out):
    """Evaluate (and plot) a surface; prints a table or JSON."""
    surface, kind = build_surface(args)
    for flag, name in ((args.poly, '--poly'), (args.blend, '--blend'), (args.explain, '--explain'),
                       (args.plot_blend, '--plot-blend'), (args.plot_tangents, '--plot-tangents'),
                       (args.closed, '--closed'), (args.function, '--function')):
        if flag:
            raise UsageError('%s does not apply to surface' % name)
    if args.continuity not in (None, True) or args.continuity is True or args.joints:
        raise UsageError('--continuity does not apply to surface')
    (u0, u1), (v0, v1) = surface.domain
    if args.at is not None:
        uv = parse_uv(args.at)
    else:
        g = np.array([0.0, 0.5, 1.0])
        uv = np.stack(np.meshgrid(u0 + g * (u1 - u0), v0 + g * (v1 - v0), indexing='ij'),
                      -1).reshape(-1, 2)
    pts = np.atleast_2d(surface.eval(uv[:, 0], uv[:, 1]))
    normals = (np.atleast_2d(surface.normal(uv[:, 0], uv[:, 1])) if surface.dim == 3
               else np.full((len(uv), 3), np.nan))
    tangents = None
    if args.tangent:
        d = surface.derivatives(uv[:, 0], uv[:, 1], 1)
        tangents = (d[:, 1, 0], d[:, 0, 1])
    if args.plot:
        from raster.curves.surfaceplot import plot_surface
        az = number(args.azimuth, 'azimuth')
        el = number(args.elevation, 'elevation')
        plot_surface(surface, args.plot, params=uv, width=plot_size(args), view=args.view,
                     azimuth=az, elevation=el, title=args.title)
    if args.json:
        obj = {'surface': kind, 'dimension': surface.dim,
               'degree': list(surface.degree), 'domain': [[u0, u1], [v0, v1]],
               'control_net': surface.control_net().tolist()}
        if kind == 'nurbs':
            obj['weights'] = surface.weights.tolist()
        if kind != 'bezier':
            obj['knots'] = [k.tolist() for k in surface.knots]
        items = []
        for k, ((u, v), p, n) in enumerate(zip(uv, pts, normals)):
            item = {'u': float(u), 'v': float(v), 'point': p.tolist(),
                    'normal': [None if not math.isfinite(x) else float(x) for x in n]
                    if surface.dim == 3 else None}
            if tangents is not None:
                item['du'] = tangents[0][k].tolist()
                item['dv'] = tangents[1][k].tolist()
            items.append(item)
        obj['points'] = items
        if args.plot:
            obj['plot'] = args.plot
        print('{\n' + ',\n'.join(' %s: %s' % (json.dumps(k), json.dumps(v))
                                 for k, v in obj.items()) + '\n}', file=out)
        return
    D = surface.dim
    print('surface: %s, %d x %d control points (%d-D), degree %d x %d, u in [%g, %g], '
          'v in [%g, %g]' % (kind, surface.net.shape[0], surface.net.shape[1], D,
                             surface.degree[0], surface.degree[1], u0, u1, v0, v1), file=out)
    axes = ['x', 'y', 'z'][:D]
    cols = ['u', 'v'] + axes + (['nx', 'ny', 'nz'] if D == 3 else [])
    if tangents is not None:
        cols += ['Su_' + a for a in axes] + ['Sv_' + a for a in axes]
    print(' '.join('%12s' % c for c in cols), file=out)
    for k, ((u, v), p, n) in enumerate(zip(uv, pts, normals)):
        row = [u, v] + p.tolist() + (n.tolist() if D == 3 else [])
        if tangents is not None:
            row += tangents[0][k].tolist() + tangents[1][k].tolist()
        print(' '.join('%12.6g' % x for x in row), file=out)
