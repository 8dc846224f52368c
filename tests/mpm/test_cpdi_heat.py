"""Heat with CPDI weights (Uintah's cpdi interpolator in interpolateTemperatureToGrid,
computeInternalHeatRate and updateParticleTemperature) on Uintah's heatcond2mat deck
(tests/mpm/heatcond2mat_cpdi.ups says how it was changed)."""
import os

import numpy as np
import pytest

from tests.mpm.helpers import run

HERE = os.path.dirname(__file__)
TEXT = open(os.path.join(HERE, "heatcond2mat_cpdi.ups")).read()
K = "<thermal_conductivity>100.0</thermal_conductivity>"


def _sorted(da, m, step):
    p = da.particles(m, step)
    o = np.lexsort(np.round(p["p.x"], 7).T)
    return p["p.x"][o], p["p.temperature"][o]


def test_contact_and_bcs_equal_uintahs_sus(tmp_path):
    """Without conduction (thermal_conductivity 0) the CPDI transfers of the temperature, the
    thermal contact and the Temperature BCs against sus after each of 3 steps (measured
    2.4e-12 K)."""
    assert K in TEXT
    _, da = run(TEXT.replace(K, "<thermal_conductivity>0.0</thermal_conductivity>"), tmp_path)
    ref = np.load(os.path.join(HERE, "data", "sus_heatcond2mat_cpdi.npz"))
    for step in (1, 2, 3):
        for m in (0, 1):
            x, T = _sorted(da, m, step)
            assert np.abs(x - ref[f"x{m}_step{step}"]).max() < 1e-12
            assert np.abs(T - ref[f"temperature{m}_step{step}"]).max() < 1e-9
    assert da.particles(1, 3)["p.temperature"].max() > 320.0        # the 100 K bar warms at the contact


@pytest.fixture(scope="module")
def conduction(tmp_path_factory):
    return [run(TEXT.replace("cpdi</interpolator>", f"{kind}</interpolator>"), tmp_path_factory.mktemp(kind))[1]
            for kind in ("cpdi", "gimp")]


def test_conduction_equals_gimps_on_undeformed_particles(conduction):
    """CPDI's corner-averaged linear weights are GIMP's on an undeformed box particle: with
    conduction the two agree while F stays near I, and conduction has moved heat (grad T lags a
    step, as Uintah's: the cold bar's coldest particle stays at 100 K for one step, then warms).
    Particles are laid with Uintah's arithmetic, so the last layer's faces sit one ulp past a
    node: GIMP gives the node beyond the bar a weight of about 1e-30, its T* there (rate / that
    weight's mass) a real share of grad T, as sus's GIMP does (test_thermal's sus comparison).
    Conduction spreads it: measured 2.6e-4 K after 3 steps, where the bars' temperatures move
    by over 10 K."""
    cpdi, gimp = conduction
    for step in (1, 2, 3):
        for m in (0, 1):
            xc, Tc = _sorted(cpdi, m, step)
            xg, Tg = _sorted(gimp, m, step)
            assert np.abs(xc - xg).max() < 1e-12
            assert np.abs(Tc - Tg).max() < 1e-3
    assert cpdi.particles(1, 1)["p.temperature"].min() == pytest.approx(100.0)
    assert cpdi.particles(1, 3)["p.temperature"].min() > 110.0


def test_insulated_conduction_keeps_the_heat(tmp_path):
    """sum_i grad S_ip = 0 holds corner by corner: without the Temperature BCs, conduction and
    thermal contact keep sum m cv T of both bars to round-off while heat moves."""
    i, j = TEXT.index("<BoundaryConditions>"), TEXT.index("</BoundaryConditions>") + len("</BoundaryConditions>")
    text = (TEXT[:i] + TEXT[j:]).replace('<save label = "p.x"/>', '<save label = "p.x"/><save label = "p.mass"/>')
    _, da = run(text, tmp_path)

    def heat(step):
        return sum(cv * np.dot(da.particles(m, step)["p.mass"], da.particles(m, step)["p.temperature"])
                   for m, cv in ((0, 903.0), (1, 603.0)))
    assert heat(3) == pytest.approx(heat(0), rel=1e-13)
    assert da.particles(1, 3)["p.temperature"].max() > 110.0
