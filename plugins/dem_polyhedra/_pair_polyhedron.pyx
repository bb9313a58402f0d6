# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True, initializedcheck=False
"""Contacts of sharp polytopes (box, cube, polyhedron, tetrahedron, pinacoid: no crust) and plain spheres
with as many contact points as the contact geometry has (Descantes 2022 sec. 2).

Per listed pair whose bounding spheres overlap (and, two polytopes, whose bounding boxes do: 15 axes):
* two polytopes: polytope_contact (dem/contact/_polytope.pyx: exact separating-axis
  depth and normal, the contacting features clipped on the contact plane): alpha = 1 (vertex/face,
  edge/edge), 2 (edge/face) or >= 3 (face/face) points, all with the shared maximum overlap. A body's
  contacting feature is its vertices within ftol = ftol_rel (r_i + r_j) + delta of its deepest vertex along
  the normal: every vertex inside the overlap slab (as a wall's `point multipoint` takes every vertex
  beyond the wall), so a face tilted by less than delta / its size still touches with all its corners,
  and the point set does not flip between 1, 2 and 4 points from round-off;
* a sphere and a polytope: crust_contact (dem/contact/_gjk.pyx) of the sharp body (crust 0) and the
  sphere's centre (a point core of crust = its radius): one point;
* two spheres: analytic, one point.
Every point goes through the shared law (dem/law/apply.pxd) with levers from the centres of mass and
weight 1/alpha: the Grains3D law (Model B averaging on the points) or, with the style's `law descantes`,
rows of Descantes' eq. 3 (dem.law.descantes: no attraction, viscous friction capped by Coulomb, no spring,
no history).

History (keyed, only with a tangential spring ks > 0): one record per contact point: xi (XI_WIDTH values)
then the point in the body frame of the list's owner i (unscaled, unrotated: R^T (p - x_i) / s_i). A new
point takes the record of the nearest old point of the pair within MATCH times the row's bounding radius
(each old record at most once, new points in their canonical order, ties to the lowest old row), else a
fresh key (1 + the largest key of the pair). So a face/face contact that becomes edge/face keeps the
springs of the two corners that remain, and back. Deterministic: no hash, no order but the canonical one."""
cimport numpy as cnp
from libc.math cimport sqrt
import numpy as np
from dem._history cimport KeyedBuffers, KeyedView, keyed_append, keyed_owner, keyed_reserve
from dem._particles cimport ParticleView, Particles, count_contact
from dem.contact.record cimport Contact
from dem.contact._bounds cimport boxes_gap
from dem.contact._gjk cimport crust_contact, CONTACT_NONE, NFEAT
from dem.contact._polytope cimport (Polytope, TopoTable, SatResult, PolyContact, polytope_ref,
                                    polytope_contact, POLY_MAXP,
                                    PC_FACE_FACE)
from dem.shapes._support cimport ShapeRef, Kind, quat_to_rot, NPARAM
from dem.shapes._table cimport ShapeView, TableView, body_ref, equivalent_radius, round_body
from dem.law.apply cimport Body, apply_pair, bind_body, contact_radius
from dem.law.row cimport XI_WIDTH, NCOEFF
from dem.contact._volume cimport OverlapVolume, overlap_volume
from dem.law.volume cimport reference_area, volume_record, volume_row, volume_couple, volume_twist

ctypedef cnp.int64_t i64

cdef enum:
    PT = XI_WIDTH                  # record slots: xi, then the body-frame point (3)
    NREC = PT + 3
RECORD = NREC
MAXP = POLY_MAXP
cdef double MATCH = 0.25           # history match radius, times the bounding radius of the owner's row
MATCH_RADIUS = MATCH
cdef double GJK_TOL = 1e-10
cdef double MARGIN_SAFETY = 1e-12  # margins are kept this much (relative to rsum) short of the round-off

cdef double POINT_PARAMS[NPARAM]   # a sphere of radius 0 (zero-initialised)

RECW = 10                          # a recorded contact point: x y z, normal (3), force on i (3), overlap
STATS = ("contacts", "points", "max_overlap", "energy", "vertex_face", "edge_edge", "edge_face", "face_face",
         "sphere", "face_face_points")


cdef inline void _rot(const Particles* P, int i, double* R) noexcept nogil:
    quat_to_rot(&P.quat[4 * i], R)


cdef inline void _unscaled(const double* Rs, double s, double* R) noexcept nogil:
    """The pure rotation of a scaled one (poses' rot[i] = s R)."""
    cdef double inv = 1.0 / s
    cdef int k
    for k in range(9):
        R[k] = Rs[k] * inv


cdef inline int _sphere_poly(const Particles* P, const TableView* T, int i, int j, bint i_round,
                             Contact* con) noexcept nogil:
    """One contact of a sphere and a sharp polytope (either order): 1, or 0 when apart."""
    cdef ShapeRef SA, SB
    cdef double Ra[9]
    cdef double Rb[9]
    cdef double g[3]
    cdef double feat[NFEAT]
    cdef double ca, cb, s
    cdef int k, code
    for k in range(NFEAT):
        feat[k] = 0.0
    if i_round:
        SA.kind = Kind.SPHERE
        SA.params = POINT_PARAMS
        SA.nverts = 0
        SA.verts = NULL
        SA.corners = NULL
        for k in range(9):
            Ra[k] = 0.0
        Ra[0] = Ra[4] = Ra[8] = 1.0
        ca = P.radius[i]
        body_ref(T, P.shape[j], &SB)
        _rot(P, j, Rb)
        s = P.radius[j] / T.radius[P.shape[j]]
        for k in range(9):
            Rb[k] *= s
        cb = 0.0
    else:
        body_ref(T, P.shape[i], &SA)
        _rot(P, i, Ra)
        s = P.radius[i] / T.radius[P.shape[i]]
        for k in range(9):
            Ra[k] *= s
        ca = 0.0
        SB.kind = Kind.SPHERE
        SB.params = POINT_PARAMS
        SB.nverts = 0
        SB.verts = NULL
        SB.corners = NULL
        for k in range(9):
            Rb[k] = 0.0
        Rb[0] = Rb[4] = Rb[8] = 1.0
        cb = P.radius[j]
    for k in range(3):
        g[k] = P.x[3 * i + k] - P.x[3 * j + k]
    if g[0] == 0.0 and g[1] == 0.0 and g[2] == 0.0:
        g[2] = 1.0
    code = crust_contact(&SA, ca, Ra, &P.x[3 * i], &SB, cb, Rb, &P.x[3 * j], GJK_TOL, g, feat,
                         &con.delta, con.n, con.p)
    if code == CONTACT_NONE:
        return 0
    return 1


cdef inline i64 _match(const KeyedView* h, i64 k, const double* b, double tol2, bint* taken, i64* fresh) noexcept nogil:
    """The key of the nearest untaken old record of entry k within sqrt(tol2) of body-frame point b, or a
    fresh key."""
    cdef i64 r, best = -1, n0 = h.offsets[k]
    cdef double d2, dbest = tol2, e
    cdef const double* v
    cdef int d
    for r in range(n0, h.offsets[k + 1]):
        if taken[r - n0]:
            continue
        v = h.values + r * h.width + PT
        d2 = 0.0
        for d in range(3):
            e = v[d] - b[d]
            d2 += e * e
        if d2 < dbest:
            dbest = d2
            best = r
    if best >= 0:
        taken[best - n0] = True
        return h.keys[best]
    fresh[0] += 1
    return fresh[0]


def compute(ParticleView view, const i64[::1] offsets, const int[::1] neigh, const double[:, :, ::1] coeff,
            ShapeView shapes, const double[:, ::1] rot, const double[::1] move,
            double[::1] margin, int[::1] cert_code, double[::1] cert_budget, double[::1] stats, KeyedBuffers hist,
            bint use_xi, bint volume, double ftol_rel, double dt, bint advance, double[:, ::1] rec,
            i64[:, ::1] rec_ij, i64[::1] nrec, i64 start):
    """Adds the contact forces and torques of list entries from `start` on; returns -1, or the entry to
    resume from when the history buffer is full (dem/_history.pxd). stats receives STATS (summed; the
    caller resets them once per step). With rows in `rec`, every contact point is recorded there (RECW
    columns; rec_ij: the local indices i, j and the type, 1-4 as PolyContactType, 5 a pair with a
    sphere), nrec[0] the rows used; an entry whose points do not fit stops the pass (nrec[1] = 1, the
    entry returned, nothing of it applied): the caller grows the buffers and resumes there. With `volume`
    (the style's `law volume`, dem/law/volume.pxd) two polytopes touch at one point: the overlap volume's
    record, its own stiffness and the couple about the normal.

    rot[i] (scale_i R_i) and move[i] (how far any point of particle i moved since the last call) come from
    dem_convex's poses, once per step. margin[k] caches a lower bound of the gap of entry k (bounding
    spheres, or the largest separation along a candidate axis of the separating-axis query); it shrinks by
    move[i] + move[j] per call and the pair is skipped while it stays positive: the test would find it apart
    again, and an apart pair has no record, so the cache changes no result (as `convex/gjk`).
    cert_code[k], cert_budget[k]: entry k's certificate of its separating axis (polytope_contact), zeroed
    with the margins; kept only while the pair goes through the test at every call, since the budget is
    spent by the moves of each call (a pair found apart has none: polytope_contact drops it, the culls
    above zero it)."""
    cdef Particles particles = view.p
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef const TopoTable* TT = &T.topo
    cdef KeyedView* h = &hist.view
    cdef int i, j, d, q, npt, si, sj, typ, sb = -1
    cdef i64 k, r, resume = -1, fresh
    cdef double dx[3]
    cdef double Ri[9]
    cdef double Rj[9]
    cdef double bpt[3]
    cdef double out[6]
    cdef double r2, rsum, dist, meff, weight, si_scale, sj_scale, reff, tol2, gap, inv_si
    cdef double vol, varea, aref, req_i, req_j
    cdef double couple[3]
    cdef double vrow[NCOEFF]
    cdef OverlapVolume ov
    cdef const double* cf
    cdef double maxov = stats[2]
    cdef bint ri, rj
    cdef bint taken[4 * POLY_MAXP]
    cdef Polytope A, B
    cdef SatResult sat
    cdef PolyContact pc
    cdef Contact con[POLY_MAXP]
    cdef double* recs[POLY_MAXP]
    cdef Body BA, BB
    if P.nlocal == 0 or start >= offsets[P.nlocal]:
        return -1
    with nogil:
        for i in range(keyed_owner(&offsets[0], P.nlocal, start), P.nlocal):
            si = -1                            # the owner's pose and topology: once per row, when needed
            for k in range(max(offsets[i], start), offsets[i + 1]):
                j = neigh[k]
                gap = margin[k] - (move[i] + move[j])
                if gap > 0.0:
                    margin[k] = gap
                    continue                   # still apart (no record: the pair's history is forgotten)
                margin[k] = 0.0
                for d in range(3):
                    dx[d] = P.x[3 * i + d] - P.x[3 * j + d]
                r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]
                rsum = P.radius[i] + P.radius[j]
                if r2 >= rsum * rsum:
                    margin[k] = sqrt(r2) - rsum - MARGIN_SAFETY * rsum
                    cert_code[k] = 0           # a certificate holds only over consecutive queries
                    continue
                if si < 0:
                    si = P.shape[i]
                    ri = round_body(T, si)
                    si_scale = P.radius[i] if ri else P.radius[i] / T.radius[si]
                    inv_si = 1.0 / si_scale
                    _unscaled(&rot[i, 0], si_scale, Ri)
                    if not ri:
                        polytope_ref(TT, si, &A)
                sj = P.shape[j]
                rj = round_body(T, sj)
                typ = -1
                vol = 0.0
                if ri and rj:                  # two spheres: analytic
                    dist = sqrt(r2)
                    if dist == 0.0:
                        continue
                    npt = 1
                    con[0].delta = rsum - dist
                    for d in range(3):
                        con[0].n[d] = dx[d] / dist
                        con[0].p[d] = P.x[3 * i + d] - (P.radius[i] - 0.5 * con[0].delta) * con[0].n[d]
                elif ri or rj:
                    npt = _sphere_poly(P, T, i, j, ri, &con[0])
                else:
                    sj_scale = P.radius[j] / T.radius[sj]
                    _unscaled(&rot[j, 0], sj_scale, Rj)
                    if sj != sb:               # (consecutive neighbours mostly share a shape)
                        polytope_ref(TT, sj, &B)
                        sb = sj
                    # bounding boxes first, unless both are boxes (the query itself stops at a gap) or the
                    # pair holds a certificate (a lasting contact: its axis is evaluated alone)
                    if ((A.half == NULL or B.half == NULL)
                            and not (cert_code[k] > 0 and cert_budget[k] > move[i] + move[j])):
                        gap = boxes_gap(Ri, 1.0, &P.x[3 * i], &T.half[3 * si], si_scale,
                                        Rj, 1.0, &P.x[3 * j], &T.half[3 * sj], sj_scale)
                        if gap > 0.0:
                            margin[k] = gap - MARGIN_SAFETY * rsum
                            cert_code[k] = 0
                            continue
                    # contacting features: the vertices within ftol of the deepest one along the normal,
                    # ftol = ftol_rel L + the overlap, i.e. every vertex inside the overlap slab
                    if A.half != NULL and B.half != NULL:   # (two boxes: closed form, no certificate)
                        npt = polytope_contact(&A, Ri, si_scale, &P.x[3 * i], &B, Rj, sj_scale, &P.x[3 * j],
                                               ftol_rel * rsum, 1.0, &sat, &pc, NULL, NULL, 0.0)
                    else:
                        npt = polytope_contact(&A, Ri, si_scale, &P.x[3 * i], &B, Rj, sj_scale, &P.x[3 * j],
                                               ftol_rel * rsum, 1.0, &sat, &pc, &cert_code[k], &cert_budget[k],
                                               move[i] + move[j])
                    if not npt:
                        margin[k] = -sat.depth - MARGIN_SAFETY * rsum
                    typ = pc.type
                    if volume and npt:         # one record from the overlap volume (none without volume)
                        if (overlap_volume(&A, Ri, si_scale, &P.x[3 * i], &B, Rj, sj_scale, &P.x[3 * j], &ov) <= 0
                                or not volume_record(&ov, &P.x[3 * i], &con[0], couple, &varea)):
                            continue
                        vol = ov.volume
                        npt = 1
                    else:
                        for q in range(npt):
                            con[q].delta = pc.depth
                            for d in range(3):
                                con[q].n[d] = pc.n[d]
                                con[q].p[d] = pc.p[3 * q + d]
                if npt == 0:
                    continue
                if rec.shape[0] > 0 and nrec[0] + npt > rec.shape[0]:
                    nrec[1] = 1
                    resume = k
                    break
                if use_xi:
                    if not keyed_reserve(h, k, npt):
                        resume = k
                        break
                    # body-frame points of the owner i and their keys (module doc)
                    fresh = 0
                    for r in range(h.offsets[k], h.offsets[k + 1]):
                        if h.keys[r] > fresh:
                            fresh = h.keys[r]
                        if r - h.offsets[k] < 4 * POLY_MAXP:
                            taken[r - h.offsets[k]] = False
                    tol2 = MATCH * (T.radius[si] if not ri else 1.0)
                    tol2 = tol2 * tol2
                    for q in range(npt):
                        for d in range(3):
                            dx[d] = con[q].p[d] - P.x[3 * i + d]
                        for d in range(3):
                            bpt[d] = (Ri[d] * dx[0] + Ri[3 + d] * dx[1] + Ri[6 + d] * dx[2]) * inv_si
                        if h.offsets[k + 1] - h.offsets[k] <= 4 * POLY_MAXP:
                            con[q].key = _match(h, k, bpt, tol2, taken, &fresh)
                        else:
                            fresh += 1
                            con[q].key = fresh
                        recs[q] = keyed_append(h, k, con[q].key)
                        if recs[q] == NULL:
                            break
                        for d in range(3):
                            recs[q][PT + d] = bpt[d]
                    if h.error:
                        break
                else:
                    for q in range(npt):
                        con[q].key = q
                        recs[q] = NULL
                dist = 2.0 * (P.radius[i] if P.radius[i] < P.radius[j] else P.radius[j])
                gap = pc.depth if vol > 0.0 else con[0].delta     # the penetration (law volume: not h)
                if gap > maxov * dist:
                    maxov = gap / dist
                stats[0] += 1.0
                stats[1] += npt
                count_contact(P, i, j, npt)
                if typ > 0:
                    stats[3 + typ] += 1.0
                    if typ == PC_FACE_FACE:
                        stats[9] += npt
                else:
                    stats[8] += 1.0
                if P.ctypes != NULL:       # per-particle census for analysis (dem/tally.py)
                    q = typ - 1 if typ > 0 else 4
                    P.ctypes[5 * i + q] += 1.0
                    P.ctypes[5 * j + q] += 1.0
                weight = 1.0 / npt
                meff = P.rmass[i] * P.rmass[j] / (P.rmass[i] + P.rmass[j])
                bind_body(&BA, P, i)
                bind_body(&BB, P, j)
                cf = &coeff[P.type[i], P.type[j], 0]
                req_i = equivalent_radius(T, si, P.radius[i])
                req_j = equivalent_radius(T, sj, P.radius[j])
                reff = contact_radius(cf, ri and rj, req_i, req_j)
                for q in range(npt):
                    if vol > 0.0:
                        aref = reference_area(req_i, req_j)
                        volume_row(cf, varea, aref, vrow)
                        stats[3] += apply_pair(vrow, &con[q], &BA, &BB, meff, reff, recs[q], dt, advance, out)
                        volume_couple(cf, vol, aref, couple, &BA, &BB, False)
                        volume_twist(vrow, varea, meff, &con[q], out, &BA, &BB, False)
                    else:
                        con[q].weight = weight
                        con[q].central = False
                        con[q].inertia = 0.0
                        stats[3] += apply_pair(cf, &con[q], &BA, &BB, meff, reff, recs[q], dt, advance, out)
                    if rec.shape[0] > 0:
                        r = nrec[0]
                        for d in range(3):
                            rec[r, d] = con[q].p[d]
                            rec[r, 3 + d] = con[q].n[d]
                            rec[r, 6 + d] = out[d]
                        rec[r, 9] = con[q].delta
                        rec_ij[r, 0] = i
                        rec_ij[r, 1] = j
                        rec_ij[r, 2] = typ if typ > 0 else 5
                        nrec[0] = r + 1
            if resume >= 0 or h.error:
                break
    stats[2] = maxov
    return resume
