"""Heat conduction and viscosity are scheduled only when a deck has them, and act correctly.

A 1D tube at rest with a temperature step: with conductivity k the profile spreads like
erf (loose check of the width). A periodic sine temperature profile at uniform pressure
decays at the rate of the exact linearised solution (within 2 %), which is close to the
isobaric rate alpha k^2, alpha = k / (rho cp). Viscosity: tests/ice/test_viscous.py.
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


SINE_DECK = """<?xml version="1.0" encoding="iso-8859-1"?>
<Uintah_specification>
  <Meta><title>conduction sine</title></Meta>
  <SimulationComponent type="ice"/>
  <Time>
    <maxTime> {t} </maxTime> <initTime> 0.0 </initTime>
    <delt_min> 0.0 </delt_min> <delt_max> 1.0 </delt_max> <delt_init> 1.0e-6 </delt_init>
    <timestep_multiplier> 1.0 </timestep_multiplier>
    <end_at_max_time_exactly> true </end_at_max_time_exactly>
  </Time>
  <Grid>
    <Level>
      <Box label="1">
        <lower> [0,0,0] </lower> <upper> [1,0.01,0.01] </upper>
        <extraCells> [0,1,1] </extraCells>
        <patches> [{patches},1,1] </patches>
        <resolution> [{n},1,1] </resolution>
      </Box>
      <periodic> [1,0,0] </periodic>
    </Level>
  </Grid>
  <DataArchiver>
    <filebase>heat.uda</filebase>
    <outputInterval> {t} </outputInterval>
    <save label="temp_CC"/> <save label="press_CC"/>
  </DataArchiver>
  <CFD> <cfl> 0.4 </cfl> <ICE><advection type="SecondOrder"/></ICE> </CFD>
  <PhysicalConstants> <gravity> [0,0,0] </gravity> <reference_pressure> 1.0 </reference_pressure> </PhysicalConstants>
  <MaterialProperties>
    <ICE>
      <material name="gas">
        <EOS type="ideal_gas"/>
        <dynamic_viscosity> 0.0 </dynamic_viscosity>
        <thermal_conductivity> {k} </thermal_conductivity>
        <specific_heat> 2.5 </specific_heat> <gamma> 1.4 </gamma>
{objects}      </material>
    </ICE>
  </MaterialProperties>
</Uintah_specification>
"""
CELL = """        <geom_object>
          <box><min> [{x0!r},-1,-1] </min><max> [{x1!r},2,2] </max></box>
          <res> [1,1,1] </res> <velocity> [0.0,0.0,0.0] </velocity>
          <temperature> {T!r} </temperature> <density> {rho!r} </density> <pressure> 1.0 </pressure>
        </geom_object>
"""


def sine_deck(k, n=50, t=1.0, amp=0.01, patches=1):
    """Periodic 1D gas at rest, p = 1, T = 1 + amp sin(2 pi x_c), rho = p / ((gamma - 1) cv T)."""
    h = 1.0 / n
    cells = []
    for i in range(n):
        T = 1.0 + amp * np.sin(2 * np.pi * (i + 0.5) * h)
        cells.append(CELL.format(x0=i * h, x1=(i + 1) * h, T=float(T), rho=float(1.0 / T)))
    return SINE_DECK.format(t=t, n=n, k=k, patches=patches, objects="".join(cells))


def linear_conduction_amplitude(t, kc, kw=2 * np.pi, cv=2.5, gamma=1.4, rho0=1.0, T0=1.0, p0=1.0):
    """Exact solution of the linearised compressible equations with heat conduction (no
    viscosity) for one Fourier mode exp(i kw x) starting at rest and uniform pressure:
    T'(t) / T'(0). State (rho', u, T'), d/dt = A, p' = R (rho0 T' + T0 rho'), R = (gamma-1) cv.
    For kw c >> alpha kw^2 it is the entropy mode exp(-alpha kw^2 t), alpha = kc / (rho cp),
    plus a small acoustic part."""
    R, ik = (gamma - 1) * cv, 1j * kw
    A = np.array([[0, -rho0 * ik, 0],
                  [-ik * R * T0 / rho0, 0, -ik * R],
                  [0, -p0 * ik / (rho0 * cv), -kc * kw * kw / (rho0 * cv)]], complex)
    w, V = np.linalg.eig(A)
    c = np.linalg.solve(V, np.array([-rho0 / T0, 0.0, 1.0]))
    return float((V @ (c * np.exp(w * t)))[2].real)


def test_heat_conduction_sine_decays_at_exact_rate(run_deck):
    """A sine temperature profile at uniform pressure in a periodic tube decays at the rate
    of the exact linear solution (the isobaric rate alpha k^2, alpha = k / (rho cp), within
    a few per cent; the exact linear solution includes the acoustic part)."""
    kc, n = 0.05, 50
    da = run_deck(text=sine_deck(kc, n=n))
    T1, (x, _, _) = da.read("temp_CC", 0, -1)
    T0, _ = da.read("temp_CC", 0, 0)
    t = da.times[-1] - da.times[0]
    s = np.sin(2 * np.pi * x)
    a0 = 2 * np.mean((T0[:, 0, 0] - 1.0) * s)
    a1 = 2 * np.mean((T1[:, 0, 0] - 1.0) * s)
    rate = -np.log(a1 / a0) / t
    exact = -np.log(linear_conduction_amplitude(t, kc)) / t
    isobaric = kc / (1.0 * 2.5 * 1.4) * (2 * np.pi) ** 2          # rho = 1, cp = gamma cv
    print(f"conduction sine n={n}: rate {rate:.5f}, exact linear {exact:.5f} (ratio {rate / exact:.4f}),"
          f" isobaric {isobaric:.5f}")
    assert abs(rate / exact - 1) < 0.02, (rate, exact)
    assert abs(rate / isobaric - 1) < 0.1, (rate, isobaric)
    p, _ = da.read("press_CC", 0, -1)
    assert np.max(np.abs(p - 1.0)) < 1e-3          # stays (nearly) isobaric
