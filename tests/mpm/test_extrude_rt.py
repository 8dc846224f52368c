"""Uintah's extrudeRT (uintah_reference/extrudeRT.ups): an L-shaped level (two <Box>es), 100
stacked geometry objects of one material (40,000 particles) and InsertParticles, which moves
colour 0 into the big box at 20 m/s in the first step.

sus reference (tests/mpm/data/sus_extrudeRT.npz, read from sus's uda with UintahArchive; the
deck with <max_Timesteps>5, output every step, p.velocity, KineticEnergy and TotalMomentum
saved, as the test runs it): times, particle counts, KineticEnergy and TotalMomentum of steps
1-5; p.x and p.stress (xx xy xz yy yz zz) of colours 0 (inserted) and 1 (stacked in the small
box, on the L's re-entrant edge) at step 3; p.x and p.velocity of colour 0 at step 5.
pysus runs with <stress_update>usl (Uintah's update; pysus's default is musl).

From step 4 the inserted block's stress parts from sus's by 1e-4 of the largest at step 5
(3e-3 in 38), growing about threefold a step: the volumetric stress of this nearly
incompressible material (Poisson's ratio 0.49) amplifies a 1e-10 difference of J. The deck on
one rectangular box (the small box widened to the whole level) parts from sus the same way
(4e-3 at step 4, 2e-2 at step 5: measured), so it is not the L-shaped level's doing.
"""
import pathlib

import numpy as np

from framework.archiver import DataArchive
from framework.controller import Controller
from tests.conftest import pysus_ranks

HERE = pathlib.Path(__file__).parent
TOL_X = 1e-12           # m; measured 2.2e-16 (step 3), 5.7e-14 (step 5)
TOL_V = 1e-8            # m/s; measured 5.0e-10 (step 5)
TOL_STRESS3 = 5e-8      # of the largest at step 3; measured 8.0e-9 (colour 0), 6.8e-9 (colour 1)
TOL_KE = 1e-10          # relative; measured 7.5e-13


def _deck(steps, usl=True):
    text = (HERE / "uintah_reference" / "extrudeRT.ups").read_text(encoding="iso-8859-1")
    text = text.replace("<delt_max>0.001</delt_max>",
                        f"<delt_max>0.001</delt_max><max_Timesteps>{steps}</max_Timesteps>")
    text = text.replace("<outputInterval>.01</outputInterval>", "<outputTimestepInterval>1</outputTimestepInterval>")
    text = text.replace('<checkpoint cycle = "2" interval = "0.02"/>',
                        '<save label="p.velocity"/><save label="KineticEnergy"/><save label="TotalMomentum"/>')
    if usl:
        text = text.replace("<interpolator>gimp</interpolator>",
                            "<interpolator>gimp</interpolator><stress_update>usl</stress_update>")
    assert f"<max_Timesteps>{steps}" in text and "TotalMomentum" in text
    return text


def _match(x, rx):
    """Index into x of the particle at each position of rx (unique within one colour)."""
    k = np.argmin(((rx[:, None, :] - x[None, :, :]) ** 2).sum(axis=2), axis=1)
    assert len(np.unique(k)) == len(rx)
    return k


def _inputs(tmp_path):
    """The deck's <include> and <InsertParticlesFile> (inputs/MPM/...) beside the deck."""
    (tmp_path / "inputs").symlink_to(HERE / "uintah_reference" / "inputs")


def test_extrude_rt_as_sus(tmp_path):
    ref = np.load(HERE / "data" / "sus_extrudeRT.npz")
    _inputs(tmp_path)
    path = tmp_path / "extrudeRT.ups"
    path.write_text(_deck(5), encoding="iso-8859-1")      # a file: its <include> is resolved
    ctl = Controller(str(path), quiet=True, filebase=str(tmp_path / "run.uda"))
    ctl.run()
    da = DataArchive(ctl.archiver.dir)
    lv = ctl.level
    assert lv.holes and len(lv.patches) == 18
    times = np.asarray(da.times)[1:]
    assert np.allclose(times, ref["time"], rtol=1e-12)
    counts = [len(da.particles(0, j)["p.x"]) for j in range(1, 6)]
    assert counts == list(ref["n"]) == [40000] * 5
    t, ke = da.reduction("KineticEnergy")
    assert np.allclose(np.asarray(ke)[1:], ref["ke"], rtol=TOL_KE, atol=0)
    _, mom = da.reduction("TotalMomentum")
    assert np.abs(np.asarray(mom)[1:] - ref["momentum"]).max() < 1e-10 * np.abs(ref["momentum"]).max()
    p3 = da.particles(0, 3)
    for c in (0, 1):
        mine = np.flatnonzero(p3["p.color"] == c)
        k = mine[_match(p3["p.x"][mine], ref[f"x3_{c}"])]
        assert np.abs(p3["p.x"][k] - ref[f"x3_{c}"]).max() < TOL_X
        s = p3["p.stress"][k][:, [0, 0, 0, 1, 1, 2], [0, 1, 2, 1, 2, 2]]
        rs = ref[f"stress3_{c}"]
        assert np.abs(s - rs).max() < TOL_STRESS3 * np.abs(rs).max()
    stacked = np.flatnonzero(p3["p.color"] == 1)
    for c in (2, 50, 99):                  # the stacked objects move as one
        other = np.flatnonzero(p3["p.color"] == c)
        o = np.lexsort(p3["p.x"][other].T[::-1]), np.lexsort(p3["p.x"][stacked].T[::-1])
        assert np.array_equal(p3["p.stress"][other][o[0]], p3["p.stress"][stacked][o[1]])
    p5 = da.particles(0, 5)
    mine = np.flatnonzero(p5["p.color"] == 0)
    k = mine[_match(p5["p.x"][mine], ref["x5_0"])]
    assert np.abs(p5["p.x"][k] - ref["x5_0"]).max() < TOL_X
    assert np.abs(p5["p.velocity"][k] - ref["v5_0"]).max() < TOL_V


def test_extrude_rt_unchanged_two_ranks_bitwise(tmp_path):
    """The deck as Uintah's regression list runs it (pysus's default musl), 3 steps on 1 and 2
    ranks: the same particles to the bit (sorted by colour and position) and KineticEnergy."""
    path = tmp_path / "extrudeRT.ups"
    path.write_text(_deck(3, usl=False), encoding="iso-8859-1")
    _inputs(tmp_path)
    runs = {}
    for n in (1, 2):
        uda = tmp_path / f"run{n}.uda"
        r = pysus_ranks(path, "--filebase", uda, np_=n, timeout=300)
        assert r.returncode == 0, r.stderr[-2000:]
        runs[n] = DataArchive(uda)
    a, b = runs[1].particles(0, -1), runs[2].particles(0, -1)
    assert len(a["p.x"]) == len(b["p.x"]) == 40000
    oa = np.lexsort((*a["p.x"].T[::-1], a["p.color"]))
    ob = np.lexsort((*b["p.x"].T[::-1], b["p.color"]))
    for lab in ("p.x", "p.velocity", "p.stress", "p.color"):
        assert np.array_equal(a[lab][oa], b[lab][ob]), lab
    assert np.array_equal(runs[1].reduction("KineticEnergy")[1], runs[2].reduction("KineticEnergy")[1])
