"""Count the numba specialisations a deck compiles and the time each costs.

    python scripts/numba_signatures.py DECK.ups [--max-timesteps N] [--top K]

Run it with an empty NUMBA_CACHE_DIR to see the compile work of a first run: every kernel
compiled (not loaded from the cache) is listed with its number of signatures and seconds.
"""
from __future__ import annotations

import argparse
import collections
import os
import sys
import tempfile
import time

from numba.core import event


class CompileLog(event.Listener):
    """Records each numba compile (name, argument types, inclusive seconds)."""

    def __init__(self):
        self.started = {}
        self.done = []
        self.depth = 0

    def on_start(self, ev):
        self.depth += 1
        self.started[id(ev.data["dispatcher"]), tuple(ev.data["args"])] = time.perf_counter()

    def on_end(self, ev):
        d = ev.data["dispatcher"]
        key = id(d), tuple(ev.data["args"])
        self.depth -= 1
        py = d.py_func
        self.done.append((f"{py.__module__}.{py.__qualname__}", tuple(str(a) for a in ev.data["args"]),
                          time.perf_counter() - self.started.pop(key), self.depth == 0))


def main(argv=None):
    p = argparse.ArgumentParser()
    p.add_argument("deck")
    p.add_argument("--max-timesteps", type=int, default=2)
    p.add_argument("--top", type=int, default=40)
    p.add_argument("--all", action="store_true", help="list every signature")
    a = p.parse_args(argv)
    log = CompileLog()
    event.register("numba:compile", log)
    from framework.controller import Controller
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        ctl = Controller(a.deck, quiet=True, filebase=os.path.join(tmp, "s.uda"), max_timesteps=a.max_timesteps)
        ctl.run()
    wall = time.perf_counter() - t0
    per = collections.defaultdict(list)
    for name, args, sec, top in log.done:
        per[name].append((args, sec, top))
    top_sec = sum(s for _, _, s, t in log.done if t)
    print(f"{a.deck}: {len(log.done)} compiles of {len(per)} functions; top-level compile {top_sec:.1f} s of {wall:.1f} s")
    rows = sorted(per.items(), key=lambda kv: -sum(s for _, s, t in kv[1] if t) - 1e-3 * len(kv[1]))
    for name, sigs in rows[:a.top]:
        print(f"  {len(sigs):3d} sig  {sum(s for _, s, t in sigs if t):7.2f} s  {name}")
        if a.all or len(sigs) > 1:
            for args, sec, top in sigs:
                print(f"        {sec:6.2f}{'' if top else '(n)'}  ({', '.join(args)})"[:300])
    return 0


if __name__ == "__main__":
    sys.exit(main())
