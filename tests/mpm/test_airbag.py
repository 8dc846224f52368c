"""Axisymmetric membranes (membranes of revolution, constitutive/membrane.py with the hoop
stress) and the airbag impact of paper 004 sec. 4.4 (inputs/MPM/airbag.ups, written by
components/mpm/airbag.py; scripts/airbag.py runs the whole impact and plots it).

- A spherical bag of the airbag's fabric holding its gas (004 Table VI), damped to rest: a
  membrane of revolution must carry sigma_tt = sigma_hh = p R / (2 h) (without the hoop
  stress it has no equilibrium); measured at dx = 0.025, R = 0.2, t = 0.02-0.03 s: 1.015 and
  1.015 p R / (2 h), p = (gamma - 1) sum m e over the volume the membrane encloses (the gas
  points' summed volume, from the nodal mass, is 1 % above it: 1.025 with that; with V0 det F
  it drifts to 3 % above), round within 0.7 %, the thickness strain of each point
  -nu (s_tt + s_hh) / E.
- The airbag deck's first 8 ms (the probe meets the bag, 218 steps, an output every step):
  the gas mass is constant to round-off; kinetic + gas internal + fabric and probe strain
  energy (per radian) stays within 10 % of the probe's initial kinetic energy, 0.6 % of the
  total with the gas's internal energy. MUSL with the FLIP update does not conserve energy
  exactly (an O(dt) error each step), and the bag starts out of equilibrium (stress-free
  fabric, gas at 4000 Pa): measured largest change +4.9 % of the kinetic energy, a spike at
  t = 1.7 ms while the fabric takes up the pressure, -2.0 % at 8 ms (-17 % by t = 0.1 s, -1.1 %
  of the total, scripts/airbag.py). The probe's momentum change equals the impulse of the
  force the bag exerts on it, summed step by step from the nodal masses and forces
  (airbag.probe_force; measured to 1e-15 relative; it fails if a boundary condition, the
  contact or the hoop terms touched the probe's axial momentum, or the particle update did
  not use the nodes' accelerations). The gas points' summed volume grows from 1.019 to 1.025
  times the enclosed volume (1.033 with V0 det F instead of <density_from_grid>).
"""
import re

import numpy as np
import pytest

from components.mpm.airbag import FABRIC, PROBE, airbag_deck, enclosed_volume, history, probe_force

from .helpers import MPM_INPUTS, run


def test_deck_is_the_generator():
    """inputs/MPM/airbag.ups is what airbag_deck() writes (behind its header)."""
    text = open(MPM_INPUTS / "airbag.ups").read()
    assert re.sub(r"<!--.*?-->\n", "", text, flags=re.S) == airbag_deck()


def test_sphere_of_revolution_hoop_stress(tmp_path):
    R, h = 0.2, FABRIC["h"]
    ctl, da = run(airbag_deck(sphere=R, t_end=0.03, out=0.002, damping=300.0), tmp_path)
    late = [k for k in range(len(da.times)) if da.times[k] >= 0.02 - 1e-9]
    assert len(late) >= 5
    # the gas points' volumes from the nodal mass (<density_from_grid>): their sum follows the
    # volume the fabric encloses (measured 1.005 times it at t = 0, at most 1.0106 after; with
    # V0 det F alone it drifts to 1.030 by t = 0.03)
    ratio = [da.particles(0, k)["p.volume"].sum() / enclosed_volume(da.particles(1, k))
             for k in range(len(da.times))]
    assert max(ratio) / ratio[0] < 1.01, ratio
    tt, hh, prh = [], [], []
    for k in late:
        g, mem = da.particles(0, k), da.particles(1, k)
        p = 0.4 * np.sum(g["p.mass"] * g["p.internalEnergy"]) / enclosed_volume(mem)
        x, t, s = mem["p.x"], mem["p.tangent"], mem["p.stress"]
        yc = 0.5 * (x[:, 1].max() + x[:, 1].min())
        r = np.linalg.norm(x[:, :2] - [0.0, yc], axis=1)
        assert r.max() - r.min() < 0.01 * R                   # stays round (measured 0.7 %)
        w = x[:, 0]                                            # ring weights
        tt.append(np.average(np.einsum("pi,pij,pj->p", t, s, t), weights=w))
        hh.append(np.average(s[:, 2, 2], weights=w))
        prh.append(p * r.mean() / (2 * h))
        # stress only in the surface: no normal component, the hoop one on the theta axis
        n = np.stack([-t[:, 1], t[:, 0], np.zeros(len(t))], 1)
        assert np.abs(np.einsum("pi,pij,pj->p", n, s, n)).max() < 1e-6 * np.abs(s).max()
        # the thickness strain of biaxial plane stress, point by point: -nu (s_tt + s_hh) / E
        s_sum = np.einsum("pi,pij,pj->p", t, s, t) + s[:, 2, 2]
        thin = -FABRIC["nu"] * s_sum / FABRIC["E"]
        assert np.abs(mem["p.thickness"] / h - 1 - thin).max() < 0.03 * np.abs(thin).max()
    tt, hh, prh = np.mean(tt), np.mean(hh), np.mean(prh)
    assert abs(tt / prh - 1) < 0.04 and abs(hh / prh - 1) < 0.04, (tt, hh, prh)
    assert abs(tt / hh - 1) < 0.03


def test_airbag_impact_conservation(tmp_path):
    ctl, da = run(airbag_deck(t_end=0.008, every_step=True), tmp_path)
    h = history(da)
    n = len(h)
    assert n > 200 and h[-1]["time"] > 0.0079
    # no gas point is lost and the gas mass does not change
    gm = np.array([r["gas_mass"] for r in h])
    assert len(da.particles(0, -1)["p.mass"]) == len(da.particles(0, 0)["p.mass"])
    assert np.abs(gm / gm[0] - 1).max() < 1e-13
    # the probe is slowed by the bag
    assert h[-1]["v"] > -0.95 * PROBE["v"]
    # energy bookkeeping: StrainEnergy holds the gas's internal energy change and the
    # fabric's and the probe's strain energy (all per radian)
    _, ke = da.reduction("KineticEnergy")
    _, se = da.reduction("StrainEnergy")
    e = np.asarray(ke) + np.asarray(se)
    assert abs(ke[0] - 0.5 * PROBE["mass"] * PROBE["v"] ** 2 / (2 * np.pi)) < 1e-3 * ke[0]
    assert np.abs(e - e[0]).max() < 0.1 * ke[0]
    gas_change = h[-1]["gas_energy"] - h[0]["gas_energy"]
    assert abs(gas_change) > 0.05 * ke[0]               # the gas takes part
    # the probe's momentum change is the impulse of the bag's force on it
    t = np.array([r["time"] for r in h])
    P = np.array([r["momentum"] for r in h])
    F = np.array([probe_force(da, k) for k in range(1, n)])
    impulse = np.cumsum(F * np.diff(t))
    assert P[-1] - P[0] > 0.03 * abs(P[0])
    assert np.abs(P[1:] - P[0] - impulse).max() < 1e-10 * abs(P[-1] - P[0])
    # the gas points' summed volume against the volume the fabric encloses (the gas's first
    # row of points straddles the base: 1.019 at t = 0): <density_from_grid> holds it
    # (measured 1.006 times that at 8 ms; with V0 det F 1.014)
    ratio = np.array([r["gas_volume"] / r["bag_volume"] for r in h])
    assert ratio[-1] / ratio[0] < 1.01


@pytest.mark.parametrize("edit, match", [
    (("<formulation>plane", "<formulation>uniaxial"), "formulation uniaxial is not implemented with <axisymmetric>"),
    (("<vertex>[", "<vertex>[0,0.003,0]</vertex><vertex>["), "membrane point at r = 0 has no ring"),
])
def test_axisymmetric_membrane_errors(tmp_path, edit, match):
    from framework.problemspec import InputError
    text = airbag_deck(t_end=1e-4)
    assert edit[0] in text
    with pytest.raises(InputError, match=match):
        run(text.replace(*edit, 1), tmp_path, name="bad")


def test_airbag_patches_bitwise(tmp_path):
    """Four patches (membrane tangents from neighbours across patch edges, ring volumes per
    patch) give bitwise the one-patch answer."""
    out = []
    for n in (1, 2):
        text = airbag_deck(t_end=0.002, out=0.002).replace("<patches>[1,1,1]</patches>",
                                                           f"<patches>[{n},{n},1]</patches>")
        ctl, da = run(text, tmp_path, name=f"p{n}")
        out.append([da.particles(m, -1) for m in (0, 1, 2)])
    for a, b in zip(*out):
        oa, ob = np.argsort(a["p.particleID"]), np.argsort(b["p.particleID"])
        assert len(oa) == len(ob) > 50
        for key in ("p.x", "p.velocity", "p.stress", "p.tangent", "p.thickness", "p.volume"):
            assert np.array_equal(a[key][oa], b[key][ob]), key
