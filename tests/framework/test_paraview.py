"""ParaView's own XDMF reader loads our output with the right values (skipped without pvbatch)."""
import shutil
import subprocess

import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import run_deck
from tests.framework import decks

SCRIPT = """
import sys
from paraview.simple import XDMFReader, servermanager
r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipeline(float(sys.argv[2]))
d = servermanager.Fetch(r)
it = d.NewIterator(); it.InitTraversal()
lo, hi, cells, parts = 1e300, -1e300, 0, 0
while not it.IsDoneWithTraversal():
    b = it.GetCurrentDataObject()
    a = b.GetCellData().GetArray("temp_CC_0")
    if a is not None:
        assert a.GetNumberOfComponents() == 1 and a.GetNumberOfTuples() == b.GetNumberOfCells()
        lo, hi = min(lo, a.GetRange()[0]), max(hi, a.GetRange()[1]); cells += b.GetNumberOfCells()
    m = b.GetPointData().GetArray("p.mass")
    if m is not None:
        assert m.GetNumberOfComponents() == 1 and m.GetNumberOfTuples() == b.GetNumberOfPoints()
        parts += b.GetNumberOfPoints()
    it.GoToNextItem()
print("RESULT", cells, parts, repr(lo), repr(hi))
"""


@pytest.mark.skipif(not (shutil.which("pvbatch") and shutil.which("xvfb-run")), reason="ParaView not installed")
def test_paraview_reads_cells_and_particles(tmp_path):
    ctl = run_deck(decks.heat(n=16, patches="[2,2,1]", maxTime=0.05, particles=True,
                              extra_save='<save label="p.x"/><save label="p.mass"/>'), tmp_path)
    (tmp_path / "pv.py").write_text(SCRIPT)
    da = DataArchive(ctl.archiver.dir)
    r = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 640x480x24 +extension GLX", "pvbatch",
                        str(tmp_path / "pv.py"), f"{ctl.archiver.dir}/output.xdmf", str(da.times[-1])],
                       capture_output=True, text=True, timeout=240)
    line = [l for l in r.stdout.splitlines() if l.startswith("RESULT")]
    assert line, r.stdout + r.stderr
    _, cells, parts, lo, hi = line[0].split()
    T, _ = da.read("temp_CC", 0, -1)
    assert int(cells) == T.size and int(parts) == len(da.particles(0, -1)["p.x"])
    assert float(lo) == T.min() and float(hi) == T.max()
