"""Semi-implicit ICE (components/ice/implicit.py): the pressure equation solved by PCG in a Loop.

Scene: the Taylor-Green vortex at Mach 0.05 (components/ice/scene_lowmach.py), a steady
Euler solution, so each run's error is its velocity's distance from the initial field.
"""
import re
from pathlib import Path

import numpy as np
import pytest

from components.ice.scene_lowmach import blob_deck, vortex_deck, vortex_errors
from framework.archiver import DataArchive
from framework.controller import Controller
from framework.problemspec import InputError
from tests.conftest import pysus_runs

N = 16
DATA = Path(__file__).parent / "data"


def _run(tmp_path, name, **kw):
    path = tmp_path / f"{name}.ups"
    path.write_text(vortex_deck(N, **kw))
    c = Controller(str(path), quiet=True, filebase=str(tmp_path / f"{name}.uda"))
    c.run()
    da = DataArchive(c.archiver.dir)
    return c, da, da.read("vel_CC", 0, -1)[0]


def test_implicit_agrees_with_explicit_to_discretisation_error(tmp_path):
    ce, de, ue = _run(tmp_path, "explicit")
    err = vortex_errors(de)["u"]
    # the explicit delT (knob_for_speedSound 1): the same scheme up to the implicit face velocities
    ck, _, uk = _run(tmp_path, "same_dt", implicit=True, knob=1.0)
    assert ck.timestep == ce.timestep
    assert np.abs(uk - ue).mean() < 0.01 * err
    # delT from the flow speed: ~20x larger steps; the difference is ICE's first-order time error
    c4, _, u4 = _run(tmp_path, "cfl04", implicit=True, cfl=0.4)
    c1, d1, u1 = _run(tmp_path, "cfl01", implicit=True, cfl=0.1)
    assert c4.timestep < ce.timestep / 15
    d04, d01 = np.abs(u4 - ue).mean(), np.abs(u1 - ue).mean()
    assert 2.5 < d04 / d01 < 5.0, (d04, d01)
    assert vortex_errors(d1)["u"] < 2.5 * err
    # one material, no exchange: the linearisation is exact, one outer iteration per step
    assert set(c1.component.outer_iterations) == {1}
    assert max(c1.component.pcg.iterations) < 25


def test_preconditioners_and_patches_agree_to_solver_tolerance(tmp_path):
    kw = dict(implicit=True, tolerance=1e-12, max_timesteps=4)
    _, _, a = _run(tmp_path, "mg1", **kw)
    cb, _, b = _run(tmp_path, "mg4", patches="[2,2,1]", **kw)
    cj, _, j = _run(tmp_path, "jac4", patches="[2,2,1]", precond="jacobi", **kw)
    _, _, m = _run(tmp_path, "linf", patches="[2,2,1]", norm="LInfinity", **kw)
    scale = np.abs(a).max()
    for other in (b, j, m):
        assert np.abs(a - other).max() < 1e-9 * scale
    assert cb.component.pcg.precond == "mg" and cj.component.pcg.precond == "jacobi"
    # 16^2 is too small to show multigrid's worth (scripts/bench/implicit_ice.py does), but fewer
    assert np.mean(cb.component.pcg.iterations) < np.mean(cj.component.pcg.iterations)


@pytest.mark.parametrize("K,limiter", [(None, None), (1e10, None), (None, "BarthJespersen")])
def test_two_materials_match_explicit_at_the_same_delT(tmp_path, K, limiter):
    """Two gases (exchange or none): eq. P's theta-weighted operator and the outer iteration
    give explicit ICE's answer when both take the same small steps (acoustic CFL 0.011: the
    schemes differ by O(CFL^2) relative, a few 1e-4 at the material interface). With Uintah's
    limiter both take the dilatation's face fractions advected second order (Uintah's advectQ of
    vol_frac in computeDelPressAndUpdatePressCC and setupRHS): measured press 3.2e-4 of its range,
    vel 1.8e-5; the donor cell's fractions in the implicit residual alone give press 2.7e-2."""
    out = {}
    for kind in ("explicit", "implicit"):
        (tmp_path / f"{kind}.ups").write_text(blob_deck(32, steps=12, materials=2, K=K, delt=1e-6, patches="[2,2,1]",
                                                        implicit=kind == "implicit", tolerance=1e-12,
                                                        outer_tol=1e-11, limiter=limiter))
        c = Controller(str(tmp_path / f"{kind}.ups"), quiet=True, filebase=str(tmp_path / f"{kind}.uda"))
        c.run()
        da = DataArchive(c.archiver.dir)
        rho = [da.read("rho_CC", m, -1)[0] for m in (0, 1)]
        # a material's velocity where it is present (a vanishing phase's velocity means little)
        out[kind] = [da.read("vel_CC", m, -1)[0][rho[m] > 1e-3 * rho[m].max()] for m in (0, 1)] \
            + [da.read("press_CC", 0, -1)[0]]
    # eq. P's face coefficients take the residual's donor-cell theta (and the exchange's E v_f): no face
    # velocity changes sign at this delT, so the residual is linear in P and one outer iteration suffices
    # (measured before, with the centred theta: 3 without exchange); Uintah's limiter advects the
    # residual's fractions second order, which the donor-cell stencil approximates (3 measured)
    assert max(c.component.outer_iterations) == (1 if limiter is None else 3)
    scale = [max(np.ptp(v) for v in out["explicit"][:2])] * 2 + [np.ptp(out["explicit"][2])]
    for e, i, s, what in zip(out["explicit"], out["implicit"], scale, ("vel0", "vel1", "press")):
        assert np.abs(e - i).max() < 1e-3 * s, what


@pytest.fixture(scope="module")
def on_ranks(tmp_path_factory):
    """The implicit vortex on 1 rank in this process, then on 2 and 3 ranks in one mpiexec
    launch: the directory of n1.uda, n2.uda, n3.uda and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("implicit_ranks")
    (d / "d.ups").write_text(vortex_deck(N, implicit=True, patches="[2,2,1]", tolerance=1e-12, max_timesteps=4))
    return d, pysus_runs([((d / "d.ups", "--filebase", d / f"n{n}.uda"), n) for n in (1, 2, 3)], d)


@pytest.mark.parametrize("nranks", [2, 3])
def test_implicit_ice_on_ranks_matches_one_rank(on_ranks, nranks):
    d, out = on_ranks
    for rc, err in (out[0], out[nranks - 1]):
        assert rc == 0, err
    for lab in ("vel_CC", "press_CC"):
        a = DataArchive(d / "n1.uda").read(lab, 0, -1)[0]
        b = DataArchive(d / f"n{nranks}.uda").read(lab, 0, -1)[0]
        ref = np.abs(a).max() if lab == "vel_CC" else np.ptp(a)
        assert np.abs(a - b).max() < 1e-9 * ref, lab


def test_second_order_fractions_independent_of_the_patch_layout(tmp_path):
    """With Uintah's limiter the residual (setupRHS) reads the neighbour patches' face velocities
    (the donors' slab offsets) and fractions: 1 and 4 patches give the same steps (measured
    1.3e-16 in press; without the face velocities' ghosts 2.4e-5)."""
    out = []
    for p in ("[1,1,1]", "[2,2,1]"):
        (tmp_path / "d.ups").write_text(blob_deck(32, steps=6, materials=2, delt=2e-5, patches=p, implicit=True,
                                                  tolerance=1e-13, outer_tol=1e-12, limiter="BarthJespersen"))
        c = Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / f"p{p[1]}.uda"))
        c.run()
        da = DataArchive(c.archiver.dir)
        out.append([da.read(lab, m, -1)[0] for lab, m in (("press_CC", 0), ("vel_CC", 1), ("rho_CC", 1))])
    for a, b, lab in zip(*out, ("press", "vel1", "rho1")):
        assert np.abs(a - b).max() <= 1e-12 * np.abs(a).max(), lab


def test_two_gas_blob_with_uintahs_scheme_is_uintahs(tmp_path):
    """The implicit two-gas blob with Uintah's scheme (limiter="BarthJespersen"
    dissipationHeating="false") against Uintah's sus on the same deck (tests/ice/data/
    sus_implicit_blob_barth_jespersen.npz: sus's fields after step 6; its deck: this one through
    scripts/accuracy_cost.uintah_deck, with sus's required tags added (initTime,
    iters_before_timestep_restart, zero viscosity, conductivity and exchange coefficients),
    extraCells [1,1,1], sus's CGSolver with LInfinity norm; 2 outer iterations a step in both).
    Measured: press_CC 8.0e-12 of its range at the worst of the 6 steps, rho_CC 5.1e-13, each
    material's velocity where it is present 1.4e-11."""
    sus = np.load(DATA / "sus_implicit_blob_barth_jespersen.npz")
    (tmp_path / "d.ups").write_text(blob_deck(32, steps=6, materials=2, delt=2e-5, implicit=True, tolerance=1e-13,
                                              outer_tol=1e-12, limiter="BarthJespersen", heating="false"))
    c = Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "d.uda"))
    c.run()
    da = DataArchive(c.archiver.dir)
    p = da.read("press_CC", 0, -1)[0].squeeze()
    assert np.abs(p - sus["press_CC"]).max() < 1e-10 * np.ptp(sus["press_CC"])
    for m in (0, 1):
        rho, ref = da.read("rho_CC", m, -1)[0].squeeze(), sus[f"rho_CC_{m}"]
        assert np.abs(rho - ref).max() < 1e-11 * ref.max(), m
        vel, vref = da.read("vel_CC", m, -1)[0].squeeze()[..., :2], sus[f"vel_CC_{m}"]
        present = ref > 1e-3 * ref.max()
        assert np.abs(vel - vref)[present].max() < 1e-9 * np.abs(vref[present]).max(), m


PISTON_BLOCK = """<ImplicitSolver>
           <max_outer_iterations>      2    </max_outer_iterations>
           <outer_iteration_tolerance> 1e-8 </outer_iteration_tolerance>
           <iters_before_timestep_restart> 5 </iters_before_timestep_restart>
           <Parameters variable = "implicitPressure">
            <solver>         cg      </solver>
            <preconditioner> {pre}    </preconditioner>
            <tolerance>      1.e-10  </tolerance>
            <maxiterations>  7500    </maxiterations>
            <npre>           1       </npre>
            <npost>          1       </npost>
            <skip>           0       </skip>
            <jump>           0       </jump>
            </Parameters>
        </ImplicitSolver>
        <TimeStepControl>
          <Scheme_for_delT_calc> aggressive   </Scheme_for_delT_calc>
          <knob_for_speedSound>  0.00         </knob_for_speedSound>
        </TimeStepControl>"""


def _uintah_deck(pre):
    text = vortex_deck(8, max_timesteps=1).replace("<SimulationComponent type=\"ice\"/>",
                                                   "<SimulationComponent type=\"ice\"/><Solver type=\"hypre\"/>")
    return text.replace('<advection type="SecondOrder"/>', '<advection type="SecondOrder"/>' +
                        PISTON_BLOCK.format(pre=pre))


def test_uintah_implicit_block_is_read_and_reported(tmp_path, capsys):
    """pistonValidation.ups's <ImplicitSolver> and <Solver type="hypre"> run on our solver."""
    (tmp_path / "u.ups").write_text(_uintah_deck("pfmg"))
    c = Controller(str(tmp_path / "u.ups"), quiet=True, filebase=str(tmp_path / "u.uda"))
    c.run()
    line = [ln for ln in capsys.readouterr().err.splitlines() if "ICE implicit pressure" in ln]
    assert len(line) == 1
    assert 'type="hypre"' in line[0] and "preconditioner=pfmg" in line[0] and "geometric multigrid" in line[0]
    assert "skip, jump" in line[0] and "recomputed with half the delT" in line[0]
    assert c.component.imp.max_outer == 2 and c.component.imp.max_iterations == 7500


def test_unknown_preconditioner_is_an_input_error(tmp_path):
    (tmp_path / "u.ups").write_text(_uintah_deck("boomerang"))
    with pytest.raises(InputError, match="preconditioner 'boomerang' is not known"):
        Controller(str(tmp_path / "u.ups"), quiet=True, filebase=str(tmp_path / "u.uda"))


def test_speed_of_sound_knob_outside_0_1_is_an_input_error(tmp_path):
    (tmp_path / "k.ups").write_text(vortex_deck(8, implicit=True, knob=2.0))
    with pytest.raises(InputError, match="knob_for_speedSound must be between 0 and 1"):
        Controller(str(tmp_path / "k.ups"), quiet=True, filebase=str(tmp_path / "k.uda"))


def _restart_deck(limit, outer_tol):
    text = vortex_deck(8, implicit=True, max_timesteps=2, outer=3, outer_tol=outer_tol)
    return text.replace("</max_outer_iterations>",
                        f"</max_outer_iterations><iters_before_timestep_restart> {limit} "
                        "</iters_before_timestep_restart>")


def test_outer_iterations_beyond_the_limit_recompute_the_step(tmp_path):
    """iters_before_timestep_restart: every step needs >= 1 outer iteration, so a limit of 0 makes
    the controller halve delT ten times and then stop with ICE's reason; a loose limit never does."""
    (tmp_path / "a.ups").write_text(_restart_deck(0, 1e-9))
    c = Controller(str(tmp_path / "a.ups"), quiet=True, filebase=str(tmp_path / "a.uda"))
    with pytest.raises(RuntimeError, match="recomputed 10 times.*ICE implicit pressure"):
        c.run()
    assert c.recomputes == 10
    (tmp_path / "b.ups").write_text(_restart_deck(3, 1e-9))
    c = Controller(str(tmp_path / "b.ups"), quiet=True, filebase=str(tmp_path / "b.uda"))
    c.run()
    assert c.recomputes == 0 and c.timestep == 2


def test_implicit_delt_is_explicit_ices_with_uintahs_default_knob(tmp_path):
    """As Uintah, implicit ICE takes explicit ICE's delT task (the equilibration's sound speed);
    without <TimeStepControl> its knob_for_speedSound is 0.5 (Uintah's implicit default): the
    first step's delT, cfl min dx / (0.5 c + |u|), is the one computed here from the initial fields."""
    text = vortex_deck(8, implicit=True, max_timesteps=1).replace(
        "<TimeStepControl><Scheme_for_delT_calc> aggressive </Scheme_for_delT_calc>"
        "<knob_for_speedSound> 0.0 </knob_for_speedSound></TimeStepControl>", "")
    assert "TimeStepControl" not in text
    (tmp_path / "d.ups").write_text(text)
    c = Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "d.uda"))
    c.run()
    assert c.component.knob == 0.5
    da = DataArchive(c.archiver.dir)
    vel, (x, _, _) = da.read("vel_CC", 0, 0)
    c_sound = np.sqrt(1.4 * da.read("press_CC", 0, 0)[0] / da.read("rho_CC", 0, 0)[0])     # ideal gas
    dx = x[1] - x[0]
    want = 0.4 * min((dx / (0.5 * c_sound + np.abs(vel[..., d]))).min() for d in range(2))
    assert da.times[0] == 0.0 and c.t == pytest.approx(want, rel=1e-12)


def test_two_gas_blob_at_the_flow_speed_delT_converges_in_few_outer_iterations(tmp_path, capsys):
    """Two gases, no exchange, 64^2, delT from the flow speed (~20x the acoustic one): the
    residual's face fractions are the donor cells' (a function of the face velocities' signs),
    so the stencil takes the same donors, rebuilt every outer iteration as Uintah's setupMatrix.
    Measured: 4, 3 outer iterations (max|rhs| 3.2, 0.13, 0.23, 5e-3, 1e-13 in the first step);
    with the centred fractions in the stencil all 20 (max|rhs| 2.5e-3 after 20)."""
    (tmp_path / "b.ups").write_text(blob_deck(64, steps=2, materials=2, implicit=True))
    c = Controller(str(tmp_path / "b.ups"), quiet=True, filebase=str(tmp_path / "b.uda"))
    c.run()
    assert max(c.component.outer_iterations) <= 5, c.component.outer_iterations
    assert c.component.outer_max_rhs <= 1e-8
    assert "not converged" not in capsys.readouterr().err
    # a step the outer iteration does not converge says so, with its timestep and residual
    (tmp_path / "one.ups").write_text(blob_deck(64, steps=1, materials=2, implicit=True, outer=1))
    Controller(str(tmp_path / "one.ups"), quiet=True, filebase=str(tmp_path / "one.uda")).run()
    err = capsys.readouterr().err
    assert re.search(r"warning: ICE implicit pressure: timestep 1: outer iteration not converged: "
                     r"max\|rhs\| \d\.\d+e[+-]\d+ above outer_iteration_tolerance 1e-08 after 1 outer", err), err
