"""A kernel compiled below numba's full optimisation level is cached apart
(framework/numba_cache_opt.py): a run at the full level never loads it and compiles its own, a
run below the full level loads the full level's kernel where the cache has one and its own
otherwise. Each run is a fresh process on one cache directory; the dispatcher's cache hits and
misses say whether it loaded or compiled, and the compile lock (framework/numba_compile_lock.py)
must see the same before the call: a kernel it can load needs no lock."""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

KERNEL = """
from numba import njit


@njit(cache=True)
def squares(n):
    total = 0
    for i in range(n):
        total += i * i
    return total
"""

RUN = """
import json, sys
sys.path.insert(0, sys.argv[1])
sys.path.insert(0, sys.argv[2])
import framework  # noqa: F401
from framework.numba_compile_lock import _in_cache
from numba import types
import kernel
in_cache = _in_cache(kernel.squares, (types.int64,))
assert kernel.squares(10) == 285
stats = kernel.squares.stats
print(json.dumps({"hits": sum(stats.cache_hits.values()), "misses": sum(stats.cache_misses.values()),
                  "in_cache": in_cache}))
"""


def _run(tmp_path, cache, level):
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_OPT"}
    env["NUMBA_CACHE_DIR"] = str(cache)
    if level is not None:
        env["NUMBA_OPT"] = str(level)
    out = subprocess.run([sys.executable, "-c", RUN, ROOT, str(tmp_path)], env=env, check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_low_level_kernels_are_cached_apart(tmp_path):
    (tmp_path / "kernel.py").write_text(KERNEL)
    loaded, compiled = {"hits": 1, "misses": 0, "in_cache": True}, {"hits": 0, "misses": 1, "in_cache": False}

    low_first = tmp_path / "low_first"
    assert _run(tmp_path, low_first, 0) == compiled
    assert _run(tmp_path, low_first, 0) == loaded         # its own level's kernel
    assert _run(tmp_path, low_first, None) == compiled    # the full level never loads it
    assert _run(tmp_path, low_first, None) == loaded

    full_first = tmp_path / "full_first"
    assert _run(tmp_path, full_first, None) == compiled
    assert _run(tmp_path, full_first, 0) == loaded        # the full level's kernel
    assert _run(tmp_path, full_first, 1) == loaded
    assert _run(tmp_path, full_first, None) == loaded
