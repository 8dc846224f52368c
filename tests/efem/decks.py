"""Small EFEM decks for the tests: a pool of water in a 1 m x 1 m box, optionally with an
elastic block in or above it."""
from __future__ import annotations

SAVES = ("vol_frac_CC", "g.velocity", "press_CC", "stress_CC", "TotalMass", "KineticEnergy")


def deck(res=(20, 20), patches=(2, 2), steps=20, max_time=10.0, pool=0.6, block=None, walls=None,
         saves=SAVES, every=None, checkpoint=None, damping=0.0, gravity=-9.81, settings="", width=1.0,
         viscosity=1e-3):
    """Deck text. block: dict(lo=(x, y), hi=(x, y), density, E, nu, velocity=(u, v)) listed
    before the water (the water fills around it); walls: {side: "wall" | "slip"};
    every: output every N steps (default: only the last); checkpoint: (interval steps, cycle)."""
    nx, ny = res
    dz = 0.05
    every = every or steps
    faces = "".join(f'<Face side="{s}" type="{t}"/>' for s, t in (walls or {}).items())
    mats = ""
    if block is not None:
        (x0, y0), (x1, y1) = block["lo"], block["hi"]
        u, v = block.get("velocity", (0.0, 0.0))
        mats += f"""
      <material name="block">
        <density> {block.get('density', 500.0)} </density>
        <youngs_modulus> {block.get('E', 1e5)} </youngs_modulus>
        <poissons_ratio> {block.get('nu', 0.3)} </poissons_ratio>
        <geom_object> <box> <min> [{x0}, {y0}, 0] </min> <max> [{x1}, {y1}, {dz}] </max> </box>
          <res> [4, 4, 1] </res> <velocity> [{u}, {v}, 0] </velocity> </geom_object>
      </material>"""
    if pool > 0:
        mats += f"""
      <material name="water">
        <density> 1000 </density>
        <dynamic_viscosity> {viscosity} </dynamic_viscosity>
        <geom_object> <box> <min> [0, 0, 0] </min> <max> [{width}, {pool}, {dz}] </max> </box>
          <res> [4, 4, 1] </res> </geom_object>
      </material>"""
    save = "\n".join(f'    <save label="{s}"/>' for s in saves)
    ckpt = f'<checkpoint timestepInterval="{checkpoint[0]}" cycle="{checkpoint[1]}"/>' if checkpoint else ""
    return f"""<?xml version="1.0" encoding="iso-8859-1"?>
<Uintah_specification>
  <Meta> <title>EFEM test</title> </Meta>
  <SimulationComponent type="efem"/>
  <Time>
    <maxTime> {max_time} </maxTime>
    <initTime> 0.0 </initTime>
    <delt_min> 0.0 </delt_min>
    <delt_max> 0.01 </delt_max>
    <max_Timesteps> {steps} </max_Timesteps>
    <timestep_multiplier> 1.0 </timestep_multiplier>
  </Time>
  <Grid>
    <Level>
      <Box label="1">
        <lower> [0, 0, 0] </lower>
        <upper> [{width}, 1, {dz}] </upper>
        <resolution> [{nx}, {ny}, 1] </resolution>
        <extraCells> [1, 1, 1] </extraCells>
        <patches> [{patches[0]}, {patches[1]}, 1] </patches>
      </Box>
    </Level>
  </Grid>
  <DataArchiver>
    <filebase>efem.uda</filebase>
    <outputTimestepInterval> {every} </outputTimestepInterval>
{save}
    {ckpt}
  </DataArchiver>
  <PhysicalConstants> <gravity> [0, {gravity}, 0] </gravity> </PhysicalConstants>
  <EFEM>
    <damping> {damping} </damping>
    {settings}
    <BoundaryConditions> {faces} </BoundaryConditions>
  </EFEM>
  <MaterialProperties>
    <EFEM>{mats}
    </EFEM>
  </MaterialProperties>
</Uintah_specification>
"""
