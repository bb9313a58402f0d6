"""The Hooke stiffness kn (and a time step) equivalent to Hertz for a Grains3D-style table of kn, en:

    dem-hooke-from-hertz --E 6.3e10 --nu 0.24 --density 2500 --diameter 0.003 --v 1 [--en 0.9] [--wall]
        [--steps 50]

(also `python -m dem.tools.hooke_from_hertz ...`, or `python tools/hooke_from_hertz.py ...` in the source
tree.) kn gives the same largest overlap as Hertz-Mindlin of that material for two equal spheres (or a
sphere and a wall of the same material, --wall) meeting at speed v; dt is the Hooke contact time / steps.
The function is dem.law.hertz.hooke_equivalent; docs/hertz.md gives the formulas."""
import argparse
import sys

from dem.errors import DemError
from dem.law.hertz import hooke_equivalent


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--E", type=float, required=True, help="Young's modulus (Pa)")
    p.add_argument("--nu", type=float, required=True, help="Poisson's ratio")
    p.add_argument("--density", type=float, required=True, help="particle density (kg/m^3)")
    p.add_argument("--diameter", type=float, required=True, help="particle diameter (m)")
    p.add_argument("--v", type=float, required=True, help="impact speed (m/s): the relative speed of the pair")
    p.add_argument("--en", type=float, default=1.0, help="restitution, for the Hooke contact time (default 1)")
    p.add_argument("--wall", action="store_true", help="a sphere on a wall instead of two equal spheres")
    p.add_argument("--steps", type=float, default=50.0, help="time steps per Hooke contact (default 50)")
    a = p.parse_args(argv)
    try:
        r = hooke_equivalent(a.E, a.nu, a.density, a.diameter, a.v, en=a.en, wall=a.wall, steps=a.steps)
    except DemError as e:
        p.error(str(e))
    print(f"kn {r['kn']:.6g}        # N/m: pair_coeff I J kn {r['kn']:.6g} en {a.en:g} ...")
    print(f"timestep {r['dt']:.6g}  # s: Hooke contact time {r['tc_hooke']:.6g} / {a.steps:g}")
    print(f"# Hertz at {a.v:g} m/s: largest overlap {r['delta_max']:.6g} m, elastic contact time "
          f"{r['tc_hertz']:.6g} s; Rayleigh time {r['rayleigh']:.6g} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
