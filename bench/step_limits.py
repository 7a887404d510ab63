#!/usr/bin/env python3
"""What set each interFoam step of a run: the cap (maxDeltaT), the Courant
limit (maxCo) or the interface Courant limit (maxAlphaCo).

Usage: python3 bench/step_limits.py RUN/case [--from T]   (a coupled run's case folder;
       --from: only the steps from simulated time T (s) on, e.g. once the waves reach the armour)

Reads RUN/case/system/controlDict for the three limits and RUN/case/log.interFoam
for each step's Courant numbers and deltaT (s); a step is put down to the limit
it sits nearest to (the cap when deltaT is within 0.1 % of it). The first 100
steps (interFoam's start-up ramp of deltaT) are left out. Prints one line.
"""
import re
import sys
from pathlib import Path


def limits(control_dict):
    text = Path(control_dict).read_text()
    get = lambda key: float(re.search(r"^\s*" + key + r"\s+([0-9.eE+-]+)\s*;", text, re.M).group(1))
    return get("maxCo"), get("maxAlphaCo"), get("maxDeltaT")


def steps(log, start=0.0):
    co = alpha = None
    t = 0.0
    for line in open(log):
        if line.startswith("Time = "):
            t = float(line.split("=")[1])
        elif line.startswith("Courant Number mean"):
            co = float(line.split("max:")[1])
        elif line.startswith("Interface Courant Number mean"):
            alpha = float(line.split("max:")[1])
        elif line.startswith("deltaT =") and co is not None and alpha is not None:
            yield t >= start, co, alpha, float(line.split("=")[1])


def main():
    args = sys.argv[1:]
    if args in (["-h"], ["--help"]):
        print(__doc__)
        return
    start = 0.0
    if len(args) == 3 and args[1] == "--from":
        start = float(args[2])
        args = args[:1]
    if len(args) != 1:
        sys.exit("usage: python3 bench/step_limits.py RUN/case [--from T]")
    case = Path(args[0])
    max_co, max_alpha, cap = limits(case / "system" / "controlDict")
    counts = {"maxDeltaT": 0, "maxCo": 0, "maxAlphaCo": 0}
    dts = []
    for k, (inside, co, alpha, dt) in enumerate(steps(case / "log.interFoam", start)):
        if k < 100 or not inside:
            continue
        dts.append(dt)
        if dt >= 0.999 * cap:
            counts["maxDeltaT"] += 1
        else:
            counts["maxCo" if co / max_co >= alpha / max_alpha else "maxAlphaCo"] += 1
    n = len(dts)
    if n == 0:
        sys.exit(f"{case}: no steps past the first 100 in log.interFoam")
    share = ", ".join(f"{k} {v / n:.1%}" for k, v in counts.items())
    print(f"{n} steps{f' from t = {start:g} s' if start else ''}, mean deltaT {sum(dts) / n:.3g} s; set by: {share} "
          f"(maxCo {max_co:g}, maxAlphaCo {max_alpha:g}, maxDeltaT {cap:g} s)")


if __name__ == "__main__":
    main()
