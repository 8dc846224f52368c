"""numba checks that a kernel's cache directory can be written to when it decorates the kernel:
it makes the directory and creates and deletes a temporary file in it, once per kernel (432
files at the start of every MPMICE process, about 0.03 CPU s). The check is made once per
directory and process here; a directory that has gone since is made and checked again.
Importing this module installs it once (framework/scheduler/__init__.py does).
"""
from __future__ import annotations

import os

from numba.core import caching as _caching

_writable = set()       # cache directories this process has checked


def _install():
    locator = _caching._CacheLocator
    if getattr(locator.ensure_cache_path, "_pysus_once", False):
        return
    original = locator.ensure_cache_path

    def ensure_cache_path(self):
        path = self.get_cache_path()
        if path in _writable and os.path.isdir(path):
            return
        original(self)
        _writable.add(path)

    ensure_cache_path._pysus_once = True
    locator.ensure_cache_path = ensure_cache_path


_install()
