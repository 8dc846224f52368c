"""Numba kernels of the multi-material Eulerian FEM (paper 003), 2D, one Gauss point per element.

Elements are the cells of the level (Q1, bilinear); nodes are its grid nodes. Loops run
over global indices [lo, hi) of cells or nodes; `c0` / `n0` are the global indices of
entry [0, 0, 0] of the stored CC / NC arrays (their halos may differ), `N` the number of
cells per direction. Arrays are (X, Y, 1[, comp]); stress is [sxx, syy, sxy].
Node a of element (I, J): 0 = (I, J), 1 = (I+1, J), 2 = (I+1, J+1), 3 = (I, J+1); at the
element centre dN_a/dx = -+ 1/(2 dx) and dN_a/dy = -+ 1/(2 dy); the hourglass vector is
Gamma = (1, -1, 1, -1).
"""
from __future__ import annotations

import numpy as np
from numba import njit

WALL_NONE, WALL_SLIP, WALL_NOSLIP, INFLOW = 0, 1, 2, 3     # per domain face; WALL_NONE: outflow
TINY_MASS = 1e-300


@njit(cache=True)
def strain_rate(vel, n0, c0, lo, hi, dx, D):
    """Eq. (18): D = B v at each element's centre, [exx, eyy, gamma_xy]; then the hourglass
    rates Gamma . v / 4 of v_x and v_y (the motion one Gauss point does not see)."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            a, b = I - n0[0], J - n0[1]
            vx0, vy0 = vel[a, b, 0, 0], vel[a, b, 0, 1]
            vx1, vy1 = vel[a + 1, b, 0, 0], vel[a + 1, b, 0, 1]
            vx2, vy2 = vel[a + 1, b + 1, 0, 0], vel[a + 1, b + 1, 0, 1]
            vx3, vy3 = vel[a, b + 1, 0, 0], vel[a, b + 1, 0, 1]
            i, j = I - c0[0], J - c0[1]
            D[i, j, 0, 0] = (vx1 + vx2 - vx0 - vx3) / (2.0 * dx[0])
            D[i, j, 0, 1] = (vy2 + vy3 - vy0 - vy1) / (2.0 * dx[1])
            D[i, j, 0, 2] = (vx2 + vx3 - vx0 - vx1) / (2.0 * dx[1]) + (vy1 + vy2 - vy0 - vy3) / (2.0 * dx[0])
            D[i, j, 0, 3] = 0.25 * (vx0 - vx1 + vx2 - vx3)
            D[i, j, 0, 4] = 0.25 * (vy0 - vy1 + vy2 - vy3)


@njit(cache=True)
def solid_stress(D, sig_old, vf, fluid, sig_new, mean, excess, lam, mu, dt, slide, phi_min, c0, lo, hi, N):
    """Eqs. (21)-(23): sigma_m += dt C_m : D (Hooke, plane strain), mean += phi_m sigma_m, and
    excess += phi_m e_v, the solid's volume strain tr(sigma_m) / (2 (lambda + mu)).

    With `slide` (the paper's slide condition, eq. 24), an element where the fluid holds more
    than the solid drops the solid's shear traction on the interface, whose normal n is the
    gradient of phi_m: sigma -= tau (n t + t n), tau = t . sigma . n; its normal stresses
    stay. Where the solid holds more, the element's centre lies inside the body and the shear
    there is the body's own: a wall two or three elements thick, all of it mixed by the
    remap, would otherwise lose the shear that carries its bending.
    Traces below phi_min (left by the remap) carry no stress."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            i, j = I - c0[0], J - c0[1]
            exx, eyy, gxy = D[i, j, 0, 0], D[i, j, 0, 1], D[i, j, 0, 2]
            phi = vf[i, j, 0]
            if phi < phi_min:
                sig_new[i, j, 0, 0] = sig_new[i, j, 0, 1] = sig_new[i, j, 0, 2] = 0.0
                continue
            sxx = sig_old[i, j, 0, 0] + dt * ((lam + 2.0 * mu) * exx + lam * eyy)
            syy = sig_old[i, j, 0, 1] + dt * (lam * exx + (lam + 2.0 * mu) * eyy)
            sxy = sig_old[i, j, 0, 2] + dt * mu * gxy
            excess[i, j, 0] += phi * (sxx + syy) / (2.0 * (lam + mu))
            if slide and fluid[i, j, 0] > phi:
                gx = (vf[i + 1, j, 0] if I + 1 < N[0] else phi) - (vf[i - 1, j, 0] if I > 0 else phi)
                gy = (vf[i, j + 1, 0] if J + 1 < N[1] else phi) - (vf[i, j - 1, 0] if J > 0 else phi)
                g = np.sqrt(gx * gx + gy * gy)
                if g > 0.0:
                    nx, ny = gx / g, gy / g
                    tx, ty = ny, -nx
                    tau = tx * (sxx * nx + sxy * ny) + ty * (sxy * nx + syy * ny)
                    sxx -= 2.0 * tau * tx * nx
                    syy -= 2.0 * tau * ty * ny
                    sxy -= tau * (tx * ny + nx * ty)
            sig_new[i, j, 0, 0], sig_new[i, j, 0, 1], sig_new[i, j, 0, 2] = sxx, syy, sxy
            mean[i, j, 0, 0] += phi * sxx
            mean[i, j, 0, 1] += phi * syy
            mean[i, j, 0, 2] += phi * sxy


@njit(cache=True)
def solid_hourglass(D, hg_old, vf, hg_new, hg_force, kx, ky, dt, phi_min, c0, lo, hi):
    """Hourglass stiffness of a solid: generalised forces Q += dt k (Gamma . v / 4), with k the
    bending stiffness of the bilinear element's hourglass mode (normal strain only, no
    parasitic shear: exact for a rectangle in pure bending); weighted by phi_m into the
    element's hourglass force, which acts on node a as -Q Gamma_a / 4."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            i, j = I - c0[0], J - c0[1]
            phi = vf[i, j, 0]
            if phi < phi_min:
                hg_new[i, j, 0, 0] = hg_new[i, j, 0, 1] = 0.0
                continue
            qx = hg_old[i, j, 0, 0] + dt * kx * D[i, j, 0, 3]
            qy = hg_old[i, j, 0, 1] + dt * ky * D[i, j, 0, 4]
            hg_new[i, j, 0, 0], hg_new[i, j, 0, 1] = qx, qy
            hg_force[i, j, 0, 0] += phi * qx
            hg_force[i, j, 0, 1] += phi * qy


@njit(cache=True)
def fluid_stress(D, vf, mean, mu, c0, lo, hi):
    """Eqs. (18), (19), (23): Newtonian shear stress mu [exx - eyy, eyy - exx, gxy], weighted by phi_m."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            i, j = I - c0[0], J - c0[1]
            w = vf[i, j, 0] * mu
            exx, eyy = D[i, j, 0, 0], D[i, j, 0, 1]
            mean[i, j, 0, 0] += w * (exx - eyy)
            mean[i, j, 0, 1] += w * (eyy - exx)
            mean[i, j, 0, 2] += w * D[i, j, 0, 2]


@njit(cache=True)
def _apply_walls(vel, a, b, I, J, N, walls, wall_vel, normal_only):
    """Boundary conditions on one node: slip faces zero the normal component, no-slip both
    (normal_only: the normal one alone), inflow faces set the face's velocity wall_vel;
    outflow faces (WALL_NONE) leave it free."""
    for d in range(2):
        e = I if d == 0 else J
        for s in range(2):
            if (s == 0 and e != 0) or (s == 1 and e != N[d]):
                continue
            f = 2 * d + s
            w = walls[f]
            if w == WALL_NONE:
                continue
            if w == INFLOW:
                vel[a, b, 0, 0] = wall_vel[f, 0]
                vel[a, b, 0, 1] = wall_vel[f, 1]
                continue
            vel[a, b, 0, d] = 0.0
            if w == WALL_NOSLIP and not normal_only:
                vel[a, b, 0, 1 - d] = 0.0


@njit(cache=True)
def velocity_star(vel, sigma, hg_force, rho, fill, vstar, mass, n0, c0, lo, hi, N, dx, vol, dt, grav, hourglass,
                  damping, walls, wall_vel, fill_min):
    """Eqs. (6), (14): lumped nodal mass, internal force -V B^T sigma and the solids' hourglass
    forces, gravity, v* = v + dt f / m.

    `hourglass` removes that fraction of each element's hourglass velocity per step
    (one Gauss point leaves the mode without stiffness); `damping` is a mass-proportional
    damping rate (1/s), zero unless a deck asks for it. A node whose elements are all void
    for the pressure equation (fill < fill_min: traces the remap leaves behind) has no mass
    and stays at rest. Walls take the normal component only; no-slip follows the projection.
    """
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            a, b = I - n0[0], J - n0[1]
            m = 0.0
            fx = 0.0
            fy = 0.0
            active = False
            for ci in range(I - 1, I + 1):
                if ci < 0 or ci >= N[0]:
                    continue
                for cj in range(J - 1, J + 1):
                    if cj < 0 or cj >= N[1]:
                        continue
                    i, j = ci - c0[0], cj - c0[1]
                    active = active or fill[i, j, 0] >= fill_min
                    mc = rho[i, j, 0] * vol
                    if mc <= 0.0:
                        continue
                    m += 0.25 * mc
                    sx = 1.0 if I == ci + 1 else -1.0          # sign of dN/dx of this node
                    sy = 1.0 if J == cj + 1 else -1.0
                    nx, ny = sx / (2.0 * dx[0]), sy / (2.0 * dx[1])
                    fx -= vol * (sigma[i, j, 0, 0] * nx + sigma[i, j, 0, 2] * ny)
                    fy -= vol * (sigma[i, j, 0, 2] * nx + sigma[i, j, 0, 1] * ny)
                    fx -= 0.25 * sx * sy * hg_force[i, j, 0, 0]
                    fy -= 0.25 * sx * sy * hg_force[i, j, 0, 1]
                    if hourglass > 0.0:
                        aa, bb = ci - n0[0], cj - n0[1]
                        hx = 0.25 * (vel[aa, bb, 0, 0] - vel[aa + 1, bb, 0, 0] + vel[aa + 1, bb + 1, 0, 0]
                                     - vel[aa, bb + 1, 0, 0])
                        hy = 0.25 * (vel[aa, bb, 0, 1] - vel[aa + 1, bb, 0, 1] + vel[aa + 1, bb + 1, 0, 1]
                                     - vel[aa, bb + 1, 0, 1])
                        gam = sx * sy
                        fx -= hourglass * 0.25 * mc * hx * gam / dt
                        fy -= hourglass * 0.25 * mc * hy * gam / dt
            if not active:
                m = 0.0
            mass[a, b, 0] = m
            if m > TINY_MASS:
                vstar[a, b, 0, 0] = vel[a, b, 0, 0] + dt * (fx / m + grav[0] - damping * vel[a, b, 0, 0])
                vstar[a, b, 0, 1] = vel[a, b, 0, 1] + dt * (fy / m + grav[1] - damping * vel[a, b, 0, 1])
            else:
                vstar[a, b, 0, 0] = 0.0
                vstar[a, b, 0, 1] = 0.0
            vstar[a, b, 0, 2] = 0.0
            _apply_walls(vstar, a, b, I, J, N, walls, wall_vel, True)


@njit(cache=True)
def _divergence_volume(v, a, b, dx, vol):
    """V div v of the element whose node 0 is local node (a, b) (eq. 16's right-hand side)."""
    exx = (v[a + 1, b, 0, 0] + v[a + 1, b + 1, 0, 0] - v[a, b, 0, 0] - v[a, b + 1, 0, 0]) / (2.0 * dx[0])
    eyy = (v[a, b + 1, 0, 1] + v[a + 1, b + 1, 0, 1] - v[a, b, 0, 1] - v[a + 1, b, 0, 1]) / (2.0 * dx[1])
    return vol * (exx + eyy)


@njit(cache=True)
def _surface_distance(fill):
    """Distance theta (in cells) from an element's centre to the p = 0 point of a ghost-fluid
    Dirichlet face towards a void neighbour: theta = f / (1 + f) puts the hydrostatic
    pressure of a layer of depth f dy at the element, so the nodes on top of a partly filled
    element carry their weight at rest (f = 1: the surface on the node line, theta = 1/2)."""
    return fill / (1.0 + fill)


@njit(cache=True)
def _under_surface(fluid, fc, I, J, c0, N, side):
    """Whether the void of an underfilled element (fill fc) with no void neighbour lies under the
    free surface: the element is mostly solid (void the remap mixed into a body's edge), or a
    neighbour along `side` (the mesh direction across gravity) holds more fluid than the
    element's fill plus half its void (void the remap carried down beside a body whose faces
    cut the elements, next to the full water); a surface element under a film of fluid has
    neighbours about as full as itself.
    Without gravity (side < 0) there is no free surface: any such void is."""
    i, j = I - c0[0], J - c0[1]
    if side < 0 or fc - fluid[i, j, 0] > fluid[i, j, 0]:
        return True
    level = 0.5 * (1.0 + fc)
    for s in range(2):
        e = (I if side == 0 else J) + 2 * s - 1
        if e < 0 or e >= N[side]:
            continue
        k, l = (i + 2 * s - 1, j) if side == 0 else (i, j + 2 * s - 1)
        if fluid[k, l, 0] > level:
            return True
    return False


@njit(cache=True)
def pressure_system(vstar, rho, fill, fluid, A, rhs, n0, c0, lo, hi, N, dx, dz, dt, open_faces, fill_min, beta,
                    side):
    """Eq. (16) on the elements: -div(dt / rho grad p) V = -V div v*, a 5-point stencil.

    A[.., 0] = kap, then W, E, S, N faces: (A p)_c = kap p_c + sum_f a_f (p_c - p_nb)
    (components.ice.solver's layout). Elements with sum_m phi_m < fill_min are void: p = 0.
    A void neighbour is a Dirichlet face (p = 0) at the free surface, _surface_distance
    cells away. Domain faces are walls (no flux) unless open (p = 0 on the face). `side`: the
    mesh direction across gravity (-1 without gravity), for the fill correction's surface test.
    """
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            i, j = I - c0[0], J - c0[1]
            for q in range(7):
                A[i, j, 0, q] = 0.0
            fc = fill[i, j, 0]
            if fc < fill_min:
                A[i, j, 0, 0] = 1.0
                rhs[i, j, 0] = 0.0
                continue
            rc = rho[i, j, 0]
            kap = 0.0
            surface = False
            for d in range(2):
                area_over_h = dz * (dx[1] / dx[0] if d == 0 else dx[0] / dx[1])
                for s in range(2):
                    ni = I + (2 * s - 1 if d == 0 else 0)
                    nj = J + (2 * s - 1 if d == 1 else 0)
                    e = ni if d == 0 else nj
                    if e < 0 or e >= N[d]:
                        if open_faces[2 * d + s]:
                            kap += 2.0 * dt / rc * area_over_h
                        continue
                    k, l = ni - c0[0], nj - c0[1]
                    fn = fill[k, l, 0]
                    if fn < fill_min:
                        kap += dt / rc * area_over_h / _surface_distance(fc)
                        surface = True
                    else:
                        A[i, j, 0, 1 + 2 * d + s] = 2.0 * dt / (rc + rho[k, l, 0]) * area_over_h
            A[i, j, 0, 0] = kap
            vol = dx[0] * dx[1] * dz
            # the fill correction: div v = beta (fill - 1) / dt, an overfilled element gives its
            # excess to its neighbours; an underfilled one that holds fluid and has no void
            # neighbour draws from them where its void lies under the surface
            excess = 0.0
            if fc > 1.0:
                excess = fc - 1.0
            elif not surface and fluid[i, j, 0] > 0.0 and _under_surface(fluid, fc, I, J, c0, N, side):
                excess = fc - 1.0
            rhs[i, j, 0] = -_divergence_volume(vstar, I - n0[0], J - n0[1], dx, vol) + beta * vol * excess / dt


@njit(cache=True)
def project(vstar, press, mass, vel, n0, c0, lo, hi, N, dx, vol, dt, walls, wall_vel):
    """Eq. (17): v = v* - dt / m grad p, the nodal gradient of the element pressures
    (the force sum_e p_e V grad N_a of a one-point element); then the full wall conditions."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            a, b = I - n0[0], J - n0[1]
            fx = 0.0
            fy = 0.0
            for ci in range(I - 1, I + 1):
                if ci < 0 or ci >= N[0]:
                    continue
                for cj in range(J - 1, J + 1):
                    if cj < 0 or cj >= N[1]:
                        continue
                    p = press[ci - c0[0], cj - c0[1], 0]
                    sx = 1.0 if I == ci + 1 else -1.0
                    sy = 1.0 if J == cj + 1 else -1.0
                    fx += vol * p * sx / (2.0 * dx[0])
                    fy += vol * p * sy / (2.0 * dx[1])
            m = mass[a, b, 0]
            for c in range(3):
                vel[a, b, 0, c] = vstar[a, b, 0, c]
            if m > TINY_MASS:
                vel[a, b, 0, 0] += dt * fx / m
                vel[a, b, 0, 1] += dt * fy / m
            _apply_walls(vel, a, b, I, J, N, walls, wall_vel, False)


@njit(cache=True)
def _element_mean(vel, gmass, a, b, q):
    """Component q of the element's velocity (paper sec. 6: nodal momentum to the element): the mean
    over those of its four nodes (node 0 at local (a, b)) that carry mass. A node without mass is
    held at rest, not moving with the body: counting it would make a body's front and back
    elements slower than the body, and the remap's velocity change there (new minus this) would
    push the body's edge nodes."""
    s = 0.0
    n = 0
    for aa, bb in ((a, b), (a + 1, b), (a + 1, b + 1), (a, b + 1)):
        if gmass[aa, bb, 0] > TINY_MASS:
            s += vel[aa, bb, 0, q]
            n += 1
    return s / n if n else 0.0


@njit(cache=True)
def element_velocity(vel, gmass, n0, c0, lo, hi, u):
    """The elements' velocities: the mean of their nodes that carry mass (_element_mean)."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            for q in range(2):
                u[I - c0[0], J - c0[1], q] = _element_mean(vel, gmass, I - n0[0], J - n0[1], q)


LIMITER_VAN_LEER, LIMITER_SUPERBEE = 0, 1


@njit(cache=True)
def _limited_slope(dm, dp, limiter):
    """The limited slope of MUSCL from the one-sided differences: van Leer's harmonic mean, or
    Roe's superbee, the most compressive TVD limiter (a body that swings back and forth keeps
    sharper faces: the bar in the stream, docs/EFEM.md)."""
    if dm * dp <= 0.0:
        return 0.0
    if limiter == LIMITER_SUPERBEE:
        a, b = abs(dm), abs(dp)
        s = max(min(2.0 * a, b), min(a, 2.0 * b))
        return s if dm > 0.0 else -s
    return 2.0 * dm * dp / (dm + dp)


@njit(cache=True)
def face_velocity(d, E, T, vstar, press, rho, fill, n0, c0, N, dx, dt, fill_min, open_face):
    """Normal velocity of the face between elements E-1 and E along d (T across): the mean of
    v* at the face's two nodes, corrected by the pressure jump across it exactly as the
    5-point operator of eq. (16) assumes, so that in any element the pressure equation holds
    its divergence is the one asked for: zero but for the fill correction (the volume
    fractions stay bounded by one)."""
    if d == 0:
        a, b = E - n0[0], T - n0[1]
        u = 0.5 * (vstar[a, b, 0, 0] + vstar[a, b + 1, 0, 0])
        il, jl, ih, jh = E - 1 - c0[0], T - c0[1], E - c0[0], T - c0[1]
    else:
        a, b = T - n0[0], E - n0[1]
        u = 0.5 * (vstar[a, b, 0, 1] + vstar[a + 1, b, 0, 1])
        il, jl, ih, jh = T - c0[0], E - 1 - c0[1], T - c0[0], E - c0[1]
    if E == 0 or E == N[d]:
        # a domain face: an outflow face is a Dirichlet face p = 0 half an element out
        if not open_face:
            return u
        if E == 0:
            return u - 2.0 * dt * press[ih, jh, 0] / (rho[ih, jh, 0] * dx[d]) if fill[ih, jh, 0] >= fill_min else u
        return u + 2.0 * dt * press[il, jl, 0] / (rho[il, jl, 0] * dx[d]) if fill[il, jl, 0] >= fill_min else u
    fl, fh = fill[il, jl, 0], fill[ih, jh, 0]
    if fl < fill_min and fh < fill_min:
        return u
    if fl < fill_min:
        return u - dt * press[ih, jh, 0] / (rho[ih, jh, 0] * _surface_distance(fh) * dx[d])
    if fh < fill_min:
        return u + dt * press[il, jl, 0] / (rho[il, jl, 0] * _surface_distance(fl) * dx[d])
    return u - 2.0 * dt / (rho[il, jl, 0] + rho[ih, jh, 0]) * (press[ih, jh, 0] - press[il, jl, 0]) / dx[d]


@njit(cache=True)
def remap_sweep(d, phi, sig, solid_of, rho_m, u, vstar, press, rho, fill, fill_min, n0, c0, lo, hi, N, dx, dt,
                walls, wall_vel, inflow_matl, limiter, stress_muscl, phi_min, phi_out, sig_out, u_out):
    """One directional sweep of the Eulerian step (eq. 4) along mesh lines d over cells [lo, hi).

    phi (nm, X, Y): volume fractions, advected by MUSCL (ref. 17; `limiter`: van Leer's or
    superbee) with the face velocities of the moved mesh (face_velocity); the donor's content
    bounds each flux. sig (ns, X, Y, q): solid state (stress, hourglass forces), carried as phi_m sigma_m with the
    material's volume flux: the upwind element's state, or with `stress_muscl` its van Leer-limited
    MUSCL value at the face where the three elements about the face hold the solid at phi_min or
    more (a bending stress varies linearly across a wall a few elements thick; first-order upwind
    diffuses it away as the wall moves through the mesh, docs/EFEM.md). u (X, Y, 2): element velocities, carried as
    momentum sum_m rho_m phi_m u (upwind u). Walls carry nothing; an inflow face brings its
    material (volume fraction 1) at its velocity, an outflow face takes the element's
    content and, where the flow turns inward, brings the element's fluids back filled to
    one (first order at both).
    """
    nm = phi.shape[0]
    t = 1 - d
    h = dx[d]
    nf = hi[d] - lo[d] + 1
    F = np.zeros((nm, nf))
    Pm = np.zeros((nf, 2))
    ns, nq = sig.shape[0], sig.shape[3]
    S = np.zeros((ns, nf, nq))                 # each solid's state at the face, times its volume flux
    for T in range(lo[t], hi[t]):
        for f in range(nf):
            E = lo[d] + f                      # face between cells E-1 and E along d
            for m in range(nm):
                F[m, f] = 0.0
            for s in range(ns):
                for q in range(nq):
                    S[s, f, q] = 0.0
            Pm[f, 0] = Pm[f, 1] = 0.0
            boundary = E <= 0 or E >= N[d]
            face = 2 * d + (0 if E <= 0 else 1)
            if boundary and walls[face] != INFLOW and walls[face] != WALL_NONE:
                continue
            uf = face_velocity(d, E, T, vstar, press, rho, fill, n0, c0, N, dx, dt, fill_min,
                               boundary and walls[face] == WALL_NONE)
            c = uf * dt / h
            if c == 0.0:
                continue
            if boundary:
                inward = (E <= 0) == (c > 0.0)
                ac = abs(c)
                if inward and walls[face] == INFLOW:
                    m = inflow_matl[face]
                    flux = ac
                    F[m, f] = flux if c > 0.0 else -flux
                    for q in range(2):
                        Pm[f, q] = (rho_m[m] * flux if c > 0.0 else -rho_m[m] * flux) * wall_vel[face, q]
                elif not inward:
                    ie = E - 1 if E >= N[d] else E
                    iu, ju = (ie - c0[0], T - c0[1]) if d == 0 else (T - c0[0], ie - c0[1])
                    mom = 0.0
                    for m in range(nm):
                        flux = ac * phi[m, iu, ju]
                        F[m, f] = flux if c > 0.0 else -flux
                        mom += rho_m[m] * flux
                        if solid_of[m] >= 0:
                            for q in range(nq):
                                S[solid_of[m], f, q] = F[m, f] * sig[solid_of[m], iu, ju, q]
                    for q in range(2):
                        Pm[f, q] = (mom if c > 0.0 else -mom) * u[iu, ju, q]
                elif walls[face] == WALL_NONE:
                    # backflow through an outflow face: the outside holds the element's fluids,
                    # full (zero gradient), so the volume the pressure equation lets in arrives
                    ie = E - 1 if E >= N[d] else E
                    iu, ju = (ie - c0[0], T - c0[1]) if d == 0 else (T - c0[0], ie - c0[1])
                    wet = 0.0
                    for m in range(nm):
                        if solid_of[m] < 0:
                            wet += phi[m, iu, ju]
                    if wet < fill_min:
                        continue
                    mom = 0.0
                    for m in range(nm):
                        if solid_of[m] < 0:
                            flux = ac * phi[m, iu, ju] / wet
                            F[m, f] = flux if c > 0.0 else -flux
                            mom += rho_m[m] * flux
                    for q in range(2):
                        Pm[f, q] = (mom if c > 0.0 else -mom) * u[iu, ju, q]
                continue
            up = E - 1 if c > 0.0 else E
            dn = E if c > 0.0 else E - 1
            uu = up - 1 if c > 0.0 else up + 1
            ac = abs(c)
            if d == 0:
                iu, ju, idn, jdn, iuu, juu = up - c0[0], T - c0[1], dn - c0[0], T - c0[1], uu - c0[0], T - c0[1]
            else:
                iu, ju, idn, jdn, iuu, juu = T - c0[0], up - c0[1], T - c0[0], dn - c0[1], T - c0[0], uu - c0[1]
            has_uu = 0 <= uu < N[d]
            mom = 0.0
            for m in range(nm):
                p_up = phi[m, iu, ju]
                dp = phi[m, idn, jdn] - p_up
                dm = p_up - phi[m, iuu, juu] if has_uu else 0.0
                face = p_up + 0.5 * (1.0 - ac) * _limited_slope(dm, dp, limiter)
                flux = min(ac * face, p_up)
                F[m, f] = flux if c > 0.0 else -flux
                mom += rho_m[m] * flux
                s = solid_of[m]
                if s < 0:
                    continue
                sharp = stress_muscl and has_uu and min(p_up, phi[m, idn, jdn], phi[m, iuu, juu]) >= phi_min
                for q in range(nq):
                    sv = sig[s, iu, ju, q]
                    if sharp:
                        sv += 0.5 * (1.0 - ac) * _limited_slope(sv - sig[s, iuu, juu, q], sig[s, idn, jdn, q] - sv,
                                                                LIMITER_VAN_LEER)
                    S[s, f, q] = F[m, f] * sv
            for q in range(2):
                Pm[f, q] = (mom if c > 0.0 else -mom) * u[iu, ju, q]
        for k in range(nf - 1):
            E = lo[d] + k
            i, j = (E - c0[0], T - c0[1]) if d == 0 else (T - c0[0], E - c0[1])
            mass_old = 0.0
            mass_new = 0.0
            for m in range(nm):
                p_new = phi[m, i, j] + F[m, k] - F[m, k + 1]
                phi_out[m, i, j] = p_new
                mass_old += rho_m[m] * phi[m, i, j]
                mass_new += rho_m[m] * p_new
                s = solid_of[m]
                if s < 0:
                    continue
                # fluxes of phi_m sigma_m: the volume flux times the face's state
                for q in range(nq):
                    total = phi[m, i, j] * sig[s, i, j, q] + S[s, k, q] - S[s, k + 1, q]
                    sig_out[s, i, j, q] = total / p_new if p_new > 1e-12 else 0.0
            for q in range(2):
                mom = mass_old * u[i, j, q] + Pm[k, q] - Pm[k + 1, q]
                u_out[i, j, q] = mom / mass_new if mass_new > 1e-300 else u[i, j, q]


@njit(cache=True)
def nodal_remap(velL, gmass, dvel, mass_new, vel, n0, c0, lo, hi, N, walls, wall_vel):
    """The remapped element velocities back to the nodes (paper sec. 6, refs. 15, 16): a node
    that had mass adds the mass-weighted mean of its elements' velocity changes, a node that
    had none takes their new velocity; a node without mass in its elements is at rest."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            a, b = I - n0[0], J - n0[1]
            w = 0.0
            sx = 0.0
            sy = 0.0
            had = gmass[a, b, 0] > TINY_MASS
            for ci in range(I - 1, I + 1):
                if ci < 0 or ci >= N[0]:
                    continue
                for cj in range(J - 1, J + 1):
                    if cj < 0 or cj >= N[1]:
                        continue
                    i, j = ci - c0[0], cj - c0[1]
                    mc = mass_new[i, j, 0]
                    if mc <= 0.0:
                        continue
                    w += mc
                    sx += mc * dvel[i, j, 0, 0]
                    sy += mc * dvel[i, j, 0, 1]
                    if not had:
                        sx += mc * _element_mean(velL, gmass, ci - n0[0], cj - n0[1], 0)
                        sy += mc * _element_mean(velL, gmass, ci - n0[0], cj - n0[1], 1)
            vel[a, b, 0, 2] = 0.0
            if w <= TINY_MASS:
                vel[a, b, 0, 0] = vel[a, b, 0, 1] = 0.0
            elif had:
                vel[a, b, 0, 0] = velL[a, b, 0, 0] + sx / w
                vel[a, b, 0, 1] = velL[a, b, 0, 1] + sy / w
            else:
                vel[a, b, 0, 0] = sx / w
                vel[a, b, 0, 1] = sy / w
            _apply_walls(vel, a, b, I, J, N, walls, wall_vel, False)


@njit(cache=True)
def nodal_from_momentum(mass, mom, vel, n0, c0, lo, hi, N, walls, wall_vel):
    """Initial nodal velocity: sum of the adjacent elements' momenta over their mass."""
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            a, b = I - n0[0], J - n0[1]
            w = 0.0
            px = 0.0
            py = 0.0
            for ci in range(I - 1, I + 1):
                if ci < 0 or ci >= N[0]:
                    continue
                for cj in range(J - 1, J + 1):
                    if cj < 0 or cj >= N[1]:
                        continue
                    i, j = ci - c0[0], cj - c0[1]
                    w += mass[i, j, 0]
                    px += mom[i, j, 0, 0]
                    py += mom[i, j, 0, 1]
            vel[a, b, 0, 0] = px / w if w > TINY_MASS else 0.0
            vel[a, b, 0, 1] = py / w if w > TINY_MASS else 0.0
            vel[a, b, 0, 2] = 0.0
            _apply_walls(vel, a, b, I, J, N, walls, wall_vel, False)


@njit(cache=True)
def kinetic_energy_max_speed(vel, mass, n0, lo, hi):
    """(sum 1/2 m |v|^2, max |v|) over nodes [lo, hi)."""
    ke = 0.0
    vmax = 0.0
    for I in range(lo[0], hi[0]):
        for J in range(lo[1], hi[1]):
            a, b = I - n0[0], J - n0[1]
            v2 = vel[a, b, 0, 0] ** 2 + vel[a, b, 0, 1] ** 2
            ke += 0.5 * mass[a, b, 0] * v2
            vmax = max(vmax, np.sqrt(v2))
    return ke, vmax
