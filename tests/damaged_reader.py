"""Reads damaged files one after the other in this process, as dem reads them, and reports each outcome on
standard output (one JSON line before and one after each file), so that the test that starts it
(test_damaged_files.py) can tell which file a crash or a hang came from:

    python damaged_reader.py KIND FILE...        KIND: restart, shapedb or data

Outcomes: "read" (accepted), "refused" (a DemError for a restart or a data file; a ShapeDBWarning for a
shape database, which is then rewritten), "bug" (any other exception, with its traceback)."""
import json
import sys
import traceback
import warnings

import numpy as np

RESOLUTION = 20        # of the shape database's entry (a small lattice: quick to compute)


def components():
    """The glued composite whose mass properties the shape database holds."""
    from dem.shapes import Cylinder
    ry90 = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])
    return [(Cylinder(1.0, 2.0), np.zeros(3), np.eye(3)), (Cylinder(0.6, 3.0), np.array([0.1, 0.0, 1.7]), ry90)]


def command_reader(command):
    """The check of one file by a dem command (read_restart, read_data): ("read" | "refused", message)."""
    def read(path):
        import dem
        try:
            dem.Simulation(screen=False).command(f"{command} {path}")
        except dem.DemError as e:
            return "refused", str(e)
        return "read", ""
    return read


class ShapeDBReader:
    """get() of the stored entry, then put() of it again (which copies the file's other entries: it reads
    the damaged file too), then get() once more: the rewritten database must hold it, without a warning."""

    def __init__(self):
        from dem.shapes import glued_mass, shape_db
        self.shape_db = shape_db
        self.text = shape_db.definition_text(components())
        self.props = glued_mass.union_mass_properties(components(), RESOLUTION)

    def __call__(self, path):
        db = self.shape_db.ShapeDB(path)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            found = db.get(self.text, RESOLUTION)
            written = db.put(self.text, RESOLUTION, self.props)
        said = " | ".join(str(w.message) for w in caught)
        if found is not None and not caught:
            return "read", ""
        if found is not None:
            return "bug", f"an entry came back with warnings: {said}"
        if not caught:
            return "bug", "no entry and no warning"
        if written:
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                again = db.get(self.text, RESOLUTION)
            if again is None or again["volume"] != self.props["volume"]:
                return "bug", "the rewritten database does not hold the entry"
        return "refused", said


def main(kind, paths):
    reader = {"restart": lambda: command_reader("read_restart"), "data": lambda: command_reader("read_data"),
              "shapedb": ShapeDBReader}[kind]()
    for path in paths:
        print(json.dumps({"path": path, "event": "start"}), flush=True)
        try:
            outcome, text = reader(path)
        except Exception:
            outcome, text = "bug", traceback.format_exc()
        print(json.dumps({"path": path, "event": outcome, "text": text}), flush=True)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
