"""A level whose <Box>es do not fill one box (framework/grid.py, gridspec.py): Uintah's
extrudeRT level (a 44 x 30 x 20 box with a 4 x 10 x 10 box on its y+ side) becomes the
box that holds both, cut along every box's edges and patch boundaries, with patches only
inside the boxes; a patch face on a hole is a boundary face. Expected values by counting
on the deck's geometry."""
import itertools
import json
import os
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

from framework.grid import Level, box_intersect
from framework.problemspec import InputError
from framework.variables import VarType
from tests.conftest import run_deck

from .test_level_boxes import _read, box

NC, CC = VarType.NC, VarType.CC
BIG = box((0.0, -0.5, -0.5), (2.2, 1.0, 0.5), (44, 30, 20), (3, 1, 1), label="1")
SMALL = box((0.0, 1.0, -0.25), (0.2, 1.5, 0.25), (4, 10, 10), (1, 1, 2), label="2")
BOXES = (((0, 0, 0), (44, 30, 20)), ((0, 30, 5), (4, 40, 15)))      # the two boxes in cells


@pytest.fixture
def level(tmp_path):
    return _read(tmp_path, BIG, SMALL)


def _in_boxes(c):
    return any(all(lo[d] <= c[d] < hi[d] for d in range(3)) for lo, hi in BOXES)


def test_extrude_rt_level_patches(level):
    """Cuts x {0,4,14,29,44}, y {0,30,40}, z {0,5,10,15,20}: 16 slots of the big box and 2 of
    the small one are patches, the other 14 holes; the patches hold exactly the boxes' cells."""
    assert level.ncells == (44, 40, 20) and level.layout == (4, 2, 4) and level.holes
    assert level.splits == [[0, 4, 14, 29, 44], [0, 30, 40], [0, 5, 10, 15, 20]]
    assert len(level.patches) == 18
    assert sum(p.ncells for p in level.patches) == 44 * 30 * 20 + 4 * 10 * 10
    for p in level.patches:
        assert _in_boxes(p.lo) and _in_boxes(tuple(h - 1 for h in p.hi))
    cells = np.array([(0, 31, 5), (0, 31, 4), (5, 30, 7), (43, 29, 19), (3, 39, 14), (3, 39, 15)])
    ids = level.patch_ids_of_cells(cells)
    assert ids[1] == -1 and ids[2] == -1 and ids[5] == -1                # in holes
    assert level.patches[ids[0]].lo == (0, 30, 5) and level.patches[ids[4]].lo == (0, 30, 10)
    assert level.patches[ids[3]].hi == (44, 30, 20)


def test_extrude_rt_level_faces_and_neighbours(level):
    """Boundary faces: the small box's patches on x-, x+ and y+ and their outer z face, not on
    y- (the big box below); the big box's patches on y+ except the two under the small box."""
    small = [p for p in level.patches if p.lo[1] == 30]
    assert [(p.lo, p.hi) for p in small] == [((0, 30, 5), (4, 40, 10)), ((0, 30, 10), (4, 40, 15))]
    assert small[0].boundary_faces == ["x-", "x+", "y+", "z-"]
    assert small[1].boundary_faces == ["x-", "x+", "y+", "z+"]
    under = [p for p in level.patches if p.hi[1] == 30 and p.lo[0] == 0 and 5 <= p.lo[2] < 15]
    assert len(under) == 2 and all("y+" not in p.boundary_faces for p in under)
    tops = [p for p in level.patches if p.hi[1] == 30 and p not in under]
    assert len(tops) == 14 and all("y+" in p.boundary_faces for p in tops)
    assert all("y-" in p.boundary_faces for p in level.patches if p.lo[1] == 0)
    for p in level.patches:                       # neighbours: patches only, touching p
        for q in level.neighbours(p):
            gap = [max(p.lo[d] - q.hi[d], q.lo[d] - p.hi[d]) for d in range(3)]
            assert max(gap) <= 0
    assert {q.id for q in level.neighbours(small[0])} >= {under[0].id, small[1].id}
    assert all(q.lo[1] < 30 or q.lo[2] >= 5 for q in level.neighbours(small[0]))


def test_every_node_has_an_owner_and_only_re_entrant_edges_two(level):
    """Each node of a cell of the boxes is inside exactly one patch (interior_box), except the
    15 on the L's re-entrant edges that two patches share (x = 0.2 and z = 0.25 at y = 1.0);
    no node or cell of a hole only is owned; every cell exactly once."""
    for vt in (CC, NC):
        count = np.zeros([n + 1 for n in level.ncells], int)
        for p in level.patches:
            lo, hi = p.interior_box(vt)
            count[tuple(slice(a, b) for a, b in zip(lo, hi))] += 1
        wanted = np.zeros_like(count, bool)
        for lo, hi in BOXES:
            wanted[tuple(slice(a, b + (vt is NC)) for a, b in zip(lo, hi))] = True
        assert np.all((count > 0) == wanted)
        twice = np.argwhere(count == 2)
        if vt is CC:
            assert len(twice) == 0
        else:
            assert len(twice) == 15 and np.all(twice[:, 1] == 30)
            assert all(c[0] == 4 or c[2] == 15 for c in twice)


@pytest.mark.parametrize("vt, g", [(NC, 1), (NC, 2), (CC, 1)])
def test_ghost_sources_are_disjoint_and_complete(level, vt, g):
    """Each patch's ghost entries come once each, never over its own, from a patch owning them;
    every window entry some other patch owns is filled."""
    for p in level.patches:
        want, own = p.window(vt, g), p.owned(vt)
        shape = [h - l for l, h in zip(*want)]
        got = np.zeros(shape, int)
        for q, shift, b in level.ghost_sources(p, vt, g):
            assert shift == (0, 0, 0) and box_intersect(b, own) is None
            assert box_intersect(b, q.owned(vt)) == b
            got[tuple(slice(b[0][d] - want[0][d], b[1][d] - want[0][d]) for d in range(3))] += 1
        assert got.max() <= 1
        owned_by_others = np.zeros(shape, bool)
        for q in level.patches:
            ov = box_intersect(want, q.owned(vt))
            if q is not p and ov is not None:
                owned_by_others[tuple(slice(ov[0][d] - want[0][d], ov[1][d] - want[0][d]) for d in range(3))] = True
        mine = box_intersect(want, own)
        owned_by_others[tuple(slice(mine[0][d] - want[0][d], mine[1][d] - want[0][d]) for d in range(3))] = False
        assert np.array_equal(got == 1, owned_by_others)


def test_rectangular_levels_are_as_before():
    """On a level without holes interior_box is the owned box within the level's interior (the
    earlier definition) and faces are boundary faces only on the level's sides."""
    for n, per, extra, layout in (((8, 6, 1), (0, 0, 0), (1, 1, 0), (2, 3, 1)),
                                  ((8, 6, 4), (1, 0, 0), (0, 1, 1), (2, 2, 2)),
                                  ((5, 7, 3), (0, 1, 1), (1, 0, 0), (3, 1, 1))):
        lv = Level((0, 0, 0), (1, 1, 1), n, layout, extra, per)
        assert not lv.holes
        for p, vt in itertools.product(lv.patches, (CC, NC, VarType.SFCX, VarType.SFCY, VarType.SFCZ)):
            assert p.interior_box(vt) == box_intersect(p.owned(vt), lv.interior_box(vt))
            assert p.at_low == tuple(p.lo[d] == 0 and not lv.periodic[d] and not lv.collapsed[d] for d in range(3))


def test_holes_refused_where_not_supported(tmp_path):
    """A periodic direction on such a level, and a component other than MPM: one line each."""
    from framework.gridspec import level_from_spec
    from framework.problemspec import ProblemSpec
    (tmp_path / "p.ups").write_text("<Uintah_specification><Grid><Level>" + BIG + SMALL +
                                    "<periodic>[0,0,1]</periodic></Level></Grid></Uintah_specification>")
    with pytest.raises(InputError) as e:
        level_from_spec(ProblemSpec.load(str(tmp_path / "p.ups")))
    assert "periodic" in str(e.value) and "\n" not in str(e.value)
    with pytest.raises(InputError) as e:
        run_deck(L_DECK.format(steps=1, every=1, bcs="", v=1).replace('type="mpm"', 'type="mpmice"'), tmp_path)
    assert 'component "mpmice" does not support' in str(e.value) and "\n" not in str(e.value)


L_DECK = """<?xml version="1.0"?>
<Uintah_specification>
  <Meta><title>L-shaped level</title></Meta>
  <SimulationComponent type="mpm"/>
  <Time><maxTime>1</maxTime><max_Timesteps>{steps}</max_Timesteps><delt_max>2e-4</delt_max>
    <timestep_multiplier>0.5</timestep_multiplier></Time>
  <Grid>
    <BoundaryConditions>{bcs}</BoundaryConditions>
    <Level>
      <Box label="a"><lower>[0,0,0]</lower><upper>[1,0.5,0.05]</upper><resolution>[20,10,1]</resolution>
        <extraCells>[1,1,0]</extraCells><patches>[2,1,1]</patches></Box>
      <Box label="b"><lower>[0,0.5,0]</lower><upper>[0.5,1,0.05]</upper><resolution>[10,10,1]</resolution>
        <extraCells>[1,1,0]</extraCells><patches>[1,1,1]</patches></Box>
    </Level>
  </Grid>
  <DataArchiver><filebase>l.uda</filebase><outputTimestepInterval>{every}</outputTimestepInterval>
    <save label="p.x"/><save label="p.velocity"/><save label="g.mass"/><save label="TotalMass"/></DataArchiver>
  <MPM><interpolator>linear</interpolator></MPM>
  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
  <MaterialProperties><MPM><material name="block"><density>1000</density>
    <constitutive_model type="comp_neo_hook"><bulk_modulus>1e6</bulk_modulus><shear_modulus>1e5</shear_modulus>
    </constitutive_model>
    <geom_object><box label="up"><min>[0.7,0.3,0]</min><max>[0.9,0.45,0.05]</max></box><res>[2,2,1]</res>
      <velocity>[0,{v},0]</velocity><temperature>300</temperature></geom_object>
  </material><contact><type>null</type></contact></MPM></MaterialProperties>
</Uintah_specification>
"""
WALL = '<Face side="y+"><BCType id="all" var="Dirichlet" label="Velocity"><value>[0,0,0]</value></BCType></Face>'


def test_mpm_block_meets_the_hole_face(tmp_path):
    """A block in box a, under the hole (x > 0.5), moving up at 20 m/s: the y+ face at y = 0.5
    there is a boundary face of the L. With a y+ wall (zero velocity) it stops below y = 0.5
    and keeps its particles; without conditions its particles leave into the hole and are
    deleted, as through any face without a wall."""
    ctl = run_deck(L_DECK.format(steps=60, every=60, bcs=WALL, v=20), tmp_path, "wall")
    from framework.archiver import DataArchive
    da = DataArchive(ctl.archiver.dir)
    p = da.particles(0, -1)
    assert len(p["p.x"]) == 48 and p["p.x"][:, 1].max() < 0.5
    ctl = run_deck(L_DECK.format(steps=60, every=60, bcs="", v=20), tmp_path, "open")
    da = DataArchive(ctl.archiver.dir)
    assert len(da.particles(0, -1)["p.x"]) < 48
    _, mass = da.reduction("TotalMass")
    assert mass[-1] < mass[0]


def test_output_of_an_l_shaped_level_opens(tmp_path):
    """The uda reads back (g.mass over the holding box, zero in the hole) and output.xdmf names
    one block per patch, each with HDF5 datasets of the sizes it declares, none in the hole."""
    ctl = run_deck(L_DECK.format(steps=2, every=1, bcs=WALL, v=1), tmp_path, "out")
    from framework.archiver import DataArchive
    da = DataArchive(ctl.archiver.dir)
    gm, _ = da.read("g.mass", 0, -1)
    assert gm.shape[:2] == (21, 21) and gm.sum() > 0 and np.all(gm[12:, 12:] == 0)
    root = ET.parse(os.path.join(ctl.archiver.dir, "output.xdmf")).getroot()
    steps = root.find("Domain/Grid").findall("Grid")
    assert len(steps) == 3
    names = [g.get("Name") for g in steps[-1].findall("Grid")]
    assert sorted(n for n in names if n.startswith("nodes")) == [f"nodes_patch{i}" for i in range(3)]
    for block in steps[-1].findall("Grid"):
        for item in block.iter("DataItem"):
            if item.get("Format") != "HDF":
                continue
            fn, path = item.text.strip().split(":")
            with h5py.File(os.path.join(ctl.archiver.dir, fn), "r") as f:
                dims = [int(x) for x in item.get("Dimensions").split()]
                assert int(np.prod(f[path].shape)) == int(np.prod(dims)), (fn, path)
        geo = block.find("Geometry/DataItem")
        if block.get("Name").startswith("nodes"):
            z, y, x = (float(v) for v in geo.text.split())
            assert not (x > 0.5 and y > 0.5)
    with open(os.path.join(ctl.archiver.dir, "index.json")) as f:
        assert json.load(f)["grid"]["ncells"] == [20, 20, 1]
