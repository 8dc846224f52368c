"""Contact between MPM materials (`<MaterialProperties><MPM><contact>`), Uintah's Contact/.

  null             each material moves on its own velocity field (no interaction)
  single_velocity  at nodes shared by the listed materials all take the centre-of-mass
                   velocity, after interpolation and again after integration: the
                   materials stick (one velocity field, as in paper 004)
  friction         Coulomb friction (Uintah's friction_bard, also accepted by that name;
  (friction_bard)  <mu>): at a node shared by the listed materials, a material whose
                   velocity relative to the centre of mass points along its outward
                   normal (approaching) loses that normal part and, of its tangential
                   part, up to mu times the normal part (sticks when that is enough).
                   Normals as Uintah's computeNormals: g_m = sum m_p grad S (outward),
                   made collinear with the other materials' (0.5 (g_m - mass-weighted
                   mean of the others' g)), unit length. The change is scaled down where it would impose a
                   strain dt |dv|/dx above 0.5 (Uintah's limiter). Applied after
                   interpolation and after integration (Uintah's OneOrTwoStep = 2).
  rigid            Uintah's SpecifiedBodyContact (also `specified`, `specified_velocity`):
  (specified)      <master_material> (default 0) moves with a prescribed velocity: its
                   own initial (grid) velocity, or a <filename> profile of lines
                   "t vx vy vz" (linear in between, held beyond), and after <stop_time>
                   (default never) <velocity_after_stop> (default 0). At every node
                   where the master material has mass, the master takes that velocity
                   and the other listed materials take its components along
                   <direction> (integer mask, default [0,0,1]). After integration only
                   (OneOrTwoStep = 1); the acceleration there becomes (v* - v)/dt.
Other Uintah types (approach, penalty, nodal_svf, friction_LR) are refused by name.
With one listed material, or with null, no contact task is scheduled.
"""
from __future__ import annotations

import numpy as np

from framework.problemspec import Param

from . import kernels

TYPES = ("null", "single_velocity", "friction", "friction_bard", "rigid", "specified",
         "specified_velocity")
CONTACT = {"type": Param("str", "null", TYPES)}
FRICTION = {"mu": Param("float", doc="Coulomb friction coefficient", at_least=0.0),
            "volume_constraint": Param("float", 0.0, (0.0,), "only 0 (no constraint)"),
            "OneOrTwoStep": Param("int", 2, (2,), "contact after interpolation and integration")}
RIGID = {"direction": Param("ivector", (0, 0, 1), doc="components imposed on the other materials"),
         "master_material": Param("int", 0),
         "stop_time": Param("float", np.inf),
         "velocity_after_stop": Param("vector", (0.0, 0.0, 0.0)),
         "filename": Param("str", ""),
         "OneOrTwoStep": Param("int", 1, (1,), "contact after integration only"),
         "include_rotation": Param("bool", False, (False,), "rotation is not implemented"),
         "normal_only": Param("bool", False, (False,), "normal_only is not implemented"),
         "volume_constraint": Param("float", 0.0, (0.0,), "only 0 (no constraint)")}


def _int_list(node):
    """Uintah's <materials>[0,1]</materials>: any number of material indices."""
    t = node.text()
    try:
        if not (t.startswith("[") and t.endswith("]")):
            raise ValueError
        return tuple(int(x) for x in t[1:-1].replace(",", " ").split())
    except ValueError:
        raise node.error(f"value '{t}' is not a list of material indices like [0,1]") from None


class Contact:
    def __init__(self, mpm_node, nmat):
        nodes = mpm_node.children("contact")
        if len(nodes) > 1:
            raise nodes[1].error("only one <contact> block is supported")
        node = nodes[0] if nodes else None
        spec = node.read(CONTACT) if node is not None else {"type": "null"}
        kind = spec["type"]
        self.type = {"friction_bard": "friction", "specified": "rigid",
                     "specified_velocity": "rigid"}.get(kind, kind)
        mnode = node.child("materials") if node is not None else None
        mats = _int_list(mnode) if mnode is not None else tuple(range(nmat))
        for m in mats:
            if not 0 <= m < nmat:
                raise mnode.error(f"material {m} does not exist; there are {nmat} MPM materials")
        if self.type == "friction":
            self.mu = node.read(FRICTION)["mu"]
            if self.mu < 0:
                raise node.child("mu").error("mu must not be negative")
        elif self.type == "rigid":
            r = node.read(RIGID)
            self.master = r["master_material"]
            if not 0 <= self.master < nmat:
                raise node.child("master_material").error(
                    f"material {self.master} does not exist; there are {nmat} MPM materials")
            mats = (self.master,) + mats               # Uintah always adds the master
            self.direction = np.array([d != 0 for d in r["direction"]], np.bool_)
            self.stop_time = r["stop_time"]
            self.vel_after_stop = np.array(r["velocity_after_stop"], float)
            self.profile = self._profile(node, r["filename"]) if r["filename"] else None
        self.materials = tuple(dict.fromkeys(mats))
        self.active = self.type != "null" and len(self.materials) > 1
        # where the contact acts: after interpolation (v) and/or after integration (v*)
        self.interpolated = self.active and self.type in ("single_velocity", "friction")
        self.needs_normals = self.active and self.type == "friction"
        self.needs_time = self.active and self.type == "rigid"

    @staticmethod
    def _profile(node, filename):
        import os
        path = filename
        if not os.path.isabs(path) and node.filename:
            path = os.path.join(os.path.dirname(os.path.abspath(node.filename)), filename)
        try:
            data = np.loadtxt(path, ndmin=2)
        except OSError:
            raise node.child("filename").error(f"cannot read the rigid motion file '{filename}'") from None
        if data.shape[1] != 4 or len(data) < 2 or np.any(np.diff(data[:, 0]) <= 0):
            raise node.child("filename").error(
                "the rigid motion file needs at least 2 lines 't vx vy vz' with increasing t")
        return data

    def rigid_velocity(self, t):
        """(velocity, use the master's own grid velocity) at sim time t (Uintah's order)."""
        if t > self.stop_time:
            return self.vel_after_stop, False
        if self.profile is not None:
            return np.array([np.interp(t, self.profile[:, 0], self.profile[:, 1 + d]) for d in range(3)]), False
        return np.zeros(3), True

    def exchange(self, gmass, gvel, gacc, gvel_old, dt, t=0.0, normals=None, dx=None):
        """Apply to dicts (per material) of node arrays; modifies gvel (and gacc: a is
        then (v_new - v_old)/dt where the contact acts)."""
        idx = list(self.materials)
        m = np.stack([gmass[i].reshape(-1) for i in idx])
        v = np.stack([gvel[i].reshape(-1, 3) for i in idx])
        integrated = gacc is not None
        a = np.stack([gacc[i].reshape(-1, 3) for i in idx]) if integrated else v
        vo = np.stack([gvel_old[i].reshape(-1, 3) for i in idx]) if integrated else v
        h = dt if integrated else 0.0
        if self.type == "single_velocity":
            kernels.single_velocity(m, v, a, vo, h)
        elif self.type == "friction":
            nrm = np.stack([normals[i].reshape(-1, 3) for i in idx])
            kernels.friction(m, v, nrm, self.mu, np.asarray(dx, float), dt, a, vo, h)
        else:
            vel, own = self.rigid_velocity(t)
            kernels.rigid(m, v, a, vo, h, idx.index(self.master), self.direction, vel, own)
        for k, i in enumerate(idx):
            gvel[i].reshape(-1, 3)[...] = v[k]
            if integrated:
                gacc[i].reshape(-1, 3)[...] = a[k]
