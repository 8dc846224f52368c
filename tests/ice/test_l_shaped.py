"""Explicit ICE on an L-shaped level (two <Box>es; framework/grid.py holes).

inputs/ICE/explosion2D (a cylindrical explosion centred in the box [0,2]^2 with reflecting
walls), on 32 x 32 cells: its flow is symmetric about x = 1 and y = 1, so u = 0 on x = 1 and
v = 0 on y = 1, and the box's solution restricted to the L [0,2]x[0,1] + [0,1]x[1,2] is the
solution of the L with reflecting walls on the faces of its hole. The explosion's centre is the
L's re-entrant corner. Expected: the L's cells equal the box's to rounding (measured 1.4e-15
after 40 steps), its hole empty; and refusals for what was not checked on such a level.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from framework.problemspec import InputError
from tests.conftest import ROOT, run_deck

BOX = ('<Level><Box label="1"><lower>[0,0,0]</lower><upper>[2,2,0.01]</upper><extraCells>[1,1,1]</extraCells>'
       '<patches>[2,2,1]</patches><resolution>[32,32,1]</resolution></Box></Level>')
L = ('<Level><Box label="1"><lower>[0,0,0]</lower><upper>[2,1,0.01]</upper><extraCells>[1,1,1]</extraCells>'
     '<patches>[2,1,1]</patches><resolution>[32,16,1]</resolution></Box>'
     '<Box label="2"><lower>[0,1,0]</lower><upper>[1,2,0.01]</upper><extraCells>[1,1,1]</extraCells>'
     '<patches>[1,1,1]</patches><resolution>[16,16,1]</resolution></Box></Level>')
TOL = 1e-13


def _deck(level):
    text = (ROOT / "inputs" / "ICE" / "explosion2D.ups").read_text(encoding="iso-8859-1")
    a, b = text.index("<Level>"), text.index("</Level>") + len("</Level>")
    text = text[:a] + level + text[b:]
    text = text.replace("<maxTime> 0.25 </maxTime>", "<maxTime> 0.25 </maxTime><max_Timesteps>40</max_Timesteps>")
    return text.replace("<outputInterval> 0.05 </outputInterval>",
                        "<outputTimestepInterval>20</outputTimestepInterval>")


def test_explosion_on_the_l_is_the_box_restricted(tmp_path):
    box = DataArchive(run_deck(_deck(BOX), tmp_path, "box").archiver.dir)
    ell = DataArchive(run_deck(_deck(L), tmp_path, "ell").archiver.dir)
    assert np.array_equal(box.times, ell.times) and len(box.times) == 3
    keep = np.ones((32, 32), bool)
    keep[16:, 16:] = False
    for j in (1, 2):
        for lab in ("rho_CC", "press_CC", "temp_CC", "vel_CC"):
            f, e = box.read(lab, 0, j)[0][:, :, 0], ell.read(lab, 0, j)[0][:, :, 0]
            assert np.abs(f[keep] - e[keep]).max() < TOL * np.abs(f).max(), (j, lab)
            assert np.all(e[~keep] == 0)
    vel = ell.read("vel_CC", 0, 2)[0][:, :, 0]
    assert np.abs(vel).max() > 0.5                       # the blast has reached the walls' region
    _, mb = box.reduction("TotalMass")
    _, me = ell.reduction("TotalMass")
    assert np.allclose(me, 0.75 * np.asarray(mb), rtol=1e-13)


@pytest.mark.parametrize("extra, what", [
    ("<ImplicitSolver>", "<ImplicitSolver>"),
    ('<Face circle="x-" origin="0 0.5 0.005" radius="0.1"><BCType id="all" label="Velocity" var="Dirichlet">'
     '<value>[0,0,0]</value></BCType>'
     + "".join(f'<BCType id="all" label="{v}" var="Neumann"><value>0</value></BCType>'
               for v in ("Pressure", "Density", "Temperature")) + '</Face>', "sub-faces"),
])
def test_what_an_l_shaped_level_refuses(tmp_path, extra, what):
    text = _deck(L)
    if what == "<ImplicitSolver>":
        text = text.replace("<ICE><advection", "<ICE><ImplicitSolver><max_outer_iterations>5</max_outer_iterations>"
                            "<outer_iteration_tolerance>1e-8</outer_iteration_tolerance><iters_before_timestep_restart>"
                            "5</iters_before_timestep_restart><Parameters variable=\"implicitPressure\">"
                            "<tolerance>1e-12</tolerance><solver>cg</solver><preconditioner>none</preconditioner>"
                            "<maxiterations>200</maxiterations></Parameters></ImplicitSolver><advection")
    else:
        text = text.replace("</BoundaryConditions>", extra + "</BoundaryConditions>")
    with pytest.raises(InputError) as e:
        run_deck(text, tmp_path)
    assert what in str(e.value) and "not supported" in str(e.value) and "\n" not in str(e.value)
