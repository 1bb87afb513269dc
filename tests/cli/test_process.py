"""What the commands do to their own process: Python's garbage collector
is paused while a command's body runs and restored afterwards, the run's
objects frozen when the command is its process's own (the library never
touches it: tests/parser/test_parser.py)."""

import gc

import pytest

from raster_cli import _common
from raster_cli.rasterize import main as rasterize

SVG = b'<svg xmlns="http://www.w3.org/2000/svg" width="6" height="4"><rect width="3" height="4"/></svg>'


def test_collector_paused_restores_the_state():
    assert gc.isenabled()
    with _common.collector_paused():
        assert not gc.isenabled()
    assert gc.isenabled()
    gc.disable()
    try:
        with _common.collector_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()          # left as the caller had it
    finally:
        gc.enable()
    with pytest.raises(KeyError):
        with _common.collector_paused():
            raise KeyError('x')
    assert gc.isenabled()


def test_a_command_body_runs_with_the_collector_paused(monkeypatch, tmp_path):
    seen = []
    real = _common.read_source

    def spy(path):
        seen.append(gc.isenabled())
        return real(path)
    monkeypatch.setattr('raster_cli.rasterize.read_source', spy)
    src = tmp_path / 'a.svg'
    src.write_bytes(SVG)
    assert rasterize([str(src), str(tmp_path / 'a.png')]) == 0
    assert seen == [False] and gc.isenabled()
    # a failing run restores it too
    assert rasterize([str(tmp_path / 'missing.svg'), str(tmp_path / 'b.png')]) == 1
    assert gc.isenabled()


def test_freezing_moves_the_objects_of_the_block_to_the_permanent_generation():
    assert gc.get_freeze_count() == 0
    try:
        with _common.collector_paused(freeze=True):
            made = [[i] for i in range(1000)]
        assert gc.isenabled() and gc.get_freeze_count() >= len(made)
    finally:
        gc.unfreeze()
    gc.disable()
    try:
        with _common.collector_paused(freeze=True):
            pass
        assert not gc.isenabled()       # left as the caller had it, nothing frozen
    finally:
        gc.enable()
    assert gc.get_freeze_count() == 0


def test_a_command_called_with_arguments_freezes_nothing(tmp_path):
    src = tmp_path / 'a.svg'
    src.write_bytes(SVG)
    assert rasterize([str(src), str(tmp_path / 'a.png')]) == 0
    assert gc.get_freeze_count() == 0 and gc.isenabled()


def run_code(code, env_extra=None):
    """The words ``code`` prints in a child without the user's BLAS and
    malloc settings (plus ``env_extra``)."""
    import os
    import subprocess
    import sys
    env = {k: v for k, v in os.environ.items()
           if k not in ('OPENBLAS_NUM_THREADS', 'GLIBC_TUNABLES') and not k.startswith('MALLOC_')}
    env.update(env_extra or {})
    return subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          env=env, check=True).stdout.split()


# a command's run() with argv %s (None: from the command line)
COMMAND = """
import os, sys
from raster_cli import _common
sys.argv = ['rasterize', '--version']
try:
    _common.run('rasterize', lambda a: 0, _common.Parser(prog='rasterize'), %s)
except SystemExit:
    pass
"""

BLAS = COMMAND + """print(os.environ.get('OPENBLAS_NUM_THREADS', '-'))
"""


def test_from_the_command_line_numpy_gets_one_blas_thread():
    assert run_code(BLAS % 'None') == ['1']
    assert run_code(BLAS % 'None', {'OPENBLAS_NUM_THREADS': '3'}) == ['3']   # the user's
    assert run_code(BLAS % '[]') == ['-']          # called with arguments: not a command line
    assert run_code('import numpy\n' + BLAS % 'None') == ['-']    # numpy already loaded


FROZEN = '''
import gc, sys
from raster_cli import _common
_common.run('rasterize', lambda a: print(gc.get_freeze_count()), _common.Parser(prog='rasterize'), %s)
print(gc.get_freeze_count(), gc.isenabled())
'''


def test_from_the_command_line_the_objects_of_the_run_are_frozen():
    before, after, enabled = run_code(FROZEN % 'None')
    assert before == '0' and int(after) > 1000 and enabled == 'True'
    assert run_code(FROZEN % '[]') == ['0', '0', 'True']



HEAP = """
import ctypes, sys
calls = []

class _Mallopt:
    argtypes = None

    def __call__(self, param, value):
        calls.append((param, value))
        return 1

class _Libc:
    mallopt = _Mallopt()

ctypes.CDLL = lambda name: _Libc()          # records instead of setting
%s
print(*[f'{p}:{v}' for p, v in calls])
"""

RENDER = """
import raster
raster.render(b'<svg xmlns="http://www.w3.org/2000/svg" width="8" height="8"><circle r="4"/></svg>')
"""


def _glibc():
    import os
    try:
        return bool(os.confstr('CS_GNU_LIBC_VERSION'))
    except (ValueError, OSError, AttributeError):
        return False


def test_from_the_command_line_malloc_gets_fixed_thresholds():
    # a command's own process fixes glibc's thresholds (M_MMAP_THRESHOLD -3,
    # M_TRIM_THRESHOLD -1); not when called with arguments, not when the
    # user tuned malloc, and on other C libraries not at all
    want = ['-3:%d' % _common.HEAP_MMAP_THRESHOLD, '-1:%d' % _common.HEAP_TRIM_THRESHOLD]
    assert run_code(HEAP % (COMMAND % 'None')) == (want if _glibc() else [])
    assert run_code(HEAP % (COMMAND % '[]')) == []
    assert run_code(HEAP % (COMMAND % 'None'), {'MALLOC_ARENA_MAX': '2'}) == []
    assert run_code(HEAP % (COMMAND % 'None'),
                    {'GLIBC_TUNABLES': 'glibc.malloc.tcache_count=0'}) == []


def test_the_library_leaves_malloc_alone():
    assert run_code(HEAP % RENDER) == []


def test_the_real_mallopt_takes_the_thresholds():
    got = run_code('from raster_cli import _common\nprint(_common.steady_heap())')
    assert got == (['True'] if _glibc() else ['False'])
