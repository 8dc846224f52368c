"""Validation scenes of ICE: shock-tube deck template and errors against the exact solution.

`shock_tube_deck(name, n, order)` writes the deck text of Sod's problem and Toro's
tests 1-5 (inputs/ICE/*.ups are made from it by inputs/ICE/make_decks.py);
`shock_tube_errors(archive, name)` gives the L1 errors of density, velocity and
pressure at the last output against components/ice/exact_riemann.py. Shared by the
tests and scripts/accuracy_cost.py.
"""
from __future__ import annotations

import os

# Toro (2009) table 4.1, gamma = 1.4, cv = 2.5 (so T = p / rho); x0 and end time per test.
TORO = {
    "sod":   dict(left=(1.0, 0.0, 1.0), right=(0.125, 0.0, 0.1), x0=0.5, t=0.2,
                  what="Sod's shock tube: rarefaction, contact, shock"),
    "toro1": dict(left=(1.0, 0.75, 1.0), right=(0.125, 0.0, 0.1), x0=0.3, t=0.2,
                  what="Toro test 1 (modified Sod): sonic point in the rarefaction"),
    "toro2": dict(left=(1.0, -2.0, 0.4), right=(1.0, 2.0, 0.4), x0=0.5, t=0.15,
                  what="Toro test 2 (the 123 problem): two rarefactions, near-vacuum centre"),
    "toro3": dict(left=(1.0, 0.0, 1000.0), right=(1.0, 0.0, 0.01), x0=0.5, t=0.012,
                  what="Toro test 3: left blast wave, pressure ratio 1e5"),
    "toro4": dict(left=(1.0, 0.0, 0.01), right=(1.0, 0.0, 100.0), x0=0.4, t=0.035,
                  what="Toro test 4: right blast wave"),
    "toro5": dict(left=(5.99924, 19.5975, 460.894), right=(5.99242, -6.19633, 46.0950), x0=0.4, t=0.035,
                  what="Toro test 5: collision of two shocks"),
}

FACE = """      <Face side="{side}">
        <BCType id="all" label="Pressure" var="Neumann"><value> 0. </value></BCType>
        <BCType id="all" label="Velocity" var="Neumann"><value> [0.,0.,0.] </value></BCType>
        <BCType id="all" label="Temperature" var="Neumann"><value> 0. </value></BCType>
        <BCType id="all" label="Density" var="Neumann"><value> 0. </value></BCType>
        <BCType id="all" label="SpecificVol" var="computeFromDensity"><value> 0. </value></BCType>
      </Face>
"""

TEMPLATE = """<?xml version="1.0" encoding="iso-8859-1"?>
<!--
  {title}
  Scene: 1D shock tube on [0, 1], {n} cells, interface at x = {x0}, ideal gas gamma = 1.4,
  cv = 2.5 (T = p / rho), {order} advection, CFL {cfl}, end time {t}.
  Checks: density, velocity and pressure against the exact Riemann solution
  (components/ice/exact_riemann.py; tests/ice/test_shock_tubes.py).
  Runtime: about {runtime} on one core.
  Command: .venv/bin/pysus inputs/ICE/{name}.ups
-->
<Uintah_specification>
  <Meta><title>{name}</title></Meta>
  <SimulationComponent type="ice"/>
  <Time>
    <maxTime> {t} </maxTime>
    <initTime> 0.0 </initTime>
    <delt_min> 0.0 </delt_min>
    <delt_max> 1.0 </delt_max>
    <delt_init> 1.0e-6 </delt_init>
    <timestep_multiplier> 1.0 </timestep_multiplier>
    <end_at_max_time_exactly> true </end_at_max_time_exactly>
  </Time>
  <Grid>
    <BoundaryConditions>
{faces}    </BoundaryConditions>
    <Level>
      <Box label="1">
        <lower> [0,0,0] </lower>
        <upper> [1,0.01,0.01] </upper>
        <extraCells> [1,1,1] </extraCells>
        <patches> [{patches},1,1] </patches>
        <resolution> [{n},1,1] </resolution>
      </Box>
    </Level>
  </Grid>
  <DataArchiver>
    <filebase>{name}.uda</filebase>
    <outputInterval> {t} </outputInterval>
    <save label="rho_CC"/>
    <save label="vel_CC"/>
    <save label="press_CC"/>
    <save label="temp_CC"/>
    <save label="TotalMass"/>
    <save label="TotalIntEng"/>
    <save label="KineticEnergy"/>
  </DataArchiver>
  <CFD>
    <cfl> {cfl} </cfl>
    <ICE>{energy}<advection type="{order}"{advection}/><delT_activeDirectionsOnly>true</delT_activeDirectionsOnly></ICE>
  </CFD>
  <PhysicalConstants>
    <gravity> [0,0,0] </gravity>
    <reference_pressure> 1.0 </reference_pressure>
  </PhysicalConstants>
  <MaterialProperties>
    <ICE>
      <material name="gas">
        <EOS type="ideal_gas"/>
        <dynamic_viscosity> 0.0 </dynamic_viscosity>
        <thermal_conductivity> 0.0 </thermal_conductivity>
        <specific_heat> 2.5 </specific_heat>
        <gamma> 1.4 </gamma>
        <geom_object>
          <box label="left"><min> [-1,-1,-1] </min><max> [{x0},1,1] </max></box>
          <res> [2,2,2] </res>
          <velocity> [{ul},0,0] </velocity>
          <temperature> {Tl} </temperature>
          <density> {rl} </density>
          <pressure> {pl} </pressure>
        </geom_object>
        <geom_object>
          <difference>
            <box><min> [-1,-1,-1] </min><max> [2,1,1] </max></box>
            <box label="left"/>
          </difference>
          <res> [2,2,2] </res>
          <velocity> [{ur},0,0] </velocity>
          <temperature> {Tr} </temperature>
          <density> {rr} </density>
          <pressure> {pr} </pressure>
        </geom_object>
      </material>
    </ICE>
  </MaterialProperties>
</Uintah_specification>
"""


WALL = """      <Face side="{side}"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
"""


def shock_tube_deck(name, n=200, order="SecondOrder", cfl=0.4, patches=1, runtime="a few seconds", walls=False,
                    conserve=False, limiter=None, heating=None):
    """The deck text of one Toro test at n cells (walls=True: closed ends, reflecting;
    conserve=True: <conserveTotalEnergy>, the pysus option; limiter, heating: the
    <advection> attributes limiter and dissipationHeating, left out when None)."""
    attrs = (f' limiter="{limiter}"' if limiter else "") + \
        (f' dissipationHeating="{str(heating).lower()}"' if heating is not None else "")
    s = TORO[name]
    (rl, ul, pl), (rr, ur, pr) = s["left"], s["right"]
    face = WALL if walls else FACE
    faces = face.format(side="x-") + face.format(side="x+")
    return TEMPLATE.format(title=s["what"], name=name, n=n, x0=s["x0"], order=order, cfl=cfl, t=s["t"],
                           runtime=runtime, faces=faces, patches=patches, rl=rl, ul=ul, pl=pl, rr=rr, ur=ur,
                           pr=pr, Tl=pl / rl, Tr=pr / rr, advection=attrs,
                           energy="<conserveTotalEnergy> true </conserveTotalEnergy>" if conserve else "")



def shock_tube_errors(da, name, timestep=-1):
    """{'rho', 'u', 'p'}: mean |numerical - exact| over the cells, plus the exact fields and x."""
    import numpy as np
    from .exact_riemann import exact_riemann
    s = TORO[name]
    rho, (x, _, _) = da.read("rho_CC", 0, timestep)
    vel, _ = da.read("vel_CC", 0, timestep)
    p, _ = da.read("press_CC", 0, timestep)
    t = da.times[timestep]
    ex = exact_riemann(s["left"], s["right"], x, t, s["x0"])
    num = {"rho": rho[:, 0, 0], "u": vel[:, 0, 0, 0], "p": p[:, 0, 0]}
    err = {k: float(np.mean(np.abs(num[k] - ex[k]))) for k in num}
    return err, num, ex, x


# -- smooth advected entropy wave (order of accuracy) -----------------------------------------
WAVE_TEMPLATE = """<?xml version="1.0" encoding="iso-8859-1"?>
<!--
  Smooth entropy (density) wave advected at uniform velocity and pressure on a periodic
  unit {what}: rho = {rho0} + {amp} sin(2 pi s), s = {sdef}, p = {p0}, u = {vel}; ideal gas
  gamma 1.4, cv 2.5. The exact solution is the translated profile; at t = {t} it is the
  initial one. Every cell is initialised to the exact cell average of rho (one geometry
  object per distinct value), temperature p / ((gamma - 1) cv rho).
  {order} advection, CFL {cfl}, {n} cells per direction.
-->
<Uintah_specification>
  <Meta><title>smooth wave {dim}D</title></Meta>
  <SimulationComponent type="ice"/>
  <Time>
    <maxTime> {t} </maxTime>
    <initTime> 0.0 </initTime>
    <delt_min> 0.0 </delt_min>
    <delt_max> 1.0 </delt_max>
    <delt_init> 1.0e-6 </delt_init>
    <timestep_multiplier> 1.0 </timestep_multiplier>
    <end_at_max_time_exactly> true </end_at_max_time_exactly>
  </Time>
  <Grid>
    <Level>
      <Box label="1">
        <lower> [0,0,0] </lower>
        <upper> [1,{yup},0.01] </upper>
        <extraCells> [0,0,1] </extraCells>
        <patches> [1,1,1] </patches>
        <resolution> [{n},{ny},1] </resolution>
      </Box>
      <periodic> [1,{py},0] </periodic>
    </Level>
  </Grid>
  <DataArchiver>
    <filebase>wave.uda</filebase>
    <outputInterval> {t} </outputInterval>
    <save label="rho_CC"/>
    <save label="vel_CC"/>
    <save label="press_CC"/>
    <save label="TotalMass"/>
    <save label="TotalIntEng"/>
    <save label="KineticEnergy"/>
  </DataArchiver>
  <CFD>
    <cfl> {cfl} </cfl>
    <ICE><advection type="{order}" transverseTerms="{transverse}"/><delT_activeDirectionsOnly>true</delT_activeDirectionsOnly></ICE>
  </CFD>
  <PhysicalConstants>
    <gravity> [0,0,0] </gravity>
    <reference_pressure> 1.0 </reference_pressure>
  </PhysicalConstants>
  <MaterialProperties>
    <ICE>
      <material name="gas">
        <EOS type="ideal_gas"/>
        <dynamic_viscosity> 0.0 </dynamic_viscosity>
        <thermal_conductivity> 0.0 </thermal_conductivity>
        <specific_heat> 2.5 </specific_heat>
        <gamma> 1.4 </gamma>
{objects}      </material>
    </ICE>
  </MaterialProperties>
</Uintah_specification>
"""
WAVE_OBJECT = """        <geom_object>
          {piece}
          <res> [1,1,1] </res>
          <velocity> {vel} </velocity>
          <temperature> {T!r} </temperature>
          <density> {rho!r} </density>
          <pressure> {p0} </pressure>
        </geom_object>
"""
WAVE = dict(rho0=1.0, amp=0.2, p0=1.0)


def wave_cell_average(n, dim):
    """Exact cell averages of the wave's density per diagonal index k = (i + j) mod n."""
    import numpy as np
    h = 1.0 / n
    sinc = np.sin(np.pi * h) / (np.pi * h)
    k = np.arange(n)
    # cell centres: s_c = (i + 1/2) h (1D), (i + j + 1) h (2D)
    sc = (k + 0.5) * h if dim == 1 else (k + 1.0) * h
    return WAVE["rho0"] + WAVE["amp"] * np.sin(2 * np.pi * sc) * sinc ** dim


def smooth_wave_deck(n, order="SecondOrder", cfl=0.4, dim=1, periods=1.0, transverse=False):
    """Deck text of the periodic smooth wave at n cells per direction, run for `periods` periods."""
    h = 1.0 / n
    rho = wave_cell_average(n, dim)
    vel = "[1.0,0.0,0.0]" if dim == 1 else "[1.0,1.0,0.0]"
    t = float(periods) if dim == 1 else 0.5 * float(periods)
    objects = []
    for k in range(n):
        if dim == 1:
            piece = f"<box><min> [{k * h!r},-1,-1] </min><max> [{(k + 1) * h!r},2,1] </max></box>"
        else:
            boxes = "".join(f"<box><min> [{i * h!r},{((k - i) % n) * h!r},-1] </min>"
                            f"<max> [{(i + 1) * h!r},{((k - i) % n + 1) * h!r},1] </max></box>" for i in range(n))
            piece = f"<union>{boxes}</union>"
        T = WAVE["p0"] / (0.4 * 2.5 * rho[k])
        objects.append(WAVE_OBJECT.format(piece=piece, vel=vel, T=float(T), rho=float(rho[k]), p0=WAVE["p0"]))
    return WAVE_TEMPLATE.format(what="interval" if dim == 1 else "square (wave along the diagonal)",
                                sdef="x" if dim == 1 else "x + y", vel=vel, t=t, order=order, cfl=cfl, n=n,
                                dim=dim, transverse=str(bool(transverse)).lower(), yup=1 if dim == 2 else 0.01, ny=n if dim == 2 else 1,
                                py=1 if dim == 2 else 0, objects="".join(objects), **WAVE)


def smooth_wave_errors(da, timestep=-1):
    """{'rho', 'u', 'p'}: mean |numerical - exact| (exact: cell averages of the translated wave)."""
    import numpy as np
    rho, (x, y, _) = da.read("rho_CC", 0, timestep)
    vel, _ = da.read("vel_CC", 0, timestep)
    p, _ = da.read("press_CC", 0, timestep)
    n = rho.shape[0]
    dim = 2 if rho.shape[1] > 1 else 1
    t = da.times[timestep]
    h = 1.0 / n
    sinc = np.sin(np.pi * h) / (np.pi * h)
    s = x[:, None] + (y[None, :] if dim == 2 else 0.0)
    shift = t if dim == 1 else 2.0 * t
    ex = WAVE["rho0"] + WAVE["amp"] * np.sin(2 * np.pi * (s - shift)) * sinc ** dim
    u_ex = np.zeros_like(vel[..., 0, :])
    u_ex[..., 0] = 1.0
    if dim == 2:
        u_ex[..., 1] = 1.0
    return {"rho": float(np.mean(np.abs(rho[:, :, 0] - ex))),
            "u": float(np.mean(np.abs(vel[:, :, 0, :] - u_ex))),
            "p": float(np.mean(np.abs(p[:, :, 0] - WAVE["p0"])))}
