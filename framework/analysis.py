"""<DataAnalysis> modules: Uintah's on-the-fly analysis (OnTheFlyAnalysis) run beside a component.

Each <Module name="..."> adds its tasks after the component's timestep. `vorticity` computes
the CC field vorticity = curl(vel_CC) (second-order central differences over the interior cells,
0 in the extra cells), a task the graph keeps only when a deck saves "vorticity". `minMax` writes,
at its sampling times within [timeStart, timeStop], one line per analysed variable to
<uda>/MinMax/L-0/<label>_<matl>: "time min max" (Vectors componentwise, in brackets), over the
interior cells (CC) or the faces of interior cells (FC), in Uintah's format.
"""
from __future__ import annotations

import os

import numpy as np
from numba import njit

from . import labels as L
from .task import NEW, Task
from .variables import Ghost, VarType

FACE_TYPES = (VarType.SFCX, VarType.SFCY, VarType.SFCZ)


@njit(cache=True)
def curl_central(vel, out, lo, hi, dx, dims):
    """omega = curl(vel), (u[c+1] - u[c-1]) / 2 dx per direction; absent directions add 0."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                d = np.zeros((3, 3))            # d[a, b] = d vel_b / d x_a
                if dims[0]:
                    for b in range(3):
                        d[0, b] = (vel[i + 1, j, k, b] - vel[i - 1, j, k, b]) / (2.0 * dx[0])
                if dims[1]:
                    for b in range(3):
                        d[1, b] = (vel[i, j + 1, k, b] - vel[i, j - 1, k, b]) / (2.0 * dx[1])
                if dims[2]:
                    for b in range(3):
                        d[2, b] = (vel[i, j, k + 1, b] - vel[i, j, k - 1, b]) / (2.0 * dx[2])
                out[i, j, k, 0] = d[1, 2] - d[2, 1]
                out[i, j, k, 1] = d[2, 0] - d[0, 2]
                out[i, j, k, 2] = d[0, 1] - d[1, 0]


def _material(node, component, tag="material"):
    """A material index as Uintah's parseAndLookupMaterial: by name (quotes dropped); with one
    material, that one whatever the name (Uintah's impVortices_turb.ups misspells its own)."""
    names = component.material_names()
    child = node.child(tag, required=True)
    text = child.text().strip().replace('"', "")
    if len(names) == 1:
        return 0
    if text not in names:
        raise child.error(f"no material named '{text}'; accepted: the <material name=...> of this deck: "
                          f"{', '.join(names)}")
    return names.index(text)


class Vorticity:
    """Uintah's vorticity module: curl of one material's vel_CC."""

    def __init__(self, node, component, level):
        self.matl = _material(node, component)
        self.label = L.create("vorticity", VarType.CC, (3,))
        self.level = level
        self.needed = set()

    def schedule(self, sched):
        sched.add_task(Task("vorticity::doAnalysis", self.compute, [self.matl])
                       .requires(NEW, L.find("vel_CC"), Ghost.AROUND_CELLS, 1).computes(self.label))

    def compute(self, patch, matls, old_dw, new_dw):
        for m in matls:
            vel = new_dw.get(L.find("vel_CC"), m, patch)
            out = new_dw.allocate(self.label, m, patch)
            lo, hi = (np.array(x, dtype=np.int64) for x in patch.interior(VarType.CC))
            curl_central(vel, out, lo, hi, np.asarray(self.level.dx, dtype=np.float64),
                         np.array([not c for c in self.level.collapsed], dtype=np.bool_))

    def after_step(self, dw, timestep, t, uda):
        pass


class MinMax:
    """Uintah's minMax module: min and max of variables, written to files in the uda."""

    def __init__(self, node, component, level):
        matl = _material(node, component)
        self.freq = node.get("samplingFrequency", above=0.0)
        self.start = node.get("timeStart")
        self.stop = node.get("timeStop")
        self.prev = self.start - 1.0 / self.freq
        self.vars = []
        for a in node.child("Variables", required=True).children("analyze"):
            name = a.attr("label")
            label = L.find(name)
            if label is None or label.vartype not in (VarType.CC,) + FACE_TYPES or label.shape not in ((), (3,)):
                raise a.error(f'label="{name}" is not a cell- or face-centred double or Vector of this deck; '
                              "accepted: a CC or FC variable the component computes")
            m = a.attr("matl", "int", matl, at_least=0)
            red = tuple(L.create(f"{name}_{m}_{op}", VarType.REDUCTION, label.shape, reduction=op)
                        for op in ("min", "max"))
            self.vars.append((label, m, red))
        self.needed = {r.name for _, _, red in self.vars for r in red}

    def schedule(self, sched):
        for label, m, (rmin, rmax) in self.vars:
            sched.add_task(Task(f"minMax::computeMinMax({label.name}_{m})", self._reduce(label, rmin, rmax), [m])
                           .requires(NEW, label).computes(rmin, matls=[m]).computes(rmax, matls=[m]))

    @staticmethod
    def _reduce(label, rmin, rmax):
        def task(patch, matls, old_dw, new_dw):
            for m in matls:
                q = new_dw.get(label, m, patch)
                lo, hi = patch.interior(VarType.CC)
                if label.vartype in FACE_TYPES:
                    d = FACE_TYPES.index(label.vartype)
                    f0 = np.array(patch.low_index(label.vartype))
                    lo = np.array(patch.lo) - f0
                    hi = np.array(patch.hi) - f0
                    hi[d] += 1
                box = q[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]].reshape((-1,) + label.shape)
                new_dw.put_reduction(rmin, box.min(axis=0), m)
                new_dw.put_reduction(rmax, box.max(axis=0), m)
        return task

    def after_step(self, dw, timestep, t, uda):
        if t < self.start or t > self.stop or t < self.prev + 1.0 / self.freq:
            return
        self.prev = t
        if uda is None:
            return
        folder = os.path.join(uda, "MinMax", "L-0")
        os.makedirs(folder, exist_ok=True)
        for label, m, (rmin, rmax) in self.vars:
            path = os.path.join(folder, f"{label.name}_{m}")
            new = not os.path.exists(path)
            lo, hi = dw.get_reduction(rmin, m), dw.get_reduction(rmax, m)
            with open(path, "a") as f:
                if new:
                    f.write("#The reported min & max values are for this level 0 \n"
                            "#Time                      min                       max\n")
                if label.shape == ():
                    f.write(f"{t:16.15E}     {float(lo):16.15E}    {float(hi):16.15E}\n")
                else:
                    f.write(f"{t:16.15E}     [{lo[0]:16.15E} {lo[1]:16.15E} {lo[2]:16.15E}]   "
                            f"[{hi[0]:16.15E} {hi[1]:16.15E} {hi[2]:16.15E}]\n")


MODULES = {"vorticity": Vorticity, "minMax": MinMax}


def read_analysis(root, component, level) -> list:
    """The deck's <DataAnalysis> modules, in order, but those the component reads itself (its
    `analysis_modules`); an unknown name is refused with the accepted ones."""
    da = root.child("DataAnalysis")
    if da is None:
        return []
    out = []
    own = set(getattr(component, "analysis_modules", ()))    # read by the component itself
    for node in da.children("Module"):
        name = node.attr("name")
        if name in own:
            continue
        cls = MODULES.get(name)
        if cls is None:
            raise node.error(f'<Module name="{name}"> is not available; accepted: {", ".join(MODULES)}')
        out.append(cls(node, component, level))
    return out
