"""MPM throughput: particle-steps per second per core, and the framework's overhead.

    .venv/bin/python scripts/bench/mpm.py [--steps 10] [--repeat 1] [--json out.json] [--quick]
                                          [--cases "2D linear"] [--cpu] [--no-reference]
                                          [--models comp_neo_hook,comp_neo_hook_plastic]
                                          [--interpolators linear,gimp,cpdi]

Cases: 2D/3D x linear/GIMP (--interpolators: also cpdi, fast_cpdi) x MUSL/USL, a block of comp_neo_hook material moving and
deforming (>= 1 M particles; --quick: ~65 k), one rank, one thread. The first step
(JIT, warm-up) is not timed; with --repeat R each case is run R times and the median
rate is reported (the machine may be shared). Beside them, `reference_2d_linear` is ONE numba function
doing the same 2D linear USL step (p2g, grid update, g2p, F, neo-Hooke stress) with no
framework, so `framework / reference` is a measured ratio. Prints a table, writes JSON.
--models runs each case with each constitutive model: comp_neo_hook (the default; under MUSL
its stress is computed in the velocity-gradient pass) or comp_neo_hook_plastic (Uintah's
UCNH with J2 plasticity, yield stress 1e3 Pa: the block moving at a uniform velocity stays
elastic, so this is the cost of its own stress pass and state, p.plasticStrain and p.bElBar).
With --cpu every time (the step loop, the per-task shares, the reference) is the CPU time of
this process instead of wall time: on a shared machine it hardly depends on the others' load.
"""
from __future__ import annotations

import argparse
import json
import time

import numpy as np
from numba import njit

CLOCK = time.perf_counter


class _CpuClock:
    """Stands in for the scheduler's `time` module under --cpu (per-task CPU seconds)."""
    perf_counter = staticmethod(time.process_time)

DECK = """<?xml version="1.0"?>
<Uintah_specification>
  <SimulationComponent type="mpm"/>
  <Time><maxTime>1e9</maxTime><delt_max>1e-3</delt_max><timestep_multiplier>0.4</timestep_multiplier></Time>
  <Grid><Level><Box label="1">
    <lower>[0,0,0]</lower><upper>{upper}</upper><resolution>{res}</resolution>
    <extraCells>{extra}</extraCells><patches>{patches}</patches>
  </Box></Level></Grid>
  <MPM><interpolator>{interp}</interpolator><stress_update>{su}</stress_update></MPM>
  <MaterialProperties><MPM><material>
    <density>1000</density>
    <constitutive_model type="{model}"><bulk_modulus>833.3</bulk_modulus><shear_modulus>384.6</shear_modulus>{plastic}</constitutive_model>
    <geom_object><box><min>{bmin}</min><max>{bmax}</max></box><res>{ppc}</res><velocity>[0.1,0.05,0.02]</velocity></geom_object>
  </material></MPM></MaterialProperties>
</Uintah_specification>
"""


PLASTIC = {"comp_neo_hook": "",
           "comp_neo_hook_plastic": "<yield_stress>1e3</yield_stress><hardening_modulus>100</hardening_modulus>"}


def deck(dim, interp, su, n, patches, model="comp_neo_hook"):
    """n cells per active direction, the block fills the inner 80 %."""
    if dim == 2:
        res, upper, ppc, pat = f"[{n},{n},1]", "[1,1,0.01]", "[2,2,1]", f"[{patches},{patches},1]"
        extra = "[1,1,0]"
        bmin, bmax = "[0.1,0.1,0]", "[0.9,0.9,0.01]"
    else:
        res, upper, ppc, pat = f"[{n},{n},{n}]", "[1,1,1]", "[2,2,2]", f"[{patches},{patches},{patches}]"
        extra = "[1,1,1]"
        bmin, bmax = "[0.1,0.1,0.1]", "[0.9,0.9,0.9]"
    return DECK.format(upper=upper, res=res, extra=extra, patches=pat, interp=interp, su=su, bmin=bmin,
                       bmax=bmax, ppc=ppc, model=model, plastic=PLASTIC[model])


def run_case(dim, interp, su, n, patches, steps, model="comp_neo_hook"):
    import framework.scheduler.scheduler as sched_mod
    from framework.controller import Controller
    sched_mod.time = _CpuClock if CLOCK is time.process_time else time
    ctl = Controller("bench.ups", deck_text=deck(dim, interp, su, n, patches, model), quiet=True, max_timesteps=1)
    dw = ctl.run()                       # JIT + first step
    npart = sum(dw.nparticles.values())
    ctl.sched.timing.clear()
    ctl.sched.overhead.clear()
    ctl.time["max_Timesteps"] = 1 + steps
    t0 = CLOCK()
    ctl.restart_info = None
    # continue the loop from the current warehouse
    from framework import labels as L
    tm = ctl.time
    while ctl.timestep < tm["max_Timesteps"]:
        delt = ctl.next_delt(ctl.sched.reduce_delT(dw), ctl.t, ctl.prev_delt, False)
        from framework.datawarehouse import DataWarehouse
        old, dw = dw, DataWarehouse(ctl.timestep + 1)
        old.set_reduction(L.delT, delt)
        old.set_reduction(L.simTime, ctl.t)
        ctl.sched.execute(ctl.step_graph, old, dw)
        ctl.t += delt
        ctl.timestep += 1
        ctl.prev_delt = delt
    wall = CLOCK() - t0
    table = ctl.sched.timing_table()
    return npart, wall, table


# ---- the single-function reference: 2D linear USL step, no framework -------------------
@njit(cache=True, fastmath={'contract'})
def reference_step(px, pv, pm, pvol, ps, pF, nx, ny, dx, dt, K, mu, rho0):
    """One explicit 2D linear USL MPM step on a whole (nx+1) x (ny+1) node grid."""
    gm = np.zeros((nx + 1, ny + 1))
    gp = np.zeros((nx + 1, ny + 1, 2))
    gf = np.zeros((nx + 1, ny + 1, 2))
    ih = 1.0 / dx
    n = px.shape[0]
    for p in range(n):
        x = px[p, 0] * ih
        y = px[p, 1] * ih
        i = int(x)
        j = int(y)
        fx = x - i
        fy = y - j
        for a in range(2):
            wx = fx if a else 1.0 - fx
            gx = ih if a else -ih
            for b in range(2):
                wy = fy if b else 1.0 - fy
                gy = ih if b else -ih
                S = wx * wy
                G0 = gx * wy
                G1 = wx * gy
                gm[i + a, j + b] += pm[p] * S
                gp[i + a, j + b, 0] += pm[p] * pv[p, 0] * S
                gp[i + a, j + b, 1] += pm[p] * pv[p, 1] * S
                gf[i + a, j + b, 0] -= pvol[p] * (ps[p, 0, 0] * G0 + ps[p, 0, 1] * G1)
                gf[i + a, j + b, 1] -= pvol[p] * (ps[p, 1, 0] * G0 + ps[p, 1, 1] * G1)
    gv = np.zeros((nx + 1, ny + 1, 2))
    ga = np.zeros((nx + 1, ny + 1, 2))
    for i in range(nx + 1):
        for j in range(ny + 1):
            if gm[i, j] > 0.0:
                for d in range(2):
                    a = gf[i, j, d] / gm[i, j]
                    ga[i, j, d] = a
                    gv[i, j, d] = gp[i, j, d] / gm[i, j] + a * dt
    for p in range(n):
        x = px[p, 0] * ih
        y = px[p, 1] * ih
        i = int(x)
        j = int(y)
        fx = x - i
        fy = y - j
        a0 = a1 = v0 = v1 = L00 = L01 = L10 = L11 = 0.0
        for a in range(2):
            wx = fx if a else 1.0 - fx
            gx = ih if a else -ih
            for b in range(2):
                wy = fy if b else 1.0 - fy
                gy = ih if b else -ih
                S = wx * wy
                a0 += S * ga[i + a, j + b, 0]
                a1 += S * ga[i + a, j + b, 1]
                v0 += S * gv[i + a, j + b, 0]
                v1 += S * gv[i + a, j + b, 1]
                L00 += gv[i + a, j + b, 0] * gx * wy
                L01 += gv[i + a, j + b, 0] * wx * gy
                L10 += gv[i + a, j + b, 1] * gx * wy
                L11 += gv[i + a, j + b, 1] * wx * gy
        pv[p, 0] += dt * a0
        pv[p, 1] += dt * a1
        px[p, 0] += dt * v0
        px[p, 1] += dt * v1
        F00 = (1 + dt * L00) * pF[p, 0, 0] + dt * L01 * pF[p, 1, 0]
        F01 = (1 + dt * L00) * pF[p, 0, 1] + dt * L01 * pF[p, 1, 1]
        F10 = dt * L10 * pF[p, 0, 0] + (1 + dt * L11) * pF[p, 1, 0]
        F11 = dt * L10 * pF[p, 0, 1] + (1 + dt * L11) * pF[p, 1, 1]
        pF[p, 0, 0] = F00
        pF[p, 0, 1] = F01
        pF[p, 1, 0] = F10
        pF[p, 1, 1] = F11
        J = F00 * F11 - F01 * F10
        pvol[p] = pm[p] / rho0 * J
        Jm23 = J ** (-2.0 / 3.0)
        b00 = F00 * F00 + F01 * F01
        b11 = F10 * F10 + F11 * F11
        b01 = F00 * F10 + F01 * F11
        tr = Jm23 * (b00 + b11 + 1.0)
        pr = 0.5 * K * (J - 1.0 / J)
        ps[p, 0, 0] = pr + mu / J * (Jm23 * b00 - tr / 3.0)
        ps[p, 1, 1] = pr + mu / J * (Jm23 * b11 - tr / 3.0)
        ps[p, 2, 2] = pr + mu / J * (Jm23 - tr / 3.0)
        ps[p, 0, 1] = ps[p, 1, 0] = mu / J * Jm23 * b01


def run_reference(n, steps):
    dx = 1.0 / n
    sub = (np.arange(2 * n) + 0.5) * dx / 2
    X, Y = np.meshgrid(sub, sub, indexing="ij")
    keep = (X >= 0.1) & (X <= 0.9) & (Y >= 0.1) & (Y <= 0.9)
    px = np.ascontiguousarray(np.stack([X[keep], Y[keep]], axis=1))
    npart = len(px)
    pv = np.tile([0.1, 0.05], (npart, 1))
    pvol = np.full(npart, dx * dx / 4 * 0.01)
    pm = 1000.0 * pvol
    ps = np.zeros((npart, 3, 3))
    pF = np.tile(np.eye(3), (npart, 1, 1))
    c = np.sqrt((833.3 + 4 * 384.6 / 3) / 1000.0)
    dt = 0.4 * dx / (c + 0.1)
    reference_step(px, pv, pm, pvol, ps, pF, n, n, dx, dt, 833.3, 384.6, 1000.0)
    t0 = CLOCK()
    for _ in range(steps):
        reference_step(px, pv, pm, pvol, ps, pF, n, n, dx, dt, 833.3, 384.6, 1000.0)
    return npart, CLOCK() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--json", default="mpm_bench.json")
    ap.add_argument("--quick", action="store_true", help="~65 k particles instead of >= 1 M")
    ap.add_argument("--repeat", type=int, default=1, help="runs per case; the median is reported")
    ap.add_argument("--cases", default="", help="only cases whose name contains this, e.g. '2D linear'")
    ap.add_argument("--no-reference", action="store_true", help="skip the single-function reference")
    ap.add_argument("--cpu", action="store_true", help="CPU time of this process instead of wall time")
    ap.add_argument("--models", default="comp_neo_hook",
                    help="comma-separated constitutive models: " + ", ".join(PLASTIC))
    ap.add_argument("--interpolators", default="linear,gimp", help="comma-separated <interpolator> values")
    a = ap.parse_args()
    models = a.models.split(",")
    for mdl in models:
        if mdl not in PLASTIC:
            ap.error(f"--models: {mdl}; accepted: {', '.join(PLASTIC)}")
    global CLOCK
    if a.cpu:
        CLOCK = time.process_time
        print("CPU seconds of this process (--cpu)")
    n2, n3, p2, p3 = (160, 32, 2, 1) if a.quick else (640, 80, 4, 2)
    rows = []
    for dim, n, pt in ((2, n2, p2), (3, n3, p3)):
        for interp in a.interpolators.split(","):
            for su in ("musl", "usl"):
                if a.cases not in f"{dim}D {interp} {su}":
                    continue
                for mdl in models:
                    runs = [run_case(dim, interp, su, n, pt, a.steps, mdl) for _ in range(a.repeat)]
                    npart, wall, table = sorted(runs, key=lambda r: r[1])[len(runs) // 2]
                    rate = npart * a.steps / wall
                    share = {name: round(pct, 1) for name, t, calls, pct in table}
                    case = f"{dim}D {interp} {su}" + ("" if mdl == "comp_neo_hook" else f" {mdl}")
                    rows.append(dict(case=case, particles=npart, patches=pt ** dim,
                                     seconds_per_step=wall / a.steps, particle_steps_per_s=rate, share=share))
                    print(f"{case:40s} {npart:9d} particles  {wall / a.steps * 1e3:8.1f} ms/step  "
                          f"{rate / 1e6:6.2f} M particle-steps/s", flush=True)
                    for name, t, calls, pct in table[:6]:
                        print(f"      {pct:5.1f}%  {name}")
    if a.no_reference:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)
        return
    refs = [run_reference(n2, a.steps) for _ in range(a.repeat)]
    npart, wall = sorted(refs, key=lambda r: r[1])[len(refs) // 2]
    ref = npart * a.steps / wall
    rows.append(dict(case="reference 2D linear usl (one numba function)", particles=npart,
                     particle_steps_per_s=ref))
    fw = next((r for r in rows if r["case"] == "2D linear usl"), {}).get("particle_steps_per_s", np.nan)
    print(f"reference 2D linear usl: {npart} particles {ref / 1e6:6.2f} M particle-steps/s; "
          f"framework 2D linear usl / reference = {fw / ref:.2f}")
    with open(a.json, "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
