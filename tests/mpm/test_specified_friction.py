"""contact type specified_friction (Uintah's SpecifiedBodyFrictionContact), kernels.specified_friction.

At one node with an alpha material: the master (rigid) keeps its velocity; a material moving
into it (relative to the master's velocity, along n = -normAlphaToBeta) loses its normal part
and, of its tangential part, up to mu times the normal part (all of it when mu is large: it
sticks); one moving away, one standing out past alpha's prominence, or any at a node where
the excluded material has mass, is left alone; the master takes nothing back (momentum is
not kept, unlike friction_LR). The deck-level check against sus is tests/mpm/test_gurson.py.
"""
import numpy as np
import pytest

from components.mpm import kernels


def exchange(v_beta, mu, prom_beta=-1.0, exclude_mass=0.0, v_master=(0.0, 0.0, 0.0), use_own=True):
    """One node, materials (master 0, beta 1, excluded 2); alpha = master, normAlphaToBeta = +y
    (the master lies below: beta moves into it when its v_y is below the master's)."""
    m = np.array([[2.0], [1.0], [exclude_mass]])
    v = np.array([[v_master], [v_beta], [(0.0, 0.0, 0.0)]], float)
    a = np.zeros_like(v)
    vo = v.copy()
    kernels.specified_friction(m, v, np.array([True, True, True]), np.array([0]), np.array([[0.0, 1.0, 0.0]]),
                               np.array([[0.0], [prom_beta], [0.0]]), 0, np.array([0.0, -5.0, 0.0]), use_own,
                               2, mu, a, vo, 1e-3)
    return v[0, 0], v[1, 0], a[1, 0]


def test_normal_part_removed_and_coulomb_friction():
    master, beta, acc = exchange((3.0, -4.0, 0.0), mu=0.0)
    assert np.array_equal(master, [0.0, 0.0, 0.0])           # the master gets nothing back
    assert beta == pytest.approx([3.0, 0.0, 0.0], abs=1e-15)     # frictionless: tangential kept
    assert acc == pytest.approx([0.0, 4.0e3, 0.0])               # a = (v - v_old)/dt where it acts
    _, beta, _ = exchange((3.0, -4.0, 0.0), mu=0.5)           # |dv_t| 3 > mu |dv_n| 2: slides
    assert beta == pytest.approx([1.0, 0.0, 0.0], abs=1e-15)
    _, beta, _ = exchange((3.0, -4.0, 0.0), mu=1.0)           # 3 < 4: sticks to the master
    assert beta == pytest.approx([0.0, 0.0, 0.0], abs=1e-15)


def test_relative_to_the_prescribed_velocity():
    """With a prescribed velocity (-5 in y, not the master's own) the master takes it and the
    other material's normal velocity becomes the master's."""
    master, beta, _ = exchange((0.0, -6.0, 0.0), mu=0.0, use_own=False)
    assert np.array_equal(master, [0.0, -5.0, 0.0])
    assert beta == pytest.approx([0.0, -5.0, 0.0])
    _, beta, _ = exchange((0.0, -4.0, 0.0), mu=0.0, use_own=False)     # separating from it: free
    assert np.array_equal(beta, [0.0, -4.0, 0.0])


@pytest.mark.parametrize("kw", [dict(v_beta=(1.0, 2.0, 0.0)), dict(v_beta=(1.0, -2.0, 0.0), prom_beta=1.0),
                                dict(v_beta=(1.0, -2.0, 0.0), exclude_mass=1.0)])
def test_left_alone(kw):
    """Moving away, standing out past alpha (no touch), or the excluded material present."""
    v_beta = kw.pop("v_beta")
    _, beta, acc = exchange(v_beta, mu=0.3, **kw)
    assert np.array_equal(beta, v_beta) and not acc.any()
