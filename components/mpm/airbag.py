"""Airbag impact (paper 004 sec. 4.4, Tables V-VI): deck text and the measurements.

Axisymmetric (x = r, y the axis): a gas-filled fabric membrane of revolution struck along
its axis by a stiff cylindrical probe. Materials: 0 the gas (ideal_gas_fluid points, Table VI
air: rho 1.2156 kg/m^3, e 8226 J/kg, so p = (gamma - 1) rho e = 4000 Pa, gamma 1.4), 1 the
fabric (membrane points, Table VI: thickness 0.5 mm, 662 kg/m^3, E = 6e7 Pa, nu = 0.4,
biaxial 'plane' formulation with the hoop stress), 2 the probe (comp_neo_hook, Table V:
diameter 200 mm, 6.03 kg, 3.90 m/s; E = 5e7 Pa as 004 chose, nu = 0.3 assumed, the density
giving the mass). All three share one velocity field (single_velocity contact: 004 sec. 3
solves one momentum equation for all materials).

The bag's shape is not in 004's text (its Figs. 14-15 show a tethered pre-inflated bag): here
a flat circular base of radius a lying on a rigid plate (the y- face, a symmetry plane, stands
for the steering wheel the bag is mounted on) closed by a half oblate spheroid dome of radius
a and height c = 0.6 a, its area giving 004's bag mass of 367.2 g (a = 0.376 m, c = 0.226 m,
67 litres). The fabric starts stress free and the gas at 004's 4000 Pa; the bag is not in
equilibrium at t = 0 (it inflates a little while the probe, one cell above the dome, comes
down) -- 004 let its tethered bag settle first. The membrane's two ends sit half a point
spacing off the axis (a ring at r = 0 has no mass).

    from components.mpm.airbag import airbag_deck, probe_history
"""
from __future__ import annotations

import numpy as np

GAS = dict(rho=1.2156, e=8226.0, gamma=1.4, mu=1.8e-5)        # 004 Table VI (air; mu of air)
FABRIC = dict(h=0.5e-3, rho=662.0, E=6.0e7, nu=0.4, mass=0.3672)  # 004 Table VI, sec. 4.4
PROBE = dict(d=0.2, mass=6.03, v=3.90, E=5.0e7, nu=0.3, length=0.1)  # 004 Table V
DOME = 0.6          # dome height / base radius


def bag_radius(mass=FABRIC["mass"], h=FABRIC["h"], rho=FABRIC["rho"], k=DOME):
    """Base radius a of the flat base plus half oblate spheroid (height k a) whose fabric
    weighs `mass`: area pi a^2 (1 + 1 + (1 - e^2)/e atanh e), e^2 = 1 - k^2."""
    e = np.sqrt(1.0 - k * k)
    area_over_a2 = np.pi * (2.0 + (1.0 - e * e) / e * np.arctanh(e))
    return float(np.sqrt(mass / (rho * h) / area_over_a2))


def meridian(a, c, y0, r0, n=400):
    """The bag's meridian from the axis along the base (y = y0) to the rim r = a, then over the
    dome r = a cos(t), y = y0 + c sin(t) back to the axis; both ends at r = r0."""
    base = np.stack([np.linspace(r0, a, n // 2, endpoint=False), np.full(n // 2, y0)], 1)
    t = np.linspace(0.0, np.arccos(r0 / a), n)
    dome = np.stack([a * np.cos(t), y0 + c * np.sin(t)], 1)
    return np.vstack([base, dome])


def airbag_deck(dx=0.025, t_end=0.1, out=2.0e-3, every_step=False, cfl=0.5, gas_ppc=4,
                spacing=None, mu=GAS["mu"], sphere=None, damping=0.0, grid_density=True):
    """Deck text: cells dx, membrane points `spacing` apart (default dx/16), gas_ppc^2 gas
    points per cell, output every `out` s (every step with every_step; the nodal masses and
    forces are saved for probe_force), the gas points' volumes from the nodal mass
    (ideal_gas_fluid <density_from_grid>) unless grid_density=False. sphere=R: instead of
    the bag and the probe, a spherical bag of radius R (centre on the axis) holding the same
    gas, with <artificial_damping_coeff> `damping` (1/s): its equilibrium has
    sigma_tt = sigma_hh = p R / (2 h)."""
    sp = spacing or dx / 16.0
    E, nu = FABRIC["E"], FABRIC["nu"]
    if sphere is None:
        a = bag_radius()
        c = DOME * a
        y0 = dx / 8.0                               # the base, just above the plate (y = 0)
        yp = y0 + c + dx                            # the probe starts one cell above the dome
        Lp, Rp = PROBE["length"], 0.5 * PROBE["d"]
        rho_p = PROBE["mass"] / (np.pi * Rp * Rp * Lp)
        nr = int(np.ceil((a + 0.16) / dx))
        ny = int(np.ceil((yp + Lp + 0.16) / dx))
        chain = meridian(a, c, y0, 0.5 * sp)
        gas = (f'<intersection><ellipsoid><origin>[0,{y0!r},0]</origin><rx>{a!r}</rx><ry>{c!r}</ry><rz>1.0</rz>'
               f'</ellipsoid><box><min>[0,{y0!r},{-dx!r}]</min><max>[{a!r},{y0 + c!r},{dx!r}]</max></box>'
               '</intersection>')
        Ep, nup = PROBE["E"], PROBE["nu"]
        probe = f"""
    <material name="probe"><density>{rho_p!r}</density>
      <constitutive_model type="comp_neo_hook"><bulk_modulus>{Ep / (3 * (1 - 2 * nup))!r}</bulk_modulus>
        <shear_modulus>{Ep / (2 * (1 + nup))!r}</shear_modulus></constitutive_model>
      <geom_object><box><min>[0,{yp!r},{-dx!r}]</min><max>[{Rp!r},{yp + Lp!r},{dx!r}]</max></box>
        <res>[2,2,1]</res><velocity>[0,{-PROBE["v"]},0]</velocity></geom_object>
    </material>"""
        plate = '\n      <Face side="y-"><BCType id="all" var="symmetry" label="Symmetric"/></Face>'
        matls = "[0,1,2]"
        title = "probe striking a gas-filled axisymmetric airbag (004 sec. 4.4)"
    else:
        R = float(sphere)
        nr = ny = int(np.ceil(1.3 * R / dx))
        ny *= 2
        yc = 0.5 * ny * dx
        t0 = np.arcsin(0.5 * sp / R) - 0.5 * np.pi
        t = np.linspace(t0, -t0, 400)
        chain = np.stack([R * np.cos(t), yc + R * np.sin(t)], 1)
        gas = f'<sphere><origin>[0,{yc!r},0]</origin><radius>{R!r}</radius></sphere>'
        probe = plate = ""
        matls = "[0,1]"
        title = "gas in a spherical membrane, axisymmetric"
    verts = "".join(f"<vertex>[{float(x)!r},{float(y)!r},0]</vertex>" for x, y in chain)
    grid_saves = '\n    <save label="g.mass"/><save label="g.internalforce"/><save label="g.externalforce"/>'
    interval = ("<outputTimestepInterval>1</outputTimestepInterval>" if every_step
                else f"<outputInterval>{out}</outputInterval>")
    return f"""<?xml version="1.0" encoding="ISO-8859-1"?>
<Uintah_specification>
  <Meta><title>{title}</title></Meta>
  <SimulationComponent type="mpm"/>
  <Time><maxTime>{t_end}</maxTime><initTime>0.0</initTime><delt_min>0.0</delt_min>
        <delt_max>1.0</delt_max><timestep_multiplier>{cfl}</timestep_multiplier></Time>
  <Grid><BoundaryConditions>
      <Face side="x-"><BCType id="all" var="symmetry" label="Symmetric"/></Face>{plate}
    </BoundaryConditions>
    <Level><Box label="1"><lower>[0,0,{-0.5 * dx!r}]</lower><upper>[{nr * dx!r},{ny * dx!r},{0.5 * dx!r}]</upper>
      <resolution>[{nr},{ny},1]</resolution><extraCells>[1,1,0]</extraCells>
      <patches>[1,1,1]</patches></Box></Level>
  </Grid>
  <DataArchiver><filebase>airbag.uda</filebase>{interval}
    <save label="KineticEnergy"/><save label="StrainEnergy"/><save label="TotalMass"/><save label="TotalMomentum"/>
    <save label="p.x"/><save label="p.velocity"/><save label="p.mass"/><save label="p.volume"/>
    <save label="p.stress"/><save label="p.particleID"/><save label="p.internalEnergy"/>
    <save label="p.tangent"/><save label="p.thickness"/>{grid_saves}
  </DataArchiver>
  <MPM><time_integrator>explicit</time_integrator><interpolator>linear</interpolator>
    <stress_update>musl</stress_update><axisymmetric>true</axisymmetric>
    <artificial_damping_coeff>{damping}</artificial_damping_coeff></MPM>
  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
  <MaterialProperties><MPM>
    <material name="gas"><density>{GAS["rho"]}</density>
      <constitutive_model type="ideal_gas_fluid"><gamma>{GAS["gamma"]}</gamma>
        <viscosity>{mu}</viscosity><specific_heat>1.0</specific_heat>
        <density_from_grid>{str(grid_density).lower()}</density_from_grid></constitutive_model>
      <geom_object>{gas}<res>[{gas_ppc},{gas_ppc},1]</res><velocity>[0,0,0]</velocity>
        <temperature>{GAS["e"]}</temperature></geom_object>
    </material>
    <material name="fabric"><density>{FABRIC["rho"]}</density>
      <constitutive_model type="membrane"><bulk_modulus>{E / (3 * (1 - 2 * nu))!r}</bulk_modulus>
        <shear_modulus>{E / (2 * (1 + nu))!r}</shear_modulus><formulation>plane</formulation></constitutive_model>
      <geom_object><membrane_polygon>{verts}<spacing>{sp!r}</spacing><thickness>{FABRIC["h"]}</thickness>
        <closed>false</closed></membrane_polygon><velocity>[0,0,0]</velocity></geom_object>
    </material>{probe}
    <contact><type>single_velocity</type><materials>{matls}</materials></contact>
  </MPM></MaterialProperties>
</Uintah_specification>
"""


def history(da):
    """Per output: time, the probe's mean axial velocity, displacement and momentum (per
    radian), the gas's volume-weighted mean pressure (gamma - 1) sum m e / sum V, its mass and
    volume (per radian), the kinetic and the strain energy (the gas's internal energy change,
    the fabric's and the probe's strain energy; per radian)."""
    gamma = GAS["gamma"]
    rows = []
    y0 = None
    for k in range(len(da.times)):
        g, mem, pr = da.particles(0, k), da.particles(1, k), da.particles(2, k)
        m, v, y = pr["p.mass"], pr["p.velocity"][:, 1], pr["p.x"][:, 1]
        ym = float(np.sum(m * y) / m.sum())
        y0 = ym if y0 is None else y0
        rows.append(dict(time=float(da.times[k]), v=float(np.sum(m * v) / m.sum()), disp=ym - y0,
                         momentum=float(np.sum(m * v)), gas_mass=float(g["p.mass"].sum()),
                         gas_volume=float(g["p.volume"].sum()), bag_volume=enclosed_volume(mem),
                         pressure=float((gamma - 1) * np.sum(g["p.mass"] * g["p.internalEnergy"])
                                        / g["p.volume"].sum()),
                         gas_energy=float(np.sum(g["p.mass"] * g["p.internalEnergy"]))))
    return rows


def enclosed_volume(mem):
    """Volume per radian inside the membrane's meridian (closed along the axis):
    the integral of r dr dy = the loop integral of r^2/2 dy (trapezoids)."""
    x = mem["p.x"][np.argsort(mem["p.particleID"])]
    r2, y = x[:, 0] ** 2, x[:, 1]
    return float(np.sum(0.25 * (r2[1:] + r2[:-1]) * np.diff(y)))


def probe_force(da, k, probe=2):
    """The axial force the bag exerts on the probe in the step that ended at output k (per
    radian), from the grid: sum_i (m_i^probe / m_i) f_i,y, f_i the node's total force. In one
    velocity field this is the probe's share of each node's force less its own internal
    force, whose axial sum is zero (sum_i dS_i/dy = 0)."""
    mats = range(len(da.materials))
    gm = {m: da.read("g.mass", m, k)[0] for m in mats}
    f = sum(da.read("g.internalforce", m, k)[0][..., 1] + da.read("g.externalforce", m, k)[0][..., 1]
            for m in mats)
    mtot = sum(gm.values())
    share = np.divide(gm[probe], mtot, out=np.zeros_like(mtot), where=mtot > 0)
    return float(np.sum(share * f))
