#!/usr/bin/env python3
"""One or more kept stability curves on one chart, and their totals side by side.

Description
    Reads results.csv of each kept stability curve (a folder written by
    studies/keep_results.py from an `armour sweep` of a damage study) and draws
    N_od against Ns at the toe: for each curve a point per value of the varied
    key (the mean of its realisations with 95 % Student-t intervals in Ns and
    N_od), Van der Meer's curve for cubes at the first curve's median N and
    s_om. Given one curve (its folders joined with +), the chart is the one
    `armour sweep` draws of its own cases (apps/sweep/sweep_report.py): each
    realisation dotted, the band a section this wide sees about Van der
    Meer's curve, Hudson's lines, and S beside N_od. Prints, per varied value
    and in all, the units displaced by each curve and Van der Meer's expected
    count at the runs' own N, Ns and s_om (the sum of
    units_displaced_van_der_meer), with the Poisson probability of a total
    this low or lower if the formula's count were the mean. What it
    answers: does a model choice (the clump, the mesh, the engine) move the
    damage, and toward the formula or away. And how widely the realisations
    scatter about the formula's counts: Pearson's chi-square over them against
    the scatter of independent units (Poisson), with the chance of one as wide;
    and, the formula's shape set aside, about each point's own mean (counts
    that scatter widely about the formula but not within the points come from
    a curve of another shape, not from units that leave in groups).

    Where the kept cases' damage.csv are there (cases/<case>/run/damage.csv,
    as keep_results.py keeps them), how many of the displaced sat in the toe
    row: seated below the foot of the face (s_m < 0), on the berm in front of
    it, where the layer has no unit below it to lean on; and, where damage.csv
    flags them (`at_foot`), how many sat at the foot: every unit seated
    seaward of the face's foot, the toe row and the units piled over it. The
    counts and the factor on Ns are given again without each, so what the
    damage owes to the toe is told from what it owes to the face. And whether
    the same seats leave at rising Ns: per seed, the units that ended 0.25 Dn
    or more from their settled pose at one point and again at the next point
    up, against the count if the next point's were drawn at random (on a
    curve whose points share their layers, a body is one seat at every point).

    Then the gap as one number: the factor f such that the curve's counts are
    Van der Meer's at Ns / f (each run's expected count from the formula at its
    own N and s_om, scaled to the section's width), the maximum of the Poisson
    likelihood of the counts, with its 95 % interval where the log-likelihood
    is within 1.92 of its peak (chi-square, one degree of freedom). f > 1:
    the model needs f times the formula's Ns for the formula's damage, which is
    what loads f times too low would do (Ns is a load over a weight). With
    --pool, one f over every curve given, as one set of realisations.

    Last, what a point would take: how many realisations of the runs' length
    each point needs for its own f to be known within +-10 % (95 %;
    --precision), from the count Van der Meer expects of a realisation there
    at the curve's f, how steeply that count moves with f there, and the
    curve's own scatter within its points (where wider than independent
    units'). All figures are dimensionless (counts, N_od, Ns, f,
    realisations); the chart is a PNG.

Usage
    python3 studies/compare_curves.py docs/results/stability_curve_47spheres \\
        docs/results/stability_curve --label "47 spheres" --label "118 spheres" --out chart.png
    python3 studies/compare_curves.py docs/results/stability_curve \\
        docs/results/stability_by_height --pool --out chart.png
    python3 studies/compare_curves.py docs/results/stability_curve_dn4 \\
        docs/results/stability_one_layer_dn4+docs/results/stability_curve_dn4:2050 --out chart.png
    python3 studies/compare_curves.py docs/results/stability_curve_dn4 \\
        docs/results/settled_layers_dn4/staged_11_waves --seeds 2,3,4 --out chart.png

    A curve given as FOLDER[:VALUE,...]+FOLDER... is one curve of several
    kept studies' points: each folder's realisations, or only those whose
    varied key takes one of the VALUEs (the second example: the one-layer
    study's points on the 2050 kg/m3 layers with the curve's own 2050 point,
    whose layers they are).

    --seeds 2,3,4 keeps only those seeds' realisations in every curve, so that
    curves run on different sets of seeds are set side by side on the same
    ones (the third example: the Dn/4 curve's seeds 2-4 settled at once beside
    the same cases settled in 11 stages). A seed a curve has no done case of
    is refused, naming the curve.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "apps", "sweep"))
from sweep_report import (mean_interval, median, save, stability_chart, van_der_meer_n_od,  # noqa: E402
                          van_der_meer_ns)

SEAT_LEFT = 0.25  # Dn: a unit ending this far from its settled pose has left its seat (the pull test's mark)
NEEDED = ("Ns", "N_od", "units_displaced", "units_displaced_van_der_meer", "waves.waves", "s_om")


def fail(message):
    print(f"armour: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_curve(spec):
    """Rows of a curve given as FOLDER[:VALUE,...][+FOLDER[:VALUE,...]...], with the varied key's name.

    One curve may join the points of several kept studies (a study that ran some points on
    another's layers, the rest being that study's own): each folder's done rows, or only those
    whose varied key takes one of the VALUEs. The folders must vary the same key.
    """
    rows, varied = [], None
    for part in spec.split("+"):
        folder, _, values = part.partition(":")
        part_rows, part_varied = read_folder(folder)
        if rows and part_varied != varied:
            fail(f"{spec}: {folder} varies '{part_varied}', the curve's first folder '{varied}'")
        if values:
            if part_varied is None:
                fail(f"{spec}: {folder} varies no key, so ':{values}' picks nothing")
            wanted = [float(v) for v in values.split(",")]
            for v in wanted:
                if not any(float(r[part_varied]) == v for r in part_rows):
                    fail(f"{spec}: {folder} has no done case with {part_varied} = {v:g}")
            part_rows = [r for r in part_rows if float(r[part_varied]) in wanted]
        rows, varied = rows + part_rows, part_varied
    return rows, varied


def only_seeds(curve, spec, seeds):
    """A curve's rows of the given seeds only; every seed must have a done case in it."""
    rows, varied = curve
    by_seed = {seed: [r for r in rows if r.get("seed") == str(seed)] for seed in seeds}
    for seed, seed_rows in by_seed.items():
        if not seed_rows:
            fail(f"{spec}: --seeds: no done case with seed {seed}")
    return [r for seed_rows in by_seed.values() for r in seed_rows], varied


def seed_list(text):
    """--seeds' value, a comma-separated list of whole numbers."""
    try:
        seeds = [int(s) for s in text.split(",")]
    except ValueError:
        fail(f"--seeds: '{text}' is not a comma-separated list of seeds (whole numbers)")
    return seeds


def default_label(spec):
    """A curve's name when --label gives none: each folder's own name, with the values it picks."""
    names = []
    for part in spec.split("+"):
        folder, colon, values = part.partition(":")
        names.append(os.path.basename(os.path.normpath(folder)) + colon + values)
    return " + ".join(names)


def read_folder(folder):
    """Rows of FOLDER/results.csv that are done, with the varied key's name."""
    path = os.path.join(folder, "results.csv")
    if not os.path.isfile(path):
        fail(f"{path}: not found (not a kept stability curve)")
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [k for k in NEEDED if k not in (reader.fieldnames or [])]
        if missing:
            fail(f"{path}: column '{missing[0]}' missing (not a damage study's results)")
        header = reader.fieldnames
        rows = [r for r in reader if r.get("status", "done") == "done"]
    if not rows:
        fail(f"{path}: no case is done")
    # The varied key: the column between `case` and `seed`.
    varied = header[1] if header[0] == "case" and header[1] != "seed" else None
    for r in rows:
        units = case_units(folder, r)
        r["toe_row_displaced"], r["toe_row_units"] = toe_row(units)
        r["at_foot_displaced"], r["at_foot_units"] = at_foot(units)
        r["left_seat"] = left_seat(units)
        r["kept_units"] = units  # each unit's row of the kept damage.csv (the same seats; studies/seats.py)
    return rows, varied


def case_units(folder, row):
    """The row's case's units, from its kept damage.csv; None if not kept."""
    path = os.path.join(folder, "cases", row.get("case", ""), "run", "damage.csv")
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        units = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not units or not {"s_m", "displaced"} <= set(units[0]):
        fail(f"{path}: columns 's_m' and 'displaced' missing (not a damage run's damage.csv)")
    return units


def displaced_among(part):
    """(displaced, units) of a part of a case's units."""
    return sum(1 for u in part if u["displaced"] == "1"), len(part)


def toe_row(units):
    """(displaced, units) of a case's units seated below the face's foot (s_m < 0); Nones if not kept."""
    if units is None:
        return None, None
    return displaced_among([u for u in units if float(u["s_m"]) < 0])


def at_foot(units):
    """(displaced, units) of a case's units seated seaward of the face's foot (damage.csv's at_foot); Nones if
    not kept or written before the damage analysis flagged them."""
    if units is None or "at_foot" not in units[0]:
        return None, None
    return displaced_among([u for u in units if u["at_foot"] == "1"])


def left_seat(units):
    """The bodies of a case that ended SEAT_LEFT Dn or more from their settled pose; None if not kept."""
    if units is None or not {"body", "final_displacement_over_Dn"} <= set(units[0]):
        return None
    return {u["body"] for u in units if float(u["final_displacement_over_Dn"]) >= SEAT_LEFT}


def without_displaced(rows, taken):
    """The rows with taken[i] of row i's displaced units taken out of units_displaced and N_od."""
    kept = []
    for r, gone in zip(rows, taken):
        shown = float(r["units_displaced"])
        n_od = float(r["N_od"]) * (shown - gone) / shown if shown > 0 else 0.0
        kept.append(dict(r, units_displaced=str(shown - gone), N_od=str(n_od)))
    return kept


def without_toe_row(rows):
    """The rows with the toe row's displaced units taken out of units_displaced and N_od."""
    return without_displaced(rows, [r["toe_row_displaced"] for r in rows])


def print_toe_row(points, rows):
    """How many of the displaced sat in the toe row, and at the foot, per point; the counts and the factor
    without them."""
    if any(r["toe_row_displaced"] is None for r in rows):
        print("  toe row: not known (the cases' damage.csv are not kept beside results.csv)")
        return
    print_part(points, rows, "toe_row", "the toe row (seated below the face's foot)")
    if all(r["at_foot_displaced"] is not None for r in rows):
        print_part(points, rows, "at_foot", "the foot (seated seaward of the face's foot, damage.csv's at_foot)")


def print_part(points, rows, key, name):
    """How many of the displaced sat in a part of the layer (the rows' KEY_displaced of KEY_units), per point;
    the counts and the factor on Ns without them."""
    per_point = ", ".join(f"{sum(r[key + '_displaced'] for r in g)} of "
                          f"{sum(int(float(r['units_displaced'])) for r in g)}" for g in points)
    shown = sum(int(float(r["units_displaced"])) for r in rows)
    part = sum(r[key + "_displaced"] for r in rows)
    part_units = sum(r[key + "_units"] for r in rows)
    rest_units = sum(int(float(r["units"])) for r in rows) - part_units if "units" in rows[0] else None
    expected = sum(float(r["units_displaced_van_der_meer"]) for r in rows)
    print(f"  from {name}: {part} of {shown} (by point in rising Ns: {per_point}); "
          f"without them {shown - part} / {expected:.1f} (P {poisson_cdf(shown - part, expected):.2g})")
    if rest_units and part_units:
        print(f"  displaced per unit: {name.split(' (')[0]} {part} of {part_units} ({100 * part / part_units:.1f} %), "
              f"the face {shown - part} of {rest_units} ({100 * (shown - part) / rest_units:.1f} %)")
    print_ns_factor(f"without {name.split(' (')[0]}",
                    without_displaced(rows, [r[key + "_displaced"] for r in rows]))


def print_same_seats(points):
    """Whether a layer decides who moves: the same seats leaving at rising Ns.

    For each seed, its realisation at each point in rising Ns: the units that
    left their seat (ended SEAT_LEFT Dn or more from their settled pose) at one
    point, and how many of them left it again at the next point up, against
    the count if that point's were drawn at random from its units. On a curve
    whose points share one settled layer per seed (`fluid.settle_density`), a
    body is the same seat at every point, so many more than at random says the
    layer ranks its seats and Ns sets how far down the ranking the waves reach.
    Where each point settled its own layers, a body number names only where
    the unit was placed before its settle.
    """
    pairs, left, again, at_random = 0, 0, 0, 0.0
    for seed in sorted({r.get("seed") for g in points for r in g}, key=str):
        chain = [r for r in (next((r for r in g if r.get("seed") == seed), None) for g in points) if r]
        for low, high in zip(chain, chain[1:]):
            if seed is None or low["left_seat"] is None or high["left_seat"] is None:
                print("  the same seats at rising Ns: not known (needs the seed column and the cases' damage.csv "
                      "with final_displacement_over_Dn)")
                return
            pairs += 1
            left += len(low["left_seat"])
            again += len(low["left_seat"] & high["left_seat"])
            at_random += len(low["left_seat"]) * len(high["left_seat"]) / len(high["kept_units"])
    if pairs == 0:
        print("  the same seats at rising Ns: no seed ran at two points")
        return
    if left == 0:
        print(f"  the same seats at rising Ns: no unit left its seat (>= {SEAT_LEFT} Dn) below a seed's top point")
        return
    print(f"  the same seats at rising Ns (per seed, units ending >= {SEAT_LEFT} Dn from their settled pose at one "
          f"point that do again at the next point up): {again} of {left} ({100 * again / left:.0f} %), "
          f"{at_random:.1f} at random (P {poisson_sf(again, at_random):.2g} of so many)")


def poisson_sf(k, mean):
    """P(X >= k) for X Poisson with this mean, summed upward so that tiny tails keep their digits."""
    if k <= 0:
        return 1.0
    if mean <= 0:
        return 0.0
    term = total = math.exp(-mean + k * math.log(mean) - math.lgamma(k + 1))
    i = k
    while i <= mean or term > 1e-17 * total:  # the terms fall from the mode on
        i += 1
        term *= mean / i
        total += term
    return total


def poisson_cdf(k, mean):
    term = total = math.exp(-mean)
    for i in range(1, k + 1):
        term *= mean / i
        total += term
    return total


def chi2_tail(chi2, dof):
    """P(X >= chi2) for X chi-square with dof degrees of freedom.

    1 - P(a, x), a = dof / 2, x = chi2 / 2, with the lower gamma's series
    P(a, x) = sum over n >= 0 of e^-x x^(a+n) / Gamma(a+n+1): each term is at
    most 1 (taken through its logarithm), so no sum overflows however wide.
    """
    a, x = dof / 2.0, chi2 / 2.0
    if x <= 0:
        return 1.0
    lower, n = 0.0, 0
    while True:
        term = math.exp(-x + (a + n) * math.log(x) - math.lgamma(a + n + 1))
        lower += term
        n += 1
        if a + n > x and term < 1e-17:
            return max(0.0, 1.0 - lower)


def print_spread(rows):
    """How widely the counts scatter about the formula's, against independent units (Poisson).

    Pearson's chi-square, sum of (count - expected)^2 / expected over the
    realisations, has as many degrees of freedom as realisations when the
    formula's counts are the means: chi2 / n near 1 is a Poisson scatter, well
    above 1 counts that come in groups (or a formula wrong case by case).
    """
    terms = [(float(r["units_displaced"]) - float(r["units_displaced_van_der_meer"])) ** 2
             / float(r["units_displaced_van_der_meer"])
             for r in rows if float(r["units_displaced_van_der_meer"]) > 0]
    if terms:
        chi2 = sum(terms)
        print(f"  spread about the formula: chi2 {chi2:.2f} over {len(terms)} realisations, "
              f"{chi2 / len(terms):.2f} x independent units' (P {chi2_tail(chi2, len(terms)):.2g} of one this wide)")


def spread_within(points):
    """(chi2, degrees of freedom): Pearson's chi-square of the counts about each point's own mean."""
    chi2, dof = 0.0, 0
    for g in points:
        g = [r for r in g if float(r["units_displaced_van_der_meer"]) > 0]
        shown = sum(float(r["units_displaced"]) for r in g)
        if len(g) < 2 or shown == 0:
            continue
        scale = shown / sum(float(r["units_displaced_van_der_meer"]) for r in g)
        for r in g:
            mean = scale * float(r["units_displaced_van_der_meer"])
            chi2 += (float(r["units_displaced"]) - mean) ** 2 / mean
        dof += len(g) - 1
    return chi2, dof


def print_spread_within(points):
    """How widely the counts scatter about each point's own mean: the scatter alone, not the shape.

    The spread about the formula is large when units leave in groups, and also
    when the model's curve has another shape than the formula's (a point high,
    the next low). Here each point's expected counts are scaled by that point's
    own factor (its count over the formula's), so that only the scatter within
    a point is left: Pearson's chi-square over realisations less points. Points
    that displaced no unit say nothing about scatter and are left out.
    """
    chi2, dof = spread_within(points)
    if dof == 0:
        print("  spread within the points: no point has two realisations and a unit displaced")
    else:
        print(f"  spread within the points (about each point's own mean): chi2 {chi2:.2f} over {dof} degrees "
              f"of freedom, {chi2 / dof:.2f} x independent units' (P {chi2_tail(chi2, dof):.2g} of one this wide)")


def formula_runs(rows):
    """Per row (Ns, N, s_om, units displaced, units per N_od of the formula's count); None where none moved.

    The scale makes each row's expected count at Ns its own
    units_displaced_van_der_meer (so the section's width is the run's own);
    rows below the formula's onset at Ns take the median width (units per
    N_od) of the rows that displaced a unit.
    """
    widths = [float(r["units_displaced"]) / float(r["N_od"]) for r in rows if float(r["units_displaced"]) > 0]
    if not widths:
        return None
    width = median(widths)
    runs = []
    for r in rows:
        ns, n, s = float(r["Ns"]), float(r["waves.waves"]), float(r["s_om"])
        at_ns = van_der_meer_n_od(ns, n, s)
        scale = float(r["units_displaced_van_der_meer"]) / at_ns if at_ns > 0 else width
        runs.append((ns, n, s, int(float(r["units_displaced"])), scale))
    return runs


def expected_at(run, f):
    """A run's expected count if its units were Van der Meer's at Ns / f."""
    ns, n, s, _, scale = run
    return max(scale * van_der_meer_n_od(ns / f, n, s), 1e-300)


def ns_factor(rows):
    """(f, low, high): the counts as Van der Meer's at Ns / f, its 95 % interval; None where no unit moved."""
    runs = formula_runs(rows)
    if runs is None:
        return None

    def log_likelihood(f):
        total = 0.0
        for run in runs:
            mean = expected_at(run, f)
            total += run[3] * math.log(mean) - mean
        return total

    grid = [0.25 * 16.0 ** (i / 40000) for i in range(40001)]  # 0.25 to 4, 0.007 % apart
    values = [log_likelihood(f) for f in grid]
    peak = max(range(len(grid)), key=values.__getitem__)
    inside = [f for f, v in zip(grid, values) if v >= values[peak] - 1.92]
    return grid[peak], min(inside), max(inside)


def poisson_deviance(count, mean):
    """Twice the log-likelihood a count loses to a mean (0 where both are 0)."""
    if mean <= 0:
        return 0.0 if count == 0 else math.inf
    return 2.0 * ((count * math.log(count / mean) if count > 0 else 0.0) - (count - mean))


def f_tail(x, d1, d2):
    """P(X >= x) for X with Fisher's F distribution on (d1, d2) degrees of freedom."""
    if x <= 0:
        return 1.0
    return beta_regularized(d2 / 2.0, d1 / 2.0, d2 / (d2 + d1 * x))


def beta_regularized(a, b, x):
    """I_x(a, b), the regularised incomplete beta function, by its continued fraction (Lentz's method).

    The fraction converges fast for x < (a + 1) / (a + b + 2); past it the
    symmetry I_x(a, b) = 1 - I_(1-x)(b, a) is used.
    """
    if x <= 0 or x >= 1:
        return 0.0 if x <= 0 else 1.0
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x))
    if x > (a + 1) / (a + b + 2):
        return 1.0 - beta_regularized(b, a, 1.0 - x)
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    fraction = d
    for m in range(1, 1000):
        for numerator in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                          -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + numerator * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + numerator / c
            c = c if abs(c) > tiny else tiny
            fraction *= c * d
        if abs(c * d - 1.0) < 1e-15:
            break
    return front * fraction / a


def print_shape(points, rows, fit):
    """Is the curve's shape the formula's? One factor on Ns against a scale of its own for each point.

    The Poisson deviance of the counts about Van der Meer's curve at Ns / f (one
    parameter) less that about each point's own mean (one a point), over points
    less one, against the points' own scatter (Pearson's chi-square within them
    over its degrees of freedom, as print_spread_within), is Fisher's F
    (quasi-Poisson: units that leave in groups widen both alike). A small P says
    the shape differs from the formula's beyond what the realisations' own
    scatter explains; a large one, that they cannot tell a shape from a sample.
    """
    runs = formula_runs(rows)
    if runs is None:
        return
    one = sum(poisson_deviance(run[3], expected_at(run, fit[0])) for run in runs)
    own = 0.0
    for g in points:
        shown = sum(float(r["units_displaced"]) for r in g)
        formula = sum(float(r["units_displaced_van_der_meer"]) for r in g)
        scale = shown / formula if formula > 0 else 0.0
        own += sum(poisson_deviance(int(float(r["units_displaced"])), scale * float(r["units_displaced_van_der_meer"]))
                   for r in g)
    within, d2 = spread_within(points)
    d1 = len(points) - 1
    if d1 < 1 or d2 < 1 or within <= 0 or math.isinf(own):
        print("  the shape: too few points or realisations to weigh it against the points' own scatter")
        return
    f_stat = (one - own) / d1 / (within / d2)
    print(f"  the shape (one factor on Ns, or a scale for each point): deviance {one:.2f} against {own:.2f}, "
          f"F {f_stat:.2f} on ({d1}, {d2}) over the points' own scatter: P {f_tail(f_stat, d1, d2):.2g} of a "
          f"shape this far from the formula's by chance (Poisson's scatter alone: {chi2_tail(one - own, d1):.2g})")


def realisations_needed(run, f, dispersion, precision):
    """Realisations like `run` for one point's f within a factor 1 +- precision (95 %).

    Over n realisations the point's count has mean M = n m (m = one
    realisation's expected count at Ns / f) and variance dispersion x M, so
    ln f is known to sqrt(dispersion / M) / |d ln m / d ln f| (the delta
    method); setting 1.96 of that to ln(1 + precision) gives n. The slope is
    the formula's own (Van der Meer's N_od grows as (Ns s_om^0.1 - 1)^2.5, so
    ~8.5 at Ns 2 and ~3.9 at Ns 4 for s_om 0.031): near the onset a
    realisation holds few units, each of which tells much about f.
    """
    step = 1e-4
    slope = abs(math.log(expected_at(run, f * (1 + step)) / expected_at(run, f * (1 - step)))) / (2 * step)
    m = expected_at(run, f)
    if slope == 0 or m <= 1e-12:
        return math.inf
    return dispersion * (1.96 / (math.log(1.0 + precision) * slope)) ** 2 / m


def print_planning(points, rows, fit, precision):
    """Per point, the realisations of the runs' length that its own f within +-precision needs."""
    runs = formula_runs(rows)
    if runs is None or fit is None:
        return
    chi2, dof = spread_within(points)
    dispersion = max(1.0, chi2 / dof) if dof else 1.0
    run_of = {id(r): run for r, run in zip(rows, runs)}  # the points hold the rows themselves
    needs = []
    for g in points:
        here = [run_of[id(r)] for r in g]
        n = median([realisations_needed(run, fit[0], dispersion, precision) for run in here])
        needs.append(f"Ns {mean_interval([run[0] for run in here])[0]:.2f}: "
                     + (f"{math.ceil(n)}" if math.isfinite(n) else "not bounded"))
    scatter = (f"the points' own scatter, {dispersion:.2f} x independent units'" if dispersion > 1.0
               else "independent units' scatter")
    print(f"  realisations a point needs for its f within +-{100 * precision:g} % (95 %), each of the runs' "
          f"length (median N {median([run[1] for run in runs]):g} waves), at f {fit[0]:.2f} and {scatter}: "
          + ", ".join(needs))


def print_ns_factor(label, rows):
    """Prints the factor on Ns and returns it (None where no unit moved)."""
    fit = ns_factor(rows)
    if fit is None:
        print(f"  {label}: no unit displaced: the factor on Ns is not bounded")
    else:
        print(f"  {label}: the counts are Van der Meer's at Ns / f, f = {fit[0]:.2f} "
              f"(95 % {fit[1]:.2f}-{fit[2]:.2f})")
    return fit


def as_sweep_cases(rows, varied):
    """The rows as summary.json lists a sweep's cases: numeric figures, and the varied value that makes a point."""
    def numeric(text):
        try:
            return float(text)
        except (TypeError, ValueError):
            return None

    cases = []
    for r in rows:
        figures = {k: x for k, v in r.items() if isinstance(v, str) and (x := numeric(v)) is not None}
        cases.append({"figures": figures, "values": {varied: numeric(r[varied])} if varied else {}})
    return cases


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[1].strip(),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("curves", nargs="+", help="folders of kept stability curves (results.csv in each); "
                        "FOLDER:V1,V2+FOLDER2 joins FOLDER's points V1 and V2 and FOLDER2's into one curve")
    parser.add_argument("--label", action="append", default=[], help="a name per curve, in order")
    parser.add_argument("--out", required=True, help="the chart to write (PNG)")
    parser.add_argument("--pool", action="store_true", help="also one factor on Ns over every curve given")
    parser.add_argument("--precision", type=float, default=0.1,
                        help="the relative half-width on a point's f (95 %%) the planning line asks for "
                        "(default 0.1)")
    parser.add_argument("--seeds", help="only these seeds' realisations in every curve, e.g. 2,3,4")
    args = parser.parse_args()
    labels = args.label or [default_label(c) for c in args.curves]
    if len(labels) != len(args.curves):
        fail(f"--label: {len(labels)} labels for {len(args.curves)} curves")
    if not 0.0 < args.precision <= 1.0:
        fail(f"--precision: {args.precision:g} is not a relative half-width in (0, 1]")
    curves = [read_curve(c) for c in args.curves]
    if args.seeds is not None:
        seeds = seed_list(args.seeds)
        curves = [only_seeds(curve, spec, seeds) for curve, spec in zip(curves, args.curves)]

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # Several curves side by side on this chart; one is drawn as a sweep draws its cases (below).
    fig, ax = plt.subplots(figsize=(6.5, 4.2)) if len(curves) > 1 else (None, None)
    top = 0.5
    for k, ((rows, varied), label) in enumerate(zip(curves, labels)):
        shift = 0.03 * (k - (len(curves) - 1) / 2)  # side by side where points share an Ns
        groups = {}
        for r in rows:
            groups.setdefault(r[varied] if varied else "all", []).append(r)
        print(f"{label}: units displaced / Van der Meer's expected count (P of this few or fewer by chance)")
        total = expected = 0.0
        by_ns = sorted(groups.items(), key=lambda kv: sum(float(r["Ns"]) for r in kv[1]) / len(kv[1]))
        for i, (value, g) in enumerate(by_ns):  # points in rising Ns, whatever key varied it
            ns = mean_interval([float(r["Ns"]) for r in g])
            n_od = mean_interval([float(r["N_od"]) for r in g])
            if ax:
                ax.errorbar([ns[0] + shift], [n_od[0]], xerr=[ns[1]], yerr=[n_od[1]], fmt="o", capsize=3,
                            color=f"C{k}", label=None if i else label)
            top = max(top, n_od[0] + n_od[1])
            shown = sum(int(float(r["units_displaced"])) for r in g)
            vdm = sum(float(r["units_displaced_van_der_meer"]) for r in g)
            total += shown
            expected += vdm
            print(f"  {varied or 'all'} {value}: Ns {ns[0]:.2f}  {shown} / {vdm:.1f} "
                  f"(P {poisson_cdf(shown, vdm):.2g})  over {len(g)} realisations")
        print(f"  all: {int(total)} / {expected:.1f} (P {poisson_cdf(int(total), expected):.2g})")
        print_spread(rows)
        print_spread_within([g for _, g in by_ns])
        fit = print_ns_factor("all", rows)
        print_shape([g for _, g in by_ns], rows, fit)
        print_planning([g for _, g in by_ns], rows, fit, args.precision)
        print_toe_row([g for _, g in by_ns], rows)
        print_same_seats([g for _, g in by_ns])
    if args.pool:
        print(f"{' + '.join(labels)}, pooled:")
        pooled = [r for rows, _ in curves for r in rows]
        print_ns_factor("all", pooled)
        if all(r["toe_row_displaced"] is not None for r in pooled):
            print_ns_factor("without the toe row", without_toe_row(pooled))
    if not ax:  # one curve: the chart a sweep draws of its own cases, over every folder joined
        stability_chart(plt, as_sweep_cases(*curves[0]), args.out)
        return
    rows = curves[0][0]
    n = median([float(r["waves.waves"]) for r in rows])
    s_om = median([float(r["s_om"]) for r in rows])
    grid = [1.3 * top * i / 200 for i in range(201)]
    ax.plot([van_der_meer_ns(d, n, s_om) for d in grid], grid, "-", color="C3",
            label=f"Van der Meer cubes (N = {n:g}, s_om = {s_om:.3g})")
    ax.set_xlabel("Ns = Hs / (Δ Dn) at the toe [-]")
    ax.set_ylabel("N_od [units per Dn width]")
    ax.set_ylim(0, 1.3 * top)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, args.out)


if __name__ == "__main__":
    main()
