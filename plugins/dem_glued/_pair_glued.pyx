# cython: language_level=3
"""Contacts between glued composites, convex particles and spheres (Grains3D Part III sec 2.5): the
particles' bounding spheres (the neighbor list), then the bounding spheres of their convex pieces (a
composite's components; any other particle is its own single piece), then the crust contact (GJK on the
shrunk cores, EPA when the cores overlap; dem/contact/_gjk.pyx) per piece pair, or the analytic contact
of two balls (sphere pieces: multisphere clumps). Every contact point goes through the shared law
(dem/law/apply.pxd) with levers from the centres of mass of the whole particles; Model B weighs each
of the N_c points of a particle pair by 1/N_c (eq. 20-21); Model A sums them (weight 1) with the damping of
each point from m_ij / N_c, i.e. gamma_n / sqrt(N_c) (eq. 18), so that the restitution stays e_n.

Pieces are posed once per step (poses): piece c of particle i at cpose[cstart[i] + c] (scaled rotation,
then centre), with its scaled bounding radius and crust.

Piece candidates (issue 39): for each entry k of the neighbor list, the piece pairs (a, b) whose bounding
sphere and box are within `margin` (the neighbor skin) when the list is built, pairs[coff[k]:coff[k+1]] in
the order of the full double loop (candidates). Each step tests only those with the same sphere and box
culls as before: a pair left out was more than `margin` apart (the gap of boxes_gap is a lower bound of the
boxes' distance), and until no particle's pieces have moved more than MOVE margin since (poses bounds the
move of each particle each step: displacement plus the chord of the rotation at the farthest box corner)
it stays more than (1 - 2 MOVE) margin apart, so the per-step culls would drop it too. Likewise a listed
pair apart by gap g > 0 at the build is dropped without its tests while the moves of its two particles sum
to less than 2 MOVE g. The tested set, the histories and the trajectories are those of the full double loop,
bit for bit. The lists are rebuilt with the neighbor list or when a particle has moved too far; nothing is
communicated (ghosts are posed as owned particles).

History: one keyed record per piece pair whose bounding spheres overlap (key a * KEY_BASE + b, a the piece
of the list's owner): the tangential spring xi, the last core separation direction (GJK warm start and
first axis), a tag of the two rows it was made for, and the last simplex (NFEAT values)."""
cimport numpy as cnp
from libc.math cimport sqrt, fabs
from libc.stdlib cimport malloc, free
import numpy as np
from dem._history cimport KeyedBuffers, KeyedView, keyed_append, keyed_owner, keyed_reserve
from dem._particles cimport ParticleView, Particles, count_contact
from dem.contact.record cimport Contact
from dem.contact._gjk cimport crust_contact, CONTACT_NONE, CONTACT_CRUST, NFEAT
from dem.shapes._support cimport ShapeRef, Kind, quat_to_rot, NPARAM
from dem.shapes._table cimport (ShapeView, TableView, core_ref, equivalent_radius, round_body, ncomponents,
                               component_row,
                                pose_component)
from dem.contact._bounds cimport boxes_apart, boxes_gap
from dem.law.apply cimport Body, apply_pair, bind_body, contact_radius
from dem.law.law cimport forget
from dem.law.row cimport XI_WIDTH

ctypedef cnp.int64_t i64

cdef enum:
    AXIS = XI_WIDTH                   # record slots (module docstring): xi, axis, tag, simplex
    TAG = AXIS + 3
    FEAT = TAG + 1
    NREC = FEAT + NFEAT               # values per record
    POSE = 12                         # a posed piece: scaled rotation (9), centre (3)
RECORD = NREC                         # (for Python)
KEY_BASE = 65536                      # key = piece of i * KEY_BASE + piece of j
cdef i64 KEY_BASE_C = KEY_BASE
MAX_PIECES = 65535                    # pieces per particle the keys can name

cdef double POINT_PARAMS[NPARAM]          # a sphere of radius 0 (zero-initialised)

STATS = ("contacts", "points", "max_overlap", "energy", "gjk", "epa", "piece_pairs", "piece_spheres",
         "piece_candidates", "piece_listed", "piece_builds")
cdef double MOVE = 0.45               # of the margin a particle's pieces may move before the lists are rebuilt


cdef class GluedWork:
    """Per-step poses of every particle's pieces (owned and ghost), the piece candidates of the neighbor
    list (coff, pairs) with the particles' state when they were made (xref, qref, rref, sref, and rho: the
    farthest box corner of a particle's pieces from its centre), and the kernel's statistics."""
    cdef public object cstart, cpose, crad, ccrust, crow, stats, worst
    cdef public object coff, pairs, cgap, xref, qref, rref, sref, rho, move, listed
    cdef public double margin
    cdef public i64 nref

    def __init__(self):
        self.cstart = np.zeros(1, np.int64)
        self.cpose = np.zeros((0, POSE))
        self.crad = np.zeros(0)
        self.ccrust = np.zeros(0)
        self.crow = np.zeros(0, np.int32)
        self.stats = np.zeros(len(STATS))
        self.worst = np.zeros(2, dtype=np.int64)
        self.coff = np.zeros(1, np.int64)
        self.pairs = np.zeros(0, np.int32)
        self.cgap = np.zeros(0)           # per candidate: its gap at the build (0: touching or unknown)
        self.move = np.zeros(0)           # per particle: how far its pieces may have moved since
        self.xref, self.qref, self.rref = np.zeros(0), np.zeros(0), np.zeros(0)
        self.sref = np.zeros(0, np.int32)
        self.rho = np.zeros(0)
        self.listed = None                # the neighbor list's offsets the candidates were made for
        self.margin = 0.0
        self.nref = -1                    # particles (nall) when they were made; -1: none yet


def poses(ParticleView view, ShapeView shapes, GluedWork work):
    """Poses, bounding radii and crusts of the pieces of all nall particles; returns whether the piece
    candidates must be rebuilt: a particle's pieces may have moved more than MOVE margin since they were
    made (or its radius, its shape or the number of particles changed)."""
    cdef Particles particles = view.p
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef int i, c, k, s, row
    cdef i64 n = 0, m
    cdef double sc
    cdef double R[9]
    for i in range(P.nall):
        n += ncomponents(T, P.shape[i])
    if work.cpose.shape[0] < n:
        m = int(n * 1.2) + 16
        work.cpose, work.crad, work.ccrust = np.zeros((m, POSE)), np.zeros(m), np.zeros(m)
        work.crow = np.zeros(m, np.int32)
    if work.cstart.shape[0] < P.nall + 1:
        work.cstart = np.zeros(int(P.nall * 1.2) + 16, np.int64)
    cdef i64[::1] cstart = work.cstart
    cdef double[:, ::1] cpose = work.cpose
    cdef double[::1] crad = work.crad, ccrust = work.ccrust
    cdef int[::1] crow = work.crow
    cdef bint stale = work.nref != P.nall
    cdef const double[::1] xref, qref, rref, rho
    cdef double[::1] moved
    cdef const int[::1] sref
    cdef double limit = MOVE * work.margin, dq, qq, rr, move
    if not stale:
        xref, qref, rref, rho, sref, moved = work.xref, work.qref, work.rref, work.rho, work.sref, work.move
    with nogil:
        n = 0
        for i in range(P.nall):
            s = P.shape[i]
            cstart[i] = n
            if not stale:
                if P.radius[i] != rref[i] or s != sref[i]:
                    stale = True
                else:
                    # every point of the pieces moves by at most the displacement plus the chord
                    # 2 rho sin(theta / 2) of the rotation since, cos(theta / 2) = |q . qref| / (|q| |qref|)
                    dq = qq = rr = move = 0.0
                    for k in range(4):
                        dq += P.quat[4 * i + k] * qref[4 * i + k]
                        qq += P.quat[4 * i + k] * P.quat[4 * i + k]
                        rr += qref[4 * i + k] * qref[4 * i + k]
                    for k in range(3):
                        move += (P.x[3 * i + k] - xref[3 * i + k]) * (P.x[3 * i + k] - xref[3 * i + k])
                    dq = 1.0 - dq * dq / (qq * rr)
                    move = sqrt(move) + (2.0 * rho[i] * sqrt(dq) if dq > 0.0 else 0.0)
                    moved[i] = move
                    if not move <= limit:      # (NaN: rebuilt, the neighbor list reports it)
                        stale = True
            if round_body(T, s):             # a plain sphere: a point core, crust = radius
                for k in range(9):
                    cpose[n, k] = 0.0
                cpose[n, 0] = cpose[n, 4] = cpose[n, 8] = 1.0
                for k in range(3):
                    cpose[n, 9 + k] = P.x[3 * i + k]
                crad[n] = ccrust[n] = P.radius[i]
                crow[n] = -1
                n += 1
                continue
            sc = P.radius[i] / T.radius[s]
            quat_to_rot(&P.quat[4 * i], R)
            for k in range(9):
                R[k] *= sc
            for c in range(ncomponents(T, s)):
                row = component_row(T, s, c)
                pose_component(T, s, c, R, &P.x[3 * i], &cpose[n, 0], &cpose[n, 9])
                crad[n] = T.radius[row] * sc
                ccrust[n] = T.crust[row] * sc if not round_body(T, row) else crad[n]
                crow[n] = row
                n += 1
        cstart[P.nall] = n
    return stale


def candidates(ParticleView view, const i64[::1] offsets, const int[::1] neigh, ShapeView shapes,
               GluedWork work, double margin):
    """The piece candidates of every entry of the neighbor list (module docstring), from the poses of this
    step, and the particles' state they are made for."""
    cdef Particles particles = view.p
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef i64 nent = offsets[P.nlocal] if P.nlocal > 0 else 0
    cdef i64 k, ia, jb, m = 0, cap
    cdef int i, j, a, b, d, na, nb
    cdef double r2, r, sa, sb, far, gap, gbox
    if work.coff.shape[0] < nent + 1:
        work.coff = np.zeros(int(nent * 1.2) + 16, np.int64)
    if work.xref.shape[0] < 3 * P.nall:
        n = int(P.nall * 1.2) + 16
        work.xref, work.qref, work.rref, work.rho = np.zeros(3 * n), np.zeros(4 * n), np.zeros(n), np.zeros(n)
        work.move = np.zeros(n)
        work.sref = np.zeros(n, np.int32)
    cdef const i64[::1] cstart = work.cstart
    cdef const double[:, ::1] cpose = work.cpose
    cdef const double[::1] crad = work.crad
    cdef const int[::1] crow = work.crow
    cdef i64[::1] coff = work.coff
    cdef double[::1] xref = work.xref, qref = work.qref, rref = work.rref, rho = work.rho, moved = work.move
    cdef int[::1] sref = work.sref
    cdef int[::1] pairs = work.pairs
    cdef double[::1] cgap = work.cgap
    while True:
        cap = pairs.shape[0] // 2
        m = 0
        with nogil:
            coff[0] = 0
            for i in range(P.nlocal):
                for k in range(offsets[i], offsets[i + 1]):
                    j = neigh[k]
                    na = <int>(cstart[i + 1] - cstart[i])
                    nb = <int>(cstart[j + 1] - cstart[j])
                    for a in range(na):        # the order of compute's tests
                        ia = cstart[i] + a
                        for b in range(nb):
                            jb = cstart[j] + b
                            r2 = 0.0
                            for d in range(3):
                                r = cpose[ia, 9 + d] - cpose[jb, 9 + d]
                                r2 += r * r
                            gap = sqrt(r2) - (crad[ia] + crad[jb])
                            if gap > margin:
                                continue
                            if crow[ia] >= 0 and crow[jb] >= 0:
                                sa = crad[ia] / T.radius[crow[ia]]
                                sb = crad[jb] / T.radius[crow[jb]]
                                gbox = boxes_gap(&cpose[ia, 0], sa, &cpose[ia, 9], &T.half[3 * crow[ia]], sa,
                                                 &cpose[jb, 0], sb, &cpose[jb, 9], &T.half[3 * crow[jb]], sb)
                                if gbox > margin:
                                    continue
                                if gbox > gap:
                                    gap = gbox
                            if m < cap:
                                pairs[2 * m] = a
                                pairs[2 * m + 1] = b
                                # a gap below 1e-6 margin is not trusted to outlast round-off: tested
                                cgap[m] = gap if gap > 1e-6 * margin else 0.0
                            m += 1
                    coff[k + 1] = m
        if m <= cap:
            break
        pairs = work.pairs = np.zeros(2 * (int(m * 1.3) + 64), np.int32)
        cgap = work.cgap = np.zeros(int(m * 1.3) + 64)
    with nogil:
        for i in range(P.nall):
            for d in range(3):
                xref[3 * i + d] = P.x[3 * i + d]
            for d in range(4):
                qref[4 * i + d] = P.quat[4 * i + d]
            rref[i] = P.radius[i]
            moved[i] = 0.0
            sref[i] = P.shape[i]
            rho[i] = 0.0                       # a plain sphere: its pieces do not turn with it
            if crow[cstart[i]] < 0:
                continue
            for ia in range(cstart[i], cstart[i + 1]):
                r2 = 0.0
                for d in range(3):
                    r = cpose[ia, 9 + d] - P.x[3 * i + d]
                    r2 += r * r
                sa = crad[ia] / T.radius[crow[ia]]
                far = sqrt(r2) + sa * sqrt(T.half[3 * crow[ia]] ** 2 + T.half[3 * crow[ia] + 1] ** 2
                                           + T.half[3 * crow[ia] + 2] ** 2)
                if far > rho[i]:
                    rho[i] = far
    work.nref = P.nall
    work.margin = margin
    work.stats[10] += 1.0


cdef inline void _piece(const TableView* T, int row, ShapeRef* ref) noexcept nogil:
    """The core GJK meets for a piece of row `row` (a ball: the point at its centre)."""
    if round_body(T, row):
        ref.kind = Kind.SPHERE
        ref.params = POINT_PARAMS
        ref.nverts = 0
        ref.verts = NULL
        ref.corners = NULL
    else:
        core_ref(T, row, ref)


def compute(ParticleView view, const i64[::1] offsets, const int[::1] neigh, const double[:, :, ::1] coeff,
            ShapeView shapes, GluedWork work, KeyedBuffers hist, bint use_xi, double tol, double dt,
            bint advance, bint model_b, i64 start):
    """Adds the contact forces and torques of list entries from `start` on, testing the piece candidates
    of `candidates` (made for this list); returns -1, or the entry to resume from when the history buffer
    is full (dem/_history.pxd). work.stats receives STATS (summed over calls of one step by the caller
    resetting it)."""
    cdef Particles particles = view.p
    cdef const Particles* P = &particles
    cdef TableView table = shapes.t
    cdef const TableView* T = &table
    cdef KeyedView* h = &hist.view
    cdef const i64[::1] cstart = work.cstart
    cdef const double[:, ::1] cpose = work.cpose
    cdef const double[::1] crad = work.crad, ccrust = work.ccrust
    cdef const int[::1] crow = work.crow
    cdef double[::1] stats = work.stats
    cdef i64[::1] worst = work.worst
    cdef int i, j, a, b, d, q, na, nb, ncand, npt, code, rowa, rowb
    cdef i64 k, m, ia, jb, key, resume = -1
    cdef const i64[::1] coff = work.coff
    cdef const int[::1] pairs = work.pairs
    cdef const double[::1] cgap = work.cgap, moved = work.move
    cdef double within
    cdef double dx[3]
    cdef double g[3]
    cdef double out[6]
    cdef double r2, rsum, r, gn, tag, meff, weight, rmin, sa, sb, reff, maxov = stats[2]
    cdef const double* cf
    cdef double ncont = 0.0, npts = 0.0, energy = 0.0, ngjk = 0.0, nepa = 0.0, npairs = 0.0, ncands = 0.0
    cdef double nspheres = 0.0, nsph_entry, nlisted = 0.0
    cdef const double* xa
    cdef const double* xb
    cdef double* rec
    cdef ShapeRef SA, SB
    cdef Body A, B
    cdef bint balls
    cdef int cap = T.nrows + 1
    cdef int maxp = 1
    for q in range(T.nrows):
        if T.comp_count[q] > maxp:
            maxp = T.comp_count[q]
    cap = maxp * maxp
    cdef int* cand = <int*>malloc(2 * cap * sizeof(int))
    cdef Contact* con = <Contact*>malloc(cap * sizeof(Contact))
    cdef double** recs = <double**>malloc(cap * sizeof(double*))
    if cand == NULL or con == NULL or recs == NULL:
        free(cand); free(con); free(recs)
        raise MemoryError()
    if P.nlocal == 0 or start >= offsets[P.nlocal]:
        free(cand); free(con); free(recs)
        return -1
    with nogil:
        for i in range(keyed_owner(&offsets[0], P.nlocal, start), P.nlocal):
            for k in range(max(offsets[i], start), offsets[i + 1]):
                j = neigh[k]
                for d in range(3):
                    dx[d] = P.x[3 * i + d] - P.x[3 * j + d]
                r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]
                rsum = P.radius[i] + P.radius[j]
                if r2 >= rsum * rsum:
                    continue                   # no record: the pair's history is forgotten
                na = <int>(cstart[i + 1] - cstart[i])
                nb = <int>(cstart[j + 1] - cstart[j])
                ncand = 0
                nsph_entry = nspheres
                nlisted += coff[k + 1] - coff[k]
                within = moved[i] + moved[j]
                for m in range(coff[k], coff[k + 1]):    # the candidates' bounding spheres
                    if 2.0 * MOVE * cgap[m] > within:
                        continue               # still apart (module docstring)
                    a = pairs[2 * m]
                    b = pairs[2 * m + 1]
                    ia = cstart[i] + a
                    jb = cstart[j] + b
                    r2 = 0.0
                    for d in range(3):
                        r = cpose[ia, 9 + d] - cpose[jb, 9 + d]
                        r2 += r * r
                    rsum = crad[ia] + crad[jb]
                    if r2 >= rsum * rsum:
                        continue
                    nspheres += 1.0
                    # then their bounding boxes (the spheres of elongated pieces are loose: Part III
                    # Fig. 29); a plain sphere particle (row -1) has none
                    sa = crad[ia] / T.radius[crow[ia]] if crow[ia] >= 0 else 1.0
                    sb = crad[jb] / T.radius[crow[jb]] if crow[jb] >= 0 else 1.0
                    if crow[ia] >= 0 and crow[jb] >= 0 and boxes_apart(
                            &cpose[ia, 0], sa, &cpose[ia, 9], &T.half[3 * crow[ia]], sa,
                            &cpose[jb, 0], sb, &cpose[jb, 9], &T.half[3 * crow[jb]], sb):
                        continue
                    cand[2 * ncand] = a
                    cand[2 * ncand + 1] = b
                    ncand += 1
                if ncand == 0:
                    npairs += na * nb
                    continue
                if not keyed_reserve(h, k, ncand):
                    nspheres = nsph_entry          # (counted again when the kernel resumes here)
                    nlisted -= coff[k + 1] - coff[k]
                    resume = k
                    break
                npairs += na * nb
                ncands += ncand
                npt = 0
                for q in range(ncand):
                    a = cand[2 * q]
                    b = cand[2 * q + 1]
                    ia = cstart[i] + a
                    jb = cstart[j] + b
                    key = a * KEY_BASE_C + b
                    rec = keyed_append(h, k, key)
                    if rec == NULL:
                        break
                    xa = &cpose[ia, 9]
                    xb = &cpose[jb, 9]
                    rowa = crow[ia]
                    rowb = crow[jb]
                    balls = round_body(T, rowa) and round_body(T, rowb)
                    con[npt].key = key
                    con[npt].weight = 1.0
                    con[npt].central = False
                    if balls:                  # two balls: analytic
                        r2 = 0.0
                        for d in range(3):
                            dx[d] = xa[d] - xb[d]
                            r2 += dx[d] * dx[d]
                        rsum = crad[ia] + crad[jb]
                        r = sqrt(r2)
                        if r >= rsum or r == 0.0:
                            if use_xi:
                                forget(rec, XI_WIDTH)
                            continue
                        for d in range(3):
                            con[npt].n[d] = dx[d] / r
                        con[npt].delta = rsum - r
                        for d in range(3):
                            con[npt].p[d] = xa[d] - (crad[ia] - 0.5 * con[npt].delta) * con[npt].n[d]
                    else:
                        _piece(T, rowa, &SA)
                        _piece(T, rowb, &SB)
                        tag = (rowa + 2) * 65536.0 + rowb + 2.0   # the rows the warm start was made for
                        if fabs(rec[TAG]) != tag:
                            for d in range(NREC - AXIS):
                                rec[AXIS + d] = 0.0
                        for d in range(3):
                            g[d] = rec[AXIS + d]
                        gn = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]
                        if gn == 0.0:          # no axis yet: the line of the pieces' centres
                            for d in range(3):
                                g[d] = xa[d] - xb[d]
                            gn = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]
                            if gn == 0.0:
                                g[2] = 1.0
                        ngjk += 1.0
                        code = crust_contact(&SA, ccrust[ia], &cpose[ia, 0], xa, &SB, ccrust[jb], &cpose[jb, 0],
                                             xb, tol, g, &rec[FEAT], &con[npt].delta, con[npt].n, con[npt].p)
                        rec[TAG] = tag
                        if code == CONTACT_CRUST:
                            for d in range(3):
                                rec[AXIS + d] = con[npt].n[d]
                        else:
                            gn = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]
                            gn = 1.0 / sqrt(gn) if gn > 0.0 else 0.0
                            for d in range(3):
                                rec[AXIS + d] = g[d] * gn
                        if code == CONTACT_NONE:
                            if use_xi:
                                forget(rec, XI_WIDTH)
                            continue
                        if code > 1:
                            nepa += 1.0
                    recs[npt] = rec
                    rmin = crad[ia] if crad[ia] < crad[jb] else crad[jb]
                    if con[npt].delta > maxov * (2.0 * rmin):
                        maxov = con[npt].delta / (2.0 * rmin)
                        worst[0] = i
                        worst[1] = j
                    npt += 1
                if h.error:
                    break
                if npt == 0:
                    continue
                ncont += 1.0
                npts += npt
                count_contact(P, i, j, npt)
                weight = 1.0 / npt if model_b else 1.0
                meff = P.rmass[i] * P.rmass[j] / (P.rmass[i] + P.rmass[j])
                if not model_b:                # eq. 18: gamma_n of N_c summed springs
                    meff /= npt
                bind_body(&A, P, i)
                bind_body(&B, P, j)
                # rolling resistance between two plain spheres only (as pair sphere); none for shaped bodies
                cf = &coeff[P.type[i], P.type[j], 0]
                reff = contact_radius(cf, round_body(T, P.shape[i]) and round_body(T, P.shape[j]),
                                      equivalent_radius(T, P.shape[i], P.radius[i]),
                                      equivalent_radius(T, P.shape[j], P.radius[j]))
                for q in range(npt):
                    con[q].weight = weight
                    con[q].inertia = 0.0
                    energy += apply_pair(cf, &con[q], &A, &B, meff, reff, recs[q] if use_xi else NULL, dt,
                                         advance, out)
            if resume >= 0 or h.error:
                break
    free(cand)
    free(con)
    free(recs)
    stats[0] += ncont
    stats[1] += npts
    stats[2] = maxov
    stats[3] += energy
    stats[4] += ngjk
    stats[5] += nepa
    stats[6] += npairs
    stats[7] += nspheres
    stats[8] += ncands
    stats[9] += nlisted
    return resume
