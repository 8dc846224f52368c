"""Adiabatic piston compression (paper 000 sec. 4.2): deck at a chosen resolution and the
bottom pressure against the adiabatic law P1 (V1/V2)^gamma (eq. 44).

    deck(n, ...)  inputs/MPMICE/piston_validation.ups (Uintah's pistonValidation.ups with the
                  piston stopped at compression ratio 5.9, as in the paper) with n cells
                  along the 2.5 mm column (dy = 2.5e-3 / n; the deck's 200 cells: n = 200);
                  gamma, speed (the piston's, m/s) and ratio (V1/V2 where it stops) vary the
                  deck's 1.4, 1e-3 and 5.9 (the times scale with 1/speed)
    history(da)   per output (the first at t = 0), of a pysus DataArchive or a sus
                  UintahArchive: t, the piston's bottom y_b (lowest particle minus half a
                  particle spacing), V1/V2 = y_b(0) / y_b(t), the trapped gas's own volume
                  ratio (sum of its volume fractions), P at the bottom cell (y = dy/2, the
                  paper's "y = 0"), the exact P1 (V1/V2)^gamma and the relative error
    errors(da)    the relative error at the highest compression ('end', the first output
                  there: just after the piston stops), its largest magnitude while the piston
                  moves ('max': from 200 cells on the start's pressure wave, about 0.024,
                  sets it) and from V1/V2 = 2 on before it stops ('late'), the mean
                  magnitude ('mean'), the mean error over the outputs from the stop on
                  ('held'; with heat exchange the gas at rest cools against the piston)
The exact law assumes the trapped gas is uniform and in equilibrium: the piston moves at
Mach 0.03, so the pressure is uniform to ~0.1 % below it. Used by scripts/piston_validation.py,
scripts/accuracy_cost.py (scene "piston") and tests/mpmice/test_piston_validation.py.
"""
from __future__ import annotations

import os

import numpy as np

from framework.uintah_uda import particle_var

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "piston_validation.ups")
H = 2.5e-3                  # column height
P1, GAMMA = 1.01325, 1.4    # the trapped gas's initial pressure and gamma (deck)
RES = 2                     # particles per cell along y (deck)
Y0, SPEED = 1.0e-3, 1.0e-3  # the piston's bottom at t = 0 and its speed (deck; it stops at V1/V2 = 5.9)


def deck(n=200, t_end=None, stop=None, heat=None, patches="1,2,1", output=None, gamma=None, speed=None, ratio=None,
         open_faces=None, delt_max=None):
    """The validation deck with n cells; t_end: maxTime; stop: the piston's stop_time;
    heat: the heat-exchange coefficients (one number for all pairs); output: outputInterval;
    gamma: both gases' gamma (their densities scaled to keep the pressure P1); speed: the piston's speed (m/s; maxTime, stop_time, delt_max and
    outputInterval scale with 1/speed unless given); ratio: V1/V2 at the stop (sets stop_time);
    open_faces: "false" for Uintah's advection next to the piston (the deck's "true": docs/MPMICE.md,
    step 12); delt_max: the largest step (s; the deck's 0.006 at its speed)."""
    text = open(DECK, encoding="iso-8859-1").read()
    reps = [("<resolution>    [1,200,1]               </resolution>", f"<resolution> [1,{int(n)},1] </resolution>"),
            ("<patches>       [1,2,1]                 </patches>", f"<patches> [{patches}] </patches>")]
    slow = SPEED / float(speed) if speed is not None else 1.0      # the deck's times over this speed's
    if speed is not None or delt_max is not None:
        dt = 0.006 * slow if delt_max is None else float(delt_max)
        reps.append(("<delt_max>           0.006    </delt_max>", f"<delt_max> {dt!r} </delt_max>"))
    if speed is not None:
        v = -float(speed)
        reps += [("<velocity>              [0.0,-0.001,0.0] </velocity>", f"<velocity> [0.0,{v!r},0.0] </velocity>"),
                 ("<velocity>             [0.0,-0.001,0.0]  </velocity>", f"<velocity> [0.0,{v!r},0.0] </velocity>")]
        output = 0.01 * slow if output is None else output
        stop = 0.8305 * slow if stop is None and ratio is None else stop
        t_end = 0.9 * slow if t_end is None and ratio is None else t_end
    if ratio is not None:
        stop = Y0 * (1.0 - 1.0 / float(ratio)) / (SPEED / slow) if stop is None else stop
        t_end = stop + 0.07 * slow if t_end is None else t_end
    if gamma is not None:
        old = "<gamma>                      1.4             </gamma>"
        assert text.count(old) == 2, old
        text = text.replace(old, f"<gamma> {float(gamma)!r} </gamma>")
        # the gases start from their density (as sus's): scaled so that they start at P1 still
        old = "<density>               1179.294693       </density>"
        assert text.count(old) == 2, old
        rho = 1179.294693 * (GAMMA - 1.0) / (float(gamma) - 1.0)
        text = text.replace(old, f"<density> {rho!r} </density>")
    if open_faces is not None:
        reps.append(('<advection type = "SecondOrder" openFaceTransfers = "true"/>',
                     f'<advection type = "SecondOrder" openFaceTransfers = "{str(open_faces).lower()}"/>'))
    if t_end is not None:
        reps.append(("<maxTime>            0.9      </maxTime>", f"<maxTime> {float(t_end)!r} </maxTime>"))
    if stop is not None:
        reps.append(("<stop_time>   0.8305          </stop_time>", f"<stop_time> {float(stop)!r} </stop_time>"))
    if heat is not None:
        h = float(heat)
        reps.append(("<heat>           [   1,    1,    1]     </heat>", f"<heat> [{h!r}, {h!r}, {h!r}] </heat>"))
    if output is not None:
        reps.append(("<outputInterval> 0.01 </outputInterval>", f"<outputInterval> {float(output)!r} </outputInterval>"))
    for old, new in reps:
        assert old in text, old
        text = text.replace(old, new)
    return text


def history(da, gamma=GAMMA):
    """Arrays over the outputs: t, y_b, ratio (geometric), ratio_gas, P (bottom cell), exact, err."""
    rows = []
    for i, t in enumerate(da.times):
        y = particle_var(da, "p.x", 0, i)[:, 1]
        p, _ = da.read("press_CC", 0, i)
        p = p.reshape(-1)
        dy = H / p.size
        yb = float(y.min()) - 0.5 * dy / RES
        try:
            vf, _ = da.read("vol_frac_CC", 1, i)
            gas = float(vf.sum()) * dy
        except KeyError:           # vol_frac_CC is computed in the step: not at t = 0
            gas = np.nan
        rows.append((t, yb, float(p[0]), gas))
    t, yb, pb, gas = (np.array(c) for c in zip(*rows))
    ratio = yb[0] / yb
    gas[0] = yb[0]                 # at t = 0 the trapped gas fills the column below the piston
    ratio_gas = yb[0] / gas
    exact = P1 * ratio ** gamma
    return {"t": t, "y_b": yb, "ratio": ratio, "ratio_gas": ratio_gas, "P": pb, "exact": exact,
            "err": (pb - exact) / exact, "err_gas": (pb - P1 * ratio_gas ** gamma) / (P1 * ratio_gas ** gamma)}


def errors(da, gamma=GAMMA):
    """Relative error of the bottom pressure against eq. 44 while the piston moves."""
    h = history(da, gamma)
    moving = np.flatnonzero(h["ratio"] >= h["ratio"].max() * (1 - 1e-9))
    last = moving[0] if moving.size else len(h["t"]) - 1       # first output at the highest compression
    sel = slice(1, last + 1)
    before = slice(1, last)
    late = np.abs(h["err"][before][h["ratio"][before] >= 2.0])
    return {"end": float(h["err"][last]), "max": float(np.abs(h["err"][sel]).max()),
            "mean": float(np.abs(h["err"][sel]).mean()), "late": float(late.max()) if late.size else np.nan,
            "held": float(h["err"][last:].mean()), "ratio": float(h["ratio"][last]),
            "end_gas": float(h["err_gas"][last])}
