"""Space-filling-curve assignment: contiguous, balanced by cost, every rank gets a patch."""
import numpy as np
import pytest

from framework.grid import Level
from framework.loadbalancer import LoadBalancer, assign, sfc_order


def test_balanced_by_cells_and_contiguous_along_curve():
    lv = Level((0, 0, 0), (1, 1, 1), (32, 32, 1), patches=(4, 4, 1))
    ranks = assign(lv.patches, 3)
    along = [ranks[p.id] for p in sfc_order(lv.patches)]
    assert along == sorted(along) and set(along) == {0, 1, 2}
    counts = np.bincount(ranks)
    assert counts.max() - counts.min() <= 1


def test_costs_move_patches():
    lv = Level((0, 0, 0), (1, 1, 1), (32, 32, 1), patches=(4, 4, 1))
    costs = [1.0] * 16
    heavy = sfc_order(lv.patches)[0].id
    costs[heavy] = 100.0
    ranks = assign(lv.patches, 2, costs)
    assert sum(1 for r in ranks if r == ranks[heavy]) == 1
    lb = LoadBalancer(lv, 2, 0)
    assert lb.rebalance(costs) and lb.version == 1 and not lb.rebalance(costs)


def test_more_ranks_than_patches_is_refused():
    lv = Level((0, 0, 0), (1, 1, 1), (8, 8, 1), patches=(1, 1, 1))
    with pytest.raises(ValueError, match="every rank needs a patch"):
        assign(lv.patches, 2)
