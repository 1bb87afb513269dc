"""The package's import graph: layers, no circles, no private names across
modules.

Every module of ``raster/`` and ``cli/`` (installed as ``raster_cli``) is
read with :mod:`ast`; imports inside functions count like any other.  The
layers (HACKING.md) are, from the bottom: the base (errors, limits), the
geometry kernel, the pixel layer, the tree, fonts, the parser and the
renderer (side by side, never importing each other), the curve toolkit,
and on top the front doors (``raster``, ``raster.svg``, ``raster.testing``)
and the commands.
"""

import ast
import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGES = {'raster': os.path.join(ROOT, 'raster'), 'raster_cli': os.path.join(ROOT, 'cli')}

# layer of a module (by longest matching prefix) -> layers it may import
LAYER_OF = {
    'raster.errors': 'base', 'raster.limits': 'base', 'raster.sources': 'base',
    'raster._regex': 'base',
    'raster.geometry': 'geometry',
    'raster.pixels': 'pixels',
    'raster.tree': 'tree',
    'raster.fonts': 'fonts',
    'raster.parser': 'parser',
    'raster.renderer': 'renderer',
    'raster.curves': 'curves',
    'raster.svg': 'front', 'raster.testing': 'front', 'raster.compat': 'front',
    'raster.pillow': 'front', 'raster': 'front',
    'raster_cli': 'commands',
}
ALLOWED = {
    'base': {'base'},
    'geometry': {'base', 'geometry'},
    'pixels': {'base', 'geometry', 'pixels'},
    'tree': {'base', 'geometry', 'tree'},
    'fonts': {'base', 'geometry', 'fonts'},
    'parser': {'base', 'geometry', 'tree', 'fonts', 'parser'},
    'renderer': {'base', 'geometry', 'pixels', 'tree', 'renderer'},
    'curves': {'base', 'geometry', 'pixels', 'curves'},
    'front': {'base', 'geometry', 'pixels', 'tree', 'fonts', 'parser', 'renderer', 'curves',
              'front'},
    'commands': {'base', 'geometry', 'pixels', 'tree', 'fonts', 'parser', 'renderer', 'curves',
                 'front', 'commands'},
}


def layer(module):
    best = None
    for prefix in LAYER_OF:
        if module == prefix or module.startswith(prefix + '.'):
            if best is None or len(prefix) > len(best):
                best = prefix
    return LAYER_OF[best] if best is not None else None


def modules():
    """``{module name: path}`` of every module of the two packages."""
    out = {}
    for pkg, base in PACKAGES.items():
        for d, _, files in os.walk(base):
            if '__pycache__' in d:
                continue
            for f in files:
                if not f.endswith('.py'):
                    continue
                rel = os.path.relpath(os.path.join(d, f), base)[:-3].split(os.sep)
                if rel[-1] == '__init__':
                    rel = rel[:-1]
                out['.'.join([pkg] + rel)] = os.path.join(d, f)
    return out


MODULES = modules()


def _is_package(name):
    return MODULES.get(name, '').endswith('__init__.py')


def _resolve(module, node):
    """The absolute module an ImportFrom names (relative levels resolved)."""
    if not node.level:
        return node.module
    base = module.split('.')
    if not _is_package(module):
        base = base[:-1]
    base = base[:len(base) - (node.level - 1)]
    return '.'.join(base + ([node.module] if node.module else []))


def imports(module, path):
    """``[(target module, imported name or None, line)]`` of a module: each
    ``import a.b`` gives ``('a.b', None)``; ``from m import x`` gives
    ``('m.x', None)`` when ``m.x`` is a module, else ``('m', 'x')``.  Also
    reports ``alias._name`` attribute reads of imported modules as
    ``(module, '_name')``."""
    tree = ast.parse(open(path, encoding='utf-8').read(), path)
    out = []
    aliases = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                out.append((a.name, None, node.lineno))
                aliases[a.asname or a.name.split('.')[0]] = a.name if a.asname else \
                    a.name.split('.')[0]
        elif isinstance(node, ast.ImportFrom):
            src = _resolve(module, node)
            for a in node.names:
                full = src + '.' + a.name
                if full in MODULES:
                    out.append((full, None, node.lineno))
                    aliases[a.asname or a.name] = full
                else:
                    out.append((src, a.name, node.lineno))
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                and node.value.id in aliases and node.attr.startswith('_')
                and not node.attr.startswith('__')):
            out.append((aliases[node.value.id], node.attr, node.lineno))
    return out


def _ours(name):
    return name in MODULES or any(name.startswith(p + '.') or name == p for p in PACKAGES)


def graph():
    """Module -> set of our modules it imports."""
    g = {}
    for m, p in MODULES.items():
        deps = set()
        for target, _, _ in imports(m, p):
            if target in MODULES and target != m:
                deps.add(target)
        g[m] = deps
    return g


def _cycles(g):
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in g.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))
    for v in sorted(g):
        if v not in index:
            visit(v)
    return out


def test_the_packages_are_read():
    assert 'raster.parser.convert' in MODULES and 'raster_cli.rasterize' in MODULES
    assert len(MODULES) > 40


def test_no_import_circles():
    assert _cycles(graph()) == []


def test_circle_detection_finds_a_circle():
    """The detector itself: a two-module circle and a three-module one."""
    assert _cycles({'a': {'b'}, 'b': {'a'}, 'c': {'a'}}) == [['a', 'b']]
    assert _cycles({'a': {'b'}, 'b': {'c'}, 'c': {'a'}}) == [['a', 'b', 'c']]
    assert _cycles({'a': {'b'}, 'b': set()}) == []


def test_no_private_names_across_modules():
    """No module imports (or reads as an attribute) a ``_private`` name of
    another module.  Package-internal helper *modules* whose file name
    starts with an underscore (``raster_cli._common``) may be imported by
    modules of their package."""
    bad = []
    for m, p in MODULES.items():
        for target, name, line in imports(m, p):
            if not _ours(target):
                continue
            if name is not None and name.startswith('_') and not name.startswith('__'):
                bad.append('%s:%d imports %s.%s' % (os.path.relpath(p, ROOT), line, target, name))
            elif name is None and target in MODULES:
                last = target.rsplit('.', 1)[-1]
                pkg = target.rsplit('.', 1)[0]
                if last.startswith('_') and not (m == pkg or m.startswith(pkg + '.')):
                    bad.append('%s:%d imports private module %s'
                               % (os.path.relpath(p, ROOT), line, target))
    assert bad == []


def test_layers():
    """Each module imports only its own layer and the layers below it; in
    particular the renderer never imports the parser and the parser never
    imports the renderer."""
    bad = []
    for m, p in MODULES.items():
        lm = layer(m)
        assert lm is not None, m
        for target, _, line in imports(m, p):
            if target not in MODULES:
                continue
            lt = layer(target)
            if lt not in ALLOWED[lm]:
                bad.append('%s:%d (%s) imports %s (%s)' % (os.path.relpath(p, ROOT), line, lm,
                                                           target, lt))
    assert bad == []


@pytest.mark.parametrize('name', ['flatten', 'bbox', 'render', 'render_image', 'load_svg',
                                  'parse_path', 'svg2png'])
def test_no_module_shadows_a_public_function(name):
    """``raster.flatten``, ``raster.bbox`` ... are functions; no module
    ``raster/<name>.py`` or ``raster/svg/<name>.py`` may share the name."""
    assert 'raster.' + name not in MODULES
    assert 'raster.svg.' + name not in MODULES
