"""What every part of the report reads off poundbench's CSV rows: loading them, their
numbers and settings, the label of a solver configuration, and saving a figure."""

import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
# Reproducible SVGs, so that regenerating a committed report changes a file only when its
# data changed: fixed element ids, and the creation date of reproducible builds.
matplotlib.rcParams["svg.hashsalt"] = "poundbench"
os.environ.setdefault("SOURCE_DATE_EPOCH", "0")
import matplotlib.pyplot as plt  # noqa: E402


def load(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows.extend(csv.DictReader(f))
    if not rows:
        sys.exit("make_report.py: no result rows in " + ", ".join(paths))
    return rows


def num(row, key):
    """A column as a float; an empty field (a value that does not exist) is NaN."""
    value = row.get(key, "")
    return float(value) if value not in ("", None) else float("nan")


def settings_fields(row):
    """The `settings` column (a JSON object of the solver's named values) as a dict."""
    return json.loads(row["settings"] or "{}")


def steps_of(row):
    """The run's step count N, or None for a run whose step is set another way (wh) or has none."""
    steps = settings_fields(row).get("steps")
    return None if steps is None else int(steps)


def config_label(row):
    """A solver configuration without its step: one line of a work-precision diagram or a
    stability plot. The full settings of each are in the CSV and the solvers' READMEs."""
    fields = settings_fields(row)
    label = row["solver"]
    if row.get("variant"):
        label += " " + row["variant"]
    if "theta" in fields:  # moreau-jean, and siconos' Moreau-Jean variants
        label += f" theta={fields['theta']}"
    if "tol_scale" in fields:  # the reference, and siconos' event-driven variant
        label += f" tol_scale={fields['tol_scale']}"
    return label


def save(fig, out_dir, stem):
    """Writes figures/STEM.png and .svg under out_dir; returns the PNG's path relative to it."""
    path = os.path.join(out_dir, "figures", stem)
    for ext in ("png", "svg"):
        fig.savefig(f"{path}.{ext}", dpi=100)
    plt.close(fig)
    return f"figures/{stem}.png"


def write_page(out_dir, lines, script):
    """Writes out_dir/README.md through a temporary file, so a failed run leaves the old one."""
    path = os.path.join(out_dir, "README.md")
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(path + ".tmp", path)
    print(f"{script}: wrote {path}")
