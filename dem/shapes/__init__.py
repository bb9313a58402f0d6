"""Convex particle shapes: mass properties, crust/core, meshes and the packed shape table.

    from dem.shapes import Sphere, Box, cube, Cylinder, Cone, Ellipsoid, Superquadric, Polyhedron
    from dem.shapes import tetrahedron, pinacoid, ShapeTable
"""
from .base import (BOX, CONE, CYLINDER, ELLIPSOID, KIND_NAMES, NPARAM, POLYHEDRON, SPHERE, SUPERQUADRIC,
                   Shape, mesh_volume)
from .polyhedron import Polyhedron, pinacoid, pinacoid_vertices, pinacoid_volume, read_mesh_vertices, tetrahedron
from .primitives import Box, Cone, Cylinder, Ellipsoid, Sphere, Superquadric, cube
from .table import ShapeTable

__all__ = ["Shape", "Sphere", "Box", "cube", "Cylinder", "Cone", "Ellipsoid", "Superquadric", "Polyhedron",
           "tetrahedron", "pinacoid", "pinacoid_vertices", "pinacoid_volume", "read_mesh_vertices",
           "ShapeTable", "mesh_volume", "KIND_NAMES", "NPARAM", "SPHERE", "BOX", "CYLINDER", "CONE",
           "ELLIPSOID", "SUPERQUADRIC", "POLYHEDRON"]
