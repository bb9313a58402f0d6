# cython: language_level=3
"""The coefficient columns of law.pxd, for Python (dem_contact)."""

COLUMNS = {"KN": C_KN, "BETA": C_BETA, "MU": C_MU, "GAMMA_T": C_GAMMA_T, "KS": C_KS, "MU_ROLL": C_MU_ROLL,
           "EN": C_EN, "BETA_T": C_BETA_T,
           "MODEL": C_MODEL, "YSTAR": C_YSTAR, "GSTAR": C_GSTAR, "MODEL_HOOKE": MODEL_HOOKE,
           "MODEL_HERTZ": MODEL_HERTZ, "NCOEFF": NCOEFF, "XI_WIDTH": XI_WIDTH}
