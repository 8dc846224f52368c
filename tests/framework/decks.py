"""Small example-component decks used by the framework tests."""

HEAT = """<?xml version="1.0"?>
<Uintah_specification>
  <Meta><title>heat</title></Meta>
  <SimulationComponent type="examples"/>
  <Time>
    <maxTime>{maxTime}</maxTime>
    <initTime>0</initTime>
    <delt_min>0</delt_min>
    <delt_max>1</delt_max>
    <timestep_multiplier>1</timestep_multiplier>
    <end_at_max_time_exactly>true</end_at_max_time_exactly>
  </Time>
  <Grid>
    <Level>
      <Box label="1">
        <lower>[0,0,0]</lower>
        <upper>[1,1,{zup}]</upper>
        <resolution>[{n},{n},{nz}]</resolution>
        <extraCells>[1,1,1]</extraCells>
        <patches>{patches}</patches>
      </Box>
      {periodic}
    </Level>
  </Grid>
  <DataArchiver>
    <filebase>heat.uda</filebase>
    {outtag}
    {saves}
    {checkpoint}
  </DataArchiver>
  <Examples>
    {diffusion}
    {particles}
  </Examples>
</Uintah_specification>
"""

DIFFUSION = """<diffusion>
      <alpha>0.01</alpha>
      <cfl>{cfl}</cfl>{implicit}
      <gaussian><center>[0.5,0.5,0.5]</center><width>0.08</width><amplitude>1</amplitude></gaussian>
    </diffusion>"""

PARTICLES = """<particles>
      <lower>[0.3,0.3,0]</lower><upper>[0.7,0.7,1]</upper>
      <res>[2,2,2]</res>
      <velocity>{velocity}</velocity>
      <omega>{omega}</omega>
      <center>[0.5,0.5,0.5]</center>
      <cfl>0.5</cfl>
    </particles>"""


def heat(n=32, nz=1, patches="[1,1,1]", maxTime=0.2, out=None, extra_save="", checkpoint="",
         periodic="", diffusion=True, particles=False, velocity="[0,0,0]", omega=6.283185307179586,
         implicit=False, cfl=0.4, tolerance=1e-10):
    saves = ('<save label="temp_CC"/>' if diffusion else "") + extra_save
    outtag = (f"<outputInterval>{maxTime}</outputInterval>" if out is None
              else f"<outputTimestepInterval>{out}</outputTimestepInterval>")
    return HEAT.format(outtag=outtag, saves=saves, n=n, nz=nz, zup=1.0 if nz > 1 else 0.05, patches=patches, maxTime=maxTime,
                       checkpoint=checkpoint, periodic=periodic,
                       diffusion=DIFFUSION.format(cfl=cfl, implicit=(
                           f"<implicit>true</implicit><tolerance>{tolerance}</tolerance>" if implicit else ""))
                       if diffusion else "",
                       particles=PARTICLES.format(velocity=velocity, omega=omega) if particles else "")
