"""A body falling through void (no fluid) keeps its velocity uniform and carries no stress:
exact for the scheme, since gravity moves every node with mass alike and the remap moves a
uniform velocity unchanged. It failed while the remap's element velocity counted nodes
without mass (held at rest): the elements at a body's front and back took its speed halved,
and the velocity change there pushed its edge nodes (the paper's ring, falling alone at
50 x 33, picked up 0.11 m/s sideways and 100 Pa of stress in 0.1 s)."""
import numpy as np

from framework.archiver import DataArchive
from tests.conftest import run_deck

from .decks import deck

# faces off the mesh lines, so the body's edge elements are cut; moving along x and y
BLOCK = dict(lo=(0.41, 0.56), hi=(0.61, 0.76), density=500.0, E=1e5, nu=0.3, velocity=(0.3, -0.5))


def test_body_in_free_fall_moves_rigidly(tmp_path):
    ctl = run_deck(deck(res=(20, 20), steps=40, pool=0.0, block=BLOCK), tmp_path)
    da = DataArchive(ctl.archiver.dir)
    t = da.times[-1]
    v, _ = da.read("g.velocity", 0, -1)
    moving = np.abs(v[..., 0, :2]).max(axis=-1) > 0.0
    assert moving.sum() > 30                    # the body's nodes (the void's are at rest)
    np.testing.assert_allclose(v[..., 0, 0][moving], 0.3, rtol=0, atol=1e-12)
    np.testing.assert_allclose(v[..., 0, 1][moving], -0.5 - 9.81 * t, rtol=0, atol=1e-12)
    s, _ = da.read("stress_CC", 0, -1)
    assert np.abs(s).max() < 1e-8, np.abs(s).max()
