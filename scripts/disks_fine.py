#!/usr/bin/env python
"""Colliding disks (inputs/MPM/disks_50x50.ups) on a finer grid through the collision:
report the energy error max |E/E0 - 1| (E = KineticEnergy + StrainEnergy), the mass
change, the number of steps and the wall time.

    .venv/bin/python scripts/disks_fine.py --res 400 --patches 2 2 --ranks 2 --max-time 3.0

Not a test (minutes at 400 x 400). The deck is disks_50x50.ups with the resolution,
patch layout, end time and output replaced; only reductions are saved.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from framework.archiver import DataArchive  # noqa: E402


def deck(res, patches, max_time, interval):
    text = (ROOT / "inputs" / "MPM" / "disks_50x50.ups").read_text()
    text = re.sub(r"<resolution>[^<]*</resolution>", f"<resolution>[{res},{res},1]</resolution>", text)
    text = re.sub(r"<patches>[^<]*</patches>", f"<patches>[{patches[0]},{patches[1]},1]</patches>", text)
    text = re.sub(r"<maxTime>[^<]*</maxTime>", f"<maxTime>{max_time}</maxTime>", text)
    text = re.sub(r"<outputInterval>[^<]*</outputInterval>", f"<outputInterval>{interval}</outputInterval>", text)
    text = re.sub(r'\s*<save label = "[pg]\.[^"]*"/>', "", text)
    text = re.sub(r"\s*<checkpoint[^>]*/>", "", text)
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--res", type=int, default=400)
    ap.add_argument("--patches", type=int, nargs=2, default=(2, 2))
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--max-time", type=float, default=3.0)
    ap.add_argument("--interval", type=float, default=0.025)
    ap.add_argument("--json", help="write the numbers here")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "disks.ups"
        path.write_text(deck(a.res, a.patches, a.max_time, a.interval))
        uda = Path(tmp) / "disks.uda"
        cmd = [str(ROOT / ".venv" / "bin" / "pysus"), str(path), "-q", "--filebase", str(uda)]
        if a.ranks > 1:
            cmd = [str(ROOT / ".venv" / "bin" / "mpiexec"), "-n", str(a.ranks)] + cmd
        t0 = time.time()
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
        wall = time.time() - t0
        if r.returncode:
            print(r.stderr[-3000:])
            sys.exit(r.returncode)
        da = DataArchive(uda)
        import numpy as np
        t, ke = da.reduction("KineticEnergy")
        _, se = da.reduction("StrainEnergy")
        _, m = da.reduction("TotalMass")
        E = np.asarray(ke) + np.asarray(se)
        out = dict(res=a.res, patches=list(a.patches), ranks=a.ranks, t_end=float(t[-1]),
                   outputs=len(t), energy_err_max=float(np.max(np.abs(E / E[0] - 1))),
                   energy_err_end=float(E[-1] / E[0] - 1), ke_min_over_ke0=float(np.min(ke) / ke[0]),
                   mass_change=float(m[-1] / m[0] - 1), all_finite=bool(np.all(np.isfinite(E))),
                   wall_s=round(wall, 1),
                   energy_err_history=[(round(float(a), 3), round(float(b / E[0] - 1), 5))
                                       for a, b in zip(t[::max(1, len(t) // 12)], E[::max(1, len(t) // 12)])])
    print(json.dumps(out, indent=1))
    if a.json:
        Path(a.json).write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
