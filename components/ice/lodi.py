"""Uintah's LODI boundaries: characteristic, non-reflecting open faces (BCType var="LODI").

Sutherland & Kennedy, J. Comput. Phys. 191 (2003) 502-524 (Uintah's CustomBCs/LODI2.cc): on a
LODI face the amplitudes L1..L5 of the waves crossing it are computed in the first interior cell
from one-sided differences (their table 5); the incoming ones are replaced by the source terms
(inflow), or L1/L5 relax the pressure towards <press_infinity> with K = sigma c (1 - M^2) / length
(outflow, their eqs. 8-9). The extra cell then takes q_in +- dx dq/dn with dq/dn from the L's
(their table 6) for press_CC, rho_CC, vel_CC and temp_CC. As Uintah:
  - the L's are recomputed at each place ICE sets these conditions, from that stage's fields:
    after the equilibration (press_equil_CC) and the pressure update (press_CC) from the old
    velocity and density; at the exchange (velocity and temperature of the Lagrangian values,
    whose extra cells then give mom_L_ME_CC and eng_L_ME_CC); after advection (the new state);
  - M (maxMach) is the largest |u| / c over a face's extra cells at the start of the step;
  - the edge cells of two LODI faces copy the diagonal interior cell, and the corner cells of a
    3D domain take Uintah's fixed values (101325 Pa, 1.7899909957225715 kg/m^3, 300 K, 0 m/s);
  - nothing is set at t = 0: the extra cells keep their initial values.
<LODI> block of <Grid><BoundaryConditions>: press_infinity (required), sigma (0.27), Li_scale (1),
material (the ICE material of every LODI BCType), vel_infinity and rho_infinity (both or neither:
the inflow targets of Uintah's LODI2.cc, relaxing u_n and rho on inflow with the same weights).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from . import kernels as K
from . import labels as I
from .specific_heat import cv_at

PRESS, DENSITY, TEMP = 0, 1, 2
# Uintah's fixed corner values (LODI2.cc: FacePress/Density/Temp/Vel_LODI)
CORNER = {PRESS: 101325.0, DENSITY: 1.7899909957225715, TEMP: 300.0}
LODI_KIND = 7       # bc.LODI
TINY = 1e-100       # Uintah's d_SMALL_NUM: guards the division by the normal velocity


class LodiInputs:
    """The <LODI> block and the faces that use it."""

    def __init__(self, node, level, material_names, n_before, gravity):
        self.press_infinity = node.get("press_infinity", "float")
        self.sigma = node.get("sigma", "float", 0.27)
        self.li_scale = node.get("Li_scale", "float", 1.0)
        has_v, has_r = node.has("vel_infinity"), node.has("rho_infinity")
        self.targets = has_v and has_r
        self.vel_infinity = np.array(node.get("vel_infinity", "vector", (0.0, 0.0, 0.0)), dtype=np.float64)
        self.rho_infinity = node.get("rho_infinity", "float", 0.0)
        mn = node.child("material", required=True)
        name = mn.text().strip().replace('"', "")
        if name not in material_names:
            raise mn.error(f"no ICE material named '{name}'; accepted: {', '.join(material_names)}")
        self.matl = n_before + list(material_names).index(name)
        self.node = node
        self.length = np.asarray(level.upper, dtype=np.float64) - np.asarray(level.anchor, dtype=np.float64)
        self.gravity = np.asarray(gravity, dtype=np.float64)

    def params(self):
        """[p_inf, sigma, Li_scale, targets, rho_inf, vel_inf(3)] for the kernels."""
        return np.array([self.press_infinity, self.sigma, self.li_scale, float(self.targets), self.rho_infinity,
                         *self.vel_infinity])


@njit(cache=True)
def _at(d, e, a, b):
    """(i, j, k) with index e along d and (a, b) along the next two directions (cyclic)."""
    if d == 0:
        return e, a, b
    if d == 1:
        return b, e, a
    return a, b, e


@njit(cache=True, error_model="numpy")
def face_max_mach(vel, cs, d, side, lo, hi):
    """The largest |u| / c over the extra cells of face (d, side), edges excluded."""
    e = lo[d] - 1 if side == 0 else hi[d]
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    out = 0.0
    for a in range(lo[d1], hi[d1]):
        for b in range(lo[d2], hi[d2]):
            i, j, k = _at(d, e, a, b)
            u = vel[i, j, k]
            out = max(out, np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) / cs[i, j, k])
    return out


@njit(cache=True, error_model="numpy")
def wave_amplitudes(L, rho, press, vel, cs, d, side, dx, max_mach, p, length, g_n, lo, hi):
    """L[0..4][a, b] = L1..L5 (Sutherland & Kennedy table 5, eqs. 8-9) in the first interior
    cells of face (d, side), first-order one-sided differences into the domain; a, b the
    transverse interior cells (directions d+1, d+2). p = LodiInputs.params()."""
    n = lo[d] if side == 0 else hi[d] - 1
    r, l = (n + 1, n) if side == 0 else (n, n - 1)
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    left, right = (1.0, 0.0) if side == 0 else (0.0, 1.0)
    p_inf, sigma, scale, targets, rho_inf = p[0], p[1], p[2], p[3] != 0.0, p[4]
    dv = np.empty(3)
    for a in range(lo[d1], hi[d1]):
        for b in range(lo[d2], hi[d2]):
            c = _at(d, n, a, b)
            cr = _at(d, r, a, b)
            cl = _at(d, l, a, b)
            drho = (rho[cr] - rho[cl]) / dx
            dp = (press[cr] - press[cl]) / dx
            for q in range(3):
                dv[q] = (vel[cr[0], cr[1], cr[2], q] - vel[cl[0], cl[1], cl[2], q]) / dx
            rc, C, pc = rho[c], cs[c], press[c]
            u = vel[c[0], c[1], c[2]]
            un = u[d]
            mach = abs(np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) / C)
            # the characteristic sources (table 4): gravity normal to the face only, no pressure
            # source (s2 = -s_p / c^2 = -0), no transverse ones (s3 = s4 = 0)
            s1 = 0.5 * (0.0 - rc * C * g_n)
            s2 = -0.0
            s5 = 0.5 * (0.0 + rc * C * g_n)
            c2 = C * C
            A = rc * C * dv[d]
            L1 = 0.5 * (un - C) * (dp - A)
            L2 = un * (drho - dp / c2)
            L3 = un * dv[d1]
            L4 = un * dv[d2]
            L5 = 0.5 * (un + C) * (dp + A)
            K = sigma * C * (1.0 - max_mach * max_mach)
            inflow = (side == 0 and un >= 0.0) or (side == 1 and un <= 0.0)
            if inflow and mach < 1.0:                       # subsonic inflow
                L1 = left * L1 + right * s1
                L2 = s2
                L3 = 0.0
                L4 = 0.0
                L5 = right * L5 + left * s5
                if targets:                                 # relax u_n and rho towards the targets
                    mf = 1.0 - mach * mach
                    vr = sigma * rc * c2 * mf * (un - p[5 + d]) / length
                    L5 += left * vr
                    L1 -= right * vr
                    L2 += sigma * C * mf * (rc - rho_inf) / length
            elif not inflow and mach < 1.0:                 # subsonic outflow (eqs. 8-9)
                term = 0.5 * K * (pc - p_inf) / length
                L1 = right * (term + s1) + left * L1
                L5 = left * (term + s5) + right * L5
            elif inflow and mach > 1.0:                     # supersonic inflow
                L1, L2, L3, L4, L5 = s1, s2, 0.0, 0.0, s5
            ia, ib = a - lo[d1], b - lo[d2]
            L[0, ia, ib] = L1 * scale
            L[1, ia, ib] = L2 * scale
            L[2, ia, ib] = L3 * scale
            L[3, ia, ib] = L4 * scale
            L[4, ia, ib] = L5 * scale


@njit(cache=True, error_model="numpy")
def fill_scalar(q, kind, L, rho, vel, cs, gamma, d, side, dx, lo, hi):
    """press_CC, rho_CC or temp_CC (kind) in the extra cells of face (d, side) from the first
    interior cell and the L's (table 6); vel, rho, cs: that stage's fields; gamma: the material's
    (a number) or per cell (the mixture's of a model owning the caloric EOS)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    sign = -1.0 if side == 0 else 1.0
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(lo[d1], hi[d1]):
        for b in range(lo[d2], hi[d2]):
            ce, c = _at(d, e, a, b), _at(d, n, a, b)
            ia, ib = a - lo[d1], b - lo[d2]
            L1, L2, L5 = L[0, ia, ib], L[1, ia, ib], L[4, ia, ib]
            un = vel[c[0], c[1], c[2], d]
            C = cs[c]
            if kind == PRESS:
                dq = L5 / (un + C) + L1 / (un - C)
            elif kind == DENSITY:
                dq = L2 / (un + TINY) + (L5 / (un + C) + L1 / (un - C)) / (C * C)
            else:
                t1 = q[c] / (rho[c] * C * C)
                g = cv_at(gamma, c[0], c[1], c[2])
                dq = t1 * (-(L2 / (un + TINY)) + (g - 1.0) * (L5 / (un + C) + L1 / (un - C)))
            q[ce] = q[c] + sign * dx * dq


@njit(cache=True, error_model="numpy")
def fill_velocity(vel, L, rho, cs, d, side, dx, lo, hi):
    """vel_CC in the extra cells of face (d, side): the normal component from L1, L5, the
    transverse ones from L3, L4 (table 6)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    sign = -1.0 if side == 0 else 1.0
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(lo[d1], hi[d1]):
        for b in range(lo[d2], hi[d2]):
            ce, c = _at(d, e, a, b), _at(d, n, a, b)
            ia, ib = a - lo[d1], b - lo[d2]
            un = vel[c[0], c[1], c[2], d]
            C = cs[c]
            dun = (1.0 / (rho[c] * C)) * (L[4, ia, ib] / (un + C) - L[0, ia, ib] / (un - C))
            dv1 = L[2, ia, ib] / (un + TINY)
            dv2 = L[3, ia, ib] / (un + TINY)
            vel[ce[0], ce[1], ce[2], d] = un + sign * dx * dun
            vel[ce[0], ce[1], ce[2], d1] = vel[c[0], c[1], c[2], d1] + sign * dx * dv1
            vel[ce[0], ce[1], ce[2], d2] = vel[c[0], c[1], c[2], d2] + sign * dx * dv2


@njit(cache=True)
def fill_edges(q, d, side, corner, at_lo, at_hi, dims, lo, hi):
    """The edge cells of face (d, side) along the domain's other faces copy the diagonal
    interior cell; a 3D domain's corner cells take `corner` (q: 4D, one entry per cell)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    idx = np.empty(3, dtype=np.int64)
    src = np.empty(3, dtype=np.int64)
    for t in ((d + 1) % 3, (d + 2) % 3):
        if not dims[t]:
            continue
        r = 3 - d - t
        for st in range(2):
            if not (at_lo[t] if st == 0 else at_hi[t]):
                continue
            idx[d], src[d] = e, n
            idx[t] = lo[t] - 1 if st == 0 else hi[t]
            src[t] = lo[t] if st == 0 else hi[t] - 1
            for x in range(lo[r], hi[r]):
                idx[r] = src[r] = x
                for c in range(q.shape[3]):
                    q[idx[0], idx[1], idx[2], c] = q[src[0], src[1], src[2], c]
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    if dims[d1] and dims[d2]:
        for s1 in range(2):
            for s2 in range(2):
                if (at_lo[d1] if s1 == 0 else at_hi[d1]) and (at_lo[d2] if s2 == 0 else at_hi[d2]):
                    idx[d] = e
                    idx[d1] = lo[d1] - 1 if s1 == 0 else hi[d1]
                    idx[d2] = lo[d2] - 1 if s2 == 0 else hi[d2]
                    for c in range(q.shape[3]):
                        q[idx[0], idx[1], idx[2], c] = corner[c]


@njit(cache=True)
def li_field(out, L, d, side, lo, hi):
    """Uintah's saved Li<k>: L_k in the first interior cells of a face, component d."""
    n = lo[d] if side == 0 else hi[d] - 1
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(lo[d1], hi[d1]):
        for b in range(lo[d2], hi[d2]):
            c = _at(d, n, a, b)
            out[c[0], c[1], c[2], d] = L[a - lo[d1], b - lo[d2]]


FACE_INDEX = {"x-": 0, "x+": 1, "y-": 2, "y+": 3, "z-": 4, "z+": 5}
VEL = 3
LABEL_OF = {PRESS: "Pressure", DENSITY: "Density", TEMP: "Temperature", VEL: "Velocity"}


class LodiTasks:
    """The LODI steps of ICE's tasks (mixed into the component class; self.lodi: LodiInputs)."""

    def max_mach_faces(self, patch, matls, old_dw, new_dw):
        """Uintah's maxMach_on_Lodi_BC_Faces: max |u| / c over each LODI face's extra cells
        (old state; 0 for the patches off that face)."""
        b = self.boxes(patch)
        out = np.zeros(6)
        m = self.lodi.matl
        vel, cs = old_dw.get(I.vel_CC, m, patch), old_dw.get(I.speedSound_CC, m, patch)
        for name in self.lodi.faces:
            if name in patch.boundary_faces:
                f = FACE_INDEX[name]
                out[f] = face_max_mach(vel, cs, f // 2, f % 2, b.lo, b.hi)
        new_dw.put_reduction(I.maxMach_faces, out)

    def lodi_set(self, patch, new_dw, rho, press, vel, cs, targets, save=None):
        """Set the extra cells of the LODI faces of each (kind, array) in targets from the wave
        amplitudes of this stage's rho, press, vel and speed of sound; save: Li1..Li5 arrays."""
        b = self.boxes(patch)
        lo_ = self.lodi
        m = lo_.matl
        max_mach = new_dw.get_reduction(I.maxMach_faces)
        dims = np.asarray(self.dims)
        at_lo, at_hi = np.array(patch.at_low), np.array(patch.at_high)
        p = lo_.params()
        for name in lo_.faces:
            if name not in patch.boundary_faces:
                continue
            f = FACE_INDEX[name]
            d, side = f // 2, f % 2
            d1, d2 = (d + 1) % 3, (d + 2) % 3
            dx = patch.level.dx[d]
            L = np.empty((5, b.hi[d1] - b.lo[d1], b.hi[d2] - b.lo[d2]))
            wave_amplitudes(L, rho, press, vel, cs, d, side, dx, max_mach[f], p, lo_.length[d], lo_.gravity[d],
                            b.lo, b.hi)
            if save is not None:
                for k in range(5):
                    li_field(save[k], L[k], d, side, b.lo, b.hi)
            table = self.bcs.table[name]
            for kind, q in targets:
                if table[LABEL_OF[kind]][0 if kind == PRESS else m][0] != LODI_KIND:
                    continue
                if kind == VEL:
                    fill_velocity(q, L, rho, cs, d, side, dx, b.lo, b.hi)
                    fill_edges(q, d, side, np.zeros(3), at_lo, at_hi, dims, b.lo, b.hi)
                else:
                    gamma = self._gamma(new_dw, m, patch) if kind == TEMP else 0.0
                    fill_scalar(q, kind, L, rho, vel, cs, gamma, d, side, dx, b.lo, b.hi)
                    fill_edges(q[..., None], d, side, np.array([CORNER[kind]]), at_lo, at_hi, dims, b.lo, b.hi)

    def lodi_press(self, patch, press, cs, old_dw, new_dw):
        """press_equil_CC or press_CC (Uintah's EqPress and update_press_CC): the L's from the
        old velocity and density and this step's speed of sound cs."""
        m = self.lodi.matl
        self.lodi_set(patch, new_dw, old_dw.get(I.rho_CC, m, patch), press, old_dw.get(I.vel_CC, m, patch), cs,
                      [(PRESS, press)])

    def lodi_exchange(self, patch, m, mass, mom, eng, old_dw, new_dw):
        """Uintah's exchange with one material under LODI: u and T of the Lagrangian values take
        every face's conditions (the L's from them, press_CC and the old density), and
        mom_L_ME_CC = m u, eng_L_ME_CC = m cv T in every cell."""
        b = self.boxes(patch)
        cv = self._cv(new_dw, m, patch)
        vel, temp = np.empty(mom.shape), np.empty(eng.shape)
        K.lagrangian_to_primitive(mass, mom, eng, cv, vel, temp, b.olo, b.ohi)
        self.lodi_set(patch, new_dw, old_dw.get(I.rho_CC, m, patch), new_dw.get(I.press_CC, 0, patch), vel,
                      new_dw.get(I.speedSound_CC, m, patch), [(VEL, vel), (TEMP, temp)])
        self.bcs.velocity(patch, vel, m, b)
        self.bcs.scalar(patch, temp, "Temperature", m, b)
        mom_me = new_dw.allocate(I.mom_L_ME_CC, m, patch, fill=None)
        eng_me = new_dw.allocate(I.int_eng_L_ME_CC, m, patch, fill=None)
        K.primitive_to_lagrangian(mass, vel, temp, cv, mom_me, eng_me, b.olo, b.ohi)

    def lodi_exchange_caloric(self, patch, matls, old_dw, new_dw):
        """lodi_exchange where a model owns the material's caloric EOS (Uintah's exchange task
        then): T from e_s = int_eng_L / mass_L and the Lagrangian species Y_L = (m Y)_L / mass_L
        in every cell, the faces' conditions on u and T, then int_eng_L_ME = mass_L e_s(T, Y_L)."""
        b = self.boxes(patch)
        own = tuple(slice(l, h) for l, h in zip(b.olo, b.ohi))
        for m in matls:
            model = self.caloric[m]
            mass, mom, eng = (new_dw.get(lab, m, patch) for lab in (I.mass_L_CC, I.mom_L_CC, I.int_eng_L_CC))
            y = np.ones((len(model.species),) + mass.shape)
            for s, sp in enumerate(model.species):
                y[s][own] = new_dw.get(sp.f_L, m, patch)[own] / mass[own]
            vel, es, temp = np.zeros(mom.shape), np.ones(eng.shape), np.ones(eng.shape)
            K.lagrangian_to_primitive(mass, mom, eng, 1.0, vel, es, b.olo, b.ohi)
            model.temperature(patch, es, y, temp, b.olo, b.ohi)
            self.lodi_set(patch, new_dw, old_dw.get(I.rho_CC, m, patch), new_dw.get(I.press_CC, 0, patch), vel,
                          new_dw.get(I.speedSound_CC, m, patch), [(VEL, vel), (TEMP, temp)])
            self.bcs.velocity(patch, vel, m, b)
            self.bcs.scalar(patch, temp, "Temperature", m, b)
            model.sensible_energy(temp, y, es, b.olo, b.ohi)
            mom_me = new_dw.allocate(I.mom_L_ME_CC, m, patch, fill=None)
            eng_me = new_dw.allocate(I.int_eng_L_ME_CC, m, patch, fill=None)
            K.primitive_to_lagrangian(mass, vel, es, 1.0, mom_me, eng_me, b.olo, b.ohi)

    def lodi_advected(self, patch, m, rho, vel, temp, new_dw):
        """rho_CC, vel_CC and temp_CC after advection (Uintah's Advection stage: the L's of the
        new state, press_CC and this step's speed of sound)."""
        self.lodi_set(patch, new_dw, rho, new_dw.get(I.press_CC, 0, patch), vel, new_dw.get(I.speedSound_CC, m, patch),
                      [(DENSITY, rho), (VEL, vel), (TEMP, temp)])

    def lodi_li(self, patch, matls, old_dw, new_dw):
        """Uintah's Li1..Li5 (saved labels): the L's after advection in the first interior cells
        of the LODI faces, the face-normal component; zero elsewhere."""
        m = self.lodi.matl
        save = [new_dw.allocate(lab, m, patch) for lab in I.LODI_Li]
        self.lodi_set(patch, new_dw, new_dw.get(I.rho_CC, m, patch), new_dw.get(I.press_CC, 0, patch),
                      new_dw.get(I.vel_CC, m, patch), new_dw.get(I.speedSound_CC, m, patch), [], save)
