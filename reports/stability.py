"""The stability part of the report: where each solver breaks on the stress case set.

Reads what `poundbench stress` writes: the per-run rows (--points; the spectrum columns
plus pi1_error) and the summary with the pass/fail checks (--out). Used by make_report.py.
"""

import os
import re
from collections import defaultdict

import numpy as np
from matplotlib.colors import to_rgb

from figure import PAGE_WIDTH, clipped, figure_width, legend_below, plt, save, solver_styles, with_legend_below
from rows import config_label as config, median, num, settings_fields

FLOOR = 1e-17  # energy excesses and penetrations at or below this are drawn on the floor


def tolerances():
    """The checks' tolerances, read from where the code states them (studies/stress.hpp, which
    `cmake --install` puts beside the installed reports/ too); {} where it is not found."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studies", "stress.hpp")
    try:
        with open(header) as f:
            found = dict(re.findall(r"inline constexpr double (k\w+) = ([^;]+);", f.read()))
    except OSError:
        return {}
    return {name: float(value) for name, value in found.items()}


def step_label(row):
    fields = settings_fields(row)
    if "wh" in fields:
        return f"w_max h = {fields['wh']}"
    if "steps" in fields:
        return f"N = {fields['steps']}"
    return ""


def steps_sentence(summary):
    """Which w_max h each solver ran at, from the summary's settings: "moreau-jean at 0.5, 2,
    10 and 100; ode at 2, 10 and 100", solvers in the order they first appear."""
    by_solver = {}
    for r in summary:
        wh = settings_fields(r).get("wh")
        if wh is not None:
            by_solver.setdefault(r["solver"], set()).add(float(wh))

    def listed(values):
        text = [f"{v:g}" for v in sorted(values)]
        return text[0] if len(text) == 1 else ", ".join(text[:-1]) + " and " + text[-1]

    return "; ".join(f"{solver} at {listed(values)}" for solver, values in by_solver.items())


def large_step_figure(points, out_dir):
    """Over the runs given with a w_max h: the share that finished, the worst energy excess
    and the worst penetration, against w_max h, one line per solver configuration. The
    penetration is the gap check's: the overlap over one step of travel at the run's fastest
    gap rate (penetration_steps), one scale for every case (delta = 0 included)."""
    runs = [r for r in points if r["solver"] != "event-driven" and "wh" in settings_fields(r)]
    if not runs:
        return None
    by_config = defaultdict(lambda: defaultdict(list))
    for r in runs:
        by_config[config(r)][float(settings_fields(r)["wh"])].append(r)
    styles = solver_styles(runs)
    fig, grid = with_legend_below(figure_width(3, 3.0), 3.4, len(by_config), wspace=0.6)
    axes = fig.subplots(1, 3, sharex=True, gridspec_kw=grid)  # one step axis: a panel with finished runs alone
    for label, per_wh in sorted(by_config.items()):
        whs = sorted(per_wh)
        ok = [[r for r in per_wh[w] if r["status"] == "ok"] for w in whs]
        share = [len(o) / len(per_wh[w]) for o, w in zip(ok, whs)]
        style = dict(styles[label], ms=4.5, lw=1.3, label=label)
        axes[0].plot(whs, share, **style)
        for ax, key in ((axes[1], "energy_excess"), (axes[2], "penetration_steps")):
            xs, ys = [], []
            for w, o in zip(whs, ok):
                values = [num(r, key) for r in o if num(r, key) == num(r, key)]
                if values:
                    xs.append(w)
                    ys.append(max(max(values), FLOOR))
            ax.plot(xs, ys, **style)
    axes[0].set_ylabel("share of runs\nthat finished")
    axes[0].set_ylim(-0.05, 1.05)
    axes[1].set_ylabel("worst energy excess\n(over the energy scale)")
    axes[2].set_ylabel("worst penetration\n(over one step of travel, h max|g'|)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("ωₘₐₓ h")
        ax.grid(True, which="both", alpha=0.25)
    for ax in axes[1:]:
        ax.set_yscale("log")
    legend_below(fig, *axes[0].get_legend_handles_labels())
    fig.suptitle(f"Large steps: every stress case at each w_max h\n(energy and penetration: the finished runs; "
                 f"at most {FLOOR:g}: drawn at it)")
    return save(fig, out_dir, "stability-large-steps")


def chain_cost_figure(points, out_dir, wh=2.0):
    """Median CPU time per run and per step against the chain's body count N: the reference,
    and every time-stepper configuration at one w_max h (the stress study times its solves with
    the monitor on: docs/cli.md, "Timing")."""
    runs = [r for r in points if r["scene"] == "chain" and r["status"] == "ok" and r.get("bodies")
            and (r["solver"] == "event-driven" or float(settings_fields(r).get("wh", "nan")) == wh)]
    if not runs:
        return None
    by_config = defaultdict(lambda: defaultdict(list))
    for r in runs:
        by_config[config(r)][int(r["bodies"])].append(r)

    styles = solver_styles(runs)
    fig, grid = with_legend_below(figure_width(2), 3.6, len(by_config), wspace=0.25)
    axes = fig.subplots(1, 2, gridspec_kw=grid)
    for label, per_n in sorted(by_config.items()):
        ns = sorted(per_n)
        style = dict(styles[label], ms=4.5, lw=1.3, label=label)
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
    legend_below(fig, *axes[0].get_legend_handles_labels())
    fig.suptitle(f"Chain: cost against the number of bodies\n(finished runs of the chain families, time-steppers "
                 f"at w_max h = {wh:g}, their monitor on)")
    return save(fig, out_dir, "stability-chain-cost")

CHECKS = ("finite", "energy", "gap", "restitution", "accuracy")  # the verdict columns, where the CSV has them
# A cell of the verdict grid: its colour and its mark, so that it reads without colour too.
PASSED, FAILED, NOT_JUDGED = "#c7e9c0", "#cb181d", "#ffffff"


def checks_of(summary):
    return [c for c in CHECKS if c in summary[0]]


def table_config(row):
    """A solver setting as the stability figure names it: config plus its step."""
    step = step_label(row)
    return config(row) + (f", {step}" if step else "")


# The verdict grid's rows (settings) and columns (families) up to these many: a row is 0.19 in,
# so 150 are a figure 29 in tall, and matplotlib refuses an image past 2^16 pixels a side (a
# 100,000-setting stress summary asked for 2.4 million); a column is 0.45 in, the room for the
# five checks' letters, so 12 fill README's 830 px beside the settings' names. The page's table
# has them all.
MAX_VERDICT_SETTINGS, MAX_VERDICT_FAMILIES = 150, 12


def cell_mark(row, checks):
    """A cell's mark and colour: the letters of the checks that fail, on red; a tick where
    every check judged passes, on light green; blank where nothing was judged."""
    if row is None:
        return "", NOT_JUDGED
    failed = [c[0].upper() for c in checks if row[c] == "fail"]
    if failed:
        return "".join(failed), FAILED
    return ("\u2713", PASSED) if any(row[c] == "pass" for c in checks) else ("", NOT_JUDGED)


def short_setting(label, most=45):
    """A setting's name as the verdict grid's row shows it: its step as "ωh=10", and a name
    too long for the column cut in its middle, so that the step at its end still shows."""
    label = " ".join(label.splitlines()).replace("w_max h = ", "\u03c9h=")
    return label if len(label) <= most else label[:most - 12] + "\u2026" + label[-11:]


def verdict_figure(summary, out_dir):
    """The verdicts as a grid, README's width: a row per solver setting, a column per stress
    family; in each cell the letters of the checks that fail (red), a tick where every check
    judged passes (green), blank where nothing was judged. Returns the figure and how many
    settings and families it leaves out (the first MAX_VERDICT_* are drawn)."""
    checks = checks_of(summary)
    every_family = list(dict.fromkeys(r["family"] for r in summary))
    every_setting = list(dict.fromkeys(table_config(r) for r in summary))
    families, settings = every_family[:MAX_VERDICT_FAMILIES], every_setting[:MAX_VERDICT_SETTINGS]
    cells = {(table_config(r), r["family"]): r for r in summary}
    marks = [[cell_mark(cells.get((s, f)), checks) for f in families] for s in settings]
    image = np.array([[to_rgb(colour) for _, colour in row] for row in marks]).reshape(len(settings), len(families), 3)
    names, cell, right = 2.95, 0.37, 0.8  # inches: the settings' names, a family's column, the last name's tail
    width = min(names + cell * len(families) + right, PAGE_WIDTH)
    top, bottom = 1.45, 0.75  # the title and the families' names; the key
    height = top + 0.19 * len(settings) + bottom
    fig = plt.figure(figsize=(width, height))
    ax = fig.add_axes([names / width, bottom / height, cell * len(families) / width, 1 - (top + bottom) / height])
    ax.imshow(image, aspect="auto", interpolation="nearest")
    for i, row in enumerate(marks):
        for j, (mark, colour) in enumerate(row):
            if mark:
                failed = colour == FAILED
                ax.text(j, i, mark, ha="center", va="center", fontsize=7.5, color="white" if failed else "#00441b",
                        fontweight="bold" if failed else None)
    ax.set_yticks(range(len(settings)), [short_setting(x) for x in settings], fontsize=8)
    ax.xaxis.tick_top()
    ax.set_xticks(range(len(families)), [clipped(f, 20) for f in families], fontsize=8, rotation=50, ha="left",
                  rotation_mode="anchor")
    ax.tick_params(axis="both", length=0)
    solvers = [(s.split() or [""])[0] for s in settings]
    for i in range(1, len(settings)):  # a thin white line between two settings, a black one between two solvers
        other = solvers[i] != solvers[i - 1]
        ax.axhline(i - 0.5, color="k" if other else "white", lw=0.8 if other else 0.5)
    for j in range(1, len(families)):
        ax.axvline(j - 0.5, color="white", lw=1.5)
    for side in ax.spines.values():
        side.set_visible(False)
    fig.text(0.5, 1 - 0.12 / height, "Stress set: the verdicts per family (columns) and solver setting (rows)",
             ha="center", va="top")
    fig.text(0.01, 0.42 / height, "In a cell: the checks that fail, " + ", ".join(
        f"{c[0].upper()} {c}" for c in checks) + ";\n\u2713 every check judged passes; blank: nothing to judge; "
        "\u03c9h: the step as w_max h.",
        ha="left", va="center", fontsize=8.5)
    return save(fig, out_dir, "stability-verdicts"), (len(every_setting) - len(settings),
                                                      len(every_family) - len(families))


def stability_summary(summary):
    """One line per solver configuration: for each check, the steps at which it fails on
    some family, with the worst value there (read off the same rows as the table)."""
    worst_key = {"energy": "energy_excess_max", "gap": "penetration_steps_max",
                 "restitution": "restitution_error_max", "accuracy": "pi1_err_p95"}
    by_config = defaultdict(list)
    for r in summary:
        by_config[config(r)].append(r)
    lines = []
    for label, rows in by_config.items():
        parts = []
        for check in checks_of(summary):
            failing = [r for r in rows if r[check] == "fail"]
            if not failing:
                judged = any(r[check] == "pass" for r in rows)
                parts.append(f"{check} passes everywhere" if judged else f"{check} not measured")
                continue
            steps = sorted({settings_fields(r).get("wh", 0) for r in failing})
            every = len(steps) == len({settings_fields(r).get("wh", 0) for r in rows})
            where = "" if steps == [0] else " at every step" if every else \
                " at w_max h = " + ", ".join(f"{w:g}" for w in steps)
            if check == "finite":
                lost = sum(int(r["runs"]) - int(r["ok"]) for r in failing)
                parts.append(f"**{check} fails**{where} ({lost} run{'' if lost == 1 else 's'} did not finish)")
            else:
                worst = max(num(r, worst_key[check]) for r in failing)
                parts.append(f"**{check} fails**{where} (worst {worst:.2g})")
        code = " ".join(label.splitlines()).replace("`", "'")  # one line of markdown, one code span
        lines.append(f"* `{code}`: " + "; ".join(parts) + ".")
    return lines
