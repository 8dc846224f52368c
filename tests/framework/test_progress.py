"""The progress line as a user sees it (under a pseudo-terminal), `--timing` adding up to the wall
time, and `--warm` compiling without leaving output behind."""
import os
import pty
import re
import subprocess
import sys

from framework.progress import Progress, clock
from tests.framework import decks

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _deck(tmp_path, maxTime=0.05):
    path = tmp_path / "heat.ups"
    path.write_text(decks.heat(n=16, maxTime=maxTime))
    return str(path)


def _pysus(args, cwd, **kw):
    env = dict(os.environ, PYTHONPATH=ROOT)
    return subprocess.run([sys.executable, "-m", "framework"] + args, cwd=cwd, env=env, timeout=300, **kw)


def test_progress_line_under_a_pty(tmp_path):
    """Run a deck with its stdout on a pseudo-terminal: the line shows step, t of maxTime, % and ETA."""
    master, slave = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "framework", _deck(tmp_path)],
                            cwd=tmp_path, stdout=slave, stderr=slave, env=dict(os.environ, PYTHONPATH=ROOT))
    os.close(slave)
    out = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:        # the child closed the terminal
            break
        if not chunk:
            break
        out += chunk
    os.close(master)
    assert proc.wait(timeout=300) == 0
    text = out.decode()
    lines = [s for s in re.split(r"[\r\n]", text) if s.startswith("step")]
    assert lines, text
    last = lines[-1]
    assert re.search(r"t = [0-9.e+-]+ of 0\.05 s \(100\.0%\)", last), last
    assert "ETA 0:00" in last and "ms/step" in last


def test_fraction_and_eta():
    p = Progress(enabled=False, max_time=2.0, start_time=1.0)
    assert p.fraction(10, 1.5) == 0.5
    line = p.line(10, 1.5, 1e-3, 20.0, 0.025)
    assert "( 50.0%)" in line and "25.00 ms/step" in line and "ETA 0:20" in line
    q = Progress(enabled=False, max_timesteps=100, start_step=50)
    assert q.fraction(75, 0.0) == 0.5
    assert clock(3725) == "1:02:05" and clock(65) == "1:05"


def test_eta_leaves_out_the_first_step():
    """A first step that compiles for 100 s, then 0.1 s a step for 100 steps to maxTime: half way
    the ETA is 5 s, not the 105 s that the average over all steps would give."""
    class Tty:
        def isatty(self):
            return True

        def write(self, text):
            self.text = text

        def flush(self):
            pass

    tty = Tty()
    p = Progress(stream=tty, interval=0.0, max_time=1.0)
    p.note("setting up")
    assert tty.text == "\rsetting up\033[K"
    p.update(1, 0.0, 0.01, 100.0)
    assert "ETA ?" in tty.text and "100000.00 ms/step" in tty.text
    p.update(51, 0.5, 0.01, 105.0)
    assert "( 50.0%)" in tty.text and "ETA 0:05" in tty.text and "100.00 ms/step" in tty.text
    q = Progress(stream=tty, max_time=1.0)
    q.note("setting up")
    q.close()                   # set-up failed: the line ends before the error message
    assert tty.text == "\n"


def test_timing_rows_add_up_to_wall(tmp_path):
    r = _pysus(["--timing", _deck(tmp_path, maxTime=0.2)], tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rows = re.findall(r"^  (.+?)\s+([0-9.]+) s", r.stdout, re.M)
    names = [n.strip() for n, _ in rows]
    total = float(rows[-1][1])
    assert names[-1] == "total (wall)"
    for want in ("set-up outside tasks (grid, first output)", "output and checkpoints", "ghost exchange"):
        assert want in names, names
    parts = sum(float(t) for n, t in rows[:-1] if not n.startswith("other"))
    other = float(dict((n.strip(), t) for n, t in rows)["other (delT, load balance, scheduling)"])
    assert other >= -1e-3
    assert abs(parts + other - total) <= 0.03 * total + 2e-3


def test_warm_leaves_no_output(tmp_path):
    deck = _deck(tmp_path)
    cache = tmp_path / "cache"
    r = _pysus(["--warm", "--cache-dir", str(cache), deck], tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "compiled" in r.stdout and str(cache) in r.stdout
    assert sorted(os.listdir(tmp_path)) == ["cache", "heat.ups"]   # no .uda next to the deck


def test_pysus_progress_overrides_the_terminal_test(monkeypatch):
    """Under mpiexec rank 0's stdout is a pipe: PYSUS_PROGRESS=1 (set by `pysus --np N` from a
    terminal) draws the line there; PYSUS_PROGRESS=0 keeps a terminal clean."""
    import io
    monkeypatch.setenv("PYSUS_PROGRESS", "1")
    assert Progress(stream=io.StringIO()).enabled
    assert not Progress(enabled=False, stream=io.StringIO()).enabled      # --quiet wins
    monkeypatch.setenv("PYSUS_PROGRESS", "0")

    class Tty(io.StringIO):
        def isatty(self):
            return True
    assert not Progress(stream=Tty()).enabled
    monkeypatch.delenv("PYSUS_PROGRESS")
    assert Progress(stream=Tty()).enabled and not Progress(stream=io.StringIO()).enabled
