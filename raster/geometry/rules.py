"""String-valued enumerations of the kernel, and the fill rule.

Members of a :class:`StrChoice` are ``str`` instances equal to (and hashing
like) their values, so code and data that use the SVG keywords keep working:
``FillRule.EVENODD == 'evenodd'``, and ``str()`` / ``format()`` give the
keyword.

>>> FillRule.lookup('evenodd') is FillRule.EVENODD, FillRule.lookup('odd')
(True, None)
>>> '%s' % FillRule.NONZERO, FillRule.values()
('nonzero', ('nonzero', 'evenodd'))
"""

import enum
from typing import Any, Optional, Tuple

__all__ = ['StrChoice', 'FillRule']


class StrChoice(str, enum.Enum):
    """Base of the kernel's string-valued enumerations (no members)."""

    __str__ = str.__str__
    __format__ = str.__format__

    @classmethod
    def lookup(cls, value: Any) -> Optional['StrChoice']:
        """The member for ``value`` (a member or its string value), or None
        for anything else."""
        try:
            return cls._value2member_map_.get(value)
        except TypeError:                     # unhashable
            return None

    @classmethod
    def values(cls) -> Tuple[str, ...]:
        """The keywords, in definition order."""
        return tuple(m.value for m in cls)


class FillRule(StrChoice):
    """Which points a closed path fills (SVG ``fill-rule``,
    ``clip-rule``): ``nonzero`` winding number, or an odd one."""

    NONZERO = 'nonzero'
    EVENODD = 'evenodd'
