"""UCNHVar (components/mpm/constitutive/ucnh_var.py): UCNH with moduli from p.color; Uintah's sus.

Uintah's disk_UCNHVar.ups (tests/mpm/uintah_reference/) as it is: test_damage_draws.py.
Edited (the gradient-enhanced velocity projection, the ThresholdVar damage and
its erosion and the saves of their variables removed; <interpolator>gimp (with fast_cpdi,
pysus and sus part at the x+ wall from the first step a particle's domain reaches it, 1e-7 in
velocity growing to 2e-2 in stress: a difference of the CPDI transfer at the wall, not of
the model); both objects at 10 m/s, so that the disk hits the wall and yields within 200
steps), sus ran 200 steps; tests/mpm/data/sus_disk_UCNHVar_gimp.npz holds, for every tenth
particle in the order of its position at step 40 (before the impact, when both codes have
moved every particle by the same 40 steps), p.stress and p.plasticStrain at steps 120, 160
and 200, and StrainEnergy.dat of every step, read from sus's uda.
"""
import dataclasses
import pathlib
import re

import numpy as np
import pytest

from components.mpm.constitutive import comp_neo_hook_plastic as cnhp, ucnh_var
from framework.problemspec import InputError

from .helpers import run

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "disk_UCNHVar.ups"
SUS = HERE / "data" / "sus_disk_UCNHVar_gimp.npz"
TABLE = ucnh_var.Params((0.0, 1.0), (3.2e6, 6.4e6), (1.2e6, 2.4e6), (1.0e3, 2.0e3), (1.0e3, 2.0e3), 1000.0, True)


def test_properties_interpolate_in_color():
    """Linear in color; the last entry's above the last color; extended below the first, as
    Uintah's findPropertiesFromColor."""
    C, K, G, Y, H = TABLE.table()
    assert ucnh_var.properties(0.0, C, K, G, Y, H) == (3.2e6, 1.2e6, 1e3, 1e3)
    assert ucnh_var.properties(1.0, C, K, G, Y, H) == (6.4e6, 2.4e6, 2e3, 2e3)
    assert ucnh_var.properties(0.25, C, K, G, Y, H) == pytest.approx((4.0e6, 1.5e6, 1.25e3, 1.25e3), rel=1e-15)
    assert ucnh_var.properties(-0.5, C, K, G, Y, H) == pytest.approx((1.6e6, 0.6e6, 500.0, 500.0), rel=1e-15)
    assert ucnh_var.properties(7.0, C, K, G, Y, H) == (6.4e6, 2.4e6, 2e3, 2e3)


@pytest.mark.parametrize("plastic", [True, False])
def test_each_particle_is_ucnh_with_its_moduli(plastic):
    """Particles of colors 0, 0.5 and 1 driven through a shear and stretch past yield: each
    has UCNH's stress, plastic strain and bElBar with the moduli of its color (and
    comp_neo_hook's without plasticity); the wave speed after the first step is
    max(sqrt((K + 4G/3) J/rho_0) + |v|)."""
    params = dataclasses.replace(TABLE, usePlasticity=plastic)
    colors = np.array([0.0, 0.5, 1.0])
    n = 3
    a, be = ucnh_var.initial_state(params, n)
    refs = [cnhp.Params(*(np.interp(c, params.colors, getattr(params, f)) for f in
                          ("bulk_modulus", "shear_modulus", "yield_stress", "hardening_modulus")),
                        usePlasticity=plastic) for c in colors]
    ref_state = [cnhp.initial_state(r, 1) for r in refs]
    F_old = np.tile(np.eye(3), (n, 1, 1))
    vel = np.array([[1.0, -2.0, 0.5]] * n)
    for k in range(1, 21):
        F = np.eye(3) + np.array([[0.01 * k, 0.02 * k, 0], [0, -0.004 * k, 0], [0, 0, 0]])
        F_new = np.tile(F, (n, 1, 1))
        vol, mass = np.full(n, np.linalg.det(F)), np.ones(n)
        s, e = np.zeros((n, 3, 3)), np.zeros(n)
        a2, be2 = np.zeros(n), np.zeros((n, 3, 3))
        ws = ucnh_var.update(params, None, F_old, F_new, vol, mass, vel, 1e-6, None, s, e, (a, be), (a2, be2),
                             color=colors)
        for i, r in enumerate(refs):
            rs, re_ = np.zeros((1, 3, 3)), np.zeros(1)
            ra2, rbe2 = np.zeros(1), np.zeros((1, 3, 3))
            cnhp.update(r, None, F_old[i:i + 1], F_new[i:i + 1], vol[i:i + 1], mass[i:i + 1], vel[i:i + 1], 1e-6,
                        None, rs, re_, ref_state[i], (ra2, rbe2))
            assert np.allclose(s[i], rs[0], rtol=0, atol=1e-12 * np.abs(rs).max())
            assert e[i] == pytest.approx(re_[0], rel=1e-11)
            if plastic:
                assert a2[i] == pytest.approx(ra2[0], rel=1e-12, abs=1e-15)
                assert np.allclose(be2[i], rbe2[0], rtol=0, atol=1e-13)
            ref_state[i] = (ra2, rbe2)
        J = np.linalg.det(F)
        assert ws[0] == pytest.approx(np.sqrt((6.4e6 + 4 / 3 * 2.4e6) * J / 1000.0) + 1.0, rel=1e-13)
        F_old, a, be = F_new, a2, be2
    assert (a.max() > 0.05) == plastic


def edited_deck(steps=200, every=40):
    """disk_UCNHVar.ups with the edits of the module docstring, sus's USL stress update."""
    text = open(DECK).read()
    for old, new in (("<UseGradientEnhancedVelocityProjection>true\n                         "
                      "</UseGradientEnhancedVelocityProjection>", ""),
                     ('<erosion algorithm = "ZeroStress"/>', ""),
                     ('<save label = "p.epsf" levels = "-1"/>', ""), ('<save label = "p.localizedMPM"/>', ""),
                     ("fast_cpdi", "gimp"),
                     ("<time_integrator>explicit  </time_integrator>",
                      "<time_integrator>explicit</time_integrator><stress_update>usl</stress_update>"),
                     ("<maxTime>0.30</maxTime>", f"<maxTime>0.30</maxTime><max_Timesteps>{steps}</max_Timesteps>"),
                     ("<outputInterval>.01</outputInterval>",
                      f"<outputTimestepInterval>{every}</outputTimestepInterval>")):
        assert old in text, old
        text = text.replace(old, new)
    text, n = re.subn(r'<damage_model type="ThresholdVar">.*?</damage_model>', "", text, flags=re.S)
    text, m = re.subn(r"<velocity>\[1\.0,0\.0,0\]</velocity>", "<velocity>[10.0,0.0,0]</velocity>", text)
    assert n == 1 and m == 2
    return text


def test_disk_UCNHVar_as_sus(tmp_path):
    """The edited deck: sus's times; at steps 120, 160, 200 (through the impact and
    yielding, plastic strain to 0.64) sus's p.stress (measured: 7e-9 of the largest) and
    p.plasticStrain (1.4e-10), and sus's StrainEnergy every step (1.3e-11)."""
    _, da = run(edited_deck(), tmp_path)
    sus = np.load(SUS)
    steps = list(da.timesteps)
    assert steps == [0, 40, 80, 120, 160, 200]
    x40 = da.particles(0, 1)["p.x"]
    order = np.lexsort(np.round(x40, 9).T[::-1])[::10]
    assert np.abs(x40[order] - sus["x40"]).max() < 1e-14
    ids = da.particles(0, 1)["p.particleID"][order]
    for k, step in enumerate(sus["timestep"]):
        p = da.particles(0, steps.index(step))
        at = {v: i for i, v in enumerate(p["p.particleID"])}
        j = [at[v] for v in ids]
        assert da.times[steps.index(step)] == pytest.approx(sus["time"][k], rel=1e-11)
        s = p["p.stress"][j]
        assert np.abs(s - sus["stress"][k]).max() < 5e-8 * np.abs(sus["stress"][k]).max()
        assert np.allclose(p["p.plasticStrain"][j], sus["plasticStrain"][k], rtol=0, atol=1e-9)
    assert sus["plasticStrain"][-1].max() > 0.6
    t, se = da.reduction("StrainEnergy")
    assert len(se) - 1 == len(sus["StrainEnergy"])
    assert np.allclose(t[1:], sus["se_time"], rtol=1e-11)
    assert np.allclose(se[1:], sus["StrainEnergy"], rtol=1e-9, atol=1e-12 * np.max(sus["StrainEnergy"]))


@pytest.mark.parametrize("old,new,words", [
    ("""<entry>
                    <color> 1.0   </color>
                    <bulk_modulus>6.4e6</bulk_modulus>
                    <shear_modulus>2.4e6</shear_modulus>
                    <yield_stress>2.0e3</yield_stress>
                    <hardening_modulus>2.0e3</hardening_modulus>
                  </entry>""", "", ("variable_properties", "two")),
    ("<color> 1.0   </color>\n                    <bulk_modulus>6.4e6", "<color> -1.0   </color>\n"
     "                    <bulk_modulus>6.4e6", ("color", "increase")),
    ("<bulk_modulus>6.4e6</bulk_modulus>", "<bulk_modulus>-6.4e6</bulk_modulus>", ("bulk_modulus",)),
    ("<withColor>      true      </withColor>", "", ("withColor", "UCNHVar")),
    ("<usePlasticity> true </usePlasticity>", "<usePlasticity> true </usePlasticity><useInitialStress>true"
     "</useInitialStress>", ("useInitialStress",)),
])
def test_bad_input_is_one_line(tmp_path, old, new, words):
    text = edited_deck(steps=1)
    assert old in text
    with pytest.raises(InputError) as e:
        run(text.replace(old, new), tmp_path)
    msg = str(e.value)
    assert "\n" not in msg and ".ups:" in msg
    for w in words:
        assert w in msg, msg
