#!/usr/bin/env python3
"""Keep the small results of an `armour sweep` folder, or of plain runs, in the repository.

Description
    Copies what a reader of a study needs from a sweep's output folder (kept
    outside the repository) into DEST: results.csv (the finished cases' rows:
    one per realisation), summary.json, report.md,
    sweep.toml, figures/*.png, and from each case its run's summary.json,
    damage.csv and damage_history.csv (when the analysis wrote them) under
    DEST/cases/<case>/run/, where report.md's links point, and its record
    (case.json: status, scene hash, wall time), so that a sweep on another
    machine counts the kept cases done: `armour sweep ... --kept DEST` copies
    those with the same scene into its --out and runs only the others. Paths of the source
    tree in summary.json (the scene, the sweep file) are written relative to
    it, so the kept files name no machine's folders. A sweep still running
    in RUN is refused (it rewrites its tables and charts as each case ends). Bodies, fields and
    checkpoints stay in the sweep folder. DEST/kept_files.txt lists the files
    a keep wrote: a later keep into DEST removes those of them it no longer
    writes (a case or a chart the sweep no longer has) and nothing else, so a
    file of one's own in DEST stays. (A DEST kept before that list: the
    files of the names a keep writes, and the charts its report.md shows,
    count as its own.) Every file is written beside its place first and
    renamed over it once all are written: a keep cut short (a file it cannot
    read, a full disk, Ctrl-C) leaves DEST as it was.

    With --runs, the folders of plain `armour run`s of a damage analysis (the
    realisations of one check run one by one, not as a sweep) are kept as a
    sweep's cases would be: each run's summary.json, damage.csv and
    damage_history.csv under DEST/cases/<the run folder's name>/run/, and
    DEST/results.csv with a row per run (case, seed: the run's waves.seed,
    unit.0.density in kg/m^3, and the figures of its summary.json, those of
    its `waves` object as waves.<name>; SI as summary.json states them), so
    that studies/compare_curves.py reads DEST as one curve of those
    realisations. DEST/summary.json lists the runs and the units displaced
    against Van der Meer's count over them. A folder without a damage run's
    summary.json is refused before anything is written.

Usage
    python3 studies/keep_results.py RUN docs/results/stability_curve
    armour sweep STUDY --out NEW_RUN --kept docs/results/stability_curve   # elsewhere: the other cases
    python3 studies/keep_results.py --runs docs/results/severe_sea_shipped RUN_SEED1 RUN_SEED2 RUN_SEED3
"""
import csv
import errno
import fcntl
import functools
import io
import json
import os
import re
import shutil
import signal
import sys
import tomllib

TOP = ("results.csv", "report.md", "sweep.toml")
PER_CASE = ("summary.json", "damage.csv", "damage_history.csv")
MANIFEST = "kept_files.txt"


def source_tree(summary):
    """The source tree the sweep ran from (studies/<file> -> the tree), or None."""
    sweep_file = summary.get("sweep_file", "")
    return os.path.dirname(os.path.dirname(sweep_file)) if os.path.isabs(sweep_file) else None


def relative_to_source(summary, root):
    """The scene and sweep file as paths inside the source tree the sweep ran from."""
    for key in ("sweep_file", "scene"):
        path = summary.get(key, "")
        if root and os.path.isabs(path) and os.path.commonpath([root, path]) == root:
            summary[key] = os.path.relpath(path, root)
    return summary


def finished_rows(text):
    """results.csv with the finished cases' rows alone: a row per realisation (the pending and failed stay in
    the sweep's own folder and its report)."""
    lines = text.splitlines(keepends=True)
    if not lines:
        return text
    column = next(csv.reader([lines[0]])).index("status") if "status" in lines[0] else None
    if column is None:
        return text
    return lines[0] + "".join(line for line in lines[1:] if next(csv.reader([line]))[column] == "done")


def refuse_while_running(run):
    """Exit 2 while an armour command holds RUN's lock: a running sweep rewrites results.csv, summary.json,
    report.md and figures/ as its cases end, the charts in place, so a keep now could take the files of two
    moments, or a chart half drawn."""
    try:
        with open(os.path.join(run, ".armour-lock")) as lock:
            try:
                fcntl.flock(lock, fcntl.LOCK_SH | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = lock.read().strip() or "unknown"
                print(f"armour: error: {run}: in use by another armour command (pid {holder}); it rewrites its "
                      f"tables and figures as its cases end: keep when it ends, or stop it (kill -TERM {holder}: "
                      "its running cases go back to pending and every table is written)", file=sys.stderr)
                sys.exit(2)
    except FileNotFoundError:
        pass


def written_before(dest):
    """The files, relative to DEST, that an earlier keep wrote there: its list, or without one (a keep before the
    list was written) the files of the names a keep writes and the charts its report.md shows."""
    try:
        with open(os.path.join(dest, MANIFEST)) as f:
            return {line.strip() for line in f if line.strip()}
    except FileNotFoundError:
        pass
    found = {name for name in TOP + ("summary.json",) if os.path.isfile(os.path.join(dest, name))}
    for top, _, names in os.walk(os.path.join(dest, "cases")):
        ours = PER_CASE if os.path.basename(top) == "run" else ("case.json",)
        found |= {os.path.relpath(os.path.join(top, n), dest) for n in names if n in ours}
    try:  # the charts: those its report.md shows (a chart of one's own there is not in it)
        with open(os.path.join(dest, "report.md")) as f:
            found |= {"figures/" + name for name in re.findall(r"\(figures/([^()\s/]+\.png)\)", f.read())}
    except FileNotFoundError:
        pass
    return found


def remove_stale(dest, stale):
    """Removes the files in `stale` (paths relative to DEST) and the folders that leaves empty under DEST."""
    for name in sorted(stale):
        if os.path.isabs(name) or ".." in name.split(os.sep):
            continue  # not a file a keep writes: a list edited by hand
        path = os.path.join(dest, name)
        if os.path.isfile(path):
            os.remove(path)
        folder = os.path.dirname(path)
        while os.path.abspath(folder) != os.path.abspath(dest) and os.path.isdir(folder) and not os.listdir(folder):
            os.rmdir(folder)
            folder = os.path.dirname(folder)


def put(dest, name, text):
    """Writes DEST/name whole or not at all (a temporary file renamed over it)."""
    staged = {}
    try:
        stage(dest, name, staged, set(), text=text)
        commit(dest, staged)
    finally:
        discard(staged, set())


def stage(dest, name, staged, made, text=None, source=None):
    """Writes DEST/name.keeping from `text` or a copy of the file `source`, and counts it in `staged` (name ->
    the temporary file) and the folders it made in `made`; `commit` renames every staged file over its place
    at the end of the keep, so a keep cut short (a file it cannot read, a full disk, Ctrl-C) changes no file
    in DEST."""
    path = os.path.join(dest, name)
    folder = os.path.dirname(path)
    while folder and not os.path.isdir(folder):
        made.add(folder)
        folder = os.path.dirname(folder)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    staged[name] = path + ".keeping"  # counted before it is written: a write cut short is cleaned up too
    try:
        if source is None:
            with open(staged[name], "w") as f:
                f.write(text)
        else:
            shutil.copyfile(source, staged[name])
    except OSError as e:
        if e.filename is None:  # a full disk names no file: name the one being written
            raise OSError(e.errno, e.strerror, staged[name]) from e
        raise


def commit(dest, staged):
    """Renames every staged file over DEST/name: a file is never half written, and the keep's files change
    together (renames within one folder tree, after every copy has succeeded)."""
    for name in list(staged):
        os.replace(staged[name], os.path.join(dest, name))
        del staged[name]


def discard(staged, made):
    """A keep cut short: the temporary files go, and the folders it made under DEST that hold nothing now."""
    for partial in staged.values():
        try:
            os.remove(partial)
        except OSError:
            pass  # not written yet, or left behind rather than hide the error that stopped the keep
    for folder in sorted(made, key=len, reverse=True):
        try:
            os.rmdir(folder)
        except OSError:
            pass  # not empty: it holds files of its own


def stage_all(run, dest, summary, root, staged, made):
    """Stages every file a keep writes (the sweep's tables, charts and each finished case's files); returns the
    number of cases kept."""
    put = functools.partial(stage, dest, staged=staged, made=made)
    put("summary.json", text=json.dumps(summary, indent=2) + "\n")
    for name in TOP:
        if os.path.exists(os.path.join(run, name)):
            with open(os.path.join(run, name)) as f:
                text = f.read()
            if name == "results.csv":
                text = finished_rows(text)
            # The report names the scene: as a path in the source tree, as summary.json does.
            put(name, text=text.replace(root + os.sep, "") if root else text)
    figures = os.path.join(run, "figures")
    for name in sorted(os.listdir(figures)) if os.path.isdir(figures) else []:
        if name.endswith(".png"):
            put(os.path.join("figures", name), source=os.path.join(figures, name))
    kept = 0
    for case in summary["cases"]:
        source = os.path.join(run, case["folder"], "run")
        files = [n for n in PER_CASE if os.path.exists(os.path.join(source, n))]
        if case["status"] != "done" or not files:
            continue
        for name in files:
            put(os.path.join(case["folder"], "run", name), source=os.path.join(source, name))
        # The record lets `armour sweep` resume from the kept cases elsewhere.
        put(os.path.join(case["folder"], "case.json"), source=os.path.join(run, case["folder"], "case.json"))
        kept += 1
    return kept


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def keep(run, dest):
    if not os.path.isfile(os.path.join(run, "summary.json")):
        fail(f"{os.path.join(run, 'summary.json')}: not found (not an armour sweep folder)")
    refuse_while_running(run)
    with open(os.path.join(run, "summary.json")) as f:
        summary = json.load(f)
    root = source_tree(summary)
    summary = relative_to_source(summary, root)
    kept = write_kept(dest, lambda staged, made: stage_all(run, dest, summary, root, staged, made))
    print(f"kept {kept} of {len(summary['cases'])} cases' results in {dest}")


def is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def run_row(run):
    """A plain damage run's row of results.csv: its name, seed, unit density and summary figures."""
    path, scene_path = os.path.join(run, "summary.json"), os.path.join(run, "scene.resolved.toml")
    try:
        with open(path) as f:
            summary = json.load(f)
    except OSError as e:
        fail(f"{e.filename}: {e.strerror} (not a finished armour run)")
    except ValueError as e:  # cut short, not JSON, not UTF-8
        fail(f"{path}: unreadable ({e})")
    try:
        with open(scene_path, "rb") as f:
            scene = tomllib.load(f)
    except OSError as e:
        fail(f"{e.filename}: {e.strerror} (not a finished armour run)")
    except ValueError as e:
        fail(f"{scene_path}: unreadable ({e})")
    for key in ("units_displaced", "units_displaced_van_der_meer"):
        if not isinstance(summary, dict) or not is_number(summary.get(key)):
            fail(f"{path}: key '{key}': not a number (not the damage run of a wave train)")
    waves = scene.get("waves") if isinstance(scene.get("waves"), dict) else {}
    units = scene.get("unit") if isinstance(scene.get("unit"), list) else []
    density = units[0].get("density", "") if units and isinstance(units[0], dict) else ""
    row = {"case": os.path.basename(os.path.normpath(run)), "seed": waves.get("seed", ""), "status": "done",
           "unit.0.density": density}
    row.update({key: value for key, value in summary.items() if is_number(value)})
    run_waves = summary.get("waves") if isinstance(summary.get("waves"), dict) else {}
    row.update({"waves." + key: value for key, value in run_waves.items() if is_number(value)})
    return row


def stage_runs(runs, dest, staged, made):
    """Stages each run's files under DEST/cases/<name>/run/, results.csv and summary.json; returns the count."""
    names = [os.path.basename(os.path.normpath(r)) for r in runs]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        fail(f"--runs: more than one run folder is named {', '.join(twice)}: a run's folder name names its case")
    rows = [run_row(run) for run in runs]  # every run read before any file is written
    for run, row in zip(runs, rows):
        for name in PER_CASE:
            if os.path.exists(os.path.join(run, name)):
                stage(dest, os.path.join("cases", row["case"], "run", name), staged, made,
                      source=os.path.join(run, name))
    columns = ["case", "seed", "status", "unit.0.density"]
    columns += sorted({k for r in rows for k in r} - set(columns))
    table = io.StringIO()
    writer = csv.writer(table, lineterminator="\n")
    writer.writerow(columns)
    writer.writerows([f"{r[c]:.10g}" if isinstance(r.get(c), float) else r.get(c, "") for c in columns]
                     for r in rows)
    stage(dest, "results.csv", staged, made, text=table.getvalue())
    summary = {"command": "keep_results.py --runs", "cases": [r["case"] for r in rows],
               "units_displaced": sum(r["units_displaced"] for r in rows),
               "units_displaced_van_der_meer": sum(r["units_displaced_van_der_meer"] for r in rows),
               "si_units": {"units_displaced": "-", "units_displaced_van_der_meer": "-"}}
    stage(dest, "summary.json", staged, made, text=json.dumps(summary, indent=2) + "\n")
    return len(rows)


def keep_runs(dest, runs):
    for run in runs:
        refuse_while_running(run)
    kept = write_kept(dest, lambda staged, made: stage_runs(runs, dest, staged, made))
    print(f"kept {kept} runs' results in {dest}")


def write_kept(dest, stage_files):
    """Stages the keep's files with stage_files(staged, made), renames them over DEST's together, removes what
    an earlier keep wrote there and this one no longer writes, and lists the files; returns stage_files' count.
    Any error before the renames leaves DEST as it was."""
    staged, made = {}, set()
    # SIGTERM (a kill, a scheduler) ends the keep as Ctrl-C does: through the clean-up below.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    try:
        before = written_before(dest)
        kept = stage_files(staged, made)
        for name in staged:  # a folder where a file goes: refused before anything is renamed
            if os.path.isdir(os.path.join(dest, name)):
                raise IsADirectoryError(errno.EISDIR, "a folder where the keep writes a file", os.path.join(dest, name))
    except OSError as e:
        discard(staged, made)
        fail(f"{e.filename or dest}: {e.strerror or e}; {dest} left as it was")
    except KeyboardInterrupt:
        discard(staged, made)
        print(f"armour: error: interrupted; {dest} left as it was", file=sys.stderr)
        sys.exit(130)
    except BaseException:
        discard(staged, made)
        raise
    written = set(staged)
    try:
        commit(dest, staged)
    except OSError as e:  # between renames: a few files new, the rest and kept_files.txt old
        discard(staged, made)
        fail(f"{e.filename or dest}: {e.strerror or e}; {dest} partly kept: keep again")
    remove_stale(dest, before - written)
    put(dest, MANIFEST, "".join(name + "\n" for name in sorted(written)))
    return kept


if __name__ == "__main__":
    if sys.argv[1:] in (["-h"], ["--help"]):
        print(__doc__)
        sys.exit(0)
    if sys.argv[1:2] == ["--runs"]:
        if len(sys.argv) < 4:
            fail("--runs: usage: keep_results.py --runs DEST RUN [RUN ...]")
        keep_runs(sys.argv[2], sys.argv[3:])
    elif len(sys.argv) != 3:
        fail("usage: keep_results.py SWEEP_OUTPUT_DIR DEST, or keep_results.py --runs DEST RUN [RUN ...]")
    else:
        keep(sys.argv[1], sys.argv[2])
