"""A visco_scram solid with <useJWLEOS> in MPMICE (components/ice/eos.py SOLID_JWL: Uintah's
ViscoScram JWL EOS in the equilibration), against sus and its own formulas.

Deck: uintah_reference/DDT_noDDT1.ups, Uintah's DDT.ups without its DDT1 reaction (its header
says what else changed): PBX 9501 (JWL EOS, <useModifiedEOS> true) next to JWL product gas at
7.0e9 Pa ("high"), and the same with the gas at 1 kg/m^3 and 101325 Pa ("low": the solid near
p_ref, where the modified EOS's threshold curve starts). data/sus_DDT_noDDT1.npz is sus's output
on both (one rank, read with framework.uintah_uda): the times, and after steps 1 and 20 the
solid's press_equil_CC, sp_vol_CC and speedSound_CC over the 50 cells.

Measured in all 50 cells, the two next to the gas included (the gas starts from its geometry
as sus's: docs/MPMICE.md "Gas start"), after 20 steps: high, pressure 8e-13, specific volume
3.8e-14, sound speed 1.6e-13; low, pressure 1.9e-8, specific volume 2.8e-13, sound speed 9.4e-9
(the threshold curve's exponent K0/p_ref = 6.6e4 magnifies round-off).
"""
import math
import pathlib

import numpy as np
import pytest

from components.ice.eos import SOLID_JWL, eos_press_eos, eos_rho_micro, solid_jwl_rho_ref
from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "DDT_noDDT1.ups"
A, B, R1, R2, OM, CV, RHO0, P_REF = 732000e9, -5.2645e9, 14.1, 1.41, 0.8867, 2.780236e6, 1832.0, 101325.0
PARAMS = np.array([A, B, R1, R2, OM, CV, RHO0, P_REF])


def deck_text(case):
    """The deck of a case: "high" as stored, "low" with the gas at 1 kg/m^3 and its 101325 Pa."""
    text = DECK.read_text()
    if case == "low":
        gA, gB, gR1, gR2, gom, grho0, gcv = 1668.9e9, 59.69e9, 5.9, 2.1, 0.45, 1832.0, 594.96
        T = (P_REF - gA * math.exp(-gR1 * grho0) - gB * math.exp(-gR2 * grho0)) / (gom * gcv * 1.0)
        text = text.replace("<temperature>    3000.0                  </temperature>",
                            f"<temperature>    {T!r} </temperature>") \
            .replace("<density>         1500        </density>", "<density>         1.0        </density>") \
            .replace("<pressure>       7035707016.835061 </pressure>", "<pressure>       101325.0 </pressure>")
    return text


def _jwl(rho, T):
    v = RHO0 / rho
    return A * math.exp(-R1 * v) + B * math.exp(-R2 * v) + OM * CV * T / v


def test_eos_is_viscoscram_jwl():
    """Above p_ref JWL itself (p, dp/drho, no energy derivative); its density the condensed root
    (not JWL's low-density one); below p_ref the threshold curve from rho_ref(T), continuous there."""
    for rho, T in ((2000.0, 298.0), (2255.0, 600.0)):
        p, dp, de = eos_press_eos(SOLID_JWL, PARAMS, rho, T, 996.0, 1.0)
        assert p == pytest.approx(_jwl(rho, T), rel=1e-14)
        assert dp == pytest.approx((_jwl(rho * (1 + 1e-7), T) - _jwl(rho * (1 - 1e-7), T)) / (2e-7 * rho), rel=1e-6)
        assert de == 0.0
        assert eos_rho_micro(SOLID_JWL, PARAMS, p, T, 996.0, 1.0, RHO0) == pytest.approx(rho, rel=1e-13)
    rho_ref, K0 = solid_jwl_rho_ref(298.0, *PARAMS)
    assert _jwl(rho_ref, 298.0) == pytest.approx(P_REF, rel=1e-4)       # Uintah's 1e-10 in rho
    assert eos_rho_micro(SOLID_JWL, PARAMS, P_REF * (1 + 1e-12), 297.9999999999999, 996.0, 1.0, RHO0) \
        == pytest.approx(rho_ref, rel=1e-9)
    p_low, _, _ = eos_press_eos(SOLID_JWL, PARAMS, rho_ref * (1 - 1e-5), 298.0, 996.0, 1.0)
    assert p_low == pytest.approx(P_REF * (1 - 1e-5) ** (K0 / P_REF), rel=1e-9)
    assert eos_rho_micro(SOLID_JWL, PARAMS, p_low, 298.0, 996.0, 1.0, RHO0) == pytest.approx(rho_ref * (1 - 1e-5),
                                                                                          rel=1e-12)


@pytest.mark.parametrize("case,tol_p,tol_v", [("high", 5e-12, 5e-13), ("low", 1e-7, 1e-12)])
def test_solid_state_as_uintah(tmp_path, case, tol_p, tol_v):
    from framework.archiver import DataArchive
    sus = np.load(HERE / "data" / "sus_DDT_noDDT1.npz")
    da = DataArchive(run_deck(deck_text(case), tmp_path, "ddt").archiver.dir)
    assert np.allclose(da.times[1:], sus[f"{case}_times"], rtol=1e-14, atol=0)
    for step in (1, 20):
        for label, tol in (("press_equil_CC", tol_p), ("sp_vol_CC", tol_v), ("speedSound_CC", tol_p)):
            ours, ref = np.squeeze(da.read(label, 0, step)[0]), sus[f"{case}_{label}_{step}"]
            assert np.allclose(ours, ref, rtol=tol, atol=0), (label, step)
