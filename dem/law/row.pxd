# cython: language_level=3
"""The coefficient row of a type pair (or of a wall and a particle type): which part of each family acts,
and their coefficients, resolved once at `init` (materials mixed, damping from en). Kernels pass a pointer
to the row; the parts read it. Python reads these numbers from dem.law (COLUMNS), rows are made by
dem.law.row."""

cdef enum:                 # columns of a coefficient row
    C_KN = 0               # Hooke: normal stiffness (N/m)
    C_BETA = 1             # gamma_n / omega0, from en (eq. 16)
    C_MU = 2               # Coulomb friction
    C_GAMMA_T = 3          # tangential damping (1/s)
    C_KS = 4               # tangential spring (N/m), part T_SPRING
    C_MU_ROLL = 5          # rolling resistance coefficient
    C_EN = 6               # restitution (kept for contact times)
    C_BETA_T = 7           # tangential damping as a fraction of critical (Descantes 2022 Table 2: 1)
    C_NORMAL = 8           # the normal part: N_HOOKE, N_HERTZ, N_JKR, N_DMT
    C_YSTAR = 9            # Hertz family: effective Young's modulus Y* (Pa)
    C_GSTAR = 10           # Hertz family: effective shear modulus G* (Pa)
    C_DAMPING = 11         # the damping part: D_RESTITUTION, D_HERTZ
    C_TANGENTIAL = 12      # the tangential part: T_SPRING, T_MINDLIN, T_VISCOUS
    C_LIMIT = 13           # 1: the damping never makes the normal force attractive (Descantes 2022 eq. 3)
    C_ROLLING = 14         # the rolling part: R_CONSTANT, R_EPSD, R_EPSD2
    C_ETA_ROLL = 15        # EPSD: rolling damping as a fraction of critical
    C_W = 16               # JKR, DMT: work of adhesion w (J/m^2)
    C_H_ROLL = 17          # history: offset of the rolling spring (3 values), or -1
    C_H_BOND = 18          # history: offset of the bond flag (forces beyond contact), or -1
    C_COHESION = 19        # the cohesion part: K_NONE, K_CAPILLARY
    C_LIQUID = 20          # capillary: liquid volume of the bridge (m^3)
    C_TENSION = 21         # capillary: surface tension of the liquid (N/m)
    C_ANGLE = 22           # capillary: contact angle (radians)
    C_PLAN = 23            # P_GRAINS3D, P_HERTZ_MINDLIN: a common combination (compose.pxd skips what it lacks)
    C_COHESION_K = 24      # sjkr: cohesion energy density k (J/m^3)
    C_ALPHA = 25           # D_TSUJI: gamma_n / sqrt(kn m*), Tsuji's alpha(en) (dem.law.tsuji_alpha)
    C_TWISTING = 26        # the twisting part: TW_NONE, TW_MARSHALL, TW_SDS
    C_K_TWIST = 27         # twisting sds: spring (N m / rad)
    C_GAMMA_TWIST = 28     # twisting sds: dashpot (N m s / rad)
    C_MU_TWIST = 29        # twisting sds: the largest torque per unit normal load (m)
    C_H_TWIST = 30         # history: offset of the twist angle (1 value), or -1
    NCOEFF = 31

cdef enum:                 # normal parts (c[C_NORMAL])
    N_HOOKE = 0            # kn delta
    N_HERTZ = 1            # 4/3 Y* sqrt(R*) delta^(3/2)
    N_JKR = 2              # Johnson-Kendall-Roberts: acts beyond contact until the pull-off distance
    N_DMT = 3              # Derjaguin-Muller-Toporov: Hertz minus 2 pi w R* while in contact

cdef enum:                 # damping parts (c[C_DAMPING]), all from en
    D_RESTITUTION = 0      # 2 beta sqrt(kn m*): the exact restitution of a Hooke spring (Grains3D eq. 16)
    D_HERTZ = 1            # 2 sqrt(5/6) beta sqrt(3/2 kn m*): LIGGGHTS's model hertz
    D_TSUJI = 2            # alpha(en) sqrt(kn m*): Tsuji et al. (1992) as LAMMPS's damping tsuji

cdef enum:                 # tangential parts (c[C_TANGENTIAL])
    T_SPRING = 0           # history spring ks (and dashpot), capped by Coulomb (Grains3D)
    T_MINDLIN = 1          # history spring kt = 8 G* a, capped by Coulomb (Hertz-Mindlin)
    T_VISCOUS = 2          # dashpot capped by Coulomb, no history (Descantes 2022 eq. 3)

cdef enum:                 # rolling parts (c[C_ROLLING])
    R_CONSTANT = 0         # mu_roll R* |F_n| against the relative spin (none when mu_roll = 0)
    R_EPSD = 1             # elastic-plastic spring-dashpot (Ai et al. 2011 model C)
    R_EPSD2 = 2            # elastic-plastic spring, no dashpot (LIGGGHTS's epsd2)

cdef enum:                 # twisting parts (c[C_TWISTING]): a torque about n against the relative spin
    TW_NONE = 0
    TW_MARSHALL = 1        # spring-dashpot-slider from the tangential part over the contact disc (Marshall 2009)
    TW_SDS = 2             # spring-dashpot-slider of the row's own k_twist, gamma_twist, mu_twist

cdef enum:                 # cohesion parts (c[C_COHESION]): forces added to the normal part's
    K_NONE = 0
    K_CAPILLARY = 1        # a liquid bridge (Willett et al. 2000), from touch to its rupture distance
    K_SJKR = 2             # simplified JKR: k times the contact area, in contact only (LIGGGHTS's sjkr)

cdef enum:                 # plans (c[C_PLAN], set by dem.law.prepare)
    P_GENERAL = 0          # any parts: cohesion, the damping limit, forces apart and the bond are checked
    P_GRAINS3D = 1         # hooke + restitution + spring, no cohesion, no limit
    P_HERTZ_MINDLIN = 2    # hertz + hertz damping + mindlin, no cohesion, no limit

cdef enum:
    XI_WIDTH = 3           # values of the tangential spring history xi (first in a contact's history)
    ROLL_WIDTH = 3         # values of the rolling spring history (a torque)
    BOND_WIDTH = 1         # the bond flag
    TWIST_WIDTH = 1        # the twist angle
