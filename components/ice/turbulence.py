"""<CFD><ICE><turbulence>: Uintah's ICE subgrid-scale viscosity models (TurbulenceModel/).

The turbulent (dynamic) viscosity mu_t is added to the molecular one in the viscous stress:

  Smagorinsky   mu_t = rho (C Delta)^2 |S|,        |S| = sqrt(2 S_ij S_ij)
  Germano       mu_t = C rho (Cs Delta)^2 |S|,     Cs^2 = <L_ij M_ij> / <M_ij M_ij>, clipped to
                [0, 10^2] (the dynamic procedure with a test filter of width 2 Delta)

Delta = (dx dy dz)^(1/3) (Uintah's implicit filter; Germano's <filter_width> is read and not
used, as in Uintah). S_ij is Uintah's grid strain rate from the face velocities uvel_FCME, ...:
the diagonal terms du/dx = (u_R - u_L)/dx, and the off-diagonal ones built from the same face
differences, S_xy = (du/dy + dv/dx)/2 with du = u_R - u_L over dy (Uintah's computeStrainRate).
The test filter is the 27-cell box filter of weights (1 - |i|/2)(1 - |j|/2)(1 - |k|/2)/8.

total_viscosity_CC = mu + mu_t in the interior and ghost cells where vol_frac > 0.9 (mu near an
interface); in the extra cells of the domain's faces mu (mu + mu_t) / (mu + 2 mu_t) of the
adjacent cell, so that the face's harmonic mean has no turbulent part (Turbulence::callTurb).
turb_viscosity_CC is mu_t in the interior cells, 0 in the extra cells.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

MODELS = ("Smagorinsky", "Germano")


@njit(cache=True)
def strain_rate(u, v, w, S, lo, hi, sh, dims, dx):
    """Uintah's grid strain rate S[..., 0:6] = (xx, yy, zz, xy, xz, yz) in the cells lo..hi from
    the face velocities (sh[d]: the local index of cell c's lower d-face is c - sh[d])."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                du = dv = dw = 0.0
                if dims[0]:
                    a, b, c = i - sh[0, 0], j - sh[0, 1], k - sh[0, 2]
                    du = u[a + 1, b, c] - u[a, b, c]
                if dims[1]:
                    a, b, c = i - sh[1, 0], j - sh[1, 1], k - sh[1, 2]
                    dv = v[a, b + 1, c] - v[a, b, c]
                if dims[2]:
                    a, b, c = i - sh[2, 0], j - sh[2, 1], k - sh[2, 2]
                    dw = w[a, b, c + 1] - w[a, b, c]
                S[i, j, k, 0] = du / dx[0]
                S[i, j, k, 1] = dv / dx[1]
                S[i, j, k, 2] = dw / dx[2]
                S[i, j, k, 3] = 0.5 * (du / dx[1] + dv / dx[0])
                S[i, j, k, 4] = 0.5 * (du / dx[2] + dw / dx[0])
                S[i, j, k, 5] = 0.5 * (dv / dx[2] + dw / dx[1])


@njit(cache=True)
def strain_magnitude(S, i, j, k):
    """|S| = sqrt(2 S_ij S_ij) of the six stored components."""
    return np.sqrt(2.0 * (S[i, j, k, 0] * S[i, j, k, 0] + S[i, j, k, 1] * S[i, j, k, 1]
                          + S[i, j, k, 2] * S[i, j, k, 2]
                          + 2.0 * (S[i, j, k, 3] * S[i, j, k, 3] + S[i, j, k, 4] * S[i, j, k, 4]
                                   + S[i, j, k, 5] * S[i, j, k, 5])))


@njit(cache=True)
def zero_neumann(q, lo, hi, elo, ehi, at_low, at_high):
    """Uintah's setZeroNeumannBC_CC on a work array: the extra cells of each domain face, in the
    order x-, x+, y-, y+, z-, z+, take their inner neighbour's value, along the face over
    elo..ehi (extra and ghost cells included)."""
    for d in range(3):
        for side in range(2):
            if not (at_low[d] if side == 0 else at_high[d]):
                continue
            e = lo[d] - 1 if side == 0 else hi[d]
            n = lo[d] if side == 0 else hi[d] - 1
            a0, a1 = elo.copy(), ehi.copy()
            a0[d], a1[d] = e, e + 1
            for i in range(a0[0], a1[0]):
                for j in range(a0[1], a1[1]):
                    for k in range(a0[2], a1[2]):
                        ii, jj, kk = (n, j, k) if d == 0 else ((i, n, k) if d == 1 else (i, j, n))
                        for c in range(q.shape[3]):
                            q[i, j, k, c] = q[ii, jj, kk, c]


@njit(cache=True)
def box_filter(q, out, lo, hi, dims):
    """Uintah's DynamicModel::applyFilter: out = the weighted 27-cell sum of q in the cells
    lo..hi, weights (1 - |i|/2)(1 - |j|/2)(1 - |k|/2)/8; a one-cell direction repeats its cell
    (the values of Uintah's symmetric extra cells there)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for c in range(q.shape[3]):
                    out[i, j, k, c] = 0.0
                for kk in range(-1, 2):
                    for jj in range(-1, 2):
                        for ii in range(-1, 2):
                            wgt = (1.0 - 0.5 * abs(ii)) * (1.0 - 0.5 * abs(jj)) * (1.0 - 0.5 * abs(kk)) / 8
                            a = i + ii if dims[0] else i
                            b = j + jj if dims[1] else j
                            e = k + kk if dims[2] else k
                            for c in range(q.shape[3]):
                                out[i, j, k, c] += q[a, b, e, c] * wgt


@njit(cache=True)
def smagorinsky_viscosity(S, rho, mu_t, lo, hi, term):
    """mu_t = rho (C Delta)^2 |S| in the cells lo..hi (term = (C Delta)^2)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                mu_t[i, j, k] = rho[i, j, k] * term * strain_magnitude(S, i, j, k)


PRODUCTS = np.array([[0, 0], [1, 1], [2, 2], [0, 1], [0, 2], [1, 2]], dtype=np.int64)


@njit(cache=True)
def dynamic_viscosity(S, vel, rho, mu_t, beta, work, hat, lo, hi, lo1, hi1, lo2, hi2, elo2, ehi2,
                      at_low, at_high, dims, fw, model_constant):
    """Germano's dynamic model (Uintah's DynamicModel::computeSmagCoeff) in the cells lo1..hi1:
    S (zero-Neumann extra cells) and vel (velTau_CC) given; beta = 2 Delta^2 |S| S_ij, the
    filtered S, beta and velocity products give L_ij = <u_i u_j> - <u_i><u_j> and
    M_ij = <beta_ij> - 2 (2 Delta)^2 |<S>| <S_ij>; Cs^2 = LM / MM (0 where LM <= 1e-20 or
    MM < 1e-20, Cs at most 10); mu_t = C rho (Cs Delta)^2 |S|. work, hat: (..., 6) scratch."""
    nx, ny, nz = S.shape[0], S.shape[1], S.shape[2]
    mean_s = np.zeros((nx, ny, nz))
    for i in range(lo2[0], hi2[0]):
        for j in range(lo2[1], hi2[1]):
            for k in range(lo2[2], hi2[2]):
                mean_s[i, j, k] = strain_magnitude(S, i, j, k)
                a = 2.0 * fw * fw * mean_s[i, j, k]
                for c in range(6):
                    beta[i, j, k, c] = a * S[i, j, k, c]
    zero_neumann(beta, lo, hi, elo2, ehi2, at_low, at_high)
    vel_hat = np.zeros((nx, ny, nz, 3))
    box_filter(vel, vel_hat, lo1, hi1, dims)
    s_hat = np.zeros((nx, ny, nz, 6))
    box_filter(S, s_hat, lo1, hi1, dims)
    beta_hat = np.zeros((nx, ny, nz, 6))
    box_filter(beta, beta_hat, lo1, hi1, dims)
    for i in range(elo2[0], ehi2[0]):
        for j in range(elo2[1], ehi2[1]):
            for k in range(elo2[2], ehi2[2]):
                for p in range(6):
                    work[i, j, k, p] = vel[i, j, k, PRODUCTS[p, 0]] * vel[i, j, k, PRODUCTS[p, 1]]
    zero_neumann(work, lo, hi, elo2, ehi2, at_low, at_high)
    box_filter(work, hat, lo1, hi1, dims)
    L = np.zeros(6)
    M = np.zeros(6)
    for i in range(lo1[0], hi1[0]):
        for j in range(lo1[1], hi1[1]):
            for k in range(lo1[2], hi1[2]):
                for p in range(6):
                    L[p] = hat[i, j, k, p] - vel_hat[i, j, k, PRODUCTS[p, 0]] * vel_hat[i, j, k, PRODUCTS[p, 1]]
                a = 2.0 * (2 * fw) * (2 * fw) * strain_magnitude(s_hat, i, j, k)
                for p in range(6):
                    M[p] = beta_hat[i, j, k, p] - a * s_hat[i, j, k, p]
                lm = L[0] * M[0] + L[1] * M[1] + L[2] * M[2] + 2 * (L[3] * M[3] + L[4] * M[4] + L[5] * M[5])
                mm = M[0] * M[0] + M[1] * M[1] + M[2] * M[2] + 2 * (M[3] * M[3] + M[4] * M[4] + M[5] * M[5])
                term = 0.0
                if mm >= 1.0e-20:
                    cs = 0.0
                    if lm > 1.0e-20:
                        cs = min(np.sqrt(lm / mm), 10.0)
                    term = (cs * fw) * (cs * fw)
                mu_t[i, j, k] = model_constant * rho[i, j, k] * term * mean_s[i, j, k]


@njit(cache=True)
def total_viscosity(mu, mu_t, vol_frac, tot, lo, hi, lo1, hi1, at_low, at_high):
    """Uintah's callTurb: tot = mu + mu_t where vol_frac > 0.9 (else mu) in the cells lo1..hi1;
    in the extra cells of the domain's faces (edges left 0) mu (mu + mu_t) / (mu + 2 mu_t) of
    the adjacent interior cell."""
    tot[...] = 0.0
    for d in range(3):
        for side in range(2):
            if not (at_low[d] if side == 0 else at_high[d]):
                continue
            e = lo[d] - 1 if side == 0 else hi[d]
            n = lo[d] if side == 0 else hi[d] - 1
            a0, a1 = lo.copy(), hi.copy()
            a0[d], a1[d] = e, e + 1
            for i in range(a0[0], a1[0]):
                for j in range(a0[1], a1[1]):
                    for k in range(a0[2], a1[2]):
                        ii, jj, kk = (n, j, k) if d == 0 else ((i, n, k) if d == 1 else (i, j, n))
                        m, t = mu[ii, jj, kk], mu_t[ii, jj, kk]
                        tot[i, j, k] = m * (m + t) / (m + 2 * t)
    for i in range(lo1[0], hi1[0]):
        for j in range(lo1[1], hi1[1]):
            for k in range(lo1[2], hi1[2]):
                if vol_frac[i, j, k] > 0.9:
                    tot[i, j, k] = mu[i, j, k] + mu_t[i, j, k]
                else:
                    tot[i, j, k] = mu[i, j, k]


class Turbulence:
    """One <turbulence model="..."> block: the model, its constant, and the task bodies' work."""

    def __init__(self, node, component):
        self.model = node.attr("model", choices=MODELS)
        self.dynamic = self.model == "Germano"
        self.model_constant = node.get("model_constant", "float")
        if self.dynamic:
            # required as in Uintah; its filter width is (dx dy dz)^(1/3) whatever this says
            self.filter_width_deck = node.get("filter_width", "float", above=0.0)
        fs = node.child("FilterScalar")
        if fs is not None:
            raise fs.error("<FilterScalar> (the scalar variance of Uintah's turbulence models) is not "
                           "available; accepted: <model_constant> and, for Germano, <filter_width>")
        for m, mat in enumerate(component.materials):
            if not mat.viscosity > 0.0:
                raise node.error(f"a turbulence model needs a non-zero <dynamic_viscosity> in every ICE "
                                 f"material (Uintah's rule); material {m} ('{mat.name}') has none")
        dx = component.level.dx
        self.fw = math.pow(dx[0] * dx[1] * dx[2], 1.0 / 3.0)
        self.ghost = 3 if self.dynamic else 2          # face velocities: the strain rate's footprint

    def ranges(self, patch, b, shape, ngc):
        """Local (lo, hi) of the interior cells grown by ngc ghost layers on the sides that have
        neighbours (Uintah's getCellIterator(ngc)), and the same with the domain faces' extra
        cells (getExtraCellIterator(ngc)), both clipped to the array."""
        lo, hi = b.lo.copy(), b.hi.copy()
        elo, ehi = b.lo.copy(), b.hi.copy()
        for d in range(3):
            if patch.level.collapsed[d]:
                continue
            lo[d] = b.lo[d] if patch.at_low[d] else max(b.lo[d] - ngc, 0)
            hi[d] = b.hi[d] if patch.at_high[d] else min(b.hi[d] + ngc, shape[d])
            elo[d] = b.lo[d] - 1 if patch.at_low[d] else lo[d]
            ehi[d] = b.hi[d] + 1 if patch.at_high[d] else hi[d]
        return lo, hi, elo, ehi

    def viscosities(self, patch, b, dims, faces, vel_tau, rho, mu, vol_frac):
        """(turb_viscosity_CC, total_viscosity_CC) of one material on one patch; faces: the
        three face-velocity arrays (uvel_FCME, ...), vel_tau: velTau_CC (Germano's filter)."""
        shape = rho.shape
        at_low = np.array(patch.at_low, dtype=np.bool_)
        at_high = np.array(patch.at_high, dtype=np.bool_)
        sh = np.array(b.sh, dtype=np.int64)
        dx = np.asarray(patch.level.dx, dtype=np.float64)
        dims = np.asarray(dims, dtype=np.bool_)
        lo1, hi1, _, _ = self.ranges(patch, b, shape, 1)
        S = np.zeros(shape + (6,))
        mu_t = np.zeros(shape)
        if self.dynamic:
            lo2, hi2, elo2, ehi2 = self.ranges(patch, b, shape, 2)
            strain_rate(*faces, S, lo2, hi2, sh, dims, dx)
            zero_neumann(S, b.lo, b.hi, elo2, ehi2, at_low, at_high)
            dynamic_viscosity(S, vel_tau, rho, mu_t, np.zeros(shape + (6,)), np.zeros(shape + (6,)),
                              np.zeros(shape + (6,)), b.lo, b.hi, lo1, hi1, lo2, hi2, elo2, ehi2,
                              at_low, at_high, dims, self.fw, self.model_constant)
        else:
            strain_rate(*faces, S, lo1, hi1, sh, dims, dx)
            term = (self.model_constant * self.fw) * (self.model_constant * self.fw)
            smagorinsky_viscosity(S, rho, mu_t, lo1, hi1, term)
        tot = np.empty(shape)
        total_viscosity(mu, mu_t, vol_frac, tot, b.lo, b.hi, lo1, hi1, at_low, at_high)
        turb = np.zeros(shape)
        turb[b.lo[0]:b.hi[0], b.lo[1]:b.hi[1], b.lo[2]:b.hi[2]] = mu_t[b.lo[0]:b.hi[0], b.lo[1]:b.hi[1],
                                                                       b.lo[2]:b.hi[2]]
        return turb, tot


def read_turbulence(ice, component):
    """The first <turbulence> block of <CFD><ICE> (Uintah's TurbulenceFactory reads only the
    first; the others are ignored, as there), or None."""
    blocks = ice.children("turbulence")
    if not blocks:
        return None
    for extra in blocks[1:]:
        extra.mark_used()
    return Turbulence(blocks[0], component)
