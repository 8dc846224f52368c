"""Contact between MPM materials (`<MaterialProperties><MPM><contact>`), Uintah's Contact/.

  null             each material moves on its own velocity field (no interaction)
  single_velocity  at nodes shared by the listed materials all take the centre-of-mass
                   velocity, after interpolation and again after integration: the
                   materials stick (one velocity field, as in paper 004)
Other Uintah types (friction, approach, specified, rigid) are refused by name.
With one material, or with null, no contact task is scheduled.
"""
from __future__ import annotations

import numpy as np

from framework.problemspec import Param

from . import kernels

CONTACT = {
    "type": Param("str", "null", ("null", "single_velocity")),
}


def _int_list(node):
    """Uintah's <materials>[0,1]</materials>: any number of material indices."""
    t = node.text()
    try:
        if not (t.startswith("[") and t.endswith("]")):
            raise ValueError
        return tuple(int(x) for x in t[1:-1].replace(",", " ").split())
    except ValueError:
        raise node.error(f"value '{t}' is not a list of material indices like [0,1]") from None


class Contact:
    def __init__(self, mpm_node, nmat):
        nodes = mpm_node.children("contact")
        if len(nodes) > 1:
            raise nodes[1].error("only one <contact> block is supported")
        spec = nodes[0].read(CONTACT) if nodes else {"type": "null"}
        self.type = spec["type"]
        mnode = nodes[0].child("materials") if nodes else None
        mats = _int_list(mnode) if mnode is not None else tuple(range(nmat))
        for m in mats:
            if not 0 <= m < nmat:
                raise mnode.error(f"material {m} does not exist; there are {nmat} MPM materials")
        self.materials = tuple(dict.fromkeys(mats))
        self.active = self.type != "null" and len(self.materials) > 1

    def exchange(self, gmass, gvel, gacc, gvel_old, dt):
        """Apply to lists (one per material) of node arrays; modifies gvel (and gacc)."""
        idx = list(self.materials)
        m = np.stack([gmass[i].reshape(-1) for i in idx])
        v = np.stack([gvel[i].reshape(-1, 3) for i in idx])
        if gacc is None:
            kernels.single_velocity(m, v, v, v, 0.0)
        else:
            a = np.stack([gacc[i].reshape(-1, 3) for i in idx])
            vo = np.stack([gvel_old[i].reshape(-1, 3) for i in idx])
            kernels.single_velocity(m, v, a, vo, dt)
            for k, i in enumerate(idx):
                gacc[i].reshape(-1, 3)[...] = a[k]
        for k, i in enumerate(idx):
            gvel[i].reshape(-1, 3)[...] = v[k]
