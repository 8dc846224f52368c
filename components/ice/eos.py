"""Equations of state for ICE materials (Uintah src/CCA/Components/ICE/EOS).

Why: ICE cell kernels (equilibration pressure, speed of sound, temperature)
evaluate the EOS of every material in every cell.  To keep multi-material
kernels monomorphic each material is described by an integer code and a
float64 parameter row ``params`` (length ``MAX_PARAMS``, zero-padded; stack the
rows of all materials into an (nmat, MAX_PARAMS) array); the ``eos_*``
dispatchers branch on the code inside numba.  ``gamma`` and ``cv`` are the ICE
material tags <gamma> and <specific_heat>, passed separately as in Uintah.

Codes and parameter layouts (Uintah deck tags in brackets):

  IDEAL_GAS = 0      ``ideal_gas``   params unused
                     p = (gamma-1) rho cv T,  e = cv T
  MURNAGHAN = 1      ``Murnaghan``   [K, n, rho0, P0]
                     K is the *compressibility* (1/bulk modulus, 1/Pa), as in
                     Uintah: p = P0 + ((rho/rho0)^n - 1)/(n K)  for rho >= rho0,
                     p = P0 (rho/rho0)^(1/(K P0))  for rho < rho0 (Uintah's
                     low-pressure branch; it is the paper-000 sec. 3.1 threshold
                     with p_th = P0, see below).  No temperature dependence.
  JWL = 2            ``JWL``         [A, B, R1, R2, om, rho0]
                     p = A exp(-R1 V) + B exp(-R2 V) + om cv T rho,  V = rho0/rho
                     (as Uintah JWL.cc: om*cv*T*rho = om cv T rho0/V, not om cv T/V)
  JWLC = 3           ``JWLC``        [A, B, C, R1, R2, om, rho0]
                     p = A exp(-R1 V) + B exp(-R2 V) + C (rho/rho0)^(1+om)
  STIFFENED_GAS = 4  ``Stiffened_gas`` [Pinf]   (not in Uintah; pysus tag names)
                     p = (gamma-1) rho e - gamma Pinf with e = cv T + Pinf/rho,
                     i.e. p = (gamma-1) rho cv T - Pinf.
  TST = 7            ``TST`` (Twu-Sim-Tassone) [a, b, u, w, Gamma]
                     p = (Gamma-1) cv T / (v - b) - a / ((v + u b)(v + w b)),  v = 1/rho;
                     rho_micro(p, T) from the cubic in v in closed form with the material's
                     <gamma> in place of Gamma, and T(p, rho), as Uintah's TST.cc
  SOLID_JWL = 6      (MPMICE: a visco_scram solid's <useJWLEOS>) [A, B, R1, R2, om, Cv, rho0, p_ref]
                     p = A exp(-R1 V) + B exp(-R2 V) + om Cv T / V, V = rho0/rho, Cv per volume
                     (Uintah's ViscoScram computePressEOSCM); dp_de = 0, c^2 = dp/drho. p_ref > 0
                     (<useModifiedEOS>): below the density rho_ref(T) where p = p_ref, the
                     threshold curve p_ref (rho/rho_ref)^(K0/p_ref), K0 = rho dp/drho there.
  SOLID_UCNH = 8     (MPMICE: comp_neo_hook, comp_neo_hook_plastic, UCNH) [K, rho0, p_ref, modified]
                     Uintah's UCNH computePressEOSCM: p = p_ref + K/2 (x - 1/x), x = rho/rho0
                     (J = 1/x), dp/drho = K (1 + J^2) / (2 rho0), c^2 = K/rho; rho(p) =
                     rho0/K (p_g + sqrt(K^2 + p_g^2)), p_g = p - p_ref. modified = 1
                     (<useModifiedEOS>): below rho0 the threshold curve p_ref x^(K/p_ref),
                     c^2 = dp/drho (as SOLID_HYPER's).
  SOLID_HYPER = 9    (MPMICE: elastic_plastic(_hp), visco_scram without <useJWLEOS>)
                     [K, rho0, p_ref, modified, viscoscram]: Uintah's ElasticPlasticHP and
                     ViscoScram computePressEOSCM, SOLID_UCNH's curves in their own arithmetic
                     (x = rho (1/rho0), rho(p) = rho0 (g + sqrt(g^2 + 1)), g = p_g/K; viscoscram = 1:
                     ViscoScram's rho (1/rho0) in the threshold curve, ElasticPlasticHP's rho/rho0).
  SOLID_HYPO = 10    (MPMICE: hypo_elastic) [K, rho0, p_ref]: Uintah's HypoElastic,
                     p = p_ref + K (1 - rho0/rho), dp/drho = K rho0/rho^2, c^2 = K/rho.
  SOLID_RIGID = 11   (MPMICE: rigid) [K, rho0, p_ref]: Uintah's RigidMaterial, rho = rho0 at any
                     pressure, p = p_ref, dp/drho = c^2 = K/rho0.
  SOLID_IDEAL_GAS = 12 (MPMICE: ideal_gas_fluid) [gamma, cv]: Uintah's IdealGasMP with the model's
                     <gamma> and <specific_heat>: p = (gamma-1) rho cv T, dp/drho = (gamma-1) cv T,
                     c^2 = dp/drho + (gamma-1) p/rho, rho(p) = p / ((gamma-1) cv T).
  SOLID_JWLPP = 13   (MPMICE: jwlpp_mpm) [A, B, R1, R2, om, cv, rho0]: Uintah's JWLppMPM,
                     rho = rho0 at any pressure; p = A exp(-R1 V) + B exp(-R2 V) + om cv T rho,
                     V = rho0/rho, c^2 = JWL's dp/drho = (R1 rho0 P1 + R2 rho0 P2)/rho^2 + om cv T
                     (Uintah's model takes its sound-speed argument as the temperature and leaves
                     it unset: sus's speedSound_CC there is whatever that variable held). The
                     dp/drho the equilibration's Newton step weighs it by is that of its density
                     law, incompressible (JWLPP_STIFF / rho0, as RigidMaterial's K = 1e200): the
                     root is where the fluids fill the rest of the cell, as sus's (whose Newton,
                     pulled to the JWL pressure, ends in its binary search there).
                     The solid codes' dp_de is 0 and eos_sound_speed2 is the model's own c^2
                     (solid_cm_press_eos), which MPMICE's equilibration takes as Uintah's.
  THOMSEN_HARTKA = 5 ``Thomsen_Hartka_water`` [a, b, co, ko, To, L, vo]
                     v = vo (1 - ko p + L (a p + T - To)^2) (Uintah Thomsen_Hartka_water.cc:
                     p(rho, T) the root of that quadratic, dp_drho, dp_de and alpha its
                     formulas; the temperature from (p, rho) as Uintah's computeTempCC).

Per-cell functions (all @njit, scalar float64):
  eos_press_eos(code, params, rho_micro, temp, cv, gamma) -> (p, dp_drho, dp_de)
      as Uintah computePressEOS; dp_drho = (dp/drho)_T, dp_de = (dp/dT)_rho / cv
  eos_press / eos_dp_drho / eos_dp_de(code, params, rho_micro, temp, cv, gamma)
  eos_rho_micro(code, params, press, temp, cv, gamma, rho_guess)  (computeRhoMicro)
  eos_temp(code, params, press, rho_micro, cv, gamma)             (computeTempCC)
  eos_alpha(code, params, rho_micro, temp, cv, gamma)   (1/v)(dv/dT)_p (getAlpha,
      paper 000 eq. 48)
  eos_sound_speed2(code, params, rho_micro, temp, cv, gamma)
      thermodynamic c^2 = (dp/drho)_T + T (dp/dT)_rho^2 / (rho^2 cv)
  sound_speed2_uintah(press, rho_micro, dp_drho, dp_de)
      Uintah ICE's c^2 = dp_drho + dp_de p / rho^2; identical for ideal gas,
      Murnaghan and JWLC; for Stiffened_gas/JWL it assumes e = cv T and differs.

Condensed-phase threshold (paper 000, sec. 3.1, Fig. 1): below a threshold
pressure p_th the condensed-phase pressure is replaced by a curve that is
continuous and smooth (C1) at p_th and tends to zero as v -> infinity.  We use
the same curve Uintah uses (MPM constitutive models' ``useModifiedEOS``, and the
Murnaghan low-pressure branch): p = p_th (rho/rho_th)^m, m = rho_th c_th^2/p_th,
with rho_th the density where the full EOS gives p_th and c_th^2 = dp/drho
there.  ``threshold_press``/``threshold_rho_micro`` are the bare curve (for MPM
solids: p_th = p_ref, rho_th = rho0, rho_th c_th^2 = bulk);
``eos_press_eos_threshold``/``eos_rho_micro_threshold`` apply it to any code.
For solids m ~ bulk/p_th ~ 1e4-1e5, so below p_th rho stays ~ rho_th while p -> 0.

Deck-level descriptions: ``make_eos(type_name, {tag: value})`` returns an
``EOSModel`` (fields type_name, code, tags, values; ``.params()`` gives the row).
JWL's cv and Stiffened_gas's gamma/cv come from the ICE material tags
<specific_heat>/<gamma>, as Uintah's JWL.cc requires only A,B,R1,R2,om,rho0.
"""
import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

IDEAL_GAS = 0
MURNAGHAN = 1
JWL = 2
JWLC = 3
STIFFENED_GAS = 4
THOMSEN_HARTKA = 5
SOLID_JWL = 6
TST = 7
SOLID_UCNH = 8
SOLID_HYPER = 9
SOLID_HYPO = 10
SOLID_RIGID = 11
SOLID_IDEAL_GAS = 12
SOLID_JWLPP = 13
JWLPP_STIFF = 1.0e200     # SOLID_JWLPP's dp/drho in the equilibration: its density is rho0 at any pressure
RHO_REF_TOL = 1e-10       # SOLID_JWL: relative tolerance of rho_ref (Uintah's computeRhoRef)
MAX_PARAMS = 8


# ----------------------------------------------------------------------------
# ideal gas (IdealGas.cc)
@njit(cache=True)
def ideal_gas_press_eos(rho, temp, cv, gamma):
    """p = (gamma-1) rho cv T with (dp/drho)_T and dp/de."""
    return (gamma - 1.0) * rho * cv * temp, (gamma - 1.0) * cv * temp, (gamma - 1.0) * rho


@njit(cache=True)
def ideal_gas_sound_speed2(rho, temp, cv, gamma):
    """eos_sound_speed2 of an ideal gas, the same operations (kernels call it in loops that
    then vectorize, without the EOS dispatch)."""
    dpdrho = (gamma - 1.0) * cv * temp
    dpdt = (gamma - 1.0) * rho * cv
    return dpdrho + temp * dpdt * dpdt / (rho * rho * cv)


@njit(cache=True)
def ideal_gas_alpha(rho, temp, cv, gamma):
    """eos_alpha of an ideal gas (1/T), the same operations."""
    dpdt = (gamma - 1.0) * rho * cv
    if dpdt == 0.0:
        return 0.0
    return dpdt / (rho * ((gamma - 1.0) * cv * temp))


@njit(cache=True)
def ideal_gas_rho_micro(press, temp, cv, gamma):
    return press / ((gamma - 1.0) * cv * temp)


# ----------------------------------------------------------------------------
# stiffened gas: p = (gamma-1) rho e - gamma pinf, e = cv T + pinf/rho
@njit(cache=True)
def stiffened_gas_press_eos(rho, temp, cv, gamma, pinf):
    return (gamma - 1.0) * rho * cv * temp - pinf, (gamma - 1.0) * cv * temp, (gamma - 1.0) * rho


@njit(cache=True)
def stiffened_gas_rho_micro(press, temp, cv, gamma, pinf):
    return (press + pinf) / ((gamma - 1.0) * cv * temp)


# ----------------------------------------------------------------------------
# Murnaghan (Murnaghan.cc); K = compressibility 1/Pa
@njit(cache=True)
def murnaghan_press_eos(rho, K, n, rho0, P0):
    if rho >= rho0:
        p = P0 + (1.0 / (n * K)) * ((rho / rho0) ** n - 1.0)
        dp = (1.0 / (K * rho0)) * (rho / rho0) ** (n - 1.0)
    else:  # low-pressure branch = paper 000 sec. 3.1 threshold at p_th = P0
        m = 1.0 / (K * P0)
        p = P0 * (rho / rho0) ** m
        dp = (1.0 / (K * rho0)) * (rho / rho0) ** (m - 1.0)
    return p, dp, 0.0


@njit(cache=True)
def murnaghan_rho_micro(press, K, n, rho0, P0):
    if press >= P0:
        return rho0 * (n * K * (press - P0) + 1.0) ** (1.0 / n)
    if press <= 0.0:
        return 0.0
    return rho0 * (press / P0) ** (K * P0)


# ----------------------------------------------------------------------------
# JWL (JWL.cc) and JWLC (JWLC.cc)
@njit(cache=True)
def jwl_press_eos(rho, temp, cv, A, B, R1, R2, om, rho0):
    v = rho0 / rho
    p1 = A * math.exp(-R1 * v)
    p2 = B * math.exp(-R2 * v)
    p3 = om * cv * temp * rho
    dp = (R1 * rho0 * p1 + R2 * rho0 * p2) / (rho * rho) + om * cv * temp
    return p1 + p2 + p3, dp, om * rho


@njit(cache=True)
def jwlc_press_eos(rho, A, B, C, R1, R2, om, rho0):
    v = rho0 / rho
    p1 = A * math.exp(-R1 * v)
    p2 = B * math.exp(-R2 * v)
    p3 = C * (rho / rho0) ** (1.0 + om)
    dp = (R1 * rho0 * p1 + R2 * rho0 * p2) / (rho * rho) + (1.0 + om) * p3 / rho
    return p1 + p2 + p3, dp, 0.0


# ----------------------------------------------------------------------------
# a solid's JWL (Uintah's ViscoScram, useJWLEOS)
@njit(cache=True)
def _solid_jwl_p(rho, temp, A, B, R1, R2, om, Cv, rho0):
    v = rho0 / (rho + 1e-100)
    return A * math.exp(-R1 * v) + B * math.exp(-R2 * v) + om * Cv * temp / v


@njit(cache=True)
def _solid_jwl_root(press, temp, A, B, R1, R2, om, Cv, rho0, rho, eps):
    """The density where the solid's JWL gives press, by Uintah's bisection-Newton
    (ViscoScram::computeRhoMicroCM, computeRhoRef): Newton steps from rho while they stay in
    the bracket [0, 1e5] and shrink by 0.7, else a bisection, until the step (or the bracket)
    is below eps relative. From the guess it finds the condensed root, not the low-density one
    JWL also has."""
    IL, IR = 0.0, 100000.0
    it = 0
    while it < 300:
        f = _solid_jwl_p(rho, temp, A, B, R1, R2, om, Cv, rho0) - press
        if f < 0.0:
            IL = rho
        elif f > 0.0:
            IR = rho
        else:
            IL = IR = rho
        if abs((IL - IR) / rho) < eps:
            return 0.5 * (IL + IR)
        delta_new = 1e100
        while True:
            v = rho0 / (rho + 1e-100)
            P1 = A * math.exp(-R1 * v)
            P2 = B * math.exp(-R2 * v)
            P3 = om * Cv * temp / v
            delta_old = delta_new
            delta_new = -f / ((P1 * R1 * v + P2 * R2 * v + P3) / rho)
            rho += delta_new
            if abs(delta_new / rho) < eps:
                return rho
            if it >= 100 or rho < IL or rho > IR or abs(delta_new) > abs(delta_old * 0.7):
                break
            f = _solid_jwl_p(rho, temp, A, B, R1, R2, om, Cv, rho0) - press
            if f < 0.0:
                IL = rho
            elif f > 0.0:
                IR = rho
            else:
                IL = IR = rho
            it += 1
        rho = 0.5 * (IL + IR)
        it += 1
    return rho


@njit(cache=True)
def solid_jwl_rho_ref(temp, A, B, R1, R2, om, Cv, rho0, p_ref):
    """(rho_ref, K0): the density where the solid's JWL gives p_ref at temp (Uintah's
    computeRhoRef: from rho0, relative 1e-10) and K0 = rho dp/drho there."""
    rho = _solid_jwl_root(p_ref, temp, A, B, R1, R2, om, Cv, rho0, rho0, RHO_REF_TOL)
    v = rho0 / rho
    return rho, v * (A * R1 * math.exp(-R1 * v) + B * R2 * math.exp(-R2 * v)) + temp * Cv * om / v


@njit(cache=True)
def solid_jwl_press_eos(rho, temp, A, B, R1, R2, om, Cv, rho0, p_ref):
    """(p, dp/drho, 0) of a solid's JWL (Uintah's ViscoScram computePressEOSCM)."""
    if p_ref > 0.0:
        rho_ref, K0 = solid_jwl_rho_ref(temp, A, B, R1, R2, om, Cv, rho0, p_ref)
        if rho < rho_ref:
            p, dp = threshold_press(rho, p_ref, rho_ref, K0)
            return p, dp, 0.0
    v = rho0 / rho
    P1 = A * math.exp(-R1 * v)
    P2 = B * math.exp(-R2 * v)
    P3 = om * Cv * temp / v
    return P1 + P2 + P3, (R1 * rho0 * P1 + R2 * rho0 * P2) / (rho * rho) + om * Cv * temp / rho0, 0.0


@njit(cache=True)
def solid_jwl_rho_micro(press, temp, A, B, R1, R2, om, Cv, rho0, p_ref, rho_guess):
    """The density at (press, temp) (Uintah's ViscoScram computeRhoMicroCM: the threshold curve
    below p_ref, else JWL's root from the guess, relative 1e-15)."""
    if p_ref > 0.0 and press < p_ref:
        rho_ref, K0 = solid_jwl_rho_ref(temp, A, B, R1, R2, om, Cv, rho0, p_ref)
        return threshold_rho_micro(press, p_ref, rho_ref, K0)
    rho = rho_guess if rho_guess <= 100000.0 else 50000.0
    return _solid_jwl_root(press, temp, A, B, R1, R2, om, Cv, rho0, rho, 1e-15)


# ----------------------------------------------------------------------------
# an MPM solid's own EOS in MPMICE (Uintah's constitutive models' computePressEOSCM and
# computeRhoMicroCM), each in its model's arithmetic; (p, dp/drho, c^2)
@njit(cache=True)
def solid_modified_press_eos(rho, K, rho0, p_ref, viscoscram):
    """<useModifiedEOS> below rho0: p = p_ref x^n, n = K/p_ref, dp/drho = c^2 = (K/rho) x^n
    (paper 000 sec. 3.1's threshold curve at p_th = p_ref)."""
    n = K / p_ref
    x_n = (rho * (1.0 / rho0)) ** n if viscoscram else (rho / rho0) ** n
    dp = (K / rho) * x_n
    return p_ref * x_n, dp, dp


@njit(cache=True)
def solid_modified_rho_micro(press, K, rho0, p_ref):
    """The inverse of solid_modified_press_eos: rho0 (p/p_ref)^(p_ref/K)."""
    return rho0 * (press / p_ref) ** (p_ref / K)


@njit(cache=True)
def ucnh_press_eos(rho, K, rho0, p_ref, modified):
    """Uintah's UCNH: p = p_ref - K/2 (J - 1/J), J = rho0/rho; c^2 = K (1 + (1/J) J) / (2 rho)."""
    if modified and rho < rho0:
        return solid_modified_press_eos(rho, K, rho0, p_ref, False)
    J = rho0 / rho
    p_cm = 0.5 * K * (J - 1.0 / J)
    return p_ref - p_cm, 0.5 * K * (1.0 + J * J) / rho0, 0.5 * K * (1.0 + 1.0 / J * J) / rho


@njit(cache=True)
def ucnh_rho_micro(press, K, rho0, p_ref, modified):
    """Uintah's UCNH computeRhoMicroCM (computeDensity of -p_g)."""
    p_g = press - p_ref
    if modified and p_g < 0.0:
        return solid_modified_rho_micro(press, K, rho0, p_ref)
    return rho0 / K * (p_g + math.sqrt(K * K + p_g * p_g))


@njit(cache=True)
def hyper_press_eos(rho, K, rho0, p_ref, modified, viscoscram):
    """Uintah's ElasticPlasticHP / ViscoScram: p = p_ref + K/2 (rho/rho0 - rho0/rho), c^2 = K/rho."""
    if modified and rho < rho0:
        return solid_modified_press_eos(rho, K, rho0, p_ref, viscoscram)
    inv_rho0 = 1.0 / rho0
    p = p_ref + 0.5 * K * (rho * inv_rho0 - rho0 / rho)
    return p, 0.5 * K * (rho0 / (rho * rho) + inv_rho0), K / rho


@njit(cache=True)
def hyper_rho_micro(press, K, rho0, p_ref, modified):
    """Uintah's ElasticPlasticHP / ViscoScram computeRhoMicroCM."""
    p_g = press - p_ref
    if modified and p_g < 0.0:
        return solid_modified_rho_micro(press, K, rho0, p_ref)
    g = p_g / K
    return rho0 * (g + math.sqrt(g * g + 1.0))


@njit(cache=True)
def solid_cm_press_eos(code, params, rho, temp):
    """(p, dp/drho, c^2) of the solid codes (SOLID_UCNH .. SOLID_JWLPP) at the solid's temp."""
    if code == SOLID_IDEAL_GAS:         # Uintah's IdealGasMP
        g, cv = params[0], params[1]
        p = (g - 1.0) * rho * cv * temp
        dp = (g - 1.0) * cv * temp
        return p, dp, dp + (g - 1.0) * rho * p / (rho * rho)
    if code == SOLID_JWLPP:             # Uintah's JWLppMPM (its temperature the cell's)
        A, B, R1, R2, om, cv, rho0 = params[0], params[1], params[2], params[3], params[4], params[5], params[6]
        V = rho0 / rho
        P1 = A * math.exp(-R1 * V)
        P2 = B * math.exp(-R2 * V)
        c2 = (R1 * rho0 * P1 + R2 * rho0 * P2) / (rho * rho) + om * cv * temp
        return P1 + P2 + om * cv * temp * rho, JWLPP_STIFF / rho0, c2
    K, rho0, p_ref = params[0], params[1], params[2]
    if code == SOLID_UCNH:
        return ucnh_press_eos(rho, K, rho0, p_ref, params[3] != 0.0)
    elif code == SOLID_HYPER:
        return hyper_press_eos(rho, K, rho0, p_ref, params[3] != 0.0, params[4] != 0.0)
    elif code == SOLID_HYPO:
        return p_ref + K * (1.0 - rho0 / rho), K * rho0 / (rho * rho), K / rho
    dp = K / rho0
    return p_ref, dp, dp


@njit(cache=True)
def solid_cm_rho_micro(code, params, press, temp):
    """rho_micro(p) of the solid codes (Uintah's computeRhoMicroCM)."""
    if code == SOLID_IDEAL_GAS:
        return press / ((params[0] - 1.0) * params[1] * temp)
    if code == SOLID_JWLPP:
        return params[6]
    K, rho0, p_ref = params[0], params[1], params[2]
    if code == SOLID_UCNH:
        return ucnh_rho_micro(press, K, rho0, p_ref, params[3] != 0.0)
    elif code == SOLID_HYPER:
        return hyper_rho_micro(press, K, rho0, p_ref, params[3] != 0.0)
    elif code == SOLID_HYPO:
        return rho0 / (1.0 - (press - p_ref) / K)
    return rho0


# ----------------------------------------------------------------------------
# Thomsen-Hartka water (Thomsen_Hartka_water.cc)
@njit(cache=True)
def thomsen_hartka_press_eos(rho, temp, a, b, co, ko, To, L, vo):
    """(p, dp_drho, dp_de) as Uintah's computePressEOS."""
    vo_rho = vo * rho
    a_L = a * L
    term1 = 1.0 / (2.0 * a_L * a * vo_rho)
    term2 = (ko + 2.0 * a_L * (To - temp)) * vo_rho
    term3 = ko * ko * vo_rho
    term4 = 4.0 * a_L * (a - (a + (temp - To) * ko) * vo_rho)
    press = term1 * (term2 - math.sqrt(vo_rho * (term3 + term4)))
    a_press = a * press
    a_press_temp = a_press + temp
    x = a_press_temp - To
    y = 1.0 - ko * press + x * x * L
    dp_drho = y * y * vo / (ko - 2.0 * a_L * (a_press_temp - To))
    d1 = ko - 2.0 * a_L * (a_press_temp - To)
    d2 = co + b * (To - temp) + 2.0 * press * L * vo * (-a_press + To - 2.0 * temp)
    dp_de = 2.0 * L * (a_press_temp - To) / (d1 * d2)
    return press, dp_drho, dp_de


@njit(cache=True)
def thomsen_hartka_rho_micro(press, temp, a, ko, To, L, vo):
    x = a * press + temp - To
    return 1.0 / (vo * (1.0 - ko * press + L * x * x))


# Twu-Sim-Tassone (Uintah's TST): p = (Gamma - 1) cv T / (v - b) - a / ((v + u b)(v + w b)), v = 1/rho
@njit(cache=True)
def tst_press_eos(rho, temp, cv, a, b, u, w, Gamma):
    """(p, (dp/drho)_T, dp/de) as Uintah's TST::computePressEOS (its own <Gamma>)."""
    v = 1.0 / rho
    d1, d2, d3 = v - b, v + u * b, v + w * b
    p1 = (Gamma - 1.0) * cv * temp / d1
    p2 = a / (d2 * d3)
    return p1 - p2, v * v * (p1 / d1 - p2 * (1.0 / d2 + 1.0 / d3)), (Gamma - 1.0) / d1


@njit(cache=True)
def tst_alpha(v, press, cv, a, b, u, w, Gamma):
    """Uintah's TST::getAlpha: 1 / (v (dT/dv)_p) at the cell's specific volume and pressure."""
    bu, bw = b * u, b * w
    n1 = 2.0 * press * v + press * bw + press * bu
    n2 = v - b
    n3 = press * v * v + press * v * (bu + bw) + press * b * b * u * w + a
    d1 = (v + bu) * (v + bw) * (Gamma - 1.0) * cv
    dT_dv = n1 * n2 / d1 - n3 * n2 / d1 * (1.0 / (v + bu) + 1.0 / (v + bw)) + n3 / d1
    return 1.0 / (v * dT_dv)


@njit(cache=True)
def tst_rho_micro(press, temp, cv, gamma, a, b, u, w):
    """Uintah's TST::computeRhoMicro: the cubic in v solved in closed form (trigonometric root);
    as Uintah's, with the material's <gamma> (its pressure takes the EOS's <Gamma>)."""
    k = (gamma - 1.0) * cv * temp
    c1 = -press
    c2 = press * b * (1.0 - u - w) + k
    c3 = k * (b * u + b * w) - a + press * b * b * (u + w - u * w)
    c4 = (press * b + k) * (b * u) * (b * w) + a * b
    r = c2 / c1
    pp = abs(c3 / c1 - r * r / 3.0)
    q = r * r * r / 13.5 - c2 * c3 / (c1 * c1) / 3.0 + c4 / c1
    cos_val = min(1.0, max(-1.0, -q / pp ** 1.5 * 2.5980762113533159402911695122588))
    v = 2.0 * math.sqrt(pp / 3.0) * math.cos(math.acos(cos_val) / 3.0) - r / 3.0
    return 1.0 / v


# ----------------------------------------------------------------------------
# dispatchers
@njit(cache=True)
def eos_press_eos(code, params, rho_micro, temp, cv, gamma):
    """(p, (dp/drho)_T, dp/de) for material EOS ``code`` (Uintah computePressEOS)."""
    if code == IDEAL_GAS:
        return ideal_gas_press_eos(rho_micro, temp, cv, gamma)
    elif code == MURNAGHAN:
        return murnaghan_press_eos(rho_micro, params[0], params[1], params[2], params[3])
    elif code == JWL:
        return jwl_press_eos(rho_micro, temp, cv, params[0], params[1], params[2],
                             params[3], params[4], params[5])
    elif code == JWLC:
        return jwlc_press_eos(rho_micro, params[0], params[1], params[2], params[3],
                              params[4], params[5], params[6])
    elif code == STIFFENED_GAS:
        return stiffened_gas_press_eos(rho_micro, temp, cv, gamma, params[0])
    elif code == THOMSEN_HARTKA:
        return thomsen_hartka_press_eos(rho_micro, temp, params[0], params[1], params[2], params[3],
                                        params[4], params[5], params[6])
    elif code == SOLID_JWL:
        return solid_jwl_press_eos(rho_micro, temp, params[0], params[1], params[2], params[3], params[4],
                                   params[5], params[6], params[7])
    elif code == TST:
        return tst_press_eos(rho_micro, temp, cv, params[0], params[1], params[2], params[3], params[4])
    elif code >= SOLID_UCNH:
        p, dp, _c2 = solid_cm_press_eos(code, params, rho_micro, temp)
        return p, dp, 0.0
    return math.nan, math.nan, math.nan


@njit(cache=True)
def eos_press(code, params, rho_micro, temp, cv, gamma):
    return eos_press_eos(code, params, rho_micro, temp, cv, gamma)[0]


@njit(cache=True)
def eos_dp_drho(code, params, rho_micro, temp, cv, gamma):
    return eos_press_eos(code, params, rho_micro, temp, cv, gamma)[1]


@njit(cache=True)
def eos_dp_de(code, params, rho_micro, temp, cv, gamma):
    return eos_press_eos(code, params, rho_micro, temp, cv, gamma)[2]


@njit(cache=True)
def eos_cold_energy(code, params, rho_micro):
    """e_c(rho): the part of the specific internal energy that is not cv T, with
    de_c/drho = (p - T (dp/dT)_rho) / rho^2 (first law; every EOS here is p_c(rho) + T f(rho)),
    so that e = cv T + e_c(rho) is the energy whose conservation the Euler equations state.
    Ideal gas 0; stiffened gas Pinf/rho; JWL/JWLC A/(R1 rho0) exp(-R1 V) + B/(R2 rho0) exp(-R2 V)
    (+ C rho^om / (om rho0^(1+om)) for JWLC); Murnaghan the integral of p/rho^2 from rho0."""
    if code == IDEAL_GAS or code == SOLID_JWL or code >= SOLID_UCNH:     # a solid's energy is its particles'
        return 0.0
    elif code == STIFFENED_GAS:
        return params[0] / rho_micro
    elif code == MURNAGHAN:
        K, n, rho0, P0 = params[0], params[1], params[2], params[3]
        x = rho_micro / rho0
        if rho_micro >= rho0:
            return (P0 - 1.0 / (n * K)) * (1.0 - 1.0 / x) / rho0 + (x ** (n - 1.0) - 1.0) / (n * K * rho0 * (n - 1.0))
        m = 1.0 / (K * P0)
        return P0 / rho0 * (x ** (m - 1.0) - 1.0) / (m - 1.0)
    elif code == JWL or code == JWLC:
        rho0 = params[5] if code == JWL else params[6]
        A, B = params[0], params[1]
        R1, R2 = (params[2], params[3]) if code == JWL else (params[3], params[4])
        v = rho0 / rho_micro
        e = A / (R1 * rho0) * math.exp(-R1 * v) + B / (R2 * rho0) * math.exp(-R2 * v)
        if code == JWLC:
            om = params[5]
            e += params[2] * (rho_micro / rho0) ** om / (om * rho0)
        return e
    elif code == TST:          # de_c = a dv / ((v + u b)(v + w b)), zero at v -> infinity
        a, b, u, w = params[0], params[1], params[2], params[3]
        v = 1.0 / rho_micro
        return a / ((w - u) * b) * math.log((v + u * b) / (v + w * b))
    return math.nan


@njit(cache=True)
def _dp_dtemp(code, params, rho_micro, temp, cv, gamma):
    """(dp/dT)_rho; every EOS here is linear in T (or T-independent)."""
    if code == IDEAL_GAS or code == STIFFENED_GAS:
        return (gamma - 1.0) * rho_micro * cv
    elif code == JWL:
        return params[4] * cv * rho_micro
    elif code == THOMSEN_HARTKA:
        return eos_dp_de(code, params, rho_micro, temp, cv, gamma) * cv
    elif code == TST:
        return (params[4] - 1.0) * cv / (1.0 / rho_micro - params[1])
    return 0.0


@njit(cache=True)
def _solve_rho(code, params, press, temp, cv, gamma, rho_guess):
    """Safeguarded Newton-bisection for p(rho, T) = press (p increasing in rho)."""
    lo = 0.0  # p(rho -> 0) -> 0 < press for JWL/JWLC
    hi = rho_guess if rho_guess > 0.0 else 1.0
    for _ in range(2000):
        if eos_press(code, params, hi, temp, cv, gamma) >= press:
            break
        lo = hi
        hi *= 2.0
    rho = rho_guess if lo < rho_guess < hi else 0.5 * (lo + hi)
    for _ in range(200):
        p, dp, _de = eos_press_eos(code, params, rho, temp, cv, gamma)
        f = p - press
        if f < 0.0:
            lo = rho
        else:
            hi = rho
        rho_new = rho - f / dp if dp > 0.0 else 0.5 * (lo + hi)
        if not (lo < rho_new < hi):
            rho_new = 0.5 * (lo + hi)
        if abs(rho_new - rho) <= 1e-15 * rho_new or (hi - lo) <= 1e-15 * hi:
            return rho_new
        rho = rho_new
    return rho


@njit(cache=True)
def eos_rho_micro(code, params, press, temp, cv, gamma, rho_guess):
    """Microscopic density at (press, temp) (Uintah computeRhoMicro)."""
    if code == IDEAL_GAS:
        return ideal_gas_rho_micro(press, temp, cv, gamma)
    elif code == MURNAGHAN:
        return murnaghan_rho_micro(press, params[0], params[1], params[2], params[3])
    elif code == STIFFENED_GAS:
        return stiffened_gas_rho_micro(press, temp, cv, gamma, params[0])
    elif code == THOMSEN_HARTKA:
        return thomsen_hartka_rho_micro(press, temp, params[0], params[3], params[4], params[5], params[6])
    elif code == JWL or code == JWLC:
        if press <= 0.0:
            return 0.0
        return _solve_rho(code, params, press, temp, cv, gamma, rho_guess)
    elif code == SOLID_JWL:
        return solid_jwl_rho_micro(press, temp, params[0], params[1], params[2], params[3], params[4], params[5],
                                   params[6], params[7], rho_guess)
    elif code == TST:
        return tst_rho_micro(press, temp, cv, gamma, params[0], params[1], params[2], params[3])
    elif code >= SOLID_UCNH:
        return solid_cm_rho_micro(code, params, press, temp)
    return math.nan


@njit(cache=True)
def eos_temp(code, params, press, rho_micro, cv, gamma):
    """Temperature from (press, rho_micro) (Uintah computeTempCC)."""
    if code == IDEAL_GAS:
        return press / ((gamma - 1.0) * cv * rho_micro)
    elif code == STIFFENED_GAS:
        return (press + params[0]) / ((gamma - 1.0) * cv * rho_micro)
    elif code == JWL:
        v = params[5] / rho_micro
        cold = params[0] * math.exp(-params[2] * v) + params[1] * math.exp(-params[3] * v)
        return (press - cold) / (params[4] * rho_micro * cv)
    elif code == THOMSEN_HARTKA:       # as Uintah's computeTempCC
        return -params[0] * press + params[4] + math.sqrt(1.0 + params[6] * rho_micro * (params[3] * press - 1.0))
    elif code == TST:                  # Uintah's TST::computeTempCC
        a, b, u, w, G = params[0], params[1], params[2], params[3], params[4]
        v = 1.0 / rho_micro
        return (v - b) * (press * v * v + press * v * b * (u + w) + press * b * b * u * w + a) / \
            ((v + u * b) * (v + w * b) * (G - 1.0) * cv)
    return 300.0  # Murnaghan, JWLC: T-independent; Uintah sets 300 K


@njit(cache=True)
def eos_alpha(code, params, rho_micro, temp, cv, gamma):
    """beta = (1/v)(dv/dT)_p = (dp/dT)_rho / (rho (dp/drho)_T)  (paper 000 eq. 48)."""
    if code == THOMSEN_HARTKA:         # Uintah's getAlpha, at p = p(rho, T)
        a, ko, To, L = params[0], params[3], params[4], params[5]
        p = eos_press(code, params, rho_micro, temp, cv, gamma)
        x = a * p + temp - To
        return 2.0 * L * x / (1.0 - ko * p + L * x * x)
    dpdt = _dp_dtemp(code, params, rho_micro, temp, cv, gamma)
    if dpdt == 0.0:
        return 0.0
    return dpdt / (rho_micro * eos_dp_drho(code, params, rho_micro, temp, cv, gamma))


@njit(cache=True)
def eos_sound_speed2(code, params, rho_micro, temp, cv, gamma):
    """Adiabatic c^2 = (dp/drho)_T + T (dp/dT)_rho^2 / (rho^2 cv); Thomsen_Hartka_water:
    Uintah's c^2 = dp_drho + dp_de p / rho^2 (its dp_de is not (dp/dT)_rho / cv); the solid
    codes: their model's c^2 (solid_cm_press_eos)."""
    if code >= SOLID_UCNH:
        return solid_cm_press_eos(code, params, rho_micro, temp)[2]
    if code == THOMSEN_HARTKA:
        p, dp_drho, dp_de = eos_press_eos(code, params, rho_micro, temp, cv, gamma)
        return sound_speed2_uintah(p, rho_micro, dp_drho, dp_de)
    dpdrho = eos_dp_drho(code, params, rho_micro, temp, cv, gamma)
    dpdt = _dp_dtemp(code, params, rho_micro, temp, cv, gamma)
    return dpdrho + temp * dpdt * dpdt / (rho_micro * rho_micro * cv)


@njit(cache=True)
def sound_speed2_uintah(press, rho_micro, dp_drho, dp_de):
    """Uintah ICE: c^2 = dp_drho + dp_de * p / rho^2 (computeEquilibrationPressure)."""
    return dp_drho + dp_de * press / (rho_micro * rho_micro)


# ----------------------------------------------------------------------------
# condensed-phase threshold (paper 000 sec. 3.1, Fig. 1)
@njit(cache=True)
def threshold_press(rho, p_th, rho_th, bulk_th):
    """p = p_th (rho/rho_th)^m, m = bulk_th/p_th; returns (p, dp/drho)."""
    m = bulk_th / p_th
    p = p_th * (rho / rho_th) ** m
    return p, m * p / rho


@njit(cache=True)
def threshold_rho_micro(press, p_th, rho_th, bulk_th):
    """Inverse of threshold_press (for 0 < press <= p_th)."""
    return rho_th * (press / p_th) ** (p_th / bulk_th)


@njit(cache=True)
def _threshold_point(code, params, temp, cv, gamma, p_th):
    rho_th = eos_rho_micro(code, params, p_th, temp, cv, gamma, 1.0)
    return rho_th, rho_th * eos_dp_drho(code, params, rho_th, temp, cv, gamma)


@njit(cache=True)
def eos_press_eos_threshold(code, params, rho_micro, temp, cv, gamma, p_th):
    """eos_press_eos with the sec. 3.1 threshold: below p_th use the C1 power law."""
    p, dp, de = eos_press_eos(code, params, rho_micro, temp, cv, gamma)
    if p >= p_th:
        return p, dp, de
    rho_th, bulk_th = _threshold_point(code, params, temp, cv, gamma, p_th)
    p, dp = threshold_press(rho_micro, p_th, rho_th, bulk_th)
    return p, dp, 0.0


@njit(cache=True)
def eos_rho_micro_threshold(code, params, press, temp, cv, gamma, rho_guess, p_th):
    """Inverse of eos_press_eos_threshold."""
    if press >= p_th:
        return eos_rho_micro(code, params, press, temp, cv, gamma, rho_guess)
    rho_th, bulk_th = _threshold_point(code, params, temp, cv, gamma, p_th)
    return threshold_rho_micro(press, p_th, rho_th, bulk_th)


# ----------------------------------------------------------------------------
# deck-level descriptions
@dataclass
class EOSModel:
    """An ICE <EOS type="..."> block: Uintah type name, code and tag values."""
    type_name: str = ""
    code: int = -1
    tags: tuple = ()
    values: dict = field(default_factory=dict)

    def params(self):
        """float64 parameter row of length MAX_PARAMS in the documented layout."""
        row = np.zeros(MAX_PARAMS, dtype=np.float64)
        for i, tag in enumerate(self.tags):
            row[i] = float(self.values[tag])
        return row


def _model(type_name, code, tags):
    def make(**values):
        missing = [t for t in tags if t not in values]
        extra = [t for t in values if t not in tags]
        if missing or extra:
            raise ValueError(f"EOS {type_name}: missing tags {missing}, unknown tags {extra}")
        return EOSModel(type_name, code, tags, {t: float(values[t]) for t in tags})
    make.__name__ = type_name
    make.__doc__ = f"EOS type='{type_name}' (code {code}); deck tags {list(tags)}."
    return make


IdealGasEOS = _model("ideal_gas", IDEAL_GAS, ())
MurnaghanEOS = _model("Murnaghan", MURNAGHAN, ("K", "n", "rho0", "P0"))
JWLEOS = _model("JWL", JWL, ("A", "B", "R1", "R2", "om", "rho0"))
JWLCEOS = _model("JWLC", JWLC, ("A", "B", "C", "R1", "R2", "om", "rho0"))
StiffenedGasEOS = _model("Stiffened_gas", STIFFENED_GAS, ("Pinf",))
ThomsenHartkaEOS = _model("Thomsen_Hartka_water", THOMSEN_HARTKA, ("a", "b", "co", "ko", "To", "L", "vo"))
TSTEOS = _model("TST", TST, ("a", "b", "u", "w", "Gamma"))

EOS_TYPES = {"ideal_gas": IdealGasEOS, "Murnaghan": MurnaghanEOS, "JWL": JWLEOS,
             "JWLC": JWLCEOS, "Stiffened_gas": StiffenedGasEOS, "Thomsen_Hartka_water": ThomsenHartkaEOS,
             "TST": TSTEOS}


def make_eos(type_name, tags):
    """Build an EOSModel from the type attribute and a {tag: value} dict."""
    if type_name not in EOS_TYPES:
        raise ValueError(f"EOS type '{type_name}' is not implemented in pysus "
                         f"(available: {sorted(EOS_TYPES)})")
    return EOS_TYPES[type_name](**tags)
