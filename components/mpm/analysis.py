"""`<DataAnalysis>` of MPM decks.

`<Module name="particleExtract">` (disks.ups has one) is read here: its tags are
read and checked, but pysus does not yet write Uintah's per-particle text files: it
says so on stderr at set-up instead of ignoring the block silently. The other modules
are the framework's (framework/analysis.py), which refuses those it does not have.
"""
import sys

from framework.problemspec import Param

PARTICLE_EXTRACT = {
    "material": Param("str"),
    "samplingFrequency": Param("float"),
    "timeStart": Param("float", 0.0),
    "timeStop": Param("float", 1e300),
    "colorThreshold": Param("float", 0.0),
}


class ParticleExtract:
    active = False      # nothing is scheduled yet

    def __init__(self, root, mpm):
        da = root.child("DataAnalysis")
        if da is None:
            return
        for mod in da.children("Module"):
            name = mod.attr("name")
            if name != "particleExtract":
                continue
            spec = mod.read(PARTICLE_EXTRACT)
            names = [m.name for m in mpm.materials]
            if spec["material"] not in names:
                raise mod.child("material").error(f"no MPM material named {spec['material']!r}; "
                                                  f"materials: {', '.join(names)}")
            if spec["colorThreshold"] and not mpm.flags["withColor"]:
                raise mod.child("colorThreshold").error("needs <MPM><withColor>true</withColor>")
            var = mod.child("Variables", required=True)
            for a in var.children("analyze"):
                a.attr("label")
            print(f"pysus: warning: {mod.filename}:{mod.line}: <Module name=\"{name}\"> is read but "
                  "its per-particle text output is not implemented in pysus; use <save> for particle data",
                  file=sys.stderr)
