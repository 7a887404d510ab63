#!/usr/bin/env python3
"""Prepare and read the stock OpenFOAM v1912 floatingObject tutorial.

prepare CASE END_TIME : in a copy of the tutorial, use the sixDoFRigidBodyMotion
    variant (constant/dynamicMeshDict.sixDoF) with its mass and inertia
    written as numbers (Debian ships no headers, so #codeStream cannot compile)
    and set endTime.
parse LOG OUT.csv     : the motion report of interFoam's log (last report of
    each time step: centre of rotation, centre of mass, orientation tensor)
    as CSV: time, com x y z, pitch angle about y (rad).
Nothing of OpenFOAM is kept in the repository: the case is copied at run
time from /usr/share/doc/openfoam-examples.
"""
import math
import re
import sys


def prepare(case, end_time):
    lx, ly, lz, rho = 0.3, 0.2, 0.5, 500.0
    mass = rho * lx * ly * lz
    ixx = mass * (ly**2 + lz**2) / 12
    iyy = mass * (lx**2 + lz**2) / 12
    izz = mass * (lx**2 + ly**2) / 12
    text = open(f"{case}/constant/dynamicMeshDict.sixDoF").read()
    text = re.sub(r"mass\s+#eval\{[^}]*\};", f"mass            {mass!r};", text)
    text = re.sub(r"momentOfInertia\s+#codeStream\s*\{.*?#\};\s*\};",
                  f"momentOfInertia ({ixx!r} {iyy!r} {izz!r});", text, flags=re.S)
    if "#codeStream" in text or "#eval" in text:
        sys.exit("floating_box_stock.py: could not replace #eval/#codeStream in dynamicMeshDict.sixDoF")
    open(f"{case}/constant/dynamicMeshDict", "w").write(text)
    cd = open(f"{case}/system/controlDict").read()
    cd = re.sub(r"\nendTime\s+[^;]*;", f"\nendTime         {end_time};", cd)
    cd = re.sub(r"\nwriteInterval\s+[^;]*;", f"\nwriteInterval   {end_time};", cd)
    open(f"{case}/system/controlDict", "w").write(cd)


def vec(s):
    return [float(v) for v in s.strip("() ").split()]


def parse(log, out):
    rows, t, cur = [], None, {}
    for line in open(log, errors="replace"):
        m = re.match(r"^Time = (\S+)", line)
        if m:
            if t is not None and "com" in cur:
                rows.append((t, cur))
            t, cur = float(m.group(1)), {}
            continue
        m = re.match(r"^\s+Centre of rotation:\s*(\(.*\))", line)
        if m:
            cur["cor"] = vec(m.group(1))
        m = re.match(r"^\s+Centre of mass:\s*(\(.*\))", line)
        if m:
            cur["com"] = vec(m.group(1))
        m = re.match(r"^\s+Orientation:\s*(\(.*\))", line)
        if m:
            cur["Q"] = vec(m.group(1))
    if t is not None and "com" in cur:
        rows.append((t, cur))
    with open(out, "w") as f:
        f.write("time,x,y,z,pitch_y\n")
        for t, c in rows:
            q = c["Q"]  # row-major tensor; rotation about y: Q = [[c,0,s],[0,1,0],[-s,0,c]]
            pitch = math.atan2(q[2], q[0])
            x, y, z = c["com"]
            f.write(f"{t!r},{x!r},{y!r},{z!r},{pitch!r}\n")
    print(f"{out}: {len(rows)} steps")


if __name__ == "__main__":
    if sys.argv[1] == "prepare":
        prepare(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "parse":
        parse(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
