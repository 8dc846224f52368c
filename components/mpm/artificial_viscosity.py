"""Artificial bulk viscosity of the MPM solids (Uintah's <MPM><artificial_viscosity>).

Uintah's ConstitutiveModel::artificialBulkViscosity, which its models call at the end of
computeStressTensor: a particle in compression (tr D < 0) gets the bulk viscous pressure

    q = rho (A1 |c_bulk tr D dx| + A2 (tr D dx)^2),   c_bulk = sqrt(K/rho),  rho = rho_0/J,

with dx the mean cell size (dx + dy + dz)/3 (visco_scram: K = 2G(1 + nu)/(3(1 - 2nu)), its
parameters not randomized; comp_mooney_rivlin: K = 4 (C1 + C2 I2)/J of the current state and
rho = m/V, as Uintah's CompMooneyRivlin), A1 = <artificial_viscosity_coeff1> (0.2) and
A2 = <artificial_viscosity_coeff2> (2.0); q = 0 in expansion. p.q is carried to the next
step, whose internal force uses sigma - q I (computeInternalForce; g.stressFS keeps sigma).
With <artificial_viscosity_heating> (on with the viscosity unless the deck says false)
elastic_plastic with sub-models also turns the viscous work into heat and energy:
p.dTdt += -q tr D/(rho c_p), p.energy -= q (V^{n+1} - V^n)/m. The other models Uintah
gives a q (hypo_elastic, comp_neo_hook, comp_neo_hook_plastic, UCNH, comp_mooney_rivlin) have no heating; a
rigid material's q is 0. Nothing here runs unless a deck turns the viscosity on.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .constitutive import comp_mooney_rivlin, plasticity_kernels as pk
from .constitutive._common import det3

# the models Uintah's artificial viscosity reaches, and the bulk modulus of c_bulk
BULK = {"elastic_plastic_hp": lambda p: p.bulk_modulus, "hypo_elastic": lambda p: p.K,
        "comp_neo_hook": lambda p: p.bulk_modulus, "comp_neo_hook_plastic": lambda p: p.bulk_modulus,
        "UCNH": lambda p: p.bulk_modulus, "visco_scram": lambda p: p.bulk_modulus, "rigid": None,
        "ArenaSoil": lambda p: 40.0e9 * p.prm[7] * p.prm[15]}    # arena: the initial b0 K_s (Uintah: the current K)
# the models whose c_bulk follows the particle's state: per-particle K from (params, F^{n+1})
CURRENT_BULK = {"comp_mooney_rivlin": lambda p, F, K: comp_mooney_rivlin.viscosity_bulk_modulus(
    p.he_constant_1, p.he_constant_2, F, K)}
HEATING = ("elastic_plastic_hp",)


@njit(cache=True)
def bulk_viscosity(L, F_new, rho0, K, dx_ave, A1, A2, q):
    """q_p of each particle from tr L (= tr D) and rho = rho_0/det F^{n+1} (Uintah's
    artificialBulkViscosity; Wilkins' linear + quadratic form)."""
    for p in range(L.shape[0]):
        Dkk = L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]
        q[p] = 0.0
        if Dkk < 0.0:
            rho = rho0 / det3(F_new[p])
            c_bulk = math.sqrt(K / rho)
            q[p] = (A1 * abs(c_bulk * Dkk * dx_ave) + A2 * (Dkk * Dkk * dx_ave * dx_ave)) * rho


@njit(cache=True)
def bulk_viscosity_current(L, rho, K, dx_ave, A1, A2, q):
    """q_p with each particle's own K and rho (a model whose c_bulk follows the state)."""
    for p in range(L.shape[0]):
        Dkk = L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]
        q[p] = 0.0
        if Dkk < 0.0:
            c_bulk = math.sqrt(K[p] / rho[p])
            q[p] = (A1 * abs(c_bulk * Dkk * dx_ave) + A2 * (Dkk * Dkk * dx_ave * dx_ave)) * rho[p]


@njit(cache=True)
def viscous_heating(q, L, F_old, F_new, rho0, mass, vol_new, T, cp_code, cpp, cp0, dTdt, e_new):
    """The viscous work to heat of elastic_plastic_hp (ElasticPlasticHP): dT/dt += -q tr D/(rho c_p)
    with c_p at the step's start temperature, specific energy e -= q dV/m."""
    for p in range(q.shape[0]):
        if q[p] == 0.0:
            continue
        Dkk = L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]
        rho = rho0 / det3(F_new[p])
        cp = pk.specific_heat(cp_code, cpp, cp0, T[p])
        dTdt[p] += (-q[p] * Dkk / rho) / cp
        vol_old = mass[p] / rho0 * det3(F_old[p])
        e_new[p] -= q[p] * (vol_new[p] - vol_old) / mass[p]


@njit(cache=True)
def stress_less_q(stress, q, out):
    """out = sigma - q I: the stress of the internal force (Uintah's computeInternalForce)."""
    for p in range(stress.shape[0]):
        for i in range(3):
            for j in range(3):
                out[p, i, j] = stress[p, i, j]
            out[p, i, i] -= q[p]


class ArtificialViscosity:
    """The deck's coefficients and, per material, what its model needs (None: q = 0)."""

    def __init__(self, mpm_node, flags, materials, dx):
        self.A1 = flags["artificial_viscosity_coeff1"]
        self.A2 = flags["artificial_viscosity_coeff2"]
        given = mpm_node is not None and mpm_node.has("artificial_viscosity_heating")
        self.heating = flags["artificial_viscosity_heating"] if given else True
        self.dx_ave = (dx[0] + dx[1] + dx[2]) / 3.0
        self.bulk = []
        for mat in materials:
            if mat.model_name in CURRENT_BULK:
                self.bulk.append(None if mat.is_rigid else CURRENT_BULK[mat.model_name])
                continue
            if mat.model_name not in BULK:
                raise mpm_node.child("artificial_viscosity").error(
                    f"artificial viscosity with constitutive_model type=\"{mat.model_name}\" (material "
                    f"{mat.index}) is not implemented; accepted models: {', '.join(list(BULK) + list(CURRENT_BULK))}")
            f = BULK[mat.model_name]
            self.bulk.append(None if f is None or mat.is_rigid else float(f(mat.params)))

    def q(self, m, mat, Lg, F_new, mass, vol_new):
        """p.q of material m's particles (mass and V^{n+1}: the density of a state-dependent K)."""
        q = np.zeros(len(F_new))
        bulk = self.bulk[m]
        if callable(bulk):
            K = np.empty(len(F_new))
            bulk(mat.params, F_new, K)
            bulk_viscosity_current(Lg, mass / vol_new, K, self.dx_ave, self.A1, self.A2, q)
        elif bulk is not None:
            bulk_viscosity(Lg, F_new, mat.density, bulk, self.dx_ave, self.A1, self.A2, q)
        return q

    def heat(self, mat, q, Lg, F_old, F_new, mass, vol_new, T, dTdt, e_new):
        """elastic_plastic_hp's viscous heating (p.dTdt, p.energy), if the deck has it."""
        if self.heating and mat.model_name in HEATING:
            P = mat.params
            viscous_heating(q, Lg, F_old, F_new, P.density, mass, vol_new, T, P.codes[4], P.cp, P.specific_heat,
                            dTdt, e_new)
