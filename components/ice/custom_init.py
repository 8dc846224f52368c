"""<CFD><ICE><customInitialization>: Uintah's velocity profiles that overwrite the geometry
objects' initial velocity (ICE's customInitialize.cc), in every cell, extra cells included.

  powerLawProfile    u = U_inf (h / H)^n below the profile height H, U_inf above
  powerLawProfile2   u_p = u_tau / 0.4 ln(Re_tau r), r the distance to the nearer channel wall
                     over the half height, u_tau = mu Re_tau / (rho h_half)
  logLawProfile      u = u_*, u_p = u_*,p / kappa ln((h - d) / z0)
  gaussianTemperature  T = 300 K + A exp(-(x-x0)^2 / 2 sx^2 - (y-y0)^2 / 2 sy^2) in the
                     interior cells, before the EOS sets pressure and sound speed (at the
                     geometry's density: the pulse starts as a pressure peak)
  vortices           Gaussian vortices about an axis (Poinsot & Lele's, Uintah's m_vortices), in
                     the interior cells within a radius R of the axis:
                     u_j -= C z A / (rho R^2), u_k += C y A / (rho R^2), A = exp(-(y^2 + z^2) / 2 R^2),
                     press_CC = 101325 + rho C^2 A / R^2 (each vortex overwrites it); the
                     pressure is then not the EOS pressure of rho and T (Uintah's
                     doesComputePressure), and the sound speed takes it
h is the cell centre's height along <verticalDir> above the domain floor; outside the
domain's height the velocity is 0 (power laws). Uintah applies them in reverse reading order.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .eos import eos_press_eos
from .specific_heat import cv_at

POWER_LAW, POWER_LAW2, LOG_LAW = 0, 1, 2
ORDER = ("logLawProfile", "powerLawProfile", "powerLawProfile2")     # Uintah's reading order
ACCEPTED = ORDER + ("gaussianTemperature", "vortices")
KNOWN = ("vortexPairs", "manufacturedSolution", "counterflow", "DNS_Moser") + ACCEPTED


@njit(cache=True)
def apply_profile(vel, kind, vdir, pdir, u_vec, p, anchor, dx, olo, ohi, c0):
    """Overwrite vel in the cells olo..ohi (local; c0 the global index of local 0) with a
    profile; p: [floor, top, H or h_half, n or Re_tau or z0, u_tau or kappa, d]."""
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                g = (i + c0[0], j + c0[1], k + c0[2])
                y = anchor[vdir] + (g[vdir] + 0.5) * dx[vdir]
                floor, top = p[0], p[1]
                if kind == POWER_LAW:
                    ratio = min(max((y - floor) / (p[2] - floor), 0.0), 1.0)
                    f = ratio ** p[3] if floor < y < p[2] else 1.0
                    for c in range(3):
                        vel[i, j, k, c] = u_vec[c] * f if floor <= y <= top else 0.0
                elif kind == POWER_LAW2:
                    if y < floor or y > top:
                        for c in range(3):
                            vel[i, j, k, c] = 0.0
                        continue
                    half = p[2]
                    ratio = (y - floor) / half if y < half else 1.0 - (y - half) / half
                    ratio = min(max(ratio, 0.0), 1.0)
                    vel[i, j, k, pdir] = p[4] / 0.4 * np.log(ratio * p[3])
                else:
                    for c in range(3):
                        vel[i, j, k, c] = u_vec[c]
                    vel[i, j, k, pdir] = u_vec[pdir] / p[4] * np.log((y - p[5]) / p[3])


@njit(cache=True)
def gaussian_temperature(temp, amp, origin, sx, sy, anchor, dx, lo, hi, c0):
    """Uintah's gaussianTemperature: T = 300 + A exp(-(a + b)) at the cell centres."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                x = anchor[0] + (i + c0[0] + 0.5) * dx[0]
                y = anchor[1] + (j + c0[1] + 0.5) * dx[1]
                a = (x - origin[0]) * (x - origin[0]) / (2.0 * sx * sx + 1e-100)
                b = (y - origin[1]) * (y - origin[1]) / (2.0 * sy * sy + 1e-100)
                temp[i, j, k] = 300.0 + amp * np.exp(-(a + b))


@njit(cache=True)
def add_vortices(vel, press, rho, axes, origins, strengths, radii, anchor, dx, lo, hi, c0):
    """Uintah's vortices, in order, on the interior cells lo..hi (c0: the global index of local 0);
    axes[v] = (j, k), the two directions across vortex v's axis."""
    p_ref = 101325.0                    # Uintah's assumed reference pressure
    for v in range(axes.shape[0]):
        a, b = axes[v, 0], axes[v, 1]
        r_sqr = radii[v] * radii[v]
        c1 = strengths[v]
        for i in range(lo[0], hi[0]):
            for j in range(lo[1], hi[1]):
                for k in range(lo[2], hi[2]):
                    g = (i + c0[0], j + c0[1], k + c0[2])
                    y = anchor[a] + (g[a] + 0.5) * dx[a] - origins[v, a]
                    z = anchor[b] + (g[b] + 0.5) * dx[b] - origins[v, b]
                    if np.sqrt(y * y + z * z) <= radii[v]:
                        amp = np.exp(-(y * y + z * z) / (2.0 * r_sqr))
                        press[i, j, k] = p_ref + rho[i, j, k] * (c1 * c1 / r_sqr) * amp
                        vel[i, j, k, a] = vel[i, j, k, a] - (c1 * z / (rho[i, j, k] * r_sqr)) * amp
                        vel[i, j, k, b] = vel[i, j, k, b] + (c1 * y / (rho[i, j, k] * r_sqr)) * amp


@njit(cache=True)
def speed_sound_at_pressure(sp_vol, temp, press, out, lo, hi, code, params, cv, gamma):
    """Uintah's initial c^2 = dp/drho + dp/de p / rho^2 with the cells' press_CC (the vortices'),
    not the EOS pressure, over the cells lo..hi."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                rho = 1.0 / sp_vol[i, j, k]
                _, dp_drho, dp_de = eos_press_eos(code, params, rho, temp[i, j, k], cv_at(cv, i, j, k), gamma)
                out[i, j, k] = np.sqrt(dp_drho + dp_de * press[i, j, k] / (rho * rho))


class CustomInitialization:
    """The profiles of one <customInitialization> block, applied to one material's vel_CC."""

    def __init__(self, node, level):
        self.level = level
        self.methods = []
        for child in node.children():
            if child.tag not in ACCEPTED:
                accepted = ", ".join(ACCEPTED)
                raise child.error(f"<{child.tag}> is not available; accepted: {accepted}"
                                  if child.tag in KNOWN else f"unsupported tag <{child.tag}>; accepted: {accepted}")
        for tag in ORDER:
            c = node.child(tag)
            if c is not None:
                self.methods.append((tag, c))
        self.vortices = None
        vn = node.child("vortices")
        if vn is not None:
            axes, origins, strengths, radii = [], [], [], []
            for vx in vn.children("vortex"):
                axis = vx.get("axis", "str").strip().upper()
                if axis not in ("X", "Y", "Z"):
                    raise vx.child("axis").error(f"axis '{axis}' is not available; accepted: X, Y, Z")
                axes.append({"X": (1, 2), "Y": (0, 2), "Z": (0, 1)}[axis])
                origins.append(vx.get("origin", "vector"))
                strengths.append(vx.get("strength", "float"))
                radii.append(vx.get("radius", "float", above=0.0))
            self.vortices = (np.array(axes, dtype=np.int64).reshape(-1, 2),
                             np.array(origins, dtype=np.float64).reshape(-1, 3),
                             np.array(strengths, dtype=np.float64), np.array(radii, dtype=np.float64))
        self.gauss = None
        g = node.child("gaussianTemperature")
        if g is not None:
            self.gauss = (g.get("amplitude", "float"), np.array(g.get("origin", "vector"), dtype=np.float64),
                          g.get("spread_x", "float"), g.get("spread_y", "float"))

    def _vdir(self, c, tag):
        v = c.get(tag, "int", at_least=0)
        if v > 2:
            raise c.child(tag).error(f"{tag} must be 0, 1 or 2 (x, y, z)")
        return v

    def resolve(self, material):
        """The profiles' parameters for one ICE material (viscosity, first object's density)."""
        lv = self.level
        out = []
        for tag, c in self.methods:
            if tag == "powerLawProfile":
                vdir = self._vdir(c, "verticalDir")
                u = np.array(c.get("U_infinity", "vector"), dtype=np.float64)
                n = c.get("exponent", "float")
                floor, top = lv.anchor[vdir], lv.upper[vdir]
                H = c.get("profileHeight", "float", top)
                out.append((POWER_LAW, vdir, 0, u, np.array([floor, top, H, n, 0.0, 0.0])))
            elif tag == "powerLawProfile2":
                vdir = self._vdir(c, "verticalDir")
                pdir = self._vdir(c, "principalDir")
                re_tau = c.get("Re_tau", "float", above=0.0)
                half = c.get("halfChannelHeight", "float", above=0.0)
                floor = c.get("channelFloor", "float", lv.anchor[vdir])
                top = c.get("channelCeiling", "float", lv.upper[vdir])
                rho = material.objects[0][1]["density"]
                u_tau = material.viscosity * re_tau / (rho * half)
                out.append((POWER_LAW2, vdir, pdir, np.zeros(3), np.array([floor, top, half, re_tau, u_tau, 0.0])))
            else:
                vdir = self._vdir(c, "verticalDir")
                pdir = self._vdir(c, "principalFlowDir")
                u = np.array(c.get("frictionVel", "vector"), dtype=np.float64)
                z0 = c.get("roughness", "float", above=0.0)
                kappa = c.get("vonKarmanConstant", "float", 0.4, above=0.0)
                d = c.get("d", "float", lv.anchor[vdir])
                out.append((LOG_LAW, vdir, pdir, u, np.array([0.0, 0.0, 0.0, z0, kappa, d])))
        return out[::-1]                 # Uintah applies them in reverse order

    def temperature(self, temp, lo, hi, c0):
        """gaussianTemperature on the interior cells lo..hi (c0: the global index of local 0)."""
        if self.gauss is not None:
            amp, origin, sx, sy = self.gauss
            gaussian_temperature(temp, amp, origin, sx, sy, self.level.anchor, self.level.dx, lo, hi, c0)

    def add_vortices(self, vel, press, rho, lo, hi, c0):
        """vortices on the interior cells lo..hi, after the profiles (Uintah's reverse order)."""
        if self.vortices is not None:
            add_vortices(vel, press, rho, *self.vortices, self.level.anchor, self.level.dx, lo, hi, c0)

    def apply(self, vel, profiles, olo, ohi, c0):
        lv = self.level
        for kind, vdir, pdir, u, p in profiles:
            apply_profile(vel, kind, vdir, pdir, u, p, lv.anchor, lv.dx, olo, ohi, c0)
