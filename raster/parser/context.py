"""What every element converter receives: the parse :class:`Options`, the
per-subtree :class:`State` and the per-document :class:`Cache`.

Converters have one signature, ``convert(el, state, cache, parent)``: the
element (an lxml element), the state of the subtree it is converted in,
the document's cache and the node list of the parent being built, to
which the converter appends what the element becomes.  A converter never
keeps state of its own between calls: everything shared lives on the
:class:`Cache`, declared here.
"""

import contextlib
import math
import os
import types
import warnings
from dataclasses import dataclass, field
from typing import Optional, Tuple

from .._regex import lazy
from ..limits import Limits, current as current_limits
from ..errors import RasterWarning, SVGError, TransformError
from ..fonts import FontOptions
from ..geometry.transform import Affine

__all__ = ['Options', 'State', 'Cache', 'SVG_NS', 'XLINK_HREF', 'NO_OWN', 'locale_languages',
           'parse_languages']

SVG_NS = 'http://www.w3.org/2000/svg'
XLINK_HREF = '{http://www.w3.org/1999/xlink}href'

#: The own (non-inherited) style of an element without declarations.
NO_OWN = types.MappingProxyType({})


_LANG_TAG = lazy(globals(), '_LANG_TAG', r'[A-Za-z]{1,8}(-[A-Za-z0-9]{1,8})*')


def parse_languages(s):
    """A comma-separated list of language tags (``'en,de-CH'``) as a tuple
    of str.

    Raises
    ------
    raster.errors.SVGError
        An empty list or an item that is not a language tag.

    >>> parse_languages('en, de-CH')
    ('en', 'de-CH')
    """
    tags = tuple(t.strip() for t in str(s).split(','))
    if not tags or not all(_LANG_TAG.fullmatch(t) for t in tags):
        raise SVGError('invalid language list %r: expected tags such as en,de-CH' % (s,))
    return tags


def locale_languages(environ=None):
    """The user's languages from the environment's locale: the first of
    ``LC_ALL``, ``LC_MESSAGES``, ``LANG`` that is set and not empty, as a
    language tag followed by its primary language (``de_CH.UTF-8`` ->
    ``('de-CH', 'de')``); ``('en',)`` when none is set or the locale is
    ``C``/``POSIX``.

    >>> locale_languages({'LANG': 'de_CH.UTF-8'}), locale_languages({'LC_ALL': 'C'})
    (('de-CH', 'de'), ('en',))
    """
    env = os.environ if environ is None else environ
    for name in ('LC_ALL', 'LC_MESSAGES', 'LANG'):
        v = env.get(name)
        if v:
            break
    else:
        return ('en',)
    v = v.split('.')[0].split('@')[0].replace('_', '-')
    if v in ('C', 'POSIX') or not _LANG_TAG.fullmatch(v):
        return ('en',)
    primary = v.split('-')[0]
    return (v,) if primary == v else (v, primary)


@dataclass(frozen=True)
class Options:
    """How a document is parsed.

    Attributes
    ----------
    dpi : float
        Pixels per inch for absolute units (``in``, ``mm``, ``pt`` ...).
    font_size : float
        The ``medium`` font size in px (for ``em``/``ex`` and keywords).
    languages : tuple of str
        The user's languages for ``systemLanguage``, as language tags;
        primary subtags are compared (``'en'`` matches ``en-US`` and
        ``'en-GB'`` matches ``en``, as browsers do).  The default is English,
        whatever the environment (:func:`locale_languages` gives the
        environment's, as the commands use).
    tolerance : float
        Flattening tolerance in device pixels at the natural size; arcs
        become cubics a hundred times finer than this divided by the
        element's scale (:data:`raster.parser.shapes.ARC_SAFETY`), so a 100x
        zoom stays within it.
    max_elements : int or None
        Most nodes to build (a ``use`` bomb stops there, with a warning);
        None: ``max_elements`` of :func:`raster.limits.current` when the
        tree is built.
    max_use_depth : int or None
        Deepest ``use`` nesting followed (None: from
        :func:`raster.limits.current`).
    extra_css : str
        A user stylesheet applied after the document's own.
    base_dir : str or None
        Directory relative references resolve against.
    allow_files_under : str or None
        Directory files may be read from (default: ``base_dir``).
    resources_dir : str or None
        A further directory files may be read from.
    fonts : raster.fonts.FontOptions
        Where the fonts of text come from (default: the system's fonts)
        and how generic families resolve.
    image_depth : int
        Nesting depth of SVG images (0: the outermost document; nested
        documents read no files).
    """
    dpi: float = 96.0
    font_size: float = 12.0
    languages: Tuple[str, ...] = ('en',)
    tolerance: float = 0.1
    max_elements: Optional[int] = None
    max_use_depth: Optional[int] = None
    extra_css: str = ''
    base_dir: Optional[str] = None
    allow_files_under: Optional[str] = None
    resources_dir: Optional[str] = None
    fonts: FontOptions = FontOptions()
    image_depth: int = 0


class State:
    """The context an element is converted in (per subtree, immutable once
    made; :meth:`sub` makes a child state).

    Attributes
    ----------
    inh, own : dict
        Computed inherited and own (non-inherited) style of the element's
        *rendering* parent (content instantiated by ``use`` inherits from
        the ``use`` element).  Shared between elements: never modified.
    vw, vh : float
        Size of the nearest viewport, for percentages.
    ctm : Affine
        The parent's user space to document px (for arc tolerances and
        overflow checks).
    use_depth : int
        Active ``use`` nesting depth.
    clip : bool
        True inside a ``clipPath``: only geometry counts.
    context : (paint, paint) or None
        The context element's fill and stroke paints, for ``context-fill``
        and ``context-stroke`` (SVG 2).
    """
    __slots__ = ('inh', 'own', 'vw', 'vh', 'ctm', 'use_depth', 'clip', 'context', 'scale_memo',
                 'arc_tol')

    def __init__(self, inh, own, vw, vh, ctm, use_depth=0, clip=False, context=None):
        self.inh, self.own = inh, own
        self.vw, self.vh, self.ctm, self.use_depth = vw, vh, ctm, use_depth
        self.clip = clip
        self.context = context
        self.scale_memo = None      # the CTM's largest singular value (memo)
        self.arc_tol = None         # the arc tolerance at this CTM (memo, see shapes)

    def scale(self):
        """Largest singular value of the CTM (memoized)."""
        s = self.scale_memo
        if s is None:
            s = self.scale_memo = self.ctm.max_scale()
        return s

    def check(self, t):
        """Raise :class:`~raster.errors.TransformError` when ``ctm @ t``
        overflows (no Affine is built for a translation)."""
        if t.is_translation:
            m = self.ctm
            e = m.a * t.e + m.c * t.f + m.e
            f = m.b * t.e + m.d * t.f + m.f
            if not (math.isfinite(e) and math.isfinite(f)):
                raise TransformError('transform overflows')
        else:
            self.ctm @ t

    def sub(self, inh=None, own=None, transform=None, vw=None, vh=None, use_depth=None,
            clip=None, context=False):
        """A child state: the given fields replaced, ``transform`` composed
        onto the CTM."""
        same = transform is None or transform.is_identity
        st = State(self.inh if inh is None else inh, self.own if own is None else own,
                   self.vw if vw is None else vw, self.vh if vh is None else vh,
                   self.ctm if same else self.ctm @ transform,
                   self.use_depth if use_depth is None else use_depth,
                   self.clip if clip is None else clip,
                   self.context if context is False else context)
        if same or transform.is_translation:
            st.scale_memo = self.scale_memo
            st.arc_tol = self.arc_tol
        return st


@dataclass(eq=False)
class Cache:
    """Everything shared by the converters of one document.

    Attributes
    ----------
    options : Options
    root : lxml element
        The document's root ``svg`` element.
    styles : dict
        Element -> declared properties (the CSS cascade and presentation
        attributes, :func:`raster.parser.css.declared_styles`).
    by_id : dict
        id -> first element with that id.
    conditional : set
        Elements with conditional processing attributes.
    converters : dict
        Element local name -> converter (the table of
        :mod:`raster.parser`); :func:`raster.parser.convert.convert`
        dispatches through it.
    parse_nested : callable
        ``parse_nested(root, options)`` -> Tree: builds an SVG image's
        document (the parser's entry point, passed in to keep modules free
        of import circles).
    count, stopped : int, bool
        Nodes built so far; whether :attr:`Options.max_elements` was hit.
    warned : set
        Kinds of warning already issued (one warning per kind).
    tree_ids : dict
        id -> first node built for it (:attr:`raster.tree.Tree.ids`).
    active : set
        Elements whose content is being converted (clip paths, masks,
        patterns, markers, filters): a reference back to one is recursion.
    memo : dict
        Bounded memo tables of the converters, by name (see each module).
    image_cache : dict
        Decoded images by resolved reference, shared with nested SVG
        images (see :mod:`raster.parser.imageload`).
    limits : raster.limits.Limits
        The budgets of this document (see :meth:`spend`).
    spent : dict
        What the document has used of its budgets, by kind.
    prepaid : int
        Depth of ``use`` copies being converted whose layers were taken
        from the budget ahead (see :func:`raster.parser.refs.instance_size`).
    open_document : callable
        ``open_document(root, options)`` -> the Cache of another document
        whose elements this one references (``use href="lib.svg#id"``;
        the parser's, passed in like ``parse_nested``).
    """
    options: Options
    root: object
    styles: dict
    by_id: dict
    conditional: set
    converters: dict
    parse_nested: object
    count: int = 0
    stopped: bool = False
    warned: set = field(default_factory=set)
    tree_ids: dict = field(default_factory=dict)
    active: set = field(default_factory=set)
    memo: dict = field(default_factory=dict)
    image_cache: dict = field(default_factory=dict)
    limits: Limits = field(default_factory=current_limits)
    spent: dict = field(default_factory=dict)
    prepaid: int = 0
    open_document: object = None

    def release(self):
        """Drop the memo tables, those of the other documents referenced
        (``use`` of another file) included: called when the tree is built.
        Memo entries may refer back to the cache (text's leaf styles keep
        a fallback function that uses it), and under the commands' paused
        collector such a cycle would keep the lxml document, its styles
        and the memos alive to the end of the process."""
        subs = self.memo.get('document_caches')
        self.memo = {}
        for sub in (subs or {}).values():
            sub.release()

    def table(self, name):
        """The memo table ``name`` (created empty on first use)."""
        t = self.memo.get(name)
        if t is None:
            t = self.memo[name] = {}
        return t

    def warn(self, kind, msg):
        """Issue ``msg`` as a :class:`~raster.errors.RasterWarning`, once
        per ``kind`` in the document."""
        if kind not in self.warned:
            self.warned.add(kind)
            warnings.warn(msg, RasterWarning, stacklevel=4)

    def tick(self, n=1):
        """Count ``n`` nodes (default one); False (with a warning) once the
        limit is hit."""
        self.count += n
        if self.count > self.options.max_elements:
            if not self.stopped:
                self.stopped = True
                self.warn('limit', 'document needs more than %d nodes; the rest is not '
                          'rendered' % self.options.max_elements)
            return False
        return True

    def spend(self, kind, amount, what):
        """Take ``amount`` of the document's budget ``max_<kind>``
        (:mod:`raster.limits`, e.g. ``'glyphs'``) for ``what``; False (with
        one warning per kind) when that would go over it: ``what`` is then
        left out."""
        used = self.spent.get(kind, 0) + amount
        budget = getattr(self.limits, 'max_' + kind)
        if used > budget:
            self.warn(('budget', kind), '%s not rendered: the document needs more than %d %s '
                      '(max_%s)' % (what, budget, kind, kind))
            return False
        self.spent[kind] = used
        return True

    def note_id(self, el, node):
        """Record ``node`` as what ``el``'s id names (the first one wins)."""
        i = el.get('id')
        if i and i not in self.tree_ids:
            self.tree_ids[i] = node
        return node

    @contextlib.contextmanager
    def referencing(self, el):
        """While converting ``el``'s content: references back to ``el``
        are recursion (see :attr:`active`)."""
        self.active.add(el)
        try:
            yield
        finally:
            self.active.discard(el)
