"""A study as the report reads it: what STUDY.csv is (the summary of `poundbench
workprecision` or of `poundbench stress`, or the rows of `poundbench spectrum`), its rows
checked, the per-run rows of --points that go with it, and what the report derives from
them: the scene of each family, the truth of each point, each setting's error over the
points where the truth has an impact. No matplotlib here.

A bad file is an InputError naming the file, the line, the column and why (the report's
entry points print it as one line and exit 2), found before anything is written."""

import csv
import math
import os
from collections import defaultdict

from rows import median, num

# What each kind of file is known by (its header has every one of these) and the numeric
# columns checked on every row (an empty field is a value that does not exist).
KINDS = {
    "workprecision": dict(
        what="a work-precision summary (`poundbench workprecision --out`)",
        columns=("family", "solver", "variant", "settings", "points", "failed", "err_median", "err_p95",
                 "cpu_median_s"),
        counts=("points", "failed"),
        numbers=("err_median", "err_p95", "err_max", "cpu_median_s", "cpu_median_low_s", "cpu_median_high_s")),
    "stress": dict(
        what="a stress summary (`poundbench stress --out`)",
        columns=("family", "solver", "variant", "settings", "runs", "ok", "finite", "energy", "gap", "restitution"),
        counts=("runs", "ok"),
        numbers=("cpu_median_s",)),
    "spectrum": dict(
        what="result rows (`poundbench spectrum`, or a study's --points)",
        columns=("family", "point", "scene", "pulse", "pi2", "solver", "variant", "settings", "status", "pi1"),
        counts=("point",),
        numbers=("pi2", "pi1", "pi1_no_contact", "cpu_seconds")),
}


class InputError(Exception):
    """A file the report cannot use: "FILE:LINE: COLUMN: why"."""


def read_csv(path):
    """The rows of a CSV file as dicts, and its header; InputError when it cannot be read."""
    if not os.path.exists(path):
        raise InputError(f"{path}: no such file")
    if not os.path.isfile(path):
        raise InputError(f"{path}: " + ("is a directory" if os.path.isdir(path) else
                                        "not a regular file (a pipe or a device): give the file itself"))
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            return rows, reader.fieldnames or []
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: cannot be read as CSV: {e}") from None


def kind_of(header):
    for kind in ("workprecision", "stress", "spectrum"):
        if all(c in header for c in KINDS[kind]["columns"]):
            return kind
    return None


def check_rows(path, rows, kind):
    """Every count a whole number >= 0 and every number a number (or empty), on every row."""
    spec = KINDS[kind]
    for i, r in enumerate(rows, start=2):
        if None in r or any(v is None for v in r.values()):
            raise InputError(f"{path}:{i}: the row has {'more' if None in r else 'fewer'} fields than the header")
        for c in spec["counts"]:
            if not r[c].isdigit():
                raise InputError(f"{path}:{i}: {c}: must be a whole number >= 0 (it is '{r[c][:40]}')")
        for c in spec["numbers"]:
            if c in r and r[c] != "":
                try:
                    float(r[c])
                except ValueError:
                    raise InputError(f"{path}:{i}: {c}: not a number ('{r[c][:40]}')") from None


def setting_key(r):
    return (r["family"], r["solver"], r["variant"], r["settings"])


class Study:
    """One study: `kind` ('workprecision', 'stress' or 'spectrum'), its rows, and the per-run
    rows of its points (empty without --points)."""

    def __init__(self, path, points_path=None):
        self.path, self.points_path = path, points_path
        self.rows, header = read_csv(path)
        self.kind = kind_of(header)
        if self.kind is None:
            raise InputError(f"{path}:1: header: not a poundbench result file (expected "
                             + "; or ".join(f"{k['what']}, with the columns {', '.join(k['columns'])}"
                                            for k in KINDS.values()) + ")")
        if not self.rows:
            raise InputError(f"{path}: no rows after the header")
        check_rows(path, self.rows, self.kind)
        self.points = []
        if points_path:
            if self.kind == "spectrum":
                raise InputError(f"--points: {points_path}: a spectrum's rows are its points already")
            self.points, points_header = read_csv(points_path)
            if kind_of(points_header) != "spectrum":
                raise InputError(f"{points_path}:1: header: not per-run rows (expected the columns "
                                 + ", ".join(KINDS['spectrum']['columns']) + ")")
            check_rows(points_path, self.points, "spectrum")
            self._check_points_belong()
        self.families = list(dict.fromkeys(r["family"] for r in self.rows))
        runs = self.rows if self.kind == "spectrum" else self.points
        self.scenes = {r["family"]: scope_of(r) for r in runs}  # family -> its answer's scope, where known
        self.truth = {}  # point -> the truth's row (the first row of each point: the study writes it first)
        if self.points:
            for r in self.points:
                self.truth.setdefault(r["point"], r)

    def _check_points_belong(self):
        """The points are this study's: every setting of the summary has runs there, and every
        run is of a family and setting the summary has (or is the truth, or a model's reference)."""
        have = {setting_key(r) for r in self.points}
        for i, r in enumerate(self.rows, start=2):
            if setting_key(r) not in have:
                raise InputError(f"{self.points_path}: no runs of {self.path}:{i}'s family {r['family']} and setting "
                                 f"{r['solver']} {r['variant']} {r['settings']}: not the points of this study")

    @property
    def name(self):
        return os.path.basename(self.path)

    def has_scenes(self):
        return all(f in self.scenes for f in self.families)


def scope_of(run):
    """The scope of the answer tables a run's family belongs to: its scene, or for a recorded
    ground motion "<scene> records", a row of its own: a record's rough load costs a
    time-stepper far more than a pulse (issue 34: the synthetic record set the cost of every
    `pair` answer, sending pulse users to a setting 60x costlier than they need)."""
    return run["scene"] + (" records" if run.get("pulse") == "record" else "")


def percentile(values, p):
    """The p-th percentile by linear interpolation between order statistics (numpy's default,
    as studies/stats.cpp computes the summary's); NaN for no values."""
    values = sorted(values)
    if not values:
        return float("nan")
    x = (len(values) - 1) * p / 100
    lo = math.floor(x)
    hi = min(lo + 1, len(values) - 1)
    return values[lo] + (values[hi] - values[lo]) * (x - lo)


def impacting_errors(study):
    """Per (family, solver, variant, settings): the relative Pi1 errors over the points where
    the truth has at least one impact, as {key: dict(points, err_median, err_p95)}: where
    the truth has none, the answer is the ground's motion through a free oscillator, which
    every scheme gets to its order, and a study's median can hide an impacting minority.
    Beside them, the second accuracy measure: the relative error in the largest impact velocity
    (rows' impact_velocity_pi, rows/physical_results.hpp) over the same points, vel_median and
    vel_p95 (NaN where the rows predate that column)."""
    errors = defaultdict(list)
    velocity = defaultdict(list)
    counted = defaultdict(int)
    for r in study.points:
        truth = study.truth[r["point"]]
        if r is truth:
            continue
        if truth["status"] != "ok" or not num(truth, "impacts") > 0:
            continue
        key = setting_key(r)
        counted[key] += 1
        exact = num(truth, "pi1")
        if r["status"] == "ok" and math.isfinite(num(r, "pi1")) and exact > 0:
            errors[key].append(abs(num(r, "pi1") - exact) / exact)
        v_exact, v = num(truth, "impact_velocity_pi"), num(r, "impact_velocity_pi")
        if r["status"] == "ok" and v_exact > 0 and math.isfinite(v):
            velocity[key].append(abs(v - v_exact) / v_exact)
    return {key: dict(points=n, err_median=percentile(errors[key], 50), err_p95=percentile(errors[key], 95),
                      vel_median=percentile(velocity[key], 50), vel_p95=percentile(velocity[key], 95))
            for key, n in counted.items()}


IMPACTING_COLUMNS = ["family", "solver", "variant", "settings", "impacting_points", "err_median", "err_p95",
                     "vel_median", "vel_p95"]


def write_impacting(impacting, path):
    """The errors over impacting points as a small CSV (the main job commits it: README's
    answer quotes it)."""
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(IMPACTING_COLUMNS)
        for key, v in impacting.items():
            w.writerow([*key, v["points"], *(repr(v[m]) if math.isfinite(v[m]) else ""
                                             for m in ("err_median", "err_p95", "vel_median", "vel_p95"))])
    os.replace(path + ".tmp", path)


def read_impacting(path):
    rows, _ = read_csv(path)
    return {setting_key(r): dict(points=int(r["impacting_points"]), err_median=num(r, "err_median"),
                                 err_p95=num(r, "err_p95"), vel_median=num(r, "vel_median"),
                                 vel_p95=num(r, "vel_p95")) for r in rows}


def spectrum_summary(rows):
    """Per family and solver configuration of spectrum rows: points, failed, median impacts,
    median CPU per point."""
    groups = defaultdict(list)
    for r in rows:
        groups[(r["family"], r["solver"], r["variant"], r["settings"])].append(r)
    return [dict(family=k[0], solver=k[1], variant=k[2], settings=k[3], points=len(g),
                 failed=sum(r["status"] != "ok" for r in g),
                 impacts=median([num(r, "impacts") for r in g]) if "impacts" in g[0] else float("nan"),
                 cpu=median([num(r, "cpu_seconds") for r in g]) if "cpu_seconds" in g[0] else float("nan"),
                 total_cpu=sum(num(r, "cpu_seconds") for r in g) if "cpu_seconds" in g[0] else float("nan"))
            for k, g in groups.items()]
