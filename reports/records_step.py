"""The step on real records (issue 34). `poundbench workprecision cases/sets/records-step.toml
--settings cases/settings/records-step.toml --points` (scripts/main.sh:
results/records-step-points.csv) solves the real-record work-precision family and the same
buildings too far apart to touch, each time-stepper at h = T_min / N and under the step rule
`record` (steps_per_sample = 1: h = DT / m, every sample a step's end) over the same N.
compact() reduces those points to one line a run (reports/records-step.csv, committed);
lines() answers from it how h relates to the record's sampling interval DT, where the error
on a record comes from, and whether the rule serves a user better than T_min / N. README's
block and the report's section are written from the same lines. No matplotlib here."""

import csv
import math
import sys

import robust
from rows import config_label, median, num, settings_fields, steps_of

SUMMARY = "records-step.csv"
FIELDS = ["family", "point", "record", "setting", "rule", "n", "h_over_dt", "steps", "error"]
TARGETS = (1e-2, 1e-3)
FREE = "-free"  # the family of the same buildings out of reach of each other


def _model(row):
    """Which exact solution a run is measured against: the rigid one, or its compliant model's
    (the event-driven solver with contact = that element, at that stiffness)."""
    f = settings_fields(row)
    if row["solver"] == "event-driven":
        return (f.get("contact", "rigid"), f.get("stiffness"))
    if row["solver"] == "compliant":
        return (row.get("variant") or "kelvin-voigt", f.get("stiffness"))
    return ("rigid", None)


def compact(points):
    """One dict a time-stepper run: its setting (without the rule), the rule, N, h / DT, its step
    count and its relative error against the tightest event-driven run of its point and model
    (inf when the run failed)."""
    ref = {}
    for r in points:
        if r["solver"] == "event-driven":
            if r["family"].endswith(FREE) and int(r["impacts"] or 0) > 0:
                sys.exit(f"records_step.py: point {r['point']} of {r['family']} pounds: its buildings are not apart")
            key = (r["family"], r["point"], _model(r))
            tol = settings_fields(r).get("tol_scale", 1)
            if key not in ref or tol < ref[key][0]:
                ref[key] = (tol, num(r, "pi1"))
    out = []
    for r in points:
        if r["solver"] == "event-driven" or steps_of(r) is None:
            continue
        exact = ref[(r["family"], r["point"], _model(r))][1]
        out.append(dict(family=r["family"], point=r["point"], record=r["record"].rsplit("/", 1)[-1],
                        setting=config_label(r).replace(f" rule=record k={settings_fields(r).get('steps_per_sample')}", ""),
                        rule="record" if "steps_per_sample" in settings_fields(r) else "T_min / N",
                        n=steps_of(r), h_over_dt=f"{num(r, 'h_over_dt'):.6g}", steps=r["steps"],
                        error=f"{abs(num(r, 'pi1') - exact) / abs(exact):.6g}" if r["status"] == "ok" else "inf"))
    return out


def write(path, runs):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, FIELDS, lineterminator="\n")
        w.writeheader()
        w.writerows(runs)


def _table(runs):
    """{(family is free, setting): {rule: {N: [(error, h / DT, steps)]}}}."""
    t = {}
    for r in runs:
        key = (r["family"].endswith(FREE), r["setting"])
        t.setdefault(key, {}).setdefault(r["rule"], {}).setdefault(int(r["n"]), []).append(
            (float(r["error"]), float(r["h_over_dt"]), int(r["steps"])))
    return t


def pct(x):
    return "fails" if math.isinf(x) else f"{100 * x:.2g} %"


def p95(values):
    values = sorted(values)
    return values[min(len(values) - 1, math.ceil(0.95 * len(values)) - 1)]


def least_n(by_n, target, stat):
    """The least N that meets the target by `stat` by the one rule (robust.py: every larger N
    meets it too); None if the largest does not. A failed run's error is inf: its N and every
    smaller one never meet."""
    ns = list(by_n)
    errors = robust.robust([("one line", n, stat([e for e, _, _ in by_n[n]])) for n in ns])
    return min((n for n, e in zip(ns, errors) if e <= target), default=None)


def _cells(runs):
    return [pct(median([e for e, _, _ in runs])), pct(p95([e for e, _, _ in runs])),
            str(int(median([s for _, _, s in runs])))] if runs else ["", "", ""]


def lines(runs):
    t = _table(runs)
    n_points = len({(r["family"], r["point"]) for r in runs if not r["family"].endswith(FREE)})
    text = [f"The {n_points} points of `cases/sets/workprecision-records.toml` (`cases/sets/records-step.toml`), "
            "each time-stepper at `h = T_min / N` and under the step rule `record` (`--steps-per-sample 1`: "
            "`h = DT / m`, `m` the least whole number with `h <= T_min / N`, so that every sample of the record is "
            "a step's end); errors against the reference solved 100x tighter (the compliant element against its "
            "own model solved exactly); *steps*: the median step count of a run, its cost; *apart*: the same "
            "buildings at Pi3 = 100, where no record closes the gap (the load and the structure alone).", "",
            "| setting | N | median h / DT | T_min / N: median error | 95th | steps | record: median | 95th | steps "
            "| apart, T_min / N: median | 95th | apart, record: median | 95th |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for (free, label), rules in t.items():
        if free:
            continue
        apart = t.get((True, label), {})
        plain = rules.get("T_min / N", {})
        for n in sorted(plain):
            cells = [label, str(n), f"{median([q for _, q, _ in plain[n]]):.2g}", *_cells(plain[n]),
                     *_cells(rules.get("record", {}).get(n, []))]
            cells += _cells(apart.get("T_min / N", {}).get(n, []))[:2] + _cells(apart.get("record", {}).get(n, []))[:2]
            text.append("| " + " | ".join(cells) + " |")
    text += ["", "At about equal cost: each N of the rule `record` beside the N of `T_min / N` whose median step "
             "count is nearest (by ratio):", "",
             "| setting | record: N | steps | median | 95th | T_min / N: N | steps | median | 95th |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for (free, label), rules in t.items():
        plain, rec = rules.get("T_min / N", {}), rules.get("record", {})
        if free or not plain or not rec:
            continue
        steps = {n: median([s for _, _, s in runs]) for n, runs in plain.items()}
        for n in sorted(rec):
            cost = median([s for _, _, s in rec[n]])
            match = min(plain, key=lambda m: abs(math.log(steps[m] / cost)))
            text.append(f"| {label} | {n} | " + " | ".join(_cells(rec[n])[2:] + _cells(rec[n])[:2]) + f" | {match} | "
                        + " | ".join(_cells(plain[match])[2:] + _cells(plain[match])[:2]) + " |")
    text += ["", "The least N from which every finer step meets 1 % and 0.1 % (median and 95th percentile of the "
             "error over the points), with the median step count of a run there:", "",
             "| setting | rule | 1 %, median | 1 %, 95th | 0.1 %, median | 0.1 %, 95th |", "|---|---|---:|---:|---:|---:|"]
    for (free, label), rules in t.items():
        if free:
            continue
        for rule, by_n in rules.items():
            cells = []
            for target in TARGETS:
                for stat in (median, p95):
                    n = least_n(by_n, target, stat)
                    cells.append(f"N = {n} ({int(median([s for _, _, s in by_n[n]]))} steps)" if n
                                 else f"beyond {max(by_n)}")
            text.append(f"| {label} | {rule} | " + " | ".join(cells) + " |")
    return text


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def section(runs):
    return ["## The step on real records", "",
            "A record is linear between its samples, so its load has a kink every DT. A step that straddles a "
            "sample averages (Moreau–Jean's exact step mean) or samples (the engines) the load across the kink, "
            "and a step longer than DT steps over the record's content above 1 / (2 h). The rule `record` puts "
            "every sample on a step's end; the buildings apart say what the load and the structure cost without "
            "the impacts.", "", *lines(runs), ""]


if __name__ == "__main__":  # the reduction alone, as make_report.py --records-step does it
    import argparse
    from rows import load
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("points", help="results/records-step-points.csv")
    parser.add_argument("--out", required=True, help="the one-line-a-run CSV (reports/records-step.csv)")
    args = parser.parse_args()
    write(args.out, compact(load([args.points])))
