#!/usr/bin/env python
"""Dog-bone membrane expansion (paper 004 sec. 4.3, Tables II-IV): gas fluid points inside a
closed membrane string expand to a circle. Runs components/mpm/scenes.py's deck at each
grid spacing and prints, at the end: mean membrane radius (004 Table III: 1.33-1.36), its
spread (roundness), mean gas pressure, mean hoop stress of the membrane points against
p r / t (Table IV: within 2-5 %), gas points escaped from the membrane
(outside it and farther than dx/4 from it; must be 0), the energy
change relative to the gas's initial internal energy, steps and wall time.

    .venv/bin/python scripts/membrane_expansion.py --dx 0.2 0.1 --t-end 4.0
    .venv/bin/python scripts/membrane_expansion.py --shape ring --dx 0.2 --t-end 0.1 --damping 300

Not a test (minutes). --damping adds <artificial_damping_coeff> (004 uses none: the gas
viscosity 0.2 damps the oscillations).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

import numpy as np  # noqa: E402

from components.mpm.scenes import GAS, membrane_deck, measure  # noqa: E402


def one(shape, dx, t_end, out, damping):
    from framework.controller import Controller
    from framework.archiver import DataArchive
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.time()
        ctl = Controller(str(Path(tmp) / "m.ups"), deck_text=membrane_deck(shape, dx=dx, t_end=t_end, out=out,
                                                                           damping=damping),
                         quiet=True, filebase=str(Path(tmp) / "m.uda"))
        ctl.run()
        wall = time.time() - t0
        da = DataArchive(ctl.archiver.dir)
        hist = []
        for k in range(len(da.times)):
            try:
                hist.append(measure(da, k, dx=dx))
            except ValueError:       # membrane points left the domain: the run blew up
                break
        m = dict(hist[-1])
        m["blew_up_after"] = None if len(hist) == len(da.times) else hist[-1]["time"]
        _, ke = da.reduction("KineticEnergy")
        _, se = da.reduction("StrainEnergy")
        gas0 = da.particles(0, 0)
        e0 = float(gas0["p.mass"].sum() * GAS["e"])
        E = np.asarray(ke) + np.asarray(se)
        k = len(hist) - 1
        m.update(dx=dx, hoop_over_prt=m["hoop"] / m["pr_over_t"],
                 gas_escaped_ever=max(h["gas_escaped"] for h in hist),
                 energy_change_over_gas_e0=float((E[k] - E[0]) / e0),
                 steps=int(getattr(ctl, "timestep", -1)), wall_s=round(wall, 1),
                 radius_history=[(round(h["time"], 3), round(h["r_mean"], 4), round(h["r_max"] - h["r_min"], 4))
                                 for h in hist])
        return m


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shape", default="dogbone", choices=("dogbone", "ring"))
    ap.add_argument("--dx", type=float, nargs="+", default=[0.2, 0.1])
    ap.add_argument("--t-end", type=float, default=4.0)
    ap.add_argument("--out", type=float, default=0.25)
    ap.add_argument("--damping", type=float, default=0.0)
    ap.add_argument("--json")
    a = ap.parse_args()
    res = []
    for dx in a.dx:
        r = one(a.shape, dx, a.t_end, a.out, a.damping)
        print(json.dumps({k: v for k, v in r.items() if k != "radius_history"}), flush=True)
        res.append(r)
    if a.json:
        Path(a.json).write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
