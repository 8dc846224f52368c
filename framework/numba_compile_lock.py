"""One process compiles a cached numba kernel while the others wait, then load it from the cache.

MPI ranks, test workers and batch jobs that start together on a cold cache would each compile
the same kernels at once (the same CPU spent N times, N times the memory). A file lock beside
the kernel's cache index (`<index>.lock`, in numba's cache directory) serialises numba's
Dispatcher.compile across processes: the first compiles and saves, the next finds the kernel
in the cache. Kernels without cache=True, recursion within one process and file systems
without flock compile as before. A kernel already in the cache is loaded without the lock (ranks
starting together on a warm cache do not queue behind each other). Importing this module
installs it once.
"""
from __future__ import annotations

import fcntl
import os
import time

from numba.core import dispatcher as _dispatcher
from numba.core import sigutils as _sigutils

from framework.numba_cache_opt import load_keys

WAIT_LIMIT_S = 900.0        # a holder that long (stopped, hung) is passed: compile regardless
_held = set()               # lock files this process holds (nested and recursive compiles)


def _lock_path(disp):
    cache_file = getattr(getattr(disp, "_cache", None), "_cache_file", None)
    index = getattr(cache_file, "_index_path", None)
    return None if index is None else index + ".lock"


def _in_cache(disp, sig):
    """Whether numba's cache index holds this signature (then loading needs no lock)."""
    try:
        cache = disp._cache
        index = cache._cache_file._load_index()
        return any(key in index for key in load_keys(cache, sig, disp.targetctx.codegen()))
    except Exception:                       # numba's private API moved: take the lock
        return False


def _acquire(path):
    """An exclusive flock on path, or None where the file system does not allow it."""
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        fd = os.open(path, os.O_CREAT | os.O_RDWR, 0o666)
    except OSError:
        return None
    start, pause = time.monotonic(), 0.002
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return fd
        except BlockingIOError:
            if time.monotonic() - start > WAIT_LIMIT_S:
                os.close(fd)
                return None
            time.sleep(pause)
            pause = min(0.02, 2 * pause)    # the holder's release is seen within 20 ms
        except OSError:
            os.close(fd)
            return None


def _install():
    cls = _dispatcher.Dispatcher
    if getattr(cls.compile, "_pysus_compile_lock", False):
        return
    original = cls.compile

    def compile(self, sig):
        path = _lock_path(self)
        if path is None or path in _held:
            return original(self, sig)
        args, _ = _sigutils.normalize_signature(sig)
        if self.overloads.get(tuple(args)) is not None or _in_cache(self, sig):
            return original(self, sig)
        fd = _acquire(path)
        if fd is None:
            return original(self, sig)
        _held.add(path)
        try:
            return original(self, sig)      # loads what another process saved meanwhile
        finally:
            _held.discard(path)
            fcntl.flock(fd, fcntl.LOCK_UN)
            os.close(fd)

    compile._pysus_compile_lock = True
    cls.compile = compile


_install()
