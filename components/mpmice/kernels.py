"""Numba kernels of the MPMICE coupling (paper 000 sec. 3.3, steps 1, 7, 8, 10 and 13; step 2
is equilibration.py): the solid's state at cell centres, its pressure force, its Lagrangian
values, the exchange's change of its velocity and temperature carried back to the nodes,
the fluid slivers in solid cells.

Index conventions as in the ICE and MPM kernels: arrays are a patch's stored arrays,
`cc_low` / `node_low` the global index of their entry [0, 0, 0]. A cell (i, j, k)
has the nodes (i..i+1, j..j+1, k..k+1) in the directions that exist (`dims`); a
collapsed direction has one node layer (index 0) and one cell layer. A solid's EOS in the
cell-centred state is ICE's code for it (mpmice/setup.py: Murnaghan n = 1, or SOLID_JWL).
"""
from __future__ import annotations

import functools

import numpy as np
from numba import njit

from components.ice.equilibration import _rho_micro
from components.mpm.shape import _over_nodes, _stencil
from components.mpm.thermal import _inv


@njit(cache=True)
def _node_weight(n, d, dims, sym_lo, sym_hi, n_lo, n_hi):
    """Weight of node index n (global) along d in a cell average: 1/2, doubled on a
    symmetry plane (the mirrored solid would give that node as much again, step 1)."""
    if not dims[d]:
        return 1.0
    w = 0.5
    if (sym_lo[d] and n == n_lo[d]) or (sym_hi[d] and n == n_hi[d]):
        w = 1.0
    return w


@njit(cache=True)
def velocity_rates(mom_me, mom_mpm, mass_L, dt, lo, hi, out):
    """Step 10 -> 13 (computeCCVelAndTempRates): dV/dt = ((mu)^L_ME - sum_w m v*) / (m^L dt),
    the solid's velocity change from the pressure source (eq. 33) and the exchange (eq. 38)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                inv = 1.0 / (mass_L[i, j, k] * dt)
                for c in range(3):
                    out[i, j, k, c] = (mom_me[i, j, k, c] - mom_mpm[i, j, k, c]) * inv


@njit(cache=True)
def velocity_rates_extra(mom_me, mass_L, vstar, dt, lo, hi, olo, ohi, out):
    """Step 10 -> 13 in the extra cells (computeCCVelAndTempRates over the extra cells):
    dV/dt = (u_ME - v*) / dt, u_ME the exchanged velocity the face's condition put there and
    v* the cell mean of the solid's nodal v* (the extra cell's own nodes, not the interior's)."""
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                if lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2]:
                    continue
                m = mass_L[i, j, k]
                if m <= 0.0:
                    continue
                for c in range(3):
                    out[i, j, k, c] = (mom_me[i, j, k, c] / m - vstar[i, j, k, c]) / dt


@njit(cache=True)
def cc_to_nc_increment(dvdt, cc_low, node_low, nlo, nhi, dims, dt, gvs, gacc):
    """Step 13 (interpolateCCToNC): every node [nlo, nhi) takes the mean dV/dt of the
    cells around it: v*_i += dt a_i, a_i += a_i(CC)."""
    sh = dvdt.shape
    for x in range(nlo[0], nhi[0]):
        for y in range(nlo[1], nhi[1]):
            for z in range(nlo[2], nhi[2]):
                gx, gy, gz = x + node_low[0], y + node_low[1], z + node_low[2]
                a0 = 0.0
                a1 = 0.0
                a2 = 0.0
                n = 0
                for a in range(2 if dims[0] else 1):
                    for b in range(2 if dims[1] else 1):
                        for c in range(2 if dims[2] else 1):
                            i = gx - a - cc_low[0] if dims[0] else 0
                            j = gy - b - cc_low[1] if dims[1] else 0
                            k = gz - c - cc_low[2] if dims[2] else 0
                            i = min(max(i, 0), sh[0] - 1)
                            j = min(max(j, 0), sh[1] - 1)
                            k = min(max(k, 0), sh[2] - 1)
                            a0 += dvdt[i, j, k, 0]
                            a1 += dvdt[i, j, k, 1]
                            a2 += dvdt[i, j, k, 2]
                            n += 1
                a0 /= n
                a1 /= n
                a2 /= n
                gvs[x, y, z, 0] += dt * a0
                gvs[x, y, z, 1] += dt * a1
                gvs[x, y, z, 2] += dt * a2
                gacc[x, y, z, 0] += a0
                gacc[x, y, z, 1] += a1
                gacc[x, y, z, 2] += a2


@njit(cache=True)
def _node_pressure(press, gx, gy, gz, cc_low, dims):
    """Mean of press_CC over the cells around global node (gx, gy, gz) (interpolatePressCCToPressNC)."""
    sh = press.shape
    s = 0.0
    n = 0
    for a in range(2 if dims[0] else 1):
        for b in range(2 if dims[1] else 1):
            for c in range(2 if dims[2] else 1):
                i = min(max(gx - a - cc_low[0], 0), sh[0] - 1) if dims[0] else 0
                j = min(max(gy - b - cc_low[1], 0), sh[1] - 1) if dims[1] else 0
                k = min(max(gz - c - cc_low[2], 0), sh[2] - 1) if dims[2] else 0
                s += press[i, j, k]
                n += 1
    return s / n


@njit(cache=True)
def _pressure_force(kind, dim, px, pvol, lp, anchor, dx, node_low, press, cc_low, dims, p_ref, gfint,
                    own, ppress):
    """Step 7 (mean pressure): p_p = sum S p_i - p_ref and fint_i -= V_p p_p grad S_ip, i.e. the
    solid's stress in the internal force is sigma + (p - p_ref) I (the bulk part the
    equilibration pressure carries, eq. 33's sigma_r - sigma). Owned p_p go to `ppress`.
    The node pressures are computed once per node of the patch (a particle's nodes outside
    it, ghost particles', on the fly): the same values as per particle."""
    if px.shape[0] == 0:
        return
    sh0, sh1, sh2 = gfint.shape[:3]
    pn = np.empty((sh0, sh1, sh2))      # interpolatePressCCToPressNC over the patch's nodes
    for x in range(sh0):
        for y in range(sh1):
            for z in range(sh2):
                pn[x, y, z] = _node_pressure(press, x + node_low[0], y + node_low[1], z + node_low[2], cc_low, dims)
    act = (1 << dim) - 1                 # the leading `dim` axes are active
    ih = _inv(dx, act)
    fi = gfint.reshape(-1)
    sh = gfint.shape[:3]
    o = 0
    all_own = own.shape[0] == 0
    for p in range(px.shape[0]):
        st = _stencil(kind, act, px, lp, p, anchor, ih, node_low)
        ijk = (st[0], st[1], st[2])
        pr = _over_nodes(_node_pressure_share, kind, act, ijk, sh, st[3:], False, 0.0,
                         (pn, press, node_low, cc_low, dims, sh)) - p_ref
        if all_own or own[p]:
            ppress[o] = pr
            o += 1
        _over_nodes(_pressure_force_share, kind, act, ijk, sh, st[3:], True, 0.0, (fi, pvol[p] * pr))


@njit(cache=True, inline="always")
def _node_pressure_share(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """p_p += S p_i at one node: from the patch's node pressures pn, beyond them on the fly."""
    pn, press, node_low, cc_low, dims, sh = args
    S = wa * wb * wc
    if S != 0.0:
        if 0 <= x < sh[0] and 0 <= y < sh[1] and 0 <= z < sh[2]:
            acc += S * pn[x, y, z]
        else:
            acc += S * _node_pressure(press, x + node_low[0], y + node_low[1], z + node_low[2], cc_low, dims)
    return acc


@njit(cache=True, inline="always")
def _pressure_force_share(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """fint_i -= V_p p_p grad S at one node (the active axes' components)."""
    fi, s = args
    f3 = 3 * n
    fi[f3] -= s * ga * wb * wc
    if act & 2:
        fi[f3 + 1] -= s * wa * gb * wc
    if act & 4:
        fi[f3 + 2] -= s * wa * wb * gc
    return acc


INTERPOLATORS = {"linear": 0, "gimp": 1}     # _pressure_force's kind


@functools.lru_cache(maxsize=None)
def _pressure_force_entry(kind, dim):
    """The pressure-force kernel for one interpolator and dimension (compile-time constants),
    compiled only where a run uses it (one entry branching on dim compiled all three: a third
    of a 1D MPMICE deck's first-run compile)."""

    @njit(cache=True)
    def pressure_force_entry(px, particle_volume, lp, anchor, dx, node_low, press_CC, cc_low, dims, p_ref,
                             grid_internal_force, owned, particle_pressure):
        _pressure_force(kind, dim, px, particle_volume, lp, anchor, dx, node_low, press_CC, cc_low, dims, p_ref,
                        grid_internal_force, owned, particle_pressure)
    return pressure_force_entry


@functools.lru_cache(maxsize=None)
def pressure_force(interpolator):
    """The pressure-force entry point for one interpolator:
    f(dim, px, particle_volume, lp, anchor, dx, node_low, press_CC, cc_low, dims, p_ref,
      grid_internal_force, owned, particle_pressure); dim 1, 2 or (any other) 3."""
    kind = INTERPOLATORS[interpolator]

    def pressure_force_entry(dim, *args):
        _pressure_force_entry(kind, dim if dim in (1, 2) else 3)(*args)
    return pressure_force_entry


@njit(cache=True)
def nc_to_cc_scalar(gmass, gq, node_low, cc_low, lo, hi, dims, sym_lo, sym_hi, n_lo, n_hi, tiny_mass,
                    empty, old, out):
    """A nodal scalar's cell mean with the weights of nc_to_cc: out = sum_w m_i q_i / sum_w m_i
    (`empty` where the cell holds no solid). With `old` (size > 1) Uintah's interpolateNCToCC_0
    Temp_CC instead: with the floor mass t in cMass = m + t and f = m / cMass (its one_or_zero),
    (1 - f) old + f (sum_w m_i q_i) / cMass, the cell's last value (old) blended with the floored
    mean, so a cell holding only a GIMP tail or the floor keeps what its last exchange left."""
    blend = old.size > 1
    w = node_weights(max(gmass.shape), node_low, dims, sym_lo, sym_hi, n_lo, n_hi)
    na = 2 if dims[0] else 1
    nb = 2 if dims[1] else 1
    nc = 2 if dims[2] else 1
    ox = cc_low[0] - node_low[0]
    oy = cc_low[1] - node_low[1]
    oz = cc_low[2] - node_low[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                m = 0.0
                s = 0.0
                for a in range(na):
                    x = i + a + ox if na == 2 else 0
                    wa = w[0, x] if na == 2 else 1.0
                    for b in range(nb):
                        y = j + b + oy if nb == 2 else 0
                        wb = w[1, y] if nb == 2 else 1.0
                        for c in range(nc):
                            z = k + c + oz if nc == 2 else 0
                            mw = wa * wb * (w[2, z] if nc == 2 else 1.0) * gmass[x, y, z]
                            m += mw
                            s += mw * gq[x, y, z]
                if blend:
                    cm = m + tiny_mass
                    one_or_zero = (cm - tiny_mass) / cm
                    out[i, j, k] = (1.0 - one_or_zero) * old[i, j, k] + one_or_zero * (s / cm)
                else:
                    out[i, j, k] = s / m if m > 0.0 else empty


@njit(cache=True)
def temperature_rates(eng_me, eng_L, mass_L, cv, dt, lo, hi, out):
    """Step 10 -> 13 (computeCCVelAndTempRates): dT/dt = ((me)^L_ME - (me)^L) / (m^L cv dt),
    the solid's temperature change from the heat exchange (eq. 39)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                out[i, j, k] = (eng_me[i, j, k] - eng_L[i, j, k]) / (mass_L[i, j, k] * cv * dt)


@njit(cache=True)
def temperature_rates_extra(temp_me, eng_L, mass_L, cv, dt, lo, hi, olo, ohi, out):
    """Step 10 -> 13 in the extra cells (computeCCVelAndTempRates over the extra cells):
    dT/dt = (T_ME - T^L) / dt, T_ME the exchanged temperature the face's condition put there
    and T^L = (me)^L / (m^L cv) the extra cell's own Lagrangian temperature (of its own nodes)."""
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                if lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2]:
                    continue
                m = mass_L[i, j, k]
                if m <= 0.0:
                    continue
                out[i, j, k] = (temp_me[i, j, k] - eng_L[i, j, k] / (m * cv)) / dt


@njit(cache=True)
def cc_to_nc_scalar(q, cc_low, node_low, nlo, nhi, dims, out):
    """Step 13 for a scalar rate (interpolateCCToNC's dTdt_NC): every node [nlo, nhi) takes
    the mean of the cells around it. With the cell mass sum_w m_i of step 1 this hands
    each node sum_c w m_i dT_c: the nodes receive exactly the heat the cells exchanged."""
    sh = q.shape
    for x in range(nlo[0], nhi[0]):
        for y in range(nlo[1], nhi[1]):
            for z in range(nlo[2], nhi[2]):
                gx, gy, gz = x + node_low[0], y + node_low[1], z + node_low[2]
                s = 0.0
                n = 0
                for a in range(2 if dims[0] else 1):
                    for b in range(2 if dims[1] else 1):
                        for c in range(2 if dims[2] else 1):
                            i = min(max(gx - a - cc_low[0], 0), sh[0] - 1) if dims[0] else 0
                            j = min(max(gy - b - cc_low[1], 0), sh[1] - 1) if dims[1] else 0
                            k = min(max(gz - c - cc_low[2], 0), sh[2] - 1) if dims[2] else 0
                            s += q[i, j, k]
                            n += 1
                out[x, y, z] = s / n


@njit(cache=True)
def trace_temperatures(masses, engs, vfs, cvs, role, theta_trace, fed, lo, hi):
    """After the exchange (eq. 39), in the cells the solids fill (every fluid's volume
    fraction below theta_trace): the fluids (role 1) take the m cv-weighted temperature of
    the solids whose temperature evolves (role 2), which give or take that heat in
    proportion to their m cv (energy conserved exactly); role 0: left out. Not in the cells
    where a reaction model feeds a fluid this step (fed nonzero; an empty fed: none): there
    the new product keeps its own temperature, as in Uintah.

    Such a gas sliver has no temperature of its own: its Lagrangian energy follows the p dV
    work of the solid's pressure swings, linearised over steps whose relative pressure
    change is large, and the exchange with a solid of large m cv cannot hold it when the
    swing is large (thousands of K)."""
    n = len(masses)
    any_fed = fed.shape[0] > 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                if any_fed and fed[i, j, k]:
                    continue
                mc_solid = 0.0
                e_solid = 0.0
                filled = True
                for m in range(n):
                    if role[m] == 1:
                        if vfs[m][i, j, k] >= theta_trace:
                            filled = False
                    elif role[m] == 2:
                        mc_solid += masses[m][i, j, k] * cvs[m]
                        e_solid += engs[m][i, j, k]
                if not filled or mc_solid <= 0.0:
                    continue
                t_mix = e_solid / mc_solid
                de = 0.0
                for m in range(n):
                    if role[m] == 1:
                        e_new = masses[m][i, j, k] * cvs[m] * t_mix
                        de += e_new - engs[m][i, j, k]
                        engs[m][i, j, k] = e_new
                for m in range(n):
                    if role[m] == 2:
                        engs[m][i, j, k] -= de * (masses[m][i, j, k] * cvs[m] / mc_solid)


@njit(cache=True)
def node_weights(nlen, node_low, dims, sym_lo, sym_hi, n_lo, n_hi):
    """_node_weight of every stored node index along each direction (rows of length nlen)."""
    w = np.ones((3, nlen))
    for d in range(3):
        for x in range(nlen):
            w[d, x] = _node_weight(x + node_low[d], d, dims, sym_lo, sym_hi, n_lo, n_hi)
    return w


@njit(cache=True)
def nc_to_cc(gmass, gvol, gvel, node_low, cc_low, lo, hi, dims, sym_lo, sym_hi, n_lo, n_hi,
             tiny_mass, rho0, vol, cmass, spv, vel, rho):
    """Step 1 (interpolateNCToCC_0): solid mass, specific volume, velocity, density per cell.

    cmass = tiny_mass + sum_w m_i (Uintah's floor in every cell), v = (sum_w V_i + tiny/rho0) / cmass,
    u = sum_w m_i u_i / cmass, rho = cmass / V, with w the node weights of _node_weight
    (looked up from node_weights: no per-node branches in the cell loop).
    `rho` may be a dummy (size 1) when not wanted, as may `spv`.
    """
    w = node_weights(max(gmass.shape), node_low, dims, sym_lo, sym_hi, n_lo, n_hi)
    want_rho = rho.size > 1
    want_spv = spv.size > 1
    na = 2 if dims[0] else 1
    nb = 2 if dims[1] else 1
    nc = 2 if dims[2] else 1
    ox = cc_low[0] - node_low[0]
    oy = cc_low[1] - node_low[1]
    oz = cc_low[2] - node_low[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                m = 0.0
                v = 0.0
                p0 = 0.0
                p1 = 0.0
                p2 = 0.0
                for a in range(na):
                    x = i + a + ox if na == 2 else 0
                    wa = w[0, x] if na == 2 else 1.0
                    for b in range(nb):
                        y = j + b + oy if nb == 2 else 0
                        wb = w[1, y] if nb == 2 else 1.0
                        for c in range(nc):
                            z = k + c + oz if nc == 2 else 0
                            wc = w[2, z] if nc == 2 else 1.0
                            ww = wa * wb * wc
                            mw = ww * gmass[x, y, z]
                            m += mw
                            v += ww * gvol[x, y, z]
                            p0 += mw * gvel[x, y, z, 0]
                            p1 += mw * gvel[x, y, z, 1]
                            p2 += mw * gvel[x, y, z, 2]
                v += tiny_mass / rho0
                m += tiny_mass
                cmass[i, j, k] = m
                vel[i, j, k, 0] = p0 / m
                vel[i, j, k, 1] = p1 / m
                vel[i, j, k, 2] = p2 / m
                if want_spv:
                    spv[i, j, k] = v / m
                if want_rho:
                    rho[i, j, k] = m / vol


@njit(cache=True)
def lagrangian_solid(cmass, vstar, temp, vel_sur, temp_sur, tiny_mass, vf, px, py, pz, shx, shy, shz, dims,
                     mass_L, mom_L, eng_L, mom_mpm, olo, ohi, lo, hi, vol, dx, dt, cv):
    """Steps 8-9 for a solid (computeLagrangianValuesMPM), one pass over the cells:
    m^L = cMass, (mu)^L = sum_w m_i v*_i - dt V theta grad p* (eq. 33, ICE's lagrangian
    term by term), (me)^L = cv sum_w m_i T*_i, each blended as Uintah's with the cell's
    step-1 state (vel_sur, temp_sur) in the proportion of the floor mass tiny_mass to cMass:
    a cell holding no more solid than the floor keeps that state, not the v* of nodes whose
    mass is a GIMP tail (their v* = dt f/m is unbounded). mom_mpm = (mu)^L less the pressure
    source (what the exchange's change is measured from, computeCCVelAndTempRates).
    m^L is (cMass / V) V, as ICE's lagrangian forms it from rho_CC."""
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                cm = cmass[i, j, k]
                m = cm / vol * vol
                mass_L[i, j, k] = m
                solid = cm - tiny_mass
                w = solid / cm                  # Uintah's one_or_zero
                eng_L[i, j, k] = (1.0 - w) * cm * temp_sur[i, j, k] * cv + w * solid * temp[i, j, k] * cv
                for c in range(3):
                    mu = (1.0 - w) * cm * vel_sur[i, j, k, c] + w * cm * vstar[i, j, k, c]
                    mom_L[i, j, k, c] = mu
                    mom_mpm[i, j, k, c] = mu
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                f = -dt * vol * vf[i, j, k]
                cm = cmass[i, j, k]
                w = (cm - tiny_mass) / cm
                for d in range(3):
                    if not dims[d]:
                        continue
                    if d == 0:
                        g = (px[i - shx[0] + 1, j - shx[1], k - shx[2]] - px[i - shx[0], j - shx[1], k - shx[2]]) / dx[0]
                    elif d == 1:
                        g = (py[i - shy[0], j - shy[1] + 1, k - shy[2]] - py[i - shy[0], j - shy[1], k - shy[2]]) / dx[1]
                    else:
                        g = (pz[i - shz[0], j - shz[1], k - shz[2] + 1] - pz[i - shz[0], j - shz[1], k - shz[2]]) / dx[2]
                    source = f * g
                    mom_L[i, j, k, d] += w * source
                    mom_mpm[i, j, k, d] -= (1.0 - w) * source


@njit(cache=True)
def solids_at_old_pressure(rhos, temps, sp_vols, press_old, solid, codes, params, cvs, gammas, fluids_too,
                           out, sp_start, tmv, vol, lo, hi):
    """The solids' densities the equilibration starts from (Uintah's computeEquilibrationPressure,
    its Docs/MPMICE.txt): a solid's volume in a cell is its EOS volume at the old pressure,
    rho_m / rho_micro_m(p_old), not the particles' mass mapped to the cell over their mapped
    volume, and Uintah divides every material's volume by the cell's total material volume
    TMV so that they fill the cell. pysus divides the solids' only (the fluids keep their
    mass): in a cell a stiff solid fills, mapping noise of its cell mass then no longer resets
    the pressure every step (which pumped p dV work into the trace gas: a compression by
    delP_Dilatate, then an isothermal re-expansion in the next equilibration, 1e5 K after
    0.4 ms in symAnnulus.ups); a solid's sliver in a gas cell stays a sliver. With fluids_too
    (the gas started from its geometry, as Uintah) the fluids of a cell holding a solid are
    scaled as well, so that the geometric gas and the particles' smeared solid start by filling
    the cell at the old pressure. out[m] is written for the materials scaled; with fluids_too
    tmv is the materials' total volume before the scaling (Uintah's TMV_CC, m^3), which the
    fluids' flow work takes as the cell's volume. sp_start[m] of a solid is 1 / rho_micro_m(p_old),
    the specific volume its Newton iteration starts from (Uintah's rho_micro start): from the
    particles' own, which the mapping's noise sets apart from the scaled density, a cell full
    of steel with a trace of air steps to p ~ 0 and takes some 40 iterations back."""
    n = len(rhos)
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                fluid = 0.0
                solid_vol = 0.0
                for m in range(n):
                    r = rhos[m][i, j, k]
                    if solid[m]:
                        rm = _rho_micro(codes[m], params, m, press_old[i, j, k], temps[m][i, j, k], cvs[m],
                                        gammas[m], 1.0 / sp_vols[m][i, j, k])
                        sp_start[m][i, j, k] = 1.0 / rm
                        solid_vol += r / rm
                    else:
                        fluid += r * sp_vols[m][i, j, k]
                scale = 1.0 / (fluid + solid_vol) if solid_vol > 0.0 else 1.0
                if fluids_too and solid_vol > 0.0:
                    tmv[i, j, k] = vol * (fluid + solid_vol)
                for m in range(n):
                    if solid[m] or fluids_too:
                        out[m][i, j, k] = rhos[m][i, j, k] * scale


@njit(cache=True)
def open_fraction(fluid_vf, tmv, vol, lo, hi, out):
    """The part of each cell [lo, hi) open to the fluids: their own volume over the cell's, the
    sum of their volume fractions times tmv / vol. fluid_vf: a tuple of the fluids' vol_frac_CC;
    tmv: TMV_CC, the materials' total volume before the equilibration divided each one's by it
    (vol where nothing was divided). Where a solid's smeared fraction overlaps gas that fills
    the cell by its own specific volume (a box and the air started from their geometry and
    moving together), the fractions say that the cell is partly closed and its gas denser than
    the next cell's, the gas's own volume that it is open and the gas as dense: nothing moves."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                f = 0.0
                for a in fluid_vf:
                    f += a[i, j, k]
                out[i, j, k] = f if tmv[i, j, k] == vol else f * (tmv[i, j, k] / vol)


# the open part below which the solid's cell takes no fluid from its neighbour (open_face_transfers):
# fluid moved into a cell the solid nearly fills is squeezed there and carried with the solid
OPEN_FILL_MIN = 0.01
# densities per open volume closer than this part of each other are equal (open_face_transfers): the
# equilibration converges to 1e-11 of the pressure, so a uniform state differs by round-off only
OPEN_SAME_DENSITY = 1e-9


@njit(cache=True)
def open_face_transfers(solid_vel, solid_vf, opn, mass, sh, d, flo, fhi, dt_dx, cap, e, inside_lo, inside_hi):
    """Step 12 next to a moving solid, per face [flo, fhi) along d (R cell = face + sh, L = R - e_d):
    u_s = the solids' own velocity across the face, the d component of their cell-centred
    velocities from their particles at the start of the step (vel_CC, step 1) weighted by
    their volume fractions in the two cells: how fast the particles carry the solid across,
    not the exchanged face velocity (which a gas flowing through a solid at rest gives it).
    Where the solid advances from its upwind cell (the donor, open part o_d = opn: the fluids'
    own volume over the cell's, open_fraction; fluid mass m_d) toward a more open neighbour
    (o_n > o_d) in which the fluid is less dense per open volume (m_n / o_n < m_d / o_d, by
    more than OPEN_SAME_DENSITY of it), e = min((o_n / o_d - 1) |u_s| dt/dx, the fraction of m_d
    that makes the two densities per open volume equal), signed as u_s. The solid fills the
    donor from the side away from the neighbour and displaces the fluid in its open part,
    which lies against the face, as though the face were as open as the neighbour: u_s o_n
    dt/dx of the cell's volume, where ICE's flux at the fluid's mean density carries about
    u o_d dt/dx. |e| <= cap on each face (a face's own bound, the same on the patches either
    side of it). Where instead the donor's fluid is the less dense per open volume (it rides
    with the solid and is not compressed with the fluid ahead of it), the neighbour's fluid
    moves in (by more than OPEN_SAME_DENSITY too): e = the fraction (m_n o_d - m_d o_n) /
    (m_n (o_d + o_n)) of m_n that makes the two equal, signed against u_s, |e| <= cap and |e| <= |u_s| dt/dx (what the solid swept
    past in the step: a solid that barely moves leaves little gas behind, and a fill beyond
    that pumped hot gas into the cold, heat-exchanged gas of a ringing steel wall's cells), and
    only where o_d >= OPEN_FILL_MIN. Nothing
    crosses a face of the domain's boundary (a cell index along d below inside_lo[d] or from
    inside_hi[d] on is an extra cell): the fluid would leave the domain or come from its
    boundary conditions. Returns whether any face moves fluid so: never where the solids'
    particles are at rest, nor where a solid and its fluid translate together (the fluid as
    dense per open volume on both sides)."""
    moved = False
    e0, e1, e2 = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            for k in range(flo[2], fhi[2]):
                e[i, j, k] = 0.0
                r0, r1, r2 = i + sh[0], j + sh[1], k + sh[2]
                l0, l1, l2 = r0 - e0, r1 - e1, r2 - e2
                ld = l0 if d == 0 else (l1 if d == 1 else l2)
                if ld < inside_lo[d] or ld + 1 >= inside_hi[d]:
                    continue
                w = 0.0
                uw = 0.0
                for s in range(len(solid_vel)):
                    wl, wr = solid_vf[s][l0, l1, l2], solid_vf[s][r0, r1, r2]
                    w += wl + wr
                    uw += wl * solid_vel[s][l0, l1, l2, d] + wr * solid_vel[s][r0, r1, r2, d]
                if w < 1e-9 or uw == 0.0:
                    continue
                us = uw / w
                if us > 0.0:
                    od, on, md, mn = opn[l0, l1, l2], opn[r0, r1, r2], mass[l0, l1, l2], mass[r0, r1, r2]
                else:
                    od, on, md, mn = opn[r0, r1, r2], opn[l0, l1, l2], mass[r0, r1, r2], mass[l0, l1, l2]
                if on > od and md * on > mn * od * (1.0 + OPEN_SAME_DENSITY):
                    x = min((on / od - 1.0) * abs(us) * dt_dx, (md * on - mn * od) / (md * (od + on)), cap)
                    e[i, j, k] = x if us > 0.0 else -x
                    moved = True
                elif on > od and od >= OPEN_FILL_MIN and mn * od > md * on * (1.0 + OPEN_SAME_DENSITY):
                    x = min((mn * od - md * on) / (mn * (od + on)), abs(us) * dt_dx, cap)
                    e[i, j, k] = -x if us > 0.0 else x
                    moved = True
    return moved
