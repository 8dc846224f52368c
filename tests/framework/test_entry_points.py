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
