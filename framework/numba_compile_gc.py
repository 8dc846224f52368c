"""Python's cyclic garbage collector paused while numba compiles a kernel.

A compile builds hundreds of thousands of small objects (IR nodes, types, llvmlite
instructions), so the collector runs over and over during it and scans the whole heap at
every full collection: about a fifth of a kernel's compile (MPM's g2p, GIMP, 3D, MUSL: 3.9 ->
3.2 CPU s). The outermost Dispatcher.compile of a thread turns the collector off (where it
is on) and back on when it returns (nested compiles of the kernels it calls run inside it);
the cycles it left are collected afterwards as usual. Nothing else changes: the same typed
IR and machine code. Importing this module installs it once.
"""
from __future__ import annotations

import gc
import threading

from numba.core import dispatcher as _dispatcher

_state = threading.local()      # depth: Dispatcher.compile calls under way in this thread


def _install():
    cls = _dispatcher.Dispatcher
    if getattr(cls.compile, "_pysus_compile_gc", False):
        return
    original = cls.compile

    def compile(self, sig):
        depth = getattr(_state, "depth", 0)
        pause = depth == 0 and gc.isenabled()
        if pause:
            gc.disable()
        _state.depth = depth + 1
        try:
            return original(self, sig)
        finally:
            _state.depth = depth
            if pause:
                gc.enable()

    compile._pysus_compile_gc = True
    cls.compile = compile


_install()
