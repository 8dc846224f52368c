"""The example component against its exact solutions, and the framework through it."""
import numpy as np
import pytest

from components.examples import gaussian
from framework.archiver import DataArchive
from tests.conftest import pysus_ranks, run_deck
from tests.framework import decks


def heat_error(uda, alpha=0.01):
    da = DataArchive(uda)
    T, (x, y, z) = da.read("temp_CC", 0, -1)
    g = dict(center=(0.5, 0.5, 0.5), width=0.08, amplitude=1.0, background=0.0)
    dims = tuple(n > 1 for n in da.ncells)
    ex = gaussian(x[:, None, None], y[None, :, None], z[None, None, :], g, alpha, da.times[-1], dims)
    return np.abs(T - ex).mean()


def test_heat_converges_to_exact_gaussian_at_second_order(tmp_path):
    # exact solution: spreading Gaussian (components.examples.gaussian); the scheme is
    # second order in space, and with delT ~ dx^2 the error should drop about 4x per refinement
    errs = []
    for n in (16, 32, 64):
        ctl = run_deck(decks.heat(n=n, maxTime=0.1), tmp_path, name=f"h{n}")
        errs.append(heat_error(ctl.archiver.dir))
    order = np.log2(errs[0] / errs[1]), np.log2(errs[1] / errs[2])
    assert errs[2] < 1e-4
    assert min(order) > 1.7, (errs, order)


def test_heat_3d_against_exact(tmp_path):
    ctl = run_deck(decks.heat(n=16, nz=16, maxTime=0.05, patches="[2,2,2]"), tmp_path)
    assert heat_error(ctl.archiver.dir) < 2e-3


def test_particles_follow_rotation_exactly_and_are_conserved(tmp_path):
    text = decks.heat(n=20, patches="[2,2,1]", maxTime=0.25, diffusion=False, particles=True,
                      extra_save='<save label="p.x"/><save label="p.particleID"/><save label="p.mass"/>'
                                 '<save label="g.mass"/><save label="TotalMass"/>')
    ctl = run_deck(text, tmp_path)
    da = DataArchive(ctl.archiver.dir)
    p0, p1 = da.particles(0, 0), da.particles(0, -1)
    assert len(p1["p.x"]) == len(p0["p.x"]) > 0
    assert len(np.unique(p1["p.particleID"])) == len(p1["p.particleID"])
    x0 = p0["p.x"][np.argsort(p0["p.particleID"])]
    x1 = p1["p.x"][np.argsort(p1["p.particleID"])]
    th = 2 * np.pi * da.times[-1]
    r = x0[:, :2] - 0.5
    exact = np.stack([0.5 + np.cos(th) * r[:, 0] - np.sin(th) * r[:, 1],
                      0.5 + np.sin(th) * r[:, 0] + np.cos(th) * r[:, 1]], 1)
    assert np.abs(x1[:, :2] - exact).max() < 1e-3
    # the blob rotated a quarter turn: most particles changed patch
    lv = ctl.level
    moved = lv.patch_ids_of_cells(lv.cells_of(x0)) != lv.patch_ids_of_cells(lv.cells_of(x1))
    assert moved.mean() > 0.5
    gm, _ = da.read("g.mass", 0, -1)
    assert gm.sum() == pytest.approx(p1["p.mass"].sum(), rel=1e-12)


@pytest.mark.parametrize("periodic", ["", "<periodic>[1,1,0]</periodic>"])
def test_one_patch_equals_eight_patches_bitwise(tmp_path, periodic):
    kw = dict(n=24, maxTime=0.1, particles=True, periodic=periodic, velocity="[2,1,0]", omega=0.0,
              extra_save='<save label="p.x"/><save label="p.particleID"/><save label="g.mass"/>')
    a = run_deck(decks.heat(patches="[1,1,1]", **kw), tmp_path, name="one")
    b = run_deck(decks.heat(patches="[4,2,1]", **kw), tmp_path, name="eight")
    da, db = DataArchive(a.archiver.dir), DataArchive(b.archiver.dir)
    for lab in ("temp_CC", "g.mass"):
        assert np.array_equal(da.read(lab, 0, -1)[0], db.read(lab, 0, -1)[0]), lab
    pa, pb = da.particles(0, -1), db.particles(0, -1)
    oa, ob = np.argsort(pa["p.particleID"]), np.argsort(pb["p.particleID"])
    assert np.array_equal(pa["p.x"][oa], pb["p.x"][ob])
    if periodic:
        assert len(pa["p.x"]) == len(da.particles(0, 0)["p.x"])
    else:
        assert b.sched.particles_removed == a.sched.particles_removed


def test_restart_equals_uninterrupted(tmp_path):
    text = decks.heat(n=24, patches="[2,2,1]", maxTime=0.12, particles=True, out=5,
                      extra_save='<save label="p.x"/><save label="p.particleID"/>',
                      checkpoint='<checkpoint timestepInterval="7" cycle="2"/>')
    full = run_deck(text, tmp_path, name="full")
    from framework.controller import Controller
    uda = full.archiver.dir
    cps = DataArchive(uda).index["checkpoints"]
    assert len(cps) == 2, "cycle=2 keeps the newest two checkpoints"
    again = Controller(restart=uda, restart_index=0, quiet=True, filebase=str(tmp_path / "again.uda"))
    again.run()
    da, db = DataArchive(uda), DataArchive(again.archiver.dir)
    assert da.times[-1] == db.times[-1]
    assert np.array_equal(da.read("temp_CC", 0, -1)[0], db.read("temp_CC", 0, -1)[0])
    pa, pb = da.particles(0, -1), db.particles(0, -1)
    assert np.array_equal(pa["p.x"][np.argsort(pa["p.particleID"])], pb["p.x"][np.argsort(pb["p.particleID"])])


def test_only_the_physics_asked_for_is_scheduled(tmp_path):
    heat_only = run_deck(decks.heat(n=8, maxTime=0.01), tmp_path, name="a")
    names = [t.name for t in heat_only.step_graph.tasks]
    assert "diffuseHeat" in names and not any("article" in n for n in names)
    parts_only = run_deck(decks.heat(n=8, maxTime=0.01, diffusion=False, particles=True,
                                     extra_save='<save label="p.x"/>'), tmp_path, name="b")
    names = [t.name for t in parts_only.step_graph.tasks]
    assert "diffuseHeat" not in names and "advectParticles" in names and "relocateParticles" in names
    # nobody saves g.mass/TotalMass/TotalHeat: their tasks are pruned
    assert "interpolateParticlesToGrid" not in names and "sumGridMass" not in names
    assert "sumHeat" in [t.name for t in heat_only.step_graph.pruned]


def test_graph_cli_lists_tasks_in_order(tmp_path, deckfile):
    path = deckfile(decks.heat(n=8, particles=True, extra_save='<save label="g.mass"/>'))
    dot = tmp_path / "g.dot"
    r = pysus_ranks("--graph", path, "--dot", dot)
    assert r.returncode == 0, r.stderr
    out = r.stdout
    assert out.index("advectParticles") < out.index("relocateParticles")
    assert "p.x(old m0 +1AroundNodes)" in out and "computes: g.mass(new m0)" in out
    assert "digraph" in dot.read_text()


def test_output_opens_as_xdmf_and_hdf5(tmp_path):
    from lxml import etree
    import h5py
    ctl = run_deck(decks.heat(n=8, patches="[2,1,1]", maxTime=0.01, out=2, particles=True,
                              extra_save='<save label="p.x"/><save label="p.mass"/>'), tmp_path)
    uda = ctl.archiver.dir
    text = open(f"{uda}/output.xdmf").read()
    assert "np." not in text
    doc = etree.parse(f"{uda}/output.xdmf")
    types = {a.get("Name"): a.get("AttributeType") for a in doc.iter("Attribute")}
    assert types["temp_CC_0"] == "Scalar" and types["p.mass_0"] == "Scalar"      # <label>_<material>
    items = doc.findall(".//DataItem[@Format='HDF']")
    assert items
    for it in items:
        fn, path = it.text.split(":")
        with h5py.File(f"{uda}/{fn}", "r") as h5:
            size = h5[path].size
        dims = [int(x) for x in it.get("Dimensions").split()]
        assert size == np.prod(dims), (it.text, size, dims)


def test_progress_display_quiet_off_terminal(tmp_path, deckfile):
    r = pysus_ranks(deckfile(decks.heat(n=8, maxTime=0.01)))
    assert r.returncode == 0 and "\r" not in r.stdout
