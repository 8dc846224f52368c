"""The MPM solids' own EOS in MPMICE's equilibration (components/ice/eos.py SOLID_UCNH .. SOLID_RIGID,
components/mpmice/setup.py solid_eos), against the formulas of Uintah's constitutive models'
computePressEOSCM / computeRhoMicroCM (UCNH.cc, ElasticPlasticHP.cc, ViscoScram.cc, HypoElastic.cc,
RigidMaterial.cc, IdealGasMP.cc, JWLppMPM.cc): pressure, dp/drho, the sound speed Uintah's MPMICE takes (the model's c^2, not
dp/drho), the density at a pressure, and the <useModifiedEOS> curve below rho0.
"""
import importlib
import math
import types

import numpy as np
import pytest

from components.ice.eos import (MAX_PARAMS, SOLID_HYPER, SOLID_HYPO, SOLID_RIGID, SOLID_UCNH, eos_alpha,
                                eos_cold_energy, eos_press_eos, eos_rho_micro, eos_sound_speed2)

K, RHO0, P_REF = 117.0e9, 8930.0, 101325.0


def _row(*values):
    row = np.zeros(MAX_PARAMS)
    row[:len(values)] = values
    return row


def _call(code, row, rho):
    p, dp, de = eos_press_eos(code, row, rho, 300.0, 386.0, 1.0)
    return p, dp, de, eos_sound_speed2(code, row, rho, 300.0, 386.0, 1.0)


@pytest.mark.parametrize("code,vs", [(SOLID_UCNH, 0.0), (SOLID_HYPER, 0.0), (SOLID_HYPER, 1.0)])
def test_compressible_neo_hookean(code, vs):
    """p = p_ref + K/2 (x - 1/x), x = rho/rho0; c^2 = K/rho; rho(p) its inverse; without
    <useModifiedEOS> the same curve in tension (p below p_ref, negative far enough)."""
    row = _row(K, RHO0, P_REF, 0.0, vs)
    for x in (1.02, 1.0, 0.999, 0.5):
        rho = x * RHO0
        p, dp, de, c2 = _call(code, row, rho)
        assert p == pytest.approx(P_REF + 0.5 * K * (x - 1.0 / x), rel=1e-13, abs=1e-6 * P_REF)
        assert dp == pytest.approx(0.5 * K * (1.0 / (x * x) + 1.0) / RHO0, rel=1e-14)
        assert de == 0.0
        assert c2 == pytest.approx(K / rho, rel=1e-14)
        assert eos_rho_micro(code, row, p, 300.0, 386.0, 1.0, 1.0) == pytest.approx(rho, rel=1e-12)
    assert _call(code, row, 0.5 * RHO0)[0] < 0.0


@pytest.mark.parametrize("code,vs", [(SOLID_UCNH, 0.0), (SOLID_HYPER, 0.0), (SOLID_HYPER, 1.0)])
def test_modified_eos_below_rho0(code, vs):
    """<useModifiedEOS>: below rho0 p = p_ref x^(K/p_ref), dp/drho = c^2 = K/rho x^(K/p_ref) (C1 at
    rho0 with the curve above, whose slope there is K/rho0); above rho0 unchanged."""
    row = _row(K, RHO0, P_REF, 1.0, vs)
    n = K / P_REF
    for x in (1.0 - 1e-7, 1.0 - 1e-6):
        rho = x * RHO0
        p, dp, de, c2 = _call(code, row, rho)
        assert p == pytest.approx(P_REF * x ** n, rel=1e-9)
        assert dp == c2 == pytest.approx(K / rho * x ** n, rel=1e-9)
        assert eos_rho_micro(code, row, p, 300.0, 386.0, 1.0, 1.0) == pytest.approx(rho, rel=1e-13)
    p, dp, _, c2 = _call(code, row, RHO0)
    assert p == P_REF and dp == pytest.approx(K / RHO0, rel=1e-15) and c2 == pytest.approx(K / RHO0, rel=1e-15)
    assert _call(code, row, 1.01 * RHO0)[0] == _call(code, _row(K, RHO0, P_REF, 0.0, vs), 1.01 * RHO0)[0]


def test_hypoelastic_and_rigid():
    """HypoElastic p = p_ref + K (1 - rho0/rho), c^2 = K/rho; RigidMaterial rho0 at any pressure,
    p = p_ref, dp/drho = c^2 = K/rho0. No solid code has a thermal or cold-energy part."""
    row = _row(K, RHO0, P_REF)
    rho = 1.01 * RHO0
    p, dp, de, c2 = _call(SOLID_HYPO, row, rho)
    assert p == pytest.approx(P_REF + K * (1.0 - 1.0 / 1.01), rel=1e-13)
    assert dp == pytest.approx(K * RHO0 / rho ** 2, rel=1e-14) and c2 == pytest.approx(K / rho, rel=1e-14)
    assert eos_rho_micro(SOLID_HYPO, row, p, 300.0, 386.0, 1.0, 1.0) == pytest.approx(rho, rel=1e-13)
    p, dp, de, c2 = _call(SOLID_RIGID, row, rho)
    assert (p, dp, c2) == (P_REF, K / RHO0, K / RHO0)
    assert eos_rho_micro(SOLID_RIGID, row, 5e9, 300.0, 386.0, 1.0, 1.0) == RHO0
    for code in (SOLID_UCNH, SOLID_HYPER, SOLID_HYPO, SOLID_RIGID):
        assert eos_alpha(code, row, rho, 300.0, 386.0, 1.0) == 0.0
        assert eos_cold_energy(code, row, rho) == 0.0


def test_ucnh_arithmetic_is_uintahs():
    """SOLID_UCNH in UCNH.cc's operations (J = rho0/rho; c^2 from dp/dJ = K/2 (1 + (1/J) J)),
    bitwise; SOLID_HYPER in ElasticPlasticHP.cc's."""
    rho = 8930.0 * 1.000123456789
    p, dp, _, c2 = _call(SOLID_UCNH, _row(K, RHO0, P_REF, 0.0), rho)
    J = RHO0 / rho
    assert p == -(0.5 * K * (J - 1.0 / J)) + P_REF
    assert dp == 0.5 * K * (1.0 + J * J) / RHO0
    assert c2 == 0.5 * K * (1.0 + 1.0 / J * J) / rho
    press = 3.0e8
    assert eos_rho_micro(SOLID_UCNH, _row(K, RHO0, P_REF, 0.0), press, 300.0, 386.0, 1.0, 1.0) == \
        RHO0 / K * ((press - P_REF) + math.sqrt(K * K + (press - P_REF) ** 2))
    p, dp, _, c2 = _call(SOLID_HYPER, _row(K, RHO0, P_REF, 0.0, 0.0), rho)
    assert p == P_REF + 0.5 * K * (rho * (1.0 / RHO0) - RHO0 / rho)
    g = (press - P_REF) / K
    assert eos_rho_micro(SOLID_HYPER, _row(K, RHO0, P_REF, 0.0, 0.0), press, 300.0, 386.0, 1.0, 1.0) == \
        RHO0 * (g + math.sqrt(g * g + 1.0))


@pytest.mark.parametrize("kind,tags,code,K", [
    ("comp_neo_hook", "<bulk_modulus>117e9</bulk_modulus><shear_modulus>43.8e9</shear_modulus>", SOLID_UCNH, 117e9),
    ("comp_neo_hook_plastic", "<bulk_modulus>117e9</bulk_modulus><shear_modulus>43.8e9</shear_modulus>"
     "<yield_stress>70e6</yield_stress><hardening_modulus>43e6</hardening_modulus>", SOLID_UCNH, 117e9),
    ("hypo_elastic", "<G>43.8e9</G><K>117e9</K>", SOLID_HYPO, 117e9),
    ("rigid", "", SOLID_RIGID, 1e200),
])
def test_deck_model_selects_its_eos(kind, tags, code, K):
    """setup.solid_eos: the model's Uintah EOS with its bulk modulus, <useModifiedEOS> in the row
    (Uintah's default false); RigidMaterial without <bulk_modulus> Uintah's K = 1e200; a prescribed
    (rmpmice) solid its model's too (Uintah's RigidMPM keeps the deck's model), the Murnaghan stand-in
    where it is left unscaled (stand_in: pysus's particle start)."""
    from components.ice.eos import MURNAGHAN
    from components.mpm.materials import MODELS
    from components.mpmice.setup import solid_eos
    from framework.problemspec import ProblemSpec
    for modified in (False, True):
        flag = "<useModifiedEOS>true</useModifiedEOS>" if modified else ""
        node = ProblemSpec.from_string(
            f'<material><density>8930</density><constitutive_model type="{kind}">{tags}{flag}'
            '</constitutive_model><thermal_conductivity>400</thermal_conductivity>'
            '<specific_heat>386</specific_heat></material>')
        cm = node.child("constitutive_model")
        model = importlib.import_module(f"components.mpm.constitutive.{MODELS[kind]}")
        params = model.Params.from_ups({c.tag: c.text() for c in cm.children()})
        mat = types.SimpleNamespace(node=node, model_name=kind, density=8930.0, params=params)
        got, row = solid_eos(mat, P_REF, False)
        assert got == code and row[0] == K and row[1] == 8930.0 and row[2] == P_REF
        if code in (SOLID_UCNH, SOLID_HYPER):
            assert row[3] == float(modified)
        assert solid_eos(mat, P_REF, True)[0] == MURNAGHAN


def test_ucnhvar_takes_its_largest_bulk_modulus():
    """Uintah's UCNHVar: UCNH's EOS with the largest of its entries' bulk moduli; it never reads
    <useModifiedEOS>."""
    from components.mpmice.setup import solid_eos
    from framework.problemspec import ProblemSpec
    node = ProblemSpec.from_string('<material><constitutive_model type="UCNHVar"><useModifiedEOS>true'
                                   '</useModifiedEOS></constitutive_model></material>')
    params = types.SimpleNamespace(bulk_modulus=(60e9, 117e9, 80e9))
    mat = types.SimpleNamespace(node=node, model_name="UCNHVar", density=8930.0, params=params)
    code, row = solid_eos(mat, P_REF, False)
    assert code == SOLID_UCNH and row[0] == 117e9 and row[3] == 0.0


def test_ideal_gas_and_jwlpp():
    """IdealGasMP: p = (gamma-1) rho cv T, dp/drho = (gamma-1) cv T, c^2 = dp/drho + (gamma-1) p/rho,
    rho(p) its inverse (the solid's temperature); JWLppMPM: rho0 at any pressure, p its JWL with
    the cell's temperature, c^2 the JWL's dp/drho, and the equilibration's dp/drho that of an
    incompressible density (Uintah's computeRhoMicroCM)."""
    from components.ice.eos import JWLPP_STIFF, SOLID_IDEAL_GAS, SOLID_JWLPP
    row = _row(1.4, 716.0)
    p, dp, de = eos_press_eos(SOLID_IDEAL_GAS, row, 5.0, 400.0, 999.0, 1.0)
    assert p == pytest.approx(0.4 * 5.0 * 716.0 * 400.0, rel=1e-15) and dp == pytest.approx(0.4 * 716.0 * 400.0)
    assert de == 0.0
    assert eos_sound_speed2(SOLID_IDEAL_GAS, row, 5.0, 400.0, 999.0, 1.0) == pytest.approx(1.4 * 0.4 * 716.0 * 400.0,
                                                                                         rel=1e-15)
    assert eos_rho_micro(SOLID_IDEAL_GAS, row, p, 400.0, 999.0, 1.0, 1.0) == pytest.approx(5.0, rel=1e-15)
    A, B, R1, R2, om, cv, rho0 = 7.73037e11, 21.629e9, 4.5, 1.5, 0.33, 1000.0, 1844.0
    row = _row(A, B, R1, R2, om, cv, rho0)
    rho, T = 1900.0, 320.0
    V = rho0 / rho
    p, dp, de = eos_press_eos(SOLID_JWLPP, row, rho, T, 999.0, 1.0)
    assert p == pytest.approx(A * math.exp(-R1 * V) + B * math.exp(-R2 * V) + om * cv * T * rho, rel=1e-14)
    assert dp == JWLPP_STIFF / rho0 and de == 0.0
    c2 = (R1 * rho0 * A * math.exp(-R1 * V) + R2 * rho0 * B * math.exp(-R2 * V)) / rho ** 2 + om * cv * T
    assert eos_sound_speed2(SOLID_JWLPP, row, rho, T, 999.0, 1.0) == pytest.approx(c2, rel=1e-14)
    assert eos_rho_micro(SOLID_JWLPP, row, 3e9, T, 999.0, 1.0, 1.0) == rho0


def test_membrane_takes_elastic_plastic_hps_curve():
    """Uintah's Membrane.cc (not in its build): ElasticPlasticHP's curve, no <useModifiedEOS>."""
    from components.mpmice.setup import solid_eos
    from framework.problemspec import ProblemSpec
    node = ProblemSpec.from_string('<material><constitutive_model type="membrane"><useModifiedEOS>true'
                                   '</useModifiedEOS></constitutive_model></material>')
    params = types.SimpleNamespace(bulk_modulus=2e9)
    mat = types.SimpleNamespace(node=node, model_name="membrane", density=1000.0, params=params)
    code, row = solid_eos(mat, P_REF, False)
    assert code == SOLID_HYPER and row[0] == 2e9 and row[3] == 0.0 and row[4] == 0.0
