"""MPM validation scenes for scripts/accuracy_cost.py: a deck per resolution and options, and its error.

Every scene takes `interpolator` (linear, gimp) and `update` (musl, usl: Uintah's
<stress_update>), so the script compares what each interpolator and update costs and buys:

  bar     fixed-free elastic bar (inputs/MPM/bar_vibration.ups, n cells per metre): the
          relative error of the period against the exact 4 L / c = 4 s.
  lame    thick-walled cylinder under internal pressure (inputs/MPM/thick_cylinder.ups,
          n cells across the 1.1 m domain): paper 000 eq. 43 against Lame (eq. 42), and the
          L1 errors of radial and hoop stress relative to the pressure.
  disks   Sulsky's colliding disks (inputs/MPM/disks_50x50.ups with n x n cells, to t = 1.6):
          the largest relative change of KineticEnergy + StrainEnergy (exact: none).
"""
from __future__ import annotations

import os
import re

import numpy as np

INPUTS = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPM")
P_LAME, RI, RO = 19.4e6, 0.5, 1.0


def _with(path, tags, interpolator, update):
    """The deck's text with simple tags replaced and the interpolator/stress update chosen."""
    text = open(os.path.join(INPUTS, path), encoding="iso-8859-1").read()
    for tag, value in tags.items():
        text, n = re.subn(rf"<{tag}>[^<]*</{tag}>", f"<{tag}>{value}</{tag}>", text, count=1)
        assert n == 1, tag
    return text.replace("<interpolator>linear</interpolator>",
                        f"<interpolator>{interpolator}</interpolator><stress_update>{update}</stress_update>")


def bar_deck(n, interpolator="linear", update="musl"):
    """delT from the CFL condition alone (the deck's delt_max 0.01 would fix it at coarse
    resolutions) and the momentum sampled every 0.005 s for the zero crossings."""
    return _with("bar_vibration.ups", {"resolution": f"[{int(round(1.2 * int(n)))},1,1]", "delt_max": "1.0",
                                       "outputInterval": "0.005"}, interpolator, update)


def bar_errors(da):
    t, P = da.reduction("TotalMomentum")
    px = np.asarray(P)[:, 0]
    i = np.where(np.sign(px[1:]) != np.sign(px[:-1]))[0]
    tc = [t[k] - px[k] * (t[k + 1] - t[k]) / (px[k + 1] - px[k]) for k in i]
    period = 2.0 * (tc[1] - tc[0])
    return {"period": abs(period / 4.0 - 1.0), "T": period}


def lame_deck(n, interpolator="linear", update="musl"):
    return _with("thick_cylinder.ups", {"resolution": f"[{int(n)},{int(n)},1]"}, interpolator, update)


def lame_errors(da):
    parts = da.particles(0, -1)
    x, s = parts["p.x"], parts["p.stress"]
    r = np.hypot(x[:, 0], x[:, 1])
    nr = np.stack([x[:, 0] / r, x[:, 1] / r], axis=1)
    nt = np.stack([-nr[:, 1], nr[:, 0]], axis=1)
    s_r = np.einsum("pi,pij,pj->p", nr, s[:, :2, :2], nr)
    s_t = np.einsum("pi,pij,pj->p", nt, s[:, :2, :2], nt)
    a = P_LAME * RI ** 2 / (RO ** 2 - RI ** 2)
    two3 = 2.0 / 3.0 * P_LAME                       # |s_r + s_t| of eq. 42 (ri^2/(ro^2-ri^2) = 1/3)
    return {"eq43": float(np.mean(np.abs(np.abs(s_r + s_t) - two3)) / two3),
            "radial": float(np.mean(np.abs(s_r - a * (1 - RO ** 2 / r ** 2)))) / P_LAME,
            "hoop": float(np.mean(np.abs(s_t - a * (1 + RO ** 2 / r ** 2)))) / P_LAME}


def disks_deck(n, interpolator="linear", update="musl"):
    return _with("disks_50x50.ups", {"resolution": f"[{int(n)},{int(n)},1]", "maxTime": "1.6"},
                 interpolator, update)


def disks_errors(da):
    _, ke = da.reduction("KineticEnergy")
    _, se = da.reduction("StrainEnergy")
    E = np.asarray(ke) + np.asarray(se)
    return {"energy": float(np.max(np.abs(E / E[0] - 1.0)))}


SCENES = {
    "bar": (bar_deck, bar_errors, "period",
            "MPM fixed-free elastic bar: relative period error against 4 L / c (interpolator, update)"),
    "lame": (lame_deck, lame_errors, "eq43",
             "MPM thick cylinder under internal pressure: paper 000 eq. 43 against Lame (interpolator, update)"),
    "disks": (disks_deck, disks_errors, "energy",
              "MPM colliding disks to t = 1.6: largest relative change of total energy (interpolator, update)"),
}
