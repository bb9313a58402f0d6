# cython: language_level=3
"""ParticleView: the atom store behind one Particles struct (see _particles.pxd)."""


cdef class ParticleView:
    """view = ParticleView(sim.atom): the current arrays, owned rows and ghosts."""

    def __cinit__(self, atom):
        d = atom.data
        cdef const double[:, ::1] x = d["x"], v = d["v"], omega = d["omega"], quat = d["quat"]
        cdef double[:, ::1] f = d["f"], torque = d["torque"]
        cdef const double[::1] radius = d["radius"], rmass = d["rmass"]
        cdef const int[::1] type_ = d["type"], shape = d["shape"], mask = d["mask"]
        cdef double[:, ::1] tally
        self._keep = tuple(d[k] for k in ("x", "v", "omega", "quat", "f", "torque", "radius", "rmass", "type", "shape", "mask"))
        self.p.nlocal = atom.nlocal
        self.p.nall = atom.nall
        self.p.x = &x[0, 0]
        self.p.v = &v[0, 0]
        self.p.omega = &omega[0, 0]
        self.p.quat = &quat[0, 0]
        self.p.f = &f[0, 0]
        self.p.torque = &torque[0, 0]
        self.p.radius = &radius[0]
        self.p.rmass = &rmass[0]
        self.p.type = &type_[0]
        self.p.shape = &shape[0]
        self.p.mask = &mask[0]
        self.p.stress = NULL
        self.p.ctypes = NULL
        self.p.ccount = NULL
        if "tally_stress" in d:
            tally = d["tally_stress"]
            self.p.stress = &tally[0, 0]
        if "tally_types" in d:
            tally = d["tally_types"]
            self.p.ctypes = &tally[0, 0]
        if "tally_count" in d:
            tally = d["tally_count"]
            self.p.ccount = &tally[0, 0]
        self._keep = self._keep + tuple(d[k] for k in ("tally_stress", "tally_types", "tally_count") if k in d)
