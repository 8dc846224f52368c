"""Uintah's artificial bulk viscosity of the MPM solids (components/mpm/artificial_viscosity.py).

inputs/MPM/adiabatic_copper_jc.ups is Uintah's adiCuJC4000s696K.ups (artificial viscosity on)
with Uintah's stress update (<stress_update>usl). tests/mpm/data/adiCuJC_av_sus.txt holds sus's copper particle after steps
1-20, every 10th and the last of its whole run (the file's header says how it was made); pysus
must give the same times, stress, plastic strain and temperature to round-off (measured over
every step: delT 6e-12, stress 2e-7 of its largest component, plastic strain 2e-8, T 1.5e-9);
tests/mpm/data/adiCuJC_bndy_sus.txt holds sus's sums on the faces of its <boundary_traction_faces>
and AccStrainEnergy, which pysus must also give.
The flow stress must also follow the Johnson-Cook law on the adiabatic path (closed form
below), which is what Uintah's test is for.
"""
import math
from pathlib import Path

import numpy as np
import pytest

from components.mpm.artificial_viscosity import bulk_viscosity
from framework.problemspec import InputError

from .helpers import MPM_INPUTS, deck_text, run

DATA = np.loadtxt(Path(__file__).parent / "data" / "adiCuJC_av_sus.txt")


def _every_step():
    """The deck with an output every timestep, as sus was run for the reference data
    (<outputTimestepInterval>1; an <outputInterval> of 1e-12 gives the same outputs, but the
    archiver steps its next output time through every 1e-12 s of the run: 8 CPU s a run)."""
    text = deck_text(MPM_INPUTS / "adiabatic_copper_jc.ups")
    every = text.replace("<outputInterval>1.0e-6</outputInterval>", "<outputTimestepInterval>1</outputTimestepInterval>")
    assert every != text
    return every


@pytest.fixture(scope="module")
def copper(tmp_path_factory):
    _, da = run(_every_step(), tmp_path_factory.mktemp("av"))
    return da


def test_whole_run_equals_sus(copper):
    da = copper
    assert len(da.times) - 1 == int(DATA[-1, 0])             # 279 steps, as sus
    for k, t, sxx, szz, ep, T in DATA:
        p = da.particles(1, int(k))
        s = p["p.stress"][0]
        assert da.times[int(k)] == pytest.approx(t, rel=1e-10), k
        assert max(abs(s[0, 0] - sxx), abs(s[2, 2] - szz)) < 1e-6 * max(abs(sxx), abs(szz)), k
        assert p["p.plasticStrain"][0] == pytest.approx(ep, rel=1e-7), k
        assert p["p.temperature"][0] == pytest.approx(T, rel=1e-8), k
    assert DATA[-1, 4] > 0.5                                  # strained past 50 %


BNDY = np.loadtxt(Path(__file__).parent / "data" / "adiCuJC_bndy_sus.txt")


def _per_step(da, label):
    """A saved reduction's (times, values) of steps 1, 2, ... (pysus also writes t = 0 for some)."""
    t, v = da.reduction(label)
    return t[t > 0], v[t > 0]


def test_boundary_sums_equal_sus(copper):
    """Its <boundary_traction_faces>[zminus,zplus] (components/mpm/boundary_tractions.py): the
    force on z- as the copper is pulled off it, the contact areas of z- and z+ (the rigid piston's
    volume reaches the nodes of z+ near step 230) and AccStrainEnergy, a line every step as sus
    writes them, against sus's (measured over every step: the force 1.4e-8 of its largest, the
    areas 1.2e-6 and 2e-11 of theirs, AccStrainEnergy 7e-9)."""
    series = {n: _per_step(copper, n) for n in ("BndyForce_zminus", "BndyForce_zplus", "BndyContactArea_zminus",
                                                "BndyContactArea_zplus", "AccStrainEnergy")}
    for n, (t, _) in series.items():
        assert len(t) == int(BNDY[-1, 0]), n
    fmax, amax = np.abs(BNDY[:, 2]).max(), BNDY[:, 4].max()
    assert fmax > 5e4 and BNDY[-1, 5] > 1e-5                 # both faces are reached
    for k, t, fz_minus, fz_plus, a_minus, a_plus, acc in BNDY:
        i = int(k) - 1
        f_minus = series["BndyForce_zminus"][1][i]
        assert series["BndyForce_zminus"][0][i] == pytest.approx(t, rel=1e-10), k
        assert abs(f_minus[2] - fz_minus) < 1e-7 * fmax and abs(f_minus[:2]).max() < 1e-9 * fmax, k
        assert np.all(series["BndyForce_zplus"][1][i] == fz_plus), k       # the piston is rigid: no force
        assert abs(series["BndyContactArea_zminus"][1][i] - a_minus) < 5e-6 * amax, k
        assert series["BndyContactArea_zplus"][1][i] == pytest.approx(a_plus, rel=1e-9, abs=1e-15 * amax), k
        assert series["AccStrainEnergy"][1][i] == pytest.approx(acc, rel=1e-7), k


def _jc(ep, T):
    """Johnson-Cook flow stress of the deck at 4000/s."""
    Ts = (T - 298.0) / (1793.0 - 298.0)
    return (90e6 + 292e6 * ep ** 0.31) * (1.0 + 0.025 * math.log(4000.0)) * (1.0 - Ts ** 1.09)


def test_flow_stress_follows_adiabatic_johnson_cook(copper):
    """While the copper yields (steps 2-121, plastic strain 0.6-51 %), q = |s_zz - s_xx| stays
    within 2.5 % of sigma_y(ep, T_ad(ep)) with dT_ad/d ep = 0.9 sigma_y/(rho c_p) from 696 K (RK4),
    and within 0.6 % once the single particle's early lateral ringing (every other step 1-2 %
    low up to step 25) has died out (measured: 0.2-0.5 %, the Mie-Gruneisen isentropic cooling
    keeping T a few K below T_ad)."""
    path = [(0.0, 696.0)]
    ep, T, h = 1e-12, 696.0, 1e-3
    heat = lambda e, t: 0.9 * _jc(e, t) / (8930.0 * 414.0)    # noqa: E731
    while ep < 0.6:
        k1 = heat(ep, T)
        k2 = heat(ep + h / 2, T + h / 2 * k1)
        k3 = heat(ep + h / 2, T + h / 2 * k2)
        T += h / 6 * (k1 + 2 * k2 + 2 * k3 + heat(ep + h, T + h * k3))
        ep += h
        path.append((ep, T))
    path = np.array(path)
    checked = 0
    for k in range(2, 122):
        p = copper.particles(1, k)
        ep, s = p["p.plasticStrain"][0], p["p.stress"][0]
        sy = _jc(ep, np.interp(ep, path[:, 0], path[:, 1]))
        assert abs(s[2, 2] - s[0, 0]) == pytest.approx(sy, rel=0.025 if k < 30 else 0.006), k
        checked += 1
    assert checked == 120 and ep > 0.5


def test_bulk_viscosity_formula():
    """q = rho (A1 |c trD dx| + A2 (trD dx)^2), c = sqrt(K/rho), rho = rho0/J; 0 in expansion."""
    L = np.zeros((2, 3, 3))
    L[0] = np.diag([-100.0, -50.0, 30.0])
    L[1] = np.diag([100.0, -50.0, 30.0])
    F = np.array([np.diag([0.9, 1.0, 1.0])] * 2)
    q = np.empty(2)
    bulk_viscosity(L, F, 8000.0, 1.0e11, 0.01, 0.2, 2.0, q)
    rho = 8000.0 / 0.9
    trD = -120.0
    assert q[0] == pytest.approx(rho * (0.2 * math.sqrt(1.0e11 / rho) * 120.0 * 0.01 + 2.0 * (trD * 0.01) ** 2),
                                 rel=1e-14)
    assert q[1] == 0.0


@pytest.mark.parametrize("edit, words", [
    (('<constitutive_model type="rigid">\n          <shear_modulus> 46.0e9  </shear_modulus>\n          '
      '<bulk_modulus>  129.0e9 </bulk_modulus>\n          <coeff_thermal_expansion> 0.00 </coeff_thermal_expansion>',
      '<constitutive_model type="jwlpp_mpm"><ignition_pressure>2.0e8</ignition_pressure>'
      '<murnaghan_K>1.9342e-10</murnaghan_K><murnaghan_n>15.2</murnaghan_n><jwl_A>7.73037e11</jwl_A>'
      '<jwl_B>21.629e9</jwl_B><jwl_C>1.339e9</jwl_C><jwl_R1>4.5</jwl_R1><jwl_R2>1.5</jwl_R2><jwl_om>0.33</jwl_om>'
      '<jwl_rho0>1844.0</jwl_rho0><reaction_G>1.0</reaction_G><reaction_b>1.05</reaction_b>'),
     ("artificial viscosity", "jwlpp_mpm", "accepted models")),
    (("<artificial_viscosity>         true", "<artificial_viscosity_heating>true</artificial_viscosity_heating>"
      "<artificial_viscosity>false"), ("artificial_viscosity_heating", "needs <artificial_viscosity>true")),
    (("<artificial_viscosity>         true", "<artificial_viscosity_coeff1>-1</artificial_viscosity_coeff1>"
      "<artificial_viscosity>true"), ("artificial_viscosity_coeff1",)),
])
def test_bad_input_is_one_clean_line(tmp_path, edit, words):
    text = deck_text(MPM_INPUTS / "adiabatic_copper_jc.ups")
    assert edit[0] in text
    text = text.replace(edit[0], edit[1])
    (tmp_path / "d.ups").write_text(text)
    from framework.controller import Controller
    with pytest.raises(InputError) as e:
        Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "r.uda"))
    msg = str(e.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg


SIBLINGS = np.loadtxt(Path(__file__).parent / "data" / "adiCu_flow_models_av_sus.txt")


@pytest.mark.parametrize("index, model", list(enumerate(["MTS", "PTW", "SCG", "ZA"])))
def test_other_flow_models_equal_sus(tmp_path, index, model):
    """Uintah's sibling decks adiCu{MTS,PTW,SCG,ZA}4000s696K.ups are the JC deck with other
    flow, shear-modulus and melting models (test_elastic_plastic_hp.FLOWS holds their blocks;
    their other extra tags are implicit MPM's or read and unused): run to the end, they give
    sus's times, stress, plastic strain and temperature (measured over every step: delT 1.4e-10,
    stress 3e-7, ep 3.3e-8, T 1.6e-9)."""
    from .test_elastic_plastic_hp import FLOWS
    text = _every_step()
    start = text.index('<flow_model type = "johnson_cook">')
    end = text.index("<yield_condition")
    _, da = run(text[:start] + FLOWS[model] + "\n          " + text[end:], tmp_path)
    rows = SIBLINGS[SIBLINGS[:, 0] == index]
    assert len(da.times) - 1 == int(rows[-1, 1])
    for _, k, t, sxx, szz, ep, T in rows:
        p = da.particles(1, int(k))
        s = p["p.stress"][0]
        assert da.times[int(k)] == pytest.approx(t, rel=1e-9), k
        assert max(abs(s[0, 0] - sxx), abs(s[2, 2] - szz)) < 1e-6 * max(abs(sxx), abs(szz)), k
        assert p["p.plasticStrain"][0] == pytest.approx(ep, rel=1e-7), k
        assert p["p.temperature"][0] == pytest.approx(T, rel=1e-8), k
