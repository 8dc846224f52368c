"""Low-Mach scenes for semi-implicit ICE: the Taylor-Green vortex and a moving warm blob.

Taylor-Green: a steady solution of the Euler equations,
u = U sin(2 pi x) cos(2 pi y), v = -U cos(2 pi x) sin(2 pi y),
p = p0 + rho0 U^2 / 4 (cos 4 pi x + cos 4 pi y) on the periodic unit square, uniform
density (T = p / ((gamma - 1) cv rho0)); U = Mach * c0. The exact solution is the
initial state at every time, so the velocity error at the end is each scheme's error.
Used by tests/ice/test_implicit.py, scripts/accuracy_cost.py (scene "vortex") and
scripts/bench/implicit_ice.py; `implicit=None` gives explicit ICE. The blob (`blob_deck`):
a hot cylinder moving through air at rest in a closed box, one material or two gases
with exchange, for the solver benchmark and the multi-material tests.
"""
from __future__ import annotations

import numpy as np

GAS = dict(p0=101325.0, rho0=1.2, cv=717.5, gamma=1.4)

DECK = """<?xml version="1.0" encoding="iso-8859-1"?>
<!-- Taylor-Green vortex at Mach {mach} on a periodic unit square, {n}x{n} cells, {kind} ICE -->
<Uintah_specification>
  <Meta><title>Taylor-Green vortex</title></Meta>
  <SimulationComponent type="ice"/>
  {solver}
  <Time>
    <maxTime> {t} </maxTime>
    <initTime> 0.0 </initTime>
    <delt_min> 0.0 </delt_min>
    <delt_max> 1.0 </delt_max>
    <delt_init> 1.0 </delt_init>
    <timestep_multiplier> 1.0 </timestep_multiplier>
    <end_at_max_time_exactly> true </end_at_max_time_exactly>
    {maxsteps}
  </Time>
  <Grid>
    <Level>
      <Box label="1">
        <lower> [0,0,0] </lower>
        <upper> [1,1,0.01] </upper>
        <extraCells> [0,0,0] </extraCells>
        <patches> {patches} </patches>
        <resolution> [{n},{n},1] </resolution>
      </Box>
      <periodic> [1,1,0] </periodic>
    </Level>
  </Grid>
  <DataArchiver>
    <filebase>vortex.uda</filebase>
    <outputInterval> {t} </outputInterval>
    <save label="vel_CC"/>
    <save label="press_CC"/>
    <save label="rho_CC"/>
  </DataArchiver>
  <CFD>
    <cfl> {cfl} </cfl>
    <ICE>
      <advection type="SecondOrder"/>
      <delT_activeDirectionsOnly>true</delT_activeDirectionsOnly>
      {implicit}
    </ICE>
  </CFD>
  <PhysicalConstants>
    <gravity> [0,0,0] </gravity>
    <reference_pressure> {p0} </reference_pressure>
  </PhysicalConstants>
  <MaterialProperties>
    <ICE>
      <material name="air">
        <EOS type="ideal_gas"/>
        <specific_heat> {cv} </specific_heat>
        <gamma> {gamma} </gamma>
{objects}      </material>
    </ICE>
  </MaterialProperties>
</Uintah_specification>
"""
OBJECT = """        <geom_object><box><min> [{x0!r},{y0!r},-1] </min><max> [{x1!r},{y1!r},1] </max></box>
          <res> [1,1,1] </res><velocity> [{u!r},{v!r},0.0] </velocity><temperature> {T!r} </temperature>
          <density> {rho!r} </density><pressure> {p!r} </pressure></geom_object>
"""
IMPLICIT = """<ImplicitSolver>
        <max_outer_iterations> {outer} </max_outer_iterations>
        <outer_iteration_tolerance> {outer_tol} </outer_iteration_tolerance>
        <Parameters variable="implicitPressure">
          <solver> cg </solver>
          <preconditioner> {precond} </preconditioner>
          <tolerance> {tol} </tolerance>{norm}
          <maxiterations> {maxit} </maxiterations>
        </Parameters>
      </ImplicitSolver>"""
TIMESTEP_CONTROL = ("<TimeStepControl><Scheme_for_delT_calc> aggressive </Scheme_for_delT_calc>"
                    "<knob_for_speedSound> {knob} </knob_for_speedSound></TimeStepControl>")


def speed(mach):
    g = GAS
    return mach * np.sqrt(g["gamma"] * g["p0"] / g["rho0"])


def exact(x, y, mach):
    """(u, v, p) of the vortex at points (x, y)."""
    U, g = speed(mach), GAS
    u = U * np.sin(2 * np.pi * x) * np.cos(2 * np.pi * y)
    v = -U * np.cos(2 * np.pi * x) * np.sin(2 * np.pi * y)
    p = g["p0"] + g["rho0"] * U * U / 4.0 * (np.cos(4 * np.pi * x) + np.cos(4 * np.pi * y))
    return u, v, p


def vortex_deck(n, mach=0.05, t=None, implicit=None, cfl=0.4, patches="[1,1,1]", precond="pfmg",
                tolerance=1e-10, outer=20, outer_tol=1e-9, maxit=500, max_timesteps=None, knob=None, norm=None):
    """Deck text; t defaults to 0.2 of the turnover time 1 / U; implicit=True for semi-implicit ICE.

    knob: <TimeStepControl><knob_for_speedSound> of an implicit run (default 0: delT from the
    flow speed; 1 gives explicit ICE's delT);
    norm: the solver's <norm> (L2, LInfinity).
    """
    g = GAS
    t = 0.2 / speed(mach) if t is None else t
    h = 1.0 / n
    xc = (np.arange(n) + 0.5) * h
    objs = []
    for i in range(n):
        for j in range(n):
            u, v, p = exact(xc[i], xc[j], mach)
            objs.append(OBJECT.format(x0=i * h, x1=(i + 1) * h, y0=j * h, y1=(j + 1) * h, u=float(u), v=float(v),
                                      p=float(p), rho=g["rho0"], T=float(p / ((g["gamma"] - 1) * g["cv"] * g["rho0"]))))
    imp = IMPLICIT.format(outer=outer, outer_tol=outer_tol, precond=precond, tol=tolerance, maxit=maxit,
                          norm=f"<norm> {norm} </norm>" if norm else "") \
        if implicit else ""
    if implicit:
        imp += TIMESTEP_CONTROL.format(knob=0.0 if knob is None else knob)
    return DECK.format(mach=mach, n=n, kind="semi-implicit" if implicit else "explicit", t=t, cfl=cfl,
                       patches=patches, implicit=imp, solver='<Solver type="hypre"/>' if implicit else "",
                       objects="".join(objs), maxsteps=f"<max_Timesteps> {max_timesteps} </max_Timesteps>"
                       if max_timesteps else "", **g)


def vortex_errors(da, timestep=-1, mach=0.05):
    """{'u', 'p'}: mean |numerical - exact| of the velocity (both components) and of p - mean p."""
    vel, (x, y, _) = da.read("vel_CC", 0, timestep)
    p, _ = da.read("press_CC", 0, timestep)
    X, Y = np.meshgrid(x, y, indexing="ij")
    u, v, pe = exact(X, Y, mach)
    pn = p[:, :, 0]
    return {"u": float(np.mean(np.abs(vel[:, :, 0, 0] - u)) + np.mean(np.abs(vel[:, :, 0, 1] - v))) / 2,
            "p": float(np.mean(np.abs((pn - pn.mean()) - (pe - pe.mean()))))}


# -- a warm blob moving through air at rest in a closed box (variable coefficients) -------------------
BLOB = """<Uintah_specification><SimulationComponent type="ice"/>{solver}
<Time><maxTime>100</maxTime><max_Timesteps>{steps}</max_Timesteps>{delt}</Time>
<Grid><BoundaryConditions>{faces}</BoundaryConditions><Level><Box label="1"><lower>[0,0,0]</lower>
<upper>[1,1,0.01]</upper><extraCells>[1,1,0]</extraCells><patches>{patches}</patches>
<resolution>[{n},{n},1]</resolution></Box></Level></Grid>
<DataArchiver><filebase>blob.uda</filebase><outputTimestepInterval>{steps}</outputTimestepInterval>
<save label="vel_CC"/><save label="press_CC"/><save label="rho_CC"/></DataArchiver>
<CFD><cfl>0.4</cfl><ICE><advection type="SecondOrder"{limiter}/>
<delT_activeDirectionsOnly>true</delT_activeDirectionsOnly>{implicit}</ICE></CFD>
<PhysicalConstants><gravity>[0,0,0]</gravity><reference_pressure>101325</reference_pressure></PhysicalConstants>
<MaterialProperties><ICE>{materials}</ICE>{exchange}</MaterialProperties></Uintah_specification>"""
BLOB_FACES = "".join(f'<Face side="{s}"><BCType id="all" label="Symmetric" var="symmetry"/></Face>'
                     for s in ("x-", "x+", "y-", "y+"))
BLOB_OBJ = """<geom_object>{piece}<res>[2,2,2]</res><velocity>[{u},0,0]</velocity><temperature>{T}</temperature>
<density>{rho}</density><pressure>101325</pressure></geom_object>"""
BLOB_MAT = """<material><EOS type="ideal_gas"/><specific_heat>{cv}</specific_heat><gamma>{gamma}</gamma>
{objects}</material>"""
CYL = '<cylinder label="c"><bottom>[0.35,0.5,-1]</bottom><top>[0.35,0.5,1]</top><radius>0.15</radius></cylinder>'
REST = '<difference><box><min>[-1,-1,-1]</min><max>[2,2,2]</max></box><cylinder label="c"/></difference>'
NOWHERE = '<box><min>[-2,-2,-2]</min><max>[-1,-1,-1]</max></box>'


def blob_deck(n, mach=0.05, steps=10, implicit=None, precond="pfmg", patches=None, tolerance=1e-10,
              outer_tol=1e-8, materials=1, K=None, delt=None, knob=None, maxit=5000, limiter=None,
              heating=None, outer=20):
    """A hot cylinder (3x T, 1/3 rho) moving at `mach` in air at rest, symmetry walls, `steps` steps.

    implicit: knob_for_speedSound `knob` (default 0: delT from the flow speed);
    materials=2: the blob is a second gas (cv 1000, gamma 1.3) with exchange coefficients K;
    delt fixes delT (delt_min = delt_max); patches default to 64^2 cells each; limiter: the
    <advection limiter> (None: pysus's default); heating: its dissipationHeating ("false" with
    Uintah's limiter is Uintah's scheme); outer: max_outer_iterations.
    """
    u = mach * np.sqrt(1.4 * 101325 / 0.4)
    hot = BLOB_OBJ.format(piece=CYL, u=u, T=900.0, rho=0.4)
    if materials == 1:
        mats = BLOB_MAT.format(cv=717.5, gamma=1.4, objects=hot + BLOB_OBJ.format(piece=REST, u=0.0, T=300.0,
                                                                                  rho=1.2))
    else:
        # the labelled cylinder is defined where it first appears (material 0's first object);
        # the geometry fractions of the two materials add up to one in every cell
        air = BLOB_OBJ.format(piece=f"<difference><box><min>[-1,-1,-1]</min><max>[2,2,2]</max></box>{CYL}"
                                    "</difference>", u=0.0, T=300.0, rho=1.2)
        gas = BLOB_OBJ.format(piece='<cylinder label="c"/>', u=u, T=900.0, rho=0.4)
        mats = BLOB_MAT.format(cv=717.5, gamma=1.4, objects=air) + BLOB_MAT.format(cv=1000.0, gamma=1.3, objects=gas)
    exch = "" if K is None else ("<exchange_properties><exchange_coefficients>"
                                 f"<momentum>[{K}]</momentum><heat>[{K}]</heat></exchange_coefficients></exchange_properties>")
    imp = ""
    if implicit:
        imp = IMPLICIT.format(outer=outer, outer_tol=outer_tol, precond=precond, tol=tolerance, maxit=maxit, norm="")
        imp += TIMESTEP_CONTROL.format(knob=0.0 if knob is None else knob)
    np_ = max(1, n // 64)
    dt = "<delt_init>1</delt_init>" if delt is None else \
        f"<delt_init>{delt}</delt_init><delt_min>{delt}</delt_min><delt_max>{delt}</delt_max>"
    return BLOB.format(steps=steps, delt=dt, faces=BLOB_FACES, patches=patches or f"[{np_},{np_},1]", n=n,
                       implicit=imp, solver='<Solver type="hypre"/>' if implicit else "", materials=mats,
                       exchange=exch, limiter=("" if limiter is None else f' limiter="{limiter}"')
                       + ("" if heating is None else f' dissipationHeating="{heating}"'))
