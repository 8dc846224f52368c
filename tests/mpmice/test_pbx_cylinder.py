"""Uintah's MPMICE regression deck PBX_Cylinder_Ext_Load (PBX_array/oneCylinder.ups): a PBX 9501
cylinder in air under a pressure load curve, with DDT1 and the heat exchange coefficients of
<exchange_properties><CoefficientModel><heat> linearVariation (Uintah's
ExchangeCoefficients::getVariableExchangeCoeff, kernels.mass_ratio_coefficients).

Kernel tests: the coefficient of a material pair against Uintah's piecewise rule, and the
exchange with it conserving the mixture's momentum and energy.

Deck test: uintah_reference/oneCylinder_small.ups (the R_Tester deck with delt_init 1e-9, 5 steps,
every step saved; its header says why and how the sus reference was made: sus spreads the load
over the whole cylinder side, pysus over its part in the domain, so sus ran with the load scaled
by 0.00975). data/sus_oneCylinder_small.npz is sus's output on that deck, one rank, read with
framework.uintah_uda.UintahArchive: the times, press_CC, temp_CC of the air and vol_frac_CC of
the cylinder over the interior cells after steps 3 and 5, the number of particles, and the
.dat files of the conservation sums (TotalMass, KineticEnergy, TotalMomentum, TotalIntEng and
their `_1`, `_2` per fluid). data/sus_oneCylinder_small_loaded.npz: sus's p.x and p.velocity (x, y)
of the 113 loaded particles of its first particle layer (p.loadCurveID > 0, z < dz/2) after each
of the 5 steps, and the largest particle speed of each step.

Measured (pysus against sus): the steps' delT equal; in the air's cells (the cylinder's volume
fraction < 0.5) press_CC within 6.8e-7 and temp_CC within 6.8e-6 of their maxima after 5
steps (2.8e-6 and 1.9e-6 after 3; press_CC 3.3e-5 before the start's pressure was Uintah's,
docs/MPMICE.md "Gas start"); vol_frac_CC within 3.6e-5 everywhere (4.0e-6 after 3 steps); half sus's particles
(pysus puts one particle layer across a one-cell direction, sus <res> 2 layers of half the mass).
The loaded particles' velocity within 2.1e-6 of the largest particle speed after 1 step and
1.05e-3 after 5: they sit in the last cells before the open x+ and y+ faces, where the solid's
dV/dt in the extra cells (MPMICE's computeCCVelAndTempRates) comes from the extra cell's own
nodes (before that fix, 23 % after 1 step and 31 % after 5). The trace air in the cylinder's
cells differs more at the cylinder's rim (its temperature by 27 K of 330 K after 3 steps; with
constant coefficients 176 K, so the test sees the model).
The solid's own heating (ViscoSCRAM's p.dTdt): after 1 step the loaded particles' temperature
rise per mean stress is sus's within 0.5 % (sus's own spread; the volume term -Gamma T tr D
dominates); after 5 steps p.temperature within 0.20 K of sus's (sus's rise up to 0.53 K), the
interior's unchanged in both. The rise differs as the rim particles' stress does (by up to 50 %
after 1 step: pysus stresses 760 particles, sus 560), not by the heating.
data/sus_oneCylinder_small_heating.npz: sus's p.temperature after steps 1 and 5 and mean stress
after step 1, one particle per (x, y) (key: p.x / 2.5e-5 rounded), from the deck as above.
"""
import pathlib

import numpy as np
import pytest

from components.ice import kernels as K
from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "oneCylinder_small.ups"


def _uintah_coefficient(m_m, m_q):
    """ExchangeCoefficients::getVariableExchangeCoeff, branch by branch."""
    r = (m_q / m_m) ** 2
    if r < 1e-12:
        return 1e12
    if r < 1e-5:
        return 1.0 / r
    if r < 1e5:
        return 1e5
    if r < 1e12:
        return r
    return 1e12


@pytest.mark.parametrize("ratio", [1e-9, 1e-6, 2e-3, 1e-2, 0.5, 1.0, 3.0, 1e3, 5e4, 1e7])
def test_mass_ratio_coefficient_is_uintahs(ratio):
    """Every branch of Uintah's rule, for both orders of a pair (Q symmetric, zero diagonal)."""
    masses = (np.full((1, 1, 1), 2.0), np.full((1, 1, 1), 2.0 * ratio), np.full((1, 1, 1), 2.0))
    Q = np.full((3, 3), -1.0)
    K.mass_ratio_coefficients(Q, masses, 0, 0, 0, 3)
    assert Q[0, 1] == Q[1, 0] == pytest.approx(_uintah_coefficient(2.0, 2.0 * ratio), rel=1e-14)
    assert Q[1, 2] == pytest.approx(_uintah_coefficient(2.0 * ratio, 2.0), rel=1e-14)
    assert Q[0, 2] == 1e5 and np.all(np.diag(Q) == 0.0)


def _cells(values):
    return tuple(np.full((1, 1, 1), float(v)) for v in values)


def test_variable_exchange_conserves_and_locks_a_trace():
    """Solid, air and a trace: the variable heat exchange conserves momentum and energy; the
    trace (mass ratio 1e-15, coefficient 1e12) ends near the solid's temperature while the air
    (mass ratio 0.1: 1e5) keeps its own; without the flags the kernel is exchange_cells."""
    lo, hi = np.zeros(3, np.int64), np.ones(3, np.int64)
    masses = _cells([1.0, 0.1, 1e-15])
    vels = [np.array([1.0, 0, 0]), np.array([-2.0, 1, 0]), np.array([5.0, 0, 0])]
    moms = tuple(np.full((1, 1, 1, 3), m[0, 0, 0]) * v for m, v in zip(masses, vels))
    cvs = np.array([1000.0, 717.0, 717.0])
    temps = [300.0, 600.0, 1500.0]
    engs = tuple(m * c * t for m, c, t in zip(masses, cvs, temps))
    vfs = _cells([0.99, 0.01 - 1e-12, 1e-12])
    sps = tuple(f / m for f, m in zip(vfs, masses))          # consistent: theta = m v / V, V = 1
    Kc, Hc = np.zeros((3, 3)), np.zeros((3, 3))
    out = lambda: (tuple(np.zeros((1, 1, 1, 3)) for _ in range(3)), tuple(np.zeros((1, 1, 1)) for _ in range(3)))
    mom_v, eng_v = out()
    K.exchange_cells_variable(masses, moms, engs, vfs, sps, cvs, mom_v, eng_v, lo, hi, 1e-9, Kc, Hc, False, True)
    assert sum(e[0, 0, 0] for e in eng_v) == pytest.approx(sum(e[0, 0, 0] for e in engs), rel=1e-14)
    assert np.allclose(sum(m[0, 0, 0] for m in mom_v), sum(m[0, 0, 0] for m in moms), rtol=1e-14)
    t_after = [e[0, 0, 0] / (m[0, 0, 0] * c) for e, m, c in zip(eng_v, masses, cvs)]
    # beta = dt theta H v / cv: 1.38e3 to the solid, 13.9 to the air; implicit: the weighted mean
    assert t_after[2] == pytest.approx((1500.0 + 1380 * 300.0 + 13.9 * 600.0) / 1394.9, abs=1.0)
    assert t_after[1] == pytest.approx(600.0, rel=1e-3)
    mom_c, eng_c = out()
    mom_n, eng_n = out()
    K.exchange_cells(masses, moms, engs, vfs, sps, cvs, mom_c, eng_c, lo, hi, 1e-9, Kc + 1e5, Hc + 1e5)
    K.exchange_cells_variable(masses, moms, engs, vfs, sps, cvs, mom_n, eng_n, lo, hi, 1e-9, Kc + 1e5, Hc + 1e5,
                              False, False)
    assert all(np.array_equal(a, b) for a, b in zip(eng_c + mom_c, eng_n + mom_n))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    ctl = run_deck(DECK.read_text(), tmp_path_factory.mktemp("pbx"), "pbx")
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_oneCylinder_small.npz")


def test_pbx_cylinder_steps_as_uintah(runs):
    """The five steps' times as sus's (delt_init 1e-9, growing by 1.5)."""
    da, sus = runs
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-12, atol=0)


@pytest.mark.parametrize("step", [3, 5])
def test_pbx_cylinder_fields_as_uintah(runs, step):
    """press_CC and the air's temp_CC in the air's cells, vol_frac_CC of the cylinder everywhere,
    the particle count (module docstring for the measured figures)."""
    da, sus = runs
    vf = sus[f"vol_frac_CC_0_step{step}"]
    air = vf < 0.5
    assert air.sum() > 100
    for label, m, key in (("press_CC", 0, "press_CC"), ("temp_CC", 1, "temp_CC_1")):
        got, want = da.read(label, m, step)[0][:, :, 0], sus[f"{key}_step{step}"]
        assert np.abs(got - want)[air].max() < 5e-5 * np.abs(want).max(), label
    assert np.abs(da.read("vol_frac_CC", 0, step)[0][:, :, 0] - vf).max() < 5e-5
    assert 2 * len(da.particles(0, step)["p.x"]) == int(sus[f"n_particles_step{step}"])
    if step == 3:        # the trace air in the cylinder's cells: the linearVariation coefficients
        t_air = da.read("temp_CC", 1, step)[0][:, :, 0]
        assert np.abs(t_air - sus["temp_CC_1_step3"])[vf > 0.999999].max() < 60.0


def test_pbx_cylinder_loaded_particles_as_uintah(runs):
    """The loaded particles' p.velocity against sus's, every step (module docstring: 1.05e-3 of
    the largest speed after 5 steps, 2.1e-6 after 1)."""
    da, _ = runs
    ref = np.load(HERE / "data" / "sus_oneCylinder_small_loaded.npz")
    for step, tol in ((1, 1e-5), (2, 5e-4), (3, 1e-3), (4, 1.5e-3), (5, 2.5e-3)):
        p = da.particles(0, step)
        where = {tuple(np.round(x / 2.5e-5).astype(int)): i for i, x in enumerate(p["p.x"][:, :2])}
        i = np.array([where[tuple(np.round(x / 2.5e-5).astype(int))] for x in ref[f"p_x_step{step}"]])
        assert np.abs(p["p.x"][i, :2] - ref[f"p_x_step{step}"]).max() < 1e-8
        err = np.abs(p["p.velocity"][i, :2] - ref[f"p_velocity_step{step}"]).max()
        assert err < tol * ref["max_speed"][step - 1], (step, err)


def test_pbx_cylinder_conservation_sums_as_uintah(runs):
    """The saved sums as sus's MPMICE writes them: TotalMass, KineticEnergy and TotalMomentum of
    the particles plus every fluid, TotalIntEng of the fluids, each fluid's in name_<m>.dat, one
    line per step from the first (none at t = 0). Measured over the 5 steps, of sus's largest:
    TotalMass 1.1e-12 (the particles' mass exactly; the air's 6.1e-9), TotalIntEng 3.4e-7, the air's
    KineticEnergy 2.3e-3 and TotalMomentum 1.2e-3; with the particles' KineticEnergy 8.6e-4,
    TotalMomentum 2.2e-5."""
    da, sus = runs
    for name, m, rtol in (("TotalMass", -1, 1e-11), ("TotalMass", 1, 2e-8), ("TotalIntEng", -1, 1e-6),
                          ("TotalIntEng", 1, 1e-6), ("KineticEnergy", 1, 5e-3), ("TotalMomentum", 1, 3e-3),
                          ("KineticEnergy", -1, 2e-3), ("TotalMomentum", -1, 1e-4)):
        t, v = da.reduction(name, m)
        want = sus[name if m < 0 else f"{name}_{m}"]
        assert np.allclose(t, want[:, 0], rtol=1e-12, atol=0), name
        want = want[:, 1:].squeeze()
        assert np.abs(v - want).max() < rtol * np.abs(want).max(), (name, m)
    particles = float(da.particles(0, 0)["p.mass"].sum())
    _, total = da.reduction("TotalMass")
    gas = da.reduction("TotalMass", 1)[1] + da.reduction("TotalMass", 2)[1]
    assert np.allclose(total, particles + gas, rtol=1e-14, atol=0)
    assert np.all(gas > 1e-4 * total)            # the air counts (8.4e-8 kg of 4.6e-4)


def test_pbx_cylinder_solid_heating_as_uintah(runs):
    """ViscoSCRAM's heating of the solid against sus (module docstring): the temperature rise per
    mean stress after 1 step, p.temperature after 5 steps, the unloaded interior unchanged."""
    da, _ = runs
    ref = np.load(HERE / "data" / "sus_oneCylinder_small_heating.npz")
    for step in (1, 5):
        p = da.particles(0, step)
        at = {tuple(k): i for i, k in enumerate(ref[f"p_x_key_step{step}"])}
        i = np.array([at[tuple(k)] for k in np.round(p["p.x"][:, :2] / 2.5e-5).astype(int)])
        rise, rise_sus = p["p.temperature"] - 300.0, ref[f"p_temperature_step{step}"][i] - 300.0
        r = np.hypot(p["p.x"][:, 0], p["p.x"][:, 1])
        inner = r < 0.5 * r.max()
        assert np.all(rise_sus[inner] == 0.0) and np.abs(rise[inner]).max() < 1e-9
        if step == 1:
            mean = np.trace(p["p.stress"], axis1=1, axis2=2) / 3.0
            mean_sus = ref["p_mean_stress_step1"][i]
            both = (np.abs(mean) > 1e3) & (np.abs(mean_sus) > 1e3)
            assert both.sum() > 300
            np.testing.assert_allclose(rise[both] / mean[both], rise_sus[both] / mean_sus[both], rtol=1e-2)
        else:
            assert rise_sus.max() > 0.5 and np.abs(rise - rise_sus).max() < 0.25
