"""MPM fluid material points (paper 004 eqs. 21-25) on Sod's shock tube against the exact
Riemann solution (components/ice/exact_riemann.py): inputs/MPM/sod_fluid_points.ups.

Measured at t = 0.143 (MUSL, 200 cells, 3 points per cell, 004's artificial viscosity):
shock (mid-density crossing) at x = 0.7518, exact 0.7497; mean |rho - exact| 0.0153, |u - exact| 0.039,
|p - exact| 0.0176; behind the shock u and p within 1 % and 2.2 % of u*, p*. Known
deficit: the left gas between the rarefaction and the contact (x = 0.5 .. 0.6) is 15-20 %
under-dense (0.35 for 0.426) while its pressure is 20 % low and its internal energy 6 %
low: the points' volumes V0 det F have outgrown their spacing (which says 0.422), and
e ~ V^(1 - gamma) followed them. The motion does not care (V p = (gamma - 1) m e), so
u, p* and the shock are right. 004 eqs. 24-25's parameters do not explain it (lambda~
0.25 .. 1.5 gives 0.36 .. 0.34); the volumes from the nodal mass
(<density_from_grid>, test_sod_density_from_grid) give 0.422 and halve the density error.
"""
import numpy as np
import pytest

from components.ice.exact_riemann import exact_riemann, star_state

from .helpers import MPM_INPUTS, deck_text, run

LEFT, RIGHT = (1.0, 0.0, 1.0), (0.125, 0.0, 0.1)


@pytest.fixture(scope="module")
def sod(tmp_path_factory):
    ctl, da = run(open(MPM_INPUTS / "sod_fluid_points.ups").read(), tmp_path_factory.mktemp("sod"))
    t = da.times[-1]
    ps = [da.particles(m, -1) for m in (0, 1)]
    x = np.concatenate([p["p.x"][:, 0] for p in ps])
    rho = np.concatenate([p["p.mass"] / p["p.volume"] for p in ps])
    u = np.concatenate([p["p.velocity"][:, 0] for p in ps])
    pr = np.concatenate([-np.trace(p["p.stress"], axis1=1, axis2=2) / 3 for p in ps])
    o = np.argsort(x)
    return t, x[o], rho[o], u[o], pr[o], exact_riemann(LEFT, RIGHT, x[o], t, x0=0.5)


def test_shock_position(sod):
    t, x, rho, u, pr, ex = sod
    assert abs(t - 0.143) < 0.002
    post = ex["rho"][(x > 0.65) & (x < 0.7)].mean()                 # 0.2656
    mid = 0.5 * (post + RIGHT[0])
    x_mpm = x[np.flatnonzero(rho > mid)[-1]]
    x_exact = x[np.flatnonzero(ex["rho"] > mid)[-1]]
    assert abs(x_exact - 0.75) < 0.005                               # 0.5 + 1.752 t
    assert abs(x_mpm - x_exact) < 0.01, (x_mpm, x_exact)            # two cells


def test_profiles_against_exact(sod):
    t, x, rho, u, pr, ex = sod
    assert np.mean(np.abs(rho - ex["rho"])) < 0.02
    assert np.mean(np.abs(u - ex["u"])) < 0.05
    assert np.mean(np.abs(pr - ex["p"])) < 0.025
    p_star, u_star = star_state(LEFT, RIGHT)
    between = (x > 0.64) & (x < 0.72)                                # contact .. shock
    assert abs(u[between].mean() / u_star - 1) < 0.02
    assert abs(pr[between].mean() / p_star - 1) < 0.04
    quiet = (x < 0.3) | (x > 0.83)                                  # the shock precursor ends by 0.82
    assert np.allclose(rho[quiet], ex["rho"][quiet], rtol=2e-3)
    assert np.allclose(pr[quiet], ex["p"][quiet], rtol=2e-3)


def test_sod_density_from_grid(sod, tmp_path):
    """The same deck with <density_from_grid> in both gas models: the same motion up to
    round-off (an ideal gas's forces V p = (gamma-1) m e and V q do not depend on V), and the density
    right in the left star state (measured 0.422 for 0.426, L1 error 0.0092 for 0.0156)."""
    text = open(MPM_INPUTS / "sod_fluid_points.ups").read().replace(
        "</constitutive_model>", "<density_from_grid>true</density_from_grid></constitutive_model>")
    ctl, da = run(text, tmp_path)
    ps = [da.particles(m, -1) for m in (0, 1)]
    x = np.concatenate([p["p.x"][:, 0] for p in ps])
    o = np.argsort(x)
    x = x[o]
    rho = np.concatenate([p["p.mass"] / p["p.volume"] for p in ps])[o]
    u = np.concatenate([p["p.velocity"][:, 0] for p in ps])[o]
    ex = exact_riemann(LEFT, RIGHT, x, da.times[-1], x0=0.5)
    _, x0, rho0, u0, _, _ = sod
    assert np.abs(x - x0).max() < 1e-12 and np.abs(u - u0).max() < 1e-10   # measured 7e-16, 2e-14
    star = (x > 0.5) & (x < 0.6)                                     # exact 0.4263
    assert abs(rho[star].mean() / ex["rho"][star].mean() - 1) < 0.03
    assert abs(rho0[star].mean() / ex["rho"][star].mean() - 1) > 0.12   # V0 det F: 0.35
    assert np.mean(np.abs(rho - ex["rho"])) < 0.012


def piston_omega(m, K=100.0, L=20.0, A=1.0, rho=1e-4, beta=1.58e6):
    """First root of 004 eq. 27, omega = sqrt((K + rho omega c A cot(omega L/c))/m), by
    bisection below the first pole of the cot (omega L/c = pi)."""
    c = np.sqrt(beta / rho)
    f = lambda w: w - np.sqrt((K + rho * w * c * A / np.tan(w * L / c)) / m)
    lo, hi = 1.0, 0.999 * np.pi * c / L
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return lo


@pytest.mark.parametrize("m,table_period,t_end", [(0.1, 0.00709, 0.0057), (1.0, 0.02234, 0.018)])
def test_piston_container_period(tmp_path, m, table_period, t_end):
    """004 Table I: piston mass m on a gas column and a spring (inputs/MPM/piston_container
    .ups; the piston is one particle of density m / (dx A)). Eq. 27: 0.0070882 s and
    0.0223479 s; measured 0.0070925 s (m = 0.1, +0.06 %) and 0.022350 s (m = 1.0, +0.01 %)."""
    from .test_bar import period
    T_exact = 2 * np.pi / piston_omega(m)
    assert abs(T_exact / table_period - 1) < 0.002          # eq. 27 reproduces Table I
    text = deck_text(MPM_INPUTS / "piston_container.ups", maxTime=t_end).replace(
        "<density>0.05</density>", f"<density>{m / 2.0}</density>")
    ctl, da = run(text, tmp_path)
    T = period(da)
    assert abs(T / T_exact - 1) < 0.02, (T, T_exact)


def _row_nodal_sums(x, m, v, dx, nodes):
    """The nodal masses and volumes (linear weights) of points along a row of cells in x."""
    gm, gv = np.zeros((nodes, 1, 1)), np.zeros((nodes, 1, 1))
    for p in range(len(x)):
        i, f = int(x[p, 0] // dx), x[p, 0] / dx - int(x[p, 0] // dx)
        for node, w in ((i, 1 - f), (i + 1, f)):
            gm[node, 0, 0] += w * m[p]
            gv[node, 0, 0] += w * v[p]
    return gm, gv


def test_density_from_grid():
    """ideal_gas_fluid <density_from_grid> on a 1D row of 4 cells (dx 0.25, unit section),
    2 points per cell of mass 0.125 (density 1): volumes that drifted to 1.5 times their
    share come back to m / rho = 0.125 exactly (every node full, the domain-end nodes with
    half a support); volumes at half their share (no node counts as full) are kept."""
    from components.mpm.constitutive.ideal_gas_fluid import grid_volumes
    dx, ncells = np.array([0.25, 1.0, 1.0]), np.array([4, 1, 1])
    x = np.zeros((8, 3))
    x[:, 0] = (np.arange(8) + 0.5) * 0.125
    m = np.full(8, 0.125)
    for scale, expect in ((1.5, 0.125), (0.5, 0.0625)):
        v = np.full(8, 0.125 * scale)
        gm, gv = _row_nodal_sums(x, m, v, 0.25, 5)
        grid_volumes(x, np.zeros(3), dx, ncells, np.zeros(3, np.bool_), np.zeros(3, np.int64),
                     gm, gv, gv, m, v)
        assert np.allclose(v, expect, rtol=1e-12), (scale, v)


def test_density_from_grid_axisymmetric():
    """The same in axisymmetry (x = r, per radian): a row of 4 cells (dx 0.25, dy 1) from the
    axis, 4 points per cell in r, V_p = r_p dr dy, density 1; volumes drifted by 1.2-1.8 times
    come back to r_p dr dy: exactly in the first three cells (their nodes' sums S_ip m_p equal
    the integrals of S_i r dr dy; the axis node is skipped), in the last within the midpoint
    sum's error at the outer face's node (0.3 %)."""
    from components.mpm.constitutive.ideal_gas_fluid import grid_volumes
    dx, ncells = np.array([0.25, 1.0, 1.0]), np.array([4, 1, 1])
    x = np.zeros((16, 3))
    x[:, 0] = (np.arange(16) + 0.5) * 0.0625
    exact = x[:, 0] * 0.0625
    m = exact.copy()
    v = exact * np.random.default_rng(3).uniform(1.2, 1.8, 16)
    gm, gv = _row_nodal_sums(x, m, v, 0.25, 5)
    grid_volumes(x, np.zeros(3), dx, ncells, np.zeros(3, np.bool_), np.zeros(3, np.int64),
                 gm, gv, gv, m, v, True)
    assert np.allclose(v[:12], exact[:12], rtol=1e-12), v / exact
    assert np.allclose(v[12:], exact[12:], rtol=4e-3), v / exact
