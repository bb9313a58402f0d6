"""compute nematic"""
import numpy as np

from dem.compute import Compute
from dem.thermo import quat_to_matrix

NAMES = ("Q_long", "Q_mid", "Q_short", "nx", "ny", "nz")


def principal_axes(quat, inertia):
    """World directions (n, 3, 3) of each particle's principal axes, [:, :, 0] the axis of the smallest
    moment (the long axis of an elongated body), [:, :, 2] the largest. Ties (cubes, spheres) keep the
    body-frame order, which is the shape's own frame (a cube's face normals)."""
    rot = quat_to_matrix(np.asarray(quat, float).reshape(-1, 4))
    order = np.argsort(np.asarray(inertia, float).reshape(-1, 3), axis=1, kind="stable")
    return np.take_along_axis(rot, order[:, None, :], axis=2)


class ComputeNematic(Compute):
    """compute ID group nematic

    Nematic order parameter Q00^2 of the group's orientations (Descantes 2022 sec. 3.1, refs. 21, 45): the
    largest eigenvalue S of the order tensor Q = < (3 u u - I) / 2 > over the particles, u a unit vector fixed
    in each body; its eigenvector is the director n. S = 1 when every u is parallel, S -> 0 for isotropic
    orientations (N random directions give S ~ 1/sqrt(N): about 0.05 for 1000; Q00^2 is the (0, 0) element
    of the rank-2 Wigner order parameters, <P2(cos theta)> about the director). u is taken along each of
    the principal axes of inertia in turn: `long` the axis of the smallest moment (an elongated pinacoid's
    long axis), `short` the largest (a flat body's normal), `mid` the other. Bodies with equal moments
    (cubes: any axis is principal; spheres) use their body frame, the shape's own axes (a cube's face
    normals): then the three values measure how the face normals line up, and aligned cubes give 1, 1, 1
    (for cubic order proper a fourth-rank, cubatic, parameter would be needed).

    Vector: [Q_long, Q_mid, Q_short, nx, ny, nz] (n: the director of the long axis); scalar: Q_long.
    Example: `compute q all nematic` then `thermo_style custom step c_q`."""

    style = "nematic"
    size_vector = len(NAMES)
    vector_names = NAMES

    def __init__(self, sim, cid, group, args):
        super().__init__(sim, cid, group, args)
        self.parser().exactly(0)

    def compute_vector(self):
        sim = self.sim
        atom, comm = sim.atom, sim.comm
        n = atom.nlocal
        sel = self.group_mask()
        axes = principal_axes(atom.data["quat"][:n][sel], atom.data["inertia"][:n][sel])
        count = comm.sum(int(sel.sum()))
        out = np.zeros(6)
        if not count:
            return out
        for k in range(3):
            u = axes[:, :, k]
            q = comm.sum_values((1.5 * np.einsum("ni,nj->ij", u, u)).reshape(9)).reshape(3, 3) / count
            w, vec = np.linalg.eigh(q - 0.5 * np.eye(3))
            out[k] = w[-1]
            if k == 0:
                d = vec[:, -1]
                out[3:] = d * np.sign(d[np.argmax(np.abs(d))])     # a sign convention: largest component > 0
        return out

    def compute_scalar(self):
        return self.vector()[0]
