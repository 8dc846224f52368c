"""Loading a kernel from numba's cache without what only compiling needs.

numba's Cache.load_overload refreshes the whole target context before every load, which at
the first kernel of a process imports and installs numba's implementations of numpy, the
typed containers, random, linalg and the rest (0.13 CPU s of every pysus process's start).
Machine code loaded from the cache needs only numba's runtime (NRT; its initialisation also
puts its functions in LLVM's symbol table) and the hash secret's symbols (numba.cpython.hashing
puts them there when imported); numba's C helpers and the C math functions are in the table
from the target context's creation, and a parallel kernel's thread pool is started by its own
reload hook. A kernel that is not in the cache compiles as before (numba's compiler refreshes
the context itself).

A cached library is machine code (an object file) and the bitcode of its module for linking
into other kernels; numba parses that bitcode at every load to list the symbols the library
defines (2 ms a kernel, 0.15 CPU s of the 51 kernels of an MPMICE run). Here the list is read
from the object file's symbol table (ELF; the same names, tests/framework/test_numba_cache_load.py)
and the bitcode is parsed only when a kernel being compiled links the library in; another
object format loads as numba does. Importing this module installs both once.
"""
from __future__ import annotations

import struct

import llvmlite.binding as _ll
from numba.core import caching as _caching
from numba.core import codegen as _codegen
from numba.core.cpu import CPUContext as _CPUContext

_SHT_SYMTAB, _STT_SECTION, _STT_FILE = 2, 3, 4


def elf_defined_symbols(obj: bytes):
    """The names of the symbols an ELF64 little-endian object file defines (named, not a section
    or file symbol, in a section); None for any other format."""
    if obj[:4] != b"\x7fELF" or obj[4] != 2 or obj[5] != 1:
        return None
    shoff, = struct.unpack_from("<Q", obj, 0x28)
    shentsize, shnum = struct.unpack_from("<HH", obj, 0x3A)
    names = set()
    for i in range(shnum):
        sh = shoff + i * shentsize
        if struct.unpack_from("<I", obj, sh + 4)[0] != _SHT_SYMTAB:
            continue
        offset, size = struct.unpack_from("<QQ", obj, sh + 0x18)
        link, = struct.unpack_from("<I", obj, sh + 0x28)
        entsize, = struct.unpack_from("<Q", obj, sh + 0x38)
        strings, = struct.unpack_from("<Q", obj, shoff + link * shentsize + 0x18)
        for sym in range(offset, offset + size, entsize):
            name, info, _, section = struct.unpack_from("<IBBH", obj, sym)
            if section == 0 or name == 0 or (info & 0xF) in (_STT_SECTION, _STT_FILE):
                continue
            start = strings + name
            names.add(obj[start:obj.index(b"\0", start)].decode())
    return names


def _ready_to_load(target_context):
    """What machine code loaded from the cache needs in this process (repeated calls are cheap)."""
    from numba.core.runtime import rtsys
    import numba.cpython.hashing  # noqa: F401   the _numba_hashsecret_* symbols
    rtsys.initialize(target_context)


def _numba_as_expected():
    """numba's code library as 0.59-0.68 has it: an object-code library unserialised from
    (object code, linking bitcode), its linking module kept in _shared_module, the engine's
    defined symbols in a set."""
    lib, engine = _codegen.JITCodeLibrary, _codegen.JitEngine
    return all(hasattr(lib, a) for a in ("_unserialize", "_get_module_for_linking", "enable_object_caching",
                                         "_set_compiled_object", "_finalize_final_module")) \
        and hasattr(engine, "_load_defined_symbols") and hasattr(_caching.Cache, "_guard_against_spurious_io_errors")


def _install():
    cache, lib = _caching.Cache, _codegen.JITCodeLibrary
    if getattr(cache.load_overload, "_pysus_cache_load", False) or not _numba_as_expected():
        return
    load_overload = cache.load_overload
    unserialize = lib._unserialize.__func__
    for_linking = lib._get_module_for_linking

    def load_overload_ready(self, sig, target_context):
        if type(target_context) is not _CPUContext:
            return load_overload(self, sig, target_context)
        _ready_to_load(target_context)
        with self._guard_against_spurious_io_errors():
            return self._load_overload(sig, target_context)

    def unserialize_lazily(cls, codegen, state):
        name, kind, data = state
        names = elf_defined_symbols(data[0]) if kind == "object" else None
        if names is None:
            return unserialize(cls, codegen, state)
        self = codegen.create_library(name)
        self.enable_object_caching()
        self._set_compiled_object(data[0])
        self._pysus_linking_bitcode = data[1]
        self._finalize_final_module()
        codegen._engine._defined_symbols |= names
        return self

    def module_for_linking(self):
        bitcode = getattr(self, "_pysus_linking_bitcode", None)
        if bitcode is not None and self._shared_module is None:
            self._shared_module = _ll.parse_bitcode(bitcode)
            self._pysus_linking_bitcode = None
        return for_linking(self)

    load_overload_ready._pysus_cache_load = True
    cache.load_overload = load_overload_ready
    lib._unserialize = classmethod(unserialize_lazily)
    lib._get_module_for_linking = module_for_linking


_install()
