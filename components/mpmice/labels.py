"""MPMICE labels (Uintah's MPMICELabel): solid state at cell centres and the coupling terms.

The MPM materials' rho_CC, vel_CC and temp_CC of the current step are put in the NEW
warehouse under ICE's labels (as Uintah does), so ICE's multi-material tasks see every
material; the solid's specific volume from its particles has its own label because
the equilibration computes sp_vol_CC for all materials.
"""
from framework import labels as L
from framework.variables import VarType

CC, P = VarType.CC, VarType.PARTICLE

cMass = L.create("cMass", CC)                      # step 1: solid mass per cell (eq. 22, then NC -> CC)
sp_vol_mpm_CC = L.create("sp_vol_mpm_CC", CC)      # step 1: solid volume / solid mass per cell
mom_mpm_CC = L.create("mom_MPM_CC", CC, (3,))      # step 8: sum_w m_i v*_i (without the pressure source)
dVdt_CC = L.create("dVdt_CC", CC, (3,))           # step 10 -> 13: solid velocity rate from exchange and grad p
pPressure = L.create("p.pressure", P)             # step 7: p - p_ref at the particles (mean pressure)

# Uintah's diagnostic labels (ICELabel / MPMICELabel), computed only when a <save> names them
mom_source_CC = L.create("mom_source_CC", CC, (3,))   # steps 8-9: momentum sources (grad p, viscous) dt
intE_source_CC = L.create("intE_source_CC", CC)       # steps 8-9: energy sources (p dV work, ADD_HEAT) dt
Tdot = L.create("Tdot", CC)                           # step 10: (T after exchange - T start of step) / dt

# the solid's heat exchange (step 10 -> 13), only when a solid exchanges heat with a fluid
dTdt_CC = L.create("dTdt_CC", CC)                     # step 10: solid temperature rate from the exchange
dTdt_NC = L.create("dTdt_NC", VarType.NC)             # step 13: its mean over the cells around a node

# the particles' conservation sums (MPM's TotalMass, KineticEnergy, TotalMomentum); the saved sums
# add the fluids' (MPMICE::sumConservedQuantities), as Uintah's MPM and ICE put into one reduction
R = VarType.REDUCTION
mpm_TotalMass = L.create("MPM.TotalMass", R, reduction="sum")
mpm_KineticEnergy = L.create("MPM.KineticEnergy", R, reduction="sum")
mpm_TotalMomentum = L.create("MPM.TotalMomentum", R, (3,), reduction="sum")
