"""A one-line progress display for long runs: step, time, delT, wall time, time per step.

It redraws at most a few times a second and only on a terminal, so batch logs stay
clean; `--quiet` turns it off everywhere.
"""
from __future__ import annotations

import sys
import time


class Progress:
    def __init__(self, enabled=True, stream=None, interval=0.25):
        self.stream = stream or sys.stdout
        self.enabled = enabled and hasattr(self.stream, "isatty") and self.stream.isatty()
        self.interval = interval
        self._last = 0.0
        self._shown = False

    def line(self, step, t, delt, wall, step_wall):
        return (f"step {step:7d}  t = {t:.6e}  delT = {delt:.3e}  wall {wall:8.2f} s  "
                f"{1e3 * step_wall:8.2f} ms/step")

    def update(self, step, t, delt, wall, step_wall):
        if not self.enabled:
            return
        now = time.monotonic()
        if now - self._last < self.interval:
            return
        self._last = now
        self.stream.write("\r" + self.line(step, t, delt, wall, step_wall))
        self.stream.flush()
        self._shown = True

    def close(self):
        if self._shown:
            self.stream.write("\n")
            self.stream.flush()
