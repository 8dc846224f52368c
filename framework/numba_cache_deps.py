"""A cached numba kernel is stale when a module it compiled in has changed, not only its own file.

numba keys a kernel's cache by its own source file, but a kernel's machine code also holds
what it took from other modules at compile time: the helpers it calls (inlined or linked)
and the module constants it reads (an EOS code, a table). After an edit or a `git pull` that
changes `eos.py` but not `equilibration.py`, numba would load equilibration's old machine
code. For source files of this repository the cache stamp here is numba's own stamp plus a
digest of the modules the file imports from the repository: every module it imports, and
further the imports of those that use numba (a kernel calling a kernel calling a kernel).
Importing this module installs it once (framework/__init__.py does). Which modules a file
imports is read from its syntax tree once per version of the file and kept beside it
(__pycache__/NAME.imports.json, under the sha256 of the source): a later process reads that
record instead of parsing the file again (the parsing was about 0.1-0.3 CPU s a process).
"""
from __future__ import annotations

import ast
import functools
import hashlib
import json
import os

from numba.core import caching as _caching

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _module_file(parts):
    """The repository file of a dotted module (a list of names), or None."""
    base = os.path.join(ROOT, *parts)
    for path in (base + ".py", os.path.join(base, "__init__.py")):
        if os.path.isfile(path):
            return path
    return None


def _module_parts(path):
    rel = os.path.relpath(path, ROOT)[:-3].split(os.sep)
    return rel[:-1] if rel[-1] == "__init__" else rel


@functools.lru_cache(maxsize=None)
def _source(path):
    with open(path, "rb") as f:
        return f.read()


def _statements(body):
    """Every statement in a list of them, nested bodies included (an import is a statement: the
    expressions, most of a module's tree, need no visit)."""
    todo = list(body)
    while todo:
        node = todo.pop()
        yield node
        for field in ("body", "orelse", "finalbody", "handlers", "cases"):
            todo.extend(getattr(node, field, ()))


@functools.lru_cache(maxsize=None)
def _sha256(path):
    return hashlib.sha256(_source(path)).hexdigest()


def _parse_imports(path):
    """The modules (lists of names) that the file's import statements name, from its syntax tree;
    None when it does not parse."""
    try:
        tree = ast.parse(_source(path))
    except (SyntaxError, ValueError):
        return None
    own = _module_parts(path)
    package = own if path.endswith("__init__.py") else own[:-1]
    found = []
    for node in _statements(tree.body):
        if isinstance(node, ast.Import):
            for alias in node.names:
                found.append(alias.name.split("."))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - (node.level - 1)] if node.level > 1 else list(package)
            else:
                base = []
            full = base + (node.module.split(".") if node.module else [])
            found.append(full)
            for alias in node.names:                 # `from . import eos`: a submodule
                found.append(full + [alias.name])
    return found


def _record(path):
    """Where the modules a file imports are kept for later processes."""
    head, name = os.path.split(path)
    return os.path.join(head, "__pycache__", name[:-3] + ".imports.json")


def _imported_modules(path):
    """_parse_imports(path), read from the file's record when that was made from the same source
    (same sha256), else parsed and recorded (written whole, then renamed: processes starting
    together never read half a record); a record that cannot be written is skipped."""
    record, key = _record(path), _sha256(path)
    try:
        with open(record, encoding="utf-8") as f:
            saved = json.load(f)
        if saved["sha256"] == key:
            return saved["modules"]
    except (OSError, ValueError, KeyError, TypeError):
        pass
    found = _parse_imports(path)
    if found is None:
        return []
    tmp = f"{record}.{os.getpid()}.tmp"
    try:
        os.makedirs(os.path.dirname(record), exist_ok=True)
        with open(tmp, "w", encoding="utf-8") as f:
            json.dump({"sha256": key, "modules": found}, f)
        os.replace(tmp, record)
    except OSError:
        try:
            os.unlink(tmp)
        except OSError:
            pass
    return found


@functools.lru_cache(maxsize=None)
def direct_imports(path):
    """Repository modules that the file at path imports anywhere in it (files, sorted)."""
    found = {_module_file(parts) for parts in _imported_modules(path)}
    found.discard(None)
    found.discard(path)
    return tuple(sorted(found))


@functools.lru_cache(maxsize=None)
def dependencies(path):
    """The files whose change makes a kernel of `path` stale: its imports, and transitively the
    imports of those that use numba."""
    seen, todo = set(), list(direct_imports(path))
    while todo:
        dep = todo.pop()
        if dep in seen or dep == path:
            continue
        seen.add(dep)
        if b"numba" in _source(dep):
            todo.extend(direct_imports(dep))
    return tuple(sorted(seen))


@functools.lru_cache(maxsize=None)
def digest(path):
    """sha256 over the dependencies' names and contents."""
    h = hashlib.sha256()
    for dep in dependencies(path):
        h.update(os.path.relpath(dep, ROOT).encode())
        h.update(bytes.fromhex(_sha256(dep)))
    return h.hexdigest()


def _install():
    mixin = _caching._SourceFileBackedLocatorMixin
    if getattr(mixin.get_source_stamp, "_pysus_deps", False):
        return
    original = mixin.get_source_stamp

    def get_source_stamp(self):
        stamp = original(self)
        path = os.path.abspath(getattr(self, "_py_file", ""))
        if path.startswith(ROOT + os.sep) and path.endswith(".py"):
            return stamp, digest(path)
        return stamp

    get_source_stamp._pysus_deps = True
    mixin.get_source_stamp = get_source_stamp


_install()
