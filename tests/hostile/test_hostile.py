"""The hostile-input corpus: every case of ``expected.json`` run as a user
runs it (the command in a child process), with its expected outcome.

For every case: the exit status; stderr is one line per message (no
traceback, no object repr, no temporary file name, no file contents, no
numpy floating-point warning) and
matches the expected pattern; when the rest of the document is expected
to be drawn, the output holds the document's red square.  Each case runs
the command's ``main`` in a child process forked from a server that has
imported raster once, with 1 GB of address space and a generous guard
against hangs; these are not timings (``bench/bench_hostile.py`` measures
time and peak memory of fresh processes).
"""

import importlib
import json
import multiprocessing
import os
import re
import resource
import sys

import numpy as np
import pytest

import _hostile_generate as generate

HERE = os.path.dirname(os.path.abspath(__file__))
with open(os.path.join(HERE, 'expected.json')) as f:
    EXPECTED = {k: v for k, v in json.load(f).items() if not k.startswith('_')}

#: Address space of a child (bytes) and the guard against hangs (s).
MEMORY = 1 << 30
HANG = 120

_COMMANDS = {'rasterize': 'raster_cli.rasterize', 'svg-bbox': 'raster_cli.svg_bbox',
             'svg-flatten': 'raster_cli.svg_flatten'}

# children fork from a server that has imported the commands once (a fresh
# interpreter per case would spend most of the run importing numpy)
_CTX = multiprocessing.get_context('forkserver')
_CTX.set_forkserver_preload(['raster', 'raster.svg'] + sorted(_COMMANDS.values()))


def _child(module, argv, cwd, stdin, err_path):
    """Run one command the way its console script does, in this (forked)
    process: its own address-space limit, stdin and stderr."""
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
    os.chdir(cwd)
    fd = os.open(err_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
    os.dup2(fd, 2)
    sys.stderr = open(2, 'w', closefd=False, buffering=1)
    if stdin is not None:
        fd = os.open(stdin, os.O_RDONLY)
        os.dup2(fd, 0)
        sys.stdin = open(0, 'r', closefd=False)
    rc = importlib.import_module(module).main(argv)
    sys.stderr.flush()
    os._exit(rc)


def run_case(case, tmp):
    """(status, stderr lines, output path) of one case run in a child."""
    spec = case['input']
    args = list(case.get('args', ()))
    stdin = None
    if spec.startswith('gen:'):
        made = getattr(generate, spec[4:])(str(tmp))
        if isinstance(made, tuple):
            made, more = made
            args += more
        source = made
    elif spec == 'zeros':
        source, stdin = '-', '/dev/zero'
    elif os.path.isabs(spec):
        source = spec
    else:
        source = os.path.join(HERE, spec)
    command = case.get('command', 'rasterize')
    out = os.path.join(str(tmp), 'out.png')
    argv = [source] + ([out] if command == 'rasterize' else ['-o', out]) + args
    err = os.path.join(str(tmp), 'stderr.txt')
    p = _CTX.Process(target=_child, args=(_COMMANDS[command], argv, str(tmp), stdin, err))
    p.start()
    p.join(HANG)
    if p.is_alive():
        p.kill()
        p.join()
        pytest.fail('%s did not finish in %d s' % (spec, HANG))
    with open(err, 'rb') as f:
        lines = f.read().decode('utf-8', 'replace').splitlines()
    return p.exitcode, lines, out


def red_square(path):
    from PIL import Image
    with Image.open(path) as im:
        px = np.asarray(im.convert('RGBA'))[5, 5]
    return px.tolist() == [255, 0, 0, 255]


@pytest.mark.parametrize('name', sorted(EXPECTED))
def test_hostile_case(name, tmp_path):
    case = EXPECTED[name]
    status, lines, out = run_case(case, tmp_path)
    shown = ' | '.join(lines)
    assert status == case['status'], shown
    for ln in lines:
        assert re.match(r'[a-z-]+: (warning|error): \S', ln), shown      # one line each
        assert 'Traceback' not in ln and ' at 0x' not in ln and '.tmp' not in ln, shown
        assert 'root:' not in ln, shown                                 # no /etc/passwd
        assert 'encountered in' not in ln, shown          # numpy's floating-point warnings
    msg = case['message']
    if msg is None:
        assert lines == [], shown
    elif msg != 'any':
        assert 1 <= len(lines) <= case.get('lines', 1), shown
        for ln in lines:
            assert re.search(msg, ln), shown
    if 'contains' in case:
        assert any(case['contains'] in ln for ln in lines), shown
    if case.get('drawn'):
        assert red_square(out), shown


def test_every_case_file_has_an_expectation():
    listed = {c['input'] for c in EXPECTED.values()}
    for f in os.listdir(os.path.join(HERE, 'cases')):
        assert 'cases/' + f in listed, f
    for c in EXPECTED.values():
        if c['input'].startswith('gen:'):
            assert callable(getattr(generate, c['input'][4:], None)), c['input']
