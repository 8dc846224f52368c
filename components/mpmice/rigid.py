"""rmpmice: solids whose motion is prescribed (Uintah's RigidMPM inside MPMICE).

In `<SimulationComponent type="rmpmice">` Uintah never evaluates a solid's constitutive
model: RigidMPM carries the particle stress forward (zero), puts no internal force and
no stable-timestep limit, and the solid moves with its own velocity, or as
`<contact type="rigid">` (SpecifiedBodyContact) prescribes: its velocity until
<stop_time>, <velocity_after_stop> after. Here a solid of an rmpmice deck is read with
any constitutive model type Uintah has; only the tags of the model's EOS act (with
<MPMICE><gas_start>geometry Uintah's: MPMICE calls the deck model's computePressEOSCM in the
equilibration pressure; with the particle start, the default here, <bulk_modulus> in a
Murnaghan stand-in: setup.py solid_eos); the model's other tags have no effect and are
reported at start-up. The stress is the rigid model's (zero).
"""
from __future__ import annotations

from components.mpm.materials import Material

# the constitutive-model tags that act in rmpmice: those of the models' EOS (setup.solid_eos)
ACTS = ("bulk_modulus", "useModifiedEOS", "K", "gamma", "specific_heat", "usePlasticity", "flow_model",
        "jwl_A", "jwl_B", "jwl_R1", "jwl_R2", "jwl_om", "PR", "G1", "G2", "G3", "G4", "G5",
        "useJWLEOS", "A", "B", "R1", "R2", "om", "Cv")


class _RigidModel:
    """A <constitutive_model> node that reads as type="rigid"."""

    def __init__(self, cm):
        self._cm = cm

    def __getattr__(self, name):
        return getattr(self._cm, name)

    def attr(self, name, *args, **kwargs):
        value = self._cm.attr(name, *args, **kwargs)
        return "rigid" if name == "type" else value


class _RigidView:
    """A <material> node whose <constitutive_model> reads as type="rigid"."""

    def __init__(self, node):
        self._node = node

    def __getattr__(self, name):
        return getattr(self._node, name)

    def child(self, tag, required=False):
        c = self._node.child(tag, required)
        return _RigidModel(c) if tag == "constitutive_model" and c is not None else c


class RigidSolid(Material):
    """An MPM material of an rmpmice deck: zero stress whatever model the deck names."""

    def __init__(self, node, index, geom_reader, with_color):
        cm = node.child("constitutive_model", required=True)
        self.model_asked = cm.attr("type")
        super().__init__(_RigidView(node), index, geom_reader, with_color)
        self.no_effect = [c.tag for c in cm.children() if c.tag not in ACTS]
        for c in cm.children():
            c.mark_used()


def activate_master_contact(contact):
    """SpecifiedBodyContact prescribes its master material even when no other MPM material
    is listed (Uintah's <materials> of an MPMICE deck may name only ICE ones, dropped here)."""
    if contact.type == "rigid" and not contact.active and contact.materials == (contact.master,):
        contact.active = True
        contact.needs_time = True


def describe(mpm, rigid_matls):
    """The start-up line of an rmpmice deck: how each solid moves and which tags do nothing."""
    c = mpm.contact
    parts = []
    for m in rigid_matls:
        mat = mpm.materials[m]
        if c.active and c.type == "rigid" and c.master == m:
            if c.profile is not None:
                how = "the <filename> velocity profile"
            else:
                how = "its own initial velocity"
            if c.stop_time != float("inf"):
                after = ", ".join(f"{v:g}" for v in c.vel_after_stop)
                how += f" until stop_time {c.stop_time:g}, then [{after}]"
            if c.materials == (m,):
                how += " (no other MPM material: <direction> has no effect)"
        else:
            how = "its own initial velocity"
        s = f"'{mat.name.strip()}' moves with {how}"
        asked = getattr(mat, "model_asked", "rigid")
        if asked != "rigid":
            s += (f"; constitutive_model {asked} acts only through its EOS in the equilibration (with "
                  "<gas_start>geometry; else <bulk_modulus> in a Murnaghan stand-in)")
        if getattr(mat, "no_effect", None):
            s += "; no effect: " + ", ".join(mat.no_effect)
        parts.append(s)
    return "pysus: rmpmice: prescribed solids (zero stress, no delT limit): " + "; ".join(parts)
