"""Rendering on a Dask cluster (the optional extra ``pip install
'raster-svg[dask]'``: dask and distributed).

* :func:`render_array` -- one document as a lazy ``dask.array.Array`` of
  shape ``(H, W, 4)`` uint8 (straight alpha), each chunk a window of the
  render (:func:`raster.renderer.render_tree` with ``window``) drawn on
  whichever worker computes it; store it (``to_zarr``), reduce it or slice
  it like any dask array: only the chunks needed are rendered.
* :func:`render_files` -- batch conversion of many files mapped over a
  cluster (a ``distributed.Client``), one result record per file.

The document's bytes travel in the task graph once; each worker process
parses a document once and keeps the last few parsed trees for the chunks
it computes.  Paths (the documents of :func:`render_files`, the images a
document references) are read on the workers: they need the files at the
same paths (a shared file system).

>>> import numpy as np
>>> doc = (b'<svg xmlns="http://www.w3.org/2000/svg" width="6" height="4">'
...        b'<rect width="3" height="4" fill="red"/></svg>')
>>> arr = render_array(doc, chunks=(2, 4))
>>> arr.shape, arr.chunks[:2]
((4, 6, 4), ((2, 2), (4, 2)))
>>> img = arr.compute(scheduler='sync')
>>> img[0, 0].tolist(), img[3, 5].tolist()
([255, 0, 0, 255], [0, 0, 0, 0])
"""

import hashlib
import os
import pickle
from collections import OrderedDict
from typing import Any, Dict, Iterable, List, Optional, Tuple, Union

import numpy as np

from .errors import RasterError, SVGError
from .sources import local_path, read_file

__all__ = ['render_array', 'render_files', 'MAX_DOCUMENT_BYTES']

#: Largest document :func:`render_array` reads and ships to the workers.
MAX_DOCUMENT_BYTES = 256 * 1024 * 1024

_LOAD_KEYS = ('dpi', 'fonts', 'resources_dir', 'languages')
_RENDER_KEYS = ('zoom', 'background', 'id', 'tolerance', 'crop')


def _split(options):
    """(load options, render options) of the keyword arguments."""
    bad = sorted(set(options) - set(_LOAD_KEYS) - set(_RENDER_KEYS) - {'premultiplied'})
    if bad:
        raise TypeError('unknown option(s) %s (known: %s)'
                        % (', '.join(bad), ', '.join(_LOAD_KEYS + _RENDER_KEYS
                                                     + ('premultiplied',))))
    load = {k: options[k] for k in _LOAD_KEYS if k in options}
    if 'languages' in load:
        load['languages'] = tuple(load['languages'])
    render = {k: options[k] for k in _RENDER_KEYS if k in options}
    return load, render


def _document(source):
    """(document bytes, base directory or None) of a source."""
    if isinstance(source, (bytes, bytearray)):
        return bytes(source), None
    if isinstance(source, str) and source.lstrip().startswith('<'):
        return source.encode('utf-8'), None
    if hasattr(source, 'read'):
        return source.read(MAX_DOCUMENT_BYTES + 1), None
    path = local_path(source)
    return (read_file(path, MAX_DOCUMENT_BYTES),
            os.path.dirname(os.path.abspath(path)))


#: Trees parsed in this process: token -> (tree, output geometry).
_TREES: 'OrderedDict[str, Tuple[Any, Any]]' = OrderedDict()
_TREES_KEPT = 4


def _tree(token, data, base, load, size, render):
    """The parsed tree and the output geometry of a document, parsed once
    per process (the last :data:`_TREES_KEPT` kept)."""
    hit = _TREES.get(token)
    if hit is not None:
        _TREES.move_to_end(token)
        return hit
    from .renderer import MAX_WINDOWED_PIXELS, output_geometry
    from .svg import load_svg
    tree = load_svg(data, base_dir=base, **load)
    crop = bool(render.get('crop')) and render.get('id') is not None
    g = output_geometry(tree, size[0], size[1], render.get('zoom'), render.get('id'), crop,
                        max_pixels=MAX_WINDOWED_PIXELS)
    _TREES[token] = (tree, g)
    while len(_TREES) > _TREES_KEPT:
        _TREES.popitem(last=False)
    return tree, g


def _render_chunk(data, spec, window):
    """One chunk: ``(y1 - y0, x1 - x0, 4)`` uint8 RGBA of the window."""
    from .renderer import DEFAULT_TOLERANCE, render_tree
    from .svg import parse_background
    token, base, load, size, render, premultiplied = spec
    tree, _ = _tree(token, data, base, load, size, render)
    crop = bool(render.get('crop')) and render.get('id') is not None
    canvas = render_tree(tree, width=size[0], height=size[1], zoom=render.get('zoom'),
                         background=parse_background(render.get('background')),
                         node_id=render.get('id'),
                         tolerance=render.get('tolerance', DEFAULT_TOLERANCE), crop=crop,
                         dtype=np.uint8, window=window)
    return canvas.to_rgba8(premultiplied=premultiplied)


def _chunk_sizes(total, size):
    size = int(size)
    if size < 1:
        raise SVGError('chunks must be positive, got %r' % (size,))
    return tuple(min(size, total - s) for s in range(0, total, size))


def render_array(source, width: Optional[int] = None, height: Optional[int] = None,
                 chunks: Union[int, Tuple[int, int]] = 2048, **options):
    """A document's render as a lazy dask array.

    Parameters
    ----------
    source : str, os.PathLike, bytes or binary file object
        The document (as for :func:`raster.render`); read here, once, and
        shipped to the workers in the task graph.
    width, height : int or None
        Output size in pixels (as for :func:`raster.render`); the whole
        output may be up to :data:`raster.renderer.MAX_WINDOWED_PIXELS`.
    chunks : int or (int, int)
        Rows and columns of a chunk (one number: square chunks); each
        chunk is at most :data:`raster.limits.MAX_PIXELS` pixels.
    **options
        ``dpi``, ``fonts``, ``resources_dir``, ``languages`` (loading),
        ``zoom``, ``background``, ``id``, ``crop``, ``tolerance`` and
        ``premultiplied`` (rendering), as for :func:`raster.render`.

    Returns
    -------
    dask.array.Array
        Shape ``(H, W, 4)``, dtype uint8, straight alpha (premultiplied
        with ``premultiplied=True``), chunks ``(rows, columns, 4)``; a
        chunk equals that part of :func:`raster.render`'s image (to
        within one level where a blur's sums round differently).

    Raises
    ------
    raster.errors.SVGError, raster.errors.CanvasError
        Bad document, options or size (found here, before any chunk).
    TypeError
        An unknown option.
    ImportError
        dask is not installed.
    """
    import dask.array as da
    from dask.highlevelgraph import HighLevelGraph
    load, render = _split(options)
    premultiplied = bool(options.get('premultiplied', False))
    data, base = _document(source)
    if len(data) > MAX_DOCUMENT_BYTES:
        raise SVGError('document exceeds %d bytes' % MAX_DOCUMENT_BYTES)
    token = hashlib.sha256(data + pickle.dumps((base, load, (width, height), render))).hexdigest()
    _tree(token, data, base, load, (width, height), render)     # errors here, not on a worker
    g = _TREES[token][1]
    cy, cx = (chunks, chunks) if np.ndim(chunks) == 0 else tuple(chunks)
    rows, cols = _chunk_sizes(g.height, cy), _chunk_sizes(g.width, cx)
    from . import limits
    if max(rows) * max(cols) > limits.MAX_PIXELS:
        raise SVGError('chunks of %d x %d exceed %d pixels' % (max(cols), max(rows),
                                                              limits.MAX_PIXELS))
    name = 'raster-render-' + token[:32] + '-%d-%d' % (cy, cx)
    doc_key = 'raster-document-' + token[:32]
    spec = (token, base, load, (width, height), render, premultiplied)
    dsk = {doc_key: data}
    y = 0
    for i, h in enumerate(rows):
        x = 0
        for j, w in enumerate(cols):
            dsk[(name, i, j, 0)] = (_render_chunk, doc_key, spec, (x, y, x + w, y + h))
            x += w
        y += h
    graph = HighLevelGraph.from_collections(name, dsk, dependencies=())
    return da.Array(graph, name, chunks=(rows, cols, (4,)), dtype=np.uint8)


def _convert_file(path, out, options):
    """Render one file to ``out`` (written atomically); the result record."""
    from .pixels.encode import encode, format_of_path
    from .svg import render
    try:
        img = render(path, **options)
        fmt = format_of_path(out) or 'png'
        data = encode(img, fmt)
        d = os.path.dirname(out)
        if d:
            os.makedirs(d, exist_ok=True)
        tmp = '%s.%s.tmp' % (out, os.urandom(6).hex())
        try:
            with open(tmp, 'wb') as f:
                f.write(data)
            os.replace(tmp, out)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
        return {'input': path, 'output': out, 'error': None}
    except (RasterError, OSError, MemoryError, ValueError) as e:
        msg = ' '.join(str(e).split()) or type(e).__name__
        if isinstance(e, OSError) and e.filename and str(e.filename) not in msg:
            msg = '%s: %s' % (e.filename, e.strerror or msg)
        return {'input': path, 'output': None, 'error': msg}


def render_files(inputs: Iterable[Union[str, 'os.PathLike[str]']], out_dir: str,
                 client=None, pattern: str = '{stem}.png',
                 **options) -> List[Dict[str, Optional[str]]]:
    """Convert many files on a cluster.

    Parameters
    ----------
    inputs : iterable of paths
        SVG/SVGZ files, read on the workers.
    out_dir : str
        Folder of the outputs (made on the workers where missing).
    client : distributed.Client or None
        Where to run (None: the current client, ``distributed.get_client()``,
        else dask's default scheduler in this process).
    pattern : str
        Output file name with the fields ``{stem}`` (the input's name
        without ``.svg``/``.svgz``) and ``{name}``; its extension chooses
        the format (``.png``, ``.jpg``, ``.webp``, ``.tif``, ``.bmp``).
    **options
        As for :func:`raster.render` (``width``, ``height``, ``zoom``,
        ``dpi``, ``background``, ``fonts``...).

    Returns
    -------
    list of dict
        One record per input, in order: ``{'input': path, 'output': path
        written or None, 'error': one-line message or None}``.  A file
        that fails does not stop the others.
    """
    jobs = []
    for p in inputs:
        p = os.fspath(p)
        name = os.path.basename(p)
        stem = name
        for suf in ('.svgz', '.svg'):
            if stem.lower().endswith(suf):
                stem = stem[:-len(suf)]
                break
        jobs.append((p, os.path.join(out_dir, pattern.format(stem=stem, name=name))))
    if client is None:
        try:
            from distributed import get_client
            client = get_client()
        except (ImportError, ValueError):
            client = None
    if client is None:
        import dask
        tasks = [dask.delayed(_convert_file, pure=False)(p, o, options) for p, o in jobs]
        return list(dask.compute(*tasks))
    futures = client.map(_convert_file, [p for p, _ in jobs], [o for _, o in jobs],
                         [options] * len(jobs), pure=False)
    return client.gather(futures)
