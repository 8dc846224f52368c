"""Exact Riemann solver for the 1D Euler equations (Toro 2009, ch. 4).

Used to validate ICE shock-tube runs (e.g. inputs ICE/riemann_sm.ups).  Each
side obeys a stiffened-gas EOS  p = (gamma-1) rho e - gamma p_inf  (p_inf = 0:
ideal gas).  A stiffened gas is an ideal gas in the shifted pressure
p + p_inf, so Toro's formulas hold with p -> p + p_inf on each side, while
pressure and velocity are continuous across the contact.

Public API
----------
star_state(left, right, gamma_left, gamma_right, pinf_left=0, pinf_right=0)
    -> (p_star, u_star)
wave_structure(left, right, ...) -> dict with p*, u*, rho*L, rho*R and the
    wave speeds (head/tail of each non-linear wave, contact speed)
exact_riemann(left, right, x, t, x0, gamma_left=1.4, gamma_right=None, ...)
    -> dict of 'rho', 'u', 'p', 'e' arrays sampled at x and time t
left/right are (rho, u, p) tuples.
"""
import math

import numpy as np
from numba import njit


@njit(cache=True)
def _f_side(p, rho_k, p_k, c_k, g, pinf):
    """Toro eqs. (4.6)-(4.7) with p -> p+pinf: f_K(p) and f_K'(p)."""
    ps = p + pinf
    pks = p_k + pinf
    if ps > pks:  # shock, eq. (4.6)/(4.37)
        a_k = 2.0 / ((g + 1.0) * rho_k)
        b_k = (g - 1.0) / (g + 1.0) * pks
        q = math.sqrt(a_k / (ps + b_k))
        f = (ps - pks) * q
        df = q * (1.0 - 0.5 * (ps - pks) / (b_k + ps))
    else:  # rarefaction, eq. (4.7)/(4.37)
        r = ps / pks
        f = 2.0 * c_k / (g - 1.0) * (r ** ((g - 1.0) / (2.0 * g)) - 1.0)
        df = r ** (-(g + 1.0) / (2.0 * g)) / (rho_k * c_k)
    return f, df


@njit(cache=True)
def _star_pressure(rl, ul, pl, rr, ur, pr, gl, gr, pinfl, pinfr):
    """Solve f(p) = f_L + f_R + du = 0 (Toro eq. 4.5) by safeguarded Newton.

    Returns (p*, u*, status); status 1 = vacuum/cavitation (no p* with
    p + p_inf > 0 on both sides), 2 = no convergence.
    """
    cl = math.sqrt(gl * (pl + pinfl) / rl)
    cr = math.sqrt(gr * (pr + pinfr) / rr)
    du = ur - ul
    p_floor = max(-pinfl, -pinfr)
    # pressure positivity condition, Toro eq. (4.40) generalised: f(p_floor) < 0
    fl0, _ = _f_side(p_floor, rl, pl, cl, gl, pinfl)
    fr0, _ = _f_side(p_floor, rr, pr, cr, gr, pinfr)
    if fl0 + fr0 + du >= 0.0:
        return 0.0, 0.0, 1
    scale = max(pl + pinfl, pr + pinfr)
    # bracket [lo, hi] with f(lo) < 0 < f(hi)
    lo = p_floor
    hi = max(pl, pr)
    while True:
        fl, _ = _f_side(hi, rl, pl, cl, gl, pinfl)
        fr, _ = _f_side(hi, rr, pr, cr, gr, pinfr)
        if fl + fr + du > 0.0:
            break
        lo = hi
        hi = p_floor + 2.0 * (hi - p_floor) + scale
    # initial guess: PVRS, Toro eq. (4.47), clipped into the bracket
    p = 0.5 * (pl + pr) - 0.125 * du * (rl + rr) * (cl + cr)
    if p <= lo or p >= hi:
        p = 0.5 * (lo + hi)
    for _ in range(200):
        fl, dfl = _f_side(p, rl, pl, cl, gl, pinfl)
        fr, dfr = _f_side(p, rr, pr, cr, gr, pinfr)
        f = fl + fr + du
        if f < 0.0:
            lo = p
        else:
            hi = p
        p_new = p - f / (dfl + dfr)  # Newton step, Toro eq. (4.44)
        if not (lo < p_new < hi):
            p_new = 0.5 * (lo + hi)  # bisection fallback keeps p + pinf > 0
        if abs(p_new - p) <= 1e-14 * (abs(p_new) + scale) or hi - lo <= 1e-14 * scale:
            p = p_new
            fl, _ = _f_side(p, rl, pl, cl, gl, pinfl)
            fr, _ = _f_side(p, rr, pr, cr, gr, pinfr)
            return p, 0.5 * (ul + ur) + 0.5 * (fr - fl), 0  # eq. (4.9)
        p = p_new
    return p, 0.0, 2


@njit(cache=True)
def _sample(x, t, x0, rl, ul, pl, rr, ur, pr, gl, gr, pinfl, pinfr, ps, us,
            rho, u, p, e):
    """Sample the self-similar solution at x/t (Toro sec. 4.5, Fig. 4.14)."""
    cl = math.sqrt(gl * (pl + pinfl) / rl)
    cr = math.sqrt(gr * (pr + pinfr) / rr)
    for i in range(x.shape[0]):
        s = (x[i] - x0) / t
        if s <= us:  # left of the contact
            g, pinf = gl, pinfl
            ratio = (ps + pinf) / (pl + pinf)
            if ps > pl:  # left shock, eqs. (4.50), (4.52)
                sl = ul - cl * math.sqrt((g + 1.0) / (2.0 * g) * ratio + (g - 1.0) / (2.0 * g))
                if s <= sl:
                    rho[i], u[i], p[i] = rl, ul, pl
                else:
                    gm = (g - 1.0) / (g + 1.0)
                    rho[i], u[i], p[i] = rl * (ratio + gm) / (gm * ratio + 1.0), us, ps
            else:  # left rarefaction, eqs. (4.53)-(4.56)
                shl = ul - cl
                stl = us - cl * ratio ** ((g - 1.0) / (2.0 * g))
                if s <= shl:
                    rho[i], u[i], p[i] = rl, ul, pl
                elif s >= stl:
                    rho[i], u[i], p[i] = rl * ratio ** (1.0 / g), us, ps
                else:
                    w = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * cl) * (ul - s)
                    rho[i] = rl * w ** (2.0 / (g - 1.0))
                    u[i] = 2.0 / (g + 1.0) * (cl + 0.5 * (g - 1.0) * ul + s)
                    p[i] = (pl + pinf) * w ** (2.0 * g / (g - 1.0)) - pinf
        else:  # right of the contact
            g, pinf = gr, pinfr
            ratio = (ps + pinf) / (pr + pinf)
            if ps > pr:  # right shock, eqs. (4.57), (4.59)
                sr = ur + cr * math.sqrt((g + 1.0) / (2.0 * g) * ratio + (g - 1.0) / (2.0 * g))
                if s >= sr:
                    rho[i], u[i], p[i] = rr, ur, pr
                else:
                    gm = (g - 1.0) / (g + 1.0)
                    rho[i], u[i], p[i] = rr * (ratio + gm) / (gm * ratio + 1.0), us, ps
            else:  # right rarefaction, eqs. (4.60)-(4.63)
                shr = ur + cr
                str_ = us + cr * ratio ** ((g - 1.0) / (2.0 * g))
                if s >= shr:
                    rho[i], u[i], p[i] = rr, ur, pr
                elif s <= str_:
                    rho[i], u[i], p[i] = rr * ratio ** (1.0 / g), us, ps
                else:
                    w = 2.0 / (g + 1.0) - (g - 1.0) / ((g + 1.0) * cr) * (ur - s)
                    rho[i] = rr * w ** (2.0 / (g - 1.0))
                    u[i] = 2.0 / (g + 1.0) * (-cr + 0.5 * (g - 1.0) * ur + s)
                    p[i] = (pr + pinf) * w ** (2.0 * g / (g - 1.0)) - pinf
        e[i] = (p[i] + g * pinf) / ((g - 1.0) * rho[i])  # stiffened-gas caloric EOS


def _unpack(left, right, gamma_left, gamma_right, pinf_left, pinf_right):
    rl, ul, pl = (float(v) for v in left)
    rr, ur, pr = (float(v) for v in right)
    gl = float(gamma_left)
    gr = gl if gamma_right is None else float(gamma_right)
    args = (rl, ul, pl, rr, ur, pr, gl, gr, float(pinf_left), float(pinf_right))
    if rl <= 0.0 or rr <= 0.0:
        raise ValueError(f"exact_riemann: densities must be positive, got {rl}, {rr}")
    if pl + pinf_left <= 0.0 or pr + pinf_right <= 0.0:
        raise ValueError("exact_riemann: need p + p_inf > 0 on both sides")
    return args


def star_state(left, right, gamma_left=1.4, gamma_right=None, pinf_left=0.0, pinf_right=0.0):
    """Return (p*, u*) of the Riemann problem; ValueError if vacuum is generated."""
    args = _unpack(left, right, gamma_left, gamma_right, pinf_left, pinf_right)
    ps, us, status = _star_pressure(*args)
    if status == 1:
        rl, ul, pl, rr, ur, pr, gl, gr, pinfl, pinfr = args
        cl = math.sqrt(gl * (pl + pinfl) / rl)
        cr = math.sqrt(gr * (pr + pinfr) / rr)
        raise ValueError(
            "exact_riemann: the initial data generate vacuum (pressure positivity "
            f"condition, Toro eq. 4.40, violated): u_R - u_L = {ur - ul:.6g} >= "
            f"2 c_L/(g_L-1) + 2 c_R/(g_R-1) = {2 * cl / (gl - 1) + 2 * cr / (gr - 1):.6g} "
            "(for p_inf != 0 evaluated at p = max(-p_inf_L, -p_inf_R))")
    if status == 2:
        raise RuntimeError("exact_riemann: Newton iteration for p* did not converge")
    return ps, us


def wave_structure(left, right, gamma_left=1.4, gamma_right=None, pinf_left=0.0, pinf_right=0.0):
    """Star state, star densities and wave speeds (head, tail) of both waves.

    For a shock head == tail == shock speed.  Keys: p_star, u_star, rho_star_L,
    rho_star_R, left_wave ('shock'|'rarefaction'), right_wave, speeds =
    (left head, left tail, contact, right tail, right head), ordered in x.
    """
    args = _unpack(left, right, gamma_left, gamma_right, pinf_left, pinf_right)
    rl, ul, pl, rr, ur, pr, gl, gr, pinfl, pinfr = args
    ps, us = star_state(left, right, gamma_left, gamma_right, pinf_left, pinf_right)
    cl = math.sqrt(gl * (pl + pinfl) / rl)
    cr = math.sqrt(gr * (pr + pinfr) / rr)
    out = {"p_star": ps, "u_star": us}
    ratio = (ps + pinfl) / (pl + pinfl)
    if ps > pl:
        gm = (gl - 1.0) / (gl + 1.0)
        out["rho_star_L"] = rl * (ratio + gm) / (gm * ratio + 1.0)  # eq. (4.50)
        sl = ul - cl * math.sqrt((gl + 1) / (2 * gl) * ratio + (gl - 1) / (2 * gl))  # (4.52)
        out["left_wave"], lh, lt = "shock", sl, sl
    else:
        out["rho_star_L"] = rl * ratio ** (1.0 / gl)  # eq. (4.53)
        out["left_wave"] = "rarefaction"
        lh, lt = ul - cl, us - cl * ratio ** ((gl - 1) / (2 * gl))  # (4.55)
    ratio = (ps + pinfr) / (pr + pinfr)
    if ps > pr:
        gm = (gr - 1.0) / (gr + 1.0)
        out["rho_star_R"] = rr * (ratio + gm) / (gm * ratio + 1.0)  # eq. (4.57)
        sr = ur + cr * math.sqrt((gr + 1) / (2 * gr) * ratio + (gr - 1) / (2 * gr))  # (4.59)
        out["right_wave"], rt, rh = "shock", sr, sr
    else:
        out["rho_star_R"] = rr * ratio ** (1.0 / gr)  # eq. (4.60)
        out["right_wave"] = "rarefaction"
        rh, rt = ur + cr, us + cr * ratio ** ((gr - 1) / (2 * gr))  # (4.62)
    out["speeds"] = (lh, lt, us, rt, rh)
    return out


def exact_riemann(left, right, x, t, x0=0.0, gamma_left=1.4, gamma_right=None,
                  pinf_left=0.0, pinf_right=0.0):
    """Exact solution at positions x (array) and time t > 0, diaphragm at x0.

    Returns dict with float64 arrays 'rho', 'u', 'p' and 'e', the specific
    internal energy e = (p + gamma p_inf) / ((gamma - 1) rho) of the local
    material (left material left of the contact), plus 'p_star', 'u_star'.
    """
    args = _unpack(left, right, gamma_left, gamma_right, pinf_left, pinf_right)
    if not t > 0.0:
        raise ValueError("exact_riemann: t must be > 0")
    ps, us = star_state(left, right, gamma_left, gamma_right, pinf_left, pinf_right)
    x = np.ascontiguousarray(x, dtype=np.float64)
    shape = x.shape
    xf = x.ravel()
    rho = np.empty_like(xf)
    u = np.empty_like(xf)
    p = np.empty_like(xf)
    e = np.empty_like(xf)
    _sample(xf, float(t), float(x0), *args, ps, us, rho, u, p, e)
    return {"rho": rho.reshape(shape), "u": u.reshape(shape), "p": p.reshape(shape),
            "e": e.reshape(shape), "p_star": ps, "u_star": us}
