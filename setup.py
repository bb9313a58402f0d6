"""Build dem: the core package `dem`, the built-in plugin packages under `plugins/`, and every Cython
kernel (`*.pyx`) found in them. Built-in styles register through the entry-point group `dem`, the same
door a third-party package uses."""
import glob
import hashlib
import os
import sys

import numpy
from Cython.Build import cythonize
from setuptools import Extension, find_packages, setup
from setuptools.command.build_ext import build_ext

JOBS = os.cpu_count() or 1     # kernels are compiled in parallel, by Cython and by the C compiler
# Cython's workers are forked processes: elsewhere they would start by running this file again
CYTHON_JOBS = JOBS if sys.platform.startswith("linux") else 0

PLUGIN_DIR = "plugins"
plugin_packages = find_packages(PLUGIN_DIR)
packages = find_packages(include=["dem", "dem.*"]) + plugin_packages


def extension(path):
    name = os.path.splitext(path)[0]
    if name.startswith(PLUGIN_DIR + os.sep):
        name = name[len(PLUGIN_DIR) + 1:]
    return Extension(name.replace(os.sep, "."), [path], include_dirs=[numpy.get_include()],
                     extra_compile_args=["-O3"], define_macros=[("NPY_NO_DEPRECATED_API", "NPY_1_7_API_VERSION")])


pyx = sorted(glob.glob("dem/**/*.pyx", recursive=True) + glob.glob(PLUGIN_DIR + "/**/*.pyx", recursive=True))
CYTHON_OPTIONS = dict(include_path=[".", PLUGIN_DIR], language_level=3, nthreads=CYTHON_JOBS,
                      compiler_directives={"boundscheck": False, "wraparound": False, "cdivision": True,
                                           "initializedcheck": False})


def kernels_fingerprint(extensions):
    """Hash of what the kernels are built from: every .pyx and .pxd of the project, the Cython, numpy
    and Python versions, the compiler settings. pip builds each install in a fresh environment, whose
    Cython and numpy headers are newer than the kernels, so timestamps alone would rebuild them all."""
    import Cython
    h = hashlib.sha256()
    sources = sorted(glob.glob("dem/**/*.p[yx][xd]", recursive=True) +
                     glob.glob(PLUGIN_DIR + "/**/*.p[yx][xd]", recursive=True))
    for path in sources:
        h.update(path.encode() + b"\0")
        with open(path, "rb") as f:
            h.update(f.read())
    h.update(repr((Cython.__version__, numpy.__version__, sys.version, CYTHON_OPTIONS["compiler_directives"],
                   [(e.name, e.extra_compile_args, e.define_macros) for e in extensions],
                   [os.environ.get(k) for k in ("CC", "CFLAGS", "LDFLAGS")])).encode())
    return h.hexdigest()


def _read(path):
    with open(path) as f:
        return f.read()


class KernelsBuild(build_ext):
    """build_ext that compiles JOBS kernels at a time (unless told `-j N`), and builds nothing when the
    kernels it built last are there and were built from the same sources and tools (the README's second
    `pip install` after the first)."""

    def finalize_options(self):
        super().finalize_options()
        if not self.parallel:
            self.parallel = JOBS

    def run(self):
        stamp = os.path.join(self.build_temp, "kernels.sha256")
        key = kernels_fingerprint(self.extensions)
        built = all(os.path.exists(path) for path in self.get_outputs())
        if not self.force and built and os.path.exists(stamp) and _read(stamp) == key:
            print(f"dem kernels: up to date ({stamp}), not rebuilt")
            return
        c_sources = {e.name: e.sources for e in cythonize(self.extensions, **CYTHON_OPTIONS)}
        for ext in self.extensions:          # setuptools' own Extension objects, now from the C files
            ext.sources = c_sources[ext.name]
        super().run()
        os.makedirs(self.build_temp, exist_ok=True)
        with open(stamp, "w") as f:
            f.write(key)


setup(
    name="dem",
    version="0.1.0",
    description="Discrete Element Method for granular media of real particle shape",
    python_requires=">=3.9",
    packages=packages,
    package_dir={**{p: os.path.join(PLUGIN_DIR, *p.split(".")) for p in plugin_packages}},
    package_data={"": ["*.pxd", "*.pyx"]},
    ext_modules=[extension(p) for p in pyx],
    cmdclass={"build_ext": KernelsBuild},
    install_requires=["numpy>=1.24", "h5py", "pluggy>=1.0", "scipy", "matplotlib"],
    extras_require={"mpi": ["mpi4py", "mpich"], "test": ["pytest", "mpi4py", "mpich", "vtk", "ovito", "coal", "gsd", "setuptools>=64", "wheel"]},
    entry_points={
        "console_scripts": ["dem = dem.cli:main", "dem-plot = dem.tools.plot_series:main",
                            "dem-frames = dem.tools.drum_frames:main",
                            "dem-drum-analysis = dem.tools.drum_analysis:main",
                            "dem-convert-restart = dem.tools.convert_restart:main",
                            "dem-hooke-from-hertz = dem.tools.hooke_from_hertz:main"],
        "dem": ["core = dem.builtin", "sphere = dem_sphere", "fixes = dem_fixes", "process = dem_process",
                "convex = dem_convex", "walls = dem_walls", "glued = dem_glued", "polyhedra = dem_polyhedra"],
    },
    zip_safe=False,
)
