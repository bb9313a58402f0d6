"""Build dem: the core package `dem`, the built-in plugin packages under `plugins/`, and every Cython
kernel (`*.pyx`) found in them. Built-in styles register through the entry-point group `dem`, the same
door a third-party package uses."""
import glob
import os

import numpy
from Cython.Build import cythonize
from setuptools import Extension, find_packages, setup

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
extensions = cythonize([extension(p) for p in pyx], include_path=[".", PLUGIN_DIR], language_level=3,
                       compiler_directives={"boundscheck": False, "wraparound": False, "cdivision": True,
                                            "initializedcheck": False})

setup(
    name="dem",
    version="0.1.0",
    description="Discrete Element Method for granular media of real particle shape",
    python_requires=">=3.9",
    packages=packages,
    package_dir={**{p: os.path.join(PLUGIN_DIR, *p.split(".")) for p in plugin_packages}},
    package_data={"": ["*.pxd", "*.pyx"]},
    ext_modules=extensions,
    install_requires=["numpy>=1.24", "h5py", "pluggy>=1.0", "scipy", "matplotlib"],
    extras_require={"mpi": ["mpi4py", "mpich"], "test": ["pytest", "mpi4py", "mpich", "vtk", "ovito", "coal", "setuptools>=64", "wheel"]},
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
