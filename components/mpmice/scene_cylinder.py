"""Pressurized cylinder (paper 000 sec. 4.1): deck at a chosen resolution and the errors
against Lame's solution (eq. 42) and the paper's error measure (eq. 43).

    deck(n, ri=, ro=, t_end=, dz=, ...)  inputs/MPMICE/pressurized_cylinder.ups with n cells
             across the 1.2 m domain (dx = 1.2 / n; the paper's 0.025 m is n = 48), the
             annulus's inner and outer radius (0.5 and 1.0 m), the end time (the deck's 5 ms)
             and the one z cell's thickness (0.025 m; "dx": as thin as dx, so that it no longer
             sets ICE's step: the same plane-strain problem, z faces symmetric); the steel's
             particles per cell per direction (ppc, the deck's <res> 2), its
             <numLevelsParticleFilling> (fill), <DoPressureStabilization> (stab: the deck's
             true, each cell's particles take the cell's mean J), <interpolator>, the artificial
             damping coefficient, geom="smooth": the steel laid in rings (a <smoothcyl>; MPM takes
             it with the linear interpolator only) rather than on the cell lattice, cut: the
             steel's <cut_cell_particles> (the deck's true: its surface sub-cells' particles hold
             the part inside; false: the lattice's whole sub-cells), and heat: the steel's heat
             exchange coefficient with the airs (the deck's 0, as Uintah's symAnnulus), and trace:
             ICE's <delT_traceVolFrac> (none: the trace airs inside the steel count in ICE's step)
    errors(da, ri=, ro=)  (a pysus DataArchive or a sus UintahArchive) at the last output:
             P = mean gauge pressure of the inner air (cells with r < 0.8 ri); over all
             particles, eq. 43
                 mean | |s_r + s_t| - 2 a | / (2 a)      a = P ri^2 / (ro^2 - ri^2)
             and the L1 errors of s_r and s_t against eq. 42, relative to P; eq43_inner: eq. 43
             over the particles more than dx inside the steel, eq43_surf over the others (the
             surface layers); level: mean(|s_r + s_t|) / (2 a) - 1.
Used by scripts/accuracy_cost.py (scene "cylinder") and tests/mpmice/test_cylinder.py.
"""
from __future__ import annotations

import os

import numpy as np

from framework.uintah_uda import particle_var

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "pressurized_cylinder.ups")
RI, RO, L, P_REF = 0.5, 1.0, 1.2, 101325.0


def deck(n, damping=None, patches="1,1,1", t_end=None, ri=RI, ro=RO, dz=None, interpolator=None, ppc=None,
         fill=None, stab=None, geom=None, cut=None, heat=None, trace=None):
    text = open(DECK, encoding="iso-8859-1").read()
    dx = L / int(n)
    ri, ro = float(ri), float(ro)
    if not 0.0 < ri < ro < L - dx:
        raise ValueError(f"radii {ri}, {ro}: need 0 < ri < ro < {L} - dx (air outside the annulus)")
    dz = 0.025 if dz is None else dx if dz == "dx" else float(dz)
    reps = [("<spacing> [0.025,0.025,0.025] </spacing>", f"<spacing> [{dx!r},{dx!r},{dz!r}] </spacing>"),
            ("<upper> [1.2,1.2,0.025] </upper>", f"<upper> [1.2,1.2,{dz!r}] </upper>"),
            ("<patches> [2,2,1] </patches>", f"<patches> [{patches}] </patches>"),
            ("<radius> 1.0 </radius>", f"<radius> {ro!r} </radius>"),
            ("<radius> 0.5 </radius>", f"<radius> {ri!r} </radius>")]
    if heat is not None:         # the steel's heat exchange coefficient with each air (the airs' own stays)
        reps.append(("<heat> [0.0, 0.0, 1e10] </heat>", f"<heat> [{float(heat)!r}, {float(heat)!r}, 1e10] </heat>"))
    if damping is not None:
        reps.append(("<artificial_damping_coeff> 4000.0 </artificial_damping_coeff>",
                     f"<artificial_damping_coeff> {float(damping)!r} </artificial_damping_coeff>"))
    if t_end is not None:
        reps += [("<maxTime> 5.0e-3 </maxTime>", f"<maxTime> {float(t_end)!r} </maxTime>"),
                 ("<outputInterval> 5.0e-3 </outputInterval>", f"<outputInterval> {float(t_end)!r} </outputInterval>")]
    if interpolator is not None:
        reps.append(("<interpolator>gimp</interpolator>", f"<interpolator>{interpolator}</interpolator>"))
    if trace is not None:
        reps.append(("<advection type=\"SecondOrder\"/>", "<advection type=\"SecondOrder\"/>\n      "
                     f"<delT_traceVolFrac> {float(trace)!r} </delT_traceVolFrac>"))
    if stab is not None:
        reps.append(("<DoPressureStabilization> true </DoPressureStabilization>",
                     f"<DoPressureStabilization> {_bool(stab, 'stab')} </DoPressureStabilization>"))
    for old, new in reps:
        assert old in text, old
        text = text.replace(old, new)
    a = text.index('<material name="steel">')
    b = text.index("</material>", a)
    steel = text[a:b]
    if ppc is not None:
        steel = steel.replace("<res> [2,2,1] </res>", f"<res> [{int(ppc)},{int(ppc)},1] </res>")
    if fill is not None:
        steel = steel.replace("</geom_object>", f"  <numLevelsParticleFilling> {int(fill)} "
                                                "</numLevelsParticleFilling>\n        </geom_object>")
    if cut is not None:
        steel = steel.replace("<cut_cell_particles> true </cut_cell_particles>",
                              f"<cut_cell_particles> {_bool(cut, 'cut')} </cut_cell_particles>")
    text = text[:a] + steel + text[b:]
    if geom not in (None, "lattice", "smooth"):
        raise ValueError(f"geom {geom!r}: lattice (the deck's) or smooth")
    if geom == "smooth":
        text = _smooth_steel(text, dx / (2 if ppc is None else int(ppc)), ri, ro, dz)
    return text


def _bool(value, name):
    """An option's true/false as the deck writes it (True, "true", "True", False, ...)."""
    word = str(value).strip().lower()
    if word not in ("true", "false"):
        raise ValueError(f"{name}={value!r}: true or false")
    return word


def _smooth_steel(text, dr, ri, ro, dz):
    """The steel laid in rings of width dr (a <smoothcyl>, constant particle volumes) instead of
    on the cell lattice: the annulus's surfaces are circles, not staircases."""
    a = text.index("<difference>", text.index('<material name="steel">'))
    b = text.index("</difference>", a) + len("</difference>")
    nr = max(1, round((ro - ri) / dr))
    text = text[:a] + (f"<smoothcyl><discretization_scheme>constant_particle_volumes</discretization_scheme>"
                       f"<bottom>[0,0,0]</bottom><top>[0,0,{dz!r}]</top><outer_radius>{ro!r}</outer_radius>"
                       f"<inner_radius>{ri!r}</inner_radius><num_radial>{nr}</num_radial><num_axial>1</num_axial>"
                       f"<arc_start_angle>0</arc_start_angle><arc_angle>90</arc_angle></smoothcyl>") + text[b:]
    text = text.replace("<cut_cell_particles> true </cut_cell_particles>", "")     # rings: no lattice to cut
    for label, r in (("outer cylinder", ro), ("inner cylinder", ri)):
        text = text.replace(f'<cylinder label="{label}"/>',
                            f'<cylinder label="{label}"><bottom>[0,0,-1]</bottom><top>[0,0,1]</top>'
                            f'<radius>{r!r}</radius></cylinder>', 1)
    return text


def stresses(da, i=-1, ri=RI):
    """(r, s_r, s_t, P) at output i: particle radius, radial and hoop stress, inner gauge pressure."""
    x, s = particle_var(da, "p.x", 0, i), particle_var(da, "p.stress", 0, i)
    r = np.hypot(x[:, 0], x[:, 1])
    n = np.stack([x[:, 0] / r, x[:, 1] / r], axis=1)
    t = np.stack([-n[:, 1], n[:, 0]], axis=1)
    s_r = np.einsum("pi,pij,pj->p", n, s[:, :2, :2], n)
    s_t = np.einsum("pi,pij,pj->p", t, s[:, :2, :2], t)
    p, _ = da.read("press_CC", 0, i)
    nx, ny = p.shape[:2]
    dx, dy = L / nx, L / ny
    xc = (np.arange(nx) + 0.5) * dx
    yc = (np.arange(ny) + 0.5) * dy
    rc = np.hypot(xc[:, None], yc[None, :])
    P = float(p[..., 0][rc < 0.8 * ri].mean()) - P_REF
    return r, s_r, s_t, P


def lame(r, P, ri=RI, ro=RO):
    a = P * ri ** 2 / (ro ** 2 - ri ** 2)
    return a * (1 - ro ** 2 / r ** 2), a * (1 + ro ** 2 / r ** 2)


def errors(da, ri=RI, ro=RO):
    r, s_r, s_t, P = stresses(da, ri=ri)
    er, et = lame(r, P, ri, ro)
    two_a = 2.0 * P * ri ** 2 / (ro ** 2 - ri ** 2)      # s_r + s_t, the same at every radius
    dev = np.abs(s_r + s_t) - two_a
    dx = L / da.read("press_CC", 0, -1)[0].shape[0]
    inner = (r > ri + dx) & (r < ro - dx)                # the particles more than dx inside the steel
    return {"eq43": float(np.mean(np.abs(dev)) / two_a),
            "radial": float(np.mean(np.abs(s_r - er)) / P),
            "hoop": float(np.mean(np.abs(s_t - et)) / P),
            "P_MPa": P / 1e6,
            "eq43_inner": float(np.mean(np.abs(dev[inner])) / two_a),
            "eq43_surf": float(np.mean(np.abs(dev[~inner])) / two_a),
            "level": float(np.mean(dev) / two_a)}


def history(da, ri=RI, ro=RO):
    """[(t, P in MPa, level, load)] at every output: level as in errors(); load the hoop force the
    steel carries, the integral of s_t over the wall (the particles' s_t V / r over the quarter's
    angle and depth), over Lame's P ri: 1 when the steel carries the inner pressure."""
    out = []
    area = 0.25 * np.pi * (ro ** 2 - ri ** 2)
    for i, t in enumerate(da.times):
        r, s_r, s_t, P = stresses(da, i, ri=ri)
        if P <= 0.0:
            continue
        volume = particle_var(da, "p.volume", 0, i)
        depth = float(volume.sum()) / area
        hoop_force = float(np.sum(s_t * volume / r)) / (0.5 * np.pi * depth)
        level = float(np.mean(np.abs(s_r + s_t))) / (2.0 * P * ri ** 2 / (ro ** 2 - ri ** 2)) - 1.0
        out.append((float(t), P / 1e6, level, abs(hoop_force) / (P * ri)))
    return out
