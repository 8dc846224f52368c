"""Every deck under inputs/ runs (two timesteps, output included), and inputs/README.md lists them all.

A deck that no longer parses, whose tags a component stopped accepting, or whose first
steps fail is caught here rather than by a user; the list in inputs/README.md is written
by scripts/list_decks.py from the decks' header comments and must be current.
"""
import subprocess
import sys

import pytest

from tests.conftest import ROOT

DECKS = sorted((ROOT / "inputs").rglob("*.ups"))


@pytest.mark.parametrize("deck", DECKS, ids=lambda p: p.relative_to(ROOT / "inputs").as_posix())
def test_deck_runs_two_steps(deck, tmp_path):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    ctl = Controller(str(deck), quiet=True, filebase=str(tmp_path / "run.uda"), max_timesteps=2)
    ctl.run()
    assert ctl.timestep == 2
    if ctl.archiver is not None:
        assert len(DataArchive(ctl.archiver.dir).times) >= 1


def test_inputs_readme_is_current():
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "list_decks.py"), "--check"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
