"""Uintah's statistics and planeAverage <DataAnalysis> modules (framework/analysis.py) against sus.

Deck: uintah_reference/impVortices_statistics.ups (the explicit Smagorinsky vortices deck, whose
flow is sus's to round-off, 6 steps, with statistics from 5e-5 s: in its window from step 4,
higher-order statistics and computeReynoldsStress on vel_CC; planeAverage on XZ planes every
step, weighting nCells, mass (the weight rho_CC) and none). data/sus_vortices_statistics.npz is
sus's output on that deck (one rank; the deck with the pysus-only advection attributes limiter
and dissipationHeating removed, which are sus's defaults), read with
framework.uintah_uda.UintahArchive: the times, each saved statistics label along the row j = 5,
k = 0 after steps 4 and 6, and its planeAverage files of step 6 (press_CC weighted by rho_CC,
vel_CC by nCells: the rows; temp_CC, weighting none: the text).

Measured (vel_CC itself is sus's to 9e-15 of its largest value): every order-n label (sums,
means, variance, skewness, kurtosis, the Reynolds stress products) to 4e-14 (about n times that) of the row's
largest |Q|^n; variance, skewness and kurtosis are differences of nearly equal moments (p^4 ~
1e20 for kurtosis), so relative to themselves only to 5e-7 (skewness of press_CC); the plane
averages to 1e-14; temp_CC's file (weighting none) is byte for byte sus's.
"""
import pathlib

import numpy as np
import pytest

from framework.problemspec import InputError

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "impVortices_statistics.ups"
ORDER = {"sum_": 1, "mean_": 1, "sum2_": 2, "variance_": 2, "sum3_": 3, "skewness_": 3, "sum4_": 4, "kurtosis_": 4}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(str(DECK), quiet=True, filebase=str(tmp_path_factory.mktemp("stats") / "run.uda"))
    c.run()
    return DataArchive(c.archiver.dir), np.load(HERE / "data" / "sus_vortices_statistics.npz")


def rows(text):
    return np.array([[float(x) for x in line.split()] for line in text.splitlines() if not line.startswith("#")])


def test_statistics_as_uintah(runs):
    da, sus = runs
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-13, atol=0)
    for q in ("press_CC", "vel_CC"):
        for step in (4, 6):
            # the scale of an order-n moment: the largest |Q|^n along the row
            value = np.abs(sus[f"{q}@{step}"]).max()
            for prefix, n in ORDER.items():
                got = da.read(prefix + q, 0, step)[0][:, 5, 0]
                ref = sus[f"{prefix}{q}@{step}"]
                scale = value ** n * (step - 3 if prefix.startswith("sum") else 1)
                assert np.abs(got - ref).max() <= 1e-13 * scale, (prefix + q, step, np.abs(got - ref).max() / scale)
        # before the window: the statistics are 0 and the sums stay 0
        assert not np.any(da.read("mean_" + q, 0, 3)[0]) and not np.any(da.read("sum4_" + q, 0, 3)[0])
    vmax = np.abs(sus["vel_CC@6"]).max()
    for label in ("sum_uv_vw_wu", "mean_uv_vw_wu", "uv_vw_wu_prime"):
        got = da.read(label, 0, 6)[0][:, 5, 0]
        assert np.abs(got - sus[f"{label}@6"]).max() <= 1e-13 * 3 * vmax ** 2, label
    # uv_vw_wu_prime after one sample: mean(u v) - mean(u) mean(v) = 0 up to round-off
    assert np.abs(da.read("uv_vw_wu_prime", 0, 4)[0]).max() <= 1e-14 * vmax ** 2


def test_plane_average_as_uintah(runs):
    da, sus = runs
    folder = pathlib.Path(da.path) / "planeAverage"
    assert sorted(p.name for p in folder.iterdir()) == [f"t{n:05d}" for n in range(1, 7)]
    press = (folder / "t00006/L-0/press_CC_0").read_text()
    assert press.startswith(str(sus["plane_press_header"]))
    got, ref = rows(press), sus["plane_press@6"]                 # weighting="mass": sum p / sum rho
    assert got.shape == ref.shape == (25, 5)
    assert np.array_equal(got[:, :3], ref[:, :3])
    assert np.allclose(got[:, 3:], ref[:, 3:], rtol=1e-14, atol=0)
    for step in (1, 6):
        got, ref = rows((folder / f"t{step:05d}/L-0/vel_CC_0").read_text()), sus[f"plane_vel@{step}"]
        assert got.shape == ref.shape == (25, 7)
        assert np.allclose(got[:, 3:6], ref[:, 3:6], rtol=0, atol=1e-14 * np.abs(ref[:, 3:6]).max())
    assert (folder / "t00006/L-0/temp_CC_0").read_text() == str(sus["plane_temp_text@6"])


@pytest.mark.parametrize("old, new, message", [
    ('<analyze label="press_CC" matl="0"/>', '<analyze label="press_XX" matl="0"/>',
     r'impVortices_statistics.ups:\d+: .*label="press_XX" is not a cell- or face-centred double or Vector'),
    ('<analyze label="vel_CC"   computeReynoldsStress="true"/>',
     '<analyze label="press_CC" matl="0" computeReynoldsStress="true"/>', "computeReynoldsStress on press_CC"),
    ("<timeStart>         5e-5", "<timeStart>         500", "timeStop is before timeStart"),
    ("<planeOrientation>  XZ", "<planeOrientation>  XX", "planeOrientation"),
    ('<analyze label="press_CC" matl="0" weighting="mass"/>', '<analyze label="press_CC" weighting="mass"/>',
     'press_CC needs matl="0"'),
    ('<weight label="rho_CC"/>', '<weight label="mass_adv"/>',
     r'weighting="mass" of press_CC needs <weight label="..."> naming a cell-centred double .*given: mass_adv'),
    ('<analyze label="temp_CC"/>', '<analyze label="temp_CC" weighting="volume"/>',
     r'attribute weighting="volume" is not accepted; accepted: nCells, mass'),
])
def test_bad_input_is_refused(tmp_path, old, new, message):
    from framework.controller import Controller
    text = DECK.read_text(encoding="iso-8859-1")
    assert old in text
    deck = tmp_path / "impVortices_statistics.ups"
    deck.write_text(text.replace(old, new, 1), encoding="iso-8859-1")
    with pytest.raises(InputError, match=message):
        Controller(str(deck), quiet=True, filebase=str(tmp_path / "r.uda"))


def test_statistics_restart_continues_the_sums(tmp_path):
    """The sums and the step count are carried in checkpoints: restarting from the step-5
    checkpoint (two steps into the window) gives step 6's statistics bit for bit."""
    from framework.archiver import DataArchive
    from tests.conftest import pysus, pysus_ranks
    text = DECK.read_text(encoding="iso-8859-1").replace(
        '      <save label="vel_CC"/>', '      <checkpoint timestepInterval="5" cycle="2"/>\n      <save label="vel_CC"/>', 1)
    deck = tmp_path / "d.ups"
    deck.write_text(text, encoding="iso-8859-1")
    r = pysus_ranks(deck, "--filebase", tmp_path / "a.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    r = pysus("-restart", tmp_path / "a.uda", "-t", "0", "--filebase", tmp_path / "b.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    a, b = DataArchive(tmp_path / "a.uda"), DataArchive(tmp_path / "b.uda")
    assert a.times[-1] == b.times[-1] and len(b.times) < len(a.times)        # b starts at step 5
    for label in ("mean_press_CC", "kurtosis_vel_CC", "uv_vw_wu_prime", "sum4_press_CC"):
        assert np.array_equal(a.read(label, 0, -1)[0], b.read(label, 0, -1)[0]), label
    assert (tmp_path / "b.uda" / "planeAverage" / "t00006" / "L-0" / "temp_CC_0").read_text() == \
        (tmp_path / "a.uda" / "planeAverage" / "t00006" / "L-0" / "temp_CC_0").read_text()
