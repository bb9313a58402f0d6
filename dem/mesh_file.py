"""Triangle mesh files: STL (ASCII or binary) and Wavefront OBJ, read into a triangle soup, for the mesh
walls (dem_walls.mesh welds it) and for polyhedral shapes read from a file (the shape is its hull).

    tris = read_triangles("inputs/meshes/hopper.stl")     # (nt, 3, 3) float64, one row per corner

File formats:

* STL, binary or ASCII, told apart by content, not by the extension: a file whose size is 84 + 50 * N
  bytes, N being the triangle count stored at byte 80, is binary (a binary file may begin with the word
  "solid", as many exporters write their header); otherwise a file beginning with "solid" and holding no
  NUL byte is ASCII; anything else is reported as a truncated binary STL or not an STL file. The normals
  stored in the file are ignored: they come from the winding (right-hand rule over v0 v1 v2).
* OBJ (extension .obj, any case): `v x y z` lines and `f` lines whose entries are `i`, `i/j`, `i/j/k` or
  `i//k` (only the vertex index i is used), 1-based or negative (relative to the vertices read so far);
  faces with more than 3 corners are fan-triangulated (0 1 2, 0 2 3, ...); every other line (vt, vn, g,
  o, s, usemtl, mtllib, l, p, comments) is ignored, and a line ending with a backslash continues on the
  next one.

Every problem with a file raises DemError naming the file and, for text formats, the line.
"""
import os
import struct

import numpy as np

from .errors import DemError

STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])
assert STL_RECORD.itemsize == 50


def read_triangles(path):
    """The triangles of an STL (ASCII or binary) or OBJ file as an (nt, 3, 3) float64 C-contiguous array:
    tris[t, k] is corner k of triangle t. Raises DemError for a missing or unreadable file, a file with no
    triangles, a bad number, an index out of range or a truncated binary STL."""
    path = os.fspath(path)
    V, T = read_mesh(path)
    if len(T) == 0:
        raise DemError(f"mesh file '{path}': no triangles")
    tris = V[T]
    bad = ~np.isfinite(tris).all(axis=(1, 2))
    if bad.any():
        raise DemError(f"mesh file '{path}': triangle {int(np.argmax(bad)) + 1} has a non-finite coordinate")
    return np.ascontiguousarray(tris, dtype=np.float64)


def read_mesh(path):
    """(vertices (n, 3), triangles (m, 3) vertex ids) of a file: an OBJ's vertices and faces as indexed
    there (vertices with no face are kept: a point cloud), an STL's corners three per triangle. Numbers
    are not checked for being finite (the caller says what they are for). DemError for a missing or
    unreadable file and what read_triangles lists."""
    path = os.fspath(path)
    try:
        with open(path, "rb") as f:
            data = f.read()
    except FileNotFoundError:
        raise DemError(f"mesh file '{path}': no such file") from None
    except IsADirectoryError:
        raise DemError(f"mesh file '{path}': is a directory, not a file") from None
    except OSError as e:
        raise DemError(f"mesh file '{path}': cannot read it ({e.strerror or e})") from None
    if path.lower().endswith(".obj"):
        return _read_obj(path, data)
    corners = _read_stl(path, data).reshape(-1, 3)
    return corners, np.arange(len(corners)).reshape(-1, 3)


def _is_binary_stl(data):
    if len(data) < 84:
        return False
    (count,) = struct.unpack_from("<I", data, 80)
    return 84 + 50 * count == len(data)


def _read_stl(path, data):
    if _is_binary_stl(data):
        (count,) = struct.unpack_from("<I", data, 80)
        records = np.frombuffer(data, dtype=STL_RECORD, count=count, offset=84)
        return records["v"].astype(np.float64)
    text = data[3:] if data.startswith(b"\xef\xbb\xbf") else data        # a UTF-8 byte-order mark
    if text.lstrip()[:5].lower() == b"solid" and b"\0" not in text:
        return _read_stl_ascii(path, text)
    if len(data) < 84:
        raise DemError(f"mesh file '{path}': not an STL file (only {len(data)} bytes: a binary STL has an "
                       f"84-byte header, an ASCII one begins with 'solid')")
    (count,) = struct.unpack_from("<I", data, 80)
    expected = 84 + 50 * count
    if len(data) < expected:
        raise DemError(f"mesh file '{path}': truncated binary STL (its header announces {count} triangles, "
                       f"{expected} bytes, but the file has {len(data)} bytes)")
    raise DemError(f"mesh file '{path}': not an STL file (as a binary STL its header announces {count} "
                   f"triangles, {expected} bytes, but the file has {len(data)} bytes; and it does not read "
                   f"as an ASCII STL)")


def _number(path, lineno, word, what):
    try:
        return float(word)
    except ValueError:
        raise DemError(f"mesh file '{path}', line {lineno}: bad number '{word}' in {what}") from None


def _read_stl_ascii(path, data):
    text = data.decode("latin-1")
    tris = []
    loop = None            # the corners of the current outer loop, or None outside a loop
    loop_line = 0
    for lineno, line in enumerate(text.splitlines(), 1):
        words = line.split()
        if not words:
            continue
        key = words[0].lower()
        if key == "vertex":
            if loop is None:
                raise DemError(f"mesh file '{path}', line {lineno}: 'vertex' outside an 'outer loop'")
            if len(words) != 4:
                raise DemError(f"mesh file '{path}', line {lineno}: a vertex needs 3 coordinates, "
                               f"found {len(words) - 1}")
            loop.append([_number(path, lineno, w, "vertex") for w in words[1:]])
        elif key == "outer":
            if loop is not None:
                raise DemError(f"mesh file '{path}', line {lineno}: 'outer loop' inside another loop "
                               f"(missing 'endloop' after line {loop_line})")
            loop, loop_line = [], lineno
        elif key == "endloop":
            if loop is None:
                raise DemError(f"mesh file '{path}', line {lineno}: 'endloop' without 'outer loop'")
            if len(loop) < 3:
                raise DemError(f"mesh file '{path}', line {lineno}: a facet with {len(loop)} vertices "
                               f"(at least 3 needed)")
            for k in range(1, len(loop) - 1):         # 3 corners as the format says; fan beyond that
                tris.append((loop[0], loop[k], loop[k + 1]))
            loop = None
        elif key == "facet":
            if len(words) >= 2 and words[1].lower() == "normal":
                for w in words[2:]:
                    _number(path, lineno, w, "facet normal")
        elif key in ("solid", "endsolid", "endfacet"):
            pass
        else:
            raise DemError(f"mesh file '{path}', line {lineno}: unexpected '{words[0][:40]}' in an ASCII "
                           f"STL (expected solid, facet, outer loop, vertex, endloop, endfacet or endsolid)")
    if loop is not None:
        raise DemError(f"mesh file '{path}': the loop begun at line {loop_line} has no 'endloop' "
                       f"(truncated file?)")
    return np.array(tris, dtype=np.float64).reshape(-1, 3, 3)


def _read_obj(path, data):
    text = data.decode("utf-8-sig", errors="replace")
    vertices = []
    faces = []                      # (line, [0-based vertex index, ...])
    pending = ""
    pending_line = 0
    for lineno, line in enumerate(text.splitlines(), 1):
        if pending:
            line = pending + " " + line
        else:
            pending_line = lineno
        if line.endswith("\\"):
            pending = line[:-1]
            continue
        pending = ""
        line = line.split("#", 1)[0]
        words = line.split()
        if not words:
            continue
        where = f"mesh file '{path}', line {pending_line}"
        if words[0] == "v":
            if len(words) < 4:
                raise DemError(f"{where}: a vertex needs 3 coordinates, found {len(words) - 1}")
            vertices.append([_number(path, pending_line, w, "vertex") for w in words[1:4]])
        elif words[0] == "f":
            if len(words) < 4:
                raise DemError(f"{where}: a face needs at least 3 vertices, found {len(words) - 1}")
            ids = []
            for w in words[1:]:
                head = w.split("/", 1)[0]
                try:
                    i = int(head)
                except ValueError:
                    raise DemError(f"{where}: bad vertex index '{w}' in face") from None
                if i == 0:
                    raise DemError(f"{where}: vertex index 0 in face (OBJ indices start at 1, or count "
                                   f"back from -1)")
                if i < 0:           # relative to the vertices read so far
                    if -i > len(vertices):
                        raise DemError(f"{where}: vertex index {i} out of range (only {len(vertices)} "
                                       f"vertices before this line)")
                    i = len(vertices) + i
                else:
                    i -= 1          # checked once all vertices are read
                ids.append(i)
            faces.append((pending_line, ids))
    nv = len(vertices)
    tris = []
    for lineno, ids in faces:
        for i in ids:
            if i >= nv:
                raise DemError(f"mesh file '{path}', line {lineno}: vertex index {i + 1} out of range "
                               f"(the file has {nv} vertices)")
        for k in range(1, len(ids) - 1):
            tris.append((ids[0], ids[k], ids[k + 1]))
    return np.asarray(vertices, dtype=np.float64).reshape(-1, 3), np.asarray(tris, dtype=np.intp).reshape(-1, 3)
