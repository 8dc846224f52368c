"""MPMICE decks on 2 and 3 ranks give bitwise the one-rank answer (4 patches in every run).

The slab at rest, the gas-driven piston, Uintah's TBurner_2dRT (its 3-step test copy: Unsteady_Burn,
semi-implicit pressure) and Uintah's symAnnulus.ups (shortened) run on 1 rank in the test's
process, then on 2 and 3 ranks, all in one mpiexec launch: cell-centred fields of every material and the particles (sorted by
particle ID) are compared with np.array_equal. The arithmetic does not depend on the rank
count: each patch computes its own cells and nodes from its own data plus ghosts, particle
sums run in particle-ID order, and the only cross-rank sums are the delT minimum.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, UINTAH_INPUTS, edited_deck, run_cases

PID = '<save label="p.particleID"/>'
CASES = {
    "slab_rest": (ROOT / "inputs" / "MPMICE" / "slab_rest.ups",
                  [("<patches> [1,1,1] </patches>", "<patches> [4,1,1] </patches>"),
                   ("<max_Timesteps> 200 </max_Timesteps>", "<max_Timesteps> 40 </max_Timesteps>"),
                   ("<outputTimestepInterval> 100 </outputTimestepInterval>",
                    "<outputTimestepInterval> 20 </outputTimestepInterval>"),
                   ('<save label="p.x"/>', '<save label="p.x"/>' + PID)]),
    "piston": (ROOT / "inputs" / "MPMICE" / "piston.ups",
               [("<patches> [1,1,1] </patches>", "<patches> [4,1,1] </patches>"),
                ("<maxTime> 5.0e-4 </maxTime>", "<maxTime> 2.0e-4 </maxTime>"),
                ('<save label="p.x"/>', '<save label="p.x"/>' + PID)]),
    # Unsteady_Burn's cell and particle memory, the semi-implicit pressure with its circular outlet
    "TBurner_2dRT": (ROOT / "tests" / "mpmice" / "uintah_reference" / "TBurner_2dRT.ups", []),
    "symAnnulus": (UINTAH_INPUTS / "MPMICE" / "symAnnulus.ups",
                   [("<maxTime>            0.006", "<maxTime> 2.0e-5"),
                    ("<outputInterval> 1.0e-4", "<outputInterval> 1.0e-5"),
                    ('<save label = "p.x"/>', '<save label = "p.x"/>' + PID)]),
}
CC = ("press_CC", "vel_CC", "rho_CC", "vol_frac_CC", "temp_CC", "sp_vol_CC", "eng_L_ME_CC", "mom_L_ME_CC")
PARTS = ("p.x", "p.velocity", "p.temperature", "p.stress", "p.volume", "p.pressure",
         "UnsteadyBurn.PartSurfTemp", "UnsteadyBurn.PartSurfTempGrad")


@pytest.fixture(scope="module")
def launched(tmp_path_factory):
    """Every case's deck (where it is available) on 1 rank in this process, then on 2 and 3 ranks
    in one mpiexec launch: the directory of the udas and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("mpmice_ranks")
    cases = sorted(case for case, (src, _) in CASES.items() if src.exists())
    for case in cases:
        src, repl = CASES[case]
        edited_deck(src, repl, d / f"{case}.ups")
    return d, run_cases(d, cases, (1, 2, 3))


@pytest.mark.parametrize("case", sorted(CASES))
def test_mpmice_ranks_equal_one_rank(launched, case):
    src, _ = CASES[case]
    if not src.exists():
        pytest.skip(f"{src} not available")
    d, out = launched
    for n in (1, 2, 3):
        rc, err = out[case, n]
        assert rc == 0, err[-2000:]
    runs = {n: DataArchive(d / f"{case}_{n}.uda") for n in (1, 2, 3)}
    one = runs[1]
    assert len(one.times) >= 2
    nmat = len(one.materials)
    for n in (2, 3):
        other = runs[n]
        assert np.array_equal(one.times, other.times)
        compared = 0
        for lab in CC:
            if lab not in one.labels:
                continue
            for m in ((0,) if lab == "press_CC" else range(nmat)):
                try:
                    a, _ = one.read(lab, m, -1)
                except KeyError:
                    continue
                b, _ = other.read(lab, m, -1)
                assert np.array_equal(a, b), (case, n, lab, m, np.abs(a - b).max())
                compared += 1
        assert compared >= 4
        a, b = one.particles(0, -1), other.particles(0, -1)
        oa, ob = np.argsort(a["p.particleID"]), np.argsort(b["p.particleID"])
        assert len(oa) > 0 and np.array_equal(a["p.particleID"][oa], b["p.particleID"][ob])
        for lab in PARTS:
            if lab in a:
                assert np.array_equal(a[lab][oa], b[lab][ob]), (case, n, lab)
