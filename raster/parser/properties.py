"""The SVG/CSS properties the renderer understands.

:data:`PROPERTIES` maps each property name to a :class:`Property`: whether it
is inherited and its initial value (as the string a document would write).
:data:`PRESENTATION_ATTRIBUTES` is the set of element attributes that are
presentation attributes, i.e. that feed the cascade with the lowest priority.

``transform`` is special: in SVG 2 it is a presentation attribute, but the
tree builder reads the ``transform`` attribute itself (``gradientTransform``
and ``patternTransform`` are separate attributes).  A CSS ``transform`` in a
stylesheet or ``style`` attribute overrides the attribute, as resvg does (its
``structure/style/transform`` test), so it is a property here but not in
:data:`PRESENTATION_ATTRIBUTES`.

``display`` is not inherited, but ``display: none`` on an ancestor hides the
whole subtree: the tree builder stops descending there.

>>> PROPERTIES['fill']
Property(inherited=True, initial='black')
>>> 'stroke-width' in PRESENTATION_ATTRIBUTES, 'width' in PRESENTATION_ATTRIBUTES
(True, False)
>>> sorted(SHORTHANDS['marker'])
['marker-end', 'marker-mid', 'marker-start']
"""

from typing import NamedTuple

__all__ = ['Property', 'PROPERTIES', 'PRESENTATION_ATTRIBUTES', 'SHORTHANDS',
           'INHERITED', 'is_inherited', 'initial_value']


class Property(NamedTuple):
    """One property: ``inherited`` (bool) and ``initial`` (str) value."""
    inherited: bool
    initial: str


_I, _N = True, False

_TABLE = [
    # painting
    ('fill', _I, 'black'),
    ('fill-opacity', _I, '1'),
    ('fill-rule', _I, 'nonzero'),
    ('stroke', _I, 'none'),
    ('stroke-width', _I, '1'),
    ('stroke-linecap', _I, 'butt'),
    ('stroke-linejoin', _I, 'miter'),
    ('stroke-miterlimit', _I, '4'),
    ('stroke-dasharray', _I, 'none'),
    ('stroke-dashoffset', _I, '0'),
    ('stroke-opacity', _I, '1'),
    ('paint-order', _I, 'normal'),
    ('vector-effect', _N, 'none'),
    ('color', _I, 'black'),
    ('color-interpolation', _I, 'sRGB'),
    ('color-interpolation-filters', _I, 'linearRGB'),
    ('color-rendering', _I, 'auto'),
    ('shape-rendering', _I, 'auto'),
    ('text-rendering', _I, 'auto'),
    ('image-rendering', _I, 'auto'),
    ('marker-start', _I, 'none'),
    ('marker-mid', _I, 'none'),
    ('marker-end', _I, 'none'),
    # visibility and compositing
    ('opacity', _N, '1'),
    ('display', _N, 'inline'),
    ('visibility', _I, 'visible'),
    ('overflow', _N, 'visible'),
    ('clip', _N, 'auto'),
    ('clip-path', _N, 'none'),
    ('clip-rule', _I, 'nonzero'),
    ('mask', _N, 'none'),
    ('mask-type', _N, 'luminance'),
    ('filter', _N, 'none'),
    ('mix-blend-mode', _N, 'normal'),
    ('isolation', _N, 'auto'),
    ('enable-background', _N, 'accumulate'),
    ('pointer-events', _I, 'visiblePainted'),
    ('cursor', _I, 'auto'),
    # gradients, filters, lighting
    ('stop-color', _N, 'black'),
    ('stop-opacity', _N, '1'),
    ('flood-color', _N, 'black'),
    ('flood-opacity', _N, '1'),
    ('lighting-color', _N, 'white'),
    # geometry-adjacent
    ('transform', _N, 'none'),
    ('transform-origin', _N, '0 0'),
    ('transform-box', _N, 'view-box'),
    # text
    ('font-family', _I, 'Times New Roman'),
    ('font-size', _I, 'medium'),
    ('font-size-adjust', _I, 'none'),
    ('font-weight', _I, 'normal'),
    ('font-style', _I, 'normal'),
    ('font-variant', _I, 'normal'),
    ('font-stretch', _I, 'normal'),
    ('font-kerning', _I, 'auto'),
    ('font-feature-settings', _I, 'normal'),
    ('font-variation-settings', _I, 'normal'),
    ('font-variant-caps', _I, 'normal'),
    ('font-variant-ligatures', _I, 'normal'),
    ('font-variant-numeric', _I, 'normal'),
    ('font-variant-east-asian', _I, 'normal'),
    ('font-variant-position', _I, 'normal'),
    ('text-anchor', _I, 'start'),
    ('letter-spacing', _I, 'normal'),
    ('word-spacing', _I, 'normal'),
    ('kerning', _I, 'auto'),
    ('text-decoration', _N, 'none'),
    ('writing-mode', _I, 'lr-tb'),
    ('direction', _I, 'ltr'),
    ('unicode-bidi', _N, 'normal'),
    ('dominant-baseline', _I, 'auto'),
    ('alignment-baseline', _N, 'auto'),
    ('baseline-shift', _N, 'baseline'),
    ('glyph-orientation-vertical', _I, 'auto'),
    ('glyph-orientation-horizontal', _I, '0deg'),
    ('text-orientation', _I, 'mixed'),
    ('white-space', _I, 'normal'),
    ('line-height', _I, 'normal'),
    ('inline-size', _N, '0'),
    ('text-overflow', _N, 'clip'),
]

#: name -> :class:`Property`
PROPERTIES = {name: Property(inh, init) for name, inh, init in _TABLE}

#: Names of the inherited properties.
INHERITED = frozenset(n for n, p in PROPERTIES.items() if p.inherited)

#: Attributes that are presentation attributes (every property except the
#: CSS-only ones and ``transform``, which the tree builder reads itself).
PRESENTATION_ATTRIBUTES = frozenset(
    n for n in PROPERTIES
    if n not in ('transform', 'transform-box', 'white-space', 'line-height',
                 'inline-size', 'text-overflow', 'font-feature-settings',
                 'font-variation-settings',
                 'font-variant-caps', 'font-variant-ligatures',
                 'font-variant-numeric', 'font-variant-east-asian',
                 'font-variant-position', 'font-kerning', 'text-orientation',
                 'mask-type', 'isolation', 'mix-blend-mode'))
# mask-type is a presentation attribute (CSS Masking) and transform-origin
# is read as one by resvg; isolation and mix-blend-mode are CSS-only
# (Compositing 1: the resvg suite's painting/*/as-property cases ignore them
# as attributes).
PRESENTATION_ATTRIBUTES = PRESENTATION_ATTRIBUTES | {'mask-type', 'transform-origin'}

#: Shorthand -> the longhands it sets.
SHORTHANDS = {
    'marker': ('marker-start', 'marker-mid', 'marker-end'),
    'font': ('font-style', 'font-variant', 'font-weight', 'font-stretch',
             'font-size', 'line-height', 'font-family'),
}


def is_inherited(name):
    """Whether property `name` inherits by default (unknown names: False).

    >>> is_inherited('fill'), is_inherited('opacity')
    (True, False)
    """
    p = PROPERTIES.get(name)
    return bool(p and p.inherited)


def initial_value(name):
    """The initial value string of property `name`, or ``None`` if unknown.

    >>> initial_value('stroke-miterlimit')
    '4'
    """
    p = PROPERTIES.get(name)
    return None if p is None else p.initial
