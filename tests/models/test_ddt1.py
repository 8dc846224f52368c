"""DDT1 (components/models/ddt1.py): Uintah's deflagration-to-detonation model.

tests/models/uintah_reference/ddt1_burn.ups: Uintah's MPMICE/DDT.ups (PBX 9501, visco_scram
with cracks, JWL products, the product's "outOfDomain" object) on 20 cells with the products
at 200 kg/m^3 and 3000 K (1.6e8 Pa) so the reactant's first cell burns conductively from the
first step. sus values: Uintah's sus on that deck (12 steps, output every step): its
totalMassBurned.dat, BurningCriteria and surfaceTemp.

tests/models/uintah_reference/burnrate.ups: Uintah's MPMICE/BurnRate.ups (semi-implicit ICE) for
8 steps with <Solver type="CGSolver"/> (sus's hypre is not built), output every step; sus values
from its totalMassBurned.dat.
"""
import os

import numpy as np
import pytest

from components.models import ddt1 as D
from framework.problemspec import InputError

HERE = os.path.dirname(__file__)
DECK = os.path.join(HERE, "uintah_reference", "ddt1_burn.ups")
Q = 4.0e5 + 3.018e6                  # CondPhaseHeat + GasPhaseHeat (J/kg)
SUS_BURNED_STEP1 = 3.0511829245648247e-13       # kg, sus totalMassBurned.dat, t = 1e-9 s
SUS_TS_STEP1 = 1069.252542223914                # K, sus surfaceTemp of cell 2 after step 1
SUS_BURNRATE = [4.3445973512350147e-15, 6.5169003289784257e-15, 9.7753653303593389e-15, 1.4663075642654024e-14,
                2.1994661343210976e-14, 3.2992058001627119e-14, 4.9488094371733386e-14, 7.4231642450690382e-14]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    out = tmp_path_factory.mktemp("ddt1")
    c = Controller(DECK, quiet=True, filebase=str(out / "ddt1_burn.uda"))
    c.run()
    d = c.archiver.dir
    return DataArchive(d), np.loadtxt(os.path.join(d, "totalMassBurned.dat")), \
        np.loadtxt(os.path.join(d, "totalHeatReleased.dat"))


def test_first_step_burn_against_sus(run):
    """Step 1: the reactant's first cell (2) burns conductively (code 2), alone, as sus; its WSB
    surface temperature and burned mass agree with sus to 0.1 % and 1 % (measured 0.04 % and 0.4 %:
    the product pressure next to the surface differs by 0.5 %, pysus's MPMICE start
    splitting the border cells' fluid volume by the particles' node masses)."""
    a, burned, _ = run
    crit = a.read("BurningCriteria", 0, 1)[0].ravel()
    assert crit[2] == D.CONDUCTIVE and np.count_nonzero(crit) == 1
    assert abs(a.read("surfaceTemp", 0, 1)[0].ravel()[2] / SUS_TS_STEP1 - 1) < 1e-3
    assert abs(burned[0, 1] / SUS_BURNED_STEP1 - 1) < 1e-2


def test_mass_and_heat_bookkeeping(run):
    """The reactant's particles lose what the product gains, the sum of totalMassBurned (closed
    box: symmetry on every face); the heat released is Qc + Qg per burned kg."""
    a, burned, heat = run
    V = 0.001 ** 3
    pm0 = a.particles(0, 0)["p.mass"].sum()
    pm1 = a.particles(0, -1)["p.mass"].sum()
    gm0 = a.read("rho_CC", 1, 0)[0].sum() * V
    gm1 = a.read("rho_CC", 1, -1)[0].sum() * V
    total = burned[:, 1].sum()
    assert total > 0
    assert abs((pm0 - pm1) / total - 1) < 1e-6
    assert abs((gm1 - gm0) / total - 1) < 1e-6
    assert np.allclose(heat[:, 1], Q * burned[:, 1], rtol=1e-12)


def test_detonation_cell():
    """A reactant cell above ThresholdPressureJWL with particles burns JWL++'s
    dF (m_r + m_p), dF = dt G p^b (1 - F), F = rho_p / (rho_r + rho_p), at most 0.2 rho0 V, E0 per kg."""
    n = (3, 3, 3)
    one = np.ones(n)
    p, rho_r, rho_p, dt, V = 8e9, 1800.0, 100.0, 1e-8, 1e-9
    G, b, E0, rho0 = 2.33e-6, 1.2, 5e6, 1832.0
    out = [np.zeros(n) for _ in range(9)]
    temps = (300.0 * one, 3000.0 * one)
    vfs = (0.9 * one, 0.1 * one)
    D.ddt1_cells(np.ones((4, 4, 4)), np.zeros(3, np.int64), np.zeros(3, np.int64), np.ones(3, np.int64),
                 np.full(3, 2, np.int64), np.ones(3, np.int64), np.full(3, 1e-3), np.full(3, -9), np.full(3, 99),
                 5 * one, 0 * one, False, temps, vfs, p * one, rho_r * one, rho_p * one, one / 1832, 0, 1,
                 np.array([G, b, E0, 5.3e9, rho0]), np.array([3, 550, 5e4, Q]), np.ones(5), 1.76e5, 8.314,
                 1e-6, 1e-12 * V, dt, *out, np.zeros(6), *(np.zeros(n) for _ in range(5)))
    burned, heat, crit, det, _, F, dF = out[:7]
    f = rho_p / (rho_r + rho_p)
    d = dt * G * p ** b * (1 - f)
    assert det[1, 1, 1] == 1 and crit[1, 1, 1] == 0 and heat[1, 1, 1] == E0
    assert np.isclose(F[1, 1, 1], f) and np.isclose(dF[1, 1, 1], d)
    assert np.isclose(burned[1, 1, 1], min(d * (rho_r + rho_p) * V, 0.2 * rho0 * V))


def _deck_with(tmp_path, old, new):
    text = open(DECK).read()
    assert old in text
    deck = tmp_path / "deck.ups"
    deck.write_text(text.replace(old, new))
    return str(deck)


@pytest.mark.parametrize("old,new,match", [
    ("<useCrackModel>      true  </useCrackModel>",
     "<useCrackModel> true </useCrackModel><useInductionTime> true </useInductionTime>",
     "IgnitionConst"),
    ("<toMaterial>   product   </toMaterial>",
     "<toMaterial>   product   </toMaterial><burnMaterial> PBX9501 </burnMaterial>",
     "burnMaterial.*not implemented"),
])
def test_refusals(tmp_path, old, new, match):
    """What DDT1 does not do is refused in one line naming the tag."""
    from framework.controller import Controller
    with pytest.raises(InputError, match=match):
        Controller(_deck_with(tmp_path, old, new), quiet=True, filebase=str(tmp_path / "x.uda"))


def test_burnrate_deck_against_sus(tmp_path):
    """Uintah's BurnRate.ups: the burned mass of its first 8 steps (delT from delt_init, the
    same in both) is sus's to 1e-4 (measured 3.2e-5)."""
    from framework.controller import Controller
    deck = os.path.join(HERE, "uintah_reference", "burnrate.ups")
    c = Controller(deck, quiet=True, filebase=str(tmp_path / "burnrate.uda"))
    c.run()
    burned = np.loadtxt(os.path.join(c.archiver.dir, "totalMassBurned.dat"))
    assert len(burned) == 8
    assert np.allclose(burned[:, 1], SUS_BURNRATE, rtol=1e-4, atol=0)


SUS_INDUCTION_STEP1 = 2.1454985145538663e-07    # s, sus inductionTime of cell 20 after steps 1 and 51


def test_induction_propagation_against_sus(tmp_path):
    """Uintah's InductionPropagation.ups (100 steps): the reactant's first cell (20) warms
    (BurningCriteria 1) from step 1 as sus's, its countTime the elapsed time (sus's at steps 1 and
    51), its inductionTime within 2 % of sus's (measured 1.1 %: the product pressure of the border
    cell, as above); it ignites (2) at the first step whose time reaches its induction time, and
    its neighbour 21 starts warming the step after (its burning neighbour is last step's), as in sus (which ignites it at t = 2.2e-7 .. 2.5e-7 s)."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    deck = os.path.join(HERE, "uintah_reference", "induction_propagation.ups")
    c = Controller(deck, quiet=True, filebase=str(tmp_path / "ip.uda"))
    c.run()
    a = DataArchive(c.archiver.dir)
    crit = [a.read("BurningCriteria", 0, k)[0].ravel() for k in range(1, len(a.timesteps))]
    ind = [a.read("inductionTime", 0, k)[0].ravel()[20] for k in range(1, len(a.timesteps))]
    count = [a.read("countTime", 0, k)[0].ravel()[20] for k in range(1, len(a.timesteps))]
    times = a.times[1:]
    assert crit[0][20] == D.WARMINGUP and np.count_nonzero(crit[0]) == 1
    assert abs(ind[0] / SUS_INDUCTION_STEP1 - 1) < 2e-2
    assert np.isclose(count[49], times[49], rtol=1e-12)
    lit = next(k for k, cr in enumerate(crit) if cr[20] == D.CONDUCTIVE)
    assert times[lit - 1] < ind[lit] <= times[lit] and 2.2e-7 < times[lit] < 2.6e-7
    assert crit[lit][21] == 0 and crit[lit + 1][21] == D.WARMINGUP and np.count_nonzero(crit[lit + 1]) == 2
