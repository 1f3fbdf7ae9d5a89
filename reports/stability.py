"""The stability part of the report: where each solver breaks on the stress case set.

Reads what `poundbench stress` writes: the per-run rows (--points; the spectrum columns
plus pi1_error) and the summary with the pass/fail checks (--out). Used by make_report.py.
"""

import os
import re
from collections import defaultdict

import matplotlib.pyplot as plt

from rows import config_label as config, num, save, settings_fields

FLOOR = 1e-17  # energy excesses and penetrations at or below this are drawn on the floor


def tolerances():
    """The checks' tolerances, read from where the code states them (studies/stress.hpp)."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studies", "stress.hpp")
    with open(header) as f:
        found = dict(re.findall(r"inline constexpr double (k\w+) = ([^;]+);", f.read()))
    return {name: float(value) for name, value in found.items()}


def step_label(row):
    fields = settings_fields(row)
    if "wh" in fields:
        return f"w_max h = {fields['wh']}"
    if "steps" in fields:
        return f"N = {fields['steps']}"
    return ""


def large_step_figure(points, out_dir):
    """Over the runs given with a w_max h: the share that finished, the worst energy excess
    and the worst penetration, against w_max h, one line per solver configuration."""
    runs = [r for r in points if r["solver"] != "event-driven" and "wh" in settings_fields(r)]
    if not runs:
        return None
    by_config = defaultdict(lambda: defaultdict(list))
    for r in runs:
        by_config[config(r)][float(settings_fields(r)["wh"])].append(r)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    colors = plt.get_cmap("tab20").colors
    for i, (label, per_wh) in enumerate(sorted(by_config.items())):
        whs = sorted(per_wh)
        ok = [[r for r in per_wh[w] if r["status"] == "ok"] for w in whs]
        share = [len(o) / len(per_wh[w]) for o, w in zip(ok, whs)]
        style = dict(color=colors[i % 20], marker="o", ms=4, lw=1.3, label=label)
        axes[0].plot(whs, share, **style)
        for ax, key in ((axes[1], "energy_excess"), (axes[2], "penetration")):
            xs, ys = [], []
            for w, o in zip(whs, ok):
                values = [num(r, key) for r in o if num(r, key) == num(r, key)]
                if values:
                    xs.append(w)
                    ys.append(max(max(values), FLOOR))
            ax.plot(xs, ys, **style)
    axes[0].set_ylabel("share of runs that finished (status ok)")
    axes[0].set_ylim(-0.05, 1.05)
    axes[1].set_ylabel("worst energy excess (over the energy scale)")
    axes[2].set_ylabel("worst penetration (over delta, or a_p/w_p^2 at Pi3 = 0)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel(r"$\omega_{\max} h$")
        ax.grid(True, which="both", alpha=0.25)
    for ax in axes[1:]:
        ax.set_yscale("log")
    axes[0].legend(fontsize=7, loc="lower left")
    fig.suptitle(f"Large steps: every stress case at each w_max h (energy and penetration over the finished runs; "
                 f"values <= {FLOOR:g} drawn at {FLOOR:g})", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    return save(fig, out_dir, "stability-large-steps")


def chain_cost_figure(points, out_dir, wh=0.5):
    """Median CPU time per run and per step against the chain's body count N: the reference,
    and every time-stepper configuration at one w_max h."""
    runs = [r for r in points if r["scene"] == "chain" and r["status"] == "ok" and r.get("bodies")
            and (r["solver"] == "event-driven" or float(settings_fields(r).get("wh", "nan")) == wh)]
    if not runs:
        return None
    by_config = defaultdict(lambda: defaultdict(list))
    for r in runs:
        by_config[config(r)][int(r["bodies"])].append(r)

    def median(values):
        values = sorted(values)
        return values[len(values) // 2]

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    colors = plt.get_cmap("tab20").colors
    for i, (label, per_n) in enumerate(sorted(by_config.items())):
        ns = sorted(per_n)
        style = dict(color=colors[i % 20], marker="o", ms=4, lw=1.3, label=label)
        axes[0].plot(ns, [1e6 * median([num(r, "cpu_seconds") for r in per_n[n]]) for n in ns], **style)
        if not label.startswith("event-driven"):
            axes[1].plot(ns, [1e9 * median([num(r, "cpu_seconds") / max(num(r, "steps"), 1) for r in per_n[n]])
                              for n in ns], **style)
    axes[0].set_ylabel("CPU time per run, median (us)")
    axes[1].set_ylabel("CPU time per step, median (ns)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("bodies in the chain, N")
        ax.grid(True, which="both", alpha=0.25)
    axes[0].legend(fontsize=7, loc="upper left")
    fig.suptitle(f"Chain: cost against the number of bodies (finished runs of the stress set's chain families; "
                 f"time-steppers at w_max h = {wh:g})", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    return save(fig, out_dir, "stability-chain-cost")

CHECKS = ("finite", "energy", "gap", "restitution")


def table_config(row):
    """A solver setting as the stability table names it: config plus its step."""
    step = step_label(row)
    return config(row) + (f", {step}" if step else "")


def failure_note(row):
    """What failed in one (family, setting), with the worst number of each failed check."""
    notes = []
    if row["finite"] == "fail":
        notes.append(f"finite {row['ok']}/{row['runs']}")
    if row["energy"] == "fail":
        notes.append(f"energy {num(row, 'energy_excess_max'):.1e}")
    if row["gap"] == "fail":
        steps = num(row, "penetration_steps_max")
        notes.append(f"gap {steps:.2g} steps" if steps == steps else f"gap {num(row, 'penetration_max'):.1e}")
    if row["restitution"] == "fail":
        notes.append(f"e {num(row, 'restitution_error_max'):.1e}")
    return ", ".join(notes)


def stability_table(summary):
    """Markdown: one line per solver setting, one column per stress family; a cell is `pass`
    or the checks that failed with their worst values (`-` where no check could judge)."""
    families = list(dict.fromkeys(r["family"] for r in summary))
    cells = defaultdict(dict)
    for r in summary:
        cells[table_config(r)][r["family"]] = r
    lines = ["| solver setting | " + " | ".join(families) + " |", "|---" * (len(families) + 1) + "|"]
    for label, per_family in cells.items():
        row = []
        for family in families:
            r = per_family.get(family)
            if r is None:
                row.append("")
            elif all(r[k] != "fail" for k in CHECKS):
                row.append("pass" if any(r[k] == "pass" for k in CHECKS) else "-")
            else:
                row.append("**fail**: " + failure_note(r))
        lines.append(f"| {label} | " + " | ".join(row) + " |")
    return lines


def stability_summary(summary):
    """One line per solver configuration: for each check, the steps at which it fails on
    some family, with the worst value there (read off the same rows as the table)."""
    worst_key = {"energy": "energy_excess_max", "gap": "penetration_steps_max",
                 "restitution": "restitution_error_max"}
    by_config = defaultdict(list)
    for r in summary:
        by_config[config(r)].append(r)
    lines = []
    for label, rows in by_config.items():
        parts = []
        for check in CHECKS:
            failing = [r for r in rows if r[check] == "fail"]
            if not failing:
                judged = any(r[check] == "pass" for r in rows)
                parts.append(f"{check} passes everywhere" if judged else f"{check} not measured")
                continue
            steps = sorted({settings_fields(r).get("wh", 0) for r in failing})
            where = "at every step" if len(steps) == len({settings_fields(r).get("wh", 0) for r in rows}) \
                else "at w_max h = " + ", ".join(f"{w:g}" for w in steps)
            if check == "finite":
                lost = sum(int(r["runs"]) - int(r["ok"]) for r in failing)
                parts.append(f"**{check} fails** {where} ({lost} runs did not finish)")
            else:
                worst = max(num(r, worst_key[check]) for r in failing)
                parts.append(f"**{check} fails** {where} (worst {worst:.2g})")
        lines.append(f"* `{label}`: " + "; ".join(parts) + ".")
    return lines
