"""ParaView's XDMF readers (the legacy one and both Xdmf3 ones) load our output with the
right values and draw the particles as cells, in 2D (a grid below the particles) and 3D
(skipped without pvbatch)."""
import shutil
import subprocess

import pytest

from framework.archiver import DataArchive
from tests.conftest import run_deck
from tests.framework import decks

READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")

SCRIPT = """
import sys
import paraview.simple as pv
from paraview import servermanager
r = getattr(pv, sys.argv[1])(FileName=[sys.argv[2]]) if sys.argv[1] != "XDMFReader" else pv.XDMFReader(FileNames=[sys.argv[2]])
r.UpdatePipeline(float(sys.argv[3]))
d = servermanager.Fetch(r)
it = d.NewIterator(); it.InitTraversal()
lo, hi, cells, parts, pcells, grid_top, parts_bottom = 1e300, -1e300, 0, 0, 0, -1e300, 1e300
while not it.IsDoneWithTraversal():
    b = it.GetCurrentDataObject()
    a = b.GetCellData().GetArray("temp_CC_0")
    if a is not None:
        assert a.GetNumberOfComponents() == 1 and a.GetNumberOfTuples() == b.GetNumberOfCells()
        lo, hi = min(lo, a.GetRange()[0]), max(hi, a.GetRange()[1]); cells += b.GetNumberOfCells()
        grid_top = max(grid_top, b.GetBounds()[5])
    m = b.GetPointData().GetArray("p.mass_0")
    if m is not None:
        parts_bottom = min(parts_bottom, b.GetBounds()[4])
        assert m.GetNumberOfComponents() == 1 and m.GetNumberOfTuples() == b.GetNumberOfPoints()
        parts += b.GetNumberOfPoints(); pcells += b.GetNumberOfCells()
    it.GoToNextItem()
print("RESULT", cells, parts, pcells, repr(lo), repr(hi), grid_top < parts_bottom)
"""


@pytest.mark.skipif(not (shutil.which("pvbatch") and shutil.which("xvfb-run")), reason="ParaView not installed")
@pytest.mark.parametrize("nz", [1, 4])
def test_paraview_readers_draw_cells_and_particles(tmp_path, nz):
    ctl = run_deck(decks.heat(n=8, nz=nz, patches="[2,2,1]", maxTime=0.05, particles=True,
                              extra_save='<save label="p.x"/><save label="p.mass"/>'), tmp_path)
    (tmp_path / "pv.py").write_text(SCRIPT)
    da = DataArchive(ctl.archiver.dir)
    T, _ = da.read("temp_CC", 0, -1)
    nparts = len(da.particles(0, -1)["p.x"])
    assert nparts > 0
    for reader in READERS:
        r = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 640x480x24 +extension GLX", "pvbatch",
                            str(tmp_path / "pv.py"), reader, f"{ctl.archiver.dir}/output.xdmf", str(da.times[-1])],
                           capture_output=True, text=True, timeout=240)
        line = [l for l in r.stdout.splitlines() if l.startswith("RESULT")]
        assert line, reader + r.stdout + r.stderr
        _, cells, parts, pcells, lo, hi, under = line[0].split()
        assert int(cells) == T.size, reader
        assert int(parts) == nparts and int(pcells) == nparts, reader    # particles are drawable cells
        assert float(lo) == T.min() and float(hi) == T.max(), reader
        assert under == str(nz == 1), reader     # in 2D the grid's top lies below every particle
