"""<thermal_contact> (Uintah's STThermalContact) and Dirichlet Temperature grid BCs on
Uintah's heatcond2mat deck (tests/mpm/heatcond2mat_k0.ups says how it was changed), against
sus and against the exchange's own bookkeeping; its <materials>[1,2,3] names two materials
that do not exist (Uintah passes over them)."""
import os

import numpy as np
import pytest

from framework.problemspec import InputError
from tests.mpm.helpers import run

HERE = os.path.dirname(__file__)
DECK = os.path.join(HERE, "heatcond2mat_k0.ups")


@pytest.fixture(scope="module")
def heat(tmp_path_factory):
    _, da = run(open(DECK).read(), tmp_path_factory.mktemp("hc"))
    return da, np.load(os.path.join(HERE, "data", "sus_heatcond2mat.npz"))


def test_temperatures_equal_uintahs_sus(heat):
    """p.temperature of both bars after each of 3 steps against sus (partextract prints 9
    digits: 1e-6 K on 300 K; measured 5e-7 K)."""
    da, ref = heat
    for step in (1, 2, 3):
        for m in (0, 1):
            p = da.particles(m, step)
            o = np.lexsort(np.round(p["p.x"], 7).T)
            assert np.abs(p["p.x"][o] - ref[f"x{m}_step{step}"]).max() < 1e-12
            assert np.abs(p["p.temperature"][o] - ref[f"temperature{m}_step{step}"]).max() < 2e-6
    hot = da.particles(1, 3)["p.temperature"]
    assert hot.max() > 320.0 and hot.min() == pytest.approx(100.0)     # the 100 K bar warms at the contact


def test_contact_alone_keeps_the_heat(tmp_path):
    """Without the Temperature BCs the exchange only moves heat between the bars: sum m cv T
    over both is the same after 3 steps (to round-off), and the bars approach each other."""
    text = open(DECK).read()
    start, end = text.index("<BoundaryConditions>"), text.index("</BoundaryConditions>")
    _, da = run(text[:start] + text[end + len("</BoundaryConditions>"):], tmp_path)

    mass_cv = {0: 10000.0 * 0.0005 ** 3 * 903.0, 1: 1000.0 * 0.0005 ** 3 * 603.0}    # rho V_p cv

    def heat_content(k):
        return sum(np.sum(mass_cv[m] * da.particles(m, k)["p.temperature"]) for m in (0, 1))
    assert heat_content(3) == pytest.approx(heat_content(0), rel=1e-13)
    assert da.particles(0, 3)["p.temperature"].min() < 299.0
    assert da.particles(1, 3)["p.temperature"].max() > 110.0


def test_flag_left_out_is_uintahs_default(heat, tmp_path):
    """Uintah's heatcond2mat.ups has no <DoExplicitHeatConduction>: Uintah's default (on)
    applies with its <thermal_contact> and Temperature BCs, so the deck without the tag
    runs as with it true (bitwise)."""
    text = open(DECK).read()
    assert "<DoExplicitHeatConduction>true</DoExplicitHeatConduction>" in text
    _, da = run(text.replace("<DoExplicitHeatConduction>true</DoExplicitHeatConduction>", ""), tmp_path)
    for m in (0, 1):
        assert np.array_equal(da.particles(m, 3)["p.temperature"], heat[0].particles(m, 3)["p.temperature"])


@pytest.mark.parametrize("edit, message", [
    (("<DoExplicitHeatConduction>true", "<DoExplicitHeatConduction>false"), "needs heat conduction"),
    (("<thermal_contact></thermal_contact>", "<thermal_contact><mu>1</mu></thermal_contact>"), "takes no tags"),
    (('var = "Dirichlet" label = "Temperature">', 'var = "symmetry" label = "Temperature">'),
     'accepted: var="Dirichlet" or "Neumann"'),
    (("<materials>[1,2,3]</materials>", "<materials>[-1,0]</materials>"), "negative"),
])
def test_bad_thermal_input_is_one_clean_error(tmp_path, edit, message):
    text = open(DECK).read()
    assert edit[0] in text
    (tmp_path / "d.ups").write_text(text.replace(edit[0], edit[1]))
    from framework.controller import Controller
    with pytest.raises(InputError, match=message):
        Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "r.uda"))
