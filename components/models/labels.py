"""Labels of the models (Uintah's ICELabel modelMass_src ..., the burn models' and MassMomEng_src's own)."""
from framework import labels as L
from framework.variables import VarType

CC, P, R = VarType.CC, VarType.PARTICLE, VarType.REDUCTION

modelMass_src = L.create("modelMass_src", CC)           # product: mass gained this step (kg per cell)
modelMom_src = L.create("modelMom_src", CC, (3,))       # product: momentum gained
modelEng_src = L.create("modelEng_src", CC)             # product: internal energy gained (J)
modelVol_src = L.create("modelVol_src", CC)             # product: volume created (m^3), at (p, T_product)
burnArea = L.create("Simple_Burn::onSurface", CC)       # reactant: burning-surface area per cell (m^2)
totalMassBurned = L.create("totalMassBurned", R, reduction="sum")       # this step, all patches (kg)
totalHeatReleased = L.create("totalHeatReleased", R, reduction="sum")   # this step: burned * Enthalpy (J)
numPPC = L.create("SteadyBurn.numPPC", CC)              # reactant: its particles per cell
burningCell = L.create("SteadyBurn.BurningCell", CC)    # reactant: 1 where a cell burns this step
surfTemp = L.create("SteadyBurn.SurfTemp", CC)          # reactant: burning-surface temperature Ts (K)
totalMass_src = L.create("TotalMass_src", R, reduction="sum")          # MassMomEng_src: this step's sums over
totalMom_src = L.create("TotalMom_src", R, (3,), reduction="sum")      # the source cells (kg, kg m/s, J)
totalEng_src = L.create("TotalEng_src", R, reduction="sum")
ubBurningCell = L.create("UnsteadyBurn.BurningCell", CC)  # reactant: steps a cell has burned in a row
ubSurfTemp = L.create("UnsteadyBurn.SurfTemp", CC)        # reactant: burning-surface temperature Ts (K)
ubSurfTempGrad = L.create("UnsteadyBurn.SurfTempGrad", CC)  # reactant: solid's surface gradient beta (K/m)
# the same two carried on the reactant's particles (and their pre-relocation twins)
ubPartSurfTemp = L.create("UnsteadyBurn.PartSurfTemp", P)
ubPartSurfTempPre = L.create("UnsteadyBurn.PartSurfTemp+", P)
ubPartSurfTempGrad = L.create("UnsteadyBurn.PartSurfTempGrad", P)
ubPartSurfTempGradPre = L.create("UnsteadyBurn.PartSurfTempGrad+", P)
jwlF = L.create("F", CC)                                  # JWLpp: the reactant's reacted fraction
jwlDelF = L.create("delF", CC)                            # JWLpp: its growth this step
# DDT1 (Uintah's names): per reactant cell
ddtBurning = L.create("burning", CC)                      # 2 conductive, 3 convective burn this step (else 0)
ddtCriteria = L.create("BurningCriteria", CC)             # the burn logic's verdict (same codes)
ddtDetonating = L.create("detonating", CC)                # 1 where the JWL++ detonation burns
ddtDetLocalTo = L.create("detLocalTo", CC)                # 1 next to a cell above ThresholdPressureJWL
ddtSurfTemp = L.create("surfaceTemp", CC)                 # WSB surface temperature of a burning cell (K)
ddtOnSurface = L.create("onSurface", CC)                  # burning-surface area of a conductive cell (m^2)
ddtCracked = L.create("crackedEnough", CC)                # 1 where a particle's crack is wide enough to burn in
ddtInductionTime = L.create("inductionTime", CC)          # DDT1: a warming cell's ignition delay (s)
ddtCountTime = L.create("countTime", CC)                  # DDT1: how long it has warmed (s)
