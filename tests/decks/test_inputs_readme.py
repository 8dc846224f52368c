"""inputs/README.md lists every deck: scripts/list_decks.py writes it from the decks' header
comments, and it must be current; and every deck lies in a folder tests/decks/ runs."""
import subprocess
import sys

from tests.conftest import ROOT


def test_inputs_readme_is_current():
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "list_decks.py"), "--check"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_every_deck_is_in_a_tested_folder():
    tested = {"EFEM", "ICE", "MPM", "MPMICE", "examples"}
    stray = [p for p in (ROOT / "inputs").rglob("*.ups") if p.relative_to(ROOT / "inputs").parts[0] not in tested]
    assert not stray, f"decks outside {sorted(tested)}: add a tests/decks/ file for them: {stray}"
