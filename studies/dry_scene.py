#!/usr/bin/env python3
"""A scene's layer without the water: dry, as settled or as a run left it.

Description
    Copies SCENE (a settled or resolved scene: one table header per line,
    its [[body]] tables the run's bodies in order) without the fluid's
    tables ([fluid], [waves], [[porous]], [[refine]], [[series]] and their
    sub-tables), the rest as written. With --run RUN --time T every [[body]]
    is moved to its pose in RUN/bodies.h5 at the record nearest T, at rest:
    held with `armour run OUT.toml`, it tells whether the layer as the waves
    left it stands without them (a unit that moves there moves under gravity
    and its contacts alone). bench/run_pull_test.sh pulls units out of the
    settled layer's dry scene. Positions in m, time in s.

Usage
    python3 studies/dry_scene.py RUN_CLUMP/settle/scene.settled.toml OUT.toml --run RUN_HULL --time 8.6
    build/apps/armour run OUT.toml --engine bullet --out OUT --set run.duration=5
"""
import argparse
import os
import re
import sys

FLUID_TABLES = {"fluid", "waves", "porous", "refine", "series"}


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def table_name(head):
    """The name of a table header line: "[[porous]] # why" -> "porous", "[fluid.x]" -> "fluid.x"."""
    return head.split("#", 1)[0].strip().strip("[]").strip()


HEADER = re.compile(r"""[ \t]*\[\[?[ \t]*[A-Za-z_][\w.\-"' \t]*\]\]?[ \t]*(#.*)?""")


def tables_of(text):
    """The text cut before each table header line ([name], [[name]], indented or spaced, a comment after):
    the part before the first header, then one piece per table. An array's row ([1, 2],) is no header."""
    pieces = [""]
    for line in text.splitlines(keepends=True):
        if HEADER.fullmatch(line.rstrip("\r\n")):
            pieces.append("")
        pieces[-1] += line
    return pieces


def body_poses(run, time):
    """The bodies' positions and orientations in RUN/bodies.h5 at the record nearest `time`."""
    import h5py  # only here: the plain dry scene needs no record
    import numpy as np
    try:
        with h5py.File(run, "r") as f:
            times = f["time"][:]
            k = int(np.argmin(np.abs(times - time)))
            return float(times[k]), f["bodies/position"][k], f["bodies/orientation"][k]
    except (OSError, KeyError) as e:
        fail(f"{run}: not a body record (time, bodies/position, bodies/orientation): {e}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[1].strip(),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="a settled or resolved scene (its [[body]] tables in the run's order)")
    parser.add_argument("out", help="the dry scene to write (TOML)")
    parser.add_argument("--run", help="a run's folder (bodies.h5): the bodies as it left them at --time")
    parser.add_argument("--time", type=float, help="the instant [s]; the record nearest it is taken")
    args = parser.parse_args()
    if (args.run is None) != (args.time is None):
        fail("--run and --time: give both (the bodies at a run's instant) or neither (as SCENE holds them)")
    record = os.path.join(args.run, "bodies.h5") if args.run else None
    for path in (args.scene, record):
        if path and not os.path.isfile(path):
            fail(f"{path}: not found")
    poses = body_poses(record, args.time) if record else None
    with open(args.scene) as f:
        tables = tables_of(f.read())
    kept, body = [tables[0]], 0  # the part before the first header: the scene's own keys
    for table in tables[1:]:
        head = table.split("\n", 1)[0]
        if table_name(head).split(".")[0] in FLUID_TABLES:
            continue
        if poses and table_name(head) == "body":
            _, position, orientation = poses
            if body == len(position):
                fail(f"{args.scene}: more [[body]] tables than the {len(position)} bodies of {record}")
            table = re.sub(r"(?m)^position = .*$", "position = [%r, %r, %r] # m" % tuple(map(float, position[body])),
                           table)
            table = re.sub(r"(?m)^orientation = .*$", "orientation = [%r, %r, %r, %r]" %
                           tuple(map(float, orientation[body])), table)
            table = re.sub(r"(?m)^(velocity|angular_velocity) = .*$", r"\1 = [0.0, 0.0, 0.0]", table)
            body += 1
        kept.append(table)
    if poses and body != len(poses[1]):
        fail(f"{args.scene}: {body} [[body]] tables where {record} has {len(poses[1])} bodies")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out + ".tmp", "w") as f:
        f.write("".join(kept))
    os.replace(args.out + ".tmp", args.out)
    at = f"at t = {poses[0]:.3f} s of {record}, at rest" if poses else "as the scene holds them"
    print(f"{args.out}: {body if poses else 'its'} bodies {at}, without the fluid's tables")


if __name__ == "__main__":
    main()
