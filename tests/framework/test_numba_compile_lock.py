"""framework.numba_compile_lock: processes that need the same cached kernel at once compile it
once; the others load it from numba's cache."""
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# a kernel that takes numba a second or two to compile, so that the processes overlap
KERNEL = "import numpy as np\nfrom numba import njit\n\n\n@njit(cache=True)\ndef kernel(a):\n    s = 0.0\n" + "".join(
    f"    for i in range(a.shape[0]):\n        v = a[i, {k % 3}] + {k}.0\n"
    f"        s += np.sin(v) * np.cos(v) + (v * v if v > {k} else -v) + np.sqrt(abs(v) + 1.0)\n"
    for k in range(25)) + "    return s\n"

DRIVER = '''
import json, os, sys, time
sys.path.insert(0, sys.argv[1])
if sys.argv[3] == "lock":
    import framework.numba_compile_lock  # noqa: F401
import numpy as np
import kernelmod
open(sys.argv[2] + f".ready{os.getpid()}", "w").close()
while not os.path.exists(sys.argv[2]):
    time.sleep(0.005)
kernelmod.kernel(np.ones((3, 3)))
print(json.dumps({"misses": sum(kernelmod.kernel._cache_misses.values()),
                  "hits": sum(kernelmod.kernel._cache_hits.values())}))
'''


def _race(tmp_path, mode, n=3):
    """n processes import the kernel, wait for one go file, then call it together."""
    work = tmp_path / mode
    work.mkdir()
    (work / "kernelmod.py").write_text(KERNEL)
    (work / "driver.py").write_text(DRIVER)
    go = work / "go"
    env = dict(os.environ, NUMBA_CACHE_DIR=str(work / "cache"),
               PYTHONPATH=os.pathsep.join([str(ROOT), str(work)]))
    procs = [subprocess.Popen([sys.executable, str(work / "driver.py"), str(ROOT), str(go), mode],
                              stdout=subprocess.PIPE, text=True, env=env, cwd=work) for _ in range(n)]
    deadline = time.monotonic() + 120
    while len(list(work.glob("go.ready*"))) < n and time.monotonic() < deadline:
        time.sleep(0.01)                # until every process imported numba and waits
    go.write_text("")
    out = [json.loads(p.communicate(timeout=300)[0].strip().splitlines()[-1]) for p in procs]
    return sum(o["misses"] for o in out), sum(o["hits"] for o in out)


def test_one_compiles_the_others_load(tmp_path):
    misses, hits = _race(tmp_path, "lock")
    assert (misses, hits) == (1, 2)


def test_without_the_lock_all_compile(tmp_path):
    """The race above is real: without the lock the processes compile side by side."""
    misses, hits = _race(tmp_path, "plain", n=2)
    assert misses >= 2


def test_a_cached_kernel_loads_while_another_process_holds_the_lock(tmp_path):
    """Ranks starting together on a warm cache load their kernels side by side: a process that
    finds the kernel in the cache does not wait for the lock (held here by the test itself,
    as a process compiling another signature of the kernel would hold it)."""
    import fcntl
    _race(tmp_path, "lock", n=1)                              # the kernel is now in the cache
    work = tmp_path / "lock"
    (lock_file,) = [p for p in (work / "cache").rglob("*.nbi.lock")]
    fd = os.open(lock_file, os.O_RDWR)
    fcntl.flock(fd, fcntl.LOCK_EX)
    try:
        env = dict(os.environ, NUMBA_CACHE_DIR=str(work / "cache"), PYTHONPATH=os.pathsep.join([str(ROOT), str(work)]))
        p = subprocess.run([sys.executable, str(work / "driver.py"), str(ROOT), str(work / "go"), "lock"],
                           capture_output=True, text=True, env=env, cwd=work, timeout=120)
    finally:
        fcntl.flock(fd, fcntl.LOCK_UN)
        os.close(fd)
    assert json.loads(p.stdout.strip().splitlines()[-1]) == {"misses": 0, "hits": 1}
