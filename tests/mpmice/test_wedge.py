"""Mach 3 flow past a rigid 20-degree wedge (paper 000 sec. 4.3, inputs/MPMICE/wedge_mach3.ups)
at twice the deck's spacing (dx = 0.02 m): an attached oblique shock at the theory's angle.

Measured with scripts/wedge_shock_angle.py (t = 1.5 ms; theory 37.76 deg, p2/p1 = 3.771):
  dx = 0.02 m: 35.18 deg (-2.59), p2/p1 = 3.458     (272 steps, 4 s)
  dx = 0.01 m: 36.70 deg (-1.06), p2/p1 = 3.565     (the deck; 542 steps, 40 s)
"""
import pytest

from tests.conftest import ROOT, load_script, run_deck


def _script():
    return load_script("wedge_shock_angle")


def test_theory_values():
    beta, ratio = _script().theory()
    assert beta == pytest.approx(37.7636, abs=1e-3) and ratio == pytest.approx(3.7713, abs=1e-3)


def test_shock_angle_coarse(tmp_path):
    text = (ROOT / "inputs" / "MPMICE" / "wedge_mach3.ups").read_text(encoding="iso-8859-1")
    old = "<spacing> [0.01,0.01,0.01] </spacing>"
    assert old in text
    ctl = run_deck(text.replace(old, "<spacing> [0.02,0.02,0.01] </spacing>"), tmp_path, "wedge")
    r = _script().measure(ctl.archiver.dir)
    assert r["columns"] >= 12
    assert abs(r["error_deg"]) < 3.5
    assert abs(r["p2_over_p1"] / r["p2_over_p1_theory"] - 1) < 0.1
