"""numba's check that a kernel's cache directory is writable runs once per directory and process
(framework/numba_cache_path.py), and again for a directory that has gone."""
import importlib.util
import shutil
import sys
import tempfile

import framework.numba_cache_path  # noqa: F401

KERNELS = """
from numba import njit


@njit(cache=True)
def one():
    return 1


@njit(cache=True)
def two():
    return 2
"""


def _load(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_cache_directory_checked_once_and_again_when_gone(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setattr(sys, "dont_write_bytecode", True)    # else importing kern_b remakes __pycache__ for its .pyc
    made = []
    real = tempfile.TemporaryFile

    def counting(*args, **kw):
        made.append(kw.get("dir"))
        return real(*args, **kw)

    monkeypatch.setattr(tempfile, "TemporaryFile", counting)
    (tmp_path / "kern_a.py").write_text(KERNELS)
    (tmp_path / "kern_b.py").write_text(KERNELS)
    a = _load(tmp_path / "kern_a.py", "pysus_test_kern_a")
    assert made == [str(tmp_path / "__pycache__")]        # two kernels, one check
    assert a.one() == 1 and a.two() == 2                  # compiled and cached there
    assert any(p.suffix == ".nbi" for p in (tmp_path / "__pycache__").iterdir())
    shutil.rmtree(tmp_path / "__pycache__")
    b = _load(tmp_path / "kern_b.py", "pysus_test_kern_b")
    assert made == [str(tmp_path / "__pycache__")] * 2    # gone: made and checked again
    assert b.two() == 2 and (tmp_path / "__pycache__").is_dir()
