"""<DataAnalysis> modules: Uintah's on-the-fly analysis (OnTheFlyAnalysis) run beside a component.

Each <Module name="..."> adds its tasks after the component's timestep. `vorticity` computes
the CC field vorticity = curl(vel_CC) (second-order central differences over the interior cells,
0 in the extra cells), a task the graph keeps only when a deck saves "vorticity". `minMax` writes,
at its sampling times within [timeStart, timeStop], one line per analysed variable to
<uda>/MinMax/L-0/<label>_<matl>: "time min max" (Vectors componentwise, in brackets), over the
interior cells (CC), the patch's own nodes of the domain (NC) or the faces of interior cells (FC), in
Uintah's format. `lineExtract` writes
the values along axis-parallel lines, one file per cell (LineExtract); `controlVolFluxes` the mass
in boxes and the mass fluxes through their faces (ControlVolFluxes); `SGS_ReynoldsStress` the
CC tensor of ICE's face stresses tau_X_FC, ... (each row the mean of its two faces);
`turbulentFluxes` running means, variances and covariances with the velocity (TurbulentFluxes);
`firstLawThermo` the fluids' and solids' internal energy and the fluids' energy flux through the
domain's faces (FirstLawThermo); `statistics` running means, variances and higher moments of CC and
FC variables (Statistics); `planeAverage` plane averages written per sampled step (PlaneAverage,
whose PlaneSums planeAvgTurbFluxes shares).
"""
from __future__ import annotations

import os

import numpy as np
from numba import njit

from . import labels as L
from .task import NEW, OLD, Task
from .variables import Ghost, VarType

FACE_TYPES = (VarType.SFCX, VarType.SFCY, VarType.SFCZ)


@njit(cache=True)
def _add_heat_content(total, temp, mass, cp):
    """total + sum of T m cp over the particles, one after the other (Uintah's order)."""
    for i in range(mass.shape[0]):
        total += temp[i] * mass[i] * cp
    return total


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


@njit(cache=True)
def face_mean_row(t, out, a, lo, hi, sh):
    """out[c, a, :] = the mean of the face stresses t on cell c's two a-faces (Uintah's
    SGS_ReynoldsStress: tau_L + (tau_R - tau_L) / 2); sh: cell c's lower face is c - sh."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                f0, f1, f2 = i - sh[0], j - sh[1], k - sh[2]
                g0, g1, g2 = f0 + (a == 0), f1 + (a == 1), f2 + (a == 2)
                for b in range(3):
                    left = t[f0, f1, f2, b]
                    out[i, j, k, a, b] = left + (t[g0, g1, g2, b] - left) / 2.0


class SGS_ReynoldsStress:
    """Uintah's SGS_ReynoldsStress module: the viscous (with <turbulence>, molecular plus
    subgrid-scale) stress at the cell centres, row a the mean of tau_a_FC on the cell's a-faces."""

    def __init__(self, node, component, level):
        self.matl = _material(node, component)
        self.taus = [L.find(f"tau_{a}_FC") for a in "XYZ"]
        if self.taus[0] is None:
            raise node.error('<Module name="SGS_ReynoldsStress"> needs the face stresses tau_X_FC, ... of ICE '
                             "with a <dynamic_viscosity>")
        self.label = L.create("SGS_ReynoldsStress", VarType.CC, (3, 3))
        self.level = level
        self.dims = np.array([not c for c in level.collapsed], dtype=np.bool_)
        self.needed = set()

    def schedule(self, sched):
        t = Task("SGS_ReynoldsStress::doAnalysis", self.compute, [self.matl]).computes(self.label)
        for d in range(3):
            if self.dims[d]:
                t.requires(NEW, self.taus[d], Ghost.AROUND_CELLS, 1)
        sched.add_task(t)

    def compute(self, patch, matls, old_dw, new_dw):
        cc0 = np.array(patch.low_index(VarType.CC))
        lo, hi = (np.array(x, dtype=np.int64) for x in patch.interior(VarType.CC))
        for m in matls:
            out = new_dw.allocate(self.label, m, patch)
            out[...] = 0.0                      # rows of one-cell directions: no face stress
            for d in range(3):
                if self.dims[d]:
                    sh = (np.array(patch.low_index(FACE_TYPES[d])) - cc0).astype(np.int64)
                    face_mean_row(new_dw.get(self.taus[d], m, patch), out, d, lo, hi, sh)

    def after_step(self, dw, timestep, t, uda):
        pass


@njit(cache=True)
def running_means(q, vel, s1, s2, sv, m1, m2, mv, s1_old, s2_old, sv_old, n, vector):
    """Uintah's turbulentFluxes Q_mean over every cell of the arrays: the sums of Q, Q Q and
    Q u_i gain this step's values, the means are the sums over n. Q Q is componentwise for a
    Vector Q; Q u_i is (Q u, Q v, Q w) for a double and (Q.x v, Q.y w, Q.z u) for a Vector."""
    nx, ny, nz = vel.shape[0], vel.shape[1], vel.shape[2]
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                for c in range(q.shape[3]):
                    var = q[i, j, k, c]
                    s1[i, j, k, c] = var + s1_old[i, j, k, c]
                    m1[i, j, k, c] = s1[i, j, k, c] / n
                    s2[i, j, k, c] = var * var + s2_old[i, j, k, c]
                    m2[i, j, k, c] = s2[i, j, k, c] / n
                for c in range(3):
                    if vector:
                        qu = q[i, j, k, c] * vel[i, j, k, (c + 1) % 3]
                    else:
                        qu = q[i, j, k, 0] * vel[i, j, k, c]
                    sv[i, j, k, c] = qu + sv_old[i, j, k, c]
                    mv[i, j, k, c] = sv[i, j, k, c] / n


@njit(cache=True)
def turbulent_fluxes(m1, m2, mv, vel_mean, variance, covariance, vector):
    """Uintah's turbFluxes: variance = mean(Q Q) - mean(Q) mean(Q), covariance = mean(Q u_i) -
    mean(Q) mean(u_i) (with the pairing of running_means), every cell."""
    nx, ny, nz = vel_mean.shape[0], vel_mean.shape[1], vel_mean.shape[2]
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                for c in range(m1.shape[3]):
                    variance[i, j, k, c] = m2[i, j, k, c] - m1[i, j, k, c] * m1[i, j, k, c]
                for c in range(3):
                    if vector:
                        qu = m1[i, j, k, c] * vel_mean[i, j, k, (c + 1) % 3]
                    else:
                        qu = m1[i, j, k, 0] * vel_mean[i, j, k, c]
                    covariance[i, j, k, c] = mv[i, j, k, c] - qu


class TurbulentFluxes:
    """Uintah's turbulentFluxes module: running sums and means over the steps that start within
    [timeStart, timeStop] of each analysed CC variable Q (double or Vector), of Q Q and of Q
    times the fluid velocity, and from them variance_Q and covariance_Q. The sums are carried
    from step to step (in checkpoints too); outside the window every label keeps its value."""

    def __init__(self, node, component, level):
        matl = _material(node, component)
        self.start = node.get("timeStart", "float")
        self.stop = node.get("timeStop", "float")
        if self.start > self.stop:
            raise node.child("timeStop").error("timeStop is before timeStart; accepted: timeStart <= timeStop")
        if node.child("monitorCell") is not None:         # Uintah's debugging output only
            node.child("monitorCell").mark_used()
        self.vars, self.vel = [], None
        for a in node.child("Variables", required=True).children("analyze"):
            name = a.attr("label")
            label = L.find(name)
            if label is None or label.vartype is not VarType.CC or label.shape not in ((), (3,)):
                raise a.error(f'label="{name}" is not a cell-centred double or Vector of this deck; '
                              "accepted: a CC variable the component computes")
            m = a.attr("matl", "int", matl, at_least=0)
            q = {"label": label, "matl": m, "vector": label.shape == (3,)}
            for key, prefix, suffix, shape in (("s1", "sum_", "", label.shape), ("s2", "sum_", "2", label.shape),
                                               ("m1", "mean_", "", label.shape), ("m2", "mean_", "2", label.shape),
                                               ("sv", "sum_Qu_Qv_Qw_", "", (3,)), ("mv", "mean_Qu_Qv_Qw_", "", (3,)),
                                               ("var", "variance_", "", label.shape),
                                               ("cov", "covariance_", "", (3,))):
                q[key] = L.find(prefix + name + suffix) or L.create(prefix + name + suffix, VarType.CC, shape)
            if a.attr("fluidVelocityLabel", default=None) is not None:
                self.vel = q
            self.vars.append(q)
        if self.vel is None:
            raise node.child("Variables").error('no <analyze ... fluidVelocityLabel="true"/>: turbulentFluxes '
                                                "needs the fluid velocity among its variables")
        self.count = L.create("turbulentFluxes_nTimesteps", VarType.REDUCTION, reduction="max")
        self.keys = ("s1", "s2", "m1", "m2", "sv", "mv", "var", "cov")
        self.needed = {q[k].name for q in self.vars for k in self.keys} | {self.count.name}

    def _matls(self):
        return sorted({q["matl"] for q in self.vars})

    def schedule_initialize(self, sched):
        t = Task("turbulentFluxes::initialize", self.initialize, self._matls()).computes(self.count)
        for q in self.vars:
            for k in self.keys:
                t.computes(q[k], matls=[q["matl"]])
        sched.add_task(t)

    def initialize(self, patch, matls, old_dw, new_dw):
        for q in self.vars:
            if q["matl"] in matls:
                for k in self.keys:
                    new_dw.allocate(q[k], q["matl"], patch)[...] = 0.0
        new_dw.put_reduction(self.count, 0.0)

    def schedule(self, sched):
        t = Task("turbulentFluxes::task_Q_mean", self.q_mean, self._matls()) \
            .requires(OLD, L.simTime).requires(OLD, self.count).computes(self.count)
        t.requires(NEW, self.vel["label"], matls=[self.vel["matl"]])
        for q in self.vars:
            m = [q["matl"]]
            t.requires(NEW, q["label"], matls=m)
            for k in ("s1", "s2", "m1", "m2", "sv", "mv"):
                t.requires(OLD, q[k], matls=m).computes(q[k], matls=m)
        sched.add_task(t)
        t = Task("turbulentFluxes::task_turbFluxes", self.fluxes, self._matls()).requires(OLD, L.simTime)
        t.requires(NEW, self.vel["m1"], matls=[self.vel["matl"]])
        for q in self.vars:
            m = [q["matl"]]
            for k in ("m1", "m2", "mv"):
                t.requires(NEW, q[k], matls=m)
            for k in ("var", "cov"):
                t.requires(OLD, q[k], matls=m).computes(q[k], matls=m)
        sched.add_task(t)

    def _active(self, old_dw):
        now = old_dw.get_reduction(L.simTime)
        return self.start <= now <= self.stop

    def q_mean(self, patch, matls, old_dw, new_dw):
        n = old_dw.get_reduction(self.count)
        active = self._active(old_dw)
        if active:
            n += 1.0
        new_dw.put_reduction(self.count, n)
        vel = new_dw.get(self.vel["label"], self.vel["matl"], patch)
        for q in self.vars:
            m = q["matl"]
            if m not in matls:
                continue
            if not active:
                for k in ("s1", "s2", "m1", "m2", "sv", "mv"):
                    new_dw.put(q[k], m, patch, old_dw.get(q[k], m, patch).copy())
                continue
            v = lambda a: a.reshape(a.shape[:3] + (-1,))
            new = {k: new_dw.allocate(q[k], m, patch) for k in ("s1", "s2", "m1", "m2", "sv", "mv")}
            running_means(v(new_dw.get(q["label"], m, patch)), vel, v(new["s1"]), v(new["s2"]), new["sv"],
                          v(new["m1"]), v(new["m2"]), new["mv"], v(old_dw.get(q["s1"], m, patch)),
                          v(old_dw.get(q["s2"], m, patch)), old_dw.get(q["sv"], m, patch), n, q["vector"])

    def fluxes(self, patch, matls, old_dw, new_dw):
        active = self._active(old_dw)
        for q in self.vars:
            m = q["matl"]
            if m not in matls:
                continue
            if not active:
                for k in ("var", "cov"):
                    new_dw.put(q[k], m, patch, old_dw.get(q[k], m, patch).copy())
                continue
            v = lambda a: a.reshape(a.shape[:3] + (-1,))
            var, cov = new_dw.allocate(q["var"], m, patch), new_dw.allocate(q["cov"], m, patch)
            turbulent_fluxes(v(new_dw.get(q["m1"], m, patch)), v(new_dw.get(q["m2"], m, patch)),
                             new_dw.get(q["mv"], m, patch), new_dw.get(self.vel["m1"], self.vel["matl"], patch),
                             v(var), cov, q["vector"])

    def after_step(self, dw, timestep, t, uda):
        pass


@njit(cache=True)
def plane_sums(q, out, lo, hi, normal, inner, outer, g0):
    """Uintah's planeAverage planarSum_Q on one patch: out[plane] = the sum of q over the
    patch's interior cells of each plane normal to `normal` (global plane index = local + g0),
    the `inner` axis fastest, as Uintah iterates."""
    idx = np.zeros(3, dtype=np.int64)
    for p in range(lo[normal], hi[normal]):
        idx[normal] = p
        for c in range(q.shape[3]):
            total = 0.0
            for b in range(lo[outer], hi[outer]):
                idx[outer] = b
                for a in range(lo[inner], hi[inner]):
                    idx[inner] = a
                    total = total + q[idx[0], idx[1], idx[2], c]
            out[p + g0, c] = total


class PlaneSums:
    """The plane sums of Uintah's planeAverage, shared by the planeAverage and planeAvgTurbFluxes
    modules: planes normal to y for XZ (z for XY, x for YZ), each one's sum of a CC variable over
    the level's interior cells as a sum reduction (n_planes, components), and the files of plane
    averages in Uintah's format, one row per plane at the cell centre of the level's middle."""

    ORIENT = {"XY": (2, 0, 1), "XZ": (1, 0, 2), "YZ": (0, 1, 2)}       # normal, inner, outer axis
    DESC = {(): "ave", (3,): "ave.x__________________ave.y______________ave.z"}

    def __init__(self, node, level):
        self.level = level
        orient = node.get("planeOrientation", "str", choices=tuple(self.ORIENT))
        self.normal, self.inner, self.outer = self.ORIENT[orient]
        ncells = [n for d, n in enumerate(level.ncells) if d != self.normal]
        self.n_planes = level.ncells[self.normal]
        self.n_cells = int(ncells[0] * ncells[1])

    def reduction(self, name, lab):
        """A sum reduction holding the plane sums of the CC double or Vector lab."""
        return L.create(name, VarType.REDUCTION, (self.n_planes, 3 if lab.shape == (3,) else 1), reduction="sum")

    def bounds(self, patch):
        """The patch's interior cells (local lo, hi) and the global index of its local plane 0."""
        lo, hi = (np.array(x, dtype=np.int64) for x in patch.interior(VarType.CC))
        return lo, hi, int(patch.low_index(VarType.CC)[self.normal])

    def patch_sums(self, q, patch):
        """This patch's share of the plane sums of the CC array q (every plane, zero elsewhere)."""
        lo, hi, g0 = self.bounds(patch)
        q = q.reshape(q.shape[:3] + (-1,))
        out = np.zeros((self.n_planes, q.shape[3]))
        plane_sums(q, out, lo, hi, self.normal, self.inner, self.outer, g0)
        return out

    def write(self, path, t, desc, values, last, last_format):
        """One file of plane rows: the cell position, the values (n_planes, components), and the
        column `last` (per plane; None: none), in Uintah's planarVar printAverage format."""
        lv = self.level
        mid = [int(np.floor(n / 2.0 + 0.5)) for n in lv.ncells]        # Uintah's roundNearest(n / 2)
        sep = " " if values.shape[1] == 3 else "  "
        with open(path, "a") as f:
            f.write(self.header(t, desc, {"%i": "nCells", "%15.14E": "weight"}.get(last_format)))
            for p in range(self.n_planes):
                c = list(mid)
                c[self.normal] = p
                pos = lv.anchor + lv.dx * np.array(c) + lv.dx * 0.5     # Uintah's getCellPosition
                f.write("%15.14E  %15.14E  %15.14E " % tuple(pos))
                row = sep.join("%15.14E" % v for v in values[p])
                if last is not None:
                    row += sep + last_format % last[p]
                f.write(row + "\n")

    def header(self, t, desc, trailer):
        lv = self.level
        text = ("# Level: 0 nCells per plane: %i\n" % self.n_cells + "# Level spatial range:\n"
                + "# %15.14E  %15.14E  %15.14E \n" % tuple(lv.anchor + 0.0) + "# %15.14E  %15.14E  %15.14E \n" % tuple(lv.upper)
                + "# Level interior CC index range:  " + "# [0 0 0] [%i %i %i] \n" % tuple(lv.ncells)
                + "# Simulation time: %16.15E \n" % t + "# Plane location (x,y,z)           Average\n"
                + "# ________CC_loc.x__________CC_loc.y______________CC_loc.z______________%s" % desc)
        return text + ("______________%s\n" % trailer if trailer else "")


@njit(cache=True)
def plane_fluctuation(q, mean, out, lo, hi, normal, g0):
    """Q' = Q - Q_bar(plane) in the interior cells lo..hi (Uintah's calc_Q_prime)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                p = (i, j, k)[normal] + g0
                for c in range(q.shape[3]):
                    out[i, j, k, c] = q[i, j, k, c] - mean[p, c]


@njit(cache=True)
def turbulent_stresses(vp, qps, normal_out, shear_out, flux_out, lo, hi):
    """Uintah's calc_TurbFluxes in the interior cells: u'u', v'v', w'w' (normal), u'v', v'w', w'u'
    (shear) and each scalar's u'Q', v'Q', w'Q' (qps[n] the n-th scalar's Q')."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for c in range(3):
                    normal_out[i, j, k, c] = vp[i, j, k, c] * vp[i, j, k, c]
                    shear_out[i, j, k, c] = vp[i, j, k, c] * vp[i, j, k, (c + 1) % 3]
                for n in range(qps.shape[0]):
                    for c in range(3):
                        flux_out[n, i, j, k, c] = qps[n, i, j, k] * vp[i, j, k, c]


class PlaneAvgTurbFluxes:
    """Uintah's planeAvgTurbFluxes module: at its sampling times within [timeStart, timeStop]
    (the time at the step's end), the plane averages (planes normal to y for XZ, ...; weighting
    nCells) of the velocity and of each analysed CC double Q, the fluctuations vel_CC_prime and
    Q_prime about them, the stresses normalTurbStrss (u'u', v'v', w'w'), shearTurbStrss (u'v',
    v'w', w'u') and Q_turbFlux (u'Q', v'Q', w'Q'), and the plane averages of those; both sets of
    averages go to files in the uda (planarAveTurbFluxes/AvgQ and /TurbFluxes, t<step>/L-0/
    <label>_<matl>) in Uintah's format. Outside the sampling times the CC labels are 0."""

    def __init__(self, node, component, level):
        matl = _material(node, component)
        self.level = level
        self.freq = node.get("samplingFrequency", "float", above=0.0)
        self.start = node.get("timeStart", "float")
        self.stop = node.get("timeStop", "float")
        self.planes = PlaneSums(node, level)
        self.normal = self.planes.normal
        for tag in ("monitorCell", "weight"):          # debugging print; the weight of weighting="mass"
            if node.child(tag) is not None:
                node.child(tag).mark_used()
                node.child(tag).attr("label", default="")
        if node.child("enableVerification") is not None:
            raise node.child("enableVerification").error("<enableVerification> is not available; accepted: "
                                                         "the module without it")
        vn = node.child("velocity", required=True)
        self.vel = L.find(vn.attr("label"))
        if self.vel is None or self.vel.vartype is not VarType.CC or self.vel.shape != (3,):
            raise vn.error(f'label="{vn.attr("label")}" is not a cell-centred Vector of this deck')
        self.matl = matl
        self.avg = []           # stage 1: (label, matl) averaged; the velocity among them
        self.scalars = []       # (label, matl, prime, turbFlux)
        for a in node.child("Variables", required=True).children("analyze"):
            name = a.attr("label")
            label = L.find(name)
            w = a.attr("weighting", default="nCells", choices=("nCells",))
            del w
            m = a.attr("matl", "int", matl, at_least=0)
            if label is None or label.vartype is not VarType.CC or label.shape not in ((), (3,)):
                raise a.error(f'label="{name}" is not a cell-centred double or Vector of this deck')
            self.avg.append((label, m))
            if label is self.vel:
                continue
            if label.shape != ():
                raise a.error(f'label="{name}": only CC doubles besides the velocity are available')
            self.scalars.append((label, m, L.create(name + "_prime", VarType.CC),
                                 L.create(name + "_turbFlux", VarType.CC, (3,))))
        if not any(lab is self.vel for lab, _ in self.avg):
            self.avg.append((self.vel, matl))
        self.vel_prime = L.create(self.vel.name + "_prime", VarType.CC, (3,))
        self.normal_strss = L.create("normalTurbStrss", VarType.CC, (3,))
        self.shear_strss = L.create("shearTurbStrss", VarType.CC, (3,))
        self.n_cells = self.planes.n_cells
        mk = lambda lab, m, stage: self.planes.reduction(f"planeAvgTurbFluxes_sum{stage}_{lab.name}_{m}", lab)
        self.sums1 = [(lab, m, mk(lab, m, 1)) for lab, m in self.avg]
        stage2 = [(self.normal_strss, matl), (self.shear_strss, matl)] + [(f, m) for _, m, _, f in self.scalars]
        self.sums2 = [(lab, m, mk(lab, m, 2)) for lab, m in stage2]
        self.last = L.create("planeAvgTurbFluxes_lastCompTime", VarType.REDUCTION, reduction="max")
        self.needed = {self.last.name} | {r.name for _, _, r in self.sums1 + self.sums2}
        self.uda = None

    def _matls(self):
        return sorted({m for _, m in self.avg} | {self.matl})

    def schedule_initialize(self, sched):
        sched.add_task(Task("planeAvgTurbFluxes::initialize", self.initialize, [self.matl]).computes(self.last))

    def initialize(self, patch, matls, old_dw, new_dw):
        new_dw.put_reduction(self.last, self.start - 1.0 / self.freq)

    def _is_it_time(self, old_dw):
        """Uintah's AnalysisModule::getTimeVars: (time at the step's end, whether to sample)."""
        now = old_dw.get_reduction(L.simTime) + old_dw.get_reduction(L.delT)
        prev = old_dw.get_reduction(self.last)
        return now, not (now < self.start or now > self.stop or now < prev + 1.0 / self.freq)

    def schedule(self, sched):
        t = Task("planeAverage::computePlanarSums(1)", self._sums(self.sums1), self._matls()) \
            .requires(OLD, L.simTime).requires(OLD, L.delT).requires(OLD, self.last).computes(self.last)
        for lab, m, r in self.sums1:
            t.requires(NEW, lab, matls=[m]).computes(r)
        sched.add_task(t)
        t = Task("planeAvgTurbFluxes::calc_TurbFluctuations", self.fluctuations, self._matls()) \
            .requires(OLD, L.simTime).requires(OLD, L.delT).requires(OLD, self.last) \
            .computes(self.vel_prime, matls=[self.matl]).computes(self.normal_strss, matls=[self.matl]) \
            .computes(self.shear_strss, matls=[self.matl])
        for lab, m, r in self.sums1:
            t.requires(NEW, lab, matls=[m]).requires(NEW, r)
        for _, m, prime, flux in self.scalars:
            t.computes(prime, matls=[m]).computes(flux, matls=[m])
        sched.add_task(t)
        t = Task("planeAverage::computePlanarSums(2)", self._sums(self.sums2), self._matls()) \
            .requires(OLD, L.simTime).requires(OLD, L.delT).requires(OLD, self.last)
        for lab, m, r in self.sums2:
            t.requires(NEW, lab, matls=[m]).computes(r)
        sched.add_task(t)

    def _sums(self, sums):
        first = sums is self.sums1

        def task(patch, matls, old_dw, new_dw):
            now, active = self._is_it_time(old_dw)
            if first:
                new_dw.put_reduction(self.last, now if active else old_dw.get_reduction(self.last))
            for lab, m, r in sums:
                active_here = active and m in matls
                new_dw.put_reduction(r, self.planes.patch_sums(new_dw.get(lab, m, patch), patch)
                                     if active_here else np.zeros(r.shape))
        return task

    def fluctuations(self, patch, matls, old_dw, new_dw):
        _, active = self._is_it_time(old_dw)
        lo, hi, g0 = self.planes.bounds(patch)
        outs = {lab: new_dw.allocate(lab, self.matl, patch)
                for lab in (self.vel_prime, self.normal_strss, self.shear_strss)}
        primes = [new_dw.allocate(prime, m, patch) for _, m, prime, _ in self.scalars]
        fluxes = [new_dw.allocate(flux, m, patch) for _, m, _, flux in self.scalars]
        if not active:
            return
        for lab, m, r in self.sums1:
            if lab is self.vel:
                mean = new_dw.get_reduction(r) / float(self.n_cells)
                plane_fluctuation(new_dw.get(lab, m, patch), mean, outs[self.vel_prime], lo, hi, self.normal, g0)
        for (lab, m, prime, _), out in zip(self.scalars, primes):
            r = next(r for l2, m2, r in self.sums1 if l2 is lab and m2 == m)
            mean = new_dw.get_reduction(r) / float(self.n_cells)
            plane_fluctuation(new_dw.get(lab, m, patch)[..., None], mean, out[..., None], lo, hi, self.normal, g0)
        qps = np.stack(primes) if primes else np.zeros((0,) + outs[self.vel_prime].shape[:3])
        fl = np.zeros((len(fluxes),) + outs[self.vel_prime].shape)
        turbulent_stresses(outs[self.vel_prime], qps, outs[self.normal_strss], outs[self.shear_strss], fl, lo, hi)
        for n, f in enumerate(fluxes):
            f[...] = fl[n]

    def after_step(self, dw, timestep, t, uda):
        if uda is None or dw.get_reduction(self.last) != t:
            return
        desc2 = {self.normal_strss.name: "u'u'__________________v'v'______________w'w'",
                 self.shear_strss.name: "u'v'__________________v'w'______________w'u'"}
        ncells = np.full(self.planes.n_planes, self.n_cells)
        for folder, sums in (("AvgQ", self.sums1), ("TurbFluxes", self.sums2)):
            path = os.path.join(uda, "planarAveTurbFluxes", folder, f"t{timestep:05d}", "L-0")
            os.makedirs(path, exist_ok=True)
            for lab, m, r in sums:
                if folder == "TurbFluxes":
                    desc = desc2.get(lab.name, "u'Q'_________________v'Q'__________________w'Q'")
                else:
                    desc = PlaneSums.DESC[lab.shape]
                self.planes.write(os.path.join(path, f"{lab.name}_{m}"), t, desc,
                                  dw.get_reduction(r) / float(self.n_cells), ncells, "%i")


class PlaneAverage:
    """Uintah's planeAverage module: at its sampling times within [timeStart, timeStop] (the
    time at the step's end), the average over each plane (planeOrientation XY, XZ or YZ) of
    every analysed CC double or Vector: the plane's sum over its cells divided by its number of
    cells (weighting="nCells") or by the plane's sum of the <weight label> (weighting="mass"),
    or the sum itself (no weighting), written to <uda>/planeAverage/t<step>/L-0/<label>_<matl>
    in Uintah's format."""

    WEIGHTINGS = ("nCells", "mass")

    def __init__(self, node, component, level):
        matl = _material(node, component)
        self.level = level
        self.freq = node.get("samplingFrequency", "float", above=0.0)
        self.start = node.get("timeStart", "float")
        self.stop = node.get("timeStop", "float")
        self.planes = PlaneSums(node, level)
        wn = node.child("weight")
        weight_name = None
        if wn is not None:
            wn.mark_used()
            weight_name = wn.attr("label")
        self.vars = []          # (label, matl, weighting, sum reduction, weight-sum reduction or None)
        for a in node.child("Variables", required=True).children("analyze"):
            name = a.attr("label")
            label = L.find(name)
            if label is None or label.vartype is not VarType.CC or label.shape not in ((), (3,)):
                raise a.error(f'label="{name}" is not a cell-centred double or Vector of this deck; '
                              "accepted: a CC variable the component computes")
            if name == "press_CC" and a.attr("matl", default=None) is None:
                raise a.error('press_CC needs matl="0" (as Uintah\'s planeAverage)')
            m = a.attr("matl", "int", matl, at_least=0)
            weighting = a.attr("weighting", default=None, choices=self.WEIGHTINGS)
            wsum = None
            if weighting == "mass":
                weight = L.find(weight_name) if weight_name is not None else None
                if weight is None or weight.vartype is not VarType.CC or weight.shape != ():
                    where = wn if wn is not None else node
                    raise where.error(f'weighting="mass" of {name} needs <weight label="..."> naming a cell-centred '
                                      f"double of this deck (given: {weight_name}); accepted: weighting=\"nCells\" "
                                      "or a weight the component computes")
                wsum = (weight, self.planes.reduction(f"planeAverage_weight_{name}_{m}", weight))
            self.vars.append((label, m, weighting, self.planes.reduction(f"planeAverage_sum_{name}_{m}", label), wsum))
        self.last = L.create("lastCompTime_planeAvg", VarType.REDUCTION, reduction="max")
        self.needed = {self.last.name} | {v[3].name for v in self.vars} | {v[4][1].name for v in self.vars if v[4]}

    def schedule_initialize(self, sched):
        sched.add_task(Task("planeAverage::initialize", self.initialize, [self.vars[0][1] if self.vars else 0])
                       .computes(self.last))

    def initialize(self, patch, matls, old_dw, new_dw):
        new_dw.put_reduction(self.last, self.start - 1.0 / self.freq)

    def schedule(self, sched):
        t = Task("planeAverage::computePlanarSums", self.sums, sorted({v[1] for v in self.vars}) or [0]) \
            .requires(OLD, L.simTime).requires(OLD, L.delT).requires(OLD, self.last).computes(self.last)
        for lab, m, _, r, wsum in self.vars:
            t.requires(NEW, lab, matls=[m]).computes(r)
            if wsum is not None:
                t.requires(NEW, wsum[0], matls=[m]).computes(wsum[1])
        sched.add_task(t)

    def sums(self, patch, matls, old_dw, new_dw):
        """This patch's plane sums of each variable (and of its weight) at the sampling times."""
        now = old_dw.get_reduction(L.simTime) + old_dw.get_reduction(L.delT)
        prev = old_dw.get_reduction(self.last)
        active = not (now < self.start or now > self.stop or now < prev + 1.0 / self.freq)
        new_dw.put_reduction(self.last, now if active else prev)
        for lab, m, _, r, wsum in self.vars:
            here = active and m in matls
            new_dw.put_reduction(r, self.planes.patch_sums(new_dw.get(lab, m, patch), patch) if here
                                 else np.zeros(r.shape))
            if wsum is not None:
                new_dw.put_reduction(wsum[1], self.planes.patch_sums(new_dw.get(wsum[0], m, patch), patch) if here
                                     else np.zeros(wsum[1].shape))

    def after_step(self, dw, timestep, t, uda):
        if uda is None or dw.get_reduction(self.last) != t:
            return
        path = os.path.join(uda, "planeAverage", f"t{timestep:05d}", "L-0")
        os.makedirs(path, exist_ok=True)
        ncells = np.full(self.planes.n_planes, self.planes.n_cells)
        for lab, m, weighting, r, wsum in self.vars:
            total = dw.get_reduction(r)
            if weighting == "nCells":
                values, last, fmt = total / ncells[:, None].astype(np.float64), ncells, "%i"
            elif weighting == "mass":
                weight = dw.get_reduction(wsum[1])[:, 0]
                values, last, fmt = total / weight[:, None], weight, "%15.14E"
            else:
                values, last, fmt = total, None, None
            self.planes.write(os.path.join(path, f"{lab.name}_{m}"), t, PlaneSums.DESC[lab.shape], values, last, fmt)


@njit(cache=True)
def running_moments(q, old1, old2, s1, s2, m1, m2, var, n, lo, hi):
    """Uintah's statistics, first and second order, over the cells lo..hi: the sums of Q and
    Q Q gain this step's value, mean = sum / n, variance = mean(Q Q) - mean(Q)^2."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for c in range(q.shape[3]):
                    me = q[i, j, k, c]
                    s1[i, j, k, c] = me + old1[i, j, k, c]
                    m1[i, j, k, c] = s1[i, j, k, c] / n
                    s2[i, j, k, c] = me * me + old2[i, j, k, c]
                    m2[i, j, k, c] = s2[i, j, k, c] / n
                    var[i, j, k, c] = m2[i, j, k, c] - m1[i, j, k, c] * m1[i, j, k, c]


@njit(cache=True)
def higher_moments(q, m1, var, old3, old4, s3, s4, m3, m4, skew, kurt, n, lo, hi):
    """Uintah's statistics, third and fourth order (computeHigherOrderStats): the sums of Q^3
    and Q^4, their means, skewness = mean(Q^3) - Qbar^3 - 3 var Qbar and kurtosis = mean(Q^4)
    - Qbar^4 - 6 var Qbar^2 - 4 skewness Qbar (central moments, not normalised, as Uintah)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for c in range(q.shape[3]):
                    me = q[i, j, k, c]
                    me2 = me * me
                    qbar = m1[i, j, k, c]
                    qbar2 = qbar * qbar
                    s3[i, j, k, c] = me * me2 + old3[i, j, k, c]
                    m3[i, j, k, c] = s3[i, j, k, c] / n
                    skew[i, j, k, c] = m3[i, j, k, c] - qbar * qbar2 - 3.0 * var[i, j, k, c] * qbar
                    s4[i, j, k, c] = me2 * me2 + old4[i, j, k, c]
                    m4[i, j, k, c] = s4[i, j, k, c] / n
                    kurt[i, j, k, c] = (m4[i, j, k, c] - qbar2 * qbar2 - 6.0 * var[i, j, k, c] * qbar2
                                        - 4.0 * skew[i, j, k, c] * qbar)


@njit(cache=True)
def reynolds_products(vel, vel_mean, old, s, mean, prime, n, lo, hi):
    """Uintah's statistics computeReynoldsStress: the sum and mean of (u v, v w, w u) and
    uv_vw_wu_prime = mean(u v) - mean(u) mean(v), ... over the cells lo..hi."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for c in range(3):
                    d = (c + 1) % 3
                    s[i, j, k, c] = vel[i, j, k, c] * vel[i, j, k, d] + old[i, j, k, c]
                    mean[i, j, k, c] = s[i, j, k, c] / n
                    prime[i, j, k, c] = mean[i, j, k, c] - vel_mean[i, j, k, c] * vel_mean[i, j, k, d]


class Statistics:
    """Uintah's statistics module: for each analysed CC or FC double or Vector Q, over the steps
    that start within [timeStart, timeStop], the running sums sum_Q, sum2_Q and the means mean_Q,
    mean2_Q and variance_Q; with <computeHigherOrderStats> also sum3_, sum4_, mean3_, mean4_,
    skewness_ and kurtosis_; an analysed Vector with computeReynoldsStress="true" adds
    sum_uv_vw_wu, mean_uv_vw_wu and uv_vw_wu_prime. Every cell of the patch (extra cells
    included). The sums and the step count are carried from step to step (in checkpoints too);
    outside the window the sums keep their values and the statistics are 0."""

    LOW = ("s1", "s2", "m1", "m2", "var")
    HIGH = ("s3", "s4", "m3", "m4", "skew", "kurt")
    NAMES = {"s1": "sum_", "s2": "sum2_", "m1": "mean_", "m2": "mean2_", "var": "variance_", "s3": "sum3_",
             "s4": "sum4_", "m3": "mean3_", "m4": "mean4_", "skew": "skewness_", "kurt": "kurtosis_"}
    SUMS = ("s1", "s2", "s3", "s4")

    def __init__(self, node, component, level):
        matl = _material(node, component)
        self.start = node.get("timeStart", "float")
        self.stop = node.get("timeStop", "float")
        if self.start > self.stop:
            raise node.child("timeStop").error("timeStop is before timeStart; accepted: timeStart <= timeStop")
        for tag in ("monitorCell", "samplingFrequency"):        # a debugging print; not read by Uintah's module
            if node.child(tag) is not None:
                node.child(tag).mark_used()
        self.higher = node.get("computeHigherOrderStats", "bool", False)
        self.keys = self.LOW + (self.HIGH if self.higher else ())
        self.vars, self.rs = [], None
        for a in node.child("Variables", required=True).children("analyze"):
            name = a.attr("label")
            label = L.find(name)
            if label is None or label.vartype not in (VarType.CC,) + FACE_TYPES or label.shape not in ((), (3,)):
                raise a.error(f'label="{name}" is not a cell- or face-centred double or Vector of this deck; '
                              "accepted: a CC or FC variable the component computes")
            q = {"label": label, "matl": a.attr("matl", "int", matl, at_least=0)}
            for k in self.keys:
                q[k] = L.create(self.NAMES[k] + name, label.vartype, label.shape)
            if a.attr("computeReynoldsStress", "bool", False):
                if label.shape != (3,) or label.vartype is not VarType.CC:
                    raise a.error(f'computeReynoldsStress on {name}; accepted: a cell-centred Vector (the velocity)')
                if self.rs is not None:
                    raise a.error("computeReynoldsStress given twice; accepted: on one variable")
                self.rs = q
                q.update({k: L.create(n, VarType.CC, (3,)) for k, n in
                          (("rs_sum", "sum_uv_vw_wu"), ("rs_mean", "mean_uv_vw_wu"), ("rs_prime", "uv_vw_wu_prime"))})
            self.vars.append(q)
        self.count = L.create("statistics_nTimesteps", VarType.REDUCTION, reduction="max")
        self.needed = {q[k].name for q in self.vars for k in self.keys if k in self.SUMS} | {self.count.name}
        if self.rs is not None:
            self.needed.add(self.rs["rs_sum"].name)

    def _sums(self, q):
        return [k for k in self.keys if k in self.SUMS] + (["rs_sum"] if q is self.rs else [])

    def _matls(self):
        return sorted({q["matl"] for q in self.vars}) or [0]

    def schedule_initialize(self, sched):
        t = Task("statistics::initialize", self.initialize, self._matls()).computes(self.count)
        for q in self.vars:
            for k in self._sums(q):
                t.computes(q[k], matls=[q["matl"]])
        sched.add_task(t)

    def initialize(self, patch, matls, old_dw, new_dw):
        for q in self.vars:
            if q["matl"] in matls:
                for k in self._sums(q):
                    new_dw.allocate(q[k], q["matl"], patch)[...] = 0.0
        new_dw.put_reduction(self.count, 0.0)

    def schedule(self, sched):
        t = Task("statistics::doAnalysis", self.analyse, self._matls()) \
            .requires(OLD, L.simTime).requires(OLD, self.count).computes(self.count)
        for q in self.vars:
            m = [q["matl"]]
            t.requires(NEW, q["label"], matls=m)
            for k in self._sums(q):
                t.requires(OLD, q[k], matls=m)
            for k in self.keys + (("rs_sum", "rs_mean", "rs_prime") if q is self.rs else ()):
                t.computes(q[k], matls=m)
        sched.add_task(t)

    def analyse(self, patch, matls, old_dw, new_dw):
        now = old_dw.get_reduction(L.simTime)
        active = self.start <= now <= self.stop
        n = old_dw.get_reduction(self.count) + (1.0 if active else 0.0)
        new_dw.put_reduction(self.count, n)
        for q in self.vars:
            m = q["matl"]
            if m not in matls:
                continue
            if not active:
                for k in self.keys + (("rs_sum", "rs_mean", "rs_prime") if q is self.rs else ()):
                    if k in self._sums(q):
                        new_dw.put(q[k], m, patch, old_dw.get(q[k], m, patch).copy())
                    else:
                        new_dw.allocate(q[k], m, patch)[...] = 0.0
                continue
            v = lambda a: a.reshape(a.shape[:3] + (-1,))
            vt = q["label"].vartype
            lo, hi = (np.array(x, dtype=np.int64) for x in patch.owned_local(vt))
            new = {k: new_dw.allocate(q[k], m, patch) for k in self.keys}
            old = {k: old_dw.get(q[k], m, patch) for k in self._sums(q)}
            val = new_dw.get(q["label"], m, patch)
            running_moments(v(val), v(old["s1"]), v(old["s2"]), v(new["s1"]), v(new["s2"]), v(new["m1"]),
                            v(new["m2"]), v(new["var"]), n, lo, hi)
            if self.higher:
                higher_moments(v(val), v(new["m1"]), v(new["var"]), v(old["s3"]), v(old["s4"]), v(new["s3"]),
                               v(new["s4"]), v(new["m3"]), v(new["m4"]), v(new["skew"]), v(new["kurt"]), n, lo, hi)
            if q is self.rs:
                rs = {k: new_dw.allocate(q[k], m, patch) for k in ("rs_sum", "rs_mean", "rs_prime")}
                reynolds_products(val, new["m1"], old["rs_sum"], rs["rs_sum"], rs["rs_mean"], rs["rs_prime"], n,
                                  lo, hi)

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
            if label is None or label.vartype not in (VarType.CC, VarType.NC) + FACE_TYPES or \
                    label.shape not in ((), (3,)):
                raise a.error(f'label="{name}" is not a cell-, node- or face-centred double or Vector of this '
                              "deck; accepted: a CC, NC or FC variable the component computes")
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
                lo, hi = patch.interior(label.vartype if label.vartype == VarType.NC else VarType.CC)
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


def abbreviate(name, max_len):
    """Uintah's AnalysisModule::abbreviateName: snake_case to camelCase, then the middle cut
    out (not splitting at a capital) when still max_len or longer."""
    out = name
    if len(out) >= max_len:
        parts = out.split("_")
        out = parts[0] + "".join(p[:1].upper() + p[1:] for p in parts[1:])
    if len(out) >= max_len:
        cut = len(out) - max_len
        start = len(out) // 2 - cut // 2
        if out[start - 1].isupper():
            start -= 1
        if out[start + cut - 1].isupper():
            start -= 1
        out = out[:start] + out[start + cut:]
    return out


class LineExtract:
    """Uintah's lineExtract module: at its sampling times the values of CC and FC variables in
    the cells of axis-parallel lines, one file per cell <uda>/<line>/L-0/i<i>_j<j>_k<k> with
    the rows "x y z timestep time values...", in Uintah's format (16-wide %E columns). Each
    rank writes the cells of its own patches (extra cells included) during the step."""

    WIDTH = 16
    ORDER = (VarType.CC, VarType.NC, VarType.SFCX, VarType.SFCY, VarType.SFCZ)   # Uintah's column order

    def __init__(self, node, component, level):
        matl = _material(node, component)
        self.level = level
        self.freq = node.get("samplingFrequency", above=0.0)
        self.start = node.get("timeStart")
        self.stop = node.get("timeStop")
        if self.start > self.stop:
            raise node.child("timeStart").error("timeStart is after timeStop; accepted: timeStart <= timeStop")
        self.prev = self.start - 1.0 / self.freq
        self.uda = None                 # set by the controller once the archive exists
        self.vars = []
        for a in node.child("Variables", required=True).children("analyze"):
            name = a.attr("label")
            label = L.find(name)
            if label is None or label.vartype not in (VarType.CC, VarType.NC) + FACE_TYPES or \
                    label.shape not in ((), (3,)):
                raise a.error(f'label="{name}" is not a cell-, node- or face-centred double or Vector of this '
                              "deck; accepted: a grid variable the component computes")
            if name == "press_CC" and a.attr("matl", default=None) is None:
                raise a.error('press_CC needs matl="0" (as Uintah\'s lineExtract)')
            self.vars.append((label, a.attr("matl", "int", matl, at_least=0)))
        kinds = {lab.vartype for lab, _ in self.vars}
        self.common = kinds.pop() if len(kinds) == 1 else None
        self.lines = []
        for ln in node.child("lines", required=True).children("line"):
            name = ln.attr("name")
            p0 = np.array(ln.get("startingPt", "vector"), dtype=np.float64)
            p1 = np.array(ln.get("endingPt", "vector"), dtype=np.float64)
            step = ln.get("stepSize", "float", 0.0, at_least=0.0)
            moving = [d for d in range(3) if p0[d] != p1[d]]
            if len(moving) != 1:
                raise ln.error("a line must be parallel to one coordinate axis; accepted: startingPt and "
                               "endingPt differing in one coordinate")
            lo, hi = level.anchor, level.upper
            if np.any(p0 < lo - 1e-12 * abs(hi - lo)) or np.any(p1 > hi + 1e-12 * abs(hi - lo)) \
                    or p0[moving[0]] > p1[moving[0]]:
                raise ln.error(f"the line from {p0.tolist()} to {p1.tolist()} is not inside the domain "
                               f"{lo.tolist()} - {hi.tolist()} from low to high")
            d = moving[0]
            self.lines.append((name, p0, p1, d, max(int(np.ceil(step / level.dx[d])), 1)))
        self.done = {}
        # the time of the last write, as Uintah's lastWriteTime: the task's output, which keeps it in the graph
        self.last_write = L.create(f"lastWriteTime_lineExtract{id(self)}", VarType.REDUCTION, reduction="max")
        self.needed = {self.last_write.name}

    def schedule(self, sched):
        t = Task("lineExtract::doAnalysis", self.write, sorted({m for _, m in self.vars})) \
            .requires(OLD, L.simTime).requires(OLD, L.delT).computes(self.last_write)
        for label, m in self.vars:
            t.requires(NEW, label, matls=[m])
        sched.add_task(t)

    def _offset(self):
        half = 0.5 * np.asarray(self.level.dx)
        if self.common in FACE_TYPES:
            half[FACE_TYPES.index(self.common)] = 0.0
        elif self.common is VarType.NC:
            half[:] = 0.0
        return half

    def _due(self, now):
        """Uintah's getTimeVars, decided once per step (every patch of it sees the same now)."""
        if now not in self.done:
            due = self.start <= now <= self.stop and now >= self.prev + 1.0 / self.freq
            if due:
                self.prev = now
            self.done = {now: due}
        return self.done[now]

    def write(self, patch, matls, old_dw, new_dw):
        now = old_dw.get_reduction(L.simTime) + old_dw.get_reduction(L.delT)
        due = self._due(now)
        new_dw.put_reduction(self.last_write, self.prev)
        if not due or self.uda is None:
            return
        lv = self.level
        olo, ohi = (np.array(x) for x in patch.owned_local(VarType.CC))
        c0 = np.array(patch.low_index(VarType.CC))
        elo, ehi = olo + c0, ohi + c0               # this patch's cells, extra cells included
        offset = self._offset()
        arrays = [(lab, new_dw.get(lab, m, patch), np.array(patch.low_index(lab.vartype))) for lab, m in self.vars]
        for name, p0, p1, d, step in self.lines:
            folder = os.path.join(self.uda, name, "L-0")
            os.makedirs(folder, exist_ok=True)
            box_lo = lv.anchor + elo * lv.dx
            box_hi = lv.anchor + ehi * lv.dx
            a, b = np.maximum(box_lo, p0), np.minimum(box_hi, p1)
            if np.any(a > b):
                continue
            i0 = np.floor((a - lv.anchor) / lv.dx).astype(np.int64)
            i1 = np.floor((b - lv.anchor) / lv.dx).astype(np.int64)
            for n in range(i0[d], i1[d], step):
                c = i0.copy()
                c[d] = n
                if np.any(c < elo) or np.any(c >= ehi):
                    continue
                self._write_row(folder, c, new_dw.dw.generation, now, lv.anchor + c * lv.dx + offset, arrays)

    def _write_row(self, folder, c, timestep, now, here, arrays):
        w = self.WIDTH
        path = os.path.join(folder, f"i{c[0]}_j{c[1]}_k{c[2]}")
        if not os.path.exists(path):
            with open(path, "w") as f:
                f.write(self._header())
        row = f"{here[0]:<{w}E} {here[1]:<{w}E} {here[2]:<{w}E} {timestep:<{w}d} {now:<{w}E}"
        for vt in self.ORDER:
            for want_vector in (False, True):
                for lab, arr, low in arrays:
                    if lab.vartype is not vt or (lab.shape == (3,)) != want_vector:
                        continue
                    v = arr[tuple(c - low)]
                    row += f"{v[0]:<{w}E} {v[1]:<{w}E} {v[2]:<{w}E}" if want_vector else f"{float(v):<{w}E}"
        with open(path, "a") as f:
            f.write(row + "\n")

    def _header(self):
        w = self.WIDTH
        tags = {VarType.CC: "CC", VarType.NC: "NC", VarType.SFCX: "SFCX", VarType.SFCY: "SFCY",
                VarType.SFCZ: "SFCZ"}
        text = ""
        loc = tags.get(self.common, "CC")
        if self.common is None:
            dx = self.level.dx
            text += ("# WARNING:  not all variables are at the cell center, you'll need apply an offset to them\n"
                     f"# dx: [{dx[0]:g}, {dx[1]:g}, {dx[2]:g}]\n")
        text += f"{'# X_' + loc:<{w}} {'Y_' + loc:<{w}} {'Z_' + loc:<{w}} {'Timestep':<{w}} {'Time [s]':<{w}}"
        for vt in self.ORDER:
            for lab, m in self.vars:
                if lab.vartype is vt and lab.shape == ():
                    text += f"{abbreviate(lab.name, w - 3) + '_' + str(m):<{w}}"
            for lab, m in self.vars:
                if lab.vartype is vt and lab.shape == (3,):
                    base = abbreviate(lab.name, w - 4) + "_" + str(m)
                    text += " ".join(f"{base + s:<{w}}" for s in (".x", ".y", ".z"))
        return text + "\n"

    def after_step(self, dw, timestep, t, uda):
        pass


@njit(cache=True)
def mass_in_cells(rho, lo, hi, vol):
    """sum rho V over the cells lo..hi."""
    total = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                total += rho[i, j, k] * vol
    return total


@njit(cache=True)
def mass_flux_faces(vel_fc, rho, d, flo, fhi, sh, area):
    """sum u_f rho_upwind A over the faces flo..fhi of direction d (face f below cell f + sh;
    upwind: the cell below where u_f > 0), Uintah's controlVolFluxes::integrate_Q_overFace."""
    q = 0.0
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            for k in range(flo[2], fhi[2]):
                u = vel_fc[i, j, k]
                c0, c1, c2 = i + sh[0], j + sh[1], k + sh[2]
                if u > 0.0:
                    if d == 0:
                        c0 -= 1
                    elif d == 1:
                        c1 -= 1
                    else:
                        c2 -= 1
                q += u * rho[c0, c1, c2] * area
    return q


class ControlVolFluxes:
    """Uintah's controlVolFluxes module: for each <box> control volume, the mass it holds and
    the mass fluxes through its six faces (face velocity times the upwind density times the
    face area), written at the sampling times to <uda>/<label>.dat in Uintah's format."""

    WIDTH, PRECISION = 18, 12
    FACES = ("x-", "x+", "y-", "y+", "z-", "z+")

    def __init__(self, node, component, level):
        self.matl = _material(node, component)
        self.level = level
        self.freq = node.get("samplingFrequency", above=0.0)
        self.start = node.get("timeStart")
        self.stop = node.get("timeStop")
        self.prev = self.start - 1.0 / self.freq
        self.cvs = []
        for box in node.child("controlVolumes", required=True).children("box"):
            name = box.attr("label")
            lo = np.array(box.get("min", "vector"), dtype=np.float64)
            hi = np.array(box.get("max", "vector"), dtype=np.float64)
            if np.any(np.abs(hi - lo) < 10 * np.finfo(float).tiny):
                raise box.error(f"box '{name}': max must differ from min in every direction")
            lo, hi = np.maximum(level.anchor, lo), np.minimum(level.upper, hi)      # clipped to the domain
            ilo = np.floor((lo - level.anchor) / level.dx + 0.5).astype(np.int64)
            ihi = np.floor((hi - level.anchor) / level.dx + 0.5).astype(np.int64)
            if np.any(ihi - ilo < 1):
                raise box.error(f"box '{name}' holds no cell in some direction; accepted: at least one cell "
                                "between min and max")
            labels = [L.create(f"{name}_controlVolFluxes{id(self)}_{tag}", VarType.REDUCTION, reduction="sum")
                      for tag in ("total",) + self.FACES]
            self.cvs.append((name, lo, hi, ilo, ihi, labels))
        self.needed = {lab.name for cv in self.cvs for lab in cv[5]}

    def schedule(self, sched):
        t = Task("controlVolFluxes::integrate_Q_overCV", self.integrate, [self.matl]) \
            .requires(NEW, L.find("rho_CC"), Ghost.AROUND_CELLS, 1)
        for d, name in enumerate(("uvel_FCME", "vvel_FCME", "wvel_FCME")):
            if not self.level.collapsed[d]:
                t.requires(NEW, L.find(name))
        for cv in self.cvs:
            for lab in cv[5]:
                t.computes(lab)
        sched.add_task(t)

    def integrate(self, patch, matls, old_dw, new_dw):
        m = self.matl
        lv = self.level
        rho = new_dw.get(L.find("rho_CC"), m, patch)
        c0 = np.array(patch.low_index(VarType.CC))
        olo, ohi = (np.array(x) for x in patch.owned_local(VarType.CC))
        elo, ehi = olo + c0, ohi + c0                       # the patch's cells, extra cells included
        plo, phi = np.array(patch.lo), np.array(patch.hi)
        vol = float(np.prod(lv.dx))
        for name, lo, hi, ilo, ihi, labels in self.cvs:
            a, b = np.maximum(ilo, plo), np.minimum(ihi, phi)
            total = mass_in_cells(rho, a - c0, b - c0, vol) if np.all(b > a) else 0.0
            new_dw.put_reduction(labels[0], total)
            for f in range(6):
                d, plus = f // 2, f % 2
                q = 0.0
                face = ihi[d] if plus else ilo[d]
                if not lv.collapsed[d] and elo[d] <= face < ehi[d]:
                    a, b = np.maximum(ilo, elo), np.minimum(ihi, ehi)       # along the face: the CV's cells here
                    a[d], b[d] = face, face + 1
                    if np.all(b > a):
                        vt = FACE_TYPES[d]
                        f0 = np.array(patch.low_index(vt))
                        area = vol / lv.dx[d]
                        q = mass_flux_faces(new_dw.get(L.find(("uvel_FCME", "vvel_FCME", "wvel_FCME")[d]), m, patch),
                                            rho, d, a - f0, b - f0, f0 - c0, area)
                new_dw.put_reduction(labels[1 + f], q)

    def after_step(self, dw, timestep, t, uda):
        if t < self.start or t > self.stop or t < self.prev + 1.0 / self.freq:
            return
        self.prev = t
        if uda is None:
            return
        w, p = self.WIDTH, self.PRECISION
        for name, lo, hi, ilo, ihi, labels in self.cvs:
            path = os.path.join(uda, f"{name}.dat")
            vals = [float(dw.get_reduction(lab)) for lab in labels]
            with open(path, "a") as f:
                if f.tell() == 0:
                    f.write(self._header(name, lo, hi, ilo, ihi))
                q = vals[1:]
                row = [t, vals[0], q[0] - q[1], q[2] - q[3], q[4] - q[5]] + q
                f.write(" ".join(f"{v:<{w}.{p}E}" for v in row) + " \n")

    def _header(self, name, lo, hi, ilo, ihi):
        w = self.WIDTH
        pt = lambda x: "[" + " ".join(f"{v:.4e}" for v in x) + "]"                  # Uintah's Point
        iv = lambda x: "[int " + ", ".join(str(int(v)) for v in x) + "]"             # and IntVector
        text = (f"#  controlVolume ({name}) box lower: {pt(lo)} upper: {pt(hi)}, lowIndex: {iv(ilo)}, "
                f"highIndex: {iv(ihi)} \n")
        text += " ".join(f"{c:<{w}}" for c in ("# ", "ControlVol", "Net face fluxes", " ", " ", "Face fluxes")) + "\n"
        text += " ".join(f"{c:<{w}}" for c in ("#Time [s]", "Total", "X faces", "Y faces", "Z faces"))
        text += " " + " ".join(f"{c:<{w}}" for c in self.FACES) + "\n"
        return text


@njit(cache=True)
def internal_energy_sum(rho, temp, cv, vol, lo, hi):
    """sum rho V cv T over the cells [lo, hi) (x fastest, as Uintah's CellIterator)."""
    total = 0.0
    for k in range(lo[2], hi[2]):
        for j in range(lo[1], hi[1]):
            for i in range(lo[0], hi[0]):
                total += rho[i, j, k] * vol * cv * temp[i, j, k]
    return total


@njit(cache=True)
def enthalpy_flux_faces(uf, rho, temp, cv, gamma, conv, d, sign, lo, hi, shift, area):
    """Uintah's 1stLawThermo face sum over the faces [lo, hi) of a face array (local indices):
    mdot (h + conv u^2/2) with mdot = sign u A (rho_c + rho_cc)/2 and h = (T_c + T_cc) gamma cv / 2,
    c the cell whose low face it is (CC index = face index + shift), cc the cell below."""
    total = 0.0
    for k in range(lo[2], hi[2]):
        for j in range(lo[1], hi[1]):
            for i in range(lo[0], hi[0]):
                c0, c1, c2 = i + shift[0], j + shift[1], k + shift[2]
                b0, b1, b2 = c0 - (d == 0), c1 - (d == 1), c2 - (d == 2)
                vel = uf[i, j, k]
                mdot = sign * vel * area * (rho[c0, c1, c2] + rho[b0, b1, b2]) / 2.0
                ke = 0.5 * vel * vel
                h = (temp[c0, c1, c2] * gamma * cv + temp[b0, b1, b2] * gamma * cv) / 2.0
                total += mdot * (h + ke * conv)
    return total


class FirstLawThermo:
    """Uintah's firstLawThermo module (1stLawThermo.cc): at its sampling times, the fluids'
    internal energy sum rho V cv T (interior cells, ICE materials), the solids' sum m cp T over
    the particles (MPM materials' <specific_heat>; 0 without MPM), their total, and the fluids'
    energy flux through the control volume's faces, sum mdot (h + conv u^2/2) over the boundary
    faces (h = gamma cv T and rho averaged over the two cells, u the face velocity uvel_FCME ...,
    conv = <engy_convt_factor>, default 1/1000), written to <uda>/1stLawThermo.dat in Uintah's
    format. <controlVolume> lists each domain face, extents="entireFace" or "partialFace" with
    <startPt>, <endPt> on the face: its cells between the two points' cells (Uintah's: on a
    minus face it reads one layer outside the domain; here the boundary faces, as on a plus face)."""

    SIDES = ("x-", "x+", "y-", "y+", "z-", "z+")

    def __init__(self, node, component, level):
        self.level = level
        self.freq = node.get("samplingFrequency", above=0.0)
        self.start = node.get("timeStart")
        self.stop = node.get("timeStop")
        self.conv = node.get("engy_convt_factor", "float", 1.0 / 1000.0)
        self.prev = self.start - 1.0 / self.freq
        self.ice = getattr(component, "ice", component)
        if not hasattr(self.ice, "gammas"):
            raise node.error('<Module name="firstLawThermo"> needs ICE materials (their energy and fluxes); '
                             "accepted with MPMICE (and ICE)")
        self.fluids = list(getattr(self.ice, "ice_matls", self.ice.matls))
        self.mpm = mpm = getattr(component, "mpm", None)
        self.solid_temp = getattr(component, "solid_temp", {})
        self.solids = [] if mpm is None else [(m, mat.specific_heat) for m, mat in enumerate(mpm.materials)]
        cvn = node.child("controlVolume", required=True)
        self.faces = {}
        for face in cvn.children("Face"):
            side = face.attr("side", choices=self.SIDES)
            if side in self.faces:
                raise face.error(f'<Face side="{side}"> given twice; accepted: one per side')
            extents = face.attr("extents", choices=("entireFace", "partialFace"))
            self.faces[side] = None if extents == "entireFace" else self._partial(face, side)
        for f, side in enumerate(self.SIDES):
            d = f // 2
            if not (level.collapsed[d] or level.periodic[d]) and side not in self.faces:
                raise cvn.error(f'no <Face side="{side}">; accepted: every face of the domain, '
                                'extents="entireFace" or "partialFace"')
        self.labels = [L.create(name, VarType.REDUCTION, reduction="sum")
                       for name in ("ICE_totalIntEng", "MPM_totalIntEng", "totalFluxes")]
        self.needed = {lab.name for lab in self.labels}

    def _partial(self, face, side):
        """The global cell-index box [lo, hi) of a partialFace (Uintah's getCellIndex of the points)."""
        lv = self.level
        d, plus = self.SIDES.index(side) // 2, self.SIDES.index(side) % 2
        start = np.array(face.get("startPt", "vector"))
        end = np.array(face.get("endPt", "vector"))
        plane = (lv.upper if plus else lv.anchor)[d]
        if start[d] != plane:
            raise face.child("startPt").error(f"the plane of face {side} from {tuple(start)} to {tuple(end)} is not at "
                                              f"the edge of the computational domain ({'xyz'[d]} = {plane:g})")
        lo = np.floor((start - lv.anchor) / lv.dx).astype(np.int64)
        hi = np.floor((end - lv.anchor) / lv.dx).astype(np.int64)
        lo[d], hi[d] = (lv.ncells[d], lv.ncells[d] + 1) if plus else (0, 1)
        return lo, hi

    def schedule(self, sched):
        rho, temp = L.find("rho_CC"), L.find("temp_CC")
        t = Task("FirstLawThermo::compute_ICE_Contributions", self.fluid_sums, self.fluids) \
            .requires(NEW, rho).requires(NEW, temp).computes(self.labels[0]).computes(self.labels[2])
        for d, name in enumerate(("uvel_FCME", "vvel_FCME", "wvel_FCME")):
            if not self.level.collapsed[d]:
                t.requires(NEW, L.find(name))
        sched.add_task(t)
        t = Task("FirstLawThermo::compute_MPM_Contributions", self.solid_sums, [m for m, _ in self.solids] or [0]) \
            .computes(self.labels[1])
        if self.solids:
            t.requires(NEW, L.find("p.mass+"))
            if self.mpm.thermal:
                t.requires(NEW, L.find("p.temperature+"))
        sched.add_task(t)

    def fluid_sums(self, patch, matls, old_dw, new_dw):
        lv = self.level
        vol = float(np.prod(lv.dx))
        c0 = np.array(patch.low_index(VarType.CC))
        lo, hi = (np.array(x, np.int64) for x in patch.interior(VarType.CC))
        elo = np.array(patch.owned_local(VarType.CC)[0]) + c0            # the patch's cells, extra included
        ehi = np.array(patch.owned_local(VarType.CC)[1]) + c0
        energy = flux = 0.0
        for m in self.fluids:
            rho, temp = new_dw.get(L.find("rho_CC"), m, patch), new_dw.get(L.find("temp_CC"), m, patch)
            cv, gamma = float(self.ice.cvs[m]), float(self.ice.gammas[m])
            energy += internal_energy_sum(rho, temp, cv, vol, lo, hi)
            for name in patch.boundary_faces:
                f = self.SIDES.index(name)
                d, plus = f // 2, f % 2
                vt = FACE_TYPES[d]
                f0 = np.array(patch.low_index(vt))
                a, b = np.array(patch.lo), np.array(patch.hi)           # faces of the patch's interior cells
                a[d] = b[d] = (lv.ncells[d] if plus else 0)
                b[d] += 1
                part = self.faces[name]
                if part is not None:
                    a, b = np.maximum(part[0], elo), np.minimum(part[1], ehi)
                    a[d], b[d] = part[0][d], part[1][d]
                if np.any(b <= a):
                    continue
                uf = new_dw.get(L.find(("uvel_FCME", "vvel_FCME", "wvel_FCME")[d]), m, patch)
                flux += enthalpy_flux_faces(uf, rho, temp, cv, gamma, self.conv, d, 1.0 if plus else -1.0,
                                            a - f0, b - f0, f0 - c0, vol / lv.dx[d])
        new_dw.put_reduction(self.labels[0], energy)
        new_dw.put_reduction(self.labels[2], flux)

    def solid_sums(self, patch, matls, old_dw, new_dw):
        total = 0.0
        for m, cp in self.solids:
            mass = new_dw.get(L.find("p.mass+"), m, patch)
            if self.mpm.thermal:
                temp = new_dw.get(L.find("p.temperature+"), m, patch)
            else:
                temp = np.full(len(mass), float(self.solid_temp[m]))
            total = _add_heat_content(total, temp, mass, cp)
        new_dw.put_reduction(self.labels[1], total)

    def after_step(self, dw, timestep, t, uda):
        if t < self.start or t > self.stop or t < self.prev + 1.0 / self.freq:
            return
        self.prev = t
        if uda is None:
            return
        ice, mpm, flux = (float(dw.get_reduction(lab)) for lab in self.labels)
        path = os.path.join(uda, "1stLawThermo.dat")
        with open(path, "a") as f:
            if f.tell() == 0:
                f.write("# This assumes:\n#    - mpm matls have constant specific heat\n"
                        "#    - mpm matls are listed in order 0, 1, 2, 3\n"
                        f"#    - Energy conversion factor, in SI units KJ ->J {self.conv:E}\n"
                        "#Time                      ICE_totalIntEng            MPM_totalIntEng             "
                        "totalIntEng                 total_ICE_Flux\n")
            f.write(f"{t:16.15E}      {ice:16.15E}      {mpm:16.15E}       {ice + mpm:16.15E}       "
                    f"{flux:16.15E}\n")


MODULES = {"vorticity": Vorticity, "minMax": MinMax, "lineExtract": LineExtract,
           "controlVolFluxes": ControlVolFluxes, "SGS_ReynoldsStress": SGS_ReynoldsStress,
           "turbulentFluxes": TurbulentFluxes, "planeAvgTurbFluxes": PlaneAvgTurbFluxes,
           "firstLawThermo": FirstLawThermo, "planeAverage": PlaneAverage, "statistics": Statistics}


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
