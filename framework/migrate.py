"""Move the data of re-assigned patches between ranks after a load re-balance."""
from __future__ import annotations


def migrate(dw, level, old_map, new_map, comm):
    """Send every variable of patches whose rank changed to their new rank."""
    me = comm.rank
    outgoing = {}
    for p in level.patches:
        src, dst = old_map[p.id], new_map[p.id]
        if src == dst or src != me:
            continue
        pack = {"grid": {}, "particles": {}, "np": {}}
        for store, name in ((dw.grid, "grid"), (dw.particles, "particles"), (dw.perpatch, "perpatch")):
            for key in [k for k in store if k[2] == p.id]:
                pack.setdefault(name, {})[key] = store.pop(key)
        for key in [k for k in dw.nparticles if k[1] == p.id]:
            pack["np"][key] = dw.nparticles.pop(key)
        outgoing.setdefault(dst, []).append(pack)
    sources = {old_map[p.id] for p in level.patches if new_map[p.id] == me and old_map[p.id] != me}
    got = comm.exchange_objects(outgoing, sources)
    for r in sorted(got):
        for pack in got[r]:
            dw.grid.update(pack.get("grid", {}))
            dw.particles.update(pack.get("particles", {}))
            dw.perpatch.update(pack.get("perpatch", {}))
            dw.nparticles.update(pack["np"])
    dw.halo_valid.clear()
    dw.ghost_particles.clear()
    dw.ghost_order.clear()
    dw.ghost_select.clear()
    dw.ghost_seen.clear()
    dw.ghost_candidates.clear()
