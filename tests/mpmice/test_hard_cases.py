"""Hard cases for MPMICE (issue: "hard cases stay stable"), each a short 1D run of a few seconds.

Built from inputs/MPMICE/piston.ups (steel in air, K = 1e15 momentum exchange, so every
case also exercises the huge exchange coefficient and a solid whose sound speed, 4.4 km/s,
is 13 times the gas's):

- tension next to compression: the two halves of a steel slab fly apart at 50 m/s inside
  air at 10 atm, with and without heat exchange. The slab goes into tension (2 GPa mean
  stress, rho c u with c = sqrt((K + 4G/3)/rho) = 4.4 km/s), the gas around it is
  compressed. Without Uintah's clamp of press_CC at 1e-12 this case stopped at step 2 (the
  pressure went to -1.7e7 Pa in the stretched cells and the energy source V theta kappa p
  delP heated the expanding trace gas to 2.5e6 K). Now pressures stay positive and finite,
  the total energy (steel KE + strain energy + gas) stays between -10 % and +1 % (measured
  +0.6 % .. -7 %: dissipated, not created), the total momentum stays zero (the set-up is
  mirror-symmetric) and the masses are exact.
  Without heat exchange the case runs to 60 us only: the release wave comes back to the
  stretched cells after 2 x 0.125 m / 4.4 km/s = 56 us, their pressure rises from 1e-4 Pa
  (tension) to 1e7 Pa in five steps (up to x25 a step), and the energy source
  V theta kappa p delP, linear in delP, multiplies the trace gas's temperature by
  1 + (gamma-1)/gamma (p/p_eq) delP/p_eq (x180 in one step at delP/p_eq = 24, where the
  adiabat gives x2.5); it reaches 2e8 K at 60 us and 1.3e10 K at 200 us, and as the time
  step counts every material's sound speed, delT falls from 2.8e-6 s to 2e-9 s (35,395
  steps to 200 us). Uintah's sus does the same on this deck (with <contact> null and the
  y, z faces symmetric): delT 2.8e-6 s until 56 us, then 1e-8 s, 2.2e-9 s at 200 us
  (27,406 steps), trace gas 2.8e9 K at 60 us, 1.3e10 K at 200 us; its energy sum, taken as
  _total_energy takes it, stays between -9.7 % and 0 % of its first output. The first 60 us
  hold what the test checks (the tension, the compressed gas, the release and the first
  jump of the trace gas) in 77 steps.
  With <MPMICE><adiabatic_compression>true (pysus's option, not Uintah's: the compressed gas's
  flow work at most the adiabat's, components/mpmice/adiabatic.py) the heat-0 case runs to
  200 us in 393 steps, the trace gas below 5e5 K until 190 us and 2.2e7 K at 200 us; the
  energy sum peaks at +3.1 % (at 130 us; the steel's KE + strain energy, which MPM takes in
  steps of 2.8e-6 s here: with <delt_max> 2e-8 the same run stays within -0.1 % .. +1.0 % to
  140 us).
  With heat exchange (1e10, run to 200 us) the trace gas reaches 1.1e6 K, and the energy
  sum (which counts no heat in the steel) peaks at +5.1 %; with pysus's trace rule as well
  (<MPMICE><trace_temperatures>true: the trace gas takes the steel's temperature) below
  2e4 K and +2.9 %.
- vanishing mass: a thin slab crosses cells at 300 m/s, so the solid's mass in the cells it
  leaves drops to zero (and the gas's in the cells it enters drops to the trace floor);
  volume fractions still sum to one, the gas mass in the closed box is conserved, the slab
  keeps moving (the gas cannot stop 8900 kg/m^3 of steel in 0.3 ms).
- a very soft solid (E = 3 MPa, sound speed 18 m/s, 19 times slower than the gas) pushed
  by air at 10 atm: it compresses strongly (J well below 1) and stays finite.
"""
import os

import numpy as np
import pytest

PISTON = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "piston.ups")
A, DX = 0.025 * 0.025, 1.0 / 40


def _deck(tmp_path, name, replacements):
    text = open(PISTON).read()
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / f"{name}.ups"
    path.write_text(text)
    return path


def _run(path):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(str(path), quiet=True, filebase=str(path.with_suffix(".uda")))
    c.run()
    return DataArchive(c.archiver.dir)


SAVE_MORE = ('<save label="p.mass"/>',
             '<save label="p.mass"/><save label="p.stress"/><save label="p.deformationMeasure"/>'
             '<save label="temp_CC"/>')


def _slab_geom(label, lo, hi, u):
    return (f'<geom_object><box label="{label}"><min> [{lo},-1,-1] </min><max> [{hi},1,1] </max></box>'
            f'<res> [2,1,1] </res><velocity> [{u},0,0] </velocity><temperature> 300 </temperature>'
            '</geom_object>')


SLAB = """<geom_object>
          <box label="slab"><min> [0.375,-1,-1] </min><max> [0.625,1,1] </max></box>
          <res> [2,1,1] </res>
          <velocity> [0,0,0] </velocity>
          <temperature> 300 </temperature>
        </geom_object>"""


def _gas_everywhere(p_left_factor=10.0):
    """Both gas pieces at the left state (10 atm), so only the slab's motion drives the flow."""
    return [("<density> 1.1792946927374306 </density>", f"<density> {1.1792946927374306 * p_left_factor} </density>"),
            ("<pressure> 101325.0 </pressure>", f"<pressure> {101325.0 * p_left_factor} </pressure>")]


def _gas_mass(archive, i):
    rho, _ = archive.read("rho_CC", 1, i)
    return float(rho.sum() * DX * A)


def _total_energy(ar, i):
    """KineticEnergy (the steel's and the gas's, as Uintah's MPMICE sums them) + StrainEnergy of
    the steel plus the gas's internal energy."""
    rho, _ = ar.read("rho_CC", 1, i)
    T, _ = ar.read("temp_CC", 1, i)
    gas = float((rho * 716.0 * T).sum() * DX * A)

    def at(name):          # each .dat by its own times (KineticEnergy has no t = 0 line, as sus's)
        t, v = ar.reduction(name)
        return float(v[int(np.argmin(np.abs(np.asarray(t) - ar.times[i])))])
    return at("KineticEnergy") + at("StrainEnergy") + gas


RULES = {True: "trace_temperatures", "adiabatic": "adiabatic_compression"}     # <MPMICE> options (module doc)


@pytest.mark.parametrize("heat,trace_rule", [("0", False), ("1e10", False), ("1e10", True), ("0", "adiabatic")])
def test_solid_in_tension_next_to_compressed_gas(tmp_path, heat, trace_rule):
    halves = _slab_geom("left_half", 0.375, 0.5, -50.0) + _slab_geom("right_half", 0.5, 0.625, 50.0)
    tag = RULES.get(trace_rule)
    rule = [("</MaterialProperties>", f"</MaterialProperties><MPMICE><{tag}>true</{tag}></MPMICE>")] if tag else []
    end = "6.0e-5" if (heat, trace_rule) == ("0", False) else "2.0e-4"   # module doc: the trace gas's delT after 56 us
    ar = _run(_deck(tmp_path, "tension", rule + [
        (SLAB, halves), ("<maxTime> 5.0e-4 </maxTime>", f"<maxTime> {end} </maxTime>"),
        ("<outputInterval> 1.0e-4 </outputInterval>", "<outputInterval> 1.0e-5 </outputInterval>"),
        ("<heat> [0] </heat>", f"<heat> [{heat}] </heat>"),
        ('<save label="p.mass"/>', '<save label="p.mass"/><save label="KineticEnergy"/><save label="StrainEnergy"/>'),
        SAVE_MORE] + _gas_everywhere()))
    parts0, parts = ar.particles(0, 0), ar.particles(0, -1)
    early = ar.particles(0, 2)                           # t = 20 us, before the release waves meet
    mean_stress = early["p.stress"][:, [0, 1, 2], [0, 1, 2]].sum(axis=1) / 3.0
    assert mean_stress.max() > 1e9                       # pulled apart: tension of order rho c u = 2e9 Pa
    for i in range(1, len(ar.times)):
        p, _ = ar.read("press_CC", 0, i)
        assert np.all(np.isfinite(p)) and p.min() > 0.0  # Uintah's clamp: never negative
        for name in ("temp_CC", "rho_CC", "vel_CC"):
            for m in (0, 1):
                assert np.all(np.isfinite(ar.read(name, m, i)[0]))
    peak = max(float(ar.read("press_CC", 0, i)[0][ar.read("vol_frac_CC", 1, i)[0] > 0.5].max())
               for i in range(1, len(ar.times)))
    assert peak > 1.01 * 1013250.0                       # the gas ahead of each half is compressed (~ rho c u)
    E = [_total_energy(ar, i) for i in range(1, len(ar.times))]
    grow = {("0", False): 1.01, ("1e10", False): 1.06, ("1e10", True): 1.05, ("0", "adiabatic"): 1.04}[
        heat, trace_rule]                                # module doc
    t_gas = max(float(ar.read("temp_CC", 1, i)[0].max()) for i in range(1, len(ar.times)))
    if trace_rule is True:                               # pysus's rule: the trace gas at the steel's temperature
        assert t_gas < 2e4
    if trace_rule == "adiabatic":                        # 1.3e10 K and 35,395 steps without it, as sus's
        assert t_gas < 1e8 and ar.timesteps[-1] < 1000
    assert max(E) < grow * E[0] and min(E) > 0.9 * E[0]  # measured down to -7 %: dissipated
    mom = float((parts["p.mass"] * parts["p.velocity"][:, 0]).sum())
    rho, _ = ar.read("rho_CC", 1, -1)
    u, _ = ar.read("vel_CC", 1, -1)
    mom += float((rho * u[..., 0]).sum() * DX * A)
    scale = float((parts0["p.mass"] * np.abs(parts0["p.velocity"][:, 0])).sum())
    # mirror symmetry: zero but for round-off, which the cells' rho_CC carry from step 1 (the particles'
    # mapping is not bitwise mirrored); the trace gas at 1e6 K of the heat-exchange case amplifies it
    # to 2.5e-9 with the solids' equilibration started at their EOS density (1e-16 from the particles')
    assert abs(mom) < (1e-8 if (heat, trace_rule) == ("1e10", False) else 1e-9) * scale
    assert parts["p.mass"].sum() == pytest.approx(parts0["p.mass"].sum(), rel=1e-14)
    assert _gas_mass(ar, -1) == pytest.approx(_gas_mass(ar, 1), rel=1e-12)


def test_solid_leaves_cells_empty(tmp_path):
    thin = _slab_geom("thin", 0.3, 0.35, 300.0)
    around = [("<max> [0.375,1,1] </max>", "<max> [0.3,1,1] </max>"),      # the air fills the rest
              ("<min> [0.625,-1,-1] </min>", "<min> [0.35,-1,-1] </min>")]
    ar = _run(_deck(tmp_path, "vanish", [(SLAB, thin), ("<maxTime> 5.0e-4 </maxTime>", "<maxTime> 3.0e-4 </maxTime>"),
                                         SAVE_MORE] + around + _gas_everywhere(1.0)
                    + [("<density> 11.792946927374306 </density>", "<density> 1.1792946927374306 </density>"),
                       ("<pressure> 1013250.0 </pressure>", "<pressure> 101325.0 </pressure>")]))
    parts0, parts = ar.particles(0, 0), ar.particles(0, -1)
    moved = parts["p.x"][:, 0].mean() - parts0["p.x"][:, 0].mean()
    assert moved > 2 * DX                                # crossed cells, leaving them empty of steel
    assert parts["p.velocity"][:, 0].min() > 250.0       # air at 1 atm cannot stop it in 0.3 ms
    th = ar.read("vol_frac_CC", 0, -1)[0] + ar.read("vol_frac_CC", 1, -1)[0]
    assert np.abs(th - 1.0).max() < 1e-9
    rho_s, _ = ar.read("rho_CC", 0, -1)
    assert (rho_s < 1e-6 * 8900.0).sum() > 20            # most cells hold no steel
    assert _gas_mass(ar, -1) == pytest.approx(_gas_mass(ar, 0), rel=1e-12)
    for name in ("press_CC", "temp_CC", "vel_CC"):
        assert np.all(np.isfinite(ar.read(name, 0 if name == "press_CC" else 1, -1)[0]))


def test_very_soft_solid_in_gas(tmp_path):
    soft = [("<density> 8900.0 </density>", "<density> 1000.0 </density>"),
            ("<bulk_modulus> 117.0e9 </bulk_modulus>", "<bulk_modulus> 2.0e6 </bulk_modulus>"),
            ("<shear_modulus> 43.8e9 </shear_modulus>", "<shear_modulus> 1.0e6 </shear_modulus>"),
            ("<maxTime> 5.0e-4 </maxTime>", "<maxTime> 1.0e-3 </maxTime>"), SAVE_MORE]
    ar = _run(_deck(tmp_path, "soft", soft))
    parts = ar.particles(0, -1)
    F = parts["p.deformationMeasure"]
    J = np.linalg.det(F)
    assert np.all(np.isfinite(J)) and J.min() > 0.0
    assert J.min() < 0.9                                 # 10 atm on a 2 MPa-bulk solid squeezes it hard
    p, _ = ar.read("press_CC", 0, -1)
    assert np.all(np.isfinite(p)) and p.min() > 0.0
    th = ar.read("vol_frac_CC", 0, -1)[0] + ar.read("vol_frac_CC", 1, -1)[0]
    assert np.abs(th - 1.0).max() < 1e-9
