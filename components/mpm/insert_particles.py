"""Uintah's InsertParticles: particles of one colour, made at the start where the deck's
<geom_object>s put them, are moved into the domain and given a new velocity at a time of a
table (`<InsertParticlesFile>`, one line per insertion: t colour dx dy dz vx vy vz), as
SerialMPM::insertParticles does after the particles' update and before their relocation:
in the step whose interval (t_n, t_n + dt] holds t (the first step also takes t = t_0)."""
from __future__ import annotations

import numpy as np

from framework import labels as FL
from framework.task import NEW, OLD, Task

from . import labels as L
from .prescribed import find_file


def read(node, deck):
    """(times, colours, translations (n, 3), velocities (n, 3)) of the file named by `node`."""
    name = node.text().strip()
    path = find_file(name, deck)
    if path is None:
        raise node.error(f"particle insertion file '{name}' not found (looked in the working directory, under "
                         "the deck's folder and its parents, and beside the deck)")
    try:
        vals = np.array(open(path).read().split(), float)
    except ValueError:
        raise node.error(f"{path}: not a table of numbers (8 a line: t, colour, translation, velocity)") from None
    rows = vals[:len(vals) // 8 * 8].reshape(-1, 8)
    return rows[:, 0].copy(), rows[:, 1].copy(), rows[:, 2:5].copy(), rows[:, 5:8].copy()


def schedule(component, sched):
    """MPM::insertParticles on p.x+ and p.velocity+ before the relocation."""
    sched.add_task(Task("MPM::insertParticles", component.insert_particles, component.matls)
                   .requires(OLD, FL.simTime).requires(OLD, FL.delT).requires(OLD, L.pColor)
                   .modifies(L.pXpre).modifies(L.pVelocityPre))


def insert(table, time, dt, color, x, v):
    """Move the particles of each colour whose time falls in (time, time + dt] (time itself
    included) by their translation and give them their velocity."""
    times, colours, shift, vel = table
    for i in np.flatnonzero((time + dt > times) & (time <= times)):
        sel = color == colours[i]
        x[sel] += shift[i]
        v[sel] = vel[i]
