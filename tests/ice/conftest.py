"""Helpers for ICE tests: run a deck (file or text) into a temporary .uda and open it."""
import os

import pytest

from framework.archiver import DataArchive
from framework.controller import Controller

UINTAH = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "uintah-inputs", "ICE")
INPUTS = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "ICE")


@pytest.fixture
def run_deck(tmp_path):
    """run_deck(path=None, text=None) -> DataArchive of the finished run."""
    def run(path=None, text=None):
        if text is not None:
            path = str(tmp_path / "deck.ups")
            with open(path, "w") as f:
                f.write(text)
        c = Controller(path, quiet=True, filebase=str(tmp_path / "run.uda"))
        c.run()
        return DataArchive(c.archiver.dir)
    return run
