"""Uintah's colliding-disks decks run unchanged and conserve energy (within 3 %).

disks_sulsky.ups (linear, comp_neo_hook, 2D) runs in full (about 5 s). disks.ups
(GIMP, comp_mooney_rivlin, 3D with 3 z-cells, 4 patches) is cut to maxTime 0.1 (the
full run takes about 50 s): the disks meet at t = 0.05 and separate by 0.09. Later,
at t = 0.17, they hit the no-slip walls (Dirichlet v = 0), which takes about 8 % of the
energy away; that is the deck's physics, not checked here.
"""
import numpy as np

from tests.conftest import UINTAH_INPUTS

from .helpers import deck_text, energy, run


def test_disks_sulsky_linear_energy(tmp_path):
    ctl, da = run(open(UINTAH_INPUTS / "MPM" / "disks_sulsky.ups").read(), tmp_path)
    t, E = energy(da)
    _, M = da.reduction("TotalMass")
    assert t[-1] >= 3.0 - 1e-9
    assert np.all(np.isfinite(E))
    assert np.max(np.abs(E / E[0] - 1)) < 0.03
    assert M[-1] == M[0]                          # no particle lost or blown up
    _, ke = da.reduction("KineticEnergy")
    assert ke.min() < 0.2 * ke[0]                 # the disks did collide and stop


def test_disks_gimp_energy(tmp_path):
    text = deck_text(UINTAH_INPUTS / "MPM" / "disks.ups", maxTime=0.1)
    ctl, da = run(text, tmp_path)
    t, E = energy(da)
    _, ke = da.reduction("KineticEnergy")
    assert t[-1] >= 0.1 - 1e-9
    assert ke.min() < 0.2 * ke[0]                 # collision happened inside the window
    assert np.max(np.abs(E / E[0] - 1)) < 0.03


def test_disks_50x50(tmp_path):
    """Finer grid (50 x 50, 4 patches): no blow-up at nearly empty nodes, energy kept."""
    from .helpers import MPM_INPUTS
    ctl, da = run(deck_text(MPM_INPUTS / "disks_50x50.ups", maxTime=1.6), tmp_path)
    t, E = energy(da)
    _, M = da.reduction("TotalMass")
    assert np.all(np.isfinite(E)) and abs(M[-1] / M[0] - 1) < 1e-12   # none lost (sum order varies by patch)
    assert np.max(np.abs(E / E[0] - 1)) < 0.03
