"""Reading armour run results for chart scripts: bodies.h5 and summary.json.

Description
    The Python twin of analysis/bodies_file.h. read_bodies loads a run's
    rigid-body record (results/body_recorder.h writes it) into numpy arrays,
    SI units as written:
        time              (steps,)            s
        unit              (bodies,)           -, index of the body's unit shape
        position          (steps, bodies, 3)  m, centre of mass, world frame
        orientation       (steps, bodies, 4)  -, quaternion w x y z, unit frame -> world
        velocity          (steps, bodies, 3)  m/s
        angular_velocity  (steps, bodies, 3)  rad/s, world frame
        external_force, contact_force (steps, bodies, 3)  N
        external_torque   (steps, bodies, 3)  N m
    and the root string attributes (scene, engine, dt, ...) as `attributes`.
    The file is opened read-only without HDF5's file lock, so a record that a
    running solver still holds can be read.

Usage
    import sys; sys.path.insert(0, "<repo>/analysis")   # bench/common.sh sets PYTHONPATH
    from armour_results import read_bodies, read_summary
    b = read_bodies("out/run")                # a run folder, or the bodies.h5 itself
    z = b.position[:, 0, 2]                   # heave of body 0, m
    s = read_summary("out/run")               # summary.json as a dict
    seats = unit_seats("out/run")             # body -> Seat(at_foot, above_layer), from damage.csv
    seat_name(seats[0])                       # "in the layer", "on top of the layer", "at the foot" or "unknown"
    rows = read_rows("out/run/damage.csv")    # a CSV's rows as dicts, its '#' comment lines skipped
"""
import csv
import json
import os
from collections import namedtuple

SERIES = ("position", "orientation", "velocity", "angular_velocity", "external_force", "external_torque",
          "contact_force")


class Bodies:
    """One run's bodies.h5 in memory (see the module's description for fields and units)."""

    def __init__(self, path):
        import h5py  # here: scripts reading only summaries need no HDF5

        self.path = path
        with h5py.File(path, "r", locking=False) as f:
            self.time = f["time"][:]
            self.unit = f["bodies/unit"][:]
            for name in SERIES:
                setattr(self, name, f["bodies/" + name][:])
            self.attributes = {k: (v.decode() if isinstance(v, bytes) else str(v)) for k, v in f.attrs.items()}

    @property
    def steps(self):
        return len(self.time)

    @property
    def bodies(self):
        return len(self.unit)


def _in_run(path, name):
    return os.path.join(path, name) if os.path.isdir(path) else path


def read_bodies(path):
    """A run folder's bodies.h5 (or the file named) as Bodies."""
    return Bodies(_in_run(path, "bodies.h5"))


def read_summary(path):
    """A run folder's summary.json (or the file named) as a dict."""
    with open(_in_run(path, "summary.json")) as f:
        return json.load(f)


def read_rows(path):
    """A CSV file's rows as dicts (damage.csv, damage_history.csv, results.csv), its '#' comment lines skipped."""
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def write_rows(path, rows, comment=None):
    """Writes rows (dicts) to the CSV file `path`: a '# comment' line first where given (the table's units), a
    header of every key in the order first met, then a line per row (a key a row lacks left empty)."""
    with open(path, "w", newline="") as f:
        if comment:
            f.write(f"# {comment}\n")
        writer = csv.DictWriter(f, fieldnames=list(dict.fromkeys(k for row in rows for k in row)))
        writer.writeheader()
        writer.writerows(rows)


if __name__ == "__main__":
    # A quick look: python3 analysis/armour_results.py RUN_DIR
    import sys

    import numpy as np

    usage = "usage: python3 analysis/armour_results.py RUN_DIR   (a one-line look at a run's bodies.h5)"
    if sys.argv[1:] in (["-h"], ["--help"]):
        print(usage)
        sys.exit(0)
    if len(sys.argv) != 2:
        print(f"armour: error: {usage}", file=sys.stderr)
        sys.exit(2)
    b = read_bodies(sys.argv[1])
    print(f"{b.path}: {b.steps} steps, {b.bodies} bodies, t = {b.time[0] if b.steps else 0:g}.."
          f"{b.time[-1] if b.steps else 0:g} s, attributes {sorted(b.attributes)}")
    if b.steps:
        print("last position of body 0 (m):", np.array2string(b.position[-1, 0]))


# A settled unit's seat on the slope: at_foot, its centre seaward of the face's foot; above_layer, its centre
# farther out of the face than the settled layer is thick (more than half of it outside the double layer). Either
# is None where the run's damage.csv does not say.
Seat = namedtuple("Seat", "at_foot above_layer")
SEATS = ("in the layer", "on top of the layer", "at the foot", "unknown")


def unit_seats(path):
    """Each body's Seat in a damage run's settled layer (a run folder), from damage.csv and summary.json: at_foot
    from the at_foot column; above_layer from n_m against damage.settled_layer.layer_thickness (the test of
    SlopeFrame::rests_on_layer, whose on_top column it repeats, here for units at the foot too). None where
    damage.csv has no such column or an empty cell, or summary.json no thickness (the damage analysis then writes
    on_top 0 for every unit). {} without damage.csv. Raises ValueError naming the file and column where a cell
    is not a number."""
    table = _in_run(path, "damage.csv")
    if not os.path.isfile(table):
        return {}
    try:
        layer = (read_summary(path).get("damage") or {}).get("settled_layer") or {}
        thickness = layer.get("layer_thickness")
    except (OSError, ValueError):
        thickness = None
    with open(table, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return seats_of_rows(rows, thickness, table)


def seats_of_rows(rows, thickness, table="damage.csv"):
    """unit_seats for damage.csv's rows already read (dicts) and the layer's thickness (m, or None); `table`
    names the file in an error."""
    seats = {}
    for r in rows:
        try:
            column = "body"
            body = int(r["body"])
            column = "n_m"
            above = float(r["n_m"]) > thickness if r.get("n_m") and thickness is not None else None
        except (KeyError, TypeError, ValueError) as e:
            raise ValueError(f"{table}: column '{column}': missing or not a number ({e})") from None
        seats[body] = Seat({"1": True, "0": False}.get(r.get("at_foot")), above)
    return seats


def seat_name(seat):
    """A Seat as one of SEATS: the foot first, then on top of the layer or in it."""
    if seat is None or seat.at_foot is None:
        return SEATS[3]
    if seat.at_foot:
        return SEATS[2]
    return SEATS[3] if seat.above_layer is None else SEATS[1] if seat.above_layer else SEATS[0]
