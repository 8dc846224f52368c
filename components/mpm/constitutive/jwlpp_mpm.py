"""Uintah's JWLppMPM (``<constitutive_model type="jwlpp_mpm">``): a reacting explosive whose
particles carry a burned fraction f (p.progressF; p.progressdelF its last increment).

The pressure mixes the unreacted Murnaghan solid and the JWL products at the particle's J:

    p_M = (J^-n - 1)/(n K)                      (murnaghan_K is the compressibility 1/K0)
    p_JWL = A exp(-R1 J) + B exp(-R2 J) + C J^-(1 + omega)
    p = (1 - f) p_M + f p_JWL,  sigma = -p I

Above the ignition pressure (the pressure p_old of the step's start) and while f is below
max_burned_fraction, the step is cut into ceil(dt / max_burn_timestep_size) sub-steps, J going
geometrically from J_old to J; each solves by Newton's iterations (or, with
doFastStressCompute, one backward-Euler update) the backward-Euler burn with the pressure mix

    f - f_old - G (1 - f) p^b dt_sub = 0,  p - (1 - f) p_M - f p_JWL = 0

(tolerance_for_Newton_iterations, max_number_of_Newton_iterations), f capped at
max_burned_fraction.  Below it f stays and p is the mix.  useInitialStress with
initial_pressure p0: sigma = -p0 I and F = (1 + n K p0)^(-1/(3n)) I at the start (the Murnaghan
J of p0); the particle volume stays the geometric one, as Uintah's.  The wave speed is
sqrt((rho/rho0)^(n-1) / (K rho0)), rho = rho0/J (the first step's: rho = m/V).  No strain
energy (Uintah's model adds none).  A particle whose J is not positive gets zero stress and
keeps its state (Uintah also flags it localized, -999, which pysus does not carry here).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import det3, max_wavespeed

ENERGY_IS_INCREMENT = False
STATE = ("p.progressF", "p.progressdelF")
TAGS = {                       # tag: (field, default; None = required)
    "ignition_pressure": ("ignition_pressure", None), "murnaghan_K": ("K", None), "murnaghan_n": ("n", None),
    "jwl_A": ("A", None), "jwl_B": ("B", None), "jwl_C": ("C", None), "jwl_R1": ("R1", None),
    "jwl_R2": ("R2", None), "jwl_om": ("omega", None), "reaction_G": ("G", None), "reaction_b": ("b", None),
    "max_burn_timestep_size": ("max_burn_timestep", 1.0e-12), "max_burned_fraction": ("max_burned_frac", 1.0),
    "tolerance_for_Newton_iterations": ("newton_tol", 1.0e-3),
}


@dataclass(frozen=True)
class Params:
    ignition_pressure: float
    K: float
    n: float
    A: float
    B: float
    C: float
    R1: float
    R2: float
    omega: float
    G: float
    b: float
    max_burn_timestep: float
    max_burned_frac: float
    newton_tol: float
    newton_max: int
    fast: bool
    initial_pressure: float       # 0 without useInitialStress
    density: float


def read_params(cm, material, props):
    """The model's tags (Uintah's names); jwl_rho0 is read and, as in Uintah, the material's
    density is rho0; useTaylorSeriesForDefGrad and num_taylor_terms are read (Uintah's model
    does not use them)."""
    v = {field: (cm.get(tag) if d is None else cm.get(tag, "float", d)) for tag, (field, d) in TAGS.items()}
    for tag in ("murnaghan_K", "murnaghan_n", "max_burn_timestep_size"):
        if v[TAGS[tag][0]] <= 0.0:
            raise cm.child(tag).error(f"<{tag}> must be positive")
    cm.get("jwl_rho0", "float", 0.0)
    cm.get("useTaylorSeriesForDefGrad", "bool", False)
    cm.get("num_taylor_terms", "int", 10)
    p0 = cm.get("initial_pressure", "float", 0.0) if cm.get("useInitialStress", "bool", False) else 0.0
    return Params(**v, newton_max=cm.get("max_number_of_Newton_iterations", "int", 20),
                  fast=cm.get("doFastStressCompute", "bool", False), initial_pressure=p0,
                  density=props["density"])


def initial_state(params, n, temperature=None):
    """p.progressF = p.progressdelF = 0."""
    return np.zeros(n), np.zeros(n)


def initial_deformation(params, n):
    """(F, stress) at the start: the initial pressure's Murnaghan F and -p0 I (useInitialStress),
    else I and 0."""
    p0 = params.initial_pressure
    F = np.zeros((n, 3, 3))
    s = np.zeros((n, 3, 3))
    c = (1.0 + params.K * params.n * p0) ** (-1.0 / (3.0 * params.n)) if p0 != 0.0 else 1.0
    for i in range(3):
        F[:, i, i] = c
        s[:, i, i] = -p0
    return F, s


def initial_J(params):
    """det F at the start (the volume stays the geometric one: V = m J / (rho0 J0) after)."""
    return initial_deformation(params, 1)[0][0, 0, 0] ** 3


@njit(cache=True, inline="always")
def _murnaghan(J, K, n):
    return (J ** -n - 1.0) / (n * K)


@njit(cache=True, inline="always")
def _jwl(J, A, B, C, R1, R2, omega):
    return A * np.exp(-R1 * J) + B * np.exp(-R2 * J) + C * J ** -(1.0 + omega)


@njit(cache=True)
def burn(P, J_old, J, f_old0, p_old0, dt):
    """(f, p) at the step's end: Uintah's computeUpdatedFractionAndPressure (module docstring).
    P: (ignition, K, n, A, B, C, R1, R2, omega, G, b, max_burn_timestep, max_frac, tol, max_iter, fast)."""
    ign, K, n, A, B, C, R1, R2, om, G, b, dts, fmax, tol, itmax, fast = P
    if not (p_old0 > ign and f_old0 < fmax):
        f = f_old0
        return f, _murnaghan(J, K, n) * (1.0 - f) + _jwl(J, A, B, C, R1, R2, om) * f
    ncyc = max(1, int(math.ceil(dt / dts)))
    dtc = dt / ncyc
    dJ = (J / J_old) ** (1.0 / ncyc)
    Jn = J_old
    f_old, p_old = f_old0, p_old0
    f, p = f_old0, p_old0
    # p^b of the current p, each power taken once: the sub-steps (up to dt / 1e-12 of them) are
    # the model's whole cost
    pb = p ** b
    for _ in range(ncyc):
        Jn *= dJ
        pM = _murnaghan(Jn, K, n)
        pJ = _jwl(Jn, A, B, C, R1, R2, om)
        if fast:                                   # two-stage backward Euler
            fac = dtc * G * pb
            f = (f_old + fac) / (1.0 + fac)
            if f > fmax:
                f = fmax
            p = pM * (1.0 - f) + pJ * f
            pb = p ** b
        else:                                      # Newton on (f, p), from the old state
            g0 = f - f_old - G * (1.0 - f) * pb * dtc
            g1 = p - (1.0 - f) * pM - f * pJ
            it = 0
            while True:
                fac = G * pb * dtc
                a00 = 1.0 + fac
                a01 = b * (1.0 - f) * (fac / p)
                a10 = pM - pJ
                det = a00 - a01 * a10                # a11 = 1
                f -= (g0 - a01 * g1) / det
                p -= (-a10 * g0 + a00 * g1) / det
                pb = p ** b
                g0 = f - f_old - G * (1.0 - f) * pb * dtc
                g1 = p - (1.0 - f) * pM - f * pJ
                it += 1
                if not (np.sqrt(g0 * g0 + g1 * g1) > tol and it < itmax):
                    break
            if np.isnan(p) or np.isnan(f):
                raise ValueError("jwlpp_mpm: NaN in the burn fraction or pressure (Uintah stops there too)")
        f_old, p_old = f, p
    if f > fmax:
        f = fmax
        p = _murnaghan(J, K, n) * (1.0 - f) + _jwl(J, A, B, C, R1, R2, om) * f
    return f, p


@njit(cache=True)
def kernel(P, rho0, K, n, dt, F_old, F_new, vol, mass, vel, stress_old, stress_new, energy, f_old, df_old, f_new,
           df_new):
    """The stress, p.progressF and p.progressdelF of every particle; the wave speed (3,). dt = 0:
    the start (stress kept, the wave speed from m/V)."""
    ws = np.zeros(3)
    for p in range(F_new.shape[0]):
        energy[p] = 0.0
        if dt == 0.0:
            rho = mass[p] / vol[p]
        else:
            f_new[p] = f_old[p]
            df_new[p] = df_old[p]
            J = det3(F_new[p])
            if not J > 0.0:
                stress_new[p] = 0.0
                continue
            pr_old = -(stress_old[p, 0, 0] + stress_old[p, 1, 1] + stress_old[p, 2, 2]) / 3.0
            f, pr = burn(P, det3(F_old[p]), J, f_old[p], pr_old, dt)
            df_new[p] = f - f_old[p]
            f_new[p] = f
            stress_new[p] = 0.0
            stress_new[p, 0, 0] = stress_new[p, 1, 1] = stress_new[p, 2, 2] = -pr
            rho = rho0 / J
        c = np.sqrt((rho / rho0) ** (n - 1.0) / (K * rho0))
        max_wavespeed(ws, c, vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old, new):
    """sigma, (p.progressF, p.progressdelF) old -> new; returns the wave speed (3,)."""
    q = params
    P = (q.ignition_pressure, q.K, q.n, q.A, q.B, q.C, q.R1, q.R2, q.omega, q.G, q.b, q.max_burn_timestep,
         q.max_burned_frac, q.newton_tol, q.newton_max, q.fast)
    (f_old, df_old), (f_new, df_new) = old, new
    return kernel(P, q.density, q.K, q.n, dt, F_old, F_new, vol, mass, vel, stress_old, stress_new, energy,
                  f_old, df_old, f_new, df_new)
