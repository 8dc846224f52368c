"""A cached kernel is recompiled when a module it took a constant or a helper from changes.

numba alone keys the cache by the kernel's own file: the control run shows it loading the old
machine code; with framework.numba_cache_deps the kernel sees the new constant."""
import os
import subprocess
import sys
import textwrap

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

RUN = textwrap.dedent("""
    import sys
    root, use_deps = sys.argv[1], sys.argv[2] == "1"
    if use_deps:
        from framework import numba_cache_deps
        numba_cache_deps.ROOT = root
    sys.path.insert(0, root)
    from pkg.kern import value
    print(value())
""")


def _write(path, text):
    with open(path, "w") as f:
        f.write(textwrap.dedent(text))


def _run(root, use_deps, cache):
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=REPO)
    out = subprocess.run([sys.executable, "-c", RUN, root, "1" if use_deps else "0"], env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return float(out.stdout.split()[-1])


@pytest.mark.parametrize("use_deps, expected", [(False, 1.0), (True, 2.0)])
def test_kernel_sees_a_changed_constant_of_another_module(tmp_path, use_deps, expected):
    root = tmp_path / "src"
    (root / "pkg").mkdir(parents=True)
    _write(root / "pkg" / "__init__.py", "")
    _write(root / "pkg" / "consts.py", "SCALE = 1.0\n")
    _write(root / "pkg" / "kern.py", """
        from numba import njit
        from .consts import SCALE

        @njit(cache=True)
        def value():
            return SCALE
        """)
    cache = str(tmp_path / "cache")
    assert _run(str(root), use_deps, cache) == 1.0
    _write(root / "pkg" / "consts.py", "SCALE = 2.0  # edited\n")
    assert _run(str(root), use_deps, cache) == expected       # numba alone: the stale 1.0


def test_dependencies_follow_numba_modules_only():
    from framework import numba_cache_deps as deps
    eq = os.path.join(REPO, "components", "ice", "equilibration.py")
    found = {os.path.relpath(p, REPO) for p in deps.dependencies(eq)}
    assert os.path.join("components", "ice", "eos.py") in found
    assert all(p.endswith(".py") for p in found)
    before = deps.digest(eq)
    assert before == deps.digest(eq) and len(before) == 64


def test_imports_come_from_the_record_of_the_same_source_and_again_from_an_edited_one(tmp_path, monkeypatch):
    """The modules a file imports are parsed once per version of the file: a later process reads
    the record kept under the source's sha256 (shown by a record altered by hand), an edited file
    is parsed again."""
    import json

    from framework import numba_cache_deps as deps
    monkeypatch.setattr(deps, "ROOT", str(tmp_path))
    (tmp_path / "pkg").mkdir()
    for name in ("__init__", "b", "c"):
        _write(tmp_path / "pkg" / f"{name}.py", "")
    a = str(tmp_path / "pkg" / "a.py")
    _write(a, "from . import b\n")
    assert deps._imported_modules(a) == [["pkg"], ["pkg", "b"]]
    with open(deps._record(a)) as f:
        record = json.load(f)
    record["modules"] = [["pkg", "c"]]
    with open(deps._record(a), "w") as f:
        json.dump(record, f)
    assert deps._imported_modules(a) == [["pkg", "c"]]
    _write(a, "import pkg.c\n")
    deps._source.cache_clear()
    deps._sha256.cache_clear()
    assert deps._imported_modules(a) == [["pkg", "c"]] and json.load(open(deps._record(a)))["sha256"] == deps._sha256(a)
    _write(a, "from .b import x\n")
    deps._source.cache_clear()
    deps._sha256.cache_clear()
    assert deps._imported_modules(a) == [["pkg", "b"], ["pkg", "b", "x"]]
