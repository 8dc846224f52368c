"""Inflow and outflow faces: water entering a full box through x- at 0.2 m/s and leaving
through x+ (p = 0) between slip walls is uniform plug flow at once (the exact solution of
the incompressible equations): u = 0.2 m/s everywhere, the box stays full. Drawn out
through x- instead, the water enters through the outflow face: the same plug flow
backwards, and the box stays full (the outflow face brings its element's fluid in)."""
import numpy as np

from framework.archiver import DataArchive
from tests.conftest import run_deck

from .decks import deck

FACES = '''<BoundaryConditions>
      <Face side="x-" type="inflow" material="water"> <velocity> [0.2, 0, 0] </velocity> </Face>
      <Face side="x+" type="outflow"/> <Face side="y-" type="slip"/> <Face side="y+" type="slip"/>
    </BoundaryConditions>'''


def _deck(**kw):
    return deck(res=(12, 12), steps=30, pool=1.0, gravity=0.0, saves=("vol_frac_CC", "g.velocity", "press_CC"),
                **kw).replace("<BoundaryConditions>  </BoundaryConditions>", FACES)


def test_plug_flow_through_inflow_and_outflow(tmp_path):
    ctl = run_deck(_deck(), tmp_path)
    a = DataArchive(ctl.archiver.dir)
    v, _ = a.read("g.velocity", 0, -1)
    np.testing.assert_allclose(v[..., 0], 0.2, atol=1e-9)
    np.testing.assert_allclose(v[..., 1], 0.0, atol=1e-9)
    f, _ = a.read("vol_frac_CC", 0, -1)
    np.testing.assert_allclose(f, 1.0, atol=1e-12)


def test_backflow_through_the_outflow_face_keeps_the_box_full(tmp_path):
    ctl = run_deck(_deck().replace("[0.2, 0, 0]", "[-0.2, 0, 0]"), tmp_path)
    a = DataArchive(ctl.archiver.dir)
    v, _ = a.read("g.velocity", 0, -1)
    np.testing.assert_allclose(v[..., 0], -0.2, atol=1e-9)
    np.testing.assert_allclose(v[..., 1], 0.0, atol=1e-9)
    f, _ = a.read("vol_frac_CC", 0, -1)
    np.testing.assert_allclose(f, 1.0, atol=1e-12)


def test_inflow_of_a_solid_is_refused(tmp_path):
    import pytest
    from framework.problemspec import InputError
    from .test_conservation import BLOCK
    text = _deck(block=BLOCK).replace('material="water"', 'material="block"')
    with pytest.raises(InputError, match="run.ups:.*solid"):
        run_deck(text, tmp_path)
