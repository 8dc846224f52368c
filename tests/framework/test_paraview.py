"""ParaView's XDMF readers (the legacy one and both Xdmf3 ones) load our output with the
right values and draw the particles as cells, in 2D (a flat grid, zero z extent, under the
particles, which lie inside its x-y bounds) and 3D (skipped without pvbatch)."""
import functools
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
def grow(box, b):
    for i in range(6):
        box[i] = (min if i % 2 == 0 else max)(box[i], b[i])
for name in sys.argv[1].split(","):       # each reader in turn, in one pvbatch
    r = getattr(pv, name)(FileName=[sys.argv[2]]) if name != "XDMFReader" else pv.XDMFReader(FileNames=[sys.argv[2]])
    r.UpdatePipeline(float(sys.argv[3]))
    d = servermanager.Fetch(r)
    it = d.NewIterator(); it.InitTraversal()
    lo, hi, cells, parts, pcells = 1e300, -1e300, 0, 0, 0
    gb = [1e300, -1e300] * 3          # bounds of the grid blocks, of the particle blocks
    pb = [1e300, -1e300] * 3
    while not it.IsDoneWithTraversal():
        b = it.GetCurrentDataObject()
        a = b.GetCellData().GetArray("temp_CC_0")
        if a is not None:
            assert a.GetNumberOfComponents() == 1 and a.GetNumberOfTuples() == b.GetNumberOfCells()
            lo, hi = min(lo, a.GetRange()[0]), max(hi, a.GetRange()[1]); cells += b.GetNumberOfCells()
            grow(gb, b.GetBounds())
        m = b.GetPointData().GetArray("p.mass_0")
        if m is not None:
            grow(pb, b.GetBounds())
            assert m.GetNumberOfComponents() == 1 and m.GetNumberOfTuples() == b.GetNumberOfPoints()
            parts += b.GetNumberOfPoints(); pcells += b.GetNumberOfCells()
        it.GoToNextItem()
    print("RESULT", name, cells, parts, pcells, repr(lo), repr(hi), " ".join(repr(x) for x in gb + pb))
"""


@functools.lru_cache(maxsize=None)
def _paraview_python():
    """Whether pvbatch runs under xvfb-run and imports paraview (Debian's paraview package
    without python3-paraview has a pvbatch that cannot)."""
    if not (shutil.which("pvbatch") and shutil.which("xvfb-run")):
        return False
    r = subprocess.run(["xvfb-run", "-a", "pvbatch", "-c", "import paraview.simple"],
                       capture_output=True, text=True, timeout=120)
    return r.returncode == 0


@pytest.mark.parametrize("nz", [1, 4])
def test_paraview_readers_draw_cells_and_particles(tmp_path, nz):
    if not _paraview_python():
        pytest.skip("ParaView's pvbatch with its Python module not installed")
    ctl = run_deck(decks.heat(n=8, nz=nz, patches="[2,2,1]", maxTime=0.05, particles=True,
                              extra_save='<save label="p.x"/><save label="p.mass"/>'), tmp_path)
    (tmp_path / "pv.py").write_text(SCRIPT)
    da = DataArchive(ctl.archiver.dir)
    T, _ = da.read("temp_CC", 0, -1)
    nparts = len(da.particles(0, -1)["p.x"])
    assert nparts > 0
    r = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 640x480x24 +extension GLX", "pvbatch",
                        str(tmp_path / "pv.py"), ",".join(READERS), f"{ctl.archiver.dir}/output.xdmf",
                        str(da.times[-1])], capture_output=True, text=True, timeout=240)
    for reader in READERS:
        line = [l for l in r.stdout.splitlines() if l.startswith(f"RESULT {reader} ")]
        assert line, reader + r.stdout + r.stderr
        _, _, cells, parts, pcells, lo, hi, *bounds = line[0].split()
        grid, parts_box = [float(x) for x in bounds[:6]], [float(x) for x in bounds[6:]]
        assert int(cells) == T.size, reader
        assert int(parts) == nparts and int(pcells) == nparts, reader    # particles are drawable cells
        assert float(lo) == T.min() and float(hi) == T.max(), reader
        assert grid[:4] == [0.0, 1.0, 0.0, 1.0], reader         # the unit square of the deck
        for d in (0, 1):      # every particle inside the grid's x and y bounds
            assert grid[2 * d] < parts_box[2 * d] and parts_box[2 * d + 1] < grid[2 * d + 1], reader
        if nz == 1:           # 2D: a plane (zero z extent) under every particle
            assert grid[4] == grid[5] == 0.0 and parts_box[4] > grid[5], reader
        else:
            assert (grid[4], grid[5]) == (0.0, 1.0) and grid[4] < parts_box[4] < parts_box[5] < grid[5], reader
