"""The command line is reachable as `python -m framework` as well as the `pysus` script."""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _run(*args):
    env = dict(os.environ, PYTHONPATH=ROOT)
    return subprocess.run([sys.executable, "-m", "framework", *args], capture_output=True, text=True, env=env,
                          timeout=120)


def test_module_entry_prints_help():
    r = _run("--help")
    assert r.returncode == 0
    assert "usage:" in r.stdout and "-restart" in r.stdout


def test_module_entry_refuses_a_missing_deck_cleanly(tmp_path):
    r = _run(str(tmp_path / "nothing.ups"))
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pysus: error:") and "nothing.ups" in lines[0]


def test_warm_writes_the_bytecode_of_pysus_modules():
    """`pysus --warm` (compile_bytecode) leaves beside each module of framework/ and components/ a
    .pyc stamped with the source's mtime and size, which later processes load instead of
    compiling the source (Python writes none itself where PYTHONDONTWRITEBYTECODE is set)."""
    import importlib.util
    import struct

    from framework.cli import compile_bytecode
    modules = [os.path.join(ROOT, rel) for rel in ("framework/cli.py", "framework/scheduler/compile.py",
                                                   "components/mpm/materials.py")]
    for src in modules:
        if os.path.exists(importlib.util.cache_from_source(src)):
            os.unlink(importlib.util.cache_from_source(src))
    compile_bytecode()
    for src in modules:
        with open(importlib.util.cache_from_source(src), "rb") as f:
            _, flags, mtime, size = struct.unpack("<4sIII", f.read(16))
        st = os.stat(src)
        assert flags == 0 and mtime == int(st.st_mtime) & 0xFFFFFFFF and size == st.st_size & 0xFFFFFFFF
