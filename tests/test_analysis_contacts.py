"""Analysis from the contact tallies (dem/tally.py): coordination by contact type (compute contact/types,
Descantes 2022 Fig. 9b) and the Love-Weber / Moreau stress (compute stress, fix ave/profile, eq. 12).

Units as tests/test_polyhedron_pair.py: cubes of side a = 2 mm, density 1250 (m = 1e-5 kg); kn = 1e3 N/m
here so that the static overlaps (m g / kn ~ 1e-7 m) carry 10 significant digits more than the positions'
round-off (1e-19 m): forces computed from placed overlaps are exact to ~1e-11 relative."""
import numpy as np
import pytest

import dem
from dem.errors import DemError

A = 0.002
M = 1250 * A ** 3
G = 9.81
KN = 1e3
HEAD = """units si
boundary {bc}
region box block {box}
create_box 1 box
shape c cube 0.002
pair_style polyhedron/multipoint
pair_coeff * * kn 1e3 en 0.5 mu 0.5
timestep 1e-6
"""


def _sim(text, bc="f f f", box="-0.02 0.02 -0.02 0.02 -0.001 0.03"):
    sim = dem.Simulation(screen=False)
    sim.commands(HEAD.format(bc=bc, box=box) + text)
    return sim


def _quat_to(u):
    """Unit quaternion (w, x, y, z) of the rotation taking unit vector u onto -z."""
    u = np.asarray(u, float) / np.linalg.norm(u)
    t = np.array([0.0, 0.0, -1.0])
    h = (u + t) / np.linalg.norm(u + t)
    q = np.r_[np.dot(u, h), np.cross(u, h)]
    return q / np.linalg.norm(q)


def test_types_face_edge_vertex_on_fixed_cubes():
    """Three fixed cubes, on each a cube resting face-down (4 points), edge-down (2) and vertex-down (1),
    1e-9 m into the base: face/face, edge/face and vertex/face contacts. Each of the 6 cubes has one contact,
    so z_s = z_d = z_t = 1/3 (2 ends of 6 particles each), z_iso = 1/3 + 2/3 + 1 = 2, z_tot = 1, shares 1/3;
    restricted to the region around the face-down top cube: z_t = 1, z_iso = 3. Exact counts."""
    ov = 1e-9
    tops = [(-0.01, 0.5 * A), (0.0, 0.5 * np.sqrt(2) * A), (0.01, 0.5 * np.sqrt(3) * A)]   # lowest point depth
    lines = []
    for x, h in tops:
        lines.append(f"create_atoms 1 single {x} 0 0.001 shape c density 1250")
        lines.append(f"create_atoms 1 single {x} 0 {float(0.002 + h - ov)!r} shape c density 1250")
    sim = _sim("\n".join(lines) + """
region top block -0.012 -0.008 -0.01 0.01 0.0025 0.0035
compute z all contact/types
compute zt all contact/types region top
""")
    q = sim.atom.data["quat"]
    q[3] = [np.cos(np.pi / 8), np.sin(np.pi / 8), 0.0, 0.0]       # 45 deg about x: an edge down
    q[5] = _quat_to([1.0, 1.0, 1.0])                             # a body diagonal down: a vertex
    sim.run(0)
    assert sim.pair.contact_types == dict(vertex_face=1, edge_edge=0, edge_face=1, face_face=1, sphere=0)
    v = sim.computes["z"].vector()
    third = 1.0 / 3.0
    assert v == pytest.approx([third, third, third, 2.0, 1.0, third, third, third, 6, 6], rel=1e-14)
    vt = sim.computes["zt"].vector()
    assert vt == pytest.approx([0, 0, 1, 3, 1, 0, 0, 1, 1, 1], abs=1e-14)
    assert sim.output.thermo.keyword("c_zt[4]") == 3.0


def test_stress_of_a_pair_across_the_periodic_boundary():
    """Two cubes face to face across the periodic x boundary, delta = 1e-7 m into each other: the contact is
    found through a ghost, and the tallies come back to the owners (per-particle types: one face/face
    contact each). Love-Weber: sigma_xx V = F l with F = kn delta, l = a - delta the minimum-image branch
    length; every other component 0 (4 symmetric corners: round-off, bound 1e-9 sigma_xx)."""
    d = 1e-7
    L = 0.02
    x0 = -0.01 + 0.5 * (A - d)
    sim = _sim(f"""create_atoms 1 single {float(x0)!r} 0 0 shape c density 1250
create_atoms 1 single {float(x0 - (A - d) + L)!r} 0 0 shape c density 1250
compute s all stress
compute z all contact/types
""", bc="p p p", box="-0.01 0.01 -0.01 0.01 -0.01 0.01")
    sim.run(0)
    assert sim.pair.ncontacts == 1 and sim.pair.npoints == 4
    assert np.array_equal(sim.atom.local("tally_types"), [[0, 0, 0, 1, 0], [0, 0, 0, 1, 0]])
    s = sim.computes["s"].vector()
    expect = KN * d * (A - d) / L ** 3
    assert s[0] == pytest.approx(expect, rel=1e-9)
    assert np.all(np.abs(s[1:]) < 1e-9 * expect)
    assert sim.computes["s"].scalar() == pytest.approx(expect / 3, rel=1e-9)


def column(n, extra=""):
    """n cubes stacked on a fixed base cube at their static overlaps delta_k = W_k / kn, W_k = (n - k + 1) m g
    the weight the k-th contact carries, at rest: the contact forces are the weights exactly."""
    z = [0.5 * A]
    for k in range(1, n + 1):
        z.append(z[-1] + A - (n - k + 1) * M * G / KN)
    lines = [f"create_atoms 1 single 0 0 {float(zk)!r} shape c density 1250" for zk in z]
    sim = _sim("\n".join(lines) + "\n" + extra, box="-0.001 0.001 -0.001 0.001 0 0.012")
    return sim, np.array(z)


def test_static_column_stress_equals_weight(tmp_path):
    """A column of 4 cubes at rest on a fixed cube, in a box of cross-section A_box = a^2 and height 6a.
    Global (compute stress, V the box): sigma_zz V = sum_k W_k l_k exactly (W_k the weight above contact k,
    l_k the centre distance), to round-off (bound 1e-9); to O(delta / a) this is m g a (1 + 2 + 3 + 4).
    Profile (fix ave/profile, one cube per slab of height a): the slab of cube k carries half of its two
    contacts, (W_k l_k + W_k+1 l_k+1) / 2 / (a A_box), which is the weight above the cube's centre per unit
    area, (n - k + 1/2) m g / A_box, to delta / a = 5e-5 (bound 2e-4): a column at rest under gravity."""
    n = 4
    path = tmp_path / "column.dat"
    sim, z = column(n, f"""compute s all stress
region everywhere block INF INF INF INF -1 1
region top block INF INF INF INF 0.0025 1
compute sr all stress region everywhere
compute sv all stress region top volume 1e-6
fix p all ave/profile 1 1 {path} z 6 szz sxx count
""")
    sim.run(1)             # no integrator: nothing moves; the profile samples the end of step 1
    w = np.array([(n - k + 1) * M * G for k in range(1, n + 1)])
    l = np.diff(z)
    vol = A * A * 0.012
    s = sim.computes["s"].vector()
    assert s[2] == pytest.approx(float(np.dot(w, l)) / vol, rel=1e-9)
    assert s[2] == pytest.approx(M * G * A * 10 / vol, rel=2e-4)
    assert abs(s[0]) < 1e-9 * s[2] and abs(s[3]) < 1e-9 * s[2]
    # a region with infinite bounds is clipped to the box; one above the base cube leaves out its half
    # of the first contact (the base's centre is below it), here over a given volume
    assert sim.computes["sr"].vector() == pytest.approx(s, rel=1e-12, abs=1e-12 * s[2])
    w_l_top = float(np.dot(w, l)) - 0.5 * w[0] * l[0]
    assert sim.computes["sv"].vector()[2] == pytest.approx(w_l_top / 1e-6, rel=1e-9)
    data = np.loadtxt(path)
    szz, sxx, count = data[:, 4], data[:, 5], data[:, 6]
    assert np.array_equal(count, [1, 1, 1, 1, 1, 0])
    for k in range(1, n + 1):
        above = (w[k - 1] * l[k - 1] + (w[k] * l[k] if k < n else 0.0)) / 2 / (A ** 3)
        assert szz[k] == pytest.approx(above, rel=1e-9)
        assert szz[k] == pytest.approx((n - k + 0.5) * M * G / A ** 2, rel=2e-4)
    assert np.all(np.abs(sxx) < 1e-9 * szz.max())


def test_stress_of_spheres_and_unsupported_types():
    """pair_style sphere tallies the stress too (central contacts: levers r - delta/2 from each centre):
    two spheres across the periodic boundary, sigma_xx V = kn delta (2 r - delta) (Hooke law) to round-off.
    contact/types needs the polyhedron kernel: a clear error naming the compute and the pair style."""
    r, d, L = 0.001, 1e-7, 0.02
    text = f"""units si
boundary p p p
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 1 box
create_atoms 1 single {float(-0.01 + r - 0.5 * d)!r} 0 0 radius {r} density 1000
create_atoms 1 single {float(0.01 - r + 0.5 * d)!r} 0 0 radius {r} density 1000
pair_style sphere
pair_coeff * * kn 1e3 en 0.5 mu 0.5
timestep 1e-6
compute s all stress
"""
    sim = dem.Simulation(screen=False)
    sim.commands(text)
    sim.run(0)
    assert sim.computes["s"].vector()[0] == pytest.approx(KN * d * (2 * r - d) / L ** 3, rel=1e-9)
    sim.command("compute z all contact/types")
    with pytest.raises(DemError, match=r"compute z \(contact/types\).*types tally.*pair_style sphere"):
        sim.run(0)


def test_bad_input():
    sim = _sim("create_atoms 1 single 0 0 0.001 shape c density 1250\n")
    with pytest.raises(DemError, match="region"):
        sim.command("compute z all contact/types region nowhere")
    with pytest.raises(DemError, match="kinetic must be yes or no"):
        sim.command("compute s all stress kinetic maybe")
    sim.command("compute s all stress")
    with pytest.raises(DemError, match="filled by the force evaluation"):
        sim.computes["s"].vector()


LATTICE = """units si
boundary p p p
processors * 1 1
region box block 0 3.996 0 4.8 0 4.8
create_box 1 box
shape c cube 1
{atoms}
pair_style polyhedron/multipoint
pair_coeff * * kn 1e3 en 0.5
timestep 1e-4
compute z all contact/types
compute s all stress
thermo_style custom step c_z[3] c_z[4] c_s[1] c_s[2] c_s[3] c_s[4]
thermo_modify format float %.17g
run 0
"""


def test_lattice_on_one_and_two_ranks(tmp_path):
    """4^3 unit cubes on a periodic lattice, spacing 0.999 along x and 1.2 along y and z: rows of cubes
    pressed face to face, delta = 1e-3, a quarter of the contacts through periodic images: z_t = 2,
    z_iso = 6 exactly, sigma_xx = 64 kn delta 0.999 / V (64 contacts, branch 0.999), sigma_yy and shear 0,
    to round-off (bound 1e-9), on 1 rank and on 2 (cut across x, the contact direction: ghost tallies
    come back to their owners on the other rank through the MPI reverse communication)."""
    from conftest import MPIEXEC
    from test_mpi import run_dem, thermo_rows
    expect = 64 * KN * 1e-3 * 0.999 / (3.996 * 4.8 * 4.8)
    atoms = "\n".join(f"create_atoms 1 single {float((i + 0.5) * 0.999)!r} {float((j + 0.5) * 1.2)!r} "
                      f"{float((k + 0.5) * 1.2)!r} shape c density 1"
                      for i in range(4) for j in range(4) for k in range(4))
    for nprocs in (1, 2):
        if nprocs == 2 and MPIEXEC is None:
            pytest.skip("mpiexec not found")
        run_dem(tmp_path, LATTICE.format(atoms=atoms), nprocs, f"log.{nprocs}")
        row = [float(w) for w in thermo_rows(tmp_path / f"log.{nprocs}")[-1]]
        assert row[1:3] == [2.0, 6.0]
        assert row[3] == pytest.approx(expect, rel=1e-9)
        assert max(abs(r) for r in row[4:7]) < 1e-9 * expect


def test_stress_of_convex_gjk_equals_force_times_branch():
    """convex/gjk (a sphere on a slightly tilted cube, off its axis: one GJK point, levers from each centre,
    force and branch not parallel): whatever the point,
    the two bodies' terms sum to F (x) (G_j - G_i), so sigma V = -F_i (x) (x_j - x_i) from the force array, to
    round-off (bound 1e-9 of the largest component), tensor symmetric by construction."""
    sim = dem.Simulation(screen=False)
    sim.commands("""units si
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 1 box
shape c cube 0.002
create_atoms 1 single 0 0 0 shape c density 2500 quat 0.99875 0.05 0 0
create_atoms 1 single 0.0004 0.0003 0.00197 radius 0.001 density 2500
pair_style convex/gjk
pair_coeff * * kn 1e5 en 0.5 mu 0.5
fix nve all nve/shape
timestep 1e-7
compute s all stress volume 1e-6
""")
    sim.run(0)
    assert sim.pair.ncontacts == 1
    f0 = sim.atom.local("f")[0]
    x = sim.atom.local("x")
    t = -np.outer(f0, x[1] - x[0])
    t = 0.5 * (t + t.T)
    expect = np.array([t[0, 0], t[1, 1], t[2, 2], t[0, 1], t[0, 2], t[1, 2]]) / 1e-6
    assert sim.computes["s"].vector() == pytest.approx(expect, abs=1e-9 * np.abs(expect).max())
