"""Regular expressions compiled on first use.

Compiling a pattern runs the pure-Python ``re`` compiler: a few hundred
microseconds for the longer patterns of the parser and the path-data
lexer, tens of them loaded with every import, most of them never used by
a given document.  A module declares its patterns with :func:`lazy`; the
first use compiles the pattern and puts the compiled object in the
module's namespace in place of the stand-in, so every later use is a plain
global lookup of a compiled pattern.

>>> ns = {}
>>> ns['WORD'] = lazy(ns, 'WORD', r'[a-z]+')
>>> type(ns['WORD']).__name__
'LazyPattern'
>>> ns['WORD'].match('abc1').group()
'abc'
>>> type(ns['WORD']).__name__, ns['WORD'].pattern
('Pattern', '[a-z]+')
"""

import re

__all__ = ['LazyPattern', 'lazy']


class LazyPattern:
    """Stand-in for ``re.compile(pattern, flags)`` bound to ``name`` in the
    namespace ``ns``: any attribute (``match``, ``sub``, ``pattern`` ...)
    compiles the pattern, rebinds ``ns[name]`` to the compiled pattern
    (when it still holds this stand-in) and is read from it."""

    __slots__ = ('_ns', '_name', '_pattern', '_flags', '_compiled')

    def __init__(self, ns, name, pattern, flags=0):
        self._ns, self._name = ns, name
        self._pattern, self._flags = pattern, flags
        self._compiled = None

    def compiled(self):
        """The compiled pattern (compiled once)."""
        c = self._compiled
        if c is None:
            c = self._compiled = re.compile(self._pattern, self._flags)
            if self._ns.get(self._name) is self:
                self._ns[self._name] = c
        return c

    def __getattr__(self, attr):
        return getattr(self.compiled(), attr)

    def __repr__(self):
        return 'LazyPattern(%r)' % (self._pattern,)


def lazy(ns, name, pattern, flags=0):
    """``ns[name] = lazy(ns, name, pattern, flags)`` (``ns`` is the module's
    ``globals()``): a :class:`LazyPattern` that becomes
    ``re.compile(pattern, flags)`` in ``ns`` on first use."""
    return LazyPattern(ns, name, pattern, flags)
