"""Heat conduction and viscosity are scheduled only when a deck has them, and act correctly.

A 1D tube at rest with a temperature step and a tiny pressure jump: with conductivity k
the temperature profile spreads like erf, (T - Tm)/(dT/2) = erf((x - x0)/sqrt(4 alpha t)),
alpha = k / (rho cv) (exact solution of the heat equation; at low Mach number the
pressure stays nearly uniform).
"""
import numpy as np
from math import erf

from components.ice.scenes import shock_tube_deck


def heat_deck(k):
    d = shock_tube_deck("sod", n=100, walls=True)
    # equal pressure, temperature step 1 -> 2 (density 1 -> 0.5)
    d = d.replace("<density> 0.125 </density>", "<density> 0.5 </density>")
    d = d.replace("<pressure> 0.1 </pressure>", "<pressure> 1.0 </pressure>")
    d = d.replace("<temperature> 0.8 </temperature>", "<temperature> 2.0 </temperature>")
    d = d.replace("<maxTime> 0.2 </maxTime>", "<maxTime> 0.05 </maxTime>").replace(
        "<outputInterval> 0.2 </outputInterval>", "<outputInterval> 0.05 </outputInterval>")
    return d.replace("<thermal_conductivity> 0.0 </thermal_conductivity>",
                     f"<thermal_conductivity> {k} </thermal_conductivity>")


def test_no_conduction_task_without_conductivity(tmp_path):
    from framework.controller import Controller
    (tmp_path / "d.ups").write_text(heat_deck(0.0))
    c = Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "r.uda"))
    names = [t.name for t in c.step_graph.tasks]
    assert "ICE::computeHeatFlux" not in names and "ICE::viscousShearStress" not in names
    assert "ICE::addExchangeToMomentumAndEnergy" not in names


def test_heat_conduction_spreads_like_erf(run_deck):
    k = 0.05
    da = run_deck(text=heat_deck(k))
    T, (x, _, _) = da.read("temp_CC", 0, -1)
    t = da.times[-1]
    # the contact moves a little as the gas expands; compare the spread, not the position
    T = T[:, 0, 0]
    prof = (T - 1.5) / 0.5
    width_num = np.sum(1 - prof ** 2) * (x[1] - x[0])
    # for erf(z / s), s = sqrt(4 alpha t): integral of 1 - erf^2 = s * 2 * 0.5642 * ... = 1.1284 s / sqrt(2)
    alpha = k / (0.75 * 2.5)            # mean density 0.75 (rho T = 1), cv = 2.5
    s = np.sqrt(4 * alpha * t)
    z = np.linspace(-10, 10, 20001)
    width_exact = np.trapezoid([1 - erf(v) ** 2 for v in z], z) * s
    assert 0.7 * width_exact < width_num < 1.4 * width_exact
