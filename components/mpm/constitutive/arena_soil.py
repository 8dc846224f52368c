"""Partially saturated soil: Uintah's ArenaSoil (Vaango's ArenaPartiallySaturated).

``<constitutive_model type="ArenaSoil">`` (Homel, Guilkey and Brannon's Arena model as
Banerjee and Brannon extended it to partly saturated soils).  Hypoelastic-plastic, in the
frame unrotated by F's polar rotation R of the step's start:

  elasticity   tangent moduli from ``<elastic_moduli_model type="arena">``: the drained bulk
               modulus K_d = K_s/(1 - n p/K_s) (b0 + b1 b3 b4 y/(e (b2 y + b3)^2)),
               e = (b3 p/(b1 K_s - b2 p))^(1/b4), y = e^b4, with the grains' K_s = 40 GPa + 4 (p - 1 atm);
               G from the Poisson ratio nu1 + nu2 exp(-K/K_s) (G0 where that is 0); with water
               (saturation > 0) in compression Gassmann's K = K_d + (1 - K_d/K_s)^2 /
               ((1 - K_d/K_s)/K_s + phi (1/K_f - 1/K_s)), K_f of the water (2.21 GPa, n 6.029) and
               air (1.4 (p + 1 atm)) at the pore pressure pbar_w
  yield        ``<plastic_yield_condition type="arena">``: sqrt(J2) = F_f(I1) F_c(I1) in the effective
               I1 = I1 + 3 pbar_w, F_f = a1 - a3 exp(a2 I1) - a4 I1 (from PEAKI1, FSLOPE, STREN, YSLOPE),
               the elliptic cap F_c^2 = 1 - ((kappa - I1)/(kappa - X))^2 below the branch point
               kappa = PEAKI1 - CR (PEAKI1 - X)
  return       Brannon's non-hardening return: the closest point of the yield surface in the
               transformed (z, r') = (I1/sqrt3, BETA sqrt(2 J2) sqrt(3K/2G)) plane, found by bisecting
               an I1 interval of a polyline of the surface; then the consistency bisection on the
               volumetric plastic strain increment (Uintah's "simplified" variant)
  hardening    the cap X = -(p0 + (1 - Sw0 + p1_sat Sw0) xi(ep_v) + 3 pbar_w) with the crush curve
               xi = p1 (phi0/phi - 1)^(1/p2), phi = 1 - exp(-p3 + ep_v); pore pressure, porosity and
               saturation from the air and water volume changes
  substeps     as many as the change of K and the stress increment relative to the yield surface
               size (times yield_surface_radius_scaling_factor) ask; up to
               subcycling_characteristic_number, tenfold smaller ones where a substep fails
  damage       p.COHER = min(old, x/(1 + x)), x = exp(-fspeed (p.TGROW/time_at_failure - 1)), p.TGROW
               summing the plastic part of each plastic substep's time; with do_damage the moduli
               are scaled by it and the yield parameters move to their failed values
  rate         Duvaut-Lions overstress relaxation with tau = T1 |D|^-T2 (both > 0)

State (Uintah's labels): p.plasticStrainTensor (Uintah's p.plasticStrain, a tensor here held
under its own name because p.plasticStrain is the scalar of the J2 models), p.plasticCumEqStrain,
p.plasticVolStrain, p.capX, p.porePressure (the backstress -pbar_w I), p.porosity,
p.saturation, p.p3, p.elasticVolStrain, p.stressQS (the rate-independent stress), p.COHER,
p.TGROW and the yield parameters of each particle p.ArenaPEAKI1 ... p.ArenaT2.

As in Uintah: the rate-dependent step starts from the old quasistatic stress (Uintah's
stateDynamic_old holds it), so p.stress is the relaxed step from p.stressQS; the wave speed
comes from the moduli at the new unrotated quasistatic stress; the strain energy is the
increment D : (sigma_old + sigma_new)/2 V dt.  Not implemented (refused): Weibull
variability of the yield parameters, use_disaggregation_algorithm.  A particle whose
update fails keeps its old state (Uintah deletes it) with a note.
"""
import sys
from dataclasses import dataclass

import numpy as np
from numba import njit

from framework.problemspec import Param

from ._common import det3, matmul3

ENERGY_IS_INCREMENT = True
SQ2, SQ3 = np.sqrt(2.0), np.sqrt(3.0)
DBL_MIN, DBL_MAX = np.finfo(np.float64).tiny, np.finfo(np.float64).max
STATE = ("p.plasticStrainTensor", "p.plasticCumEqStrain", "p.plasticVolStrain", "p.capX", "p.porePressure",
         "p.porosity", "p.saturation", "p.p3", "p.elasticVolStrain", "p.stressQS", "p.COHER", "p.TGROW",
         "p.ArenaPEAKI1", "p.ArenaFSLOPE", "p.ArenaSTREN", "p.ArenaYSLOPE", "p.ArenaBETA", "p.ArenaCR",
         "p.ArenaT1", "p.ArenaT2")
YIELD_STATE = 12        # STATE[12:]: the yield parameters of each particle

TOP = {
    "initial_porosity": Param("float", doc="phi0", above=0.0),
    "initial_saturation": Param("float", doc="Sw0, 0..1", at_least=0.0),
    "initial_fluid_pressure": Param("float", doc="pbar_w0 (Pa)", at_least=0.0),
    "reference_porosity": Param("float", -1.0, doc="porosity of the calibration (default phi0)"),
    "yield_surface_radius_scaling_factor": Param("float", 1.0, doc="1..1e6", at_least=1.0),
    "consistency_bisection_tolerance": Param("float", 1.0e-4, doc="1e-16..1e-2", at_least=1.0e-16),
    "subcycling_characteristic_number": Param("int", 256, doc="most substeps", at_least=1),
    "use_disaggregation_algorithm": Param("bool", False, (False,), "Uintah's disaggregation is not implemented"),
    "p0": Param("float", doc="crush curve: initial strength (Pa; at least 1000)"),
    "p1": Param("float", doc="crush curve scale (Pa)"),
    "p1_sat": Param("float", doc="p1 factor of the saturated part"),
    "p1_density_scale_fac": Param("float", 0.0, doc="Pabst-Gregorova scaling of p1"),
    "p2": Param("float", doc="crush curve exponent", above=0.0),
    "p3": Param("float", doc="read; the model uses -ln(1 - phi0), as Uintah's"),
    "do_damage": Param("bool", False, doc="coherence scales moduli and yield parameters"),
    "fspeed": Param("float", 1.0e-9, doc="damage growth speed"),
    "time_at_failure": Param("float", 1.0e9, doc="damage time scale (s)", above=0.0),
    "eq_plastic_strain_at_failure": Param("float", 1.0e9, doc="read; not used by Uintah's model"),
    "K0_Murnaghan_EOS": Param("float", 2.5e8, doc="MPMICE only: read"),
    "n_Murnaghan_EOS": Param("float", 13.0, doc="MPMICE only: read"),
}
ELASTIC = {t: Param("float", doc=f"bulk modulus parameter {t}") for t in ("b0", "b1", "b2", "b3", "b4")}
ELASTIC.update({"G0": Param("float", doc="shear modulus (Pa)", above=0.0),
                "nu1": Param("float", doc="Poisson ratio"), "nu2": Param("float", doc="Poisson ratio term")})
YIELD = {t: Param("float", doc=t, at_least=0.0) for t in ("PEAKI1", "FSLOPE", "STREN", "YSLOPE", "T1", "T2")}
YIELD.update({"BETA": Param("float", doc="nonassociativity", above=0.0),
              "CR": Param("float", doc="cap shape, 0 < CR < 1", above=0.0)})
FAILED = ("PEAKI1_failed", "FSLOPE_failed", "STREN_failed", "YSLOPE_failed")

# indices of the parameter vector handed to the kernel
(PHI0, SW0, PBW0, P0, P1, P1SAT, P2, B0, B1, B2, B3, B4, G0, NU1, NU2, SCALE, TOL, IMAX, NMAX, YFAC, DAMAGE,
 FSPEED, TFAIL, PK_F, FS_F, ST_F, YS_F, NPRM) = range(28)


@dataclass(frozen=True)
class Params:
    prm: tuple            # the kernel's parameter vector (indices above)
    yield_params: tuple   # PEAKI1, FSLOPE, STREN, YSLOPE, BETA, CR, T1, T2


def _limit_ok(PEAKI1, FSLOPE, STREN, YSLOPE):
    """One of Uintah's four shapes of the shear limit surface."""
    return ((FSLOPE > 0 and PEAKI1 >= 0 and STREN == 0 and YSLOPE == 0)
            or (FSLOPE == 0 and PEAKI1 == 0 and STREN > 0 and YSLOPE == 0)
            or (FSLOPE > 0 and YSLOPE == 0 and STREN > 0 and PEAKI1 == 0)
            or (FSLOPE > YSLOPE > 0 and STREN > YSLOPE * PEAKI1 and PEAKI1 >= 0))


def read_params(cm, material, props):
    """Params from <constitutive_model type="ArenaSoil"> and its two sub-model nodes."""
    top = cm.read(TOP)
    em = cm.child("elastic_moduli_model", required=True)
    em.attr("type", choices=("arena",))
    el = em.read(ELASTIC)
    yc = cm.child("plastic_yield_condition", required=True)
    yc.attr("type", choices=("arena",))
    y = yc.read(YIELD)
    for t in YIELD:
        if yc.has(f"weibullDist_{t}"):
            raise yc.child(f"weibullDist_{t}").error("Weibull variability of the yield parameters is not "
                                                     f"implemented; give the plain <{t}> only")
    defaults = (1.0e-5, 0.5 * y["FSLOPE"], 0.1 * y["STREN"], 1.0e-5)
    failed = [yc.get(t, "float", d, at_least=0.0) for t, d in zip(FAILED, defaults)]
    if not _limit_ok(y["PEAKI1"], y["FSLOPE"], y["STREN"], y["YSLOPE"]):
        raise yc.error("bad shear limit surface: accepted PEAKI1, FSLOPE, STREN, YSLOPE of linear Drucker-Prager "
                       "(STREN = YSLOPE = 0), von Mises (only STREN), or FSLOPE > YSLOPE > 0, STREN > YSLOPE PEAKI1")
    if not y["CR"] < 1.0:
        raise yc.child("CR").error("CR must be below 1")
    if (y["T1"] > 0) != (y["T2"] > 0):
        raise yc.error("rate dependence needs both T1 and T2 positive (or both 0)")
    if not el["b0"] > 0 or min(el["b1"], el["b2"], el["b3"]) < 0 or el["b4"] < 1:
        raise em.error("the arena bulk modulus needs b0 > 0, b1, b2, b3 >= 0 and b4 >= 1")
    if not top["initial_porosity"] < 1.0 or top["initial_saturation"] > 1.0:
        raise cm.error("needs 0 < initial_porosity < 1 and 0 <= initial_saturation <= 1")
    tol = top["consistency_bisection_tolerance"]
    if tol > 1.0e-2:
        raise cm.child("consistency_bisection_tolerance").error("must be in [1e-16, 1e-2]")
    if top["yield_surface_radius_scaling_factor"] > 1.0e6:
        raise cm.child("yield_surface_radius_scaling_factor").error("must be in [1, 1e6]")
    phi0 = top["initial_porosity"]
    phi_ref = top["reference_porosity"] if top["reference_porosity"] >= 0 else phi0
    scale = np.exp(-phi0 / (1.0 - phi0) + phi_ref / (1.0 - phi_ref))     # Pabst and Gregorova 2015
    b1, b3 = el["b1"], el["b3"] if el["b1"] >= 1.0e-16 else 0.0
    prm = [0.0] * NPRM
    prm[PHI0], prm[SW0], prm[PBW0] = phi0, top["initial_saturation"], top["initial_fluid_pressure"]
    prm[P0] = max(top["p0"], 1000.0)
    prm[P1] = top["p1"] * np.exp(top["p1_density_scale_fac"] * scale * (scale - 1.0))
    prm[P1SAT], prm[P2] = top["p1_sat"], top["p2"]
    prm[B0], prm[B1], prm[B2], prm[B3], prm[B4] = el["b0"], b1, el["b2"], b3, el["b4"]
    prm[G0], prm[NU1], prm[NU2] = el["G0"], el["nu1"], el["nu2"]
    prm[SCALE], prm[TOL] = scale, tol
    prm[IMAX] = float(np.ceil(-10.0 * np.log(tol)))
    prm[NMAX], prm[YFAC] = float(top["subcycling_characteristic_number"]), top["yield_surface_radius_scaling_factor"]
    prm[DAMAGE], prm[FSPEED], prm[TFAIL] = float(top["do_damage"]), top["fspeed"], top["time_at_failure"]
    prm[PK_F], prm[FS_F], prm[ST_F], prm[YS_F] = failed
    ys = tuple(y[t] for t in ("PEAKI1", "FSLOPE", "STREN", "YSLOPE", "BETA", "CR", "T1", "T2"))
    return Params(tuple(prm), ys)


def initial_state(params, n, temperature=None):
    """Uintah's initializeCMData: no plastic strain, the cap at the crush curve's start
    (shifted by the initial pore pressure), backstress -pbar_w0 I, phi0, Sw0, p3 = -ln(1 - phi0),
    coherence 1, the yield parameters of the deck."""
    prm = params.prm
    pbw0, phi0, sw0, p0 = prm[PBW0], prm[PHI0], prm[SW0], prm[P0]
    capX = -(p0 + 3.0 * pbw0) if sw0 > 0.0 else -p0
    back = np.zeros((n, 3, 3))
    if pbw0 > 0.0:
        back[:, 0, 0] = back[:, 1, 1] = back[:, 2, 2] = -pbw0
    sqs = np.zeros((n, 3, 3))
    sqs[:, 0, 0] = sqs[:, 1, 1] = sqs[:, 2, 2] = pbw0
    out = [np.zeros((n, 3, 3)), np.zeros(n), np.zeros(n), np.full(n, capX), back, np.full(n, phi0),
           np.full(n, sw0), np.full(n, -np.log(1.0 - phi0)), np.zeros(n), sqs, np.ones(n), np.zeros(n)]
    out += [np.full(n, v) for v in params.yield_params]
    return tuple(out)


# -- the fluids and grains --------------------------------------------------------------------
@njit(cache=True)
def _K_grain(p):
    return 40.0e9 + 4.0 * (p - 101325.0) if p > 0.0 else 40.0e9


@njit(cache=True)
def _K_water(p):
    return 2.21e9 if p < 1.0e-4 else 2.21e9 + 6.029 * (p - 1.0e-4)


@njit(cache=True)
def _K_air(p):
    return 1.4 * 101325.0 if p < 0.0 else 1.4 * (p + 101325.0)


@njit(cache=True)
def _ev_air(p):
    return 0.0 if p < 0.0 else -1.0 / 1.4 * np.log(p / 101325.0 + 1.0)


@njit(cache=True)
def _ev_water(p, p0):
    e0 = 0.0 if p0 < 1.0e-4 else -(p0 - 1.0e-4) / _K_water(p0)
    e = 0.0 if p < 1.0e-4 else -(p - 1.0e-4) / _K_water(p)
    return e - e0


@njit(cache=True)
def _drained(I1bar, prm):
    """Drained K, G at the compressive effective I1bar."""
    if I1bar > 0.0:
        p = I1bar / 3.0
        Ks = _K_grain(p)
        KsRatio = Ks / (1.0 - 4.0 * p / Ks)
        if prm[B1] > 1.0e-30:
            ev = ((prm[B3] * p) / (prm[B1] * Ks - prm[B2] * p)) ** (1.0 / prm[B4])
            y = ev ** prm[B4]
            z = prm[B2] * y + prm[B3]
            K = KsRatio * (prm[B0] + (1.0 / ev) * prm[B1] * prm[B3] * prm[B4] * y / (z * z))
        else:
            K = KsRatio * prm[B0]
    else:
        Ks = 40.0e9
        K = prm[B0] * Ks
    nu = prm[NU1] + prm[NU2] * np.exp(-K / Ks)
    G = 1.5 * K * (1.0 - 2.0 * nu) / (1.0 + nu) if nu > 0.0 else prm[G0]
    return K, G


@njit(cache=True)
def _moduli(I1_eff, pbar_w, phi, Sw, coher, prm):
    """Tangent K, G at a state (Uintah's computeElasticProperties)."""
    I1bar = -I1_eff
    K, G = _drained(I1bar, prm)
    if Sw > 0.0 and I1bar > 0.0:      # Gassmann with the pore fluid
        Ks = _K_grain(I1bar / 3.0)
        Kf = 1.0 / (Sw / _K_water(pbar_w) + (1.0 - Sw) / _K_air(pbar_w))
        r = 1.0 - K / Ks
        K = K + r * r / (1.0 / Ks * r + phi * (1.0 / Kf - 1.0 / Ks))
    K *= prm[SCALE]
    G *= prm[SCALE]
    if prm[DAMAGE] != 0.0:
        K *= coher + 1.0e-16
        G *= coher + 1.0e-16
    return K, G


# -- the yield surface -----------------------------------------------------------------------
@njit(cache=True)
def _invariants(sig, pbar_w):
    """(I1_eff, sqrt(J2), deviator) with Uintah's round-off cut of J2."""
    I1 = sig[0, 0] + sig[1, 1] + sig[2, 2]
    s = sig - (I1 / 3.0) * np.eye(3)
    J2 = 0.5 * np.sum(s * s)
    if J2 < 1e-16 * (I1 * I1 + J2):
        J2 = 0.0
    return I1 + pbar_w * 3.0, np.sqrt(J2), s


@njit(cache=True)
def _limit(yp):
    """a1..a4 of F_f from PEAKI1, FSLOPE, STREN, YSLOPE."""
    PEAKI1, FSLOPE, STREN, YSLOPE = yp[0], yp[1], yp[2], yp[3]
    if FSLOPE > 0.0 and PEAKI1 >= 0.0 and STREN == 0.0 and YSLOPE == 0.0:
        return PEAKI1 * FSLOPE, 0.0, 0.0, FSLOPE
    if FSLOPE == 0.0 and PEAKI1 == 0.0 and STREN > 0.0 and YSLOPE == 0.0:
        return STREN, 0.0, 0.0, 0.0
    if FSLOPE > 0.0 and YSLOPE == 0.0 and STREN > 0.0 and PEAKI1 == 0.0:
        return STREN, FSLOPE / STREN, STREN, 0.0
    a2 = (FSLOPE - YSLOPE) / (STREN - YSLOPE * PEAKI1)
    return STREN, a2, (STREN - YSLOPE * PEAKI1) * np.exp(-a2 * PEAKI1), YSLOPE


@njit(cache=True)
def _yields(I1, sqrtJ2, X, yp):
    """Is (I1_eff, sqrt J2) outside the surface with cap X_eff (Uintah's evalYieldCondition)."""
    a1, a2, a3, a4 = _limit(yp)
    PEAKI1 = yp[0]
    Ff = a1 - a3 * np.exp(a2 * I1) - a4 * I1
    kappa = PEAKI1 - yp[5] * (PEAKI1 - X)
    if I1 < X:
        return True
    if X < I1 and I1 < kappa:
        r = (kappa - I1) / (kappa - X)
        return sqrtJ2 * sqrtJ2 > Ff * Ff * (1.0 - r * r)
    if I1 <= PEAKI1:
        return sqrtJ2 > Ff
    return True


@njit(cache=True)
def _sqrtJ2_max(X, yp):
    """Largest sqrt J2 of the surface over 11 points of the I1 range."""
    a1, a2, a3, a4 = _limit(yp)
    PEAKI1 = yp[0]
    kappa = PEAKI1 - yp[5] * (PEAKI1 - X)
    rad = 0.5 * (PEAKI1 - X)
    cen = 0.5 * (PEAKI1 + X)
    J2max = DBL_MIN
    delta = np.pi / 10.0
    for i in range(11):
        I1 = cen + rad * np.cos(delta * i)
        Ff = a1 - a3 * np.exp(a2 * I1) - a4 * I1
        Fc = 1.0
        if I1 < kappa and X < I1:
            r = (kappa - I1) / (kappa - X)
            Fc = 1.0 - r * r
        J2max = max(J2max, Ff * Ff * Fc)
    return np.sqrt(J2max)


@njit(cache=True)
def _closest(zt, rt, X, K, G, yp):
    """Closest point (z, r') of the surface to (zt, rt): the nearest point of a polyline of
    the surface over an I1 interval halved towards it until it settles."""
    a1, a2, a3, a4 = _limit(yp)
    PEAKI1, BETA = yp[0], yp[4]
    kappa = PEAKI1 - yp[5] * (PEAKI1 - X)
    sqrtKG = np.sqrt(1.5 * K / G)
    dia = max((PEAKI1 - X) / SQ3, 2.0 * _sqrtJ2_max(X, yp) * SQ2 * sqrtKG)
    ratio = np.sqrt(zt * zt + rt * rt) / dia
    npts = 5
    if ratio > 0.0 and np.log(ratio) > 5.0:
        npts = int(np.ceil(np.log(ratio)))
    lo_I1, hi_I1 = X, PEAKI1
    eta_lo, eta_hi = 0.0, 1.0
    mid_I1 = 0.5 * (lo_I1 + hi_I1)
    eta_mid = 0.5
    rad = 0.5 * (PEAKI1 - X)
    cen = 0.5 * (PEAKI1 + X)
    zs = np.empty(npts + 1)
    rs = np.empty(npts + 1)
    zc = rc = 0.0
    zo, ro = DBL_MAX, DBL_MAX
    it = 1
    while abs(eta_hi - eta_lo) > 1.0e-10:
        th_max = np.arccos(max((lo_I1 - cen) / rad, -1.0))
        th_min = np.arccos(min((hi_I1 - cen) / rad, 1.0))
        delta = (th_max - th_min) / npts
        for i in range(npts + 1):
            I1 = max(cen + rad * np.cos(th_min + delta * i), X)
            Ff = a1 - a3 * np.exp(a2 * I1) - a4 * I1
            Fc = 1.0
            if I1 < kappa:
                r = (kappa - I1) / (kappa - X)
                Fc = max(1.0 - r * r, 0.0)
            zs[i] = I1 / SQ3
            rs[i] = BETA * np.sqrt(2.0 * (Ff * Ff * Fc)) * sqrtKG
        best = DBL_MAX
        for i in range(npts):
            mx, my = zs[i + 1] - zs[i], rs[i + 1] - rs[i]
            nx, ny = zt - zs[i], rt - rs[i]
            mm = mx * mx + my * my
            px, py = zs[i], rs[i]
            if mm >= 1.0e-12:
                t0 = (mx * nx + my * ny) / mm
                if t0 >= 1.0:
                    px, py = zs[i + 1], rs[i + 1]
                elif t0 > 0.0:
                    px, py = mx * t0 + zs[i], my * t0 + rs[i]
            d = (zt - px) ** 2 + (rt - py) ** 2
            if d < best:
                best, zc, rc = d, px, py
        if SQ3 * zc < mid_I1:
            hi_I1, eta_hi = mid_I1, eta_mid
        else:
            lo_I1, eta_lo = mid_I1, eta_mid
        mid_I1 = 0.5 * (lo_I1 + hi_I1)
        eta_mid = 0.5 * (eta_lo + eta_hi)
        if it > 10 and (zc - zo) ** 2 + (rc - ro) ** 2 < 1.0e-16:
            break
        zo, ro = zc, rc
        it += 1
    return zc, rc


@njit(cache=True)
def _return(deps, sig_old, ep_old, K, G, pbw_trial, pbar_w, X, p3, sig_trial, yp):
    """Non-hardening return of sig_trial to the surface at fixed internal variables (cap X,
    pore pressure pbar_w): (ok, sig_fixed, plastic strain increment).  The trial point's
    effective I1 takes pbw_trial: in the consistency bisection Uintah keeps the trial state's
    invariants of the substep's start."""
    BETA = yp[4]
    sqrtKG = np.sqrt(1.5 * K / G)
    I1t, sJt, st = _invariants(sig_trial, pbw_trial)
    zc, rc = _closest(I1t / SQ3, BETA * (SQ2 * sJt) * sqrtKG, X + 3.0 * pbar_w, K, G, yp)
    I1c = SQ3 * zc - 3.0 * pbar_w
    sJc = 1.0 / (sqrtKG * BETA * SQ2) * rc
    sig = (1.0 / 3.0 * I1c) * np.eye(3) + ((sJc / sJt) * st if sJt > 0.0 else st)
    dsig = sig - sig_old
    iso = (1.0 / 3.0 * np.trace(dsig)) * np.eye(3)
    dep = deps - (iso * (1.0 / 3.0 / K) + (dsig - iso) * (0.5 / G))
    ev = np.trace(ep_old + dep)
    return not (ev < 0.0 and -ev > p3), sig, dep


@njit(cache=True)
def _Xbar_drained(epsbar, p3, prm):
    """Drained hydrostatic compressive strength: p0 + the crush curve."""
    X = prm[P0]
    if epsbar > 0.0:
        e = min(epsbar, 0.99999999 * p3)
        ptmp = np.exp(-p3 + e)
        phi = 1.0 - ptmp
        X += prm[P1] * max(prm[PHI0] / phi - 1.0, 0.0) ** (1.0 / prm[P2])
    return X


@njit(cache=True)
def _internal(ev_p, pbar_w, phi, Sw, p3, dev_p, prm):
    """Internal variables after the volumetric plastic strain increment dev_p from the
    state (ev_p, pbar_w, phi, Sw): (ok, pbar_w, phi, Sw, capX)."""
    phi0, Sw0, pbw0 = prm[PHI0], prm[SW0], prm[PBW0]
    dbar = -dev_p
    ebar = -ev_p
    if ebar + dbar > p3:
        return False, pbar_w, phi, Sw, 0.0
    iKa, iKw = 1.0 / _K_air(pbar_w), 1.0 / _K_water(pbar_w)
    ea0 = _ev_air(pbw0)
    ea = max(-(_ev_air(pbar_w) - ea0), 0.0)
    ew = max(-_ev_water(pbar_w, pbw0), 0.0)
    xa, xw = np.exp(ebar - ea), np.exp(ebar - ew)
    Bp = 1.0 / ((1.0 - Sw0) * xa + Sw0 * xw) * (-(1.0 - phi) * (phi / phi0) * (Sw * iKw + (1.0 - Sw) * iKa)
                                                + (1.0 - Sw0) * iKa * xa + Sw0 * iKw * xw)
    pw = max(pbar_w + 1.0 / Bp * dbar, 0.0)
    enew = ebar + dbar
    ea = max(-(_ev_air(pw) - ea0), 0.0)
    ew = max(-_ev_water(pw, pbw0), 0.0)
    Cp = Sw0 * np.exp(ea - ew)
    Sw_new = Cp / (1.0 - Sw0 + Cp)
    phi_new = (1.0 - Sw0) * phi0 * np.exp(enew - ea) + Sw0 * phi0 * np.exp(enew - ew)
    Xd = _Xbar_drained(enew, p3, prm)
    Xbar = prm[P0] + (1.0 - Sw0 + prm[P1SAT] * Sw0) * (Xd - prm[P0]) + 3.0 * pw
    if phi_new > 1.0:
        return False, pbar_w, phi, Sw, 0.0
    return True, pw, phi_new, Sw_new, -Xbar


@njit(cache=True)
def _trial(sig, deps, K, G):
    iso = (1.0 / 3.0 * np.trace(deps)) * np.eye(3)
    return sig + iso * (3.0 * K) + (deps - iso) * (2.0 * G)


@njit(cache=True)
def _substep(D, dt, st, ep, yp, prm):
    """One substep of time dt from the state st = (sigma, capX, pbar_w, phi, Sw, p3, coherence,
    t_grow, ep_cum_eq, K, G) and the plastic strain ep: (ok, new state, new plastic strain).
    Elastic, or the non-hardening return followed by the consistency bisection."""
    sig, capX, pbw, phi, Sw, p3, coh, tg, epeq, K, G = st
    deps = D * dt
    sig_t = _trial(sig, deps, K, G)
    I1t, sJt, _ = _invariants(sig_t, pbw)
    if not _yields(I1t, sJt, capX + 3.0 * pbw, yp):
        Kt, Gt = _moduli(I1t, pbw, phi, Sw, coh, prm)
        return True, (sig_t, capX, pbw, phi, Sw, p3, coh, tg, epeq, Kt, Gt), ep
    ok, sig_f, dep_f = _return(deps, sig, ep, K, G, pbw, pbw, capX, p3, sig_t, yp)
    if not ok:
        return False, st, ep
    # consistency bisection on the volumetric plastic strain increment (Uintah's simplified one)
    ev_old = np.trace(ep)
    dv_fixed = np.trace(dep_f)
    sig_fn, dep_fn, dv_fn = sig_f, dep_f, dv_fixed
    lo, hi = 0.0, 1.0
    ii = 1
    while abs(hi - lo) > prm[TOL]:
        mid = 0.5 * (lo + hi)
        ok, pw_m, phi_m, Sw_m, X_m = _internal(ev_old, pbw, phi, Sw, p3, mid * dv_fixed, prm)
        if not ok:
            return False, st, ep
        if not _yields(I1t, sJt, X_m + 3.0 * pw_m, yp):     # the trial invariants of the start, as Uintah
            hi = mid
            ii += 1
            continue
        ok, sig_fn, dep_fn = _return(deps, sig, ep, K, G, pbw, pw_m, X_m, p3, sig_t, yp)
        if not ok:
            return False, st, ep
        if np.signbit(np.trace(sig_t - sig_fn)) != np.signbit(np.trace(sig_t - sig_f)):
            hi = mid
            ii += 1
            continue
        dv_fn = np.trace(dep_fn)
        dv_fixed = mid * np.trace(dep_f)       # as Uintah: the next midpoint scales this
        if abs(dv_fn) > mid * abs(dv_fixed):
            lo = mid
        else:
            hi = mid
        ii += 1
        if ii > prm[IMAX]:
            return False, st, ep
    ok, pw_n, phi_n, Sw_n, X_n = _internal(ev_old, pbw, phi, Sw, p3, dv_fn, prm)
    if not ok:
        return False, st, ep
    ep_n = ep + dep_fn
    I1n, _, _ = _invariants(sig_fn, pw_n)
    Kn, Gn = _moduli(I1n, pw_n, phi_n, Sw_n, coh, prm)
    dd = dep_fn - (np.trace(dep_fn) / 3.0) * np.eye(3)
    epeq_n = epeq + np.sqrt(2.0 / 3.0 * np.sum(dd * dd))
    # damage: the plastic fraction of the substep's time grows TGROW
    dn = np.sqrt(np.sum(deps * deps))
    dpn = np.sqrt(np.sum((ep_n - ep) ** 2))
    tg_n = tg + min(dt, (dpn / dn) * dt)
    x = np.exp(-prm[FSPEED] * (tg_n / prm[TFAIL] - 1.0))
    coh_n = min(x / (1.0 + x), coh)
    return True, (sig_fn, X_n, pw_n, phi_n, Sw_n, p3, coh_n, tg_n, epeq_n, Kn, Gn), ep_n


@njit(cache=True)
def _rate_independent(D, delT, st, ep, yp, prm):
    """Substepped quasistatic update: (ok, state, plastic strain)."""
    deps = D * delT
    if np.sqrt(np.sum(deps * deps)) < 1.0e-30:
        return True, st, ep
    sig, capX, pbw, phi, Sw, p3, coh, tg, epeq, K, G = st
    sig_t = _trial(sig, deps, K, G)
    I1t, _, _ = _invariants(sig_t, pbw)
    Kt, _ = _moduli(I1t, pbw, phi, Sw, coh, prm)
    n_bulk = max(np.ceil(abs(K - Kt) / K), 1.0)
    X = capX + 3.0 * pbw
    size = max(0.5 * (yp[0] - X), _sqrtJ2_max(X, yp)) * prm[YFAC]
    n_yield = np.ceil(np.sqrt(np.sum((sig_t - sig) ** 2)) / size)
    nsub = max(max(n_bulk, n_yield), 1.0)
    if nsub > prm[NMAX]:
        return False, st, ep
    dt = delT / int(nsub)
    chi = 1
    t = 0.0
    while True:
        ok, st_n, ep_n = _substep(D, dt, st, ep, yp, prm)
        if ok:
            t += dt
            st, ep = st_n, ep_n
        else:
            dt /= 10.0
            chi += 1
            if chi > 5:
                return False, st, ep
        if not t < delT:
            break
    return True, st, ep


@njit(cache=True)
def _inv_T(a):
    """(a^-1)^T: the cofactors over the determinant."""
    d = 1.0 / det3(a)
    c = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            i1, i2, j1, j2 = (i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3
            c[i, j] = (a[i1, j1] * a[i2, j2] - a[i1, j2] * a[i2, j1]) * d
    return c


@njit(cache=True)
def _rotate(R, A, forward):
    return matmul3(matmul3(R, A), R.T) if forward else matmul3(matmul3(R.T, A), R)


@njit(cache=True)
def _rotation(F):
    """R of F = R U (Newton's R <- (R + R^-T)/2)."""
    R = F.copy()
    for _ in range(100):
        Rn = 0.5 * (R + _inv_T(R))
        ch = np.max(np.abs(Rn - R))
        R = Rn
        if ch < 1.0e-15:
            break
    return R


@njit(cache=True)
def kernel(prm, L, F_old, F_new, vol, mass, vel, dt, s_old, s_new, energy, ep_o, epeq_o, epv_o, capX_o, back_o,
           phi_o, Sw_o, p3_o, eev_o, sqs_o, coh_o, tg_o, yp_o, ep_n, epeq_n, epv_n, capX_n, back_n, phi_n, Sw_n,
           p3_n, eev_n, sqs_n, coh_n, tg_n, yp_n, failed):
    """Every particle's stress, state and strain energy increment; the wave speed (3,).
    yp_o / yp_n: (n, 8) yield parameters. failed[0] counts the particles whose update failed."""
    ws = np.zeros(3)
    for p in range(F_new.shape[0]):
        Ls = L[p]
        Ro = _rotation(F_old[p])
        D = _rotate(Ro, 0.5 * (Ls + Ls.T), False)
        sqs_old = _rotate(Ro, sqs_o[p], False)
        yp = yp_o[p].copy()
        pbw = -np.trace(back_o[p]) / 3.0
        I1, _, _ = _invariants(sqs_old, pbw)
        K, G = _moduli(I1, pbw, phi_o[p], Sw_o[p], coh_o[p], prm)
        st = (sqs_old, capX_o[p], pbw, phi_o[p], Sw_o[p], p3_o[p], coh_o[p], tg_o[p], epeq_o[p], K, G)
        ok, st_n, ep = _rate_independent(D, dt, st, ep_o[p].copy(), yp, prm)
        if not ok:
            failed[0] += 1
            st_n, ep = st, ep_o[p].copy()
        sq, capX, pw, phi, Sw, p3, coh, tg, epeq, Kq, Gq = st_n
        ep_n[p] = ep
        epeq_n[p] = epeq
        epv_n[p] = np.trace(ep)
        capX_n[p] = capX
        back_n[p] = -pw * np.eye(3)
        phi_n[p], Sw_n[p], p3_n[p], coh_n[p], tg_n[p] = phi, Sw, p3, coh, tg
        Fn = F_new[p]
        eev_n[p] = np.log(det3(Fn)) - epv_n[p] if ok else eev_o[p]
        # Duvaut-Lions relaxation towards the quasistatic stress (from the old quasistatic one)
        sig = sq
        if yp[6] != 0.0 and yp[7] != 0.0:
            I1o, _, _ = _invariants(sqs_o[p], pbw)
            Ko, Go = _moduli(I1o, pbw, phi_o[p], Sw_o[p], coh_o[p], prm)
            I1q, _, _ = _invariants(sq, pw)
            Kn, Gn = _moduli(I1q, pw, phi, Sw, coh, prm)
            deps = D * dt
            if np.sqrt(np.sum(deps * deps)) >= 1.0e-30:
                trial = _trial(sqs_old, deps, 0.5 * (Ko + Kn), 0.5 * (Go + Gn))
                tau = yp[6] * (1.0 / max(np.sqrt(np.sum(D * D)), 1.0e-15)) ** yp[7]
                dtt = dt / tau
                rh = np.exp(-dtt)
                RH = (1.0 - rh) / dtt
                sig = sq + ((trial - sqs_old) - (sq - sqs_o[p])) * RH + (sqs_old - sqs_o[p]) * rh
        J = det3(Fn)
        Rn = np.eye(3) if np.max(np.abs(Fn)) > 1.0e16 or J < 1.0e-16 or J > 1.0e16 else _rotation(Fn)
        s_new[p] = _rotate(Rn, sig, True)
        sqs_n[p] = _rotate(Rn, sq, True)
        I1q, _, _ = _invariants(sq, pw)
        Kw, Gw = _moduli(I1q, pw, phi, Sw, coh, prm)
        max_ws(ws, np.sqrt((Kw + 4.0 / 3.0 * Gw) / (mass[p] / vol[p])), vel, p)
        energy[p] = np.sum(D * 0.5 * (s_new[p] + s_old[p])) * vol[p] * dt
        if prm[DAMAGE] != 0.0:      # the yield parameters between intact and failed by the coherence
            c0, c1 = coh_o[p], coh
            for k in range(4):
                fail = prm[PK_F + k]
                intact = (yp[k] - (1.0 - c0) * fail) / c0
                yp_n[p, k] = c1 * intact + (1.0 - c1) * fail
            for k in range(4, 8):
                yp_n[p, k] = yp[k]
        else:
            yp_n[p] = yp
    return ws


@njit(cache=True)
def max_ws(ws, c, vel, p):
    for d in range(3):
        s = c + abs(vel[p, d])
        if s > ws[d]:
            ws[d] = s


@njit(cache=True)
def _initial_ws(prm, vol, mass, vel, stress, pbw0):
    """Uintah's first delT: the initial moduli K = b0 K_s, G from the Poisson ratio."""
    ws = np.zeros(3)
    K = 40.0e9 * prm[B0]
    nu = prm[NU1] + prm[NU2] * np.exp(-K / 40.0e9)
    G = 1.5 * K * (1.0 - 2.0 * nu) / (1.0 + nu) if nu > 0.0 else prm[G0]
    K *= prm[SCALE]
    G *= prm[SCALE]
    for p in range(vol.shape[0]):
        max_ws(ws, np.sqrt((K + 4.0 / 3.0 * G) * (vol[p] / mass[p])), vel, p)
        for i in range(3):
            stress[p, i, i] = pbw0
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old=None, new=None):
    """Stress and state old -> new (STATE order); returns the wave speed (3,).  dt = 0: the
    initial step (stress pbar_w0 I, the initial moduli's wave speed)."""
    prm = np.array(params.prm)
    if dt == 0.0:
        energy[:] = 0.0
        return _initial_ws(prm, vol, mass, vel, stress_new, params.prm[PBW0])
    yp_o = np.ascontiguousarray(np.stack(old[YIELD_STATE:], axis=1))
    yp_n = np.empty_like(yp_o)
    failed = np.zeros(1, np.int64)
    ws = kernel(prm, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, *old[:YIELD_STATE], yp_o,
                *new[:YIELD_STATE], yp_n, failed)
    for k, arr in enumerate(new[YIELD_STATE:]):
        arr[:] = yp_n[:, k]
    if failed[0]:
        print(f"pysus: note: ArenaSoil: the update of {failed[0]} particle(s) failed (too many substeps or no "
              "convergence); they keep their old state (Uintah deletes them)", file=sys.stderr)
    return ws
