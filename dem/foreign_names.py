"""LIGGGHTS and LAMMPS names that dem does not take, each with dem's equivalent in one line.

The one source of these answers: an unknown command or style found here is answered with its row
instead of a "did you mean" (`dem.errors.unknown_style`), and docs/migration.md shows the same rows
(`markdown_table`; tests/test_migration.py checks the page against this table). A row's answer must be
true of dem today: it names dem's command with its words, says plainly when dem has nothing like it,
and what to do instead.

A row is (kind, name, when, origin, answer). kind is the registry's ("command", "pair", "fix", "dump",
"compute", "region"); `when` is a word of the line's arguments that selects a sharper answer than the
name's general row (`pair_style gran model hooke`, `fix wall/gran ... mesh`, `fix property/global
youngsModulus ...`), None for the general row every name has. No name may be a dem style: the table
answers only what dem would otherwise call unknown (tests/test_migration.py asserts it).
"""

LIGGGHTS, LAMMPS, BOTH = "LIGGGHTS", "LAMMPS", "LAMMPS and LIGGGHTS"

_MATERIAL = "pair_coeff * * model hertz E 5e6 nu 0.45 en 0.3 mu 0.5"
_REMOVE = "dem does not need this line: remove it"
_LAW = "kn KN en EN mu MU ks KS | model hertz E .. nu .. en .. mu .. (or none: pair_coeff T T of the wall's type T)"

ROWS = [
    # -- commands ------------------------------------------------------------------------------------------
    ("command", "communicate", None, LIGGGHTS,
     f"{_REMOVE} (it is LAMMPS's comm_modify; dem's ghosts always carry velocities and follow the particle sizes)"),
    ("command", "compute_modify", None, BOTH,
     f"{_REMOVE}: dem has no temperature compute (thermo_temp) whose degrees of freedom to change, and its "
     "computes take their group's particles anew at every evaluation (inserted ones included: always 'dynamic yes')"),
    ("command", "fix_modify", None, LAMMPS,
     "dem has no fix_modify: its fixes take no energy or virial options; read a fix's values with "
     "f_ID[name] in thermo_style: remove the line"),
    ("command", "hard_particles", None, LIGGGHTS,
     f"{_REMOVE}: dem takes any stiffness and stops the run when an overlap exceeds thermo_modify overlap "
     "(a fraction of the smaller diameter, default 0.2)"),
    ("command", "soft_particles", None, LIGGGHTS,
     f"{_REMOVE}: dem takes any Young's modulus (pair_coeff ... model hertz E ..); time step: a warning at "
     "each run when dt exceeds a tenth of the contact time"),
    ("command", "velocity", None, LAMMPS,
     "dem's set group G v VX VY VZ (and omega WX WY WZ) gives velocities; fix insert and create_atoms take "
     "v VX VY VZ on their line"),
    ("command", "mass", None, LAMMPS,
     "dem's mass follows from density and size: density RHO on create_atoms or fix insert, or set ... "
     "density RHO | mass M: remove the line"),
    ("command", "lattice", None, LAMMPS,
     "dem's create_atoms TYPE lattice REGION-ID sc|bcc|fcc SPACING takes the lattice on its own line: "
     "remove this line"),
    ("command", "delete_atoms", None, LAMMPS,
     "dem has no delete_atoms: fix ID group remove REGION-ID deletes the group's particles inside a region "
     "during the next run"),
    ("command", "log", None, LAMMPS,
     "dem names its log on the command line: dem -in SCRIPT -log FILE|none: remove the line"),
    ("command", "minimize", None, LAMMPS,
     "dem has no energy minimisation: let a bed settle in a run, faster with fix ID all damping/potyondy "
     "alpha 0.7"),
    ("command", "run_style", None, LAMMPS,
     f"{_REMOVE}: dem has one integrator, the leap-frog of fix nve/sphere or nve/shape"),
    ("command", "kspace_style", None, LAMMPS, "dem has no long-range forces: remove the line"),
    # -- pair styles ---------------------------------------------------------------------------------------
    ("pair", "gran", None, LIGGGHTS,
     "pair_style sphere, the law on the pair_coeff line: model hertz tangential history is "
     f"'{_MATERIAL}' (the property/global values), model hooke is 'pair_coeff * * kn KN en EN mu MU ks KS' "
     "(docs/contact_law.md for cohesion and rolling)"),
    ("pair", "gran", "hertz", LIGGGHTS,
     f"pair_style sphere with '{_MATERIAL}': the fix property/global values become the words E nu en mu "
     "(Hertz-Mindlin with tangential history, docs/hertz.md)"),
    ("pair", "gran", "hooke", LIGGGHTS,
     "pair_style sphere with 'pair_coeff * * kn KN en EN mu MU ks KS': dem takes the Hooke stiffness kn "
     "itself (from LIGGGHTS's E, nu and characteristicVelocity V: dem-hooke-from-hertz --E .. --nu .. "
     "--density .. --diameter .. --v V); ks 2/7 kn is LAMMPS's default"),
    ("pair", "gran/hooke", None, BOTH,
     "pair_style sphere with 'pair_coeff * * kn KN en EN mu MU' (no tangential spring: give gamma_t GT "
     "for the viscous tangential force)"),
    ("pair", "gran/hooke/history", None, BOTH,
     "pair_style sphere with 'pair_coeff * * kn KN en EN mu MU ks KS' (ks: LAMMPS's Kt; dem supplies no "
     "default, 2/7 kn is LAMMPS's; en, the restitution, replaces LAMMPS's damping gamma_n)"),
    ("pair", "gran/hertz/history", None, BOTH,
     f"pair_style sphere with '{_MATERIAL}': dem takes the materials, not LAMMPS's Kn per unit area "
     "(Kn = 4/3 Y*: Y* = E / (2 (1 - nu^2)))"),
    ("pair", "granular", None, LAMMPS,
     "pair_style sphere: LAMMPS's pair_coeff models are dem's parts on the pair_coeff line, e.g. "
     "'pair_coeff * * normal hertz E 1e7 nu 0.3 en 0.5 tangential mindlin mu 0.5 rolling epsd mu_roll 0.1 "
     "eta_roll 0.3' (docs/contact_law.md)"),
    ("pair", "hybrid", None, LAMMPS,
     "dem has one pair style per run; different laws per type pair are pair_coeff lines of pair_style sphere "
     "(docs/contact_law.md)"),
    ("pair", "hybrid/overlay", None, LAMMPS,
     "dem has one pair style per run; cohesion on top of the contact law is a part of pair_coeff: "
     "cohesion sjkr|capillary (docs/contact_law.md)"),
    ("pair", "soft", None, LAMMPS,
     "dem has no soft push-off: create_atoms random and fix insert place particles without overlap"),
    # -- fixes ---------------------------------------------------------------------------------------------
    ("fix", "property/global", None, LIGGGHTS,
     "material properties are words of dem's pair_coeff line (and of a wall's): youngsModulus E, "
     "poissonsRatio nu, coefficientRestitution en, coefficientFriction mu, coefficientRollingFriction "
     f"mu_roll, e.g. '{_MATERIAL}': remove the line"),
    ("fix", "property/global", "youngsModulus", LIGGGHTS,
     f"Young's modulus is the word E of dem's pair_coeff line ('{_MATERIAL}'): remove the line"),
    ("fix", "property/global", "poissonsRatio", LIGGGHTS,
     f"Poisson's ratio is the word nu of dem's pair_coeff line ('{_MATERIAL}'): remove the line"),
    ("fix", "property/global", "coefficientRestitution", LIGGGHTS,
     f"the restitution is the word en of dem's pair_coeff line ('{_MATERIAL}'; pair_coeff I J per type "
     "pair): remove the line"),
    ("fix", "property/global", "coefficientFriction", LIGGGHTS,
     f"the friction coefficient is the word mu of dem's pair_coeff line ('{_MATERIAL}'): remove the line"),
    ("fix", "property/global", "coefficientRollingFriction", LIGGGHTS,
     "the rolling friction is the word mu_roll of dem's pair_coeff line (rolling constant, the default; "
     "LIGGGHTS's epsd2: rolling epsd2 mu_roll ..): remove the line"),
    ("fix", "property/global", "coefficientRollingViscousDamping", LIGGGHTS,
     "the rolling damping is the word eta_roll of dem's pair_coeff line with rolling epsd (pair_coeff * * "
     "... rolling epsd mu_roll .. eta_roll ..): remove the line"),
    ("fix", "property/global", "cohesionEnergyDensity", LIGGGHTS,
     "LIGGGHTS's sjkr cohesion is the pair_coeff part 'cohesion sjkr cohesion_energy_density K' "
     "(docs/contact_law.md): remove the line"),
    ("fix", "property/global", "characteristicVelocity", LIGGGHTS,
     "dem's Hooke law takes kn itself: dem-hooke-from-hertz --E .. --nu .. --density .. --diameter .. "
     "--v V (V this velocity) gives the kn of LIGGGHTS's model hooke for pair_coeff: remove the line"),
    ("fix", "property/global", "k_finnie", LIGGGHTS,
     "dem does not model wear (Finnie): remove the line; fix wall/mesh gives the force on the mesh, "
     "f_ID[fx] f_ID[fy] f_ID[fz]"),
    ("fix", "property/atom", None, LIGGGHTS,
     "dem has no per-particle properties declared by the script and no heat transfer: remove the line "
     "(the particle fields are in dump custom and sim.gather)"),
    ("fix", "mesh/surface", None, LIGGGHTS,
     "LIGGGHTS's fix mesh/surface + fix wall/gran ... mesh are one dem command: fix ID group wall/mesh file "
     "FILE [scale S] [move DX DY DZ] [rotate axis X Y Z angle A] [law words], so remove this line and write that in "
     "place of the wall/gran line; a mesh used only as an insertion_face becomes a block region for fix insert"),
    ("fix", "mesh/surface/stress", None, LIGGGHTS,
     "as mesh/surface, one dem command with the wall: fix ID group wall/mesh file FILE ...; the force and "
     "torque on the mesh are its thermo values f_ID[fx] .. f_ID[tz]; wear is not modelled"),
    ("fix", "mesh/surface/stress/servo", None, LIGGGHTS,
     "dem has no servo-controlled wall: fix wall/mesh moves at an imposed velocity (linear, turn) or by a "
     "motion table (table FILE)"),
    ("fix", "move/mesh", None, LIGGGHTS,
     "the motion is on dem's fix wall/mesh line: linear VX VY VZ | turn origin X Y Z axis X Y Z rpm W | "
     "table FILE (any imposed motion, e.g. a vibration): remove this line"),
    ("fix", "wall/gran", None, BOTH,
     "dem's walls: fix ID group wall/plane xplane|yplane|zplane LO HI (NULL for none; LAMMPS's zplane LO HI), "
     "wall/drum AXIS C1 C2 R (a zcylinder), wall/mesh file FILE (a mesh), with the law words "
     f"{_LAW}"),
    ("fix", "wall/gran", "primitive", LIGGGHTS,
     "fix ID group wall/plane xplane|yplane|zplane LO HI: both walls of an axis in one fix (NULL for none: "
     "xplane -0.05 NULL), type T as here (the law of pair_coeff T I); zcylinder R C1 C2 is wall/drum z C1 C2 R"),
    ("fix", "wall/gran", "mesh", LIGGGHTS,
     "LIGGGHTS's fix mesh/surface + fix wall/gran ... mesh are one dem command: fix ID group wall/mesh file "
     "FILE [scale S] [move DX DY DZ] [rotate axis X Y Z angle A] (the mesh/surface's words) with the law "
     f"words {_LAW}"),
    ("fix", "wall/gran/hooke", None, LIGGGHTS,
     "fix ID group wall/plane xplane|yplane|zplane LO HI with kn KN en EN mu MU (or wall/mesh, wall/drum)"),
    ("fix", "wall/gran/hooke/history", None, LIGGGHTS,
     "fix ID group wall/plane xplane|yplane|zplane LO HI with kn KN en EN mu MU ks KS (or wall/mesh, wall/drum)"),
    ("fix", "wall/gran/hertz/history", None, LIGGGHTS,
     "fix ID group wall/plane xplane|yplane|zplane LO HI with model hertz E .. nu .. en .. mu .. "
     "(or wall/mesh, wall/drum)"),
    ("fix", "wall/gran/region", None, LAMMPS,
     "dem's walls are planes (wall/plane), drums (wall/drum) and triangle meshes (wall/mesh file FILE): "
     "write the region's surface as an STL file"),
    ("fix", "wall/region", None, LAMMPS,
     "dem's walls are planes (wall/plane), drums (wall/drum) and triangle meshes (wall/mesh file FILE)"),
    ("fix", "particletemplate/sphere", None, LIGGGHTS,
     "dem's fix insert draws the sizes itself: radius R | radius uniform A B | radius gaussian M SD | radius "
     "discrete R1 F1 R2 F2 ..., with density RHO and type T on the fix insert line: remove this line"),
    ("fix", "particletemplate/multisphere", None, LIGGGHTS,
     "a clump is a shape: shape NAME multisphere X Y Z R ..., inserted with fix insert ... shape NAME, "
     "in contact by pair_style glued/convex, moved by fix nve/shape"),
    ("fix", "particletemplate/superquadric", None, LIGGGHTS,
     "a shape: shape NAME superquadric A B C N1 N2, inserted with fix insert ... shape NAME, pair_style "
     "convex/gjk, fix nve/shape"),
    ("fix", "particledistribution/discrete", None, LIGGGHTS,
     "the mixture is on dem's fix insert line: radius discrete R1 F1 R2 F2 ... (F in number fractions: "
     "LIGGGHTS's mass fractions w become w / R^3, normalised) or, for shapes, mix NAME1 W1 NAME2 W2 (mass "
     "fractions): remove this line"),
    ("fix", "insert/pack", None, LIGGGHTS,
     "fix ID group insert SEED REGION-ID volfrac PHI (volumefraction_region) | count N (particles_in_region) "
     "with the sizes (radius ...), density RHO, type T and v VX VY VZ (vel constant) on the line; all at the "
     "first step (insert_every once), no overlap and all inside the region always"),
    ("fix", "insert/stream", None, LIGGGHTS,
     "fix ID group insert SEED REGION-ID count N massrate Q (particlerate P: Q = P x particle mass) with "
     "radius ..., density RHO, v VX VY VZ; the insertion_face swept by extrude_length is a block region"),
    ("fix", "insert/rate/region", None, LIGGGHTS,
     "fix ID group insert SEED REGION-ID count N massrate Q (or every M per K) with radius ..., density RHO, "
     "v VX VY VZ"),
    ("fix", "pour", None, LAMMPS,
     "fix ID group insert SEED REGION-ID count N [every M per K] radius ... density RHO v VX VY VZ"),
    ("fix", "check/timestep/gran", None, LIGGGHTS,
     f"{_REMOVE} and its f_ID values from thermo_style: dem checks the time step at every run (a warning "
     "when dt exceeds a tenth of the shortest contact time, Hertz's at twice the largest speed)"),
    ("fix", "multisphere", None, LIGGGHTS,
     "fix ID group nve/shape moves clumps (shape NAME multisphere ...), pair_style glued/convex"),
    ("fix", "nve/asphere", None, LAMMPS, "fix ID group nve/shape (every shape, spheres included)"),
    ("fix", "nve/superquadric", None, LIGGGHTS, "fix ID group nve/shape (every shape, spheres included)"),
    ("fix", "rigid", None, LAMMPS,
     "a rigid clump is a shape: shape NAME glued ... | multisphere ..., moved by fix nve/shape, "
     "pair_style glued/convex"),
    ("fix", "rigid/small", None, LAMMPS,
     "a rigid clump is a shape: shape NAME glued ... | multisphere ..., moved by fix nve/shape, "
     "pair_style glued/convex"),
    ("fix", "viscous", None, LAMMPS,
     "dem has no viscous drag; to settle a bed: fix ID group damping/potyondy alpha A (local non-viscous "
     "damping, define it after the force fixes)"),
    ("fix", "freeze", None, LAMMPS,
     "dem has no fix freeze: particles outside the group of the integration fix (nve/sphere) do not move "
     "and still touch the others; or make the obstacle a wall (wall/mesh)"),
    ("fix", "adapt", None, LAMMPS,
     "dem has no fix adapt: set group G diameter D between runs (mass at constant density); a dense packing: "
     "fix insert and settle under gravity (inputs/in.packing_box)"),
    ("fix", "ave/time", None, LAMMPS,
     "fix ID group print/series N FILE value ... (the values at every N steps) or ave/vector Nevery Nfreq "
     "FILE c_ID ... (time averages of compute vectors)"),
    ("fix", "ave/spatial", None, BOTH,
     "fix ID group ave/profile Nevery Nfreq FILE x|y|z NBIN value ..."),
    ("fix", "ave/chunk", None, LAMMPS,
     "fix ID group ave/profile Nevery Nfreq FILE x|y|z NBIN value ... (radial bins too)"),
    ("fix", "print", None, LAMMPS, "fix ID group print/series N FILE value ..."),
    ("fix", "heat/gran", None, LIGGGHTS, "dem does not model heat transfer: remove the line"),
    ("fix", "heat/gran/conduction", None, LIGGGHTS, "dem does not model heat transfer: remove the line"),
    ("fix", "enforce2d", None, LAMMPS,
     "dem is three-dimensional: a 2D problem is a thin periodic slab one particle deep"),
    ("fix", "couple/cfd", None, LIGGGHTS, "dem has no CFD coupling"),
    # -- dumps ---------------------------------------------------------------------------------------------
    ("dump", "custom/vtk", None, LIGGGHTS,
     "dump ID group vtk N file_*.vtu [fields id type velocity omega radius ...] (ParaView; fix wall/mesh "
     "meshes come with every frame) or vtp for OVITO"),
    ("dump", "mesh/stl", None, LIGGGHTS,
     "dem does not need this line: remove it (dem's dump vtk and h5 write every fix wall/mesh mesh with "
     "each frame, where it is then)"),
    ("dump", "mesh/vtk", None, LIGGGHTS,
     "dem does not need this line: remove it (dem's dump vtk and h5 write every fix wall/mesh mesh with "
     "each frame; the force on it is f_ID[fx] .. of the fix)"),
    ("dump", "mesh/gran/VTK", None, LIGGGHTS,
     "dem does not need this line: remove it (dem's dump vtk and h5 write every fix wall/mesh mesh with "
     "each frame; the force on it is f_ID[fx] .. of the fix; wear is not modelled)"),
    ("dump", "local/gran/vtk", None, LIGGGHTS,
     "dem writes contact points only for pair_style polyhedron/multipoint (dump ID all contacts N "
     "file_*.vtp); for spheres, compute stress and coord give the contact statistics"),
    ("dump", "atom", None, LAMMPS, "dump ID group custom N FILE id type x y z"),
    ("dump", "atom/vtk", None, LAMMPS, "dump ID group vtk N file_*.vtu"),
    ("dump", "xyz", None, LAMMPS, "dump ID group custom N FILE id type x y z"),
    ("dump", "image", None, LAMMPS,
     "dump ID group png N FILE [axis x|y|z]: pictures along an axis coloured by speed"),
    ("dump", "local", None, LAMMPS,
     "dem has no per-contact dump for spheres (dump contacts: pair_style polyhedron/multipoint)"),
    # -- computes ------------------------------------------------------------------------------------------
    ("compute", "erotate/sphere", None, BOTH, "compute ID group erotate (every shape, spheres included)"),
    ("compute", "erotate/superquadric", None, LIGGGHTS, "compute ID group erotate (every shape)"),
    ("compute", "erotate/asphere", None, LAMMPS, "compute ID group erotate (every shape)"),
    ("compute", "pair/gran/local", None, LIGGGHTS,
     "dem has no per-contact output for spheres: compute stress (the contact stress tensor), coord, "
     "contact/types; dump contacts for pair_style polyhedron/multipoint"),
    ("compute", "wall/gran/local", None, LIGGGHTS,
     "dem has no per-contact wall output: the wall fixes give f_ID[contacts] and (wall/mesh) the force "
     "f_ID[fx] .. on the wall"),
    ("compute", "contact/atom", None, BOTH,
     "compute ID group coord (the mean contacts per particle, walls counted in its second value)"),
    ("compute", "coord/atom", None, LAMMPS, "compute ID group coord (the mean contacts per particle)"),
    ("compute", "property/atom", None, BOTH,
     "the per-particle values are columns of dump custom (radius, mass, vx ...) and sim.gather('radius') "
     "in Python"),
    ("compute", "reduce", None, LAMMPS,
     "dem has no compute reduce: thermo keywords (ke, atoms, maxov), compute vmean, body (centre of mass "
     "and mean velocity of a group)"),
    ("compute", "com", None, LAMMPS, "compute ID group body (centre of mass, then mean velocity and spin)"),
    ("compute", "temp", None, LAMMPS,
     "dem has no temperature compute: compute ke; the granular temperature is fix ave/profile's T"),
    ("compute", "stress/atom", None, LAMMPS, "compute ID group stress (the group's stress tensor)"),
    ("compute", "nparticles/tracer/region", None, LIGGGHTS,
     "dem has no tracer counts; fix remove counts particles leaving through a region (f_ID[removed])"),
    # -- regions -------------------------------------------------------------------------------------------
    ("region", "mesh/tet", None, LIGGGHTS, "dem's regions are block, cylinder and sphere"),
    ("region", "prism", None, LAMMPS, "dem's regions are block, cylinder and sphere"),
    ("region", "cone", None, LAMMPS, "dem's regions are block, cylinder and sphere"),
    ("region", "plane", None, LAMMPS, "dem's regions are block, cylinder and sphere (side in|out); a floor or a wall is fix wall/plane"),
    ("region", "intersect", None, LAMMPS,
     "dem's regions are block, cylinder and sphere; group ID intersect G1 G2 combines groups"),
    ("region", "union", None, LAMMPS,
     "dem's regions are block, cylinder and sphere; group ID union G1 G2 combines groups"),
]

_ROWS = {(kind, name, when): (origin, answer) for kind, name, when, origin, answer in ROWS}


class Answer:
    """One row: where the name comes from and dem's equivalent."""

    def __init__(self, kind, name, when, origin, text):
        self.kind, self.name, self.when, self.origin, self.text = kind, name, when, origin, text


def answer(kind, name, args=()):
    """The row for `name` of this kind: the first of its `when` rows whose word is among args, else its
    general row; None when the table does not know the name."""
    if (kind, name, None) not in _ROWS:
        return None
    words = set(args)
    for row_kind, row_name, when, origin, text in ROWS:
        if row_kind == kind and row_name == name and when is not None and when in words:
            return Answer(kind, name, when, origin, text)
    return Answer(kind, name, None, *_ROWS[(kind, name, None)])


def names(kind):
    """The table's names of this kind (for the did-you-mean of a misspelt one)."""
    return sorted({name for row_kind, name, *_ in ROWS if row_kind == kind})


KIND_WORD = {"command": "", "pair": "pair_style ", "fix": "fix ID group ", "dump": "dump ID group ",
             "compute": "compute ID group ", "region": "region ID "}


def idiom(kind, name, when):
    """How the row's line starts in a LIGGGHTS or LAMMPS script, e.g. `fix ID group wall/gran ... mesh`."""
    text = f"{KIND_WORD[kind]}{name}"
    return f"{text} ... {when}" if when else text


def markdown_table():
    """The rows as the Markdown table of docs/migration.md."""
    out = ["| script line | from | in dem |", "|---|---|---|"]
    for kind, name, when, origin, text in ROWS:
        out.append(f"| `{idiom(kind, name, when)}` | {origin} | {text.replace('|', '&#124;')} |")
    return "\n".join(out)
