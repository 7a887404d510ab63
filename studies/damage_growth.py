#!/usr/bin/env python3
"""Does the damage go on growing with the waves, as Van der Meer's does?

Description
    Reads long coupled damage runs (`armour run` folders of a scene with
    analysis.kind = "damage", ended or still running) at a series of
    simulated times: at each time T it asks `armour report RUN --until T`
    for the run's figures so far (the waves counted at the toe, N; Ns and
    s_om of those waves; units displaced; N_od; S; rocking units; Van der
    Meer's expected count at that N, Ns and s_om; and, from the report's
    damage.csv, the units that then lie 0.25 Dn or more from their settled
    poses: a layer that goes on deforming shows there before its units are
    displaced) and tabulates them, so a run's damage can be held against the
    formula's growth wave by wave.

    Van der Meer's formula for double-layer cubes, Ns = (6.7 N_od^0.4 /
    N^0.3 + 1.0) s_om^-0.1 (Van der Meer 1988), holds N_od proportional to
    N^0.75 at one Ns. Whatever a model's level against the formula (its
    count may be the formula's at another Ns), if its damage grows as the
    formula's, a unit displaced by the end left after the first N0 waves
    with the chance q = 1 - E(N0) / E(N_end), E the formula's expected count
    at the run's own waves and Ns (the report's units_displaced_van_der_meer):
    given a run's final count D, its count after N0 waves is then binomial
    (D, q), and over several runs the sum of those. The script prints that
    test for each run and pooled: the count after N0, its expectation D q and
    the chance of so few or fewer (the exact binomial tail; pooled, the exact
    distribution of the sum). It conditions on the final count, so it asks
    only whether the units left when the formula's would, not how many; a
    small chance says the damage stopped growing as the formula's does (the
    layer lost its units early and then held); with a handful of units a
    large one says little either way. A run whose formula count does not
    grow after N0 (its Ns, measured over the waves so far, falls faster
    than N^0.75 grows) is not tested, and the table says why. Units that
    are displaced and come back count as the reports count them (at each
    time, those displaced then).

    Writes OUT/growth.csv (one row per run and time; SI units and counts),
    OUT/summary.json (the test, per run and pooled) and OUT/growth.png (units
    displaced against the waves, each run beside the formula's expected
    count and the formula's growth scaled to the run's count at N0), and
    nothing else (the reports are made in a temporary folder and dropped).
    Only reads the runs.

Usage
    python3 studies/damage_growth.py RUN1 RUN2 --every 10 --after 27 --out OUT
    python3 studies/damage_growth.py RUN --times 20,40,80,160 --armour build/apps/armour --out OUT
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analysis"))
from armour_results import read_rows, read_summary, write_rows  # noqa: E402

COLUMNS = ("time_s", "wave_source", "waves", "Ns", "s_om", "units_displaced", "units_moved_quarter_Dn", "N_od",
           "damage_S", "rocking_units", "units_displaced_van_der_meer", "N_od_van_der_meer")
MOVED = 0.25  # Dn: a unit moved this far from its settled pose has left its seat, displaced or not


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def parse_times(text):
    try:
        times = sorted({float(t) for t in text.split(",") if t.strip()})
    except ValueError:
        fail(f"--times: '{text}' is not a comma-separated list of times in s")
    if not times or any(not math.isfinite(t) or t <= 0 for t in times):
        fail(f"--times: '{text}': every time must be a finite number > 0 s")
    return times


def report(armour, run, until, out):
    """The report's figures up to `until` (s; None: the run's last record), or its one-line error."""
    command = [armour, "report", run, "--out", out] + ([] if until is None else ["--until", f"{until:g}"])
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        lines = [l for l in (done.stderr + done.stdout).splitlines() if l.strip()]
        return None, (lines[-1] if lines else f"exit {done.returncode}")
    path = os.path.join(out, "summary.json")
    try:
        summary = read_summary(path)
        row = {"time_s": float(summary["simulated_seconds"]), "wave_source": summary["damage"]["wave_source"],
               "waves": float(summary["damage"]["waves"]), "records": summary.get("records")}
        for key in COLUMNS[3:]:
            row[key] = float(summary[key]) if summary.get(key) is not None else None
        row["units_moved_quarter_Dn"] = units_moved(os.path.join(out, "damage.csv"))
        for key in ("units_displaced", "rocking_units"):  # counts
            row[key] = int(round(row[key])) if row[key] is not None else None
    except (OSError, json.JSONDecodeError, KeyError, TypeError, ValueError) as e:
        fail(f"{path}: not a damage report's summary ({e})")
    if row["units_displaced"] is None:
        fail(f"{path}: key 'units_displaced' missing (not a damage run)")
    return row, None


def units_moved(path):
    """The units whose pose at the report's end lies MOVED Dn or more from their settled one (None without the
    report's damage.csv)."""
    if not os.path.isfile(path):
        return None
    try:
        return sum(float(r["final_displacement_over_Dn"]) >= MOVED for r in read_rows(path))
    except (KeyError, TypeError, ValueError):
        fail(f"{path}: column 'final_displacement_over_Dn' missing or not a number")


def sum_of_binomials_tail(pairs, k):
    """P(sum X_i <= k) for independent X_i ~ binomial(n_i, q_i): the exact distribution, convolved."""
    dist = [1.0]
    for n, q in pairs:
        own = [math.comb(n, i) * q**i * (1 - q) ** (n - i) for i in range(n + 1)]
        dist = [sum(dist[j] * own[i - j] for j in range(len(dist)) if 0 <= i - j < len(own))
                for i in range(len(dist) + n)]
    return sum(dist[: k + 1])


def growth_test(rows, after):
    """Per run: the count after the first `after` waves against the formula's growth, or why not."""
    first = next((r for r in rows if r["waves"] >= after), None)
    last = rows[-1]
    if first is None or first is last:
        return {"tested": False, "why": f"no report after {after:g} waves and another later"}
    expected_first, expected_last = first["units_displaced_van_der_meer"], last["units_displaced_van_der_meer"]
    if not expected_first or not expected_last or expected_last <= 0:
        return {"tested": False, "why": "Van der Meer's expected count is missing or zero"}
    if expected_last <= expected_first:
        # The run's Ns is measured over the waves so far; where it falls faster than N^0.75 grows,
        # the formula expects no unit after N0, and a test against zero would say nothing.
        return {"tested": False, "why": f"Van der Meer's expected count does not grow after {after:g} waves "
                f"({expected_first:.2f} at {first['waves']:g} waves, {expected_last:.2f} at {last['waves']:g}: "
                "the Ns measured so far falls)"}
    q = 1.0 - expected_first / expected_last
    total = last["units_displaced"]
    later = max(0, total - first["units_displaced"])
    return {"tested": True, "at_time_s": first["time_s"], "waves_at": first["waves"], "waves_end": last["waves"],
            "displaced_at": first["units_displaced"], "displaced_end": total,
            "displaced_after": later, "share_after_van_der_meer": q, "expected_after": total * q,
            "chance_of_so_few": sum_of_binomials_tail([(total, q)], later),
            "van_der_meer_at": expected_first, "van_der_meer_end": expected_last}


def chart(runs, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for i, (name, rows, test) in enumerate(runs):
        colour = f"C{i}"
        waves = [r["waves"] for r in rows]
        ax.plot(waves, [r["units_displaced"] for r in rows], "o-", color=colour, label=f"{name}: displaced")
        ax.plot(waves, [r["units_displaced_van_der_meer"] or math.nan for r in rows], "--", color=colour,
                label=f"{name}: Van der Meer at its N, Ns, s_om")
        if test.get("tested") and test["displaced_at"] > 0:
            scale = test["displaced_at"] / test["van_der_meer_at"]
            later = [r for r in rows if r["time_s"] >= test["at_time_s"]]
            ax.plot([r["waves"] for r in later], [scale * (r["units_displaced_van_der_meer"] or math.nan)
                                                   for r in later], ":", color=colour,
                    label=f"{name}: the formula's growth from its count at {test['waves_at']:.0f} waves")
    ax.set_xlabel("waves at the toe, N")
    ax.set_ylabel("units displaced (≥ 1 Dn)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def read_runs(args, asked, scratch):
    """Each run's rows (its reports at the times asked and at its last record) and growth test."""
    runs, rows_out = [], []
    for index, run in enumerate(args.runs):
        name = os.path.basename(os.path.normpath(run)) or run
        reports = os.path.join(scratch, f"{index}-{name}")
        os.makedirs(reports)
        whole, error = report(args.armour, run, None, os.path.join(reports, "end"))
        if whole is None:
            fail(f"{run}: `armour report` found no damage figures ({error})")
        end = whole["time_s"]  # the run's last record: its end, or how far it has come
        times = asked or [args.every * k for k in range(1, int(end / args.every) + 1)]
        # The end itself is `whole`, and so is a time within one record of it (its report would read the record
        # before the last: a row that repeats the end's).
        interval = end / (whole["records"] - 1) if whole["records"] and whole["records"] > 1 else 0.0
        times = [t for t in times if t < end - max(interval, 1e-9)]
        rows = []
        for t in times:
            row, error = report(args.armour, run, t, os.path.join(reports, f"t{t:g}"))
            if row is None:
                print(f"{name}: t = {t:g} s: no figures ({error})")
                continue
            rows.append(row)
        rows.append(whole)
        test = growth_test(rows, args.after)
        runs.append((run, rows, test))
        rows_out += [{"run": run, **{k: r[k] for k in COLUMNS}} for r in rows]
    return runs, rows_out


def write_results(args, runs, rows_out):
    """growth.csv, summary.json and growth.png in --out, and the tables on stdout."""
    os.makedirs(args.out, exist_ok=True)
    write_rows(os.path.join(args.out, "growth.csv"), rows_out,
               "units displaced against the waves, with Van der Meer's expected count at each run's N, Ns and "
               "s_om so far (time_s in s; waves, counts and Ns dimensionless)")

    tested = [t for _, _, t in runs if t.get("tested")]
    pooled = None
    if tested:
        later = sum(t["displaced_after"] for t in tested)
        pooled = {"runs": len(tested), "displaced_end": sum(t["displaced_end"] for t in tested),
                  "displaced_after": later, "expected_after": sum(t["expected_after"] for t in tested),
                  "chance_of_so_few": sum_of_binomials_tail(
                      [(t["displaced_end"], t["share_after_van_der_meer"]) for t in tested], later)}
    for name, rows, test in runs:
        print(f"{name}:")
        print("  time_s  waves    Ns   displaced  Van der Meer  moved 0.25 Dn   N_od      S  rocking")
        for r in rows:
            cells = [(r["time_s"], 6, ".1f"), (r["waves"], 6, ".0f"), (r["Ns"], 5, ".2f"), (r["units_displaced"], 9, "d"),
                     (r["units_displaced_van_der_meer"], 13, ".2f"), (r["units_moved_quarter_Dn"], 14, "d"),
                     (r["N_od"], 6, ".2f"), (r["damage_S"], 6, ".2f"), (r["rocking_units"], 8, "d")]
            print("  " + " ".join(format(v, spec).rjust(width) if v is not None else "-".rjust(width)
                                  for v, width, spec in cells))
        if test.get("tested"):
            print(f"  after {test['waves_at']:.0f} waves ({test['at_time_s']:g} s): {test['displaced_after']} of the "
                  f"{test['displaced_end']} displaced at {test['waves_end']:.0f} waves; the formula's growth puts "
                  f"{100 * test['share_after_van_der_meer']:.0f}% of them there ({test['expected_after']:.2f}); "
                  f"chance of so few {100 * test['chance_of_so_few']:.1f}%")
        else:
            print(f"  not tested: {test['why']}")
    if pooled:
        print(f"pooled over {pooled['runs']} runs: {pooled['displaced_after']} of {pooled['displaced_end']} left after "
              f"each run's first report at or past {args.after:g} waves, the formula's growth "
              f"{pooled['expected_after']:.2f}; chance of so few {100 * pooled['chance_of_so_few']:.1f}%")
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump({"after_waves": args.after, "runs": {n: t for n, _, t in runs}, "pooled": pooled,
                   "si_units": {"time_s": "s"}}, f, indent=2)
    chart(runs, os.path.join(args.out, "growth.png"))


def main():
    parser = argparse.ArgumentParser(description="Damage of long damage runs against Van der Meer's growth "
                                     "with the waves (`armour report --until` at a series of times).")
    parser.add_argument("runs", nargs="+", help="`armour run` folders of a damage scene with [fluid]")
    parser.add_argument("--every", type=float, help="report every this many s of simulated time [s]")
    parser.add_argument("--times", help="or at these simulated times, comma-separated [s]")
    parser.add_argument("--after", type=float, default=27.0,
                        help="the test counts the units displaced after this many waves at the toe "
                        "(default 27: the kept curves' trains)")
    parser.add_argument("--armour", default=os.path.join("build", "apps", "armour"), help="the armour program")
    parser.add_argument("--out", required=True, help="folder for growth.csv, summary.json and growth.png")
    args = parser.parse_args()
    if (args.every is None) == (args.times is None):
        fail("give one of --every or --times")
    if args.every is not None and not (math.isfinite(args.every) and args.every > 0):
        fail(f"--every: must be a finite number > 0 s (got {args.every:g})")
    if not (math.isfinite(args.after) and args.after > 0):
        fail(f"--after: must be a finite number of waves > 0 (got {args.after:g})")
    if not os.access(args.armour, os.X_OK):
        fail(f"--armour: '{args.armour}' is not a program this user can run")
    for run in args.runs:
        if not os.path.isdir(run):
            fail(f"{run}: not a folder")

    times = parse_times(args.times) if args.times else None
    with tempfile.TemporaryDirectory() as scratch:
        runs, rows_out = read_runs(args, times, scratch)
    write_results(args, runs, rows_out)


if __name__ == "__main__":
    main()
