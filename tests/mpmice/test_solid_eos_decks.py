"""The solids' EOS in MPMICE's equilibration for the models that had a stand-in before, against
sus on one small deck: data/solid_eos_slab.ups, a 3 mm slab in air (1D, 20 cells, linear
interpolation), the slab's model filled in per case. data/sus_solid_eos_slab.npz is sus's output
on the same deck (one rank, read with framework.uintah_uda): press_equil_CC, press_CC, sp_vol_CC
of the solid and the air, and the solid's speedSound_CC after the steps listed.

  ideal    Uintah's ideal_gas (IdealGasMP) as pysus's ideal_gas_fluid (eos.py SOLID_IDEAL_GAS),
           a 5 kg/m^3 gas slab at 300 K in 1 atm air. After step 1 pressure 5e-13, specific
           volumes 3.2e-12, sound speed (sqrt(gamma (gamma-1) cv T)) 1.6e-12; later steps differ
           by the two models' stress (0.4 % after step 5).
  jwlpp    jwlpp_mpm (JWLppMPM, SOLID_JWLPP: rho0 at any pressure), 10 atm air. After step 1
           pressure and specific volumes to 1e-15; sus's speedSound_CC is not compared (its model
           leaves it unset: 2.2e-155 m/s there, pysus the JWL's 4998 m/s).
  rigid    rmpmice, comp_neo_hook K = 1.17e9 with <useModifiedEOS>, 10 atm air: the deck's
           model's UCNH EOS (Uintah's RigidMPM keeps the model), pysus with <gas_start>geometry
           (Uintah's start and scaling). After step 5: pressure 9.6e-13, the air's sp_vol 9.6e-13,
           the solid's 8e-16, its sound speed 3e-16 (the Murnaghan stand-in, unscaled: 1.1e-2 and
           3.9e-4).
  rigidnm  the same without <useModifiedEOS>, the air at 1013 Pa (UCNH in tension): after step 1
           pressure 1.3e-10; after step 5 pressure 1.9e-5, the solid's sp_vol 1e-11, sound speed
           5e-12, the times 1e-6 (the trace air inside the slab, 1e-12 of its cells, is not
           compared after step 5).

comp_mooney_rivlin is refused: Uintah's CompMooneyRivlin has no EOS (sus stops at step 1 with NaN).
Uintah's own rmpmice deck advect_periodic.ups (uintah_reference/, unchanged; the run's edits in
advect_periodic_text) against data/sus_advect_periodic_3steps.npz, every cell after steps 1 and 3.
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = (HERE / "data" / "solid_eos_slab.ups").read_text()
JWLPP = ("<constitutive_model type=\"jwlpp_mpm\"><ignition_pressure>2.0e8</ignition_pressure>"
         "<murnaghan_K>1.9342e-10</murnaghan_K><murnaghan_n>15.2</murnaghan_n><jwl_A>7.73037e11</jwl_A>"
         "<jwl_B>21.629e9</jwl_B><jwl_C>1.339e9</jwl_C><jwl_R1>4.5</jwl_R1><jwl_R2>1.5</jwl_R2>"
         "<jwl_om>0.33</jwl_om><jwl_rho0>1844.0</jwl_rho0><reaction_G>1.0</reaction_G>"
         "<reaction_b>1.05</reaction_b></constitutive_model>")
UCNH = ("<constitutive_model type=\"comp_neo_hook\"><bulk_modulus>117.0e7</bulk_modulus>"
        "<shear_modulus>43.8e7</shear_modulus>{}</constitutive_model>")
CASES = {   # component, rho0, cv, model block, air pressure
    "ideal": ("mpmice", 5.0, 716.0, "<constitutive_model type=\"ideal_gas_fluid\"><gamma>1.4</gamma>"
              "<specific_heat>716.0</specific_heat><viscosity>0.0</viscosity></constitutive_model>", 101325.0),
    "jwlpp": ("mpmice", 1844.0, 1000.0, JWLPP, 1013250.0),
    "rigid": ("rmpmice", 8900.0, 386.0, UCNH.format("<useModifiedEOS>true</useModifiedEOS>"), 1013250.0),
    "rigidnm": ("rmpmice", 8900.0, 386.0, UCNH.format(""), 1013.25),
    "mooney": ("mpmice", 1000.0, 1000.0, "<constitutive_model type=\"comp_mooney_rivlin\"><he_constant_1>1e5"
               "</he_constant_1><he_constant_2>2e4</he_constant_2><he_PR>.49</he_PR></constitutive_model>",
               1013250.0),
}


def deck(name, steps):
    """The slab deck of a case, as sus ran it (air density from its pressure at 300 K, cv 716,
    gamma 1.4); rmpmice with pysus's <gas_start>geometry."""
    comp, rho0, cv, cm, p_air = CASES[name]
    text = DECK
    if comp == "rmpmice":
        text = text.replace("    <MPM>\n", "    <MPMICE><gas_start>geometry</gas_start></MPMICE>\n    <MPM>\n", 1)
    for key, value in (("COMPONENT", comp), ("RHO0", repr(rho0)), ("CV", repr(cv)), ("CM", cm),
                       ("RHOGAS", repr(p_air / (0.4 * 716.0 * 300.0))), ("PGAS", repr(p_air)), ("STEPS", str(steps))):
        text = text.replace(f"@{key}@", value)
    return text


@pytest.mark.parametrize("name,steps,tol,sound", [
    ("ideal", (1,), 1e-11, True), ("jwlpp", (1,), 1e-14, False), ("rigid", (1, 5), 1e-12, True),
    ("rigidnm", (1,), 1e-9, True), ("rigidnm", (5,), 5e-5, True)])
def test_solid_eos_as_sus(tmp_path, name, steps, tol, sound):
    from framework.archiver import DataArchive
    sus = np.load(HERE / "data" / "sus_solid_eos_slab.npz")
    da = DataArchive(run_deck(deck(name, max(steps)), tmp_path, name).archiver.dir)
    assert np.allclose(da.times[1:max(steps) + 1], sus[f"{name}_times"][:max(steps)],
                       rtol=1e-5 if name == "rigidnm" else 1e-12, atol=0)
    labels = [("press_equil_CC", 0), ("press_CC", 0), ("sp_vol_CC", 0), ("sp_vol_CC", 1)] + \
        [("speedSound_CC", 0)] * sound
    for step in steps:
        for label, m in labels:
            if name == "rigidnm" and step == 5 and (label, m) == ("sp_vol_CC", 1):
                continue            # the trace air inside the slab
            ref = sus[f"{name}_{label}{m}_{step}"]
            ours = np.squeeze(da.read(label, m, step)[0])
            err = np.max(np.abs(ours - ref)) / np.max(np.abs(ref))
            assert err < (2e-10 if name == "rigidnm" and label == "sp_vol_CC" else tol), (label, m, step, err)
    if name == "jwlpp":
        assert np.all(np.squeeze(da.read("sp_vol_CC", 0, 1)[0]) == 1.0 / 1844.0)


def test_mooney_rivlin_refused(tmp_path):
    """Uintah's CompMooneyRivlin returns rho_micro 0 (sus: NaN, stops in step 1): a one-line error."""
    from framework.problemspec import InputError
    with pytest.raises(InputError, match="comp_mooney_rivlin.*not accepted with MPMICE"):
        run_deck(deck("mooney", 1), tmp_path, "mooney")


def advect_periodic_text():
    """Uintah's advect_periodic.ups (R_Tester MPMICE.py, rmpmice_advect_periodic) as sus ran it for
    data/sus_advect_periodic_3steps.npz: 3 steps, output every step, sp_vol_CC and speedSound_CC
    saved, no checkpoints; for pysus <MPMICE><gas_start>geometry."""
    import re
    text = (HERE / "uintah_reference" / "advect_periodic.ups").read_text(encoding="iso-8859-1")
    text = re.sub(r"<max_Timesteps>\s*500\s*</max_Timesteps>", "<max_Timesteps>3</max_Timesteps>", text)
    text = text.replace("<outputTimestepInterval>10</outputTimestepInterval>",
                        "<outputTimestepInterval>1</outputTimestepInterval>")
    text = text.replace('<save label="press_equil_CC"/>',
                        '<save label="press_equil_CC"/><save label="sp_vol_CC"/><save label="speedSound_CC"/>')
    text = re.sub(r"<checkpoint[^>]*/>", "", text)
    i = text.index("<MPM>")
    return text[:i] + "<MPMICE><gas_start>geometry</gas_start></MPMICE>\n    " + text[i:]


def test_rmpmice_advect_periodic_as_sus(tmp_path):
    """A rigid comp_neo_hook_plastic box (<useModifiedEOS>, K = 1.17e9) translating with the air,
    periodic, 20^3 cells: with Uintah's start the box's UCNH EOS keeps every field sus's, after
    3 steps press_CC 3.4e-12, press_equil_CC 1.4e-13, the air's sp_vol 6e-14, the box's sound
    speed exactly (pysus's default particle start: press_CC up to 7.9e5 Pa, sus 101325)."""
    from framework.archiver import DataArchive
    sus = np.load(HERE / "data" / "sus_advect_periodic_3steps.npz")
    da = DataArchive(run_deck(advect_periodic_text(), tmp_path, "ap").archiver.dir)
    assert np.allclose(da.times[1:4], sus["times"], rtol=1e-12, atol=0)
    for step in (1, 3):
        for label, m in (("press_equil_CC", 0), ("press_CC", 0), ("sp_vol_CC", 0), ("sp_vol_CC", 1),
                         ("speedSound_CC", 0)):
            ref = sus[f"{label}{m}_{step}"]
            err = np.max(np.abs(da.read(label, m, step)[0] - ref)) / np.max(np.abs(ref))
            assert err < 1e-11, (label, m, step, err)


@pytest.mark.parametrize("cm,stand_in,tag,words", [
    (UCNH.format("").replace("117.0e7", "-117.0e7"), False, "bulk_modulus", "> 0"),
    ("<constitutive_model type=\"hypo_elastic\"><G>43.8e7</G><K>nan</K></constitutive_model>", False, "K",
     "finite number"),
    ("<constitutive_model type=\"hypo_elastic\"><G>-43.8e7</G><K>117.0e7</K></constitutive_model>", False, "G",
     ">= 0"),
    (UCNH.format("").replace("117.0e7", "-117.0e7"), True, "bulk_modulus", ">= 0"),
], ids=["ucnh_negative_K", "hypo_nan_K", "hypo_negative_G", "stand_in_negative_K"])
def test_rmpmice_solid_model_out_of_range(tmp_path, cm, stand_in, tag, words):
    """An rmpmice solid's own model (read as rigid by MPM, its EOS in the equilibration: setup.py
    _asked_model, or the <bulk_modulus> of the Murnaghan stand-in without <gas_start>) with a bad
    parameter is refused with the file, line and tag before any step."""
    from framework.controller import Controller
    from framework.problemspec import InputError
    text = deck("rigid", 1).replace(CASES["rigid"][3], cm)
    if stand_in:
        text = text.replace("<MPMICE><gas_start>geometry</gas_start></MPMICE>", "")
    line = next(i for i, s in enumerate(text.splitlines(), 1) if f"<{tag}>" in s)
    (tmp_path / "bad.ups").write_text(text)
    with pytest.raises(InputError) as e:
        Controller(str(tmp_path / "bad.ups"), quiet=True, filebase=str(tmp_path / "bad.uda"))
    msg = str(e.value)
    assert f"bad.ups:{line}: <" in msg and f"{tag}>" in msg and words in msg and "\n" not in msg, msg


def test_rmpmice_elastic_plastic_hp_solid_is_read(tmp_path):
    """An rmpmice solid whose own model reads sub-model nodes (elastic_plastic with a <flow_model>:
    ElasticPlasticHP) gets the material's properties it needs (melt_temp) and its HP curve's EOS."""
    from components.ice.eos import SOLID_HYPER
    from framework.controller import Controller
    hp = ("<constitutive_model type=\"elastic_plastic\"><shear_modulus>43.8e7</shear_modulus>"
          "<bulk_modulus>117.0e7</bulk_modulus><flow_model type=\"isotropic_hardening\"><K>1e8</K>"
          "<sigma_Y>7e7</sigma_Y></flow_model><yield_condition type=\"vonMises\"/></constitutive_model>")
    (tmp_path / "hp.ups").write_text(deck("rigid", 1).replace(CASES["rigid"][3], hp))
    ice = Controller(str(tmp_path / "hp.ups"), quiet=True, filebase=str(tmp_path / "hp.uda")).component.ice
    assert ice.codes[0] == SOLID_HYPER and ice.params[0, 0] == 117.0e7
