# cython: language_level=3
"""The wall kernel of every wall fix (wall/plane, wall/drum): particles of a group against a set of
surfaces (planes and the inside of cylinders, at rest or turning; dem/contact/_surface.pxd), one contact
per particle and surface (only the pairs within the neighbor skin, listed at each rebuild: `candidates`), the shared law (dem/law/apply.pxd: the row's parts; the fixes' `law descantes` makes
the rows Descantes' eq. 3) with m_ij = m_i.

Spheres: analytic, the contact point midway in the overlap, levers along the normal, rolling resistance
(mu_roll r_i |F_n| against the spin relative to the wall). Shaped particles: their true body's deepest
point (or `centroid`), lever from the centre of mass to it, no rolling resistance (Grains3D). A glued
composite touches a surface with each of its components (pieces): N_c contact points, each weighing 1/N_c
(Model B, `average`) or 1 (Model A, with the damping of m_i / N_c: eq. 18), levers from the composite's
centre of mass."""
cimport numpy as cnp
import numpy as np
from libc.stdlib cimport malloc, free
from dem._particles cimport ParticleView, Particles
from dem.contact.record cimport Contact
from dem.contact._surface cimport (Surface, S_CYLINDER, S_A, S_SIDE, S_POS, S_R, S_CENTRE, S_SPIN,
                                   S_OMEGA, S_NCOL, load_surface, bound_gap, sphere_normal, plane_touch,
                                   cylinder_touch, candidate_point, surface_depth)
from dem.shapes._support cimport ShapeRef, BOX, POLYHEDRON, MARGIN
from dem.shapes._table cimport (ShapeView, TableView, body_ref, equivalent_radius, pose_body, round_body, ncomponents,
                                component_row, pose_component)
from dem.law.apply cimport Body, apply_wall, bind_body, contact_radius
from dem.law.law cimport forget, holds
from dem.law.rolling cimport sphere_rolling_inertia
from dem.law.row cimport C_ETA_ROLL, NCOEFF
from dem.contact._polytope cimport Polytope, polytope_ref
from dem.contact._volume cimport OverlapVolume, overlap_halfspace
from dem.law.volume cimport reference_area, volume_record, volume_row, volume_couple, volume_twist

ctypedef cnp.int64_t i64

cdef enum:                 # what the kernel sums into stats
    W_CONTACTS = 0
    W_MAXOV = 1            # largest overlap / diameter
    W_ENERGY = 2           # elastic energy of the wall contacts
    W_TORQUE = 3           # torque of the turning surfaces on the particles about their axis
    W_WORST_I = 4          # the contact of the largest overlap: local particle index (-1: none)
    W_WORST_W = 5          # ... its surface
    W_WORST_GAP = 6        # ... distance of the particle's centre in front of the surface (< 0: behind)
    W_BEHIND = 7           # particles whose centre lies behind a surface (created there, or shot through)
    W_NSTAT = 8

# the enums above, for Python (dem_walls.wall_fix)
SURFACE = {"CYLINDER": S_CYLINDER, "A": S_A, "SIDE": S_SIDE, "POS": S_POS, "R": S_R, "CENTRE": S_CENTRE,
           "SPIN": S_SPIN, "OMEGA": S_OMEGA, "NCOL": S_NCOL}
STAT = {"CONTACTS": W_CONTACTS, "MAXOV": W_MAXOV, "ENERGY": W_ENERGY, "TORQUE": W_TORQUE, "WORST_I": W_WORST_I,
        "WORST_W": W_WORST_W, "WORST_GAP": W_WORST_GAP, "BEHIND": W_BEHIND, "NSTAT": W_NSTAT}

cdef enum:
    VOL_COLS = 5           # law volume, per contact point: V, |S|, the unit couple (3)

cdef double TIE_BIAS = 1e-9          # relative tilt of the support direction that breaks ties (plane_touch)
cdef double ZERO[3]
ZERO[:] = [0.0, 0.0, 0.0]


cdef inline void _wall_motion(const Surface* w, const double* q, const double* x, double* p, double* vw,
                              double* ww) noexcept nogil:
    """p: q relative to the turning axis (its axial part from the particle centre x), vw the surface velocity
    omega e x p at q, ww its spin omega e."""
    cdef double e[3]
    cdef int d
    for d in range(3):
        e[d] = 0.0
        p[d] = q[d] - w.centre[d]
    e[w.spin] = 1.0
    p[w.spin] = q[w.spin] - x[w.spin]
    vw[0] = w.omega * (e[1] * p[2] - e[2] * p[1])
    vw[1] = w.omega * (e[2] * p[0] - e[0] * p[2])
    vw[2] = w.omega * (e[0] * p[1] - e[1] * p[0])
    for d in range(3):
        ww[d] = w.omega * e[d]


cdef inline int _vertices_beyond(const ShapeRef* S, const double* R, const double* x, const Surface* W,
                                 const double* n, double delta, double tol, Contact* out) noexcept nogil:
    """The vertices of a posed polytope beyond the surface W (depth + tol > 0, tol a round-off margin so that
    a face level with the wall gives all its corners): one point each, at the vertex moved back to the
    middle of the overlap along n, all with the deepest overlap delta (Descantes: the points of a pair share
    its maximum overlap). Returns their number (>= 1: the deepest vertex is one of them)."""
    cdef double qv[3]
    cdef double dn[3]
    cdef double depth
    cdef int k = 0, m = 0, d
    for d in range(3):
        dn[d] = -n[d]
    while candidate_point(S, R, x, dn, k, qv):
        k += 1
        depth = surface_depth(W, qv)
        if depth + tol <= 0.0:
            continue
        out[m].delta = delta
        out[m].central = False
        for d in range(3):
            out[m].n[d] = n[d]
            out[m].p[d] = qv[d] + (depth - 0.5 * delta) * n[d]
        m += 1
    return m


def candidates(ParticleView view, int groupbit, const double[:, ::1] surfaces, double reach):
    """The (particle, surface) pairs that may touch before the next neighbor rebuild: the group's owned
    particles whose bounding sphere comes within `reach` of a surface (reach: the neighbor skin, which bounds
    a particle's move between rebuilds, plus how far beyond contact a row acts). Returns (particles (int32),
    offsets (int64, one more than particles), surfaces (int32)): particle k's surfaces are
    surfaces[offsets[k]:offsets[k + 1]], in increasing order. A pair left out is apart at every step until
    the next rebuild, and the kernel's test would find it so (and keep its history at zero)."""
    cdef Particles particles = view.p
    cdef const Particles* P = &particles
    cdef int i, w, nw = surfaces.shape[0], n = 0, m = 0
    cdef double rho
    cdef Surface* surf = <Surface*>malloc(max(nw, 1) * sizeof(Surface))
    if surf == NULL:
        raise MemoryError()
    for w in range(nw):
        load_surface(&surfaces[w, 0], &surf[w])
    pi = np.empty(P.nlocal, np.int32)
    off = np.zeros(P.nlocal + 1, np.int64)
    pw = np.empty(max(P.nlocal * nw, 1), np.int32)
    cdef int[::1] cpi = pi
    cdef cnp.int64_t[::1] coff = off
    cdef int[::1] cpw = pw
    with nogil:
        for i in range(P.nlocal):
            if not (P.mask[i] & groupbit):
                continue
            for w in range(nw):
                if bound_gap(&surf[w], &P.x[3 * i], &rho) < P.radius[i] + reach:
                    cpw[m] = w
                    m += 1
            if m > coff[n]:
                cpi[n] = i
                n += 1
                coff[n] = m
    free(surf)
    return pi[:n].copy(), off[:n + 1].copy(), pw[:m].copy()


def walls(ParticleView view, int groupbit, const double[:, ::1] surfaces, const double[:, :, ::1] coeff,
          ShapeView shapes, double[:, ::1] xi, int hw, bint use_history, bint bonds, double dt, bint advance,
          int point, bint average, bint volume, const int[::1] cand, const cnp.int64_t[::1] cand_off,
          const int[::1] cand_w, double[::1] stats):
    """surfaces: rows of S_NCOL values (SURFACE). coeff[w, type]: the law row of surface w. xi: hw history
    values (the law's width) per surface and piece per particle (piece c of surface w at hw (c nw + w);
    pieces beyond the array's width keep no history); bonds: whether a row acts beyond contact once touched.
    point: 0 the deepest point, 1 the centroid of the candidate
    points beyond the surface, 2 multipoint: a polytope (box, polyhedron) touches at every vertex beyond
    the surface, each with the deepest overlap and a weight 1/alpha, alpha the particle's points against
    that surface (Descantes 2022 eq. 3; no tangential spring: the points are not tracked). average: Model B
    over the pieces touching one surface. volume (the fix's `law volume`, dem/law/volume.pxd): a sharp
    polytope (or piece) touches through its overlap volume with the half-space behind the surface (planes
    only: wall/drum refuses the law), at one point. A sphere whose row acts beyond contact (JKR, a bridge) keeps its
    contact after it leaves the surface while bonded and within the row's reach. cand, cand_off, cand_w:
    the pairs to test (`candidates`, built at each neighbor rebuild); the others are apart. stats: the W_
    sums (STAT)."""
    cdef Particles particles = view.p          # local copies: no call can change them (kept in registers)
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef int i, w, d, s, c, q, npc, row, npt, nw = surfaces.shape[0], ci
    cdef cnp.int64_t wk
    cdef int hpieces = xi.shape[1] // (hw * max(nw, 1)) if use_history else 0
    cdef double gap, rho, energy = 0.0, torque = 0.0, ncont = 0.0, maxov = 0.0, ov
    cdef double worst_i = -1.0, worst_w = -1.0, worst_gap = 0.0, behind = 0.0
    cdef double p[3]
    cdef double vw[3]
    cdef double ww[3]
    cdef double out[6]
    cdef double R[9]
    cdef double Rc[9]
    cdef double xc[3]
    cdef double bias[3]
    cdef double weight
    cdef const double* x
    cdef Surface* surf = <Surface*>malloc(max(nw, 1) * sizeof(Surface))
    cdef bint centroid = point == 1, multi = point == 2
    cdef int maxp = 1, nvq, k
    cdef double depth, scale, aref
    cdef double Ru[9]
    cdef double vrow[NCOEFF]
    cdef Polytope poly
    cdef OverlapVolume vo
    for q in range(T.nrows):           # room for the points of one particle against one surface
        nvq = 0
        for c in range(ncomponents(T, q)):
            row = component_row(T, q, c)
            nvq += (8 if T.kind[row] == BOX else T.nv[row]) if multi else 1
            if nvq < c + 1:
                nvq = c + 1
        if nvq > maxp:
            maxp = nvq
    cdef Contact* pts = <Contact*>malloc(maxp * sizeof(Contact))
    cdef int* ptc = <int*>malloc(maxp * sizeof(int))
    cdef double* pvol = <double*>malloc(maxp * VOL_COLS * sizeof(double))    # law volume: V, |S|, couple
    if surf == NULL or pts == NULL or ptc == NULL or pvol == NULL:
        free(surf)
        free(pts)
        free(ptc)
        free(pvol)
        raise MemoryError()
    cdef const Surface* W
    cdef ShapeRef S
    cdef Contact con
    cdef Body A, B
    cdef bint posed, sphere
    cdef const double* cf
    for w in range(nw):
        load_surface(&surfaces[w, 0], &surf[w])
    con.key = 0
    con.weight = 1.0
    con.arm_b = 0.0
    con.inertia = 0.0
    with nogil:
        for ci in range(cand.shape[0]):
            i = cand[ci]
            if not (P.mask[i] & groupbit):
                continue
            x = &P.x[3 * i]
            s = P.shape[i]
            sphere = round_body(T, s)
            posed = False
            for wk in range(cand_off[ci], cand_off[ci + 1]):
                w = cand_w[wk]
                W = &surf[w]
                gap = bound_gap(W, x, &rho)
                # apart: a bonded sphere holds until its reach (R* = R_i), any other contact forgets
                if (gap >= P.radius[i] and not (bonds and sphere and holds(
                        &coeff[w, P.type[i], 0], &xi[i, hw * w] if hpieces > 0 else NULL, gap - P.radius[i],
                        equivalent_radius(T, s, P.radius[i])))) or (sphere and not sphere_normal(W, x, rho, con.n)):
                    if use_history and advance:
                        for c in range(hpieces):
                            forget(&xi[i, hw * (c * nw + w)], hw)
                    continue
                npt = 0
                if sphere:
                    pts[0].n[0], pts[0].n[1], pts[0].n[2] = con.n[0], con.n[1], con.n[2]
                    pts[0].central = True
                    pts[0].delta = P.radius[i] - gap
                    pts[0].arm_a = P.radius[i] - 0.5 * pts[0].delta
                    for d in range(3):
                        pts[0].p[d] = x[d] - pts[0].arm_a * pts[0].n[d]
                    ptc[0] = 0
                    pvol[0] = 0.0
                    npt = 1
                else:
                    if not posed:
                        pose_body(T, s, &P.quat[4 * i], P.radius[i], &S, R)
                        posed = True
                    npc = ncomponents(T, s)
                    for c in range(npc):
                        row = component_row(T, s, c)
                        body_ref(T, row, &S)
                        pose_component(T, s, c, R, x, Rc, xc)
                        for d in range(3):    # ties between equally deep points: away from the centre
                            bias[d] = TIE_BIAS * (xc[d] - x[d]) / P.radius[i]
                        pts[npt].central = False
                        if W.cylinder:
                            pts[npt].delta = cylinder_touch(&S, Rc, xc, W, centroid, 1e-9 * P.radius[i],
                                                            pts[npt].n, pts[npt].p)
                        else:
                            pts[npt].delta = plane_touch(&S, Rc, xc, W, centroid, 1e-9 * P.radius[i],
                                                         bias if npc > 1 else NULL, pts[npt].n, pts[npt].p)
                        if pts[npt].delta <= 0.0:
                            if use_history and advance and c < hpieces:
                                forget(&xi[i, hw * (c * nw + w)], hw)
                            continue
                        pvol[VOL_COLS * npt] = 0.0
                        if volume and (S.kind == BOX or S.kind == POLYHEDRON) and S.params[MARGIN] == 0.0:
                            # the half-space behind the plane, n . y <= n . q + delta / 2 (q lies midway in
                            # the overlap)
                            polytope_ref(&T.topo, row, &poly)
                            scale = P.radius[i] / T.radius[s]
                            for d in range(9):
                                Ru[d] = Rc[d] / scale
                            depth = pts[npt].delta
                            if (overlap_halfspace(&poly, Ru, scale, xc, pts[npt].n,
                                                  pts[npt].n[0] * pts[npt].p[0] + pts[npt].n[1] * pts[npt].p[1]
                                                  + pts[npt].n[2] * pts[npt].p[2] + 0.5 * depth, &vo) <= 0
                                    or not volume_record(&vo, xc, &pts[npt], &pvol[VOL_COLS * npt + 2],
                                                         &pvol[VOL_COLS * npt + 1])):
                                continue
                            pvol[VOL_COLS * npt] = vo.volume
                            ptc[npt] = c
                            npt += 1
                            continue
                        if multi and (S.kind == BOX or S.kind == POLYHEDRON) and S.params[MARGIN] == 0.0:
                            k = _vertices_beyond(&S, Rc, xc, W, pts[npt].n, pts[npt].delta, 1e-9 * P.radius[i],
                                                 &pts[npt])
                            for q in range(npt, npt + k):
                                ptc[q] = -1          # no spring
                                pvol[VOL_COLS * q] = 0.0
                            npt += k
                            continue
                        ptc[npt] = c
                        npt += 1
                weight = 1.0 / npt if (average or multi) and npt > 1 else 1.0
                for q in range(npt):
                    con.delta = pts[q].delta
                    con.central = pts[q].central
                    con.arm_a = pts[q].arm_a
                    for d in range(3):
                        con.n[d] = pts[q].n[d]
                        con.p[d] = pts[q].p[d]
                    con.key = ptc[q] if ptc[q] >= 0 else 0
                    con.weight = weight
                    ncont += 1.0
                    ov = con.delta / (2.0 * P.radius[i])
                    if ov > maxov:
                        maxov = ov
                        worst_i, worst_w, worst_gap = i, w, gap
                    if gap < 0.0:
                        behind += 1.0
                    if W.spin >= 0:
                        _wall_motion(W, con.p, x, p, vw, ww)
                        B.v = vw
                        B.w = ww
                    else:
                        B.v = ZERO
                        B.w = ZERO
                    B.s = NULL
                    bind_body(&A, P, i)
                    A.x = x
                    cf = &coeff[w, P.type[i], 0]
                    # the rolling inertia about the contact, I + m r^2 (the EPSD dashpot: spheres only)
                    con.inertia = sphere_rolling_inertia(P.rmass[i], P.radius[i]) if (
                        sphere and cf[C_ETA_ROLL] > 0.0) else 0.0
                    if pvol[VOL_COLS * q] > 0.0:     # law volume: the contact's own row and its couple
                        con.weight = 1.0
                        aref = reference_area(equivalent_radius(T, s, P.radius[i]), -1.0)
                        volume_row(cf, pvol[VOL_COLS * q + 1], aref, vrow)
                        volume_couple(cf, pvol[VOL_COLS * q], aref, &pvol[VOL_COLS * q + 2], &A, &B, True)
                        cf = vrow
                    energy += apply_wall(cf, &con, &A, &B,
                                         P.rmass[i] if average or npt == 1 else P.rmass[i] / npt,
                                         contact_radius(cf, sphere, equivalent_radius(T, s, P.radius[i]), -1.0),
                                         &xi[i, hw * (ptc[q] * nw + w)] if 0 <= ptc[q] < hpieces else NULL,
                                         dt, advance, out)
                    if pvol[VOL_COLS * q] > 0.0:
                        volume_twist(vrow, pvol[VOL_COLS * q + 1], P.rmass[i], &con, out, &A, &B, True)
                    if W.spin >= 0:   # torque about the turning axis: e . (p x F) + e . rolling torque
                        torque += p[(W.spin + 1) % 3] * out[(W.spin + 2) % 3] - p[(W.spin + 2) % 3] * out[(W.spin + 1) % 3]
                        torque += out[3 + W.spin]
    free(surf)
    free(pts)
    free(ptc)
    free(pvol)
    stats[W_CONTACTS] = ncont
    stats[W_MAXOV] = maxov
    stats[W_ENERGY] = energy
    stats[W_TORQUE] = torque
    stats[W_WORST_I] = worst_i
    stats[W_WORST_W] = worst_w
    stats[W_WORST_GAP] = worst_gap
    stats[W_BEHIND] = behind
