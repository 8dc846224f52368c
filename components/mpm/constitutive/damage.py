"""Uintah's damage models of an MPM material: ``<damage_model type="Brittle">``.

The damage model is a sibling of ``<constitutive_model>`` in the material (Uintah's
DamageModelFactory); after the constitutive model has computed p.stress+, it scales it
down.  Uintah asks for an ``<erosion algorithm="...">`` beside any Brittle damage model and
refuses the deck without one; the algorithm acts only on localized particles, which
Brittle damage never makes, so it changes nothing here.

Brittle (Uintah's BrittleDamage; Oliver et al.'s isotropic softening): tags
``brittle_damage_initial_threshold`` (r0, Pa^1/2), ``brittle_damage_fracture_energy``
(G_f), ``brittle_damage_constant_D`` (D), ``brittle_damage_max_damage_increment`` (the most
damage may grow in a step), ``brittle_damage_allowRecovery``,
``brittle_damage_recoveryCoeff``, ``brittle_damage_printDamage``; E from the constitutive
model's bulk and shear moduli, E = 9 K G / (3 K + G).  State: p.epsf (the energy threshold
r, r0 at the start) and p.damage (d, 0).  Each step, with the new F, V and stress:

    in tension (tr sigma > 0): e = (I - (F F^T)^-1)/2, tau = sqrt(E) max eig(e)
        tau > r:  C = r0 V^(1/3) (1 + D) ln(1 + D) / (G_f D),
                  d = 0.999/D ((1 + D)/(1 + D exp(-C (tau - r0))) - 1)  (at most d_old + the
                  increment), r = tau, sigma *= 1 - d
        else, once damaged: sigma *= 1 - d_old
    in compression, once damaged: sigma *= 1 - d_old

(with recovery a damaged particle's stress is also scaled by the recovery coefficient and
its damage flagged negative, as Uintah's; Uintah skips the factor 1 - d of compression when
printing).  Uintah leaves its particle loop at the first undamaged particle in compression
(a ``return``); each particle is updated here, which is the same for a lone damaged particle.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

TYPES = ("Brittle",)
EROSION = ("none", "AllowNoTension", "ZeroStress", "AllowNoShear", "PreserveStress")


@dataclass(frozen=True)
class Brittle:
    r0: float                      # brittle_damage_initial_threshold
    Gf: float                      # brittle_damage_fracture_energy
    D: float                       # brittle_damage_constant_D
    max_increment: float           # brittle_damage_max_damage_increment
    allow_recovery: bool
    recovery_coeff: float
    print_damage: bool
    youngs: float                  # E = 9 K G / (3 K + G) of the constitutive model

    STATE = ("p.epsf", "p.damage")

    def initial_state(self, n):
        """p.epsf = r0, p.damage = 0 (Uintah's initializeLabels)."""
        return np.full(n, self.r0), np.zeros(n)

    def apply(self, F_new, vol_new, stress_new, old, new):
        """Scale p.stress+ by the damage; (p.epsf, p.damage) old -> new."""
        (r_old, d_old), (r_new, d_new) = old, new
        brittle_kernel(self.r0, self.Gf, self.D, self.max_increment, self.allow_recovery, self.recovery_coeff,
                       self.print_damage, self.youngs, F_new, vol_new, stress_new, r_old, d_old, r_new, d_new)


BRITTLE_TAGS = {"brittle_damage_initial_threshold": 57.0, "brittle_damage_fracture_energy": 11.2,
                "brittle_damage_constant_D": 0.1, "brittle_damage_max_damage_increment": 0.1,
                "brittle_damage_recoveryCoeff": 1.0}


def read(material, cm):
    """The material's damage model (None without a <damage_model>), Uintah's defaults."""
    dm = material.child("damage_model")
    if dm is None:
        return None
    kind = dm.attr("type", choices=TYPES)
    er = material.child("erosion")
    if er is None:
        raise dm.error(f'a <damage_model type="{kind}"> needs an <erosion algorithm="..."> in its material '
                       "(Uintah: an erosion model must be specified when a damage model is used)")
    er.attr("algorithm", default="none", choices=EROSION)
    if er.has("char_time"):
        er.get("char_time", above=0.0)
    v = {t: dm.get(t, "float", d) for t, d in BRITTLE_TAGS.items()}
    for t in ("brittle_damage_fracture_energy", "brittle_damage_constant_D"):
        if v[t] <= 0.0:
            raise dm.child(t).error(f"<{t}> must be positive")
    if not 0.0 <= v["brittle_damage_recoveryCoeff"] <= 1.0:
        raise dm.child("brittle_damage_recoveryCoeff").error("<brittle_damage_recoveryCoeff> must lie in [0, 1]")
    K, G = cm.get("bulk_modulus", above=0.0), cm.get("shear_modulus", at_least=0.0)
    return Brittle(v["brittle_damage_initial_threshold"], v["brittle_damage_fracture_energy"],
                   v["brittle_damage_constant_D"], v["brittle_damage_max_damage_increment"],
                   dm.get("brittle_damage_allowRecovery", "bool", False), v["brittle_damage_recoveryCoeff"],
                   dm.get("brittle_damage_printDamage", "bool", False), 9.0 * K * G / (3.0 * K + G))


@njit(cache=True, inline="always")
def max_eigenvalue_sym(a00, a11, a22, a01, a02, a12):
    """The largest eigenvalue of a symmetric 3x3 matrix (the trigonometric solution of its cubic)."""
    q = (a00 + a11 + a22) / 3.0
    p1 = a01 * a01 + a02 * a02 + a12 * a12
    b00, b11, b22 = a00 - q, a11 - q, a22 - q
    p2 = b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * p1
    if p2 <= 1e-300:
        return q
    p = np.sqrt(p2 / 6.0)
    ip = 1.0 / p
    c00, c11, c22, c01, c02, c12 = b00 * ip, b11 * ip, b22 * ip, a01 * ip, a02 * ip, a12 * ip
    r = 0.5 * (c00 * (c11 * c22 - c12 * c12) - c01 * (c01 * c22 - c12 * c02) + c02 * (c01 * c12 - c11 * c02))
    r = min(1.0, max(-1.0, r))
    return q + 2.0 * p * np.cos(np.arccos(r) / 3.0)


@njit(cache=True)
def brittle_kernel(r0, Gf, D, max_inc, recovery, rc, printing, E, F, vol, stress, r_old, d_old, r_new, d_new):
    """Brittle damage of every particle (module docstring); scales stress in place."""
    for p in range(F.shape[0]):
        r_new[p] = r_old[p]
        d = d_old[p]
        d_new[p] = d
        if stress[p, 0, 0] + stress[p, 1, 1] + stress[p, 2, 2] < 0.0:      # compression
            if d <= 0.0:
                continue
            if recovery:
                stress[p] *= rc
                d_new[p] = -d
            if not printing:
                stress[p] *= 1.0 - d
            continue
        # b^-1 with b = F F^T: the Eulerian (Almansi) strain e = (I - b^-1)/2
        b00 = F[p, 0, 0] ** 2 + F[p, 0, 1] ** 2 + F[p, 0, 2] ** 2
        b11 = F[p, 1, 0] ** 2 + F[p, 1, 1] ** 2 + F[p, 1, 2] ** 2
        b22 = F[p, 2, 0] ** 2 + F[p, 2, 1] ** 2 + F[p, 2, 2] ** 2
        b01 = F[p, 0, 0] * F[p, 1, 0] + F[p, 0, 1] * F[p, 1, 1] + F[p, 0, 2] * F[p, 1, 2]
        b02 = F[p, 0, 0] * F[p, 2, 0] + F[p, 0, 1] * F[p, 2, 1] + F[p, 0, 2] * F[p, 2, 2]
        b12 = F[p, 1, 0] * F[p, 2, 0] + F[p, 1, 1] * F[p, 2, 1] + F[p, 1, 2] * F[p, 2, 2]
        det = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02)
        i00, i11, i22 = (b11 * b22 - b12 * b12) / det, (b00 * b22 - b02 * b02) / det, (b00 * b11 - b01 * b01) / det
        i01, i02, i12 = (b02 * b12 - b01 * b22) / det, (b01 * b12 - b02 * b11) / det, (b01 * b02 - b00 * b12) / det
        eps = max_eigenvalue_sym(0.5 * (1.0 - i00), 0.5 * (1.0 - i11), 0.5 * (1.0 - i22), -0.5 * i01, -0.5 * i02,
                                 -0.5 * i12)
        tau = np.sqrt(E * eps * eps)
        if tau > r_old[p]:
            C = r0 * np.cbrt(vol[p]) * (1.0 + D) / (Gf * D) * np.log(1.0 + D)
            dn = 0.999 / D * ((1.0 + D) / (1.0 + D * np.exp(-C * (tau - r0))) - 1.0)
            if dn - d > max_inc:
                dn = d + max_inc
            r_new[p] = tau
            d_new[p] = dn
            stress[p] *= 1.0 - dn
        elif d != 0.0:
            if recovery:
                stress[p] *= rc
                d_new[p] = -d
            else:
                stress[p] *= 1.0 - d


# the constitutive models a damage model may follow: their stress needs no temperature, and
# their state (if any) is what their own update takes
MODELS = ("comp_neo_hook", "comp_mooney_rivlin", "hypo_elastic", "comp_neo_hook_plastic", "UCNH")


class Damaged:
    """A constitutive model module followed by a damage model: its update, then the damage's
    on the new stress; the state is the model's (n_model arrays) then the damage's."""

    def __init__(self, model, n_model, damage):
        self.model, self.n_model, self.damage = model, n_model, damage

    def __getattr__(self, name):           # the model's constants (ENERGY_IS_INCREMENT, Params ...)
        if name in ("state_of", "STATE", "read_params"):
            raise AttributeError(name)
        return getattr(self.model, name)

    def initial_state(self, params, n, temperature=None):
        own = ()
        if self.n_model:
            own = self.model.initial_state(params, n, temperature)
            own = own if isinstance(own, tuple) else (own,)
        return own + self.damage.initial_state(n)

    def update(self, params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old, new):
        k = self.n_model
        if k == 0:
            ws = self.model.update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy)
        else:
            mo, mn = (old[0], new[0]) if k == 1 else (old[:k], new[:k])
            ws = self.model.update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
                                   mo, mn)
        self.damage.apply(F_new, vol, stress_new, old[k:], new[k:])
        return ws
