# cython: language_level=3
"""Damping parts, all set from the restitution coefficient en: the normal dashpot gamma_n (force
gamma_n U_rn) from the normal stiffness kn, and the tangential dashpot nu_t (force nu_t U_rt) from the
tangential spring kt. beta = -ln en / sqrt(ln^2 en + pi^2) (c[C_BETA]).

D_RESTITUTION (Grains3D eq. 16): gamma_n = 2 beta sqrt(kn m*), the exact en of a Hooke spring;
    nu_t = 2 gamma_t m* + 2 beta_t sqrt(kn m*) (gamma_t in 1/s, beta_t a fraction of critical).
D_HERTZ (LIGGGHTS's model hertz, doc/gran_model_hertz.html of CFDEMproject/LIGGGHTS-PUBLIC):
    gamma_n = 2 sqrt(5/6) beta sqrt(3/2 kn m*), nu_t = 2 sqrt(5/6) beta sqrt(kt m*).
D_TSUJI (Tsuji, Tanaka & Ishida, Powder Technol. 71 (1992) 239, as LAMMPS's `damping tsuji`):
    gamma_n = alpha sqrt(kn m*), alpha Tsuji's polynomial of en (c[C_ALPHA], dem.law.tsuji_alpha);
    nu_t = gamma_n (Tsuji's choice, LAMMPS's x_gamma_t = 1)."""
from libc.math cimport sqrt
from dem.law.row cimport C_BETA, C_GAMMA_T, C_BETA_T, C_ALPHA, D_RESTITUTION, D_TSUJI


cdef inline double normal_damping(int part, const double* c, double kn, double meff, double* w) noexcept nogil:
    """gamma_n of the damping part `part`; w receives sqrt(kn m*) (the tangential dashpots of D_RESTITUTION
    and D_TSUJI reuse it)."""
    w[0] = sqrt(kn * meff)
    if part == D_RESTITUTION:
        return 2.0 * c[C_BETA] * w[0]
    if part == D_TSUJI:
        return c[C_ALPHA] * w[0]
    return 2.0 * sqrt(5.0 / 6.0) * c[C_BETA] * sqrt(1.5 * kn * meff)


cdef inline double tangential_damping(int part, const double* c, double w, double kt, double meff) noexcept nogil:
    """nu_t of the damping part `part`, with w = sqrt(kn m*) from normal_damping."""
    if part == D_RESTITUTION:
        return 2.0 * c[C_GAMMA_T] * meff + 2.0 * c[C_BETA_T] * w
    if part == D_TSUJI:
        return c[C_ALPHA] * w
    return 2.0 * sqrt(5.0 / 6.0) * c[C_BETA] * sqrt(kt * meff)
