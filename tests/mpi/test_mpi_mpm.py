"""MPM decks on 2 and 3 ranks give bitwise the one-rank answer.

Particle-to-grid sums run in particle-ID order over owned and ghost particles, and
relocation keeps each patch's particles sorted by ID, so neither the patch layout nor
the rank count changes the arithmetic.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, UINTAH_INPUTS, edited_deck, run_cases

CASES = {
    "disks_sulsky": (UINTAH_INPUTS / "MPM" / "disks_sulsky.ups",
                     [("<patches>[1,1,1]</patches>", "<patches>[2,2,1]</patches>"),
                      ("<maxTime>3.0</maxTime>", "<maxTime>0.6</maxTime>"),
                      ('<save label = "p.x"/>', '<save label = "p.x"/><save label="p.particleID"/>')]),
    # GIMP's ghost particles: Uintah's disks.ups on one cell in z (the disks' thickness; the patches
    # split x and y only), with comp_neo_hook of the same moduli for comp_mooney_rivlin and g.volume
    # saved for g.stressFS: the kernels inputs/MPMICE/pressurized_cylinder.ups compiles (GIMP in 2D,
    # neo-Hooke in the grad pass, p2g with the volume) instead of ones only this test used; the
    # order of the sums does not depend on them
    "disks_gimp": (UINTAH_INPUTS / "MPM" / "disks.ups",
                   [("<maxTime>0.2</maxTime>", "<maxTime>0.01</maxTime>"),
                    ('<save label = "p.x"/>', '<save label = "p.x"/><save label="p.particleID"/>'),
                    ('<save label = "g.stressFS"/>', '<save label = "g.volume"/>'),
                    ("<lower>[0,0,0]</lower>", "<lower>[0,0,.05]</lower>"),
                    ("<upper>[1.0,1.0,.15]</upper>", "<upper>[1.0,1.0,.1]</upper>"),
                    ("<resolution>[40,40,3]</resolution>", "<resolution>[40,40,1]</resolution>"),
                    ('<constitutive_model type="comp_mooney_rivlin"> ', '<constitutive_model type="comp_neo_hook">'),
                    ("<he_constant_1>100000.0</he_constant_1>", "<shear_modulus>2.4e5</shear_modulus>"),
                    ("<he_constant_2>20000.0</he_constant_2>", "<bulk_modulus>1.192e7</bulk_modulus>"),
                    ("<he_PR>.49</he_PR>", "")]),
    # friction_LR contact (normals from ghost particles of the other patches), 4 patches
    "nairn_friction_lr": (ROOT / "tests" / "mpm" / "nairn_friction.ups",
                          [("<patches>[2,1,1]</patches>", "<patches>[4,1,1]</patches>"),
                           ("<max_Timesteps>3</max_Timesteps>", "<max_Timesteps>20</max_Timesteps>"),
                           ("<outputTimestepInterval>1<", "<outputTimestepInterval>20<")]),
    # pressure + torque load curves, a spinning rigid stem (include_rotation), 4 patches
    "load_curve_spin": (ROOT / "tests" / "mpm" / "load_curve_spin.ups",
                        [("<max_Timesteps>2</max_Timesteps>", "<max_Timesteps>4</max_Timesteps>")]),
}


@pytest.fixture(scope="module")
def launched(tmp_path_factory):
    """Every case's deck on 1 rank in this process, then on 2 and 3 ranks in one mpiexec launch:
    the directory of the udas and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("mpm_ranks")
    (d / "spin.txt").write_text("0 0 0 0 0 0 0 0 0 50\n9.9 0 0 0 0 0 0 0 0 50\n")
    for case, (src, repl) in CASES.items():
        edited_deck(src, repl, d / f"{case}.ups")
    return d, run_cases(d, sorted(CASES), (1, 2, 3))


@pytest.mark.parametrize("case", sorted(CASES))
def test_mpm_ranks_equal_one_rank(launched, case):
    d, out = launched
    for n in (1, 2, 3):
        rc, err = out[case, n]
        assert rc == 0, err[-2000:]
    runs = {n: DataArchive(d / f"{case}_{n}.uda") for n in (1, 2, 3)}
    base = {m: runs[1].particles(m, -1) for m in range(len(runs[1].materials))}
    assert sum(len(b["p.x"]) for b in base.values()) > 0
    for n in (2, 3):
        assert np.array_equal(runs[1].times, runs[n].times)
        for m, b in base.items():
            other = runs[n].particles(m, -1)
            oa, ob = np.argsort(b["p.particleID"]), np.argsort(other["p.particleID"])
            assert np.array_equal(b["p.particleID"][oa], other["p.particleID"][ob])
            for lab in ("p.x", "p.velocity", "p.stress"):
                if lab in b:
                    assert np.array_equal(b[lab][oa], other[lab][ob]), (case, n, m, lab)
