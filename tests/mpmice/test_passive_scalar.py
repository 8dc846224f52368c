"""Uintah's PassiveScalar model under MPMICE (components/models/passive_scalar.py), against sus.

Deck: uintah_reference/advect_scalars.ups (Uintah's MPMICE advect.ups on a coarser grid,
without its TracerParticles model, c2 a constant; a Dirichlet scalar-f_CC of 0.5 on the
inflow face x-). The sus values in data/sus_advect_scalars.npz are sus's output on that
deck (one rank): the time after each step (timestep.xml), totalSum_scalar-f_CC.dat and
totalSum_scalar-q_CC.dat, and scalar-f_CC / scalar-q_CC (material 1) over the interior
cells after steps 1 and 10 (read with framework.uintah_uda).

The scalars' algorithm is ICE's, and the flow that carries them is sus's: the gas starts
around the copper box from its geometry as sus's (docs/MPMICE.md, "Gas start"). Measured:
the times of 10 steps 7e-15 relative, step 1 f and q 3e-16 off sus, the sums of all 10 steps
7e-16; after 10 steps each code's f is 1 - 100 t (the linear decay) to round-off away from the
inlet. (With the particles' smeared start the pressure moved where sus's stays at 101325 Pa:
delT 2.8e-7 s off over 10 steps, f 1.5e-11 after step 1.)
"""
import pathlib

import numpy as np
import pytest

from framework.problemspec import InputError
from tests.conftest import run_deck

REF = pathlib.Path(__file__).parent / "uintah_reference"
DECK = REF / "advect_scalars.ups"
RATE, DECAY = 100.0, 60.0 * 1.0 + 1e-5           # rateOfChange0; c1 c2 + c3


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    ctl = run_deck(DECK.read_text(encoding="iso-8859-1"), tmp_path_factory.mktemp("scalars"), "scalars")
    return DataArchive(ctl.archiver.dir), np.load(pathlib.Path(__file__).parent / "data" / "sus_advect_scalars.npz")


def test_scalars_decay_with_the_air(runs):
    """Away from the inlet f = 1 - 100 t (rateOfChange0) and everywhere q = exp(-(c1 c2 + c3) t):
    a uniform scalar stays uniform whatever the carrier's mass does."""
    da, _ = runs
    for step in (1, 10):
        t = da.times[step]
        f, q = da.read("scalar-f_CC", 1, step)[0], da.read("scalar-q_CC", 1, step)[0]
        assert np.abs(f[6:] - (1.0 - RATE * t)).max() < 1e-12
        assert np.abs(q - np.exp(-DECAY * t)).max() < 1e-14
        assert f[0].max() < 1.0 - RATE * t - 1e-3                  # the inlet brings f = 0.5 in


def test_scalars_as_uintah(runs):
    da, sus = runs
    assert np.allclose(da.times[1:3], sus["times"][:2], rtol=1e-14, atol=0)
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-13, atol=0)
    assert np.allclose(da.read("scalar-f_CC", 1, 1)[0], sus["f_step1"], rtol=0, atol=1e-14)
    assert np.allclose(da.read("scalar-q_CC", 1, 1)[0], sus["q_step1"], rtol=0, atol=1e-15)
    sums_f, sums_q = da.reduction("totalSum_scalar-f_CC")[1], da.reduction("totalSum_scalar-q_CC")[1]
    assert np.allclose(sums_f[:2], sus["totalSum_f"][:2], rtol=1e-14, atol=0)
    assert np.allclose(sums_q[:2], sus["totalSum_q"][:2], rtol=1e-14, atol=0)
    assert np.allclose(sums_f, sus["totalSum_f"], rtol=1e-14, atol=0)
    # after 10 steps: the deficit below 1 - 100 t (the inlet's Dirichlet 0.5) in each code's time
    t_py, t_sus = da.times[-1], sus["times"][-1]
    deficit_py = da.read("scalar-f_CC", 1, -1)[0] - (1.0 - RATE * t_py)
    deficit_sus = sus["f_step10"] - (1.0 - RATE * t_sus)
    assert np.abs(deficit_sus).max() > 0.01
    assert np.allclose(deficit_py, deficit_sus, rtol=0, atol=1e-5)
    assert np.allclose(da.read("scalar-q_CC", 1, -1)[0] / np.exp(-DECAY * t_py),
                       sus["q_step10"] / np.exp(-DECAY * t_sus), rtol=1e-12, atol=0)


@pytest.mark.parametrize("old, new, message", [
    ("<material>atmosphere</material>", "<material>0</material>", "carried by an ICE material"),
    ('<Model type="PassiveScalar">', '<Model type="mass_momentum_energy_src">', "available for ICE alone"),
])
def test_refused_under_mpmice(tmp_path, old, new, message):
    text = DECK.read_text(encoding="iso-8859-1").replace(old, new, 1)
    with pytest.raises(InputError, match=message):
        run_deck(text, tmp_path)
