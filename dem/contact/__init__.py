"""The home of contact geometry: where two bodies (or a body and a wall) touch, never how hard they push.

    _gjk.pyx / .pxd    GJK distance, EPA penetration, the Grains3D crust contact (convex cores + crust)
    _surface.pxd       a posed body against a wall surface (plane, inside of a cylinder): depth, normal, point
    record.pxd         the contact record a geometry routine produces (overlap, normal, point, levers, key,
                       weight), handed to the law by dem/law/apply.pxd

A new contact algorithm (GJK-TD, face clipping, component pairs of glued bodies) goes here as nogil
functions that fill `Contact` records; the law and the force bookkeeping stay in dem/law.
`geometry.py` (`dem.contact.geometry`) is the public Python entry point to these kernels (tests, tools, set-up).
"""
