"""A kernel loaded from numba's cache runs without numba's target set-up (the registries'
refresh) and without parsing its linking bitcode (framework/numba_cache_load.py): kernels that
allocate (numba's runtime), hash strings in a dict (the hash secret's symbols) and raise give
the same results in a fresh process that loads them as in the one that compiled them, that
process never refreshes the context, the symbols read from each object file are those numba
reads from the bitcode, and a kernel compiled later links a loaded one in."""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

KERNELS = """
import numpy as np
from numba import njit


@njit(cache=True)
def allocate(n):
    a = np.empty(n)
    for i in range(n):
        a[i] = i * i
    return a


@njit(cache=True)
def words(n):
    d = {}
    for i in range(n):
        d[str(i % 7)] = i
    return len(d), d["3"]


@njit(cache=True)
def doubled(n):
    return 2.0 * allocate(n)


@njit(cache=True)
def checked(x):
    if x < 0.0:
        raise ValueError("negative")
    return np.sqrt(x)
"""

RUN = """
import json, sys
sys.path.insert(0, sys.argv[1])
sys.path.insert(0, sys.argv[2])
from numba.core import base
refreshed = []
original = base.BaseContext.refresh
base.BaseContext.refresh = lambda self: (refreshed.append(1), original(self))[1]
import framework.numba_cache_load  # noqa: F401
from numba.core import codegen
loaded, unserialize = [], codegen.JITCodeLibrary._unserialize.__func__


def capture(cls, cg, state):
    loaded.append(state[2])
    return unserialize(cls, cg, state)


codegen.JITCodeLibrary._unserialize = classmethod(capture)
import kern_load
out = {"allocate": kern_load.allocate(5).tolist(), "words": list(kern_load.words(20)),
       "checked": kern_load.checked(4.0)}
try:
    kern_load.checked(-1.0)
except ValueError as e:
    out["raised"] = str(e)
out["refreshed"] = len(refreshed)
out["hits"] = sum(sum(f.stats.cache_hits.values()) for f in (kern_load.allocate, kern_load.words, kern_load.checked))
import llvmlite.binding as ll
from framework.numba_cache_load import elf_defined_symbols
out["lazy"], out["same_symbols"] = [], []
for f in (kern_load.allocate, kern_load.words, kern_load.checked):
    out["lazy"].append(getattr(next(iter(f.overloads.values())).library, "_pysus_linking_bitcode", None) is not None)
for obj, bitcode in loaded:
    mod = ll.parse_bitcode(bitcode)
    defined = {g.name for gs in (mod.functions, mod.global_variables) for g in gs if not g.is_declaration}
    out["same_symbols"].append(defined == elf_defined_symbols(obj))
if sys.argv[3] == "link":
    out["doubled"] = kern_load.doubled(3).tolist()
print(json.dumps(out))
"""


def _run(tmp_path, link=False):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    out = subprocess.run([sys.executable, "-c", RUN, ROOT, str(tmp_path), "link" if link else "load"], env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_cached_kernels_run_without_the_target_refresh(tmp_path):
    (tmp_path / "kern_load.py").write_text(KERNELS)
    first = _run(tmp_path)                       # compiles (and refreshes, as numba's compiler does)
    assert first["hits"] == 0 and first["refreshed"] > 0
    second = _run(tmp_path)                      # loads all three from the cache
    assert second["hits"] == 3 and second["refreshed"] == 0
    assert second["lazy"] == [True] * 3 and second["same_symbols"] == [True] * 3
    third = _run(tmp_path, link=True)            # compiles doubled, linking the loaded allocate in
    assert third["doubled"] == [0.0, 2.0, 8.0]
    expected = {"allocate": [0.0, 1.0, 4.0, 9.0, 16.0], "words": [7, 17], "checked": 2.0, "raised": "negative"}
    for run in (first, second, third):
        assert {k: run[k] for k in expected} == expected
