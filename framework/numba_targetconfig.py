"""Faster comparison of numba's compile flags: the same values, equality and hash, computed
without one property call per option.

numba keys each overload template's implementation cache by the compile flags
(templates._get_impl), so every typing of an operator, a ufunc or an overloaded function
hashes a Flags object and compares it with the cached one; TargetConfig.values builds a dict
of all ~30 options through their properties each time, and hash and == call it. That was a
tenth of ICE's first-run compile. Here values() is the class's defaults updated by the
options set, equality of two configs of one class with the same options set needs no dict
at all, and the hash (numba's hashes the sorted option names only) is computed once per
class. Importing this module installs it once.
"""
from __future__ import annotations

from numba.core import targetconfig as _tc

ENABLED = True      # False: numba's own methods (for comparison in tests)

_defaults = {}      # TargetConfig subclass -> ({option: default} in option order, numba's hash)


def _class_defaults(cls):
    got = _defaults.get(cls)
    if got is None:
        values = {name: option.default for name, option in cls.options.items()}
        got = _defaults[cls] = (values, hash(tuple(sorted(values))))
    return got


def values(self):
    """A dict of every option's value, in option order (numba's TargetConfig.values)."""
    if not ENABLED:
        return _numba_values(self)
    defaults = _class_defaults(type(self))[0]
    own = self._values
    if not own.keys() <= defaults.keys():       # copied from another kind of config
        return _numba_values(self)
    out = dict(defaults)
    out.update(own)
    return out


def __eq__(self, other):
    if not isinstance(other, _tc.TargetConfig):
        return NotImplemented
    if ENABLED and type(self) is type(other) and self._values == other._values:
        return True
    return values(self) == values(other)


def __hash__(self):
    if not ENABLED:
        return _numba_hash(self)
    return _class_defaults(type(self))[1]


def _numba_as_expected():
    """TargetConfig as numba 0.59-0.68 has it: option properties over a `_values` dict,
    equality by values(), the hash of the sorted option names."""
    cls = _tc.TargetConfig
    return "_values" in getattr(cls, "__slots__", ()) \
        and isinstance(getattr(cls, "options", None), _tc.MappingProxyType) \
        and all(getattr(cls, name).__module__ == _tc.__name__ for name in ("values", "__eq__", "__hash__"))


_numba_values = _tc.TargetConfig.values
_numba_hash = _tc.TargetConfig.__hash__
if _numba_as_expected():
    _tc.TargetConfig.values = values
    _tc.TargetConfig.__eq__ = __eq__
    _tc.TargetConfig.__hash__ = __hash__
