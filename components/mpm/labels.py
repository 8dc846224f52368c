"""MPM variable labels, named as in Uintah's MPMLabel.

Particle state carried between steps: p.x, p.velocity, p.mass, p.volume, p.stress,
p.deformationMeasure (F), p.particleID, p.externalforce (pressure BCs only), p.size
(uGIMP half-widths, GIMP only), p.color (withColor only) and per-model state
(plastic strain, elastic left Cauchy-Green tensor, internal energy, membrane tangent/thickness, accumulated strain
energy of rate models), p.temperature (with heat conduction or MPMICE heat
exchange, thermal.py), p.loadCurveID (load curves, 3 ids), p.surface (friction_LR).
Each has a "+" twin written by the update before relocation.
Grid: g.mass, g.velocity, g.volume, g.externalforce, g.internalforce,
g.velocity_star, g.acceleration, g.temperature, g.temperatureRate. Reductions as in Uintah.
"""
import numpy as np

from framework import labels as L
from framework.variables import VarType

P, NC, R = VarType.PARTICLE, VarType.NC, VarType.REDUCTION


def _pair(name, shape=(), dtype=np.float64):
    """The carried particle label and its pre-relocation twin."""
    return L.create(name, P, shape, dtype), L.create(name + "+", P, shape, dtype)


pX, pXpre = _pair("p.x", (3,))
pVelocity, pVelocityPre = _pair("p.velocity", (3,))
pMass, pMassPre = _pair("p.mass")
pVolume, pVolumePre = _pair("p.volume")
pStress, pStressPre = _pair("p.stress", (3, 3))
pF, pFPre = _pair("p.deformationMeasure", (3, 3))
pID, pIDPre = _pair("p.particleID", dtype=np.int64)
pExtForce, pExtForcePre = _pair("p.externalforce", (3,))
pSize, pSizePre = _pair("p.size", (3,))
# CPDI with <smoothcyl> particles: the columns are the half-vectors of the undeformed domain (m),
# half the edges of the particle's ring sector (Uintah's p.size matrix times dx)
pSizeMatrix, pSizeMatrixPre = _pair("p.sizeMatrix", (3, 3))
pColor, pColorPre = _pair("p.color")
pPlasticStrain, pPlasticStrainPre = _pair("p.plasticStrain")
pBElBar, pBElBarPre = _pair("p.bElBar", (3, 3))       # elastic volume-preserving b (UCNH plasticity)
pIntEnergy, pIntEnergyPre = _pair("p.internalEnergy")
pTangent, pTangentPre = _pair("p.tangent", (3,))
pThickness, pThicknessPre = _pair("p.thickness")
pStrainEnergy, pStrainEnergyPre = _pair("p.strainEnergy")
pLoadCurveID, pLoadCurveIDPre = _pair("p.loadCurveID", (3,))     # up to 3 load-curve ids (pressure.py)
pExternalHeatRate, pExternalHeatRatePre = _pair("p.externalHeatRate")   # W, <heat_flux> (pressure.py)
pSurface, pSurfacePre = _pair("p.surface")        # 1 on its object's surface (friction_LR prominence)
pTemperature, pTemperaturePre = _pair("p.temperature")      # heat conduction / MPMICE (thermal.py)
pTemperatureGradient, pTemperatureGradientPre = _pair("p.temperatureGradient", (3,))   # K/m, grad T* of the last step (thermal.py)
pPlasticStrainRate, pPlasticStrainRatePre = _pair("p.plasticStrainRate")   # elastic_plastic_hp
pEnergy, pEnergyPre = _pair("p.energy")                  # elastic_plastic_hp: specific internal energy
pStrainRate, pStrainRatePre = _pair("p.strainRate")      # elastic_plastic_hp: sqrt(2/3) |D|
pDisp, pDispPre = _pair("p.displacement", (3,))          # x - X: <RunMMSProblem> (mms.py) or saved
pQ, pQPre = _pair("p.q")                                 # <artificial_viscosity>: bulk viscosity (Pa)
pScaleFactor, pScaleFactorPre = _pair("p.scalefactor", (3, 3))   # F diag(2 p.size): the deformed particle (saved)
STATE = {"p.plasticStrain": (pPlasticStrain, pPlasticStrainPre),   # per-model state
         "p.internalEnergy": (pIntEnergy, pIntEnergyPre),
         "p.pStatedata_vs": _pair("p.pStatedata_vs", (5, 3, 3)),        # visco_scram: Maxwell stresses
         "p.crackRad": _pair("p.crackRad"),                              # visco_scram: crack radius
         "p.tempPrevious": _pair("p.tempPrevious"),                      # visco_scram: T one step back
         "p.plasticStrainRate": (pPlasticStrainRate, pPlasticStrainRatePre),
         "p.energy": (pEnergy, pEnergyPre),
         "p.strainRate": (pStrainRate, pStrainRatePre),
         "p.porosity": _pair("p.porosity"),              # elastic_plastic_hp with gurson or erosion: void fraction
         "p.bElBar": (pBElBar, pBElBarPre),                              # comp_neo_hook_plastic, UCNH
         "p.epsf": _pair("p.epsf"),                      # damage.py: Brittle's energy threshold, ThresholdVar's
                                                         # failure stress or strain
         "p.damage": _pair("p.damage"),                  # damage.py: Brittle's, Johnson-Cook's damage
         "p.localizedMPM": _pair("p.localizedMPM"),      # 1 once ThresholdVar or elastic_plastic_hp localized it
         "p.timeofloc": _pair("p.timeofloc"),            # damage.py: when it localized (erosion)
         "p.yieldStress": _pair("p.yieldStress"),        # UCNH with yield_distrib uniform: drawn yield stress
         "p.progressF": _pair("p.progressF"),            # jwlpp_mpm: burned fraction
         "p.progressdelF": _pair("p.progressdelF")}      # jwlpp_mpm: its increment of the last step
# ArenaSoil (arena_soil.py): Uintah's labels; its plastic strain tensor (Uintah's p.plasticStrain)
# has its own name beside the J2 models' scalar p.plasticStrain
for _name in ("p.plasticStrainTensor", "p.porePressure", "p.stressQS"):
    STATE[_name] = _pair(_name, (3, 3))
for _name in ("p.plasticCumEqStrain", "p.plasticVolStrain", "p.capX", "p.porosity", "p.saturation", "p.p3",
              "p.elasticVolStrain", "p.COHER", "p.TGROW", "p.ArenaPEAKI1", "p.ArenaFSLOPE", "p.ArenaSTREN",
              "p.ArenaYSLOPE", "p.ArenaBETA", "p.ArenaCR", "p.ArenaT1", "p.ArenaT2"):
    STATE[_name] = _pair(_name)
# elastic_plastic_hp with <deviatoric_stress_model type="hypoViscoElastic">: the deviatoric
# stress of Maxwell element j (Uintah's names sigmaDevj, sigmaDevj+)
MAX_MAXWELL_ELEMENTS = 8
for _j in range(MAX_MAXWELL_ELEMENTS):
    STATE[f"sigmaDev{_j}"] = _pair(f"sigmaDev{_j}", (3, 3))
# <UseGradientEnhancedVelocityProjection>: L_p of the particle's last step (Uintah's carried
# p.velGrad; here p.velGrad is this step's L_p, not carried)
pVelGradLast, pVelGradLastPre = _pair("p.velGradLast", (3, 3))
pdTdt = L.create("p.dTdt", P)                      # elastic_plastic_hp: the model's temperature rate (not carried)
pVelGrad = L.create("p.velGrad", P, (3, 3))        # L_p of this step (not carried)
pTangentNbr = L.create("p.tangentFromNeighbours", P, (3,))   # membrane: from the chain (not carried)

gMass = L.create("g.mass", NC)
gVolume = L.create("g.volume", NC)
gVelocity = L.create("g.velocity", NC, (3,))
gExtForce = L.create("g.externalforce", NC, (3,))
gIntForce = L.create("g.internalforce", NC, (3,))
gStressFS = L.create("g.stressFS", NC, (3, 3))     # mass-weighted nodal stress (output)
gVelocityL = L.create("g.velocity_L", NC, (3,))     # remapped updated velocity (MUSL, 004 eq. 13)
gSurfNorm = L.create("g.surfNorm", NC, (3,))       # outward unit normal (friction contact)
gNormTraction = L.create("g.normtraction", NC)     # n . sum S sigma . n (friction_bard: < 0 pressed)
gAlphaMaterial = L.create("g.alphaMaterial", NC)           # friction_LR: the alpha material, -99 none (matl 0)
gNormAlphaToBeta = L.create("g.normAlphaToBeta", NC, (3,))  # friction_LR: unit normal alpha -> beta (matl 0)
gMatlProminence = L.create("g.matlProminence", NC)         # friction_LR: extreme face projection, -99 none
gColor = L.create("g.color", NC)                           # friction_LRVar: mass-weighted p.color
gVelSPSSP = L.create("g.velSPSSP", NC, (3,))      # XPIC(2): sum S m_p (sum S v_i)_p / m_i (tasks.py)
gVelocityStar = L.create("g.velocity_star", NC, (3,))
gAcceleration = L.create("g.acceleration", NC, (3,))
gTemperature = L.create("g.temperature", NC)            # mass-weighted nodal temperature (thermal.py)
gTemperatureRate = L.create("g.temperatureRate", NC)    # conduction dT/dt at the nodes (thermal.py)
gTemperatureNoBC = L.create("g.temperatureNoBC", NC)    # g.temperature before the Temperature BCs
gThermalContactRate = L.create("g.thermalContactTemperatureRate", NC)   # <thermal_contact> (thermal.py)

KineticEnergy = L.create("KineticEnergy", R, reduction="sum")
StrainEnergy = L.create("StrainEnergy", R, reduction="sum")
TotalMass = L.create("TotalMass", R, reduction="sum")
TotalMomentum = L.create("TotalMomentum", R, (3,), reduction="sum")
CenterOfMassPosition = L.create("CenterOfMassPosition", R, (3,), reduction="sum")
ThermalEnergy = L.create("ThermalEnergy", R, reduction="sum")   # sum m_p cv T_p (thermal.py)
RigidReactionForce = L.create("RigidReactionForce", R, (3,), reduction="sum")     # specified contact (contact.py)
RigidReactionTorque = L.create("RigidReactionTorque", R, (3,), reduction="sum")
SumTransmittedForce = L.create("SumTransmittedForce", R, (3,), reduction="sum")   # force-transmitting material
# force-transmitting materials (materials.py): per material m, [4m] its nodal mass and [4m+1:4m+4]
# its nodal external force summed over the level; the contact's part of the force comes apart
FTMForce = L.create("MPM.ftmMassAndForce", R, (64,), reduction="sum")
FTMContactForce = L.create("MPM.ftmContactForce", R, (3,), reduction="sum")
WaveSpeed = L.create("MPM.waveSpeed", R, (3,), reduction="max")
# Uintah's StrainEnergy (the rate models' increments of the step, the others' totals) and its
# sum over the steps; pysus's StrainEnergy is the total strain energy of every model
StepStrainEnergy = L.create("MPM.stepStrainEnergy", R, reduction="sum")
AccStrainEnergy = L.create("AccStrainEnergy", R, reduction="max")
# <boundary_traction_faces> (boundary_tractions.py), per face in Uintah's order and names
BOUNDARY_FACES = ("xminus", "xplus", "yminus", "yplus", "zminus", "zplus")
BndyForce = [L.create(f"BndyForce_{f}", R, (3,), reduction="sum") for f in BOUNDARY_FACES]
BndyTraction = [L.create(f"BndyTraction_{f}", R, (3,), reduction="sum") for f in BOUNDARY_FACES]
BndyContactArea = [L.create(f"BndyContactArea_{f}", R, reduction="sum") for f in BOUNDARY_FACES]
BndyContactCellArea = [L.create(f"BndyContactCellArea_{f}", R, reduction="sum") for f in BOUNDARY_FACES]
# fluid points' artificial viscosity (004 eq. 24): per material m, [2m] the largest sound
# speed and [2m+1] the largest |div v| over the whole level (MPM materials <= 16)
AVScale = L.create("MPM.artificialViscosityScale", R, (32,), reduction="max")
PressureBCParticles = L.create("MPM.pressureBCParticles", R, (16,), reduction="sum")  # N per pressure BC
