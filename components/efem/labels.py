"""EFEM variable labels (names as a Uintah user would look for them).

State carried from step to step: vol_frac_CC (per material), stress_CC (per solid
material: [sxx, syy, sxy] of its Cauchy stress, Pa), hourglass_CC (per solid) and g.velocity (the one nodal
velocity of the mixture, material 0). Computed each step and saveable: press_CC (the
projection pressure), rho_CC (mixture density), mean_stress_CC (eq. 23 minus press_CC),
g.mass, and the reductions TotalMass and KineticEnergy.
"""
from framework import labels as L
from framework.variables import VarType

CC, NC, R = VarType.CC, VarType.NC, VarType.REDUCTION

# state
vol_frac_CC = L.create("vol_frac_CC", CC)                 # element density function phi_m (eq. 23)
stress_CC = L.create("stress_CC", CC, (3,))               # solid stress [sxx, syy, sxy] (eq. 22)
gVelocity = L.create("g.velocity", NC, (3,))              # nodal velocity (material 0)
hourglass_CC = L.create("hourglass_CC", CC, (2,))         # solid hourglass generalised forces (x, y)

# the Lagrangian step
rho_CC = L.create("rho_CC", CC)                           # mixture density sum_m phi_m rho_m (material 0)
fill_CC = L.create("efem.fill_CC", CC)                    # sum_m phi_m: 1 full, 0 void (material 0)
stress_L_CC = L.create("efem.stress_L_CC", CC, (3,))      # solid stress after eq. 22, before the remap
sigma_CC = L.create("efem.sigma_CC", CC, (3,))            # mixed element stress of eq. 23 (material 0)
hourglass_L_CC = L.create("efem.hourglass_L_CC", CC, (2,))  # solid hourglass forces before the remap
fluid_CC = L.create("efem.fluid_CC", CC)                  # sum of the fluids' phi_m (material 0)
excess_CC = L.create("efem.excess_CC", CC)                # sum_s phi_s e_v,s: the solids' volume strain (material 0)
hgForce_CC = L.create("efem.hgForce_CC", CC, (2,))        # sum_m phi_m Q_m (material 0)
gMass = L.create("g.mass", NC)                            # lumped nodal mass (material 0)
gVelocityStar = L.create("g.velocity_star", NC, (3,))     # eq. 14: velocity without the pressure
press_CC = L.create("press_CC", CC)                       # eq. 16 / 20 (material 0)
gVelocityL = L.create("efem.velocity_L", NC, (3,))        # eq. 17: the Lagrangian step's end velocity
mean_stress_CC = L.create("mean_stress_CC", CC, (3,))     # eq. 23 stress minus press_CC (saved only)

# the pressure system (solved by components.ice.solver.pcg)
press_A = L.create("efem.pressA", CC, (7,))               # 5-point stencil [kap, aW, aE, aS, aN, aB, aT]
press_rhs = L.create("efem.pressRHS", CC)

# the Eulerian (remap) step
dvel_CC = L.create("efem.dvel_CC", CC, (3,))              # change of the element velocity by the remap
mass_CC = L.create("efem.mass_CC", CC)                    # element mass after the remap (material 0)
mom_CC = L.create("efem.mom_CC", CC, (3,))                # element momentum at t = 0 (material 0)

# reductions
TotalMass = L.create("TotalMass", R, reduction="sum")
KineticEnergy = L.create("KineticEnergy", R, reduction="sum")
maxSpeed = L.create("efem.maxSpeed", R, reduction="max")
