"""pysus info / extract / plot on a small heat + particles run, checked against its
initial state: the Gaussian of components/examples (exact at t = 0) and particles of
known mass filling a known box; and DataArchive's metadata."""
import csv
import io
import sys

import numpy as np
import pytest

from framework import uda_tools
from framework.archiver import DataArchive
from tests.conftest import run_deck
from tests.framework import decks

N, DZ = 8, 0.05
H = 1.0 / N


def gauss(x, y):
    """The deck's initial temperature (centre 0.5, width 0.08, amplitude 1, 2D)."""
    return np.exp(-((x - 0.5) ** 2 + (y - 0.5) ** 2) / (2 * 0.08 ** 2))


@pytest.fixture(scope="module")
def uda(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("tools")
    ctl = run_deck(decks.heat(n=N, patches="[2,2,1]", maxTime=0.02, particles=True,
                              extra_save='<save label="p.x"/><save label="p.mass"/><save label="TotalHeat"/>'), tmp)
    return ctl.archiver.dir


def tool(capsys, *argv):
    code = uda_tools.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_info_lists_labels_with_initial_min_max(uda, capsys):
    code, out, _ = tool(capsys, "info", uda, "-t", 0)
    assert code == 0
    rows = {l.split()[0]: l.split() for l in out.splitlines() if l.startswith("  ") and "label" not in l}
    assert rows["temp_CC"][1:4] == ["CC", "double", "0"] and rows["temp_CC"][-1] == "K"
    c = np.arange(N) * H + H / 2                       # cell centres
    assert float(rows["temp_CC"][4]) == pytest.approx(gauss(c[0], c[0]), rel=1e-5)
    assert float(rows["temp_CC"][5]) == pytest.approx(gauss(c[N // 2], c[N // 2]), rel=1e-5)
    mass = H * H * DZ / 4                              # 2x2 particles per cell, density 1
    assert rows["p.mass"][1] == "Particle" and float(rows["p.mass"][4]) == pytest.approx(mass, rel=1e-5)
    assert rows["p.x"][1:3] == ["Particle", "Vector"]
    r = np.linalg.norm(DataArchive(uda).particles(0, 0)["p.x"], axis=1)   # a Vector's magnitude, as puda's
    assert [float(v) for v in rows["p.x"][4:6]] == pytest.approx([r.min(), r.max()], rel=1e-5)


def test_extract_line_gives_the_cells_along_x(uda, capsys, tmp_path):
    out = tmp_path / "line.csv"
    y = 0.5 + H / 2
    code, _, _ = tool(capsys, "extract", uda, "--var", "temp_CC", "-t", 0,
                      "--line", f"0,{y},0.01", f"1,{y},0.01", "-o", out)
    assert code == 0
    rows = list(csv.DictReader(out.open()))
    x = np.array([float(r["x"]) for r in rows])
    assert np.allclose(x, np.arange(N) * H + H / 2)    # every cell once, in order
    assert all(float(r["y"]) == pytest.approx(y) for r in rows)
    assert np.allclose([float(r["temp_CC"]) for r in rows], gauss(x, y), rtol=1e-12, atol=0)


def test_extract_line_short_points_and_stdout(uda, capsys, tmp_path, monkeypatch):
    """--line 0 1 (or "x,y") runs through the domain's centre in the missing directions; -o - is stdout."""
    monkeypatch.chdir(tmp_path)
    code, out, _ = tool(capsys, "extract", uda, "--var", "temp_CC", "-t", 0, "--line", "0", "1", "-o", "-")
    assert code == 0 and not (tmp_path / "-").exists()
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == N and float(rows[0]["y"]) == pytest.approx(0.5 + H / 2)   # the centre 0.5 is a face
    code, out2, _ = tool(capsys, "extract", uda, "--var", "temp_CC", "-t", 0, "--line", "0,0.5", "1,0.5")
    assert code == 0 and out2 == out


def test_extract_particles_rows(uda, capsys):
    code, out, _ = tool(capsys, "extract", uda, "--particles", "-t", 0)
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    assert set(rows[0]) == {"p.x[0]", "p.x[1]", "p.x[2]", "p.mass"}
    px = np.array([[float(r["p.x[0]"]), float(r["p.x[1]"])] for r in rows])
    assert px.min() > 0.25 and px.max() < 0.75           # the box [0.3, 0.7]^2, to a cell
    assert np.allclose([float(r["p.mass"]) for r in rows], H * H * DZ / 4)


def test_bad_arguments_are_one_line(uda, capsys, tmp_path):
    code, _, err = tool(capsys, "extract", uda, "--var", "nope", "--line", "0,0,0", "1,1,0")
    assert code == 2 and err.startswith("pysus: error: --var nope: not saved") and err.count("\n") == 1
    code, _, err = tool(capsys, "extract", uda, "--var", "temp_CC", "--line", "0,0,0,0", "1,nan", "-o", tmp_path / "e.csv")
    assert code == 2 and "x,y,z" in err
    assert not (tmp_path / "e.csv").exists()            # an error leaves no empty file behind
    code, _, err = tool(capsys, "extract", uda, "--var", "temp_CC", "--line", "2", "3")
    assert code == 2 and "misses the domain" in err
    code, _, err = tool(capsys, "info", uda, "-t", 99)
    assert code == 2 and "-t 99" in err


def test_plot_writes_png_or_says_matplotlib_is_missing(uda, capsys, tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    out = tmp_path / "f.png"
    code, _, err = tool(capsys, "plot", uda, "--var", "temp_CC", "-o", out)
    assert code == 0, err
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    code, _, err = tool(capsys, "plot", uda, "--var", "temp_CC", "p.x", "-o", out)  # particles by |p.x|
    assert code == 0, err
    code, _, err = tool(capsys, "plot", uda, "--var", "TotalHeat", "-o", out)      # a sum against time
    assert code == 0, err
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    code, _, err = tool(capsys, "plot", uda, "--var", "TotalHeat", "temp_CC", "-o", out)
    assert code == 2 and "apart from the fields" in err
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    code, _, err = tool(capsys, "plot", uda, "--var", "temp_CC", "-o", out)
    assert code == 2 and "needs matplotlib" in err


def test_dataarchive_metadata_and_repr(uda):
    da = DataArchive(uda)
    assert da.label_info("temp_CC") == {"centring": "CC", "materials": [0], "shape": (), "units": "K"}
    assert da.label_info("p.x")["centring"] == "Particle" and da.label_info("p.x")["units"] == "m"
    text = repr(da)
    assert uda in text and "temp_CC" in text and f"{len(da.times)} timesteps" in text
    table = da.particles_table(0, 0)
    assert set(table) == {"p.x[0]", "p.x[1]", "p.x[2]", "p.mass"} and all(v.ndim == 1 for v in table.values())
    pd = pytest.importorskip("pandas")
    assert len(pd.DataFrame(table)) == len(da.particles(0, 0)["p.x"])
