# cython: language_level=3
"""The coefficient columns and part codes of row.pxd, for Python (dem.law)."""
from dem.law.row cimport *

COLUMNS = {"KN": C_KN, "BETA": C_BETA, "MU": C_MU, "GAMMA_T": C_GAMMA_T, "KS": C_KS, "MU_ROLL": C_MU_ROLL,
           "EN": C_EN, "BETA_T": C_BETA_T, "NORMAL": C_NORMAL, "YSTAR": C_YSTAR, "GSTAR": C_GSTAR,
           "DAMPING": C_DAMPING, "TANGENTIAL": C_TANGENTIAL, "LIMIT": C_LIMIT, "ROLLING": C_ROLLING,
           "ETA_ROLL": C_ETA_ROLL, "W": C_W, "H_ROLL": C_H_ROLL, "H_BOND": C_H_BOND, "COHESION": C_COHESION,
           "LIQUID": C_LIQUID, "TENSION": C_TENSION, "ANGLE": C_ANGLE, "PLAN": C_PLAN, "COHESION_K": C_COHESION_K,
           "ALPHA": C_ALPHA, "TWISTING": C_TWISTING, "K_TWIST": C_K_TWIST, "GAMMA_TWIST": C_GAMMA_TWIST,
           "MU_TWIST": C_MU_TWIST, "H_TWIST": C_H_TWIST, "NCOEFF": NCOEFF,
           "XI_WIDTH": XI_WIDTH, "ROLL_WIDTH": ROLL_WIDTH, "BOND_WIDTH": BOND_WIDTH, "TWIST_WIDTH": TWIST_WIDTH}
PARTS = {"normal": {"hooke": N_HOOKE, "hertz": N_HERTZ, "jkr": N_JKR, "dmt": N_DMT},
         "damping": {"restitution": D_RESTITUTION, "hertz": D_HERTZ, "tsuji": D_TSUJI},
         "tangential": {"spring": T_SPRING, "mindlin": T_MINDLIN, "viscous": T_VISCOUS},
         "rolling": {"constant": R_CONSTANT, "epsd": R_EPSD, "epsd2": R_EPSD2},
         "cohesion": {"none": K_NONE, "capillary": K_CAPILLARY, "sjkr": K_SJKR},
         "twisting": {"none": TW_NONE, "marshall": TW_MARSHALL, "sds": TW_SDS}}
PLANS = {"general": P_GENERAL, "grains3d": P_GRAINS3D, "hertz_mindlin": P_HERTZ_MINDLIN}
