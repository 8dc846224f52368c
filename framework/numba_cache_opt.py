"""Kernels compiled below numba's full optimisation level are cached apart from the others.

numba's cache key holds the signature, the machine and the source, not the optimisation level
(NUMBA_OPT, 3 by default): a kernel compiled at NUMBA_OPT=2, which compiles faster and may run
slower, would be loaded by every later run at the full level. Below the full level a kernel is
saved here under a key that also names its level, and loading tries the full level's key first:
such a process uses the fully optimised kernels the cache holds and compiles only the rest at
its own level, and a run at the full level never loads those. The test suite runs at
NUMBA_OPT=2 (scripts/test) after the shipped decks' kernels were compiled at the full level.
Importing this module installs it once (framework/__init__.py does).
"""
from __future__ import annotations

from numba.core import caching as _caching
from numba.core import config as _config

FULL_LEVEL = 3          # numba's default NUMBA_OPT


def opt_level():
    """This process's numba optimisation level: 0..3, or FULL_LEVEL for NUMBA_OPT=max."""
    level = _config.OPT
    return FULL_LEVEL if getattr(level, "is_opt_max", False) else int(level)


def load_keys(cache, sig, codegen):
    """The index keys a kernel may be loaded under in this process, in the order tried."""
    own = cache._index_key(sig, codegen)
    full = getattr(cache, "_pysus_full_key", None)
    return (own,) if full is None else (full(sig, codegen), own)


def _install():
    cache = _caching.Cache
    if getattr(cache._index_key, "_pysus_opt_apart", False) or opt_level() >= FULL_LEVEL:
        return
    full_key = cache._index_key
    mark = f"NUMBA_OPT={opt_level()}"

    def key_at_this_level(self, sig, codegen):
        sig_, machine, source = full_key(self, sig, codegen)
        return sig_, machine + (mark,), source

    def load_full_level_first(self, sig, target_context):
        if not self._enabled:
            return None
        for key in load_keys(self, sig, target_context.codegen()):
            data = self._cache_file.load(key)
            if data is not None:
                return self._impl.rebuild(target_context, data)
        return None

    key_at_this_level._pysus_opt_apart = True
    cache._index_key = key_at_this_level
    cache._pysus_full_key = full_key
    cache._load_overload = load_full_level_first


_install()
