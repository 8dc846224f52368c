"""A kernel loaded from numba's cache needs numba's runtime (NRT) and the symbols numba's
modules put in LLVM's symbol table, not the lowering and typing registries: numba's
Cache.load_overload refreshes the whole target context before every load, which at the first
kernel of a process imports and installs numba's implementations of numpy, the typed
containers, random, linalg and the rest (0.13 CPU s of every pysus process's start). Here a
load from the cache makes ready only what loaded machine code calls: the runtime (its
initialisation also puts its functions in the symbol table) and the hash secret's symbols
(numba.cpython.hashing puts them there when imported); numba's C helpers and the C math
functions are in the table from the target context's creation, and a parallel kernel's
thread pool is started by its own reload hook. A kernel that is not in the cache compiles as
before (numba's compiler refreshes the context itself). Importing this module installs it once.
"""
from __future__ import annotations

from numba.core import caching as _caching
from numba.core.cpu import CPUContext as _CPUContext


def _ready_to_load(target_context):
    """What machine code loaded from the cache needs in this process (repeated calls are cheap)."""
    from numba.core.runtime import rtsys
    import numba.cpython.hashing  # noqa: F401   the _numba_hashsecret_* symbols
    rtsys.initialize(target_context)


def _install():
    cache = _caching.Cache
    if getattr(cache.load_overload, "_pysus_cache_load", False):
        return
    original = cache.load_overload

    def load_overload(self, sig, target_context):
        if type(target_context) is not _CPUContext:
            return original(self, sig, target_context)
        _ready_to_load(target_context)
        with self._guard_against_spurious_io_errors():
            return self._load_overload(sig, target_context)

    load_overload._pysus_cache_load = True
    cache.load_overload = load_overload


_install()
