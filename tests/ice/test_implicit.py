"""Semi-implicit ICE (components/ice/implicit.py): the pressure equation solved by PCG in a Loop.

Scene: the Taylor-Green vortex at Mach 0.05 (components/ice/scene_lowmach.py), a steady
Euler solution, so each run's error is its velocity's distance from the initial field.
"""
import numpy as np
import pytest

from components.ice.scene_lowmach import blob_deck, vortex_deck, vortex_errors
from framework.archiver import DataArchive
from framework.controller import Controller
from framework.problemspec import InputError
from tests.conftest import pysus_ranks

N = 16


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


@pytest.mark.parametrize("K", [None, 1e10])
def test_two_materials_match_explicit_at_the_same_delT(tmp_path, K):
    """Two gases (exchange or none): eq. P's theta-weighted operator and the outer iteration
    give explicit ICE's answer when both take the same small steps (acoustic CFL 0.011: the
    schemes differ by O(CFL^2) relative, a few 1e-4 at the material interface)."""
    out = {}
    for kind in ("explicit", "implicit"):
        (tmp_path / f"{kind}.ups").write_text(blob_deck(32, steps=12, materials=2, K=K, delt=1e-6, patches="[2,2,1]",
                                                        implicit=kind == "implicit", tolerance=1e-12,
                                                        outer_tol=1e-11))
        c = Controller(str(tmp_path / f"{kind}.ups"), quiet=True, filebase=str(tmp_path / f"{kind}.uda"))
        c.run()
        da = DataArchive(c.archiver.dir)
        rho = [da.read("rho_CC", m, -1)[0] for m in (0, 1)]
        # a material's velocity where it is present (a vanishing phase's velocity means little)
        out[kind] = [da.read("vel_CC", m, -1)[0][rho[m] > 1e-3 * rho[m].max()] for m in (0, 1)] \
            + [da.read("press_CC", 0, -1)[0]]
    if K is None:
        assert max(c.component.outer_iterations) >= 2      # donor-cell theta: not linear
    else:       # the exchange is in eq. P's face coefficients (E v_f): one outer iteration suffices here
        assert max(c.component.outer_iterations) == 1
    scale = [max(np.ptp(v) for v in out["explicit"][:2])] * 2 + [np.ptp(out["explicit"][2])]
    for e, i, s, what in zip(out["explicit"], out["implicit"], scale, ("vel0", "vel1", "press")):
        assert np.abs(e - i).max() < 1e-3 * s, what


@pytest.mark.parametrize("nranks", [2, 3])
def test_implicit_ice_on_ranks_matches_one_rank(tmp_path, nranks):
    (tmp_path / "d.ups").write_text(vortex_deck(N, implicit=True, patches="[2,2,1]", tolerance=1e-12,
                                                max_timesteps=4))
    for n in (1, nranks):
        r = pysus_ranks(tmp_path / "d.ups", "--filebase", tmp_path / f"n{n}.uda", np_=n)
        assert r.returncode == 0, r.stderr
    for lab in ("vel_CC", "press_CC"):
        a = DataArchive(tmp_path / "n1.uda").read(lab, 0, -1)[0]
        b = DataArchive(tmp_path / f"n{nranks}.uda").read(lab, 0, -1)[0]
        ref = np.abs(a).max() if lab == "vel_CC" else np.ptp(a)
        assert np.abs(a - b).max() < 1e-9 * ref, lab


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
