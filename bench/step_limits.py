#!/usr/bin/env python3
"""What set each interFoam step of a run: the cap (maxDeltaT), the Courant
limit (maxCo) or the interface Courant limit (maxAlphaCo).

Usage: python3 bench/step_limits.py RUN/case   (a coupled run's case folder)

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


def steps(log):
    co = alpha = None
    for line in open(log):
        if line.startswith("Courant Number mean"):
            co = float(line.split("max:")[1])
        elif line.startswith("Interface Courant Number mean"):
            alpha = float(line.split("max:")[1])
        elif line.startswith("deltaT =") and co is not None and alpha is not None:
            yield co, alpha, float(line.split("=")[1])


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: python3 bench/step_limits.py RUN/case")
    case = Path(sys.argv[1])
    max_co, max_alpha, cap = limits(case / "system" / "controlDict")
    counts = {"maxDeltaT": 0, "maxCo": 0, "maxAlphaCo": 0}
    dts = []
    for k, (co, alpha, dt) in enumerate(steps(case / "log.interFoam")):
        if k < 100:
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
    print(f"{n} steps, mean deltaT {sum(dts) / n:.3g} s; set by: {share} "
          f"(maxCo {max_co:g}, maxAlphaCo {max_alpha:g}, maxDeltaT {cap:g} s)")


if __name__ == "__main__":
    main()
