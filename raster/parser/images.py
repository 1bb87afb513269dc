"""The ``<image>`` element to an :class:`~raster.tree.ImageNode` (wrapped
in a Group when the element has a transform or group effects).

Geometry: ``x``, ``y``, ``width``, ``height`` (``auto`` or absent: the
intrinsic size, the other side keeping the aspect ratio; zero or negative:
not rendered), ``preserveAspectRatio`` through
:func:`raster.parser.values.viewbox_transform`; ``ImageNode.transform`` maps
image pixels (SVG images: the image document's pixels) to the element's
user space, ``ImageNode.clip`` is the visible rectangle (set for ``slice``
and for every SVG image, whose content may overflow its natural size).
``image-rendering`` ``optimizeSpeed``/``pixelated``/``crisp-edges`` selects
nearest-neighbour sampling (``smooth=False``).  The document's
``tolerance`` (device pixels at its natural size) is honoured inside SVG
images: an image document drawn larger than its natural size is built with
a proportionally finer tolerance.  An image that cannot be used (see
:mod:`raster.parser.imageload`) is skipped with one warning.
"""

import dataclasses
import math

import numpy as np

from ..errors import RasterError
from ..geometry.pathdata import rect_path
from ..tree import ImageNode, PathNode
from .context import XLINK_HREF
from .effects import NO_EFFECTS, effects, emit
from .imageload import ImageError, load_image
from .style import length, length_context, style_of, transform_of
from .values import parse_length, parse_preserve_aspect_ratio, viewbox_transform

__all__ = ['convert_image']

_NEAREST = frozenset(['optimizeSpeed', 'pixelated', 'crisp-edges'])


def _size_attr(el, name, axis, ctx):
    """A width/height attribute: a length, None for auto (absent, 'auto',
    invalid)."""
    s = el.get(name)
    if s is None or s.strip() == 'auto':
        return None
    return parse_length(s, axis, ctx)


def convert_image(el, state, cache, parent):
    """An ``image`` element to an ImageNode appended to ``parent`` (inside a
    Group when it has a transform or group effects); nothing when it is
    hidden, of zero size, or the image cannot be used (then one
    RasterWarning says why)."""
    inh, own = style_of(el, state.inh, state.own, cache)
    hidden = inh.get('visibility', 'visible') in ('hidden', 'collapse')
    ctx = length_context(inh, state, cache)
    t = transform_of(el, own, ctx)
    if t is None:
        return
    w = _size_attr(el, 'width', 'x', ctx)
    h = _size_attr(el, 'height', 'y', ctx)
    if (w is not None and not w > 0) or (h is not None and not h > 0):
        return
    href = el.get('href')
    if href is None:
        href = el.get(XLINK_HREF)
    if href is None or not href.strip():
        return
    tol = float(cache.options.tolerance)
    try:
        img = load_image(href, cache, tol)
    except ImageError as e:
        cache.warn(('image', str(e)), 'image not rendered: %s' % e)
        return
    if isinstance(img, np.ndarray):
        iw, ih = float(img.shape[1]), float(img.shape[0])
        tree = None
    else:
        iw, ih = float(img.width), float(img.height)
        tree = img
    if not (iw > 0 and ih > 0):
        return
    if w is None and h is None:
        w, h = iw, ih
    elif w is None:
        w = h * iw / ih
    elif h is None:
        h = w * ih / iw
    x = length(el, 'x', 'x', ctx)
    y = length(el, 'y', 'y', ctx)
    par = parse_preserve_aspect_ratio(el.get('preserveAspectRatio', ''))
    try:
        m = viewbox_transform((0.0, 0.0, iw, ih), par, w, h, x, y)
    except RasterError:
        return
    if tree is not None:
        # the image document's tolerance is in its own pixels: when it is
        # scaled up, rebuild it finer (by powers of two, so uses share)
        scale = (state.ctm @ t @ m).max_scale()
        if scale > 1.0 and math.isfinite(scale):
            fine = tol * 2.0 ** math.floor(math.log2(1.0 / scale))
            try:
                tree = load_image(href, cache, max(fine, 1e-9))
            except ImageError as e:
                cache.warn(('image', str(e)), 'image not rendered: %s' % e)
                return
    clip = None
    slice_ = par is not None and par[0] != 'none' and par[1] == 'slice'
    if tree is not None or slice_:
        # visible part: the image's box (under m) within the viewport
        x0 = max(x, m.e)
        y0 = max(y, m.f)
        x1 = min(x + w, m.e + m.a * iw)
        y1 = min(y + h, m.f + m.d * ih)
        if not (x1 > x0 and y1 > y0):
            return
        clip = (x0, y0, x1 - x0, y1 - y0)
    smooth = inh.get('image-rendering', 'auto').strip() not in _NEAREST
    node = ImageNode(id=el.get('id') or '', view_rect=(x, y, w, h), transform=m, clip=clip,
                     pixels=None if tree is not None else img, tree=tree, smooth=smooth)
    cache.note_id(el, node)
    # group effects; an object bounding box (clip path / mask units) is the
    # image's viewport, so effects see a rectangle standing in for the image
    proxy = [PathNode(path=rect_path(x, y, w, h))]
    e = effects(el, own, state.sub(transform=t), cache, proxy)
    if not e.ok:
        return
    if hidden or e.opacity <= 0.0:
        # rendered but invisible: its viewport still counts in its
        # parent's object bounding box
        if not state.clip:
            emit(proxy[0], t, NO_EFFECTS, cache, parent)
        return
    if not e.composited:
        node.opacity = e.opacity        # drawn in one pass: no layer needed
        e = dataclasses.replace(e, opacity=1.0)
    emit(node, t, e, cache, parent)
