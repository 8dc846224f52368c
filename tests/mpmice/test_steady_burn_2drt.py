"""Uintah's MPMICE regression deck SteadyBurn_2dRT (uintah_reference/SteadyBurn_2dRT.ups): a 4340
steel ring (elastic_plastic with steel_Cp, Johnson-Cook flow, Mie-Gruneisen EOS) around HMX
(visco_scram) in its TST product gas, approach contact with <computeColinearNormals> false,
Steady_Burn, semi-implicit ICE.

Every part of the deck is read, the steel's <erosion algorithm="ZeroStress"> with
elastic_plastic's own localization (melting, the TEPLA porosity rule, the drucker_becker stability
check; tests/mpm/test_elastic_plastic_hp_failure.py) and its Johnson-Cook damage model. Against
sus on a copy (sus with <Solver type="CGSolver"/>, 5 steps from delt_init 1e-10, output every step):
the steps' times equal, the steel's p.x to 1.5e-13 of its extent, no particle localized in either;
the gas next to the steel: after 5 steps press_CC is 5.0 % from sus's (36 % before Steady_Burn's
pressure source took Uintah's delP_MassX and the trace-temperature rule left burning cells alone),
the burned mass 4.3 %; step 1's press_CC is 0.69 % off where the product is a sliver in a
solid-filled cell that does not burn (pysus gives it the solid's 560 K, sus keeps 341 K);
p.porosity and p.damage are Uintah's seeded gauss draws, but pysus makes one
particle layer along the one-cell z direction where sus makes two (<res> [2,2,2]), so the draws
fall on other particles. Not a comparison test here.
"""
import pathlib

import pytest

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "SteadyBurn_2dRT.ups"


def _validate(text, tmp_path, capsys):
    from framework.cli import main
    path = tmp_path / "steady.ups"
    path.write_text(text, encoding="latin-1")
    rc = main(["-validate", "-q", str(path)])
    return rc, capsys.readouterr().err


def test_steady_burn_2drt_is_read_unchanged(tmp_path, capsys):
    rc, err = _validate(DECK.read_text(encoding="latin-1"), tmp_path, capsys)
    assert rc == 0, err


@pytest.mark.parametrize("flag", ["true", "false"])
def test_colinear_normals_flag_is_read(tmp_path, capsys, flag):
    """<computeColinearNormals> (Uintah's MPM flag, default true) is read either way."""
    text = DECK.read_text(encoding="latin-1")
    text = text.replace("<computeColinearNormals>        false      </computeColinearNormals>",
                        f"<computeColinearNormals> {flag} </computeColinearNormals>")
    assert f"<computeColinearNormals> {flag} </computeColinearNormals>" in text
    rc, err = _validate(text, tmp_path, capsys)
    assert rc == 0, err
