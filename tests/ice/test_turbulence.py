"""ICE's turbulence models (components/ice/turbulence.py) on fields with known answers.

The strain rate is Uintah's (SmagorinskyModel::computeStrainRate): the diagonal from the face
velocities' differences, the off-diagonal terms from the same differences, S_xy = (du/dy +
dv/dx) / 2 with du = u(x + dx/2) - u(x - dx/2); so a linear stretching u = a x has
|S| = sqrt(2 (a^2 + 2 ((a/2)^2 + (a/2)^2))) = 2a on a cubic grid, and a simple shear u = g y
has S = 0, as in Uintah.
"""
import numpy as np
import pytest

from components.ice import turbulence as T

N = 6                                   # cells per direction, ghost layer included: 1..4 inside
DX = np.array([0.1, 0.1, 0.1])
DIMS = np.array([True, True, True])
SH = np.zeros((3, 3), dtype=np.int64)   # face f of a direction is the lower face of cell f


def faces(fu, fv, fw):
    """Face-velocity arrays (N+1 faces along their own direction) from functions of the face centre."""
    out = []
    for d, f in enumerate((fu, fv, fw)):
        shape = [N, N, N]
        shape[d] += 1
        idx = np.indices(shape).astype(float)
        centre = [(idx[e] + (0.0 if e == d else 0.5)) * DX[e] for e in range(3)]
        out.append(f(*centre))
    return out


def smagorinsky(u, v, w, rho=1.2, c=0.1):
    S = np.zeros((N, N, N, 6))
    lo, hi = np.array([1, 1, 1]), np.array([N - 1] * 3)
    T.strain_rate(u, v, w, S, lo, hi, SH, DIMS, DX)
    mu_t = np.zeros((N, N, N))
    fw = (DX[0] * DX[1] * DX[2]) ** (1.0 / 3.0)
    T.smagorinsky_viscosity(S, np.full((N, N, N), rho), mu_t, lo, hi, (c * fw) * (c * fw))
    return mu_t[1:-1, 1:-1, 1:-1], fw


def test_translation_has_no_turbulent_viscosity():
    """Uniform flow (solid-body translation): S = 0, mu_t = 0 exactly, in both models."""
    u, v, w = faces(lambda x, y, z: 3.0 + 0 * x, lambda x, y, z: -2.0 + 0 * x, lambda x, y, z: 1.0 + 0 * x)
    mu_t, _ = smagorinsky(u, v, w)
    assert np.all(mu_t == 0.0)
    S = np.zeros((N, N, N, 6))
    lo2, hi2 = np.zeros(3, np.int64), np.array([N - 1] * 3)
    T.strain_rate(u, v, w, S, lo2, hi2, SH, DIMS, DX)
    vel = np.broadcast_to(np.array([3.0, -2.0, 1.0]), (N, N, N, 3)).copy()
    mu_dyn = np.full((N, N, N), -1.0)
    lo, hi = np.ones(3, np.int64), np.array([N - 1] * 3)
    no = np.zeros(3, dtype=np.bool_)
    T.dynamic_viscosity(S, vel, np.full((N, N, N), 1.2), mu_dyn, np.zeros((N, N, N, 6)), np.zeros((N, N, N, 6)),
                        np.zeros((N, N, N, 6)), lo, hi, lo, hi, lo2, hi2, lo2, hi2, no, no, DIMS, 0.1, 0.1)
    assert np.all(mu_dyn[1:-1, 1:-1, 1:-1] == 0.0)


def test_smagorinsky_stretching_formula():
    """u = a x: mu_t = rho (C Delta)^2 2a, Delta = (dx dy dz)^(1/3)."""
    a, rho, c = 7.0, 1.2, 0.1
    u, v, w = faces(lambda x, y, z: a * x, lambda x, y, z: 0 * x, lambda x, y, z: 0 * x)
    mu_t, fw = smagorinsky(u, v, w, rho, c)
    assert np.allclose(mu_t, rho * (c * fw) ** 2 * 2 * a, rtol=1e-13, atol=0)


def test_smagorinsky_simple_shear_is_zero_as_uintah():
    """u = g y: Uintah's off-diagonal S_xy takes u's x-difference over dy, which is 0 here."""
    u, v, w = faces(lambda x, y, z: 5.0 * y, lambda x, y, z: 0 * x, lambda x, y, z: 0 * x)
    mu_t, _ = smagorinsky(u, v, w)
    assert np.all(mu_t == 0.0)


def test_total_viscosity_boundary_and_interface():
    """mu + mu_t inside (mu where vol_frac <= 0.9); on a domain face's extra cells
    mu (mu + mu_t) / (mu + 2 mu_t) of the adjacent cell, the domain's edge cells 0."""
    mu = np.full((N, N, N), 2e-5)
    mu_t = np.zeros((N, N, N))
    mu_t[1:-1, 1:-1, 1:-1] = 3e-3
    vf = np.ones((N, N, N))
    vf[2, 2, 2] = 0.5
    tot = np.empty((N, N, N))
    lo, hi = np.ones(3, np.int64), np.array([N - 1] * 3)
    yes = np.ones(3, dtype=np.bool_)
    T.total_viscosity(mu, mu_t, vf, tot, lo, hi, lo, hi, yes, yes)
    assert tot[3, 3, 3] == 2e-5 + 3e-3 and tot[2, 2, 2] == 2e-5
    assert tot[0, 3, 3] == pytest.approx(2e-5 * (2e-5 + 3e-3) / (2e-5 + 6e-3), rel=1e-15)
    assert tot[0, 0, 3] == 0.0


def test_no_turbulence_no_task(tmp_path):
    """A deck without <turbulence> schedules no turbulence task (and compiles none of its kernels)."""
    import pathlib
    from framework.controller import Controller
    ref = pathlib.Path(__file__).parent / "uintah_reference"
    for deck, expect in (("XY_explicit.ups", False), ("impVortices_smag_explicit.ups", True)):
        c = Controller(str(ref / deck), quiet=True, filebase=str(tmp_path / "run.uda"))

        class Names:
            def __init__(self):
                self.names = []

            def add_task(self, t):
                self.names.append(t.name)
        s = Names()
        c.component.schedule_time_advance(c.level, s)
        assert ("ICE::computeTurbViscosity" in s.names) == expect
        assert (c.component.turbulence is not None) == expect


@pytest.mark.parametrize("edit, message", [
    ('<turbulence model = "Smagorinsky">', '<turbulence model = "WALE">'),
    ("<model_constant>      0.1   </model_constant>", ""),
    ("<dynamic_viscosity>      15.89e-6            </dynamic_viscosity>",
     "<dynamic_viscosity>      0.0            </dynamic_viscosity>"),
    ("<model_constant>      0.1   </model_constant>",
     "<model_constant>      0.1   </model_constant><FilterScalar><name>f</name></FilterScalar>"),
])
def test_turbulence_bad_input(tmp_path, edit, message):
    """Bad <turbulence> input: one line naming the file, line and what is accepted."""
    import pathlib
    from framework.controller import Controller
    from framework.problemspec import InputError
    old, new = edit, message
    deck = (pathlib.Path(__file__).parent / "uintah_reference" / "impVortices_smag_explicit.ups").read_text()
    assert old in deck
    (tmp_path / "d.ups").write_text(deck.replace(old, new))
    with pytest.raises(InputError) as e:
        Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "run.uda"))
    text = str(e.value)
    assert "\n" not in text.strip() and "d.ups" in text, text


def test_germano_two_ranks_equal_one_rank(tmp_path):
    """The dynamic model's 27-cell filter reaches two ghost layers (face velocities three), the
    plane averages sum over patches of both ranks: the explicit impVortices_dyn copy on 2 ranks
    is bitwise the one-rank answer (5 steps, 2 of them sampled by planeAvgTurbFluxes)."""
    import pathlib
    from framework.archiver import DataArchive
    from tests.conftest import pysus_ranks
    deck = pathlib.Path(__file__).parent / "uintah_reference" / "impVortices_dyn_explicit.ups"
    text = deck.read_text().replace("<max_Timesteps>  10 <", "<max_Timesteps>  5 <")
    path = tmp_path / "dyn.ups"
    path.write_text(text)
    runs = {}
    for n in (1, 2):
        r = pysus_ranks(path, "--filebase", tmp_path / f"r{n}.uda", np_=n)
        assert r.returncode == 0, r.stderr[-2000:]
        runs[n] = DataArchive(tmp_path / f"r{n}.uda")
    for lab in ("vel_CC", "press_CC", "temp_CC", "turb_viscosity_CC", "total_viscosity_CC", "SGS_ReynoldsStress",
                "variance_vel_CC", "vel_CC_prime", "temp_CC_turbFlux"):
        assert np.array_equal(runs[1].read(lab, 0, -1)[0], runs[2].read(lab, 0, -1)[0]), lab
    # planeAvgTurbFluxes' files (plane sums over both ranks' patches, written by rank 0)
    one = sorted((tmp_path / "r1.uda" / "planarAveTurbFluxes").rglob("*_0"))
    assert len(one) == 10
    for f in one:
        assert f.read_text() == (tmp_path / "r2.uda" / f.relative_to(tmp_path / "r1.uda")).read_text()
