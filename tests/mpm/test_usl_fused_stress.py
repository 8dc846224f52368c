"""USL with every material's model in transfer.FUSED (comp_neo_hook): the g2p pass
(interpolateToParticlesAndUpdate) computes the stress, strain energy and wave speed that
computeStressTensor computes otherwise; both paths give bitwise the same run (particle
state, reductions, time steps from the wave speed)."""
import numpy as np
import pytest

from components.mpm import labels as L
from components.mpm.component import MPM

from .helpers import MPM_INPUTS, deck_text, run

USL = "<interpolator>{0}</interpolator><stress_update>usl</stress_update>"
CASES = {       # disks: two materials and contact; thick_cylinder: pressure BC on load curves
    "disks_50x50": ({"maxTime": "0.05"}, "linear"),
    "thick_cylinder": ({"resolution": "[22,22,1]", "maxTime": "2e-4"}, "linear"),
}
LABELS = ("p.x", "p.particleID", "p.velocity", "p.stress", "p.volume", "p.deformationMeasure")


def _run(case, tmp_path, fused, monkeypatch):
    tags, interp = CASES[case]
    text = deck_text(MPM_INPUTS / f"{case}.ups", **tags)
    text = text.replace("<interpolator>linear</interpolator>", USL.format(interp), 1)
    saves = "".join(f'<save label="{lab}"/>' for lab in LABELS + ("StrainEnergy",) if f'"{lab}"' not in text)
    text = text.replace("</DataArchiver>", saves + "</DataArchiver>", 1)
    monkeypatch.setattr(MPM, "fuse_usl_stress", fused)
    ctl, da = run(text, tmp_path, f"{case}_{fused}")
    assert ctl.component.usl_fused is fused
    return ctl, da


@pytest.mark.parametrize("case", sorted(CASES))
def test_usl_fused_stress_bitwise(tmp_path, case, monkeypatch):
    (c1, a), (c2, b) = (_run(case, tmp_path, f, monkeypatch) for f in (True, False))
    assert c1.timestep == c2.timestep > 2 and c1.t == c2.t
    for lab in (L.StrainEnergy, L.WaveSpeed, L.KineticEnergy):
        assert np.array_equal(c1.final_dw.get_reduction(lab), c2.final_dw.get_reduction(lab)), lab.name
    assert np.array_equal(a.reduction("StrainEnergy")[1], b.reduction("StrainEnergy")[1])
    for m in range(len(a.materials)):
        pa, pb = a.particles(m, -1), b.particles(m, -1)
        assert len(pa["p.x"]) > 10
        for lab in LABELS:
            assert np.array_equal(pa[lab], pb[lab]), (case, m, lab)
