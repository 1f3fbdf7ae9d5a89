"""A study as the report reads it: what STUDY.csv is (the summary of `poundbench
workprecision` or of `poundbench stress`, or the rows of `poundbench spectrum`), its rows
checked, the per-run rows of --points that go with it, and what the report derives from
them: the scene of each family, the truth of each point, each setting's error over the
points where the truth has an impact. No matplotlib here.

A bad file is an InputError naming the file, the line, the column and why (the report's
entry points print it as one line and exit 2), found before anything is written."""

import csv
import json
import math
import os
import sys
from collections import defaultdict

from rows import median, num

# What each kind of file is (what writes it) and is known by (its header has
# every one of these columns, which the report reads on every row), and the domain of every
# column it reads as a number (checked on every row where the file has the column; an empty
# field is a value that does not exist, which poundbench writes for NaN). Domains (DOMAINS):
# "count" a whole number >= 0, "error" a number >= 0 or inf (a relative error against a
# reference of 0), "seconds" and "nonnegative" a finite number >= 0, "positive" a finite
# number > 0, "number" a finite one.
KINDS = {
    "workprecision": dict(
        what="a work-precision summary (`poundbench workprecision --out`)",
        columns=("family", "solver", "variant", "settings", "points", "failed", "err_median", "err_p95",
                 "cpu_median_s"),
        required=("points", "failed"),
        domains=dict(points="count", failed="count", unresolved="count", err_median="error", err_p95="error",
                     err_max="error", cpu_median_s="seconds", cpu_mean_s="seconds", cpu_median_low_s="seconds",
                     cpu_median_high_s="seconds"),
        at_most=(("failed", "points"), ("unresolved", "points"))),
    "stress": dict(
        what="a stress summary (`poundbench stress --out`)",
        columns=("family", "solver", "variant", "settings", "runs", "ok", "finite", "energy", "gap", "restitution"),
        required=("runs", "ok"),
        domains=dict(runs="count", ok="count", cpu_median_s="seconds", cpu_median_low_s="seconds",
                     cpu_median_high_s="seconds", energy_excess_max="number", penetration_max="nonnegative",
                     penetration_steps_max="nonnegative", restitution_error_max="nonnegative", pi1_err_median="error",
                     pi1_err_p95="error", pi1_err_max="error"),
        at_most=(("ok", "runs"),)),
    "spectrum": dict(
        what="per-run rows (`poundbench spectrum`, a study's --points)",
        columns=("family", "point", "scene", "pulse", "directivity", "pi2", "solver", "variant", "settings", "status",
                 "pi1"),
        required=("point", "pi2"),
        domains=dict(point="count", pi2="positive", pi1="error", pi1_no_contact="error", cpu_seconds="seconds",
                     impacts="count", steps="count", bodies="count", impact_velocity_pi="error",
                     energy_excess="number", penetration_steps="nonnegative", pi1_error="error"),
        at_most=()),
}

DOMAINS = {
    "count": ("a whole number >= 0", lambda text, x: text.isdigit()),
    "error": ("a number >= 0 (or inf)", lambda text, x: x >= 0),
    "seconds": ("a finite number >= 0", lambda text, x: 0 <= x < math.inf),
    "nonnegative": ("a finite number >= 0", lambda text, x: 0 <= x < math.inf),
    "positive": ("a finite number > 0", lambda text, x: 0 < x < math.inf),
    "number": ("a finite number", lambda text, x: math.isfinite(x)),
}


class InputError(Exception):
    """A file the report cannot use: "FILE:LINE: COLUMN: why"."""


def read_csv(path):
    """The rows of a CSV file as dicts, its header, and the line each row ends on (a quoted
    field may hold line ends); InputError when it cannot be read."""
    if not os.path.exists(path):
        raise InputError(f"{path}: no such file")
    if not os.path.isfile(path):
        raise InputError(f"{path}: " + ("is a directory" if os.path.isdir(path) else
                                        "not a regular file (a pipe or a device): give the file itself"))
    csv.field_size_limit(sys.maxsize)  # a field as long as the file (a family's name): memory is the limit
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows, lines = [], []
            for row in reader:
                rows.append(row)
                lines.append(reader.line_num)
            return rows, reader.fieldnames or [], lines
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: cannot be read as CSV: {clip(str(e))}") from None


def clip(text, most=40):
    """A value as a message quotes it: at most `most` characters, on one line."""
    text = text if len(text) <= most else text[:most] + "..."
    return text.encode("unicode_escape").decode("ascii") if not text.isprintable() else text


def header_problem(path, header, kinds=None):
    """Why a header is none of `kinds`' (default: any kind's): the columns missing from the
    kind it is closest to, where it has most of that kind's; else what a result file is."""
    kinds = kinds or list(KINDS)
    closest = max(kinds, key=lambda k: sum(c in header for c in KINDS[k]["columns"]))
    columns = KINDS[closest]["columns"]
    missing = [c for c in columns if c not in header]
    if 2 * len(missing) < len(columns) or len(kinds) == 1:
        return (f"{path}:1: header: no column {', '.join(missing)} (the columns of {KINDS[closest]['what']}: "
                f"{', '.join(columns)})")
    return (f"{path}:1: header: not a poundbench result file (a summary of `poundbench workprecision` or "
            "`poundbench stress`, or the rows of `poundbench spectrum`)")


def kind_of(header):
    for kind in ("workprecision", "stress", "spectrum"):
        if all(c in header for c in KINDS[kind]["columns"]):
            return kind
    return None


def check_value(where, column, text, domain):
    """InputError unless `text` (not empty) is in `domain` (DOMAINS)."""
    what, holds = DOMAINS[domain]
    try:
        x = float(text)
    except ValueError:
        x = None
    if x is None or math.isnan(x) or not holds(text, x):
        raise InputError(f"{where}: {column}: must be {what} (it is '{clip(text)}')")


# The fields of the `settings` column that the report reads, and what each must be.
SETTING_FIELDS = {"steps": "count", "theta": "number", "tol_scale": "number", "stiffness": "number",
                  "rtol": "number", "wh": "number", "h_s": "number", "k_contact": "number", "projection_tol": "number", "steps_per_sample": "count",
                  "contact_steps": "count"}
SETTING_TEXTS = ("contact", "integrator", "method", "lcp")


def settings_problem(text):
    """Why a `settings` field is not a JSON object of the named values the report reads, or
    None (an empty field is no settings)."""
    try:
        fields = json.loads(text or "{}", parse_constant=lambda c: float("nan"))
    except (ValueError, RecursionError) as e:
        return f"not a JSON object ({clip(str(e), 60)})"
    if not isinstance(fields, dict):
        return "not a JSON object"
    for name, domain in SETTING_FIELDS.items():
        value = fields.get(name)
        if value is None:
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or \
                (domain == "count" and (value < 1 or value != int(value))):
            return f"{name}: must be {'a whole number >= 1' if domain == 'count' else 'a finite number'} " \
                   f"(it is {clip(json.dumps(value))})"
    for name in SETTING_TEXTS:
        if name in fields and not isinstance(fields[name], str):
            return f"{name}: must be a string (it is {clip(json.dumps(fields[name]))})"
    return None


def check_rows(path, rows, lines, kind):
    """Every column the report reads as a number in its domain on every row (KINDS), every
    count no more than the count it is part of, every `settings` a JSON object."""
    spec = KINDS[kind]
    present = [c for c in spec["domains"] if c in rows[0]] if rows else []
    settings_seen = {}
    for r, line in zip(rows, lines):
        where = f"{path}:{line}"
        if None in r or any(v is None for v in r.values()):
            raise InputError(f"{where}: the row has {'more' if None in r else 'fewer'} fields than the header")
        for c in present:
            if r[c] != "" or c in spec["required"]:
                check_value(where, c, r[c], spec["domains"][c])
        for part, whole in spec["at_most"]:
            if r.get(part) and r.get(whole) and int(r[part]) > int(r[whole]):
                raise InputError(f"{where}: {part}: must be at most {whole} ({r[whole]}) (it is '{r[part]}')")
        text = r["settings"]
        if text not in settings_seen:
            settings_seen[text] = settings_problem(text)
        if settings_seen[text]:
            raise InputError(f"{where}: settings: {settings_seen[text]}")


def setting_key(r):
    return (r["family"], r["solver"], r["variant"], r["settings"])


class Study:
    """One study: `kind` ('workprecision', 'stress' or 'spectrum'), its rows, and the per-run
    rows of its points (empty without --points)."""

    def __init__(self, path, points_path=None):
        self.path, self.points_path = path, points_path
        self.rows, header, lines = read_csv(path)
        self.kind = kind_of(header)
        if self.kind is None:
            raise InputError(header_problem(path, header))
        if not self.rows:
            raise InputError(f"{path}: no rows after the header")
        check_rows(path, self.rows, lines, self.kind)
        self.lines = lines
        self.points = []
        if points_path:
            if self.kind == "spectrum":
                raise InputError(f"--points: {points_path}: a spectrum's rows are its points already")
            self.points, points_header, point_lines = read_csv(points_path)
            if kind_of(points_header) != "spectrum":
                raise InputError(header_problem(points_path, points_header, ["spectrum"]))
            check_rows(points_path, self.points, point_lines, "spectrum")
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
        for line, r in zip(self.lines, self.rows):
            if setting_key(r) not in have:
                raise InputError(f"{self.points_path}: no runs of {self.path}:{line}'s family {clip(r['family'])} and "
                                 f"setting {clip(r['solver'])} {clip(r['variant'])} {clip(r['settings'], 80)}: not the "
                                 "points of this study")

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
    (rows' impact_velocity_pi, rows/result_fields.cpp) over the same points, vel_median and
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
    rows, _, _ = read_csv(path)
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
