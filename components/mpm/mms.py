"""Manufactured solutions for large deformations (<MPM><RunMMSProblem>, Uintah's tag).

A prescribed motion x = phi(X, t) of a comp_neo_hook solid is made exact by a body force
b = a - div(sigma) / rho on every particle, evaluated at its reference position
X = p.x - p.displacement and the step's start time (Uintah's MMS::computeExternalForceForMMS,
through p.externalforce). The motions start from rest and stop at t = mms_ramp_time with
the ramp s(t) = A (1 - cos(pi t / T)) / 2 (A = mms_amplitude), so no initial velocity field
is needed; the body force comes from the deck's own density, bulk and shear modulus.

  StretchedBar    uniaxial strain along x of the bar 0 <= X <= 1 (a 1D grid, or y/z faces
                  that are symmetry planes): u = s(t) g(X), g = X - sin(2 pi X) / (2 pi).
                  The ends stay unstretched (traction-free), the end X = 1 moves to 1 + A
                  (A = 1: the bar doubles its length, 3x locally at its middle).
  TwistedAnnulus  plane strain twist of the ring 0.75 <= R <= 1.25 about the z axis:
                  the angle alpha = s(t) h(R), h = (1 - 16 (R - 1)^2)^2 (Uintah's
                  GeneralizedVortex motion, isochoric; its shear R dalpha/dR reaches
                  7.1 A). Uintah's own MMS types are hard-coded for its cnh_mms model.

exact(kind, X, t, ...) gives the positions and Cauchy stresses the particles should have.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

KINDS = ("StretchedBar", "TwistedAnnulus")
UINTAH_KINDS = ("AxisAligned", "AxisAligned3L", "GeneralizedVortex", "ExpandingRing")
R_IN, R_OUT = 0.75, 1.25


@njit(cache=True)
def _ramp(t, A, T):
    """s, ds/dt, d2s/dt2 of s(t) = A (1 - cos(pi t / T)) / 2, held at A after T."""
    if t >= T:
        return A, 0.0, 0.0
    w = math.pi / T
    return 0.5 * A * (1.0 - math.cos(w * t)), 0.5 * A * w * math.sin(w * t), 0.5 * A * w * w * math.cos(w * t)


@njit(cache=True)
def bar_force(X, mass, t, A, T, K, mu, rho, out):
    """Uniaxial strain: rho0 u_tt = dP/dX + rho0 b, P = sigma_xx(lambda) of comp_neo_hook
    (J = lambda): sigma_xx = K/2 (l - 1/l) + 2 mu / 3 (l^(1/3) - l^(-5/3))."""
    s, _, sdd = _ramp(t, A, T)
    tp = 2.0 * math.pi
    for p in range(X.shape[0]):
        x0 = X[p, 0]
        g = x0 - math.sin(tp * x0) / tp
        lam = 1.0 + s * (1.0 - math.cos(tp * x0))
        dlam = s * tp * math.sin(tp * x0)
        dP = (0.5 * K * (1.0 + lam ** -2.0)                                  # d sigma_xx / d lambda
              + 2.0 * mu / 3.0 * (lam ** (-2.0 / 3.0) / 3.0 + 5.0 / 3.0 * lam ** (-8.0 / 3.0)))
        out[p, 0] = mass[p] * (sdd * g - dP * dlam / rho)
        out[p, 1] = 0.0
        out[p, 2] = 0.0


@njit(cache=True)
def annulus_force(X, mass, t, A, T, mu, rho, out):
    """Twist alpha(R, t): gamma = R alpha_R; comp_neo_hook with J = 1 gives sigma = mu dev(b):
    s_rr = s_zz = -mu gamma^2 / 3, s_tt = 2 mu gamma^2 / 3, s_rt = mu gamma, so
    b_r = -R alpha_t^2 + mu/rho (2 gamma gamma_R / 3 + gamma^2 / R),
    b_t = R alpha_tt - mu/rho (gamma_R + 2 gamma / R)."""
    s, sd, sdd = _ramp(t, A, T)
    for p in range(X.shape[0]):
        R = math.hypot(X[p, 0], X[p, 1])
        u = R - 1.0
        if abs(u) >= 0.25:
            out[p, 0] = out[p, 1] = out[p, 2] = 0.0
            continue
        q = 1.0 - 16.0 * u * u
        h = q * q
        dh = -64.0 * u * q
        d2h = -64.0 + 3072.0 * u * u
        g = R * s * dh
        dg = s * (dh + R * d2h)
        br = -R * (sd * h) ** 2 + mu / rho * (2.0 * g * dg / 3.0 + g * g / R)
        bt = R * sdd * h - mu / rho * (dg + 2.0 * g / R)
        th = math.atan2(X[p, 1], X[p, 0]) + s * h
        c, sn = math.cos(th), math.sin(th)
        out[p, 0] = mass[p] * (c * br - sn * bt)
        out[p, 1] = mass[p] * (sn * br + c * bt)
        out[p, 2] = 0.0


def exact(kind, X, t, A, T, K, mu):
    """The positions (n, 3) and Cauchy stresses (n, 3, 3) of particles at reference X (n, 3)."""
    s = _ramp(t, A, T)[0]
    x = np.array(X, float)
    sig = np.zeros((len(X), 3, 3))
    if kind == "StretchedBar":
        tp = 2.0 * np.pi
        x[:, 0] = X[:, 0] + s * (X[:, 0] - np.sin(tp * X[:, 0]) / tp)
        lam = 1.0 + s * (1.0 - np.cos(tp * X[:, 0]))
        pr = 0.5 * K * (lam - 1.0 / lam)
        dv = mu / 3.0 * (lam ** (1.0 / 3.0) - lam ** (-5.0 / 3.0))
        sig[:, 0, 0] = pr + 2.0 * dv
        sig[:, 1, 1] = sig[:, 2, 2] = pr - dv
        return x, sig
    R = np.hypot(X[:, 0], X[:, 1])
    u = np.clip(R - 1.0, -0.25, 0.25)
    h = (1.0 - 16.0 * u * u) ** 2
    g = R * s * (-64.0 * u * (1.0 - 16.0 * u * u))
    th = np.arctan2(X[:, 1], X[:, 0]) + s * h
    c, sn = np.cos(th), np.sin(th)
    x[:, 0], x[:, 1] = R * c, R * sn
    srr, stt, srt = -mu * g * g / 3.0, 2.0 * mu * g * g / 3.0, mu * g
    sig[:, 0, 0] = c * c * srr + sn * sn * stt - 2.0 * c * sn * srt
    sig[:, 1, 1] = sn * sn * srr + c * c * stt + 2.0 * c * sn * srt
    sig[:, 0, 1] = sig[:, 1, 0] = c * sn * (srr - stt) + (c * c - sn * sn) * srt
    sig[:, 2, 2] = srr
    return x, sig


class ManufacturedSolution:
    """The deck's <RunMMSProblem> with its material's constants; forces() per particle."""

    def __init__(self, mpm_node, flags, materials, level):
        self.kind = flags["RunMMSProblem"]
        node = mpm_node.child("RunMMSProblem")
        if self.kind in UINTAH_KINDS:
            raise node.error(f"{self.kind} is Uintah's manufactured solution hard-coded for its cnh_mms model, "
                             f"which pysus does not implement; accepted: {', '.join(KINDS)}")
        if self.kind not in KINDS:
            raise node.error(f"unknown manufactured solution {self.kind!r}; accepted: {', '.join(KINDS)}")
        if len(materials) != 1 or materials[0].model_name != "comp_neo_hook":
            raise node.error("a manufactured solution needs exactly one material, of type comp_neo_hook "
                             "(its body force comes from that model)")
        if self.kind == "TwistedAnnulus" and (level.collapsed[0] or level.collapsed[1]):
            raise node.error("TwistedAnnulus twists in the x-y plane: the grid needs cells along x and y")
        mat = materials[0]
        self.A, self.T = flags["mms_amplitude"], flags["mms_ramp_time"]
        self.rho, self.K, self.mu = mat.density, mat.params.bulk_modulus, mat.params.shear_modulus

    def forces(self, px, disp, mass, t):
        """p.externalforce: mass times the body force at X = p.x - p.displacement, time t."""
        out = np.empty((len(px), 3))
        X = px - disp
        if self.kind == "StretchedBar":
            bar_force(X, mass, t, self.A, self.T, self.K, self.mu, self.rho, out)
        else:
            annulus_force(X, mass, t, self.A, self.T, self.mu, self.rho, out)
        return out
