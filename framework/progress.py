"""A one-line progress display for long runs: step, simulated time of maxTime, percentage,
wall time per step and the estimated time to the end.

The time per step is measured wall time between redraws (tasks, output, exchanges and all), not a
sum of task times. The ETA extrapolates the rate since the end of the first step, whose wall time
(numba compiling the kernels on a first run: a minute or more) says nothing about the rest. It redraws at most a few times a second and only on a terminal, so batch logs
stay clean; `--quiet` turns it off everywhere. Under mpiexec rank 0 writes into a pipe, not the
terminal: `pysus --np N` (or PYSUS_PROGRESS=1) keeps the line on, PYSUS_PROGRESS=0 turns it off.
"""
from __future__ import annotations

import math
import os
import sys
import time


def clock(seconds: float) -> str:
    """Seconds as h:mm:ss (or m:ss under an hour)."""
    s = int(round(seconds))
    h, s = divmod(s, 3600)
    m, s = divmod(s, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


class Progress:
    def __init__(self, enabled=True, stream=None, interval=0.25, max_time=math.inf,
                 max_timesteps=2**62, start_step=0, start_time=0.0, start_wall=0.0):
        self.stream = stream or sys.stdout
        wanted = os.environ.get("PYSUS_PROGRESS", "")
        tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.enabled = enabled and (wanted == "1" or (wanted != "0" and tty))
        self.interval = interval
        self.max_time = max_time
        self.max_timesteps = max_timesteps
        self.start_step, self.start_time = start_step, start_time
        self._last = 0.0
        self._last_step, self._last_wall = start_step, start_wall
        self.start_wall = start_wall
        self._step_wall = 0.0
        self._shown = False
        self._latest = None
        self._ref = None        # (wall, fraction) at the end of the first step: where the ETA's rate starts

    def begin(self, start_step, start_time, start_wall):
        """Where the stepping starts (after set-up, or at a restart's checkpoint)."""
        self.start_step, self.start_time, self.start_wall = start_step, start_time, start_wall
        self._last_step, self._last_wall = start_step, start_wall

    def note(self, text):
        """A line shown until the first redraw replaces it (only on a terminal)."""
        if self.enabled:
            self.stream.write("\r" + text + "\033[K")
            self.stream.flush()
            self._shown = True

    def fraction(self, step, t) -> float:
        """How far the run is, by simulated time or by step count, whichever ends it first."""
        f = 0.0
        if math.isfinite(self.max_time) and self.max_time > self.start_time:
            f = (t - self.start_time) / (self.max_time - self.start_time)
        if self.max_timesteps < 2**62 and self.max_timesteps > self.start_step:
            f = max(f, (step - self.start_step) / (self.max_timesteps - self.start_step))
        return min(max(f, 0.0), 1.0)

    def line(self, step, t, delt, wall, step_wall):
        f = self.fraction(step, t)
        w0, f0 = self._ref or (self.start_wall, 0.0)
        eta = clock(0.0) if f >= 1.0 else clock((wall - w0) * (1.0 - f) / (f - f0)) if f > f0 else "?"
        end = f" of {self.max_time:.4g}" if math.isfinite(self.max_time) else ""
        return (f"step {step:7d}  t = {t:.6e}{end} s ({100.0 * f:5.1f}%)  delT = {delt:.3e}  "
                f"{1e3 * step_wall:8.2f} ms/step  wall {clock(wall)}  ETA {eta}")

    def update(self, step, t, delt, wall):
        """Redraw if due; wall is the run's wall time so far."""
        if not self.enabled:
            return
        self._latest = (step, t, delt, wall)
        if self._ref is None and step > self.start_step:
            self._ref = (wall, self.fraction(step, t))
        now = time.monotonic()
        if now - self._last < self.interval:
            return
        self._last = now
        if step > self._last_step:
            self._step_wall = (wall - self._last_wall) / (step - self._last_step)
            self._last_step, self._last_wall = step, wall
        self.stream.write("\r" + self.line(step, t, delt, wall, self._step_wall) + "\033[K")
        self.stream.flush()
        self._shown = True

    def close(self):
        """Draw the final state (the last redraw may be older) and end the line."""
        if self.enabled and self._latest is not None:
            self._last = -math.inf
            self.update(*self._latest)
        if self._shown:
            self.stream.write("\n")
            self.stream.flush()
