"""Simple_Burn (components/models) on 1 patch, on 4 patches and on 2 and 3 ranks, 60 steps of
burning (the explosive starts above ThresholdTemp): bitwise the same answer (the burned mass per
cell sums the cell's particles in ID order, and every particle is burned on the patch that owns
it)."""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, pysus_runs

DECK = ROOT / "inputs" / "MPMICE" / "burning_container2D.ups"


@pytest.fixture(scope="module")
def launched(tmp_path_factory):
    """The burning container on 1 and 4 patches and the tracers' deck (t1), each on 1 rank in this
    process, then the container on 2 and 3 ranks and the tracers on 2 (t2), all three in one
    mpiexec launch: the directory of the udas (NAME.uda) and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("models_ranks")
    text = DECK.read_text().replace("<outputTimestepInterval> 100 </outputTimestepInterval>",
                                    "<outputTimestepInterval> 60 </outputTimestepInterval>") \
        .replace('<save label="p.x"/>', '<save label="p.x"/><save label="p.particleID"/>')
    one, four = d / "one.ups", d / "four.ups"
    one.write_text(text.replace("<patches> [2,2,1] </patches>", "<patches> [1,1,1] </patches>"))
    four.write_text(text)
    tracers = ROOT / "tests" / "ice" / "uintah_reference" / "stagnationPoint_explicit.ups"
    runs = [("p1", (one, "--max-timesteps", 60), 1), ("p4", (four, "--max-timesteps", 60), 1), ("t1", (tracers,), 1),
            ("r2", (four, "--max-timesteps", 60), 2), ("r3", (four, "--max-timesteps", 60), 3), ("t2", (tracers,), 2)]
    out = pysus_runs([((*args, "--filebase", d / f"{name}.uda"), n) for name, args, n in runs], d)
    return d, {name: o for (name, _, _), o in zip(runs, out)}


def archives(launched, names):
    d, out = launched
    for name in names:
        rc, err = out[name]
        assert rc == 0, err[-2000:]
    return {name: DataArchive(d / f"{name}.uda") for name in names}


def test_burning_container_ranks_and_patches_equal(launched):
    runs = archives(launched, ("p1", "p4", "r2", "r3"))
    base = runs["p1"]
    assert base.particles(1, -1)["p.mass"].sum() < base.particles(1, 0)["p.mass"].sum()   # it burned
    for name in ("p4", "r2", "r3"):
        other = runs[name]
        assert np.array_equal(base.times, other.times)
        for lab, m in (("press_CC", 0), ("rho_CC", 2), ("temp_CC", 2)):
            assert np.array_equal(base.read(lab, m, -1)[0], other.read(lab, m, -1)[0]), (name, lab)
        for m in (0, 1):
            b, o = base.particles(m, -1), other.particles(m, -1)
            ob, oo = np.argsort(b["p.particleID"]), np.argsort(o["p.particleID"])
            for lab in ("p.x", "p.mass"):
                assert np.array_equal(b[lab][ob], o[lab][oo]), (name, m, lab)


def test_tracer_particles_one_and_two_ranks(launched):
    """TracerParticles (components/models/tracer_particles.py) on the stagnation-point deck, 6
    steps with injection, on 1 and 2 ranks: the flow, the particle count and every particle's
    variables (by ID) are bitwise the same; the particles cross patch and rank boundaries only
    by relocation, and each rank injects into its own patches."""
    runs = archives(launched, ("t1", "t2"))
    one, two = runs["t1"], runs["t2"]
    assert np.array_equal(one.times, two.times)
    for k in range(len(one.times)):
        for lab in ("press_CC", "vel_CC", "scalar-f"):
            assert np.array_equal(one.read(lab, 0, k)[0], two.read(lab, 0, k)[0]), (k, lab)
        a, b = one.particles(0, k), two.particles(0, k)
        oa, ob = np.argsort(a["p.particleID"]), np.argsort(b["p.particleID"])
        assert len(oa) == len(ob) and len(oa) >= 2560
        for lab in a:
            assert np.array_equal(a[lab][oa], b[lab][ob]), (k, lab)
