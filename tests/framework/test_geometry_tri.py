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


def _latlong_sphere(R, nlat, nlon):
    """A closed lat-long triangulation of a sphere of radius R (poles as single points)."""
    pts = [[0.0, 0.0, R]]
    for i in range(1, nlat):
        th = np.pi * i / nlat
        for j in range(nlon):
            ph = 2 * np.pi * j / nlon
            pts.append([R * np.sin(th) * np.cos(ph), R * np.sin(th) * np.sin(ph), R * np.cos(th)])
    pts.append([0.0, 0.0, -R])
    ring = lambda i, j: 1 + (i - 1) * nlon + j % nlon
    tri = [[0, ring(1, j), ring(1, j + 1)] for j in range(nlon)]
    for i in range(1, nlat - 1):
        for j in range(nlon):
            tri += [[ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)], [ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]]
    s = len(pts) - 1
    tri += [[s, ring(nlat - 1, j + 1), ring(nlat - 1, j)] for j in range(nlon)]
    return np.array(pts), np.array(tri)


def test_sphere_surface_many_triangles():
    """6320 triangles, 200000 points: exact away from the facets' chord error (binned rays)."""
    pts, tri = _latlong_sphere(1.0, 40, 80)
    surf = TriSurface(pts, tri)
    x = np.random.default_rng(2).uniform(-1.2, 1.2, (200000, 3))
    r = np.linalg.norm(x, axis=1)
    far = np.abs(r - 1.0) > 0.01          # chord error of the facets ~ 1 - cos(pi / 40) = 0.003
    got = surf.inside(x)
    assert np.array_equal(got[far], r[far] < 1.0)
    # the same answer as testing every triangle (one bin per ray), on the first 20000 points
    from framework.geometry_kernels import CROSS, RAYS, inside_surface
    y = x[:20000]
    one = tuple(np.array([0, len(tri)], np.int64) for _ in range(3))
    every = tuple(np.arange(len(tri), dtype=np.int64) for _ in range(3))
    out = np.empty(len(y), np.bool_)
    inside_surface(y, surf.v0, surf.e1, surf.e2, surf.lo, surf.hi, RAYS, CROSS, np.zeros((3, 2)),
                   np.full((3, 2), 10.0), np.ones((3, 2), np.int64), one, every, out)
    assert np.array_equal(out, got[:20000])
