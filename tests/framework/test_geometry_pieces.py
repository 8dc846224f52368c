"""Uintah's analytic geometry pieces (framework/geometry.py): parallelepiped, ellipsoid, cone,
torus, polyhedron, smoothcyl and null; nested combinations; MPM particle counts against
Uintah's sus; an ICE material that starts absent (its object outside the domain)."""
import numpy as np
import pytest

from components.mpm.materials import Material, SmoothCylinder
from framework.geometry import GeometryReader
from framework.grid import Level
from framework.problemspec import InputError, ProblemSpec

RNG = np.random.default_rng(7)
X = RNG.uniform(-0.2, 1.2, (40000, 3))


def _piece(xml):
    return GeometryReader().read(ProblemSpec.from_string(xml))


def test_parallelepiped_inside():
    p1, a, b, c = np.array([0.1, 0.1, 0.1]), np.array([0.5, 0.1, 0]), np.array([0.1, 0.6, 0.05]), np.array([0.2, 0.15, 0.7])
    got = _piece("<parallelepiped><p1>[0.1,0.1,0.1]</p1><p2>[0.6,0.2,0.1]</p2><p3>[0.2,0.7,0.15]</p3>"
                 "<p4>[0.3,0.25,0.8]</p4></parallelepiped>").inside(X)
    r = np.linalg.solve(np.stack([a, b, c], axis=1), (X - p1).T).T
    assert np.array_equal(got, np.all((r > 0) & (r <= 1), axis=1)) and got.sum() > 1000


def test_ellipsoid_inside():
    got = _piece("<ellipsoid><origin>[0.5,0.45,0.5]</origin><v1>[0.3,0.1,0]</v1><v2>[-0.05,0.15,0]</v2>"
                 "<v3>[0,0,0.2]</v3></ellipsoid>").inside(X)
    d = X - [0.5, 0.45, 0.5]
    u = np.array([[0.3, 0.1, 0], [-0.05, 0.15, 0], [0, 0, 0.2]])
    q = sum((d @ v) ** 2 / (v @ v) ** 2 for v in u)         # sum (d . e_k / r_k)^2
    keep = np.abs(q - 1) > 1e-9
    assert np.array_equal(got[keep], (q < 1)[keep]) and got.sum() > 500
    box = _piece("<ellipsoid><origin>[0.5,0.5,0.5]</origin><rx>0.3</rx><ry>0.2</ry><rz>0.4</rz></ellipsoid>")
    q = (((X - 0.5) / [0.3, 0.2, 0.4]) ** 2).sum(axis=1)
    assert np.array_equal(box.inside(X)[np.abs(q - 1) > 1e-9], (q < 1)[np.abs(q - 1) > 1e-9])


def test_cone_inside():
    b, t = np.array([0.2, 0.3, 0.1]), np.array([0.7, 0.8, 0.9])
    got = _piece("<cone><bottom>[0.2,0.3,0.1]</bottom><top>[0.7,0.8,0.9]</top><bottom_radius>0.25"
                 "</bottom_radius><top_radius>0.05</top_radius></cone>").inside(X)
    e = (t - b) / np.linalg.norm(t - b)
    s = (X - b) @ e
    dist = np.linalg.norm(X - b - s[:, None] * e, axis=1)
    frac = s / np.linalg.norm(t - b)
    want = (frac >= 0) & (frac <= 1) & (dist <= 0.25 + (0.05 - 0.25) * frac)
    assert np.array_equal(got, want) and got.sum() > 500


def test_torus_inside():
    """Axis y, theta: the point turned by -theta in the y-z plane, then (R - rho)^2 + y^2 < r^2."""
    th = 0.3
    got = _piece("<torus><center>[0.5,0.5,0.5]</center><major_radius>0.3</major_radius><minor_radius>0.12"
                 "</minor_radius><axis>y</axis><theta>0.3</theta></torus>").inside(X)
    d = X - 0.5
    y = d[:, 1] * np.cos(-th) - d[:, 2] * np.sin(-th)
    z = d[:, 1] * np.sin(-th) + d[:, 2] * np.cos(-th)
    want = (0.3 - np.hypot(d[:, 0], z)) ** 2 + y ** 2 < 0.12 ** 2
    assert np.array_equal(got, want) and got.sum() > 200


def test_polyhedron_inside():
    """Six half-spaces (relative and absolute) making the box [0.2,0.8] x [0.3,0.7] x [0.25,0.75]."""
    got = _piece("""<polyhedron><center>[0.5,0.5,0.5]</center><bounds>
      <half_space type="relative"><offset>[0.3,0,0]</offset></half_space>
      <half_space type="relative"><offset>[-0.3,0,0]</offset></half_space>
      <half_space type="absolute"><planePoint>[0,0.3,0]</planePoint><normal>[0,2,0]</normal></half_space>
      <half_space type="absolute"><planePoint>[0,0.7,0]</planePoint><normal>[0,-1,0]</normal></half_space>
      <half_space type="relative"><offset>[0,0,0.25]</offset></half_space>
      <half_space type="relative"><offset>[0,0,-0.25]</offset></half_space></bounds></polyhedron>""")
    lo, hi = np.array([0.2, 0.3, 0.25]), np.array([0.8, 0.7, 0.75])
    assert np.allclose(got.bounds()[0], lo) and np.allclose(got.bounds()[1], hi)
    away = np.all(np.minimum(np.abs(X - lo), np.abs(X - hi)) > 1e-5, axis=1)
    assert np.array_equal(got.inside(X)[away], np.all((X > lo) & (X < hi), axis=1)[away])


def test_smoothcyl_inside_and_null():
    got = _piece("<smoothcyl><discretization_scheme>pie_slices</discretization_scheme><bottom>[0.5,0.5,0.1]"
                 "</bottom><top>[0.5,0.5,0.7]</top><outer_radius>0.4</outer_radius><inner_radius>0.2</inner_radius>"
                 "<num_radial>2</num_radial><num_axial>1</num_axial><num_angular>8</num_angular>"
                 "<endcap_thickness>0.1</endcap_thickness></smoothcyl>").inside(X)
    r = np.hypot(X[:, 0] - 0.5, X[:, 1] - 0.5)
    want = (X[:, 2] >= 0.0) & (X[:, 2] <= 0.8) & (r <= 0.4) & (r > 0.2)
    assert np.array_equal(got, want)
    assert _piece("<null/>").inside(X).all()


def test_combiner_children_and_errors():
    nested = _piece("""<difference><difference><box><min>[0,0,0]</min><max>[1,1,1]</max></box>
        <sphere><origin>[0,0,0]</origin><radius>0.5</radius></sphere></difference>
        <ellipsoid><origin>[1,1,1]</origin><rx>0.5</rx><ry>0.5</ry><rz>0.5</rz></ellipsoid></difference>""")
    pts = np.array([[0.1, 0.1, 0.1], [0.9, 0.9, 0.9], [0.5, 0.5, 0.5], [0.9, 0.1, 0.1]])
    assert nested.inside(pts).tolist() == [False, False, True, True]
    with pytest.raises(InputError, match="<res> is not a geometry piece"):
        _piece("<union><box><min>[0,0,0]</min><max>[1,1,1]</max></box><res>[2,2,2]</res></union>")
    with pytest.raises(InputError, match="orthogonal"):
        _piece("<ellipsoid><origin>[0,0,0]</origin><v1>[1,0,0]</v1><v2>[1,1,0]</v2><v3>[0,0,1]</v3></ellipsoid>")
    with pytest.raises(InputError, match="accepted: x, y, z"):
        _piece("<torus><center>[0,0,0]</center><major_radius>1</major_radius><minor_radius>0.1</minor_radius>"
               "<axis>w</axis></torus>")


# -- MPM particles against sus ---------------------------------------------------------------

def _particles(level, xml, density=1000.0, res=(2, 2, 2)):
    """pysus's particles of one MPM material with one geometry object, over every patch."""
    geo = GeometryReader(level)
    g = ProblemSpec.from_string(f"<geom_object>{xml}</geom_object>")
    m = object.__new__(Material)
    m.index, m.density = 0, density
    piece = geo.read_object(g)
    m.objects = [dict(res=res, velocity=(0, 0, 0), temperature=300.0, color=None, piece=piece, node=g,
                      smooth=isinstance(piece, SmoothCylinder))]
    parts = [m.create(p, 0) for p in level.patches]
    return {k: np.concatenate([p[k] for p in parts]) for k in ("x", "vol", "mass")}


# Each row: a piece on the level [0,1]^3 of 12 x 11 x 10 cells (2 x 2 x 1 patches, res [2,2,2]), and
# sus's particle count and sum of p.volume at t = 0 (sus with <outputInitTimestep/>, read with puda).
PIECES = [
    ("<ellipsoid><origin>[0.5,0.45,0.5]</origin><v1>[0.3,0.1,0]</v1><v2>[-0.05,0.15,0]</v2><v3>[0,0,0.2]</v3>"
     "</ellipsoid>", 456, 4.3181818183e-02),
    ("<ellipsoid><origin>[0.52,0.5,0.47]</origin><rx>0.33</rx><ry>0.21</ry><rz>0.27</rz></ellipsoid>",
     828, 7.8409090912e-02),
    ("<cone><bottom>[0.2,0.3,0.1]</bottom><top>[0.7,0.8,0.9]</top><bottom_radius>0.25</bottom_radius>"
     "<top_radius>0.05</top_radius></cone>", 912, 8.6363636366e-02),
    ("<torus><center>[0.5,0.5,0.5]</center><major_radius>0.3</major_radius><minor_radius>0.12</minor_radius>"
     "<axis>y</axis><theta>0.3</theta></torus>", 920, 8.7121212124e-02),
    ("""<polyhedron><center>[0.5,0.5,0.5]</center><bounds>
        <half_space type="relative"><offset>[0.3,0,0]</offset></half_space>
        <half_space type="relative"><offset>[-0.25,0.05,0]</offset></half_space>
        <half_space type="relative"><offset>[0,0.35,0.1]</offset></half_space>
        <half_space type="absolute"><planePoint>[0.5,0.2,0.5]</planePoint><normal>[0.1,1,0]</normal></half_space>
        <half_space type="relative"><offset>[0,0,0.3]</offset></half_space>
        <half_space type="absolute"><planePoint>[0.5,0.5,0.15]</planePoint><normal>[0,0.2,1]</normal></half_space>
        </bounds></polyhedron>""", 2609, 2.4706439395e-01),
    ("<parallelepiped><p1>[0.1,0.1,0.1]</p1><p2>[0.6,0.2,0.1]</p2><p3>[0.2,0.7,0.15]</p3><p4>[0.3,0.25,0.8]</p4>"
     "</parallelepiped>", 2120, 2.0075757576e-01),
    ("<null></null>", 0, 0.0),
    ("""<difference><difference><box><min>[0.1,0.1,0.1]</min><max>[0.9,0.9,0.9]</max></box>
        <cone><bottom>[0.5,0.5,0.0]</bottom><top>[0.5,0.5,1.0]</top><bottom_radius>0.3</bottom_radius>
        <top_radius>0</top_radius></cone></difference>
        <union><sphere><origin>[0.2,0.2,0.2]</origin><radius>0.2</radius></sphere>
        <intersection><torus><center>[0.5,0.5,0.5]</center><major_radius>0.35</major_radius><minor_radius>0.1
        </minor_radius><axis>z</axis></torus><parallelepiped><p1>[0,0,0]</p1><p2>[1,0,0]</p2><p3>[0,0.6,0]</p3>
        <p4>[0,0,1]</p4></parallelepiped></intersection></union></difference>""", 4393, 4.1600378789e-01),
    ("""<smoothcyl><discretization_scheme>pie_slices</discretization_scheme><bottom>[0.5,0.5,0.1]</bottom>
        <top>[0.6,0.55,0.8]</top><outer_radius>0.3</outer_radius><inner_radius>0.1</inner_radius>
        <num_radial>4</num_radial><num_axial>3</num_axial><num_angular>400</num_angular>
        <arc_start_angle>30</arc_start_angle><arc_angle>200</arc_angle></smoothcyl>""", 2079, 8.4130663369e-02),
    ("""<smoothcyl><discretization_scheme>constant_particle_volumes</discretization_scheme>
        <bottom>[0.4,0.5,0.5]</bottom><top>[0.6,0.5,0.5]</top><outer_radius>0.35</outer_radius>
        <inner_radius>0</inner_radius><num_radial>5</num_radial><num_axial>2</num_axial></smoothcyl>""",
     152, 7.6969020008e-02),
]


@pytest.mark.parametrize("xml, count, vol", PIECES)
def test_particle_counts_match_sus(xml, count, vol):
    lv = Level((0, 0, 0), (1, 1, 1), (12, 11, 10), (2, 2, 1), (1, 1, 1))
    p = _particles(lv, xml)
    assert len(p["x"]) == count
    assert abs(p["vol"].sum() - vol) <= 1e-8 * max(vol, 1e-30)          # sus's sum, printed to 8 digits
    assert np.allclose(p["mass"], 1000.0 * p["vol"])


def test_uintah_deck_pieces_match_sus():
    """The pieces of disks_complex.ups (smoothcyl, constant_particle_volumes), PressSmoothCylCBDI.ups
    (smoothcyl, a 90-degree arc of pie slices) and Charpy.ups (the striker: nested <difference>s
    with <parallelepiped>s), on their decks' grids; counts and sums from sus at t = 0."""
    disks = _particles(Level((0, 0, 0.05), (1, 1, 0.1), (40, 40, 1), (3, 2, 1), (0, 0, 1), (1, 1, 0)), """
        <smoothcyl><discretization_scheme>constant_particle_volumes</discretization_scheme>
        <bottom>[.25,.25,.05]</bottom><top>[.25,.25,.1]</top><outer_radius>.2</outer_radius>
        <inner_radius>0</inner_radius><num_radial>20</num_radial><num_axial>1</num_axial>
        <num_angular>60</num_angular><arc_start_angle>0</arc_start_angle><arc_angle>360</arc_angle></smoothcyl>""",
                       res=(2, 2, 1))
    assert len(disks["x"]) == 1246
    assert abs(disks["vol"].sum() - 6.2831853085e-03) < 1e-8 * 6.3e-3
    assert np.allclose(disks["x"].sum(axis=0), [311.5, 311.5, 93.45], rtol=0, atol=1e-6)
    press = _particles(Level((0, 0, -0.005), (0.6, 0.6, 0.01), (120, 120, 3), (8, 8, 1), (1, 1, 1)), """
        <smoothcyl><discretization_scheme>pie_slices</discretization_scheme><bottom>[0,0,0]</bottom>
        <top>[0,0,0.005]</top><outer_radius>0.55</outer_radius><inner_radius>0.45</inner_radius>
        <num_radial>20</num_radial><num_axial>1</num_axial><num_angular>157</num_angular>
        <arc_start_angle>0</arc_start_angle><arc_angle>90</arc_angle></smoothcyl>""", density=8e6, res=(1, 1, 1))
    assert len(press["x"]) == 3140
    assert abs(press["vol"].sum() - 3.9269908228e-04) < 1e-8 * 3.9e-4
    assert np.allclose(press["x"].sum(axis=0), [999.49721142, 999.49721142, 7.85], rtol=0, atol=1e-6)
    striker = _particles(Level((-3, -2.75, -0.5), (3, 2.75, 0.5), (40, 20, 1), (4, 2, 1), (1, 1, 1)), """
        <difference><difference><box><min>[-0.5, 0.375, -0.5]</min><max>[ 0.5, 2.59, 0.5]</max></box>
        <parallelepiped><p1>[ 0.2, 0.375, 0.5]</p1><p2>[ 0.2, 0.375, -0.5]</p2><p3>[ 0.5, 0.375, 0.5]</p3>
        <p4>[ 0.5, 0.99, 0.5]</p4></parallelepiped></difference>
        <parallelepiped><p1>[ -0.2, 0.375, 0.5]</p1><p2>[ -0.2, 0.375, -0.5]</p2><p3>[ -0.5, 0.375, 0.5]</p3>
        <p4>[ -0.5, 0.99, 0.5]</p4></parallelepiped></difference>""", density=13425.26, res=(2, 2, 1))
    assert len(striker["x"]) == 204
    assert abs(striker["vol"].sum() - 2.10375) < 1e-12
    assert abs(striker["x"][:, 1].sum() - 326.425) < 1e-9


def test_smoothcyl_placement_rules():
    """A smoothcyl object lays its own particles only alone in its material, with linear
    interpolation; and its particles must lie in the domain (as Uintah)."""
    lv = Level((0, 0, 0), (1, 1, 1), (10, 10, 10))
    with pytest.raises(InputError, match="outside the domain"):
        _particles(lv, "<smoothcyl><discretization_scheme>constant_particle_volumes</discretization_scheme>"
                       "<bottom>[0.5,0.5,0.1]</bottom><top>[0.5,0.5,0.9]</top><outer_radius>0.7</outer_radius>"
                       "<num_radial>2</num_radial><num_axial>1</num_axial></smoothcyl>")


# -- an ICE material outside the domain: Uintah's "starts with no mass" ------------------------

ICE_DECK = """<?xml version="1.0"?>
<Uintah_specification>
  <Meta><title>absent material</title></Meta>
  <SimulationComponent type="ice"/>
  <Time><maxTime>1.0</maxTime><initTime>0.0</initTime><delt_min>0.0</delt_min><delt_max>1.0</delt_max>
    <delt_init>1.0e-9</delt_init><max_Timesteps>1</max_Timesteps></Time>
  <Grid>
    <BoundaryConditions>
      <Face side="x-"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
      <Face side="x+"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
    </BoundaryConditions>
    <Level><Box label="1"><lower>[0,0,0]</lower><upper>[1,0.05,0.05]</upper><extraCells>[1,0,0]</extraCells>
      <patches>[1,1,1]</patches><resolution>[20,1,1]</resolution></Box></Level>
  </Grid>
  <DataArchiver><filebase>{uda}</filebase><outputTimestepInterval>1</outputTimestepInterval>
    <save label="rho_CC"/><save label="temp_CC"/><save label="sp_vol_CC"/></DataArchiver>
  <CFD><cfl>0.3</cfl><ICE><advection type="SecondOrder"/></ICE></CFD>
  <PhysicalConstants><gravity>[0,0,0]</gravity><reference_pressure>101325.0</reference_pressure></PhysicalConstants>
  <MaterialProperties>
    <ICE>
      {materials}
    </ICE>
    {exchange}
  </MaterialProperties>
</Uintah_specification>
"""
PRODUCT = """<material name="product"><EOS type="ideal_gas"/><dynamic_viscosity>0</dynamic_viscosity>
        <thermal_conductivity>0</thermal_conductivity><specific_heat>1000</specific_heat><gamma>1.4</gamma>
        <geom_object><box><min>[99,99,99]</min><max>[100,100,100]</max></box><res>[2,2,2]</res>
          <velocity>[0,0,0]</velocity><temperature>470.588235294</temperature><density>2.0</density>
          <pressure>1e5</pressure></geom_object></material>"""
AIR = """<material name="air"><EOS type="ideal_gas"/><dynamic_viscosity>0</dynamic_viscosity>
        <thermal_conductivity>0</thermal_conductivity><specific_heat>717.5</specific_heat><gamma>1.4</gamma>
        <geom_object><box><min>[-1,-1,-1]</min><max>[2,1,1]</max></box><res>[2,2,2]</res>
          <velocity>[0,0,0]</velocity><temperature>6.96864111498</temperature><density>50</density>
          <pressure>1e5</pressure></geom_object></material>"""
EXCHANGE = ("<exchange_properties><exchange_coefficients><momentum>[1e15]</momentum><heat>[0]</heat>"
            "</exchange_coefficients></exchange_properties>")


def test_ice_material_outside_starts_absent(tmp_path):
    """Product (its box at [99,100]^3) beside air: it starts as Uintah's cells no object covers,
    volume fraction 0 plus the trace rho_CC = tiny_rho rho_micro, its object's temperature; pysus
    takes that trace's rho_micro at the air's pressure (1e5 Pa / (0.4 * 1000 * 470.588) = 0.53125).
    Sus on JWLppCuRS2d.ups gives the same trace form for its absent product: vol_frac 1e-12 and
    rho_CC 1e-12 times its <density> (there the deck density is the EOS density at that state)."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    deck = tmp_path / "absent.ups"
    deck.write_text(ICE_DECK.format(uda=tmp_path / "absent.uda", materials=PRODUCT + AIR, exchange=EXCHANGE))
    c = Controller(str(deck), quiet=True, filebase=str(tmp_path / "absent.uda"))
    c.run()
    a = DataArchive(c.archiver.dir)
    rho, temp = a.read("rho_CC", 0, 0)[0], a.read("temp_CC", 0, 0)[0]
    assert np.allclose(rho, 1e-12 * 0.53125, rtol=1e-9) and np.allclose(temp, 470.588235294)
    assert np.allclose(a.read("rho_CC", 1, 0)[0], 50.0)


def test_outside_object_refused_where_likely_a_mistake(tmp_path):
    """The only material with its object outside, and an MPM object outside: refused."""
    from framework.controller import Controller
    deck = tmp_path / "alone.ups"
    deck.write_text(ICE_DECK.format(uda=tmp_path / "alone.uda", materials=PRODUCT, exchange=""))
    with pytest.raises(InputError, match="wholly outside the domain.*only where other materials"):
        Controller(str(deck), quiet=True, filebase=str(tmp_path / "alone.uda"))
    lv = Level((0, 0, 0), (1, 1, 1), (4, 4, 4))
    with pytest.raises(InputError, match="wholly outside"):
        GeometryReader(lv).read_object(ProblemSpec.from_string(
            "<geom_object><box><min>[99,99,99]</min><max>[100,100,100]</max></box></geom_object>"))


def test_outside_object_beside_one_inside_accepted(tmp_path, capfd):
    """A material with one object outside the domain and another inside: Uintah's own MPMICE
    decks (DDT.ups, BurnRate.ups, InductionTime.ups: the product's "outOfDomain" box) use it,
    and sus runs them; the outside object puts nothing anywhere, a note says so, and the
    material's cells hold the inside object's values."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    air_object = AIR[AIR.index("<geom_object>"):AIR.index("</material>")]
    two = PRODUCT.replace("</material>", air_object + "</material>")
    deck = tmp_path / "two.ups"
    deck.write_text(ICE_DECK.format(uda=tmp_path / "two.uda", materials=two, exchange=""))
    c = Controller(str(deck), quiet=True, filebase=str(tmp_path / "two.uda"))
    assert "wholly outside the domain and puts no material anywhere" in capfd.readouterr().err
    c.run()
    a = DataArchive(c.archiver.dir)
    assert np.allclose(a.read("rho_CC", 0, 0)[0], 50.0 * (1 + 1e-12), rtol=1e-9)
    assert np.allclose(a.read("temp_CC", 0, 0)[0], 6.96864111498)
