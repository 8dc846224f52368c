"""Every deck under inputs/ runs two timesteps with output: the shared part of tests/decks/.

One test file per inputs/ folder, so that pytest-xdist (`--dist loadfile`) can hand the
folders to different workers instead of running every deck on one.
"""
from tests.conftest import ROOT


def decks(folder):
    """The decks of inputs/<folder>, and their test ids."""
    paths = sorted((ROOT / "inputs" / folder).rglob("*.ups"))
    return paths, [p.relative_to(ROOT / "inputs").as_posix() for p in paths]


def run_two_steps(deck, tmp_path):
    """Run the deck for two timesteps; it must get there and, if it archives, write a time."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    ctl = Controller(str(deck), quiet=True, filebase=str(tmp_path / "run.uda"), max_timesteps=2)
    ctl.run()
    assert ctl.timestep == 2
    if ctl.archiver is not None:
        assert len(DataArchive(ctl.archiver.dir).times) >= 1
