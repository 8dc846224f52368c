"""The per-step health check of the carried state (framework/health.py): a blown-up run stops
with one line naming the step, variable, material and cell, and writes that state as output."""
import subprocess
import sys
from pathlib import Path

import numpy as np

from framework.health import first_bad

ROOT = Path(__file__).resolve().parents[2]


def test_first_bad_finds_nan_inf_and_negative():
    a = np.ones((3, 4, 2, 1))
    assert first_bad(a, True) == (-1, -1, -1, -1)
    a[1, 2, 0, 0] = np.nan
    a[2, 0, 0, 0] = np.inf
    assert first_bad(a, False) == (1, 2, 0, 0)
    b = np.ones((5, 1, 1, 3))
    b[3, 0, 0, 2] = -1e-300
    assert first_bad(b, False) == (-1, -1, -1, -1)      # negative is fine for a velocity
    assert first_bad(b, True) == (3, 0, 0, 2)           # not for a mass or a temperature
    assert first_bad(b[:, :, :, :0], True) == (-1, -1, -1, -1)


def test_unstable_diffusion_stops_at_first_negative_temperature(tmp_path):
    # explicit diffusion at 5x its stability limit (alpha 0.1, cfl 5): the Gaussian's edge goes
    # negative, a state the exact solution (non-negative for a non-negative start) never has
    deck = (ROOT / "inputs/examples/quickstart.ups").read_text(encoding="latin-1")
    deck = deck.replace("<cfl>   0.4  </cfl>", "<cfl>   5.0  </cfl>").replace(
        "<alpha> 0.01 </alpha>", "<alpha> 0.1 </alpha>")
    (tmp_path / "blow.ups").write_text(deck, encoding="latin-1")
    r = subprocess.run([sys.executable, "-m", "framework", "-q", "blow.ups"], cwd=tmp_path,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 1
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    assert "blew up at timestep" in lines[0] and "temp_CC of material 0 is -" in lines[0]
    step = int(lines[0].split("blew up at timestep ")[1].split(":")[0])
    assert (tmp_path / "quickstart.uda" / f"t{step:05d}").is_dir()
    from framework.archiver import DataArchive
    temp, _ = DataArchive(tmp_path / "quickstart.uda").read("temp_CC", 0, -1)
    assert np.nanmin(temp) < 0.0


def test_check_schedule_is_fixed(tmp_path, monkeypatch):
    """The check's schedule does not depend on measured times: every step by default (the first
    negative step, the same on every run), every N steps with PYSUS_CHECK_STATE=N (the first
    checked step at or after it), and a value that is not a count is a clear error."""
    import pytest

    from framework.errors import RunStopped
    from framework.problemspec import InputError
    from tests.conftest import run_deck
    deck = (ROOT / "inputs/examples/quickstart.ups").read_text(encoding="latin-1")
    deck = deck.replace("<cfl>   0.4  </cfl>", "<cfl>   5.0  </cfl>").replace(
        "<alpha> 0.01 </alpha>", "<alpha> 0.1 </alpha>")
    steps = []
    for i, every in enumerate(("1", "1", "4")):
        monkeypatch.setenv("PYSUS_CHECK_STATE", every)
        with pytest.raises(RunStopped) as stop:
            run_deck(deck, tmp_path, f"blow{i}")
        steps.append(int(str(stop.value).split("blew up at timestep ")[1].split(":")[0]))
    assert steps[0] == steps[1]
    assert steps[0] <= steps[2] < steps[0] + 4
    monkeypatch.setenv("PYSUS_CHECK_STATE", "often")
    with pytest.raises(InputError, match="PYSUS_CHECK_STATE"):
        run_deck(deck, tmp_path, "bad")
