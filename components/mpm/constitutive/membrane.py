"""Elastic membrane / string material points in 2D (004 sec. 3.2).

The strain increment dt*D (004 eq. 13) is projected on the particle's unit
tangent t:  d_eps_tt = t.D.t dt;  sigma_tt += E' d_eps_tt and the stress is
projected back:  sigma = sigma_tt t (x) t  (no other components).
E' = E for a uniaxial string ('uniaxial'), E/(1-nu^2) for a membrane with
zero out-of-plane strain ('plane').  The tangent is convected with the
incremental deformation, t <- F_inc t / |F_inc t|, F_inc = F_new F_old^-1;
the thickness h follows the lateral strain (-nu or -nu/(1-nu) times
d_eps_tt), and the particle volume V_new = V |F_inc t| h_new/h.

Axisymmetric (``hoop``; the polygon is a meridian in (r, z), 'plane' formulation): the
membrane of revolution is in biaxial plane stress, its second in-surface direction the hoop
one, with the hoop strain increment d_eps_hh = L_thth dt = dr / r:
    sigma_tt += E' (d_eps_tt + nu d_eps_hh),   sigma_hh += E' (d_eps_hh + nu d_eps_tt),
    sigma = sigma_tt t (x) t + sigma_hh e_th (x) e_th,
the thickness follows -nu/(1-nu) (d_eps_tt + d_eps_hh) and V_new = V |F_inc t| (r_new/r) h_new/h.

Tags (Uintah ``type="membrane"``): ``bulk_modulus``, ``shear_modulus``
(E, nu derived), optional ``formulation`` ('uniaxial' | 'plane').
``energy`` receives the stress-work INCREMENT.  c = sqrt(E' V/m).
Tangents from the consecutive numbering of the points: ``chain_tangents`` at the start;
in the component, each step's t_old is taken from the neighbours ID -+ 1 (owned or ghost
particles, MPM::membraneTangents, 004 sec. 3.2), the convected one where none is found.
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, inv3, max_wavespeed

ENERGY_IS_INCREMENT = True


@dataclass(frozen=True)
class Params:
    bulk_modulus: float
    shear_modulus: float
    formulation: str = "uniaxial"

    @classmethod
    def from_ups(cls, d):
        return cls(_get(d, "bulk_modulus"), _get(d, "shear_modulus"),
                   str(d.get("formulation", "uniaxial")).strip())

    @classmethod
    def from_young(cls, E, nu, formulation="uniaxial"):
        return cls(E / (3.0 * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu)), formulation)

    @property
    def young(self):
        K, G = self.bulk_modulus, self.shear_modulus
        return 9.0 * K * G / (3.0 * K + G)

    @property
    def poisson(self):
        K, G = self.bulk_modulus, self.shear_modulus
        return (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G))

    def moduli(self):
        """(E', lateral strain ratio) of the chosen formulation."""
        E, nu = self.young, self.poisson
        if self.formulation == "plane":
            return E / (1.0 - nu * nu), nu / (1.0 - nu)
        if self.formulation == "uniaxial":
            return E, nu
        raise ValueError(f"membrane formulation {self.formulation!r}")


@njit(cache=True)
def kernel(Eeff, lat, nu, hoop, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new,
           t_old, t_new, h_old, h_new, vol_new, energy):
    ws = np.zeros(3)
    Fi = np.empty((3, 3))
    Finc = np.empty((3, 3))
    for p in range(L.shape[0]):
        t0, t1, t2 = t_old[p, 0], t_old[p, 1], t_old[p, 2]
        deps = 0.0
        stt = 0.0
        for i in range(3):
            ti = t_old[p, i]
            for j in range(3):
                deps += ti * 0.5 * (L[p, i, j] + L[p, j, i]) * t_old[p, j]
                stt += ti * stress_old[p, i, j] * t_old[p, j]
        deps *= dt
        if hoop:      # membrane of revolution: biaxial plane stress with the hoop strain dr/r
            deph = L[p, 2, 2] * dt
            shh = stress_old[p, 2, 2]
            snew = stt + Eeff * (deps + nu * deph)
            shh_new = shh + Eeff * (deph + nu * deps)
        else:
            snew = stt + Eeff * deps  # tangential Hooke's law on projected eq. 13 strain
        inv3(F_old[p], Fi)
        for i in range(3):
            for j in range(3):
                Finc[i, j] = F_new[p, i, 0] * Fi[0, j] + F_new[p, i, 1] * Fi[1, j] \
                    + F_new[p, i, 2] * Fi[2, j]
        u0 = Finc[0, 0] * t0 + Finc[0, 1] * t1 + Finc[0, 2] * t2
        u1 = Finc[1, 0] * t0 + Finc[1, 1] * t1 + Finc[1, 2] * t2
        u2 = Finc[2, 0] * t0 + Finc[2, 1] * t1 + Finc[2, 2] * t2
        lam = np.sqrt(u0 * u0 + u1 * u1 + u2 * u2)
        t_new[p, 0] = u0 / lam
        t_new[p, 1] = u1 / lam
        t_new[p, 2] = u2 / lam
        for i in range(3):
            for j in range(3):
                stress_new[p, i, j] = snew * t_new[p, i] * t_new[p, j]
        if hoop:
            stress_new[p, 2, 2] += shh_new
            h_new[p] = h_old[p] * (1.0 - lat * (deps + deph))
            vol_new[p] = vol[p] * lam * Finc[2, 2] * (1.0 - lat * (deps + deph))
            energy[p] = 0.5 * ((stt + snew) * deps + (shh + shh_new) * deph) * vol[p]
        else:
            h_new[p] = h_old[p] * (1.0 - lat * deps)
            vol_new[p] = vol[p] * lam * (1.0 - lat * deps)
            energy[p] = 0.5 * (stt + snew) * deps * vol[p]
        max_wavespeed(ws, np.sqrt(Eeff * vol[p] / mass[p]), vel, p)
    return ws


@njit(cache=True)
def chain_tangents(px, closed, t):
    """Unit tangents of an ordered chain of points (central differences,
    one-sided at the ends of an open chain)."""
    n = px.shape[0]
    for p in range(n):
        a = p - 1
        b = p + 1
        if closed:
            a %= n
            b %= n
        else:
            a = max(a, 0)
            b = min(b, n - 1)
        d0 = px[b, 0] - px[a, 0]
        d1 = px[b, 1] - px[a, 1]
        d2 = px[b, 2] - px[a, 2]
        s = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
        t[p, 0] = d0 / s
        t[p, 1] = d1 / s
        t[p, 2] = d2 / s


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
           t_old, t_new, h_old, h_new, vol_new, hoop=False):
    """Update stress, tangent, thickness and volume; returns wave speed (3,). hoop: the
    axisymmetric membrane of revolution (biaxial, 'plane' formulation)."""
    Eeff, lat = params.moduli()
    return kernel(Eeff, lat, params.poisson, bool(hoop), L, F_old, F_new, vol, mass, vel, dt,
                  stress_old, stress_new, t_old, t_new, h_old, h_new, vol_new, energy)
