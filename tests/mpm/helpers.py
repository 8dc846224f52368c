"""Shared helpers of the MPM tests: run deck text, read energies."""
import re

import numpy as np

from framework.archiver import DataArchive
from tests.conftest import ROOT, UINTAH_INPUTS, run_deck

MPM_INPUTS = ROOT / "inputs" / "MPM"


def deck_text(path, **tags):
    """The deck's text with the given simple tags' values replaced (e.g. maxTime=0.1)."""
    text = open(path).read()
    for tag, value in tags.items():
        text, n = re.subn(rf"<{tag}>[^<]*</{tag}>", f"<{tag}>{value}</{tag}>", text, count=1)
        assert n == 1, tag
    return text


def run(text, tmp_path, name="run"):
    ctl = run_deck(text, tmp_path, name)
    return ctl, DataArchive(ctl.archiver.dir)


def energy(da):
    t, ke = da.reduction("KineticEnergy")
    _, se = da.reduction("StrainEnergy")
    return np.asarray(t), np.asarray(ke) + np.asarray(se)
