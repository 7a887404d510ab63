#!/usr/bin/env python3
"""A dry scene of a layer as it stood at one instant of a run.

Description
    Copies SCENE (the run's settled or resolved scene, whose [[body]] tables
    are the run's bodies in order) without the fluid's tables ([fluid],
    [waves], [[porous]], [[refine]], [[series]]) and with every [[body]] at
    its pose in RUN/bodies.h5 at the record nearest T, its velocities left at
    rest. Held with `armour run OUT.toml`, it tells whether the layer as the
    waves left it stands without them: a unit that moves there moves under
    gravity and its contacts alone. Positions in m, time in s.

Usage
    python3 studies/dry_scene_at.py RUN_CLUMP/settle/scene.settled.toml RUN_HULL 8.6 OUT.toml
    build/apps/armour run OUT.toml --engine bullet --out OUT --set run.duration=5
"""
import argparse
import os
import re
import sys

import h5py
import numpy as np

FLUID_TABLES = ("[fluid]", "[waves]", "[[porous]]", "[[refine]]", "[[series]]")


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[1].strip(),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="the run's scene (its [[body]] tables in the run's order)")
    parser.add_argument("run", help="the run's folder (bodies.h5)")
    parser.add_argument("time", type=float, help="the instant [s]; the record nearest it is taken")
    parser.add_argument("out", help="the dry scene to write (TOML)")
    args = parser.parse_args()
    record = os.path.join(args.run, "bodies.h5")
    for path in (args.scene, record):
        if not os.path.isfile(path):
            fail(f"{path}: not found")
    with h5py.File(record, "r") as f:
        times = f["time"][:]
        k = int(np.argmin(np.abs(times - args.time)))
        position, orientation = f["bodies/position"][k], f["bodies/orientation"][k]
    with open(args.scene) as f:
        tables = re.split(r"(?m)^(?=\[)", f.read())
    kept, body = [], 0
    for table in tables:
        head = table.split("\n", 1)[0].strip()
        if head.startswith(FLUID_TABLES):
            continue
        if head == "[[body]]":
            if body == len(position):
                fail(f"{args.scene}: more [[body]] tables than the {len(position)} bodies of {record}")
            table = re.sub(r"(?m)^position = .*$", "position = [%r, %r, %r] # m" % tuple(map(float, position[body])),
                           table)
            table = re.sub(r"(?m)^orientation = .*$", "orientation = [%r, %r, %r, %r]" %
                           tuple(map(float, orientation[body])), table)
            table = re.sub(r"(?m)^(velocity|angular_velocity) = .*$", r"\1 = [0.0, 0.0, 0.0]", table)
            body += 1
        kept.append(table)
    if body != len(position):
        fail(f"{args.scene}: {body} [[body]] tables where {record} has {len(position)} bodies")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out + ".tmp", "w") as f:
        f.write("".join(kept))
    os.replace(args.out + ".tmp", args.out)
    print(f"{args.out}: {body} bodies at t = {times[k]:.3f} s of {record}, at rest, without the fluid's tables")


if __name__ == "__main__":
    main()
