"""<MPMICE><adiabatic_compression>: a compressed ideal gas's flow work in a step at most the adiabat's.

ICE's flow work V theta kappa p delP (eq. 37) is linear in delP: an ideal gas whose pressure
rises from p_eq to p = p_eq + delP in a step gains the fraction (gamma-1)/gamma (p/p_eq)
delP/p_eq of its internal energy, where the adiabat gives (p/p_eq)^((gamma-1)/gamma) - 1; the
two agree to first order in delP/p_eq, but where a solid's cell goes from tension (press_CC
near Uintah's 1e-12 clamp) to compression the trace gas in it sees p/p_eq up to 25 in a step
(x180 linear, x2.5 adiabatic), and the linear work heats it to 1e10 K, as in Uintah's sus
(tests/mpmice/test_hard_cases.py). The option removes the linear work's excess over the
adiabat's where delP > 0; expansion keeps the linear work (the adiabat would cool a trace gas
in a stretched cell, at 1e-12 Pa, to 0 K). Not Uintah's.
"""
from numba import njit


@njit(cache=True)
def limit_compression_work(rho, temp, vf, sp_vol, speed_sound, press, delP, tmv, eng_L, lo, hi, cv, gamma):
    """eng_L -= max(0, linear - adiabatic work) over the interior cells lo..hi with delP > 0 and
    p_eq = press - delP > 0; the work's volume is tmv (MPMICE's TMV_CC) as in the linear term."""
    a = (gamma - 1.0) / gamma
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                d = delP[i, j, k]
                p = press[i, j, k]
                p_eq = p - d
                if d <= 0.0 or p_eq <= 0.0:
                    continue
                work_volume = tmv[i, j, k]
                linear = work_volume * vf[i, j, k] * sp_vol[i, j, k] / speed_sound[i, j, k] ** 2 * p * d
                adiabat = work_volume * rho[i, j, k] * cv * temp[i, j, k] * ((p / p_eq) ** a - 1.0)
                if adiabat < linear:
                    eng_L[i, j, k] -= linear - adiabat
