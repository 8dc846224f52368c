"""Runs under mpiexec -n 2 and -n 3 equal the one-rank answer; restart across rank counts.

The tests run pysus under mpiexec (oversubscribed on small machines is fine; the 3-rank runs
share one launch, conftest.pysus_launch) and compare the archives bitwise: the example component's sums are ordered by
particle ID and ghost cells are exact copies, so no round-off differs.
"""
import os

import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import pysus, pysus_launch, pysus_ranks
from tests.framework import decks

SAVE = ('<save label="p.x"/><save label="p.particleID"/><save label="p.mass"/><save label="g.mass"/>'
        '<save label="TotalHeat"/>')


def deck(**kw):
    base = dict(n=24, patches="[3,2,1]", maxTime=0.1, particles=True, velocity="[1,0.5,0]",
                omega=3.0, extra_save=SAVE, out=4, checkpoint='<checkpoint timestepInterval="10" cycle="3"/>')
    base.update(kw)
    return decks.heat(**base)


def same(a, b, steps=(-1,)):
    da, db = DataArchive(a), DataArchive(b)
    n = min(len(da.times), len(db.times))  # a restarted run holds only the later outputs
    assert n > 0 and np.array_equal(da.times[-n:], db.times[-n:])
    for s in steps:
        for lab in ("temp_CC", "g.mass"):
            assert np.array_equal(da.read(lab, 0, s)[0], db.read(lab, 0, s)[0]), (lab, s)
        pa, pb = da.particles(0, s), db.particles(0, s)
        oa, ob = np.argsort(pa["p.particleID"]), np.argsort(pb["p.particleID"])
        assert np.array_equal(pa["p.particleID"][oa], pb["p.particleID"][ob])
        for lab in ("p.x", "p.mass"):
            assert np.array_equal(pa[lab][oa], pb[lab][ob]), lab


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    d = tmp_path_factory.mktemp("serial")
    (d / "deck.ups").write_text(deck())
    r = pysus_ranks(d / "deck.ups", "--filebase", d / "one.uda")
    assert r.returncode == 0, r.stderr
    return d


def rebalancing_deck():
    return deck().replace("<DataArchiver>", '<LoadBalancer type="DLB"><timestepInterval>3</timestepInterval>'
                                            '</LoadBalancer>\n  <DataArchiver>')


@pytest.fixture(scope="module")
def ranks(serial):
    """ranks(n): the deck's uda on n ranks, run once for the tests that read it; 2 ranks through
    `pysus --np 2` (pysus relaunching itself under mpiexec); 3 in one mpiexec launch with this
    file's other 3-rank runs (pysus_launch): the restart of the 2-rank run from its first
    checkpoint (again3.uda) and the deck with rebalancing (lb.uda), all in serial's directory."""
    udas = {}

    def uda(n):
        if n not in udas:
            if n == 2:
                r = pysus(serial / "deck.ups", "--filebase", serial / "n2.uda", "--np", "2")
                assert r.returncode == 0, r.stderr
            else:
                (serial / "lb.ups").write_text(rebalancing_deck())
                r = pysus_launch([((serial / "deck.ups", "--filebase", serial / "n3.uda"), 3),
                                  (("-restart", uda(2), "-t", "0", "--filebase", serial / "again3.uda"), 3),
                                  ((serial / "lb.ups", "--filebase", serial / "lb.uda"), 3)], serial)
                assert r.returncode == 0, r.stderr
            udas[n] = serial / f"n{n}.uda"
        return udas[n]
    return uda


@pytest.mark.parametrize("nranks", [2, 3])
def test_ranks_equal_one_rank(serial, ranks, nranks):
    uda = ranks(nranks)
    same(serial / "one.uda", uda, steps=(1, 3, -1))
    # sums over patches are added in patch order on any number of ranks: bitwise equal
    t1, h1 = DataArchive(serial / "one.uda").reduction("TotalHeat")
    tn, hn = DataArchive(uda).reduction("TotalHeat")
    assert np.array_equal(t1, tn) and np.array_equal(h1, hn)
    assert (serial / "one.uda" / "TotalHeat.dat").read_bytes() == (uda / "TotalHeat.dat").read_bytes()
    files = os.listdir(uda / DataArchive(uda).index["timesteps"][-1]["dir"])
    assert sum(f.endswith(".h5") for f in files) == nranks


def test_particles_cross_ranks_without_loss_or_duplicates(ranks):
    da = DataArchive(ranks(3))
    p0, p1 = da.particles(0, 0), da.particles(0, -1)
    assert len(np.unique(p1["p.particleID"])) == len(p1["p.particleID"])
    # nothing leaves this domain: count and total mass are kept exactly
    assert len(p1["p.x"]) == len(p0["p.x"])
    assert p1["p.mass"].sum() == pytest.approx(p0["p.mass"].sum(), rel=1e-14)
    e = da.index["timesteps"][-1]
    owners = {int(pid): pm["file"] for pid, pm in e["patches"].items() if pm.get("np", {}).get("0", 0)}
    assert len(set(owners.values())) > 1


@pytest.mark.parametrize("onto", [3, 1])
def test_restart_from_two_ranks_onto_other_counts(serial, ranks, tmp_path, onto):
    if onto == 3:
        ranks(3)                    # restarted in the 3-rank launch
        again = serial / "again3.uda"
    else:
        again = tmp_path / "again.uda"
        r = pysus_ranks("-restart", ranks(2), "-t", "0", "--filebase", again)
        assert r.returncode == 0, r.stderr
    same(serial / "one.uda", again)


def test_error_on_one_rank_ends_all_ranks_and_keeps_checkpoint(serial, tmp_path):
    uda = tmp_path / "fail.uda"
    r = pysus(serial / "deck.ups", "--filebase", uda, np_=3, env={"PYSUS_FAULT": "1:15"}, timeout=120)
    assert r.returncode != 0
    assert "[rank 1]" in r.stderr and "fault injected" in r.stderr
    summary = [ln for ln in r.stderr.splitlines() if "pysus: the run failed" in ln]
    assert summary and "timestep 16" in summary[0] and "checkpoints/t00010" in summary[0]
    cps = DataArchive(uda).index["checkpoints"]
    assert [c["timestep"] for c in cps] == [10]
    r = pysus("-restart", uda, "--filebase", tmp_path / "resumed.uda", np_=2)
    assert r.returncode == 0, r.stderr
    same(serial / "one.uda", tmp_path / "resumed.uda")


def test_np_option_relaunches_under_mpiexec(serial, ranks):
    uda = ranks(2)                  # run with --np 2
    same(serial / "one.uda", uda)
    files = os.listdir(uda / DataArchive(uda).index["timesteps"][-1]["dir"])
    assert sum(f.endswith(".h5") for f in files) == 2           # written by two ranks


def test_rebalancing_keeps_the_answer(serial, ranks):
    ranks(3)                        # the rebalancing deck runs in the 3-rank launch
    same(serial / "one.uda", serial / "lb.uda", steps=(1, -1))


def test_a_rank_killed_ends_the_others(tmp_path):
    """SIGKILL of one rank (a node failing) ends the whole job promptly instead of a hang."""
    import signal
    import subprocess
    import time

    from tests.conftest import BIN
    (tmp_path / "long.ups").write_text(deck(n=64, maxTime=50.0, checkpoint=""))
    job = subprocess.Popen([str(BIN / "mpiexec"), "-n", "2", str(BIN / "pysus"), "-q", str(tmp_path / "long.ups"),
                            "--filebase", str(tmp_path / "long.uda")], cwd=tmp_path,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    ranks = []
    deadline = time.time() + 120
    while len(ranks) < 2 and time.time() < deadline:      # the two pysus processes under mpiexec
        ranks = [pid for pid in _pids_running(str(tmp_path / "long.ups")) if pid != job.pid and _is_rank(pid)]
        time.sleep(0.5)
    assert len(ranks) == 2, "both ranks started"
    while not (tmp_path / "long.uda" / "t00004").exists() and time.time() < deadline:
        time.sleep(0.1)                                     # into the time loop: its output of step 4
    assert (tmp_path / "long.uda" / "t00004").exists() and job.poll() is None
    t0 = time.time()
    os.kill(ranks[1], signal.SIGKILL)
    try:
        job.wait(timeout=30)
    finally:
        if job.poll() is None:
            os.killpg(job.pid, signal.SIGKILL)
    assert time.time() - t0 < 10.0
    assert job.returncode != 0


def _pids_running(text):
    """Processes whose command line mentions text (from /proc, no pgrep needed)."""
    found = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/cmdline", "rb") as f:
                    if text.encode() in f.read():
                        found.append(int(d))
            except OSError:
                continue
    return found


def _is_rank(pid):
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            cmd = f.read().split(b"\0")
    except OSError:
        return False
    return any(c.endswith(b"pysus") for c in cmd) and not any(c.endswith(b"mpiexec") or b"hydra" in c for c in cmd)
