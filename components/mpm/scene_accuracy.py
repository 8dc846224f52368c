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
  stretch comp_neo_hook bar stretched to twice its length by the StretchedBar manufactured
          solution (mms.py; 1D, n cells per metre, 2 particles per cell): at the end
          (t = T) the L1 error of sigma_xx relative to the largest exact one, of the positions
          relative to the bar's length, and the largest gap between neighbouring particles
          in cells (exact: 1.5, the 3x stretch at the middle).
  twist   the TwistedAnnulus manufactured solution (mms.py; the ring 0.75 < R < 1.25 twisted
          by A rad, shear up to 7.1 A; n cells per metre, 2 x 2 particles per cell): at the end
          the L1 error of the in-plane stress (Frobenius norm) relative to the largest exact
          one, and of the positions relative to the ring's width 0.5.
Every scene also takes `interpolator` cpdi and fast_cpdi.
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


def lame_deck(n, interpolator="linear", update="musl", cut=None):
    """cut: the cylinder's <cut_cell_particles> (its surface sub-cells' particles hold the part inside)."""
    text = _with("thick_cylinder.ups", {"resolution": f"[{int(n)},{int(n)},1]"}, interpolator, update)
    if cut is not None:
        text = text.replace("<res>[2,2,1]</res>", f"<res>[2,2,1]</res><cut_cell_particles>{str(cut).lower()}"
                                                  "</cut_cell_particles>", 1)
        assert "cut_cell_particles" in text
    return text


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


STRETCH = dict(rho=1.0, K=0.6, mu=0.3)        # c = sqrt((K + 4 mu/3) / rho) = 1 m/s
TWIST = dict(rho=1000.0, K=833.33, mu=384.62)   # Uintah's GeneralizedVortex: E = 1000 Pa, nu = 0.3


def _mms_deck(kind, lower, upper, cells, extra, res, geom, mat, interpolator, update, amplitude, ramp):
    """A one-material comp_neo_hook deck driven by <RunMMSProblem> (mms.py) to t = ramp."""
    return f"""<?xml version="1.0" encoding="ISO-8859-1"?>
<Uintah_specification>
  <Meta><title>MMS {kind}</title></Meta>
  <SimulationComponent type="mpm"/>
  <Time><maxTime>{ramp}</maxTime><initTime>0.0</initTime><delt_min>0.0</delt_min><delt_max>1.0</delt_max>
    <timestep_multiplier>0.4</timestep_multiplier></Time>
  <Grid><Level><Box label="1"><lower>{lower}</lower><upper>{upper}</upper><resolution>{cells}</resolution>
    <extraCells>{extra}</extraCells><patches>[1,1,1]</patches></Box></Level></Grid>
  <DataArchiver><filebase>mms.uda</filebase><outputInterval>{ramp}</outputInterval>
    <save label="p.x"/><save label="p.stress"/><save label="p.displacement"/><save label="KineticEnergy"/>
  </DataArchiver>
  <MPM><interpolator>{interpolator}</interpolator><stress_update>{update}</stress_update>
    <RunMMSProblem>{kind}</RunMMSProblem><mms_amplitude>{amplitude}</mms_amplitude>
    <mms_ramp_time>{ramp}</mms_ramp_time></MPM>
  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
  <MaterialProperties><MPM><material><density>{mat["rho"]}</density>
    <constitutive_model type="comp_neo_hook"><bulk_modulus>{mat["K"]}</bulk_modulus>
      <shear_modulus>{mat["mu"]}</shear_modulus></constitutive_model>
    <geom_object>{geom}<res>{res}</res><velocity>[0,0,0]</velocity></geom_object></material>
    <contact><type>null</type></contact></MPM></MaterialProperties>
</Uintah_specification>
"""


def stretch_deck(n, interpolator="linear", update="musl", amplitude="1.0", ramp="1.0", strip=False):
    """The bar 0 < X < 1 in the 1D domain -0.25 < x < 2.25 (n cells per metre). strip: the bar
    as a 2D strip two cells high, periodic in y (the same uniaxial strain, on the 2D kernels)."""
    n = int(n)
    rows = 2 if strip else 1
    box = f'<box label="bar"><min>[0,0,0]</min><max>[1,{rows / n},{1.0 / n}]</max></box>'
    text = _mms_deck("StretchedBar", "[-0.25,0,0]", f"[2.25,{rows / n},{1.0 / n}]", f"[{int(2.5 * n)},{rows},1]",
                     "[1,0,0]", f"[2,{rows},1]", box, STRETCH, interpolator, update, float(amplitude), float(ramp))
    return text.replace("</Box></Level>", "</Box><periodic>[0,1,0]</periodic></Level>") if strip else text


def _mms_final(da, kind, mat):
    from .mms import exact
    parts = da.particles(0, -1)
    x, s, disp = parts["p.x"], parts["p.stress"], parts["p.displacement"]
    meta = _mms_meta(da)
    xe, se = exact(kind, x - disp, da.times[-1], meta["A"], meta["T"], mat["K"], mat["mu"])
    return x, s, xe, se


def _mms_meta(da):
    """mms_amplitude, mms_ramp_time and the cells along x as the run's deck held them."""
    text = open(os.path.join(da.path, "input.ups"), encoding="iso-8859-1").read()
    get = lambda tag: re.search(rf"<{tag}>\[?([^<,\]]*)", text).group(1)   # noqa: E731
    return {"A": float(get("mms_amplitude")), "T": float(get("mms_ramp_time")), "nx": int(get("resolution"))}


def stretch_errors(da):
    x, s, xe, se = _mms_final(da, "StretchedBar", STRETCH)
    scale = np.abs(se[:, 0, 0]).max()
    cells_per_m = _mms_meta(da)["nx"] / 2.5
    return {"stress": float(np.mean(np.abs(s[:, 0, 0] - se[:, 0, 0])) / scale),
            "x": float(np.mean(np.abs(x[:, 0] - xe[:, 0]))),
            "gap": float(np.diff(np.sort(x[:, 0])).max() * cells_per_m)}


def twist_deck(n, interpolator="linear", update="musl", amplitude="0.5", ramp="1.0"):
    """The ring in -1.5 < x, y < 1.5 (n cells per metre)."""
    n = int(n)
    dz = 1.0 / n
    cyl = '<cylinder label="{0}"><bottom>[0,0,0]</bottom><top>[0,0,{1}]</top><radius>{2}</radius></cylinder>'
    geom = f'<difference>{cyl.format("outer", dz, 1.25)}{cyl.format("inner", dz, 0.75)}</difference>'
    return _mms_deck("TwistedAnnulus", "[-1.5,-1.5,0]", f"[1.5,1.5,{dz}]", f"[{3 * n},{3 * n},1]", "[1,1,0]",
                     "[2,2,1]", geom, TWIST, interpolator, update, float(amplitude), float(ramp))


def twist_errors(da):
    x, s, xe, se = _mms_final(da, "TwistedAnnulus", TWIST)
    norm = lambda a: np.sqrt(np.einsum("pij,pij->p", a[:, :2, :2], a[:, :2, :2]))    # noqa: E731
    return {"stress": float(np.mean(norm(s - se)) / norm(se).max()),
            "x": float(np.mean(np.hypot(*(x - xe)[:, :2].T))) / 0.5}


SCENES = {
    "bar": (bar_deck, bar_errors, "period",
            "MPM fixed-free elastic bar: relative period error against 4 L / c (interpolator, update)"),
    "lame": (lame_deck, lame_errors, "eq43",
             "MPM thick cylinder under internal pressure: paper 000 eq. 43 against Lame (interpolator, update, cut)"),
    "disks": (disks_deck, disks_errors, "energy",
              "MPM colliding disks to t = 1.6: largest relative change of total energy (interpolator, update)"),
    "stretch": (stretch_deck, stretch_errors, "stress",
                "MPM comp_neo_hook bar stretched to twice its length (StretchedBar MMS, 3x at the middle): L1 "
                "error of sigma_xx / max, of x / L, largest particle gap in cells (exact 1.5) (interpolator, "
                "update, amplitude, ramp)"),
    "twist": (twist_deck, twist_errors, "stress",
              "MPM comp_neo_hook ring twisted by `amplitude` rad (TwistedAnnulus MMS, shear up to 7.1 A): L1 "
              "error of the in-plane stress / max, of x / ring width (interpolator, update, amplitude, ramp)"),
}
