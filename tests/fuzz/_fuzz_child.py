"""Renders in a child process under a time and memory budget.

:func:`render_in_child` forks a child from a server that has imported
raster once, gives it an address-space limit, renders the document there
and reports what escaped:

* ``('ok', drawn)`` -- rendered; ``drawn``: some pixel is not transparent;
* ``('raster-error', message)`` -- a :class:`raster.errors.RasterError`
  (allowed: bad input says so);
* ``('bug', text)`` -- anything else: another exception, a warning that is
  not a :class:`raster.errors.RasterWarning` (numpy floating-point
  warnings included: they are errors in the child), a message of more than
  one line, a crash, or no answer within the time budget.

The budgets are guards against hangs and runaway memory, not timings.
"""

import multiprocessing
import resource
import traceback
import warnings

#: Address space of a child, bytes.
MEMORY = 1 << 30
#: Seconds a child may take before it counts as hung.
TIME = 60

_CTX = multiprocessing.get_context('forkserver')
_CTX.set_forkserver_preload(['raster', 'raster.svg', 'numpy', 'PIL.Image'])


def _render(conn, data, width):
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
    import raster
    from raster.errors import RasterError, RasterWarning
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter('error')
            warnings.simplefilter('always', RasterWarning)
            img = raster.render(data, width=width)
        bad = [str(w.message) for w in caught if '\n' in str(w.message)]
        if bad:
            conn.send(('bug', 'warning of several lines: %r' % bad[0]))
        else:
            conn.send(('ok', bool(img[..., 3].any())))
    except RasterError as e:
        msg = str(e)
        conn.send(('bug', 'error of several lines: %r' % msg) if '\n' in msg
                  else ('raster-error', msg))
    except BaseException:
        conn.send(('bug', traceback.format_exc()))
    conn.close()


def render_in_child(data, width=None):
    """Render ``data`` (the document as bytes) in a child; see the module
    docstring for the answers."""
    here, there = _CTX.Pipe(duplex=False)
    p = _CTX.Process(target=_render, args=(there, data, width))
    p.start()
    there.close()
    try:
        if here.poll(TIME):
            try:
                return here.recv()
            except EOFError:
                pass
        else:
            p.kill()
            return ('bug', 'no answer in %d s' % TIME)
    finally:
        p.join(TIME)
        if p.is_alive():
            p.kill()
            p.join()
        here.close()
    return ('bug', 'child died (exit status %s)' % p.exitcode)
