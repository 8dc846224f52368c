"""components/mpm/materials.cut_cells (the geom_object's <cut_cell_particles>): the particles of
the sub-cells an object's surface cuts hold the part inside, so that the particles hold the
object's volume; checked against the exact area and volume of the pieces."""
import types

import numpy as np

from components.mpm.materials import CUT_SAMPLES, cut_cells, fill_levels, lattice_positions
from framework.geometry import Cylinder, Difference, Sphere


def _patch(ncells, dx, collapsed):
    level = types.SimpleNamespace(anchor=np.zeros(3), dx=np.asarray(dx, float), ncells=tuple(ncells),
                                  collapsed=tuple(collapsed))
    return types.SimpleNamespace(level=level, lo=np.zeros(3, np.int64), hi=np.asarray(ncells, np.int64))


def test_quarter_annulus_area():
    """The pressurized cylinder's steel (ri = 0.6, ro = 1.0, a quarter) at dx = 0.1, two particles
    per cell per direction: the fractions' area is the exact pi (ro^2 - ri^2) / 4 to 0.1 % (the
    8 x 8 sampling of the cut sub-cells), the lattice centres' is 1 % off."""
    ring = Difference(Cylinder([0, 0, -1], [0, 0, 1], 1.0), Cylinder([0, 0, -1], [0, 0, 1], 0.6))
    patch = _patch((12, 12, 1), (0.1, 0.1, 0.1), (False, False, True))
    res = np.array([2, 2, 1])
    exact = np.pi * (1.0 - 0.36) / 4
    h2 = 0.05 * 0.05
    sub, x, fraction = cut_cells(ring, patch, res)
    ((_, sub0, x0),) = fill_levels(ring, patch, res, 0)
    assert abs(fraction.sum() * h2 / exact - 1.0) < 1e-3
    assert abs(len(x0) * h2 / exact - 1.0) > 5e-3
    # a whole sub-cell is the lattice's particle, bitwise; a cut one's centroid lies in its sub-cell
    whole = fraction == 1.0
    assert np.array_equal(x[whole], lattice_positions(patch.level.anchor, patch.level.dx, res, sub[whole]))
    lo = sub * 0.05
    assert np.all((x[:, :2] >= lo[:, :2]) & (x[:, :2] <= lo[:, :2] + 0.05))
    assert np.all((fraction > 0.0) & (fraction <= 1.0)) and np.all(x[:, 2] == 0.05)
    assert set(map(tuple, sub0)) <= set(map(tuple, sub))     # every lattice particle is still there
    # the first moment: the particles' centroid is the quarter annulus's, 4 (ro^3 - ri^3) / (3 pi (ro^2 - ri^2))
    c = (fraction[:, None] * x[:, :2]).sum(axis=0) / fraction.sum()
    assert np.allclose(c, 4 * (1.0 - 0.216) / (3 * np.pi * 0.64), rtol=2e-3)


def test_sphere_volume_and_centroid_3d():
    """A sphere of radius 0.33 at (0.5, 0.45, 0.52) on 10^3 cells, one particle per cell: the
    fractions' volume is 4/3 pi r^3 to 0.3 % (8^3 samples in each cut cell) and their centroid is
    the sphere's centre to 1e-3 dx."""
    ball = Sphere([0.5, 0.45, 0.52], 0.33)
    patch = _patch((10, 10, 10), (0.1, 0.1, 0.1), (False, False, False))
    sub, x, fraction = cut_cells(ball, patch, np.array([1, 1, 1]))
    assert abs(fraction.sum() * 1e-3 / (4 / 3 * np.pi * 0.33 ** 3) - 1.0) < 3e-3
    c = (fraction[:, None] * x).sum(axis=0) / fraction.sum()
    assert np.allclose(c, [0.5, 0.45, 0.52], atol=1e-4)
    assert CUT_SAMPLES == 8


def test_ring_of_revolution_pappus():
    """Axisymmetric particles hold r_centroid * area per radian (materials.Material.create): for a
    disk of radius 0.23 at r = 0.5, z = 0.4 in the (r, z) plane, the cut-cell particles' sum of
    fraction * dr dz * r is Pappus's pi R^2 r0 to 0.3 % (measured 0.22 %, as their area), the
    lattice centres' 2.3 % off."""
    disk = Cylinder([0.5, 0.4, -1], [0.5, 0.4, 1], 0.23)
    patch = _patch((10, 10, 1), (0.1, 0.1, 0.1), (False, False, True))
    res = np.array([2, 2, 1])
    exact = np.pi * 0.23 ** 2 * 0.5
    sub, x, fraction = cut_cells(disk, patch, res)
    ((_, _, x0),) = fill_levels(disk, patch, res, 0)
    assert abs((fraction * x[:, 0]).sum() * 0.05 * 0.05 / exact - 1.0) < 3e-3
    assert abs(x0[:, 0].sum() * 0.05 * 0.05 / exact - 1.0) > 1e-2
