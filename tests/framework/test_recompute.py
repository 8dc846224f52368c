"""A component may ask for a timestep to be redone with a smaller delT (Uintah's recompute)."""
import numpy as np
import pytest

from framework import labels as L
from framework.component import Component, register
from framework.task import NEW, OLD, Task
from framework.variables import VarType
from tests.conftest import run_deck

U = L.create("test.recompute.u", VarType.CC)

DECK = """<Uintah_specification><SimulationComponent type="test_recompute"/>
<Time><maxTime>1.0</maxTime><delt_init>1</delt_init></Time>
<Grid><Level><Box label="1"><lower>[0,0,0]</lower><upper>[1,1,1]</upper><resolution>[8,8,1]</resolution>
<patches>[2,2,1]</patches></Box></Level></Grid></Uintah_specification>"""


@register("test_recompute")
class Recomputing(Component):
    """u grows by delT each step; any step asked with delT > 0.3 is refused once per patch."""

    may_recompute = True

    def problem_setup(self, root, level):
        self.materials = ["m"]
        self.asked = []

    def schedule_initialize(self, level, sched):
        sched.add_task(Task("init", lambda p, m, o, n: n.allocate(U, 0, p), [0]).computes(U))

    def schedule_compute_stable_timestep(self, level, sched):
        sched.add_task(Task("dt", lambda p, m, o, n: n.put_reduction(L.delT, 0.5), [0]).computes(L.delT))

    def schedule_time_advance(self, level, sched):
        self.sched = sched

        def step(patch, matls, old_dw, new_dw):
            dt = old_dw.get_reduction(L.delT)
            self.asked.append(dt)
            if dt > 0.3 and patch.id == 3:         # one patch (one rank) is enough to ask
                self.sched.request_recompute("delT too large for the test")
            new_dw.allocate(U, 0, patch)[...] = old_dw.get(U, 0, patch) + dt

        sched.add_task(Task("advance", step, [0]).requires(OLD, U).requires(OLD, L.delT).computes(U))


def test_step_is_redone_with_half_delt_from_the_intact_old_warehouse(tmp_path):
    ctl = run_deck(DECK.replace("</Uintah_specification>", "<DataArchiver><filebase>r.uda</filebase>"
                                "<outputInterval>1.0</outputInterval><save label=\"test.recompute.u\"/>"
                                "</DataArchiver></Uintah_specification>"), tmp_path)
    assert ctl.recomputes > 0 and ctl.t == pytest.approx(1.0)
    asked = sorted(set(ctl.component.asked))
    assert asked == [0.25, 0.5]
    u = ctl.final_dw.get(U, 0, ctl.level.patches[0])
    lo, hi = ctl.level.patches[0].interior()
    # u sums the delT of the accepted steps only: exactly the end time
    assert np.all(u[lo[0]:hi[0], lo[1]:hi[1], 0] == 1.0)
