#!/usr/bin/env python
"""Write the triangle meshes of the example inputs into inputs/meshes/ as binary STL files (float32
coordinates, SI units: metres), through dem_walls.mesh (weld, then Mesh.write_stl). Every dimension is a
command-line option (`python tools/make_meshes.py --help`); the defaults make the committed files:

    python tools/make_meshes.py                 # all of them, into inputs/meshes/
    python tools/make_meshes.py --outdir /tmp/m --outlet 0.018

Circles are polygons of --segments (64) vertices on the circle (vertex i at angle 2 pi i / 64 from +x),
so a flat facet lies up to R (1 - cos(pi/64)) = 1.2e-3 R inside the true circle (60 um for R = 0.05 m).

1. hopper.stl: a conical hopper, axis z, open at both ends. A vertical cylinder of radius 0.05 m from
   z = 0.06 to 0.16 m sits on a cone going down from radius 0.05 at z = 0.06 to its exit radius D/2 at
   z = 0 (D = 0.04 m, --default-outlet). The cone height is fixed (0.06 m), so the half-angle follows
   from the exit: atan((0.05 - D/2) / 0.06), 26.6 degrees for D = 0.04 m. Each of the cylinder and the
   cone is one band of 64 quads (one quad from z = 0.06 to 0.16 on the cylinder, one from the exit to
   z = 0.06 on the cone), 2 triangles each: 256 triangles on 3 rings of 64 = 192 vertices, 448 edges,
   128 of them boundary edges (the exit rim and the top rim); 12,884 bytes. Normals point inwards,
   towards the axis, where the particles are. `--outlet D` (repeatable) also writes hoppers of other
   exits as hopper_dNN.stl (NN = D in mm).
2. orifice_d15.stl ... orifice_d30.stl: the flat bottom plate of the hopper with a round orifice: the
   ring at z = 0 from the orifice radius d/2 out to the hopper's exit radius (0.02 m), normals up (+z),
   for d = 15, 18, 21, 24, 27, 30 mm (--orifice, repeatable; the Beverloo study of inputs/in.hopper): one
   band of 64 quads, 128 triangles, 128 vertices, 64 + 64 boundary edges; 6,484 bytes.
3. mixer_vessel.stl: a cylinder closed at the bottom, open at the top: radius 0.05 m, from z = 0 to
   0.08 m. The bottom disc at z = 0 is a fan of 64 triangles about a vertex on the axis, the side wall a
   band of 64 quads (128 triangles): 192 triangles, 129 vertices, 320 edges, 64 boundary edges (the top rim);
   9,684 bytes. Normals point inwards (+z on the bottom, towards the axis on the side).
4. mixer_blades.stl: the impeller, as one triangle mesh of 5 closed boxes (12 triangles each, outward
   normals, boxes disjoint): 60 triangles, 40 vertices, 90 edges, no boundary edge; 3,084 bytes.
   * the shaft: a square prism on the axis, half-width 0.003 m, from z = 0.005 to 0.08 m;
   * 4 flat blades at 0, 90, 180 and 270 degrees about z: each a box 0.04 m long radially from r = 0.004
     m (to r = 0.044 m), 0.004 m thick (tangentially) and 0.02 m tall, from z = 0.008 to 0.028 m before
     pitching, pitched by 45 degrees about its own radial centre line (the radial line through the
     middle of the box, at z = 0.018 m), all in the same sense (right-hand rule about the outward radial
     direction), so that its vertical extent becomes about z = 0.0095 to 0.0265 m. The blades'
     inner ends (r = 0.004) stand 1 mm off the shaft's faces (at 0.003): the boxes do not touch.
"""
import argparse
import math
import os
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
try:                           # the installed plugins (the source tree's hold no compiled kernels)
    from dem_walls.mesh import rotation_about, weld
except ImportError:            # not installed: the source tree's pure-Python module
    sys.path[:0] = [p for p in (str(ROOT), str(ROOT / "plugins")) if p not in sys.path]
    from dem_walls.mesh import rotation_about, weld

ORIFICES = (0.015, 0.018, 0.021, 0.024, 0.027, 0.030)   # the Beverloo study (m)


def ring(radius, z, segments):
    """(segments, 3) points on a horizontal circle about the z axis, point i at angle 2 pi i / segments."""
    angle = 2.0 * np.pi * np.arange(segments) / segments
    return np.stack([radius * np.cos(angle), radius * np.sin(angle), np.full(segments, float(z))], axis=1)


def band(lower, upper, inward=True):
    """Triangles joining two rings of the same number of points (lower below upper), 2 per quad, normals
    towards the axis (inward) or away from it."""
    a, b = lower, np.roll(lower, -1, axis=0)          # a -> b counter-clockwise seen from +z
    d, c = upper, np.roll(upper, -1, axis=0)
    if inward:
        tris = [np.stack([a, c, b], axis=1), np.stack([a, d, c], axis=1)]
    else:
        tris = [np.stack([a, b, c], axis=1), np.stack([a, c, d], axis=1)]
    return np.concatenate(tris)


def disc(points, up=True):
    """A fan of triangles about the centre of a horizontal ring of points, normals +z (up) or -z."""
    centre = np.broadcast_to(points.mean(axis=0) * [0.0, 0.0, 1.0], points.shape)
    nxt = np.roll(points, -1, axis=0)
    return np.stack([centre, points, nxt] if up else [centre, nxt, points], axis=1)


def box(lo, hi, rotation=np.eye(3), pivot=(0.0, 0.0, 0.0)):
    """12 triangles of the axis-aligned box [lo, hi], then rotated by `rotation` about `pivot`; normals
    outward."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    corner = np.array([[(hi if (i >> axis) & 1 else lo)[axis] for axis in range(3)] for i in range(8)])
    # each face as a quad of corner ids (bit 0: x, bit 1: y, bit 2: z), counter-clockwise seen from outside
    faces = [(0, 4, 6, 2), (1, 3, 7, 5),       # -x, +x
             (0, 1, 5, 4), (2, 6, 7, 3),       # -y, +y
             (0, 2, 3, 1), (4, 5, 7, 6)]       # -z, +z
    tris = np.array([[corner[q[0]], corner[q[1]], corner[q[2]]] for q in faces] +
                    [[corner[q[0]], corner[q[2]], corner[q[3]]] for q in faces])
    pivot = np.asarray(pivot, float)
    return (tris - pivot) @ np.asarray(rotation, float).T + pivot


def hopper(outlet=0.02, radius=0.05, junction=0.06, top=0.16, segments=64):
    """Triangles of the hopper: the cone from radius outlet/2 at z = 0 to `radius` at z = junction, the
    cylinder up to z = top; normals inward."""
    if not 0.0 < outlet / 2.0 < radius:
        raise ValueError(f"outlet diameter {outlet} must be positive and below the hopper's {2 * radius}")
    if not 0.0 < junction < top:
        raise ValueError("need 0 < junction < top")
    rims = [ring(outlet / 2.0, 0.0, segments), ring(radius, junction, segments), ring(radius, top, segments)]
    return np.concatenate([band(rims[0], rims[1]), band(rims[1], rims[2])])


def orifice(diameter, rim=0.02, segments=64):
    """Triangles of the plate at z = 0 between the orifice (radius diameter/2) and the rim; normals +z."""
    if not 0.0 < diameter / 2.0 < rim:
        raise ValueError(f"orifice diameter {diameter} must be positive and below the plate's {2 * rim}")
    inner, outer = ring(diameter / 2.0, 0.0, segments), ring(rim, 0.0, segments)
    a, b = inner, np.roll(inner, -1, axis=0)
    d, c = outer, np.roll(outer, -1, axis=0)
    return np.concatenate([np.stack([a, c, b], axis=1), np.stack([a, d, c], axis=1)])


def mixer_vessel(radius=0.05, height=0.08, segments=64):
    """Triangles of the vessel: the bottom disc at z = 0 and the side wall up to z = height (open top);
    normals inward."""
    bottom = ring(radius, 0.0, segments)
    return np.concatenate([disc(bottom, up=True), band(bottom, ring(radius, height, segments))])


def mixer_blades(shaft_half_width=0.003, shaft_bottom=0.005, shaft_top=0.08, blades=4, blade_r0=0.004,
                 blade_length=0.04, blade_thickness=0.004, blade_height=0.02, blade_bottom=0.008,
                 pitch_deg=45.0):
    """Triangles of the shaft and the pitched blades, each a closed box with outward normals."""
    w = shaft_half_width
    parts = [box((-w, -w, shaft_bottom), (w, w, shaft_top))]
    zc = blade_bottom + blade_height / 2.0
    blade = box((blade_r0, -blade_thickness / 2.0, blade_bottom),
                (blade_r0 + blade_length, blade_thickness / 2.0, blade_bottom + blade_height),
                rotation_about((1.0, 0.0, 0.0), math.radians(pitch_deg)), pivot=(0.0, 0.0, zc))
    for k in range(blades):
        parts.append(blade @ rotation_about((0.0, 0.0, 1.0), 2.0 * math.pi * k / blades).T)
    return np.concatenate(parts)


def outlet_name(d, kind="hopper"):
    return f"{kind}_d{round(d * 1000.0, 6):g}.stl"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--outdir", default=str(ROOT / "inputs" / "meshes"), help="folder of the STL files")
    p.add_argument("--segments", type=int, default=64, help="polygon vertices per circle")
    p.add_argument("--outlet", type=float, action="append", metavar="D", default=[],
                   help="also a hopper of exit diameter D (m), written as hopper_dNN.stl (NN: D in mm); "
                        "repeatable")
    p.add_argument("--default-outlet", type=float, default=0.04, help="exit diameter of hopper.stl (m)")
    p.add_argument("--orifice", type=float, action="append", metavar="D",
                   help="orifice diameter (m) of a bottom plate, written as orifice_dNN.stl; repeatable; "
                        f"default: the Beverloo set {', '.join(map(str, ORIFICES))}")
    p.add_argument("--hopper-radius", type=float, default=0.05, help="radius of the hopper's cylinder (m)")
    p.add_argument("--hopper-junction", type=float, default=0.06, help="z of the cone-cylinder junction (m)")
    p.add_argument("--hopper-top", type=float, default=0.16, help="z of the hopper's top rim (m)")
    p.add_argument("--vessel-radius", type=float, default=0.05, help="mixer vessel radius (m)")
    p.add_argument("--vessel-height", type=float, default=0.08, help="mixer vessel height (m)")
    p.add_argument("--shaft-half-width", type=float, default=0.003, help="(m)")
    p.add_argument("--shaft-bottom", type=float, default=0.005, help="z of the shaft's lower end (m)")
    p.add_argument("--shaft-top", type=float, default=0.08, help="z of the shaft's upper end (m)")
    p.add_argument("--blades", type=int, default=4, help="number of blades")
    p.add_argument("--blade-r0", type=float, default=0.004, help="radius of the blades' inner ends (m)")
    p.add_argument("--blade-length", type=float, default=0.04, help="radial length (m)")
    p.add_argument("--blade-thickness", type=float, default=0.004, help="(m)")
    p.add_argument("--blade-height", type=float, default=0.02, help="before pitching (m)")
    p.add_argument("--blade-bottom", type=float, default=0.008, help="z of the blades' lower edge before "
                                                                      "pitching (m)")
    p.add_argument("--pitch", type=float, default=45.0, help="blade pitch about its radial axis (degrees)")
    a = p.parse_args(argv)
    if a.segments < 3:
        p.error("--segments must be at least 3")
    geometry = dict(radius=a.hopper_radius, junction=a.hopper_junction, top=a.hopper_top, segments=a.segments)
    jobs = [("hopper.stl", hopper(a.default_outlet, **geometry))]
    jobs += [(outlet_name(d), hopper(d, **geometry)) for d in a.outlet]
    jobs += [(outlet_name(d, "orifice"), orifice(d, a.default_outlet / 2.0, a.segments))
             for d in (a.orifice or ORIFICES)]
    jobs.append(("mixer_vessel.stl", mixer_vessel(a.vessel_radius, a.vessel_height, a.segments)))
    jobs.append(("mixer_blades.stl", mixer_blades(
        a.shaft_half_width, a.shaft_bottom, a.shaft_top, a.blades, a.blade_r0, a.blade_length,
        a.blade_thickness, a.blade_height, a.blade_bottom, a.pitch)))
    os.makedirs(a.outdir, exist_ok=True)
    for name, tris in jobs:
        mesh = weld(tris)
        path = os.path.join(a.outdir, name)
        mesh.write_stl(path)
        print(f"{path}: {len(mesh.triangles)} triangles, {len(mesh.vertices)} vertices, {mesh.nedges} edges, "
              f"{mesh.boundary_edges()} boundary edges, {os.path.getsize(path)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
