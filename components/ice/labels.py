"""ICE variable labels, named as in Uintah's ICELabel.cc.

Per-material CC variables are stored for every ICE material; the single-field
pressure variables (press_equil_CC, press_CC, delP_Dilatate, press*_FC) live under
material 0, as Uintah's "press_matl". Vectors have shape (3,) in 1D and 2D too.
"""
from framework import labels as L
from framework.variables import VarType

CC, X, Y, Z, R = VarType.CC, VarType.SFCX, VarType.SFCY, VarType.SFCZ, VarType.REDUCTION

# state carried from step to step
rho_CC = L.create("rho_CC", CC)                 # macroscopic density (mass / cell volume)
vel_CC = L.create("vel_CC", CC, (3,))
temp_CC = L.create("temp_CC", CC)
sp_vol_CC = L.create("sp_vol_CC", CC)           # specific volume 1/rho_micro
press_CC = L.create("press_CC", CC)             # material 0

# cv and gamma per cell (Uintah's computeThermoTransportProperties): with a <SpecificHeatModel>
# (specific_heat.py) specific_heat = cv(temp_CC) of the step's start, which the step reads;
# else the material's <specific_heat>; gamma is <gamma> (computed only when saved)
specific_heat = L.create("specific_heat", CC)
gamma = L.create("gamma", CC)

# step 2: equilibration (eq. 13)
press_equil_CC = L.create("press_equil_CC", CC)
vol_frac_CC = L.create("vol_frac_CC", CC)
speedSound_CC = L.create("speedSound_CC", CC)
TMV_CC = L.create("TMV_CC", CC)                 # MPMICE: the cell's total material volume (material 0)

# step 3: face velocities (eq. 28) and their exchange
FC_VEL = (L.create("uvel_FC", X), L.create("vvel_FC", Y), L.create("wvel_FC", Z))
FC_VEL_ME = (L.create("uvel_FCME", X), L.create("vvel_FCME", Y), L.create("wvel_FCME", Z))

# steps 5-6: pressure increment (eq. 29-30), face pressure (eq. 31)
delP_Dilatate = L.create("delP_Dilatate", CC)
delP_MassX = L.create("delP_MassX", CC)          # diagnostic: the pressure that mass exchange adds
term2 = L.create("term2", CC)                    # diagnostic: sumKappa delP_MassX (Uintah's impICE)
PRESS_FC = (L.create("pressX_FC", X), L.create("pressY_FC", Y), L.create("pressZ_FC", Z))

# optional physics sources (viscous stress, heat conduction)
viscous_src_CC = L.create("viscous_src_CC", CC, (3,))
viscosity = L.create("viscosity", CC)            # dynamic viscosity (<dynamic_viscosity> and its models)
thermalCond = L.create("thermalCond", CC)        # thermal conductivity (a model's per cell; gasCombustion)
heatCond_src_CC = L.create("heatCond_src_CC", CC)
turb_viscosity_CC = L.create("turb_viscosity_CC", CC)      # <turbulence>: the subgrid-scale viscosity
total_viscosity_CC = L.create("total_viscosity_CC", CC)    # and molecular + subgrid-scale (turbulence.py)
TAU_FC = tuple(L.create(f"tau_{a}_FC", t, (3,)) for a, t in (("X", X), ("Y", Y), ("Z", Z)))   # diagnostic

# steps 8-11: Lagrangian values (eq. 35-37), exchange (38-39), specific volume (40)
mass_L_CC = L.create("mass_L_CC", CC)
mom_L_CC = L.create("mom_L_CC", CC, (3,))
mom_source_CC = L.create("mom_source_CC", CC, (3,))   # diagnostic: dt (-grad p V + viscous + m g)
int_eng_L_CC = L.create("int_eng_L_CC", CC)
mom_L_ME_CC = L.create("mom_L_ME_CC", CC, (3,))
int_eng_L_ME_CC = L.create("eng_L_ME_CC", CC)       # Uintah's name
sp_vol_L_CC = L.create("sp_vol_L_CC", CC)       # material volume m*v, advected
sp_vol_src_CC = L.create("sp_vol_src_CC", CC)   # diagnostic: ((m v)^L - m v) / (rho V), eq. 40's source
# <conserveTotalEnergy> (pysus extension): Lagrangian total energy m (e + |u|^2/2)
tot_eng_L_CC = L.create("tot_eng_L_CC", CC)
tot_eng_L_ME_CC = L.create("tot_eng_L_ME_CC", CC)

# diagnostics
mach = L.create("mach", CC)
TotalMass = L.create("TotalMass", R, reduction="sum")
KineticEnergy = L.create("KineticEnergy", R, reduction="sum")
TotalIntEng = L.create("TotalIntEng", R, reduction="sum")
TotalMomentum = L.create("TotalMomentum", R, (3,), reduction="sum")

# LODI faces (lodi.py): the largest Mach number on each face's extra cells at the start of a
# step (Uintah's maxMach_xminus ... maxMach_zplus, faces in the order x-, x+, y-, y+, z-, z+), and
# the wave amplitudes L1..L5 after advection (Uintah's Li1..Li5, computed only when saved)
maxMach_faces = L.create("maxMach_faces", R, (6,), reduction="max")
LODI_Li = tuple(L.create(f"Li{k}", CC, (3,)) for k in range(1, 6))
