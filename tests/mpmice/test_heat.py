"""The solid's temperature in the MPMICE heat exchange (paper 000 eqs. 38-39, step 7 of
sec. 3.3): the exchange changes the solid's cell temperature as it does a fluid's, and
that change goes back to the nodes and particles (components/mpmice/tasks.py).

Scene: a closed 1D gas box in which every cell holds a thin solid plate (a third of
the cell) at 600 K, the gas at 300 K, everything at rest and uniform, so only the
exchange acts. The exact end state is the mixed temperature
T_eq = (m_s cv_s T_s + m_g cv_g T_g) / (m_s cv_s + m_g cv_g) in both materials, and the
heat sum m cv T over both materials is constant (the small p dV work between the gas
and the stiff solid is below 1e-4 of it).
"""
import re

import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import pysus_ranks, pysus_runs, run_deck

N, DX = 10, 0.01
RHO_S, CV_S, T_S = 10.0, 100.0, 600.0
RHO_G, CV_G, T_G, P0 = 101325.0 / (0.4 * 716.0 * 300.0), 716.0, 300.0, 101325.0


def deck(steps=500, patches=1, heat="1e7", extra_mpm="", k_solid=0.0, k_gas=0.0):
    plates = "".join(f"<box><min>[{(i + 0.3) * DX},-1,-1]</min><max>[{(i + 0.7) * DX},1,1]</max></box>"
                     for i in range(N))
    return f"""<?xml version="1.0"?>
<Uintah_specification>
  <Meta><title>solid plates exchanging heat with gas</title></Meta>
  <SimulationComponent type="mpmice"/>
  <Time><maxTime>1.0</maxTime><initTime>0.0</initTime><delt_min>0.0</delt_min><delt_max>1.0</delt_max>
    <delt_init>1.0e-7</delt_init><max_Timesteps>{steps}</max_Timesteps><timestep_multiplier>0.5</timestep_multiplier></Time>
  <Grid>
    <BoundaryConditions>
      <Face side="x-"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
      <Face side="x+"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
    </BoundaryConditions>
    <Level><Box label="1"><lower>[0,0,0]</lower><upper>[{N * DX},0.01,0.01]</upper><extraCells>[1,1,1]</extraCells>
      <patches>[{patches},1,1]</patches><resolution>[{N},1,1]</resolution></Box></Level>
  </Grid>
  <DataArchiver><filebase>heat.uda</filebase><outputTimestepInterval>{steps}</outputTimestepInterval>
    <save label="temp_CC"/><save label="rho_CC"/><save label="vel_CC"/><save label="p.temperature"/>
    <save label="p.x"/><save label="p.particleID"/><save label="ThermalEnergy"/></DataArchiver>
  <CFD><cfl>0.4</cfl><ICE><advection type="SecondOrder"/></ICE></CFD>
  <MPM><time_integrator>explicit</time_integrator><interpolator>linear</interpolator>{extra_mpm}</MPM>
  <PhysicalConstants><gravity>[0,0,0]</gravity><reference_pressure>{P0}</reference_pressure></PhysicalConstants>
  <MaterialProperties>
    <MPM><material name="plates"><density>{RHO_S}</density>
        <constitutive_model type="comp_neo_hook"><bulk_modulus>1e8</bulk_modulus><shear_modulus>5e7</shear_modulus></constitutive_model>
        <thermal_conductivity>{k_solid}</thermal_conductivity><specific_heat>{CV_S}</specific_heat>
        <geom_object><union label="plates">{plates}</union><res>[3,1,1]</res><velocity>[0,0,0]</velocity>
          <temperature>{T_S}</temperature></geom_object></material></MPM>
    <ICE><material name="air"><EOS type="ideal_gas"/><dynamic_viscosity>0.0</dynamic_viscosity>
        <thermal_conductivity>{k_gas}</thermal_conductivity><specific_heat>{CV_G}</specific_heat><gamma>1.4</gamma>
        <geom_object><difference><box><min>[-1,-1,-1]</min><max>[2,1,1]</max></box><union label="plates"/></difference>
          <res>[3,1,1]</res><velocity>[0,0,0]</velocity><temperature>{T_G}</temperature>
          <density>{RHO_G}</density><pressure>{P0}</pressure></geom_object></material></ICE>
    <exchange_properties><exchange_coefficients><momentum>[1e15]</momentum><heat>[{heat}]</heat>
    </exchange_coefficients></exchange_properties>
  </MaterialProperties>
</Uintah_specification>
"""


def _gas(da, i):
    """(gas temperatures, gas heat sum m cv T) at output i."""
    T, _ = da.read("temp_CC", material=1, timestep=i)
    rho, _ = da.read("rho_CC", material=1, timestep=i)
    return T.ravel(), float(np.sum(rho * (DX * 0.01 * 0.01) * CV_G * T))


def test_hot_plates_and_cold_gas_reach_the_mixed_temperature(tmp_path):
    ctl = run_deck(deck(), tmp_path)
    da = DataArchive(ctl.archiver.dir)
    Tg0, eg0 = _gas(da, 0)
    assert np.allclose(Tg0, T_G) and np.allclose(da.particles(0, 0)["p.temperature"], T_S)
    t, es = da.reduction("ThermalEnergy")
    es = np.asarray(es)
    Tg, eg = _gas(da, -1)
    Ts = da.particles(0, -1)["p.temperature"]
    cs, cg = es[0] / T_S, eg0 / T_G              # heat capacities m cv of the solid and the gas
    T_eq = (cs * T_S + cg * T_G) / (cs + cg)
    assert 0.2 < cs / cg < 5                      # both matter
    assert np.all(np.abs(Tg / T_eq - 1) < 2e-3), (Tg, T_eq)
    assert np.all(np.abs(Ts / T_eq - 1) < 2e-3), (Ts.min(), Ts.max(), T_eq)
    assert abs((eg + es[-1]) / (eg0 + es[0]) - 1) < 1e-4


def test_no_heat_coefficient_no_temperature_tasks(tmp_path):
    text = deck(heat="0").replace('<save label="p.temperature"/>', "").replace('<save label="ThermalEnergy"/>', "")
    path = tmp_path / "g.ups"
    path.write_text(text)
    r = pysus_ranks("--graph", path)
    assert r.returncode == 0, r.stderr
    assert "Temperature" not in r.stdout and "computeCCTempRates" not in r.stdout and "dTdt" not in r.stdout


def test_deck_without_boundary_conditions_runs(tmp_path):
    """A periodic deck without <BoundaryConditions> whose solid carries a temperature sets up and
    runs: no Temperature face condition reaches the solid's nodes (mpmice/setup.py GridBCsWithICE)."""
    text = re.sub(r"<BoundaryConditions>.*</BoundaryConditions>", "", deck(steps=2), flags=re.S)
    text = text.replace("</Box></Level>", "</Box><periodic>[1,1,1]</periodic></Level>")
    assert "<BoundaryConditions>" not in text and "<Face" not in text
    ctl = run_deck(text, tmp_path)
    assert ctl.component.mpm.thermal and not ctl.component.mpm.temperature_bcs
    T = DataArchive(ctl.archiver.dir).particles(0, -1)["p.temperature"]
    assert np.all(T < T_S) and np.all(T > T_G)          # the plates cool toward the gas


def test_one_two_three_ranks_bitwise(tmp_path):
    path = tmp_path / "heat.ups"
    path.write_text(deck(steps=40, patches=3))
    out = {}
    runs = pysus_runs([((path, "--filebase", tmp_path / f"r{n}.uda"), n) for n in (1, 2, 3)], tmp_path)
    for n, (rc, err) in zip((1, 2, 3), runs):
        assert rc == 0, err[-2000:]
        da = DataArchive(tmp_path / f"r{n}.uda")
        p = da.particles(0, -1)
        out[n] = (p["p.temperature"][np.argsort(p["p.particleID"])], da.read("temp_CC", material=1, timestep=-1)[0])
    for n in (2, 3):
        assert np.array_equal(out[1][0], out[n][0]) and np.array_equal(out[1][1], out[n][1])
    assert out[1][0].max() < T_S                  # the plates cooled


def test_heat_exchange_needs_a_specific_heat(tmp_path):
    from framework.problemspec import InputError
    with pytest.raises(InputError, match="specific_heat"):
        run_deck(deck().replace(f"<specific_heat>{CV_S}</specific_heat>", "<specific_heat>0</specific_heat>"), tmp_path)


def test_gas_conduction_is_scheduled_and_conserves(tmp_path):
    """ICE heat conduction in the fluids runs under MPMICE (the plates' scene with a
    conducting gas: the heat sum over gas and plates stays constant)."""
    text = deck(steps=200, k_gas=50.0)
    path = tmp_path / "g.ups"
    path.write_text(text)
    r = pysus_ranks("--graph", path)
    assert r.returncode == 0, r.stderr
    assert "ICE::computeHeatFlux" in r.stdout
    da = DataArchive(run_deck(text, tmp_path).archiver.dir)
    _, es = da.reduction("ThermalEnergy")
    e0, e1 = _gas(da, 0)[1] + es[0], _gas(da, -1)[1] + es[-1]
    assert abs(e1 / e0 - 1) < 1e-4


MIN_MAX_NODES = """<DataAnalysis><Module name="minMax"><material>plates</material>
  <samplingFrequency>1e10</samplingFrequency><timeStart>0</timeStart><timeStop>100</timeStop>
  <Variables><analyze label="g.mass" matl="0"/><analyze label="press_CC" matl="0"/></Variables>
</Module></DataAnalysis></Uintah_specification>"""


def test_fluid_internal_energy_every_step_and_min_max_of_nodes(tmp_path):
    """A saved TotalIntEng under MPMICE is the fluids' sum m cv T (Uintah's ICE TestConservation
    over the ICE materials; the closed box has no boundary flux), with a .dat line every
    timestep as in Uintah; minMax reads a node-centred variable (g.mass) over the domain's nodes."""
    steps = 6
    text = deck(steps=steps).replace('<save label="ThermalEnergy"/>', '<save label="TotalIntEng"/><save label="g.mass"/>')
    da = DataArchive(run_deck(text.replace("</Uintah_specification>", MIN_MAX_NODES), tmp_path).archiver.dir)
    t, ie = da.reduction("TotalIntEng")
    assert len(t) == steps and len(da.times) == 2 and t[-1] == da.times[-1]      # two outputs, a line per step
    assert float(ie[-1]) == pytest.approx(_gas(da, -1)[1], rel=1e-12)
    rows = [line.split() for line in open(f"{da.path}/MinMax/L-0/g.mass_0") if not line.startswith("#")]
    assert len(rows) == steps
    gmass, _ = da.read("g.mass", 0, -1)
    assert float(rows[-1][1]) == pytest.approx(gmass.min(), rel=1e-15)      # 16 digits as Uintah writes
    assert float(rows[-1][2]) == pytest.approx(gmass.max(), rel=1e-15) and gmass.max() > 1.5 * gmass.min() > 0.0
