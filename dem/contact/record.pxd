# cython: language_level=3
"""The contact record: what a geometry routine (sphere pair, GJK crust contact, a wall surface, later
component pairs and polyhedron face clipping) hands to the shared law (dem/law/apply.pxd).

`n` is the unit normal from body b to body a (the direction a must move to separate), `delta` the
overlap along it (> 0; < 0 only while a cohesive contact holds beyond touch, dem/law/law.pxd `reach`). The levers from each centre of mass to the contact point are either `p - x` (`central`
false: any shape) or along the normal (`central` true: spheres, -arm_a n from a and +arm_b n from b, exact
and cheaper; p is then unused). `key` names the contact inside its pair for the keyed history (0 for a
single contact); `weight` scales the law's force (1 for one point, 1/N_c for Grains3D's Model B average,
a per-point share for Descantes' law). `inertia` is the rolling inertia about the contact for the EPSD
rolling dashpot (dem/law/rolling.pxd): 1 / (1 / (I_a + m_a r_a^2) + 1 / (I_b + m_b r_b^2)) for spheres, 0
where a geometry gives none (no rolling dashpot)."""
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
    double inertia
