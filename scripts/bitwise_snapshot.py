"""Run a few shortened MPM / MPMICE decks and save their final particle state, or compare it
with a saved snapshot bitwise: the check for refactorings that must not change one bit.

    python scripts/bitwise_snapshot.py save SNAP.npz      (on the code before the change)
    python scripts/bitwise_snapshot.py compare SNAP.npz   (on the code after it)

Run it from the repository root whose code it should use (the current directory comes
first on sys.path). Every saved particle variable of every material at the last output
is compared, ordered by p.particleID.
"""
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path.cwd()
sys.path.insert(0, str(ROOT))

from framework.archiver import DataArchive  # noqa: E402

# deck, <MPM> flags, --max-timesteps
CASES = {
    "disks_usl": ("inputs/MPM/disks_50x50.ups", {"interpolator": "linear", "stress_update": "usl"}, 4),
    "disks_musl": ("inputs/MPM/disks_50x50.ups", {"interpolator": "linear", "stress_update": "musl"}, 4),
    "disks_gimp": ("inputs/MPM/disks_50x50.ups", {"interpolator": "gimp", "stress_update": "musl"}, 4),
    "disks_gimp_usl": ("inputs/MPM/disks_50x50.ups", {"interpolator": "gimp", "stress_update": "usl"}, 4),
    "thick_cylinder": ("inputs/MPM/thick_cylinder.ups", {}, 4),
    "piston": ("inputs/MPMICE/piston.ups", {}, 6),
}
LABELS = ("p.x", "p.velocity", "p.stress", "p.mass", "p.volume", "p.deformationMeasure", "p.particleID")


def deck(path, flags):
    """The deck's text with the given <MPM> flags set and the compared labels saved."""
    text = open(path).read()
    for tag, value in flags.items():
        text = re.sub(rf"\s*<{tag}>[^<]*</{tag}>", "", text)
        text = text.replace("</MPM>", f"<{tag}>{value}</{tag}></MPM>", 1)
    if flags.get("interpolator") == "gimp":
        text = re.sub(r"<extraCells>[^<]*</extraCells>", "<extraCells>[1,1,0]</extraCells>", text)
    saves = "".join(f'<save label="{lab}"/>' for lab in LABELS if f'"{lab}"' not in text)
    return text.replace("</DataArchiver>", saves + "</DataArchiver>", 1)


def run(name, tmp):
    """Final particle arrays of one case, keyed name/material/label, in particle-ID order."""
    path, flags, steps = CASES[name]
    ups = Path(tmp) / f"{name}.ups"
    ups.write_text(deck(ROOT / path, flags))
    uda = Path(tmp) / f"{name}.uda"
    code = "import sys; from framework.cli import main; sys.exit(main())"
    r = subprocess.run([sys.executable, "-c", code, str(ups), "--filebase", str(uda), "--max-timesteps", str(steps),
                        "-q"], cwd=ROOT, capture_output=True, text=True, timeout=900)
    if r.returncode:
        raise SystemExit(f"{name}: {r.stderr[-2000:]}")
    da = DataArchive(uda)
    out = {}
    for m in range(len(da.materials)):
        p = da.particles(m, -1)
        if "p.particleID" not in p:
            continue
        order = np.argsort(p["p.particleID"])
        for lab, arr in p.items():
            out[f"{name}/{m}/{lab}"] = np.asarray(arr)[order]
    return out


def main():
    mode, snap = sys.argv[1], sys.argv[2]
    names = sys.argv[3:] or sorted(CASES)
    with tempfile.TemporaryDirectory() as tmp:
        arrays = {}
        for name in names:
            arrays.update(run(name, tmp))
    if mode == "save":
        np.savez(snap, **arrays)
        print(f"saved {len(arrays)} arrays")
        return 0
    ref = np.load(snap)
    bad = [k for k in ref.files if k.split("/")[0] in names
           and (k not in arrays or not np.array_equal(ref[k], arrays[k], equal_nan=True))]
    for k in bad:
        print("DIFFERS:", k)
    print(f"compared {len(ref.files)} arrays: {len(bad)} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
