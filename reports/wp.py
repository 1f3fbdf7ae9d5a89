"""The work-precision part of the report: the diagrams (relative Pi1 error against CPU time
per run, a figure per family and solver family, the Pareto front over every solver) and the
spectra at one step count against the reference, split the same way, so that no figure holds
more lines than can be told apart at the size it is shown. Reads what `poundbench
workprecision` writes: the summary (--out) and the per-run rows (--points)."""

import math
from collections import defaultdict

from matplotlib.lines import Line2D

from answer import MIDDLE_N, has_spread
from figure import MARKERS, colors, figure_width, legend_below, log_spans, save, with_legend_below
from rows import config_label, num, sound, steps_of

ERROR_FLOOR = 1e-13  # errors below this are round-off: drawn in a band under it, one row per setting
FLOOR_ROW = 10 ** -0.6  # the factor between two rows of that band
STYLE = {"moreau-jean": "-", "ode": "--", "bullet": ":", "siconos": "-.", "mujoco": (0, (5, 1, 1, 1)),
         "compliant": (0, (3, 1)), "event-driven": "-", "dart": (0, (1, 1)), "simbody": (0, (5, 2))}
# The panels of a diagram: one per solver family, the in-house stepper with the reference;
# Siconos in two, its Moreau–Jean integrators apart from its other ones, so that no panel
# carries more lines than can be told apart.
PANELS = {"moreau-jean": "in-house: Moreau–Jean, reference",
          "event-driven": "in-house: Moreau–Jean, reference",
          "ode": "ODE (libode)", "bullet": "Bullet (libbullet, single precision)",
          "siconos": "Siconos: Moreau–Jean and its projections",
          "siconos-other": "Siconos: its other integrators",
          "mujoco": "MuJoCo (libmujoco, soft contacts)",
          "dart": "DART (libdart)", "simbody": "Simbody (libsimbody; hunt-crossley: compliant)",
          "compliant": "Compliant contact elements (CVODE, Newmark) and their models' own references"}
SICONOS_MOREAU_JEAN = ("moreau-jean-lemke", "moreau-jean-enum", "combined-projection", "direct-projection")


def panel_of(row):
    """The panel of a row's configuration (PANELS)."""
    if row["solver"] == "siconos" and row["variant"] not in SICONOS_MOREAU_JEAN:
        return PANELS["siconos-other"]
    if row["solver"] == "event-driven" and "contact" in row["settings"]:  # a compliant model, solved exactly
        return PANELS["compliant"]
    return PANELS.get(row["solver"], row["solver"])


ERRORS = (("err_median", "median"), ("err_p95", "95th percentile"))


def pareto_front(rows, key):
    """The rows no other row beats in both cost and error (errors under the floor count as
    the floor), in order of cost; settings with failed or unresolved runs are not candidates."""
    candidates = sorted((r for r in rows if sound(r) and math.isfinite(num(r, key))),
                        key=lambda r: num(r, "cpu_median_s"))
    front = []
    for r in candidates:
        if not front or max(num(r, key), ERROR_FLOOR) < max(num(front[-1], key), ERROR_FLOOR):
            front.append(r)
    return front


def _draw_setting(ax, lrows, key, style, floor_y):
    """One configuration's line over its step counts; points under the floor in its own row
    of the floor band; hollow markers where some runs failed or did not resolve; the low-high of the timing
    repetitions as horizontal bars where the rows have it."""
    above = [r for r in lrows if num(r, key) >= ERROR_FLOOR]
    ax.plot([1e6 * num(r, "cpu_median_s") for r in above], [num(r, key) for r in above], ls=style["ls"],
            color=style["color"], lw=1.3, zorder=3)
    for r in lrows:
        x = 1e6 * num(r, "cpu_median_s")
        y = num(r, key) if num(r, key) >= ERROR_FLOOR else floor_y
        hollow = not sound(r)
        ax.plot([x], [y], marker=style["marker"], ms=4.5, color=style["color"], zorder=4,
                markerfacecolor="white" if hollow else style["color"])
        if has_spread(r):
            lo, hi = 1e6 * num(r, "cpu_median_low_s"), 1e6 * num(r, "cpu_median_high_s")
            ax.errorbar([x], [y], xerr=[[x - lo], [hi - x]], fmt="none", ecolor=style["color"], elinewidth=0.9,
                        capsize=2, zorder=4)


SLUGS = {PANELS["moreau-jean"]: "in-house", PANELS["ode"]: "ode", PANELS["bullet"]: "bullet",
         PANELS["siconos"]: "siconos-moreau-jean", PANELS["siconos-other"]: "siconos-other",
         PANELS["mujoco"]: "mujoco", PANELS["compliant"]: "compliant"}


def slug(panel):
    """A panel as a file name's part ("in-house"); another solver's panel (its name) as itself."""
    return SLUGS.get(panel) or "".join(c if c.isalnum() else "-" for c in panel.lower()).strip("-") or "other"


def panels_of(rows):
    """The configurations of rows (config_label -> their rows, cheapest first), grouped by
    panel in PANELS' order (other solvers after, by name); configurations that failed on
    every point are left out (the report's table of failures names them)."""
    lines = defaultdict(list)
    for r in rows:
        lines[config_label(r)].append(r)
    for lrows in lines.values():
        lrows.sort(key=lambda r: num(r, "cpu_median_s"))
    panels = defaultdict(list)
    for label in sorted(lines):
        if all(int(r["failed"]) == int(r["points"]) for r in lines[label]):
            continue
        panels[panel_of(lines[label][0])].append(label)
    return lines, dict(sorted(panels.items(), key=lambda p: panel_rank(p[0])))


def panel_rank(panel):
    """Where a panel comes: PANELS' order, another solver's after them by name."""
    order = list(dict.fromkeys(PANELS.values()))
    return (order.index(panel) if panel in order else len(order), panel)



def cost_label(rows):
    """The cost axis: CPU time, or the solver's own time for a setting whose runs report it
    (the table's cost column, studies/stats.hpp: an external program's solve_seconds, a Python
    callable timed around its call)."""
    own = {r.get("cost") for r in rows} - {None, "", "cpu_seconds"}
    return "CPU time per run (us)" if not own else "cost per run (us): CPU time; a solver's own solve time where it reports one"

def wp_diagram(family, panel, labels, lines, rows, out_dir):
    """One family's diagram for one panel's configurations: the median and the 95th percentile
    of the error side by side, the other solvers in grey and the Pareto front over every solver
    behind them, the legend below at the size of the text."""
    # The floor band: a row per configuration of the panel with a point under the floor; the
    # Pareto front's points there of other panels' configurations on its first row.
    under = [lb for lb in labels if any(num(r, k) < ERROR_FLOOR for r in lines[lb] for k, _ in ERRORS)]
    floor_rows = {lb: ERROR_FLOOR * FLOOR_ROW ** (i + 1) for i, lb in enumerate(under)}
    band = any(num(r, k) < ERROR_FLOOR for r in rows for k, _ in ERRORS)
    deepest = min(floor_rows.values(), default=ERROR_FLOOR * FLOOR_ROW)
    spread = any(has_spread(r) for r in rows)
    hollow = any(not sound(r) for r in rows)
    palette = colors(len(labels))
    styles = {lb: dict(color=palette[i], marker=MARKERS[i % len(MARKERS)], ls=STYLE.get(lines[lb][0]["solver"], "-"))
              for i, lb in enumerate(labels)}

    entries = len(labels) + 2 + hollow + spread
    fig, grid = with_legend_below(figure_width(2), 3.8, entries)
    axes = fig.subplots(1, 2, sharex=True, sharey=True, gridspec_kw=grid)
    for col, (key, title) in enumerate(ERRORS):
        ax = axes[col]
        for label, lrows in lines.items():  # the other solvers, for context
            if label not in labels:
                ok = [r for r in lrows if num(r, key) >= ERROR_FLOOR]
                ax.plot([1e6 * num(r, "cpu_median_s") for r in ok], [num(r, key) for r in ok], color="0.85",
                        lw=0.8, zorder=1)
        front = pareto_front(rows, key)
        ax.plot([1e6 * num(r, "cpu_median_s") for r in front],
                [num(r, key) if num(r, key) >= ERROR_FLOOR else floor_rows.get(config_label(r), ERROR_FLOOR * FLOOR_ROW)
                 for r in front],
                color="k", lw=7, alpha=0.12, solid_capstyle="round", zorder=2)
        for label in labels:
            _draw_setting(ax, [r for r in lines[label] if math.isfinite(num(r, key))], key, styles[label],
                          floor_rows.get(label, ERROR_FLOOR))
        if band:
            ax.axhspan(deepest * FLOOR_ROW ** 1.2, ERROR_FLOOR, color="0.93", zorder=0)
            ax.text(0.02, 0.02, f"below {ERROR_FLOOR:g}: round-off", transform=ax.transAxes, color="0.35")
        ax.set_ylim(deepest * FLOOR_ROW ** 1.2 if band else None, 3)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="major", alpha=0.3)
        ax.set_title(f"{title} over the points")
        ax.set_xlabel(cost_label(rows))
    axes[0].set_ylabel("relative Pi1 error")
    handles = [Line2D([], [], ls=styles[lb]["ls"], marker=styles[lb]["marker"], color=styles[lb]["color"], ms=5,
                      label=lb) for lb in labels]
    handles += [Line2D([], [], color="k", lw=7, alpha=0.12, label="Pareto front, every solver"),
                Line2D([], [], color="0.85", lw=0.8, label="the other solvers")]
    if hollow:
        handles.append(Line2D([], [], ls="", marker="o", color="0.3", markerfacecolor="white",
                              label="hollow: some runs failed or did not resolve"))
    if spread:
        handles.append(Line2D([], [], ls="-", marker="|", color="0.3", label="bar: low–high of the repetitions"))
    legend_below(fig, handles)
    fig.suptitle(f"{family}: {panel}")
    return save(fig, out_dir, f"wp-{family}-{slug(panel)}", vector=False)


def wp_diagrams(summary, out_dir):
    """Every family's diagrams: [(family, [(panel, figure path)])]."""
    out = []
    for family in dict.fromkeys(r["family"] for r in summary):
        rows = [r for r in summary if r["family"] == family]
        lines, panels = panels_of(rows)
        out.append((family, [(panel, wp_diagram(family, panel, labels, lines, rows, out_dir))
                             for panel, labels in panels.items()]))
    return out


def spectra_steps(points):
    """The step count N at which spectra are compared: MIDDLE_N where the study has it, else
    the study's step count nearest to it (geometrically); None without stepped runs."""
    steps = {n for n in (steps_of(r) for r in points) if n is not None}
    if not steps:
        return None
    return min(steps, key=lambda n: (abs(math.log(n / MIDDLE_N)), n))


def spectra_rows(points):
    """The rows a spectra figure draws, and its step count: every configuration at that N
    (those with no step, the reference's and CVODE's, at their one setting), the truth apart."""
    n = spectra_steps(points)
    truth = {}
    for r in points:
        truth.setdefault(r["point"], r)
    chosen = [r for r in points if truth[r["point"]] is not r and steps_of(r) in (None, n)]
    return n, truth, chosen


def spectrum_panels(rows):
    """The panels of a family's spectra: one per (pulse, Pi5), sine first."""
    return sorted({(r["pulse"], r["pi5"]) for r in rows}, reverse=True)


def wp_spectrum(family, panel, labels, frows, truth, n, out_dir):
    """One family's spectra of one panel's configurations: Pi1 against Pi2 over the truth, a
    column per (pulse, Pi5), their relative error below; the legend below at text size."""
    panels = spectrum_panels(frows)
    palette = colors(len(labels))  # a colour per configuration: a panel's are mostly one solver's
    styles = {lb: dict(color=palette[i], ls=STYLE.get(next(r["solver"] for r in frows if config_label(r) == lb), "-"))
              for i, lb in enumerate(labels)}
    fig, grid = with_legend_below(figure_width(len(panels)), 5.6, len(labels) + 2, wspace=0.38, hspace=0.12)
    axes = fig.subplots(2, len(panels), squeeze=False, sharex=True, gridspec_kw=dict(grid, height_ratios=[3, 2]))
    for pi, (pulse, pi5) in enumerate(panels):
        prows = [r for r in frows if r["pulse"] == pulse and r["pi5"] == pi5]
        refs = sorted({r["point"]: truth[r["point"]] for r in prows}.values(), key=lambda r: num(r, "pi2"))
        refs = [r for r in refs if r["status"] == "ok"]
        top, bottom = axes[0][pi], axes[1][pi]
        x = [num(r, "pi2") for r in refs]
        top.plot(x, [num(r, "pi1_no_contact") for r in refs], color="0.6", lw=1, ls="--", label="no contact")
        top.plot(x, [num(r, "pi1") for r in refs], color="k", lw=2.4, label="reference (rigid, 100x tighter)")
        for label in labels:
            crow = sorted((r for r in prows if config_label(r) == label and r["status"] == "ok"),
                          key=lambda r: num(r, "pi2"))
            if not crow:
                continue
            style = dict(styles[label], marker=None, lw=1.3)
            top.plot([num(r, "pi2") for r in crow], [num(r, "pi1") for r in crow], label=label, **style)
            err = [max(abs(num(r, "pi1") - num(truth[r["point"]], "pi1")) / num(truth[r["point"]], "pi1"),
                       ERROR_FLOOR) for r in crow if num(truth[r["point"]], "pi1") > 0]
            bottom.plot([num(r, "pi2") for r in crow if num(truth[r["point"]], "pi1") > 0], err, **style)
        top.set_title(f"{pulse}" + (f", Pi5 = {pi5}" if pi5 else ""))
        if log_spans([num(r, "pi1") for r in refs]):
            top.set_yscale("log")
        bottom.set_xscale("log")
        bottom.set_yscale("log")
        bottom.set_xlabel(r"$\Pi_2 = \omega_0/\omega_p$")
        for ax in (top, bottom):
            ax.grid(True, which="both", alpha=0.25)
    axes[0][0].set_ylabel(r"$\Pi_1$")
    axes[1][0].set_ylabel(f"relative Pi1 error\n(below {ERROR_FLOOR:g}: at it)")
    handles, names = axes[0][0].get_legend_handles_labels()
    for ax in axes[0][1:]:  # a configuration missing from the first panel
        for h, name in zip(*ax.get_legend_handles_labels()):
            if name not in names:
                handles.append(h)
                names.append(name)
    legend_below(fig, handles, names)
    fig.suptitle(f"{family}: {panel}, at N = {n}" if n else f"{family}: {panel}")
    return save(fig, out_dir, f"wp-spectra-{family}-{slug(panel)}", vector=False)


def wp_spectra(points, out_dir):
    """Each family's spectra, a figure per panel of configurations: [(family, N, [(panel, path)])]."""
    n, truth, chosen = spectra_rows(points)
    out = []
    for family in dict.fromkeys(r["family"] for r in chosen):
        frows = [r for r in chosen if r["family"] == family]
        panels = defaultdict(list)
        for label in sorted({config_label(r) for r in frows}):
            if any(r["status"] == "ok" for r in frows if config_label(r) == label):
                panels[panel_of(next(r for r in frows if config_label(r) == label))].append(label)
        ordered = sorted(panels.items(), key=lambda p: panel_rank(p[0]))
        out.append((family, n, [(panel, wp_spectrum(family, panel, labels, frows, truth, n, out_dir))
                                for panel, labels in ordered]))
    return out
