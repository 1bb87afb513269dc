"""libFuzzer (atheris) on the SVG front door: ``python atheris_render.py
[libFuzzer flags]``, e.g. ``-max_total_time=600 -timeout=20 -rss_limit_mb=1024``
(libFuzzer's own budget per input: a slow or greedy input is a finding).

Each input is used twice: as raw bytes of a document, and as the seed of
the document grammar of ``_fuzz_grammar.py`` (structure-aware: the
mutations reach deep into valid documents).  A finding is any exception
other than :class:`raster.errors.RasterError`, a warning other than a
:class:`raster.errors.RasterWarning` (numpy's floating-point warnings
included), or a message of more than one line; libFuzzer writes the input
to ``crash-*`` and it becomes a case of ``tests/hostile/``.
"""

import os
import sys
import warnings

import atheris

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

with atheris.instrument_imports():
    import raster
    from raster.errors import RasterError, RasterWarning
    import _fuzz_grammar as grammar


def _render(data):
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter('error')
            warnings.simplefilter('always', RasterWarning)
            raster.render(data, width=48)
    except RasterError as e:
        if '\n' in str(e):
            raise AssertionError('error of several lines: %r' % str(e))
        return
    for w in caught:
        if '\n' in str(w.message):
            raise AssertionError('warning of several lines: %r' % str(w.message))


def test_one_input(data):
    _render(data)
    _render(grammar.seeded(grammar.document, data).encode('utf-8'))


def main():
    atheris.Setup(sys.argv, test_one_input)
    atheris.Fuzz()


if __name__ == '__main__':
    main()
