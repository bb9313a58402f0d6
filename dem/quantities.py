"""What a thermo keyword, a compute value (c_ID, c_ID[k]) or a fix value (f_ID[name]) is, and its unit (SI;
"-" dimensionless), for the labels of plots (dem-plot) and the header of fix print/series. The thermo
keywords are this table (dem/thermo.py computes them); computes and fixes declare their own
(Compute.quantity, Fix.thermo_quantities). None where nothing is declared: a plot then shows the name."""
import re

THERMO = {
    "step": ("step", "-"), "time": ("simulated time", "s"), "dt": ("time step", "s"),
    "atoms": ("particles", "-"),
    "ke": ("translational kinetic energy", "J"), "erot": ("rotational kinetic energy", "J"),
    "pe": ("elastic energy of the contacts", "J"), "etotal": ("total energy", "J"),
    "contacts": ("particle-particle contacts", "-"), "cn": ("coordination number", "-"),
    "maxov": ("largest overlap / smaller diameter", "-"),
    "lost": ("particles lost", "-"), "nbuild": ("neighbour list builds", "-"),
    "xlo": ("box x low", "m"), "xhi": ("box x high", "m"), "ylo": ("box y low", "m"),
    "yhi": ("box y high", "m"), "zlo": ("box z low", "m"), "zhi": ("box z high", "m"),
    "lx": ("box length x", "m"), "ly": ("box length y", "m"), "lz": ("box length z", "m"),
    "vol": ("box volume", "m^3"),
    "cpu": ("wall time of the run", "s"), "pct": ("run done", "%"), "tps": ("steps per second", "1/s"),
    "eta": ("run's time left", "s"), "jpct": ("job done", "%"), "jeta": ("job's time left", "s"),
    "spcpu": ("steps per second", "1/s"), "tpcpu": ("simulated seconds per second", "-"),
    "cpuremain": ("run's time left", "s"),
}

_FIX = re.compile(r"^f_([^\[\]]+)\[([^\[\]]+)\]$")
_COMPUTE = re.compile(r"^c_([^\[\]]+)(?:\[(\d+)\])?$")
HEADER = "# quantity [unit]: "          # the print/series header line that names them
SEPARATOR = " | "
UNKNOWN = "?"


def describe(sim, name):
    """(quantity, unit) of an output name in this simulation, or None."""
    if name in THERMO:
        return THERMO[name]
    match = _COMPUTE.match(name)
    if match and match.group(1) in sim.computes:
        index = int(match.group(2)) if match.group(2) else None
        return sim.computes[match.group(1)].quantity(index)
    match = _FIX.match(name)
    if match:
        fix = next((f for f in sim.modify.fixes if f.id == match.group(1)), None)
        if fix is not None:
            return fix.thermo_quantities.get(match.group(2))
    return None


def label(name, described=None):
    """The axis label of an output: `name [unit]` (the name alone where its unit is not known)."""
    described = described or THERMO.get(name)
    return f"{name} [{described[1]}]" if described else name


def header_line(descriptions):
    """The print/series line naming each column's quantity and unit (UNKNOWN where not known)."""
    return HEADER + SEPARATOR.join(f"{d[0]} [{d[1]}]" if d else UNKNOWN for d in descriptions)


def parse_header_line(line):
    """[(quantity, unit) or None] of a header_line, None when `line` is not one."""
    if not line.startswith(HEADER):
        return None
    out = []
    for item in line[len(HEADER):].rstrip("\n").split(SEPARATOR):
        match = re.fullmatch(r"(.*) \[(.*)\]", item.strip())
        out.append((match.group(1), match.group(2)) if match else None)
    return out
