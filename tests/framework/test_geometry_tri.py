"""<tri> geometry piece (framework/geometry.py TriSurface): a closed triangulated surface read
from name.pts / name.tri (Uintah's TriGeometryPiece), inside by ray casting (numba)."""
import os

import numpy as np
import pytest

from framework.geometry import GeometryReader, TriSurface
from framework.problemspec import InputError, ProblemSpec

CUBE_PTS = np.array([[x, y, z] for x in (0.25, 0.75) for y in (0.25, 0.75) for z in (0.25, 0.75)])
# 12 triangles, two per face (points indexed x*4 + y*2 + z)
CUBE_TRI = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5],      # x = lo, hi
                     [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],      # y = lo, hi
                     [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])     # z = lo, hi
TET_PTS = np.array([[0.1, 0.1, 0.1], [0.9, 0.1, 0.1], [0.1, 0.9, 0.1], [0.1, 0.1, 0.9]])
TET_TRI = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def _write(base, pts, tri):
    np.savetxt(str(base) + ".pts", pts)
    np.savetxt(str(base) + ".tri", tri, fmt="%d")
    return str(base)


def test_cube_and_tetrahedron_inside(tmp_path):
    rng = np.random.default_rng(1)
    x = rng.random((20000, 3))
    cube = TriSurface.from_files(_write(tmp_path / "cube", CUBE_PTS, CUBE_TRI))
    exact = np.all((x >= 0.25) & (x <= 0.75), axis=1)
    assert np.array_equal(cube.inside(x), exact)
    tet = TriSurface.from_files(_write(tmp_path / "tet", TET_PTS, TET_TRI))
    y = x - 0.1
    exact = np.all(y >= 0, axis=1) & (y.sum(axis=1) <= 0.8)
    assert np.array_equal(tet.inside(x), exact)
    # points on a grid that passes through the cube's faces, edges and vertices
    g = np.stack(np.meshgrid(*[np.linspace(0, 1, 21)] * 3, indexing="ij"), -1).reshape(-1, 3)
    strict = np.all((g > 0.25 + 1e-9) & (g < 0.75 - 1e-9), axis=1)
    outside = np.any((g < 0.25 - 1e-9) | (g > 0.75 + 1e-9), axis=1)
    got = cube.inside(g)
    assert got[strict].all() and not got[outside].any()


def test_deck_tri_piece_fills_particles(tmp_path):
    """An MPM deck whose body is a <tri> cube: particles exactly where the cube is."""
    _write(tmp_path / "cube", CUBE_PTS, CUBE_TRI)
    deck = tmp_path / "tri.ups"
    deck.write_text(DECK.format(name="cube"))
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(str(deck), quiet=True, filebase=str(tmp_path / "tri.uda"))
    c.run()
    parts = DataArchive(c.archiver.dir).particles(0, 0)
    x = parts["p.x"]
    assert len(x) == 5 ** 3 * 8          # 5 x 5 x 5 cells of 0.1 m, 2 x 2 x 2 particles each
    assert np.all((x > 0.25) & (x < 0.75))
    assert abs(parts["p.mass"].sum() - 1000.0 * 0.5 ** 3) < 1e-9


def test_tri_errors(tmp_path):
    reader = GeometryReader()
    root = ProblemSpec.from_string("<g>\n<tri><name>%s</name></tri></g>" % (tmp_path / "none"))
    with pytest.raises(InputError, match="no files"):
        reader.read(root.child("tri"))
    _write(tmp_path / "bad", CUBE_PTS, CUBE_TRI + 8)
    root = ProblemSpec.from_string("<g><tri><name>%s</name></tri></g>" % (tmp_path / "bad"))
    with pytest.raises(InputError, match="indices"):
        reader.read(root.child("tri"))


def test_relative_name_next_to_deck(tmp_path, monkeypatch):
    _write(tmp_path / "tet", TET_PTS, TET_TRI)
    deck = tmp_path / "d.ups"
    deck.write_text("<g><tri><name>tet</name></tri></g>")
    monkeypatch.chdir(os.path.dirname(__file__))
    piece = GeometryReader().read(ProblemSpec.load(str(deck)).child("tri"))
    assert piece.inside(np.array([[0.2, 0.2, 0.2], [0.8, 0.8, 0.8]])).tolist() == [True, False]


DECK = """<?xml version="1.0"?>
<Uintah_specification>
  <Meta><title>tri cube</title></Meta>
  <SimulationComponent type="mpm"/>
  <Time>
    <maxTime>1.0</maxTime><initTime>0.0</initTime><delt_min>0.0</delt_min><delt_max>1e-5</delt_max>
    <timestep_multiplier>0.5</timestep_multiplier><max_Timesteps>1</max_Timesteps>
  </Time>
  <Grid>
    <Level>
      <Box label="1">
        <lower>[0,0,0]</lower><upper>[1,1,1]</upper><resolution>[10,10,10]</resolution>
        <extraCells>[0,0,0]</extraCells><patches>[2,1,1]</patches>
      </Box>
    </Level>
  </Grid>
  <DataArchiver>
    <filebase>tri.uda</filebase>
    <outputTimestepInterval>1</outputTimestepInterval>
    <save label="p.x"/><save label="p.mass"/>
  </DataArchiver>
  <MPM><time_integrator>explicit</time_integrator><interpolator>linear</interpolator></MPM>
  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
  <MaterialProperties>
    <MPM>
      <material name="cube">
        <density>1000.0</density>
        <constitutive_model type="comp_neo_hook">
          <bulk_modulus>1e6</bulk_modulus><shear_modulus>5e5</shear_modulus>
        </constitutive_model>
        <geom_object>
          <tri><name>{name}</name></tri>
          <res>[2,2,2]</res><velocity>[0,0,0]</velocity><temperature>300</temperature>
        </geom_object>
      </material>
    </MPM>
  </MaterialProperties>
</Uintah_specification>
"""
