"""Contact between MPM materials (`<MaterialProperties><MPM><contact>`), Uintah's Contact/.

  null             each material moves on its own velocity field (no interaction)
  single_velocity  at nodes shared by the listed materials all take the centre-of-mass
                   velocity, after interpolation and again after integration: the
                   materials stick (one velocity field, as in paper 004)
  friction         Coulomb friction (Uintah's friction_bard and approach, also accepted by
  (friction_bard,  those names; <mu>): at a node shared by the listed materials, a
  approach)        material whose velocity relative to the centre of mass points along its outward
                   normal (approaching) loses that normal part and, of its tangential
                   part, up to mu times the normal part (sticks when that is enough).
                   Normals as Uintah's computeNormals: g_m = sum m_p grad S (outward),
                   made collinear with the other materials' (0.5 (g_m - mass-weighted
                   mean of the others' g)), unit length. The change is scaled down where it would impose a
                   strain dt |dv|/dx above 0.5 (Uintah's limiter). Applied after
                   interpolation and after integration (Uintah's OneOrTwoStep = 2).
                   This is Uintah's ApproachContact (with its volume constraint 0);
                   friction_bard adds a separation test pysus does not make. A legacy
                   <vel_fields> is read: Uintah does not use it.
  rigid            Uintah's SpecifiedBodyContact (also `specified`, `specified_velocity`):
  (specified)      <master_material> (default 0) moves with a prescribed velocity: its
                   own initial (grid) velocity, or a <filename> profile of lines
                   "t vx vy vz" (linear in between, held beyond), and after <stop_time>
                   (default never) <velocity_after_stop> (default 0). At every node
                   where the master material has mass, the master takes that velocity
                   and the other listed materials take its components along
                   <direction> (integer mask, default [0,0,1]). After integration only
                   (OneOrTwoStep = 1); the acceleration there becomes (v* - v)/dt.
                   <include_rotation>true: the file's lines are "t vx vy vz ox oy oz wx wy
                   wz" (origin o, angular velocity w, linear in t) and a node at x takes
                   v + the rotation part: exact over dt, (R(w dt) x - x)/dt, when w lies
                   within 0.99 of a coordinate axis, else w x (x - o) (Uintah's two cases).
                   RigidReactionForce / RigidReactionTorque (reductions, all materials
                   together): the sum over the nodes where the master has mass of minus
                   the other contact materials' internal force, and of (x - o) x that
                   (0 without include_rotation, as Uintah).
  specified_friction  Uintah's SpecifiedBodyFrictionContact: the <master_material> (default
                   0, rigid) moves as `rigid` does (its own grid velocity, a <filename> profile
                   "t vx vy vz", <stop_time>, <velocity_after_stop>; <include_rotation> is
                   refused); at a node with friction_LR's alpha material (below) the master
                   takes that velocity and each other listed material touching it (prominence
                   not past alpha's) and approaching it (dv.n > 0, dv relative to the rigid
                   velocity) loses its normal part and, of its tangential part, up to <mu>
                   times that; the master takes nothing back. Nodes where <ExcludeMaterial>
                   has mass are left alone. <OneOrTwoStep> 1 (default): after integration
                   only; 2: also after interpolation. RigidReactionForce is not computed.
  friction_LR      Nairn & Hammerquist's logistic-regression contact (Uintah's
  (friction_LRVar) FrictionContactLR, <mu>): at every node where two or more materials
                   have mass (and particles), the one with the most mass is alpha
                   (g.alphaMaterial); the normal from alpha to the others
                   (g.normAlphaToBeta) separates their nearby particle positions by a
                   regularised logistic regression (kernels.lr_normals); each
                   material's prominence there (g.matlProminence) is the farthest face
                   centre of its surface particles (p.surface) along it. A material
                   not standing out past alpha's and moving toward it loses its normal
                   velocity relative to the centre of mass and, of its tangential one,
                   up to mu times that; alpha takes the opposite momentum.
                   <OneOrTwoStep> 2 (default): after interpolation and integration; 1:
                   after integration only. The normal's component into a symmetry face
                   (and along a collapsed 2D/1D direction) is removed, as Uintah does.
                   friction_LRVar: mu from the <master_material>'s colour at the node
                   (g.color, needs <withColor>): linear in the <variable_friction>
                   <entry><color>..</color><mu>..</mu></entry> table (at least two,
                   colours increasing), held above its last colour and, as Uintah's
                   findMuFromColor, extrapolated from the first two below the first.
                   <volume_constraint> and <separation_factor> are read: Uintah's
                   friction_LR uses neither.
<materials>[a,b,..] lists the materials in contact (default all). As Uintah's
ContactMaterialSpec, an index beyond the last MPM material names no material and is
passed over (a pysus warning says so); a negative index is refused.
Other Uintah types (penalty, nodal_svf, ...) are refused by name.
With one listed material, or with null, no contact task is scheduled.
"""
from __future__ import annotations

import numpy as np

from framework.problemspec import Param

from . import kernels

TYPES = ("null", "single_velocity", "friction", "friction_bard", "approach", "rigid", "specified",
         "specified_velocity", "friction_LR", "friction_LRVar", "specified_friction")
CONTACT = {"type": Param("str", "null", TYPES)}
FRICTION = {"mu": Param("float", doc="Coulomb friction coefficient", at_least=0.0),
            "volume_constraint": Param("float", 0.0, (0.0,), "only 0 (no constraint)"),
            "OneOrTwoStep": Param("int", 2, (2,), "contact after interpolation and integration"),
            "vel_fields": Param("str", "", doc="read; Uintah does not use it")}
FRICTION_LR = {"mu": Param("float", doc="Coulomb friction coefficient", at_least=0.0),
               "volume_constraint": Param("float", 0.0, doc="read; Uintah's friction_LR does not use it"),
               "separation_factor": Param("float", 0.0, doc="read; Uintah's friction_LR does not use it"),
               "OneOrTwoStep": Param("int", 2, (1, 2), "1: after integration only; 2: also after interpolation")}
FRICTION_LRVAR = {**{k: v for k, v in FRICTION_LR.items() if k != "mu"},
                  "master_material": Param("int", doc="the material whose colour sets mu")}
RIGID = {"direction": Param("ivector", (0, 0, 1), doc="components imposed on the other materials"),
         "master_material": Param("int", 0),
         "stop_time": Param("float", np.inf),
         "velocity_after_stop": Param("vector", (0.0, 0.0, 0.0)),
         "filename": Param("str", ""),
         "OneOrTwoStep": Param("int", 1, (1,), "contact after integration only"),
         "include_rotation": Param("bool", False),
         "normal_only": Param("bool", False, (False,), "normal_only is not implemented"),
         "volume_constraint": Param("float", 0.0, (0.0,), "only 0 (no constraint)")}
SPECIFIED_FRICTION = {"mu": Param("float", doc="Coulomb friction coefficient", at_least=0.0),
                      "master_material": Param("int", 0),
                      "stop_time": Param("float", np.inf),
                      "velocity_after_stop": Param("vector", (0.0, 0.0, 0.0)),
                      "filename": Param("str", ""),
                      "include_rotation": Param("bool", False, (False,), "include_rotation is not implemented "
                                                "with specified_friction"),
                      "ExcludeMaterial": Param("int", -999, doc="nodes where it has mass are left alone"),
                      "OneOrTwoStep": Param("int", 1, (1, 2), "1: after integration only; 2: also after "
                                            "interpolation")}


def _int_list(node):
    """Uintah's <materials>[0,1]</materials>: any number of material indices."""
    t = node.text()
    try:
        if not (t.startswith("[") and t.endswith("]")):
            raise ValueError
        return tuple(int(x) for x in t[1:-1].replace(",", " ").split())
    except ValueError:
        raise node.error(f"value '{t}' is not a list of material indices like [0,1]") from None


def rotation_axis(omega):
    """Uintah's test: the coordinate axis within 0.99 of omega's direction, else -1."""
    length = np.linalg.norm(omega)
    for d in range(3):
        if length > 0 and abs(omega[d]) / length > 0.99:
            return d
    return -1


class Contact:
    def __init__(self, mpm_node, nmat):
        nodes = mpm_node.children("contact")
        if len(nodes) > 1:
            raise nodes[1].error("only one <contact> block is supported")
        node = nodes[0] if nodes else None
        spec = node.read(CONTACT) if node is not None else {"type": "null"}
        kind = spec["type"]
        self.type = {"friction_bard": "friction", "approach": "friction", "specified": "rigid",
                     "specified_velocity": "rigid"}.get(kind, kind)
        if kind == "null" and node is not None and node.has("mu"):
            node.child("mu").mark_used()          # Uintah's NullContact does not read it
        mnode = node.child("materials") if node is not None else None
        mats = _int_list(mnode) if mnode is not None else tuple(range(nmat))
        if any(m < 0 for m in mats):
            raise mnode.error(f"material index {min(mats)} is negative; accepted: indices 0 to {nmat - 1}")
        if any(m >= nmat for m in mats):
            gone = [m for m in mats if m >= nmat]
            note = mnode.error(f"materials {gone} do not exist (there are {nmat} MPM materials); "
                               "passed over as Uintah does")
            print(f"pysus: warning: {note}")
            mats = tuple(m for m in mats if m < nmat)
        if self.type == "null" and node is not None and node.has("mu"):
            node.child("mu").mark_used()          # Uintah's NullContact passes it over too
        if self.type == "friction":
            self.mu = node.read(FRICTION)["mu"]
            if self.mu < 0:
                raise node.child("mu").error("mu must not be negative")
        elif self.type in ("friction_LR", "friction_LRVar"):
            self._read_lr(node, nmat, mats)
        elif self.type == "specified_friction":
            r = node.read(SPECIFIED_FRICTION)
            self.master, self.mu, self.one_or_two = r["master_material"], r["mu"], r["OneOrTwoStep"]
            if not 0 <= self.master < nmat:
                raise node.child("master_material").error(
                    f"material {self.master} does not exist; there are {nmat} MPM materials")
            self.exclude = r["ExcludeMaterial"] if 0 <= r["ExcludeMaterial"] < nmat else -1
            mats = (self.master,) + mats
            self.stop_time = r["stop_time"]
            self.vel_after_stop = np.array(r["velocity_after_stop"], float)
            self.rotation = False
            self.profile = self._profile(node, r["filename"], 4) if r["filename"] else None
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
            self.rotation = r["include_rotation"]
            self.profile = self._profile(node, r["filename"], 10 if self.rotation else 4) if r["filename"] else None
            if self.rotation and self.profile is None:
                raise node.child("include_rotation").error("<include_rotation> needs a <filename> with the "
                                                           "lines 't vx vy vz ox oy oz wx wy wz'")
        self.materials = tuple(dict.fromkeys(mats))
        self.active = self.type != "null" and len(self.materials) > 1
        # where the contact acts: after interpolation (v) and/or after integration (v*)
        lr = self.type in ("friction_LR", "friction_LRVar", "specified_friction")
        self.interpolated = self.active and (self.type in ("single_velocity", "friction")
                                             or (lr and self.one_or_two == 2))
        self.needs_normals = self.active and self.type == "friction"
        # friction_bard also holds a node in compression (Uintah's g.normtraction < 0)
        self.needs_traction = self.needs_normals and kind == "friction_bard"
        self.needs_lr = self.active and lr
        self.needs_color = self.active and self.type == "friction_LRVar"
        self.needs_time = self.active and self.type in ("rigid", "specified_friction")

    def _read_lr(self, node, nmat, mats):
        """friction_LR's <mu>, friction_LRVar's <master_material> and colour table."""
        spec = node.read(FRICTION_LR if self.type == "friction_LR" else FRICTION_LRVAR)
        self.one_or_two = spec["OneOrTwoStep"]
        if self.type == "friction_LR":
            self.mu_colors, self.mu_values = np.zeros(1), np.array([spec["mu"]])
            self.master = -1
            return
        self.master = spec["master_material"]
        if self.master not in mats:
            raise node.child("master_material").error(
                f"material {self.master} is not one of the contact <materials> {list(mats)}")
        table = node.child("variable_friction", required=True)
        entries = table.children("entry")
        if len(entries) < 2:
            raise table.error("<variable_friction> needs at least two <entry> (<color>, <mu>)")
        self.mu_colors = np.array([e.get("color", "float") for e in entries])
        self.mu_values = np.array([e.get("mu", "float", at_least=0.0) for e in entries])
        if np.any(np.diff(self.mu_colors) <= 0):
            raise table.error("the <color> of the entries must increase")

    def mu_at(self, color):
        """mu per node: friction_LR's constant, friction_LRVar's table at the master's g.color."""
        c, mu = self.mu_colors, self.mu_values
        if color is None:
            return np.full(1, mu[0])
        hi = np.clip(np.searchsorted(c, color, side="left"), 1, len(c) - 1)
        s = (c[hi] - color) / (c[hi] - c[hi - 1])
        return np.where(color >= c[-1], mu[-1], mu[hi - 1] * s + mu[hi] * (1.0 - s))

    @staticmethod
    def _profile(node, filename, ncol):
        import os
        path = filename
        if not os.path.isabs(path) and node.filename:
            path = os.path.join(os.path.dirname(os.path.abspath(node.filename)), filename)
        try:
            data = np.loadtxt(path, ndmin=2)
        except OSError:
            raise node.child("filename").error(f"cannot read the rigid motion file '{filename}'") from None
        line = "t vx vy vz" + (" ox oy oz wx wy wz" if ncol == 10 else "")
        if data.shape[1] != ncol or len(data) < 2 or np.any(np.diff(data[:, 0]) <= 0):
            raise node.child("filename").error(
                f"the rigid motion file needs at least 2 lines '{line}' with increasing t")
        return data

    def _stacked(self, gmass, gvel, gacc, gvel_old, lr):
        """The logistic-regression contacts' inputs over all MPM materials, one row per material:
        (materials, m, v, a, v_old, requested, alpha, normal, prominence); a and v_old are v
        itself where the velocities are not integrated yet (gacc None)."""
        idx = sorted(gmass)
        alpha, normal, prom = lr
        m = np.stack([gmass[i].reshape(-1) for i in idx])
        v = np.stack([gvel[i].reshape(-1, 3) for i in idx])
        integrated = gacc is not None
        a = np.stack([gacc[i].reshape(-1, 3) for i in idx]) if integrated else v
        vo = np.stack([gvel_old[i].reshape(-1, 3) for i in idx]) if integrated else v
        requested = np.array([i in self.materials for i in idx], np.bool_)
        return (idx, m, v, a, vo, requested, alpha.reshape(-1).astype(np.int64), normal.reshape(-1, 3),
                np.stack([prom[i].reshape(-1) for i in idx]))

    @staticmethod
    def _unstack(idx, v, a, gvel, gacc):
        """The rows back into each material's grid velocity (and acceleration once integrated)."""
        for k, i in enumerate(idx):
            gvel[i].reshape(-1, 3)[...] = v[k]
            if gacc is not None:
                gacc[i].reshape(-1, 3)[...] = a[k]

    def _exchange_lr(self, gmass, gvel, gacc, gvel_old, dt, lr, color):
        """friction_LR(Var) over all MPM materials (alpha may be any of them)."""
        idx, m, v, a, vo, requested, alpha, normal, prom = self._stacked(gmass, gvel, gacc, gvel_old, lr)
        mu = self.mu_at(None if color is None else color.reshape(-1))
        if len(mu) == 1:
            mu = np.full(m.shape[1], mu[0])
        kernels.friction_lr(m, v, requested, alpha, normal, prom, mu, a, vo, dt if gacc is not None else 0.0)
        self._unstack(idx, v, a, gvel, gacc)

    def _exchange_specified_friction(self, gmass, gvel, gacc, gvel_old, dt, t, lr):
        """specified_friction over all MPM materials, with friction_LR's normals."""
        idx, m, v, a, vo, requested, alpha, normal, prom = self._stacked(gmass, gvel, gacc, gvel_old, lr)
        vel, _, _, own = self.rigid_velocity(t)
        kernels.specified_friction(m, v, requested, alpha, normal, prom, idx.index(self.master),
                                   np.asarray(vel, float), own, idx.index(self.exclude) if self.exclude >= 0 else -1,
                                   self.mu, a, vo, dt if gacc is not None else 0.0)
        self._unstack(idx, v, a, gvel, gacc)

    def reaction(self, gmass, fint, t, node_x, own):
        """(RigidReactionForce, RigidReactionTorque) of one patch: see the module doc."""
        idx = list(self.materials)
        master = gmass[self.master].reshape(-1)
        f = np.stack([fint[i].reshape(-1, 3) for i in idx])
        others = np.array([i != self.master for i in idx], np.bool_)
        _, origin, _, _ = self.rigid_velocity(t)
        anchor, spacing, low = node_x
        force, torque = np.zeros(3), np.zeros(3)
        kernels.rigid_reaction(master, f, others, np.asarray(own[0], np.int64), np.asarray(own[1], np.int64),
                               np.array(gmass[self.master].shape, np.int64), np.asarray(anchor, float),
                               np.asarray(spacing, float), np.asarray(low, np.int64), origin,
                               bool(self.rotation), force, torque)
        return force, torque

    def rigid_velocity(self, t):
        """(velocity, origin, angular velocity, use the master's own grid velocity) at sim
        time t (Uintah's order: after <stop_time> no rotation)."""
        zero = np.zeros(3)
        if t > self.stop_time:
            return self.vel_after_stop, zero, zero, False
        if self.profile is not None:
            val = np.array([np.interp(t, self.profile[:, 0], self.profile[:, c])
                            for c in range(1, self.profile.shape[1])])
            if self.rotation:
                return val[0:3], val[3:6], val[6:9], False
            return val, zero, zero, False
        return zero, zero, zero, True

    def exchange(self, gmass, gvel, gacc, gvel_old, dt, t=0.0, normals=None, dx=None, node_x=None,
                 lr=None, color=None, traction=None):
        """Apply to dicts (per material) of node arrays; modifies gvel (and gacc: a is
        then (v_new - v_old)/dt where the contact acts). node_x: (anchor, dx, low index)
        of the patch's nodes, for a rotating rigid body; lr: (g.alphaMaterial,
        g.normAlphaToBeta, {material: g.matlProminence}) and color: the master's g.color
        for friction_LR(Var); traction: friction_bard's g.normtraction per material."""
        if self.type == "specified_friction":
            self._exchange_specified_friction(gmass, gvel, gacc, gvel_old, dt, t, lr)
            return
        if self.needs_lr:
            self._exchange_lr(gmass, gvel, gacc, gvel_old, dt, lr, color)
            return
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
            tn = np.stack([traction[i].reshape(-1) for i in idx]) if self.needs_traction else np.empty((0, 0))
            kernels.friction(m, v, nrm, tn, self.mu, np.asarray(dx, float), dt, a, vo, h)
        else:
            vel, origin, omega, own = self.rigid_velocity(t)
            shape = np.array(gmass[idx[0]].shape, np.int64)
            anchor, spacing, low = node_x if node_x is not None else (np.zeros(3), np.ones(3), np.zeros(3, np.int64))
            kernels.rigid(m, v, a, vo, h, dt, idx.index(self.master), self.direction, vel, own,
                          origin, omega, rotation_axis(omega), shape, np.asarray(anchor, float),
                          np.asarray(spacing, float), np.asarray(low, np.int64))
        for k, i in enumerate(idx):
            gvel[i].reshape(-1, 3)[...] = v[k]
            if integrated:
                gacc[i].reshape(-1, 3)[...] = a[k]
