# cython: language_level=3
"""The contact record: what a geometry routine (sphere pair, GJK crust contact, a wall surface, later
component pairs and polyhedron face clipping) hands to the shared law (plugins/dem_contact/apply.pxd).

`n` is the unit normal from body b to body a (the direction a must move to separate), `delta` > 0 the
overlap along it. The levers from each centre of mass to the contact point are either `p - x` (`central`
false: any shape) or along the normal (`central` true: spheres, -arm_a n from a and +arm_b n from b, exact
and cheaper; p is then unused). `key` names the contact inside its pair for the keyed history (0 for a
single contact); `weight` scales the law's force (1 for one point, 1/N_c for Grains3D's Model B average,
a per-point share for Descantes' law)."""
cimport numpy as cnp

cdef struct Contact:
    double delta
    double n[3]
    double p[3]
    double arm_a
    double arm_b
    bint central
    cnp.int64_t key
    double weight
