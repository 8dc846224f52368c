"""Patch -> rank assignment along a space-filling curve, weighted by measured cost.

Patches are ordered along a Morton (Z-order) curve of their layout indices, so that
consecutive patches are neighbours in space, and the curve is cut into one piece per
rank with nearly equal cost (cells plus weighted particles). `<LoadBalancer>` in the
deck sets the re-balancing interval; the executor recompiles its communication plan
only when the assignment actually changes.
"""
from __future__ import annotations

import numpy as np

PARTICLE_WEIGHT = 2.0


def morton_key(idx) -> int:
    key = 0
    for bit in range(21):
        for d in range(3):
            key |= ((idx[d] >> bit) & 1) << (3 * bit + d)
    return key


def sfc_order(patches):
    return sorted(patches, key=lambda p: (morton_key(p.index), p.id))


def assign(patches, nranks: int, costs=None) -> list[int]:
    """rank of each patch id: contiguous pieces of the curve with balanced cost."""
    if nranks > len(patches):
        raise ValueError(f"{nranks} ranks but only {len(patches)} patches: every rank needs a patch; "
                         "raise <patches> in the deck's <Box>")
    order = sfc_order(patches)
    cost = np.array([float(costs[p.id]) if costs is not None else float(p.ncells) for p in order])
    cost = np.maximum(cost, 1e-12)
    mid = np.cumsum(cost) - 0.5 * cost
    piece = np.minimum((mid / cost.sum() * nranks).astype(int), nranks - 1)
    if len(set(piece.tolist())) < nranks:
        piece = np.arange(len(order)) * nranks // len(order)
    ranks = [0] * len(patches)
    for p, r in zip(order, piece):
        ranks[p.id] = int(r)
    return ranks


class LoadBalancer:
    """Holds the current assignment and decides when to re-balance."""

    def __init__(self, level, nranks: int, rank: int, interval: int = 0):
        self.level = level
        self.nranks = nranks
        self.rank = rank
        self.interval = interval
        self.rank_of = assign(level.patches, nranks)
        self.version = 0

    def local_patches(self):
        """This rank's patches, in level order (kept until the assignment changes: the
        scheduler asks for them at every task)."""
        kept = getattr(self, "_local", None)
        if kept is None or kept[0] != self.version or kept[1] is not self.rank_of or kept[2] is not self.level.patches:
            kept = self._local = (self.version, self.rank_of, self.level.patches,
                                  [p for p in self.level.patches if self.rank_of[p.id] == self.rank])
        return kept[3]

    def due(self, timestep: int) -> bool:
        return self.interval > 0 and timestep > 0 and timestep % self.interval == 0

    def rebalance(self, costs) -> bool:
        """New assignment from measured costs; True when it changed."""
        new = assign(self.level.patches, self.nranks, costs)
        if new == self.rank_of:
            return False
        self.rank_of = new
        self.version += 1
        return True
