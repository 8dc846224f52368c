"""The <Models> of an ICE deck (MPMICE: PassiveScalar, TracerParticles; it reads its reaction models
in __init__.py).

    PassiveScalar             a scalar carried by a material's flow (passive_scalar.py)
    mass_momentum_energy_src  fans and heaters: fixed velocity/temperature regions (mass_mom_eng_src.py)
    TracerParticles           massless particles carried by the flow (tracer_particles.py)
    gasCombustion             a reacting gas mixture: its species as scalars, finite-rate chemistry,
                              the material's caloric EOS (gas_combustion.py)

`read_ice_models` returns them grouped by what the ICE component does with them: the
scalars it transports, the sources it adds to the Lagrangian state, and the particle models.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .gas_combustion import GasCombustion
from .mass_mom_eng_src import MassMomEngSrc
from .passive_scalar import PassiveScalar
from .tracer_particles import TracerParticles

ICE_MODELS = {"PassiveScalar": PassiveScalar, "mass_momentum_energy_src": MassMomEngSrc,
              "TracerParticles": TracerParticles, "gasCombustion": GasCombustion}


@dataclass
class IceModels:
    scalars: list = field(default_factory=list)      # PassiveScalar
    sources: list = field(default_factory=list)      # MassMomEngSrc
    tracers: list = field(default_factory=list)      # TracerParticles


def read_ice_models(root, ice, geo, others=()) -> IceModels:
    """The models of an ICE deck's <Models> (none without the block), in deck order. others: the
    model types another reader takes (MPMICE's reactions, __init__.py), skipped here; in MPMICE
    (ice.n_before > 0) PassiveScalar and TracerParticles are ICE's, carried by an ICE material."""
    out = IceModels()
    node = root.child("Models")
    if node is None:
        return out
    t0 = root.child("Time").get("initTime", "float", 0.0) if root.child("Time") is not None else 0.0
    for m in node.children("Model"):
        if ice.n_before:
            kind = m.attr("type")
            here = ("PassiveScalar", "TracerParticles") + tuple(others)
            if kind not in here:
                alone = " (available for ICE alone)" if kind in ICE_MODELS else ""
                raise m.error(f'attribute type="{kind}" is not accepted in MPMICE{alone}; accepted: ' + ", ".join(here))
        else:
            kind = m.attr("type", choices=tuple(ICE_MODELS))
        if kind in others:
            continue
        if kind == "PassiveScalar":
            out.scalars.append(PassiveScalar(m, ice, geo))
            if out.scalars[-1].matl < ice.n_before:
                raise m.child("PassiveScalar").child("material").error(
                    "a PassiveScalar is carried by an ICE material's flow; accepted: an ICE material")
        elif kind == "mass_momentum_energy_src":
            out.sources.append(MassMomEngSrc(m, ice, geo))
        elif kind == "gasCombustion":
            out.sources.append(GasCombustion(m, ice, geo))
            out.scalars.extend(out.sources[-1].species)
        else:
            out.tracers.append(TracerParticles(m, ice, geo, t0))
            if out.tracers[-1].matl < ice.n_before:
                raise m.child("TracerParticles").child("material").error(
                    "tracer particles are carried by an ICE material's flow; accepted: an ICE material")
    if not (out.scalars or out.sources or out.tracers or others):
        raise node.error("<Models> without a <Model type=...>; accepted for ICE: " + ", ".join(ICE_MODELS))
    names = [s.name for s in out.scalars]
    for s in out.scalars:
        if names.count(s.name) > 1:
            raise node.error(f"two PassiveScalar models name their scalar {s.name}; accepted: distinct names")
    matls = [s.matl for s in out.sources]
    if len(set(matls)) < len(matls):
        raise node.error("two source models (mass_momentum_energy_src, gasCombustion) act on one material; "
                         "accepted: one per material (a MassMomEng_src's <sources> may hold several regions)")
    if len(out.tracers) > 1:
        raise node.error(f"{len(out.tracers)} TracerParticles models; accepted: one")
    for tr in out.tracers:
        tr.resolve()
    return out
