#!/usr/bin/env python3
"""Which cells set a coupled run's interFoam step: at each checkpoint of the
run, the cells whose Courant number is near the largest, at the free surface
(the interface Courant number that maxAlphaCo limits) and anywhere (maxCo).

Usage: python3 bench/step_cells.py RUN [--top N]
  RUN    a coupled run's folder (its --out) with checkpoints (run.checkpoint_interval > 0)
  --top  cells listed per checkpoint (default 8)

bench/step_limits.py says which limit sets the steps; this says where. For
each RUN/checkpoints/<t>/fluid/<time> it copies the mesh and the fields to a
temporary case and runs OpenFOAM's own `postProcess -func CourantNo` (Co =
0.5 sum|phi_f| / V dt, with the step of that time) and `-func writeCellCentres`,
then lists the cells within 80 % of the largest interface Courant number
(interFoam's interface: 0.01 < alpha.water < 0.99) with their centre (m),
alpha, the units' solid fraction chi and velocity (m/s). Needs
WM_PROJECT_DIR (default /usr/share/openfoam, Debian's openfoam). Prints text.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np


def read_field(path):
    """The internalField of an ASCII volField: n scalars or n x 3 vectors."""
    text = path.read_text()
    m = re.search(r"internalField\s+nonuniform\s+List<(\w+)>\s*(\d+)\s*\(", text)
    n, body = int(m.group(2)), text[m.end():]
    body = body[: body.index("\n)")]
    if m.group(1) == "scalar":
        values = np.array(body.split(), float)
    else:
        values = np.array(body.replace("(", " ").replace(")", " ").split(), float).reshape(-1, 3)
    if len(values) != n:
        sys.exit(f"{path}: {len(values)} values where the header says {n}")
    return values


def foam(tool, case, *args):
    log = case / f"log.{tool}"
    with open(log, "w") as out:
        if subprocess.call([tool, "-case", str(case), *args], stdout=out, stderr=subprocess.STDOUT) != 0:
            sys.exit(f"{tool} failed: {log}")


def fields_at(run, checkpoint, work):
    """Co, alpha, chi, U and the cell centres at one checkpoint."""
    fluid = checkpoint / "fluid"
    time = next(p.name for p in fluid.iterdir() if p.is_dir() and re.match(r"^[0-9.eE+-]+$", p.name))
    case = work / checkpoint.name
    (case / "constant").mkdir(parents=True)
    shutil.copytree(run / "case" / "system", case / "system")
    shutil.copytree(run / "case" / "constant" / "polyMesh", case / "constant" / "polyMesh")
    shutil.copytree(fluid / time, case / time)
    control = (case / "system" / "controlDict").read_text()
    control = re.sub(r"^libs .*$", "libs ();", control, flags=re.M)  # no plugin: stock tools only
    control = re.sub(r"^writeFormat .*$", "writeFormat ascii;", control, flags=re.M)
    control = re.sub(r"^functions\s*\{.*\}\s*$", "", control, flags=re.M | re.S)
    (case / "system" / "controlDict").write_text(control)
    for tool, args in (("postProcess", ["-func", "CourantNo"]), ("postProcess", ["-func", "writeCellCentres"]),
                       ("foamFormatConvert", [])):
        foam(tool, case, *args, "-time", time)
    read = lambda name: read_field(case / time / name)
    return float(time), read("Co"), read("alpha.water"), read("armourChi"), read("U"), read("C")


def main():
    args = sys.argv[1:]
    if args in (["-h"], ["--help"]):
        print(__doc__)
        return
    top = 8
    if len(args) == 3 and args[1] == "--top":
        top, args = int(args[2]), args[:1]
    if len(args) != 1:
        sys.exit("usage: python3 bench/step_cells.py RUN [--top N]")
    run = Path(args[0])
    checkpoints = sorted((p for p in (run / "checkpoints").glob("*") if (p / "checkpoint.json").exists()),
                         key=lambda p: float(p.name))
    if not checkpoints:
        sys.exit(f"{run}/checkpoints: no complete checkpoint (run.checkpoint_interval > 0)")
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    with tempfile.TemporaryDirectory() as tmp:
        for checkpoint in checkpoints:
            t, co, alpha, chi, u, c = fields_at(run, checkpoint, Path(tmp))
            interface = np.where((alpha > 0.01) & (alpha < 0.99), co, 0.0)
            near = np.flatnonzero(interface > 0.8 * interface.max())
            print(f"t = {t:.3f} s: {len(co)} cells; largest Co {co.max():.3f} at {c[co.argmax()].round(3)} m "
                  f"(alpha {alpha[co.argmax()]:.2f}); largest interface Co {interface.max():.3f}; "
                  f"{len(near)} cells within 80 % of it, x {c[near, 0].min():.3f}..{c[near, 0].max():.3f} m, "
                  f"z {c[near, 2].min():.3f}..{c[near, 2].max():.3f} m, {int((chi[near] > 0.01).sum())} in a unit")
            for i in near[np.argsort(-interface[near])][:top]:
                print(f"  Co {interface[i]:.3f}  x {c[i, 0]:.3f}  y {c[i, 1]:+.3f}  z {c[i, 2]:.3f}  "
                      f"alpha {alpha[i]:.2f}  chi {chi[i]:.2f}  U {u[i].round(2)} m/s")


if __name__ == "__main__":
    main()
