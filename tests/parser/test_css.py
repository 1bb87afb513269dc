"""Tests of raster.parser.css (parser, selectors, cascade) and
raster.parser.properties."""

import glob
import os

import pytest
from hypothesis import given, settings, strategies as st
from lxml import etree

from raster.errors import RasterError
from raster.parser.css import (CSSError, Declaration, declared_styles, parse_declarations,
                            parse_selector, parse_selector_list, parse_stylesheet, select)
from raster.parser.properties import (PRESENTATION_ATTRIBUTES, PROPERTIES, SHORTHANDS,
                                   initial_value, is_inherited)

SVG = 'http://www.w3.org/2000/svg'
from _shared import CORPUS, SUITE_TESTS as SUITE


def doc(body, ns=True):
    return etree.fromstring('<svg%s>%s</svg>' % (' xmlns="%s"' % SVG if ns else '', body))


def by_id(root, i):
    return root.xpath('//*[@id=$i]', i=i)[0]


def style_of(body, i='r', extra_css=''):
    root = doc(body)
    return declared_styles(root, extra_css)[by_id(root, i)]


# --------------------------------------------------------------------------
# properties table
# --------------------------------------------------------------------------

def test_property_table():
    inherited = {'fill', 'fill-opacity', 'fill-rule', 'stroke', 'stroke-width',
                 'stroke-linecap', 'stroke-linejoin', 'stroke-miterlimit',
                 'stroke-dasharray', 'stroke-dashoffset', 'stroke-opacity', 'color',
                 'visibility', 'paint-order', 'shape-rendering', 'clip-rule',
                 'font-family', 'font-size', 'font-weight', 'font-style',
                 'text-anchor', 'letter-spacing', 'word-spacing', 'writing-mode',
                 'direction', 'marker-start', 'marker-mid', 'marker-end',
                 'image-rendering', 'dominant-baseline'}
    not_inherited = {'opacity', 'display', 'clip-path', 'mask', 'filter',
                     'mix-blend-mode', 'isolation', 'stop-color', 'stop-opacity',
                     'overflow', 'mask-type', 'transform', 'transform-origin',
                     'baseline-shift', 'alignment-baseline', 'text-decoration'}
    for n in inherited:
        assert is_inherited(n), n
    for n in not_inherited:
        assert n in PROPERTIES and not is_inherited(n), n
    assert initial_value('fill') == 'black'
    assert initial_value('stroke') == 'none'
    assert initial_value('stroke-width') == '1'
    assert initial_value('stroke-miterlimit') == '4'
    assert initial_value('nope') is None and not is_inherited('nope')
    assert 'transform' not in PRESENTATION_ATTRIBUTES
    assert 'marker' not in PRESENTATION_ATTRIBUTES  # resvg: attribute ignored
    assert {'fill', 'stroke', 'opacity', 'mask-type', 'transform-origin'} \
        <= PRESENTATION_ATTRIBUTES <= set(PROPERTIES)
    # Compositing 1: mix-blend-mode and isolation are CSS-only (resvg suite
    # painting/mix-blend-mode/as-property, painting/isolation/as-property)
    assert not {'mix-blend-mode', 'isolation'} & PRESENTATION_ATTRIBUTES
    assert SHORTHANDS['marker'] == ('marker-start', 'marker-mid', 'marker-end')


# --------------------------------------------------------------------------
# declarations and stylesheets
# --------------------------------------------------------------------------

def test_declarations():
    D = Declaration
    assert parse_declarations('fill:red') == (D('fill', 'red', False),)
    assert parse_declarations(' FILL : red ; stroke:blue;') == (
        D('fill', 'red', False), D('stroke', 'blue', False))
    assert parse_declarations('fill: red ! important') == (D('fill', 'red', True),)
    assert parse_declarations('fill: red !IMPORTANT') == (D('fill', 'red', True),)
    assert parse_declarations('/*text*/fill:green/*text*/') == (D('fill', 'green', False),)
    assert parse_declarations('fill:;stroke;:red;1x:2;fill: a ! b') == ()
    assert parse_declarations("font-family: 'a;b', serif; fill: url(#a;b)") == (
        D('font-family', "'a;b', serif", False), D('fill', 'url(#a;b)', False))
    with pytest.raises(RasterError):
        parse_declarations(None)


def test_marker_shorthand():
    assert parse_declarations('marker: url(#m) !important') == tuple(
        Declaration(n, 'url(#m)', True) for n in ('marker-start', 'marker-mid', 'marker-end'))


def test_font_shorthand():
    d = dict((x.name, x.value) for x in parse_declarations("font: 50px 'Noto Sans'"))
    # the shorthand also resets the properties it cannot set (CSS Fonts 4, 2.8)
    assert d == {'font-style': 'normal', 'font-variant': 'normal', 'font-weight': 'normal',
                 'font-stretch': 'normal', 'font-size': '50px', 'line-height': 'normal',
                 'font-family': "'Noto Sans'", 'font-kerning': 'auto',
                 'font-feature-settings': 'normal', 'font-variation-settings': 'normal'}
    d = dict((x.name, x.value) for x in parse_declarations(
        'font: italic bold condensed 12pt/1.5 Arial, sans-serif'))
    assert d['font-style'] == 'italic' and d['font-weight'] == 'bold'
    assert d['font-stretch'] == 'condensed' and d['font-size'] == '12pt'
    assert d['line-height'] == '1.5' and d['font-family'] == 'Arial, sans-serif'
    d = dict((x.name, x.value) for x in parse_declarations('font: small-caps 700 large serif'))
    assert (d['font-variant'], d['font-weight'], d['font-size']) == ('small-caps', '700', 'large')
    for bad in ('font: bold', 'font: 12px', 'font: foo 12px serif', 'font: caption'):
        assert parse_declarations(bad) == (), bad


def test_stylesheet_parsing():
    css = """
    /* comment { } */ <!--
    @import url(foo.css);
    @media screen { rect { fill: red } @supports (x) { a { b: c } } }
    @font-face { font-family: X; src: url(x.ttf) }
    rect, .a { fill: green; stroke: blue !important }
    a $ b, rect { fill: red }
    .1a { fill: red }
    circle::before, :hover { fill: red }
    g { fill: "a}b" ; stroke: c }
    -->
    """
    rules = parse_stylesheet(css)
    texts = [r.selector.text for r in rules]
    assert texts == ['rect', '.a', 'circle::before', ':hover', 'g']
    assert rules[0].order == rules[1].order < rules[2].order
    assert rules[0].declarations == (Declaration('fill', 'green', False),
                                     Declaration('stroke', 'blue', True))
    assert rules[-1].declarations == (Declaration('fill', '"a}b"', False),
                                      Declaration('stroke', 'c', False))
    # unterminated input never hangs and keeps what parsed
    assert [r.selector.text for r in parse_stylesheet('a { fill: red } b { fill')] == ['a', 'b']
    assert parse_stylesheet('@media x { a { fill: red }') == []
    assert parse_stylesheet('}}} a { fill: red }')[0].selector.text == 'a'
    # an unclosed '[' swallows the rest of the sheet, as CSS Syntax says
    assert [r.selector.text for r in parse_stylesheet('a{b:c} x[ {fill:red} y {b:c}')] == ['a']


@settings(max_examples=150, deadline=None)
@given(st.text(alphabet='ab{}();:,@"\'/*!#.[]=>+~ \n', max_size=60))
def test_stylesheet_never_crashes(text):
    rules = parse_stylesheet(text)
    for r in rules:
        assert isinstance(r.declarations, tuple)


def test_selector_errors():
    for bad in ('', 'a >', '> a', 'a,', '[x', '.', '#', 'a:', 'a::', 'a $ b', 'a:not(b',
                '[x=1]', '.1a', 'a|b'):
        with pytest.raises(CSSError):
            parse_selector_list(bad)


@pytest.mark.parametrize('sel, spec', [
    ('*', (0, 0, 0)), ('rect', (0, 0, 1)), ('.a', (0, 1, 0)), ('#a', (1, 0, 0)),
    ('[x]', (0, 1, 0)), ('g > rect.a[x="1"]:first-child', (0, 3, 2)),
    ('#a #b .c d', (2, 1, 1)), ('* + *', (0, 0, 0)), ('a:hover', (0, 1, 1)),
])
def test_specificity(sel, spec):
    assert parse_selector(sel).specificity == spec


# --------------------------------------------------------------------------
# matching
# --------------------------------------------------------------------------

TREE = """
<g id="g1" class="layer top">
  <rect id="r1" class="a b" x="1" lang="en-US" data="foo bar" href="#x.svg"/>
  <!-- a comment between siblings -->
  <circle id="c1"/>
  <rect id="r2" class="b"/>
  <g id="g2"><rect id="r3"/><text id="t1">hi</text></g>
</g>
<rect id="r4"/>
"""


@pytest.mark.parametrize('sel, ids', [
    ('rect', ['r1', 'r2', 'r3', 'r4']),
    ('*', ['root', 'g1', 'r1', 'c1', 'r2', 'g2', 'r3', 't1', 'r4']),
    ('.b', ['r1', 'r2']),
    ('.a.b', ['r1']),
    ('rect.b:first-child', ['r1']),
    ('#c1', ['c1']),
    ('rect#c1', []),
    ('[x]', ['r1']),
    ('[x="1"]', ['r1']), ("[x='2']", []),
    ('[data~=bar]', ['r1']), ('[data~=ba]', []),
    ('[lang|=en]', ['r1']), ('[lang|=en-US]', ['r1']), ('[lang|=e]', []),
    ('[href^="#x"]', ['r1']), ('[href$=".svg"]', ['r1']), ('[href*="x.s"]', ['r1']),
    ('[href^=""]', []), ('[lang="EN-us" i]', ['r1']), ('[lang="EN-us"]', []),
    ('svg rect', ['r1', 'r2', 'r3', 'r4']),
    ('svg > rect', ['r4']),
    ('g > rect', ['r1', 'r2', 'r3']),
    ('g g rect', ['r3']),
    ('.layer > g > rect', ['r3']),
    ('rect + circle', ['c1']),        # the comment between is not an element
    ('rect + rect', []),
    ('circle + rect', ['r2']),
    ('rect ~ rect', ['r2']),
    ('rect ~ *', ['c1', 'r2', 'g2', 't1']),
    ('g ~ rect', ['r4']),
    (':first-child', ['root', 'g1', 'r1', 'r3']),  # Selectors 4: root too
    ('rect:first-child + circle ~ g text', ['t1']),
    ('rect:hover', []), ('rect:visited', []), ('rect::before', []), ('rect::first-line', []),
    # structural pseudo-classes (Selectors 4): element children only, the
    # comment between r1 and c1 does not count
    ('rect:nth-child(1)', ['r1', 'r3']),
    (':root', ['root']), ('g:root', []),
    (':last-child', ['root', 'g2', 't1', 'r4']),
    (':only-child', ['root']),
    ('g > :nth-child(odd)', ['r1', 'r2', 'r3']), ('g > :nth-child(2n+1)', ['r1', 'r2', 'r3']),
    ('g > :nth-child(even)', ['c1', 'g2', 't1']), ('g > *:nth-child(2n)', ['c1', 'g2', 't1']),
    ('#g1 > :nth-child(-n+2)', ['r1', 'c1']), ('#g1 > :nth-child(n+3)', ['r2', 'g2']),
    ('#g1 > :nth-child( 3 )', ['r2']), ('#g1 > :nth-child(0n+4)', ['g2']),
    ('#g1 > :nth-child(-2n+3)', ['r1', 'r2']), ('#g1 > :nth-child(0)', []),
    ('#g1 > :nth-last-child(1)', ['g2']), ('#g1 > :nth-last-child(odd)', ['c1', 'g2']),
    ('rect:first-of-type', ['r1', 'r3', 'r4']), ('rect:last-of-type', ['r2', 'r3', 'r4']),
    ('#g1 > :only-of-type', ['c1', 'g2']), ('text:only-of-type', ['t1']),
    ('#g1 > rect:nth-of-type(2)', ['r2']), ('#g1 > rect:nth-last-of-type(2)', ['r1']),
    (':empty', ['r1', 'c1', 'r2', 'r3', 'r4']),
    (':lang(en)', ['r1']), (':lang(EN-us)', ['r1']), (':lang(e)', []), (':lang(de, en)', ['r1']),
    ('rect:not(.b)', ['r3', 'r4']), ('*:not(g, rect)', ['root', 'c1', 't1']),
    (':not(:first-child):not(:last-child)', ['c1', 'r2']), ('g :not(g > *)', []), (':not(g > *)', ['root', 'g1', 'r4']),
    ('rect:not(:nth-child(1))', ['r2', 'r4']),

    ('circle, #r4', ['c1', 'r4']),
])
def test_selector_matching(sel, ids):
    root = doc(TREE.replace('\n', ''))
    root.set('id', 'root')
    assert [e.get('id') for e in select(root, sel)] == ids


def test_matching_without_namespace_and_foreign_elements():
    root = doc('<rect id="r"/>', ns=False)
    assert [e.get('id') for e in select(root, 'svg > rect')] == ['r']
    root = etree.fromstring('<svg xmlns="%s" xmlns:x="urn:x"><x:rect id="f"/>'
                            '<rect id="r"/></svg>' % SVG)
    # type selectors match local names (no namespace prefixes in selectors)
    assert [e.get('id') for e in select(root, 'rect')] == ['f', 'r']


# --------------------------------------------------------------------------
# cascade
# --------------------------------------------------------------------------

def test_cascade_order():
    body = """<style>
        #r { fill: red }
        rect { fill: blue; stroke: red; opacity: 0.5 }
        .c { stroke: green }
        rect { opacity: 0.25 }
    </style>
    <rect id="r" class="c" fill="yellow" stroke-width="3" width="5"/>"""
    # id beats type whatever the order; class beats type; later type rule wins
    assert style_of(body) == {'fill': 'red', 'stroke': 'green', 'opacity': '0.25',
                              'stroke-width': '3'}


def test_specificity_tie_resolved_by_order():
    assert style_of('<style>.a{fill:red} .b{fill:green}</style><rect id="r" class="b a"/>') \
        == {'fill': 'green'}
    assert style_of('<style>.b{fill:green} .a{fill:red}</style><rect id="r" class="b a"/>') \
        == {'fill': 'red'}
    # two style elements chain in document order
    assert style_of('<style>rect{fill:red}</style><rect id="r"/><style>rect{fill:green}</style>') \
        == {'fill': 'green'}


def test_style_attribute_and_important():
    # resvg structure/style/resolve-order: style attribute beats stylesheet
    assert style_of('<style>.fil {fill:blue}</style>'
                    '<rect id="r" style="fill:green" class="fil"/>') == {'fill': 'green'}
    # resvg structure/style/important: !important beats later normal rule
    assert style_of('<style>#r { fill: green !important; } #r { fill: red; }</style>'
                    '<rect id="r"/>') == {'fill': 'green'}
    # stylesheet !important beats the style attribute's normal declaration
    assert style_of('<style>rect { fill: green !important }</style>'
                    '<rect id="r" style="fill: red"/>') == {'fill': 'green'}
    # the style attribute's !important beats everything
    assert style_of('<style>#r { fill: red !important }</style>'
                    '<rect id="r" style="fill: green !important; stroke: red"/>') \
        == {'fill': 'green', 'stroke': 'red'}
    # among !important stylesheet declarations, specificity still counts
    assert style_of('<style>#r { fill: green !important } rect { fill: red !important }'
                    '</style><rect id="r"/>') == {'fill': 'green'}


def test_cascade_filters_and_keeps():
    # resvg non-presentational-attribute: `height` in CSS is ignored; CSS
    # transform is kept (resvg structure/style/transform)
    s = style_of('<style>#r { height:160px; transform: scale(2) }</style>'
                 '<rect id="r" transform="scale(3)" fill=" inherit " marker="url(#m)"'
                 ' style="bogus: 1; stroke: inherit"/>')
    assert s == {'transform': 'scale(2)', 'fill': 'inherit', 'stroke': 'inherit'}


def test_style_type_and_cdata():
    assert style_of('<style type="no-a-css">.fil { fill: red; }</style>'
                    '<rect id="r" class="fil" fill="green"/>') == {'fill': 'green'}
    assert style_of('<style type="text/css"><![CDATA[ .fil { fill: green; } ]]></style>'
                    '<rect id="r" class="fil"/>') == {'fill': 'green'}
    assert style_of('<style type="">rect { fill: green }</style><rect id="r"/>') \
        == {'fill': 'green'}


def test_extra_css_and_marker_in_css():
    assert style_of('<style>rect{fill:red}</style><rect id="r"/>',
                    extra_css='rect{fill:green}') == {'fill': 'green'}
    s = style_of('<style>#r { marker:url(#marker1) }</style><path id="r"/>')
    assert s == {'marker-start': 'url(#marker1)', 'marker-mid': 'url(#marker1)',
                 'marker-end': 'url(#marker1)'}


def test_every_element_gets_an_entry():
    root = doc(TREE.replace('\n', ''))
    styles = declared_styles(root)
    elements = [e for e in root.iter() if isinstance(e.tag, str)]
    assert list(styles) == elements
    assert all(v == {} for v in styles.values())


def test_index_matches_brute_force():
    # The rule index (id/class/type/universal) must give exactly the result
    # of testing every rule against every element.
    import random
    rng = random.Random(7)
    tags, classes = ['rect', 'g', 'circle'], ['a', 'b', 'c']
    sels = ['rect', '.a', '.b.c', '#e3', '*', 'g > rect', 'g .a', '.a + .b', 'rect ~ g',
            '[id$="1"]', 'g:first-child', '#e5 *', 'circle.c', 'g g .a', 'rect ~ g .b',
            '.a ~ * ~ g', 'g > g rect', '* g ~ .c *']
    for trial in range(20):
        parts, n = [], 0

        def gen(depth):
            nonlocal n
            out = ''
            for _ in range(rng.randint(1, 4)):
                n += 1
                tag = rng.choice(tags)
                cls = ' '.join(rng.sample(classes, rng.randint(0, 2)))
                kids = gen(depth + 1) if depth < 3 and rng.random() < 0.4 else ''
                out += '<%s id="e%d" class="%s">%s</%s>' % (tag, n, cls, kids, tag)
            return out
        chosen = rng.sample(sels, 5)
        css = ''.join('%s { stroke-width: %d }' % (s, i) for i, s in enumerate(chosen))
        root = doc('<style>%s</style>%s' % (css, gen(0)))
        styles = declared_styles(root)
        rules = parse_stylesheet(css)
        for el, d in styles.items():
            best = None
            for r in rules:
                # no memo here: plain backtracking is the reference
                if r.selector._match(el, 0, None):
                    key = (r.selector.specificity, r.order)
                    if best is None or key > best[0]:
                        best = (key, r.declarations[0].value)
            assert d.get('stroke-width') == (best[1] if best else None)


def test_resvg_style_tests_parse():
    files = sorted(glob.glob(os.path.join(SUITE, 'structure', 'style', '*.svg')))
    assert len(files) >= 14
    n_rules = 0
    for path in files:
        root = etree.parse(path).getroot()
        for st_el in root.iter('{%s}style' % SVG):
            n_rules += len(parse_stylesheet(''.join(st_el.itertext())))
        styles = declared_styles(root)
        assert len(styles) == sum(1 for e in root.iter() if isinstance(e.tag, str))
        rect = by_id(root, 'rect1')
        name = os.path.basename(path)
        expect = {
            'attribute-selector.svg': 'green', 'class-selector.svg': 'green',
            'combined-selectors.svg': 'green', 'important.svg': 'green',
            'invalid-type.svg': 'green', 'resolve-order.svg': 'green',
            'style-inside-CDATA.svg': 'green', 'type-selector.svg': 'green',
            'universal-selector.svg': 'green', 'unresolved-class-selector.svg': 'green',
            'non-presentational-attribute.svg': 'red', 'transform.svg': 'green',
        }.get(name)
        if expect is not None:
            assert styles[rect].get('fill') == expect, name
    assert n_rules >= 11


def test_corpus_documents_cascade():
    paths = sorted(glob.glob(os.path.join(CORPUS, '*.svg')))[:6]
    assert len(paths) == 6, 'corpus missing at %s' % CORPUS
    for path in paths:
        root = etree.parse(path, etree.XMLParser(huge_tree=True)).getroot()
        styles = declared_styles(root)
        for d in styles.values():
            assert set(d) <= set(PROPERTIES)


def test_deep_tree_matching_is_not_exponential():
    # Without the matching cache, 'x g g ... *' backtracks over C(200, 10)
    # ancestor combinations and never finishes.
    depth = 200
    root = etree.fromstring('<svg><style>x g g g g g g g g g g * { fill: red }'
                            ' g ~ g ~ g g { stroke: red }</style>'
                            + '<g>' * depth + '<rect/>' + '</g>' * depth + '</svg>')
    styles = declared_styles(root)
    assert all(d == {} for d in styles.values())
    assert select(root, 'x g g g g g g g g g *') == []
    assert len(select(root, 'svg g g g g g g g g g rect')) == 1


def test_whole_resvg_suite_cascades():
    files = sorted(glob.glob(os.path.join(SUITE, '**', '*.svg'), recursive=True))
    n = 0
    for path in files:
        try:
            root = etree.parse(path).getroot()
        except etree.XMLSyntaxError:
            continue  # a few suite files are deliberately malformed
        styles = declared_styles(root)
        for el, d in styles.items():
            assert set(d) <= set(PROPERTIES), path
            # every presentation attribute the element carries is present
            # unless CSS overrode it (then the value may differ)
            for k in el.keys():
                if k in PRESENTATION_ATTRIBUTES:
                    assert k in d, (path, k)
        n += 1
    assert n > 1000


def test_declared_styles_reports_requested_attributes():
    root = etree.fromstring(
        '<svg xmlns="http://www.w3.org/2000/svg" id="s"><style>#a { fill: red }</style>'
        '<rect id="a" fill="blue" style="stroke: green"/><g systemLanguage="en">'
        '<circle id="b" class="c" requiredExtensions=""/></g></svg>')
    found = {'id': [], 'systemLanguage': [], 'requiredExtensions': [], 'fill': []}
    styles = declared_styles(root, '', found)
    assert styles == declared_styles(root)
    assert [e.get('id') for e in found['id']] == ['s', 'a', 'b']      # document order
    assert [e.tag.split('}')[1] for e in found['systemLanguage']] == ['g']
    assert [e.get('id') for e in found['requiredExtensions']] == ['b']
    assert found['fill'] == []          # presentation attributes are styles, not reported
    assert styles[root[1]] == {'fill': 'red', 'stroke': 'green'}


# --------------------------------------------------------------------------
# structural pseudo-classes and @import
# --------------------------------------------------------------------------

@pytest.mark.parametrize('arg', ['n+', '2x', '', 'odd even', '3n+-1', 'n n'])
def test_bad_nth_argument_drops_the_rule(arg):
    assert parse_stylesheet(':nth-child(%s) { fill: red } a { fill: blue }' % arg)[0].selector.text == 'a'


def test_pseudo_class_specificity():
    sp = [s.specificity for s in parse_selector_list(
        'rect:nth-child(2n), :root, a:not(#x, .y), :not(rect), :lang(en) :empty')]
    assert sp == [(0, 1, 1), (0, 1, 0), (1, 0, 1), (0, 0, 1), (0, 2, 0)]


@settings(max_examples=60, deadline=None)
@given(a=st.integers(-4, 4), b=st.integers(-6, 8), n=st.integers(1, 14))
def test_nth_child_is_an_plus_b(a, b, n):
    """:nth-child(an+b) picks the k-th child (1-based) exactly when
    k = a*m + b for some m >= 0; :nth-last-child counts from the end."""
    root = doc(''.join('<rect id="r%d"/>' % k for k in range(1, n + 1)))
    want = {k for k in range(1, n + 1) if any(a * m + b == k for m in range(0, 40))}
    got = [e.get('id') for e in select(root, 'rect:nth-child(%dn%+d)' % (a, b))]
    assert got == ['r%d' % k for k in sorted(want)]
    got = [e.get('id') for e in select(root, 'rect:nth-last-child(%dn%+d)' % (a, b))]
    assert got == ['r%d' % k for k in range(1, n + 1) if n + 1 - k in want]


def test_nth_child_on_many_siblings():
    """20,000 siblings with :nth-child and :last-of-type: positions count
    element children only (the style element is child 1)."""
    n = 20000
    root = doc('<style>rect:nth-child(3n+1){fill:red} rect:last-of-type{fill:blue}</style>'
               + '<rect/>' * n)
    styles = declared_styles(root)
    fills = [styles[el].get('fill') for el in root[1:]]
    assert fills[0] is None and fills[1] is None and fills[2] == 'red' and fills[-1] == 'blue'
    assert sum(f == 'red' for f in fills) == len(range(4, n + 2, 3))


def _write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write(text)


def test_import_follows_local_sheets(tmp_path):
    """@import url() and string forms, relative to the importing sheet,
    before the rules of the sheet that imports them (so those win ties);
    media lists all/screen apply, print does not."""
    from raster.parser import build_tree
    from raster.parser.document import load_document
    _write(str(tmp_path / 'css' / 'a.css'), '@import "b.css"; #r1 { fill: #00ff00 }')
    _write(str(tmp_path / 'css' / 'b.css'), '#r1 { fill: red } #r2 { fill: #0000ff }')
    _write(str(tmp_path / 'p.css'), '#r2 { fill: red }')
    _write(str(tmp_path / 's.css'), '#r3 { fill: #ff00ff }')
    svg = ('<svg xmlns="%s" width="30" height="10"><style>@import url(css/a.css);'
           '@import url("p.css") print; @import \'s.css\' screen, print;</style>'
           '<rect id="r1" width="10" height="10"/><rect id="r2" x="10" width="10" height="10"/>'
           '<rect id="r3" x="20" width="10" height="10"/></svg>' % SVG)
    _write(str(tmp_path / 'd.svg'), svg)
    root = load_document(svg.encode())
    tree = build_tree(root, base_dir=str(tmp_path))
    colours = [c.fill.paint.color for c in tree.root.children]
    assert colours == [(0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0), (1.0, 0.0, 1.0, 1.0)]


def test_import_refusals_warn_and_are_bounded(tmp_path):
    """Cycles, files outside the allowed directories, network URLs and
    imports after a rule are not followed; a long chain stops at the depth
    limit; each refusal is a RasterWarning, never an exception."""
    from raster.errors import RasterWarning
    from raster.parser import build_tree
    from raster.parser.document import load_document
    from raster.parser.imageload import MAX_IMPORT_DEPTH
    d = tmp_path / 'doc'
    _write(str(d / 'loop.css'), '@import "loop2.css"; #r1 { fill: #00ff00 }')
    _write(str(d / 'loop2.css'), '@import "loop.css";')
    _write(str(tmp_path / 'outside.css'), '#r2 { fill: red }')
    for k in range(MAX_IMPORT_DEPTH + 3):
        _write(str(d / ('c%d.css' % k)), '@import "c%d.css"; #r3 { fill: #%02x0000 }' % (k + 1, k))
    svg = ('<svg xmlns="%s" width="30" height="10"><style>@import "loop.css";'
           '@import "../outside.css"; @import url(https://example.com/x.css); @import "c0.css";'
           '#r2 { fill: #0000ff } @import "outside.css";</style>'
           '<rect id="r1" width="10" height="10"/><rect id="r2" x="10" width="10" height="10"/>'
           '<rect id="r3" x="20" width="10" height="10"/></svg>' % SVG)
    with pytest.warns(RasterWarning) as rec:
        tree = build_tree(load_document(svg.encode()), base_dir=str(d))
    msgs = ' '.join(str(w.message) for w in rec)
    assert 'cycle' in msgs and 'outside the allowed' in msgs and 'not fetched' in msgs
    assert 'levels' in msgs
    c = [ch.fill.paint.color for ch in tree.root.children]
    assert c[0] == (0.0, 1.0, 0.0, 1.0) and c[1] == (0.0, 0.0, 1.0, 1.0)
    # the deepest sheet read is c{MAX-1}: its rule comes first, c0's last wins
    assert c[2] == (0.0, 0.0, 0.0, 1.0)


def test_import_inside_svg_image_is_refused(tmp_path):
    """An SVG image reads no files, style sheets included (data: URIs do)."""
    from raster.parser import build_tree
    from raster.parser.document import load_document
    _write(str(tmp_path / 'x.css'), 'rect { fill: red }')
    root = load_document(('<svg xmlns="%s" width="10" height="10"><style>@import "x.css";'
                          '@import "data:text/css,circle%%7Bfill:%%2300f%%7D";</style>'
                          '<rect width="5" height="5"/><circle r="3"/></svg>' % SVG).encode())
    import warnings
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter('always')
        tree = build_tree(root, base_dir=str(tmp_path), image_depth=1)
    assert any('inside an SVG image' in str(w.message) for w in rec)
    rect, circle = tree.root.children
    assert rect.fill.paint.color == (0.0, 0.0, 0.0, 1.0)
    assert circle.fill.paint.color == (0.0, 0.0, 1.0, 1.0)


def _scan_reference(text, pos, stops):
    # one character at a time: strings skipped (a quote escaped by a
    # backslash does not end one; an unclosed string runs to the end),
    # parentheses and brackets nest, a stop counts at depth 0 only
    depth = 0
    while pos < len(text):
        ch = text[pos]
        if ch in '"\'':
            end = pos + 1
            while end < len(text) and not (text[end] == ch and text[end - 1] != '\\'):
                end += 1
            pos = end + 1
            continue
        if depth == 0 and ch in stops:
            return pos
        if ch in '([':
            depth += 1
        elif ch in ')]':
            depth = max(depth - 1, 0)
        pos += 1
    return len(text)


@settings(max_examples=400, deadline=None)
@given(st.text(alphabet='ab ;,:{}()[]"\'\\#', max_size=40), st.integers(0, 45),
       st.sampled_from([';', ')', ',', ';{}', '{}', '}']))
def test_property_scan_to_skips_strings_and_nesting(text, pos, stops):
    from raster.parser.css import _scan_to
    assert _scan_to(text, pos, stops) == min(_scan_reference(text, pos, stops), len(text))


def test_scan_to_by_hand():
    from raster.parser.css import _scan_to
    s = "fill:url(#a;b);font-family:'x;y\\'z;w';stroke:red"
    assert _scan_to(s, 0, ';') == s.index(');') + 1
    assert _scan_to(s, 15, ';') == s.index("';stroke") + 1
    assert _scan_to('a(b[c)d]e)f;g', 0, ';') == 11     # (unbalanced: depth never below 0)
    assert _scan_to('"unclosed;', 0, ';') == 10
