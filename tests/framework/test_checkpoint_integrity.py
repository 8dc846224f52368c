"""Checkpoints carry a sha256 per file: a damaged one is never restarted from silently.

A truncated or overwritten rank file, or an edited checkpoint.json, makes restart fall back to
the newest intact checkpoint with a one-line notice (or a clean error when none is intact, or
when the damaged one was asked for by -t); pruning renames before deleting, so no directory
under a checkpoint's name is ever incomplete.
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from framework.archiver import DataArchive, _remove_dir, load_checkpoint
from framework.controller import Controller
from tests.conftest import run_deck
from tests.framework import decks

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@pytest.fixture
def finished(tmp_path):
    """A finished run that kept its newest three checkpoints."""
    text = decks.heat(n=24, patches="[2,1,1]", maxTime=0.12, out=2,
                      checkpoint='<checkpoint timestepInterval="2" cycle="3"/>')
    ctl = run_deck(text, tmp_path, name="full")
    uda = ctl.archiver.dir
    cps = sorted(os.listdir(os.path.join(uda, "checkpoints")))
    assert len(cps) == 3 and all(c.startswith("t") and "." not in c for c in cps)
    return uda, cps


def _restart(uda, tmp_path, name, index=-1):
    c = Controller(restart=uda, restart_index=index, quiet=True, filebase=str(tmp_path / f"{name}.uda"))
    return c


def test_intact_checkpoint_restarts_as_before(finished, tmp_path):
    uda, cps = finished
    notices = []
    d, info, _ = load_checkpoint(uda, -1, notices)
    assert os.path.basename(d) == cps[-1] and notices == []
    assert set(info["sha256"]) >= {"input.ups", "rank0000.h5"}


@pytest.mark.parametrize("damage", ["truncate", "overwrite64", "edit_json", "bad_json", "delete_rank_file"])
def test_damaged_newest_checkpoint_falls_back(finished, tmp_path, damage):
    uda, cps = finished
    newest = os.path.join(uda, "checkpoints", cps[-1])
    rank_file = os.path.join(newest, "rank0000.h5")
    if damage == "truncate":
        with open(rank_file, "r+b") as f:
            f.truncate(os.path.getsize(rank_file) // 2)
    elif damage == "overwrite64":
        with open(rank_file, "r+b") as f:
            f.seek(os.path.getsize(rank_file) - 200)
            f.write(b"\x7f" * 64)
    elif damage == "edit_json":
        path = os.path.join(newest, "checkpoint.json")
        info = json.load(open(path))
        info["time"] *= 2
        with open(path, "w") as f:
            json.dump(info, f, indent=1)
    elif damage == "bad_json":
        with open(os.path.join(newest, "checkpoint.json"), "w") as f:
            f.write("{not json")
    else:
        os.remove(rank_file)
    notices = []
    d, info, _ = load_checkpoint(uda, -1, notices)
    assert os.path.basename(d) == cps[-2]
    assert len(notices) == 1 and cps[-1] in notices[0] and cps[-2] in notices[0]
    # and the restart from the older one runs to the same end as the uninterrupted run
    again = _restart(uda, tmp_path, "again")
    again.run()
    a, b = DataArchive(uda), DataArchive(again.archiver.dir)
    assert a.times[-1] == b.times[-1]
    assert np.array_equal(a.read("temp_CC", 0, -1)[0], b.read("temp_CC", 0, -1)[0])


def test_damaged_checkpoint_chosen_by_index_is_an_error(finished):
    uda, cps = finished
    with open(os.path.join(uda, "checkpoints", cps[0], "rank0000.h5"), "r+b") as f:
        f.truncate(100)
    with pytest.raises(FileNotFoundError, match="damaged"):
        load_checkpoint(uda, 0)


def test_no_intact_checkpoint_is_one_clean_line(finished, tmp_path):
    uda, cps = finished
    for c in cps:
        with open(os.path.join(uda, "checkpoints", c, "checkpoint.json"), "a") as f:
            f.write(" ")
    env = dict(os.environ, PYTHONPATH=ROOT)
    r = subprocess.run([sys.executable, "-m", "framework", "-q", "-restart", uda], capture_output=True, text=True,
                       env=env, timeout=300, cwd=tmp_path)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "no intact checkpoint" in lines[0], r.stderr


def test_prune_never_leaves_an_incomplete_checkpoint_name(tmp_path):
    d = tmp_path / "checkpoints" / "t00004"
    d.mkdir(parents=True)
    (d / "rank0000.h5").write_bytes(b"x" * 10)
    real_rmtree = shutil.rmtree
    calls = []

    def killed_midway(path, ignore_errors=False):
        if os.path.exists(path):
            calls.append(str(path))
            raise KeyboardInterrupt           # the process dies while deleting
    shutil.rmtree = killed_midway
    try:
        with pytest.raises(KeyboardInterrupt):
            _remove_dir(str(d))
    finally:
        shutil.rmtree = real_rmtree
    assert not d.exists(), "the checkpoint's own name is gone before anything is deleted"
    assert os.listdir(tmp_path / "checkpoints") == ["t00004.old"] and calls[0].endswith(".old")
    assert load_checkpoint_names(tmp_path) == []


def load_checkpoint_names(uda):
    """What restart would consider: the leftover .old is not a checkpoint."""
    with pytest.raises(FileNotFoundError, match="no complete checkpoint"):
        load_checkpoint(str(uda))
    return []


def test_full_disk_is_one_line(tmp_path, monkeypatch, capsys):
    """A full disk (ENOSPC anywhere in the exception chain) ends with the failure line alone."""
    import errno

    from framework import cli
    from framework.controller import Controller as Ctl

    def no_space(self):
        try:
            raise OSError(errno.ENOSPC, "No space left on device")
        except OSError as e:
            raise RuntimeError("writing output failed") from e
    monkeypatch.setattr(Ctl, "run", no_space)
    deck = tmp_path / "d.ups"
    deck.write_text(decks.heat(n=8, maxTime=0.01))
    monkeypatch.chdir(tmp_path)
    assert cli.main([str(deck), "-q"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("pysus: the run failed") and "writing output failed" in err[0]


def test_sigkill_while_checkpointing_leaves_a_restartable_checkpoint(tmp_path):
    """Killed with SIGKILL at three moments of a run that checkpoints every step, each time the
    newest complete checkpoint restarts, and the run continued to the end equals the run that
    never stopped, bitwise."""
    import signal
    import time

    from tests.conftest import BIN
    text = decks.heat(n=64, patches="[2,2,1]", maxTime=0.3, out=4,
                      checkpoint='<checkpoint timestepInterval="1" cycle="2"/>')
    (tmp_path / "d.ups").write_text(text)
    whole = run_deck(text, tmp_path, name="whole")
    ref = DataArchive(whole.archiver.dir).read("temp_CC", 0, -1)[0]
    restarted = 0
    for k, delay in enumerate((0.0, 0.1, 0.3)):
        uda = tmp_path / f"killed{k}.uda"
        p = subprocess.Popen([str(BIN / "pysus"), "-q", str(tmp_path / "d.ups"), "--filebase", str(uda)],
                             cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        start = time.monotonic()        # killed `delay` s after its first checkpoint, however long the start-up
        while p.poll() is None and time.monotonic() - start < 120:
            if (uda / "checkpoints").is_dir() and any(c.startswith("t") for c in os.listdir(uda / "checkpoints")):
                break
            time.sleep(0.01)
        time.sleep(delay)
        if p.poll() is not None:
            continue                        # it finished first: nothing was killed
        p.send_signal(signal.SIGKILL)
        p.wait()
        if not (uda / "checkpoints").is_dir() or not any(
                c.startswith("t") and "." not in c for c in os.listdir(uda / "checkpoints")):
            continue                        # killed before its first checkpoint: nothing to restart
        again = _restart(str(uda), tmp_path, f"again{k}")
        again.run()
        assert np.array_equal(DataArchive(again.archiver.dir).read("temp_CC", 0, -1)[0], ref)
        restarted += 1
    assert restarted >= 1


def test_real_full_disk_keeps_the_last_checkpoint(tmp_path):
    """Output to a 3 MB file system fills it: one failure line, no traceback, and the newest
    complete checkpoint restarts (needs root to mount a tmpfs; skipped otherwise)."""
    disk = tmp_path / "disk"
    disk.mkdir()
    if os.geteuid() != 0 or not shutil.which("mount") or subprocess.run(
            ["mount", "-t", "tmpfs", "-o", "size=3m", "tmpfs", str(disk)], capture_output=True).returncode != 0:
        pytest.skip("cannot mount a small tmpfs here")
    try:
        text = decks.heat(n=64, maxTime=10.0, out=1, checkpoint='<checkpoint timestepInterval="3" cycle="2"/>')
        (tmp_path / "d.ups").write_text(text)
        env = dict(os.environ, PYTHONPATH=ROOT)
        r = subprocess.run([sys.executable, "-m", "framework", "-q", str(tmp_path / "d.ups"), "--filebase",
                            str(disk / "run.uda")], capture_output=True, text=True, env=env, timeout=300)
        assert r.returncode == 1
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("pysus: the run failed") and "checkpoint" in lines[0], r.stderr
        shutil.copytree(disk / "run.uda", tmp_path / "copy.uda")
    finally:
        subprocess.run(["umount", str(disk)], capture_output=True)
    d, info, _ = load_checkpoint(str(tmp_path / "copy.uda"))
    start = info["state"]["timestep"]
    assert start > 0
    again = Controller(restart=str(tmp_path / "copy.uda"), quiet=True, filebase=str(tmp_path / "again.uda"),
                       max_timesteps=start + 2)
    again.run()
    assert again.timestep == start + 2
