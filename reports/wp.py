"""The work-precision part of the report: the diagrams (relative Pi1 error against CPU time
per run, a figure per family and solver family, the Pareto front over every solver) and the
spectra at one step count against the reference, split the same way, so that no figure holds
more lines than can be told apart at the size it is shown. Reads what `poundbench
workprecision` writes: the summary (--out) and the per-run rows (--points)."""

import math
from collections import defaultdict

from matplotlib.lines import Line2D

import styles as setting_style
from answer import MIDDLE_N, has_spread
from figure import (clipped, figure_width, joined, label_axes, legend_below, legend_columns, log_spans, reused_figure,
                    save, title_room, ylabel_beside)
from rows import by_family, config_label, external_name, num, settings_fields, sound, steps_of

ERROR_FLOOR = 1e-13  # errors below this are round-off: drawn in a band under it, one row per setting
FLOOR_ROW = 10 ** -0.6  # the factor between two rows of that band
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
    if row["solver"] == "external":  # a program or Python callable of the user's: a panel by its name
        return external_name(settings_fields(row))
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
    repetitions as horizontal bars where the rows have it. A few artists whatever the count of
    points: an artist per point made a configuration of 7,500 step counts 30,000 artists."""
    above = [r for r in lrows if num(r, key) >= ERROR_FLOOR]
    ax.plot([1e6 * num(r, "cpu_median_s") for r in above], [num(r, key) for r in above], ls=style["ls"],
            color=style["color"], lw=1.3, zorder=3)
    x = [1e6 * num(r, "cpu_median_s") for r in lrows]
    y = [num(r, key) if num(r, key) >= ERROR_FLOOR else floor_y for r in lrows]
    for hollow in (False, True):
        pick = [i for i, r in enumerate(lrows) if sound(r) != hollow]
        if pick:
            ax.plot([x[i] for i in pick], [y[i] for i in pick], ls="", marker=style["marker"], ms=4.5,
                    color=style["color"], zorder=4, markerfacecolor="white" if hollow else style["color"])
    bars = [i for i, r in enumerate(lrows) if has_spread(r)]
    if bars:
        lo = [x[i] - 1e6 * num(lrows[i], "cpu_median_low_s") for i in bars]
        hi = [1e6 * num(lrows[i], "cpu_median_high_s") - x[i] for i in bars]
        ax.errorbar([x[i] for i in bars], [y[i] for i in bars], xerr=[lo, hi], fmt="none", ecolor=style["color"],
                    elinewidth=0.9, capsize=2, zorder=4)


def diagram_line(lrows, key):
    """A configuration's line of a diagram, (CPU time in us, error `key`), over its settings
    with a finite error above the floor."""
    ok = [r for r in lrows if ERROR_FLOOR <= num(r, key) < math.inf]
    return [1e6 * num(r, "cpu_median_s") for r in ok], [num(r, key) for r in ok]


# A panel of more configurations than this draws them as a crowd: one colour, every line and
# point in three artists, no legend entry each; past 18 (figure.PAIRED) colours are shades of
# one map that nobody tells apart, and a legend of thousands of entries is taller than the
# figure. report.html names each setting on hover.
MAX_LINES = 18


def _draw_crowd(ax, labels, lines, key):
    """A panel's configurations as a crowd: their lines in one light artist, their settings
    as points (hollow where some runs failed or did not resolve), those under the floor on
    the band's first row."""
    ax.plot(*joined(diagram_line(lines[lb], key) for lb in labels), color="tab:blue", lw=0.6, alpha=0.35, zorder=3)
    rows = [r for lb in labels for r in lines[lb] if math.isfinite(num(r, key))]
    for hollow in (False, True):
        pick = [r for r in rows if sound(r) != hollow]
        if pick:
            ax.plot([1e6 * num(r, "cpu_median_s") for r in pick],
                    [num(r, key) if num(r, key) >= ERROR_FLOOR else ERROR_FLOOR * FLOOR_ROW for r in pick],
                    ls="", marker="o", ms=2.5, color="tab:blue", zorder=4,
                    markerfacecolor="white" if hollow else "tab:blue")


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


def setting_styles(rows):
    """Every configuration's line style (styles.py), the same in each figure and on the page:
    assigned in the order the legends list them (by panel, then by name)."""
    first = {}
    for r in rows:
        first.setdefault(config_label(r), r)
    return setting_style.assign(sorted(first, key=lambda lb: (panel_rank(panel_of(first[lb])), lb)))


def line_style(style):
    """A setting's style as matplotlib's keywords of a line."""
    return dict(color=style["color"], ls=setting_style.matplotlib_dash(style["dash"]), marker=style["marker"])


def panel_rank(panel):
    """Where a panel comes: PANELS' order, another solver's after them by name."""
    order = list(dict.fromkeys(PANELS.values()))
    return (order.index(panel) if panel in order else len(order), panel)



def cost_label(rows):
    """The cost axis, named by its clock: CPU time for every solver (the table's cost column,
    issue 48); a file of an earlier version whose rows costed a program's own solve time says so."""
    own = {r.get("cost") for r in rows} - {None, "", "cpu_seconds"}
    return ("CPU time per run (us)" if not own
            else "cost per run (us): CPU time; a solver's own solve time where it reported one (earlier version)")

def wp_diagram(family, panel, labels, lines, rows, out_dir, styles):
    """One family's diagram for one panel's configurations: the median and the 95th percentile
    of the error side by side, the other solvers in grey and the Pareto front over every solver
    behind them, the legend below at the size of the text. More than MAX_LINES configurations
    are drawn as a crowd (_draw_crowd)."""
    crowd = len(labels) > MAX_LINES
    # The floor band: a row per configuration of the panel with a point under the floor (a
    # crowd's on one row); the Pareto front's points there of other panels' configurations on its first row.
    under = [] if crowd else [lb for lb in labels if any(num(r, k) < ERROR_FLOOR for r in lines[lb] for k, _ in ERRORS)]
    floor_rows = {lb: ERROR_FLOOR * FLOOR_ROW ** (i + 1) for i, lb in enumerate(under)}
    band = any(num(r, k) < ERROR_FLOOR for r in rows for k, _ in ERRORS)
    deepest = min(floor_rows.values(), default=ERROR_FLOOR * FLOOR_ROW)
    spread = not crowd and any(has_spread(r) for r in rows)
    hollow = any(not sound(r) for r in rows)
    shown = {} if crowd else {lb: line_style(styles[lb]) for lb in labels}

    entries = (1 if crowd else len(labels)) + 2 + hollow + spread
    columns = 1 if crowd else 2  # a crowd's one entry is a sentence
    fig, axes, new = reused_figure("wp-diagram", figure_width(2), 3.8, entries, (1, 2), columns, sharex=True,
                                   sharey=True)
    axes = axes[0]
    mine = set(labels)
    for col, (key, title) in enumerate(ERRORS):
        ax = axes[col]
        if new:
            ax.set_xscale("log")  # before the limits: a shared axis already log refuses a linear autoscale's bottom <= 0
            ax.set_yscale("log")
            ax.grid(True, which="major", alpha=0.3)
        ax.plot(*joined(diagram_line(lrows, key) for label, lrows in lines.items() if label not in mine),
                color="0.85", lw=0.8, zorder=1)  # the other solvers, for context
        front = pareto_front(rows, key)
        ax.plot([1e6 * num(r, "cpu_median_s") for r in front],
                [num(r, key) if num(r, key) >= ERROR_FLOOR else floor_rows.get(config_label(r), ERROR_FLOOR * FLOOR_ROW)
                 for r in front],
                color="k", lw=7, alpha=0.12, solid_capstyle="round", zorder=2)
        if crowd:
            _draw_crowd(ax, labels, lines, key)
        for label, style in shown.items():
            _draw_setting(ax, [r for r in lines[label] if math.isfinite(num(r, key))], key, style,
                          floor_rows.get(label, ERROR_FLOOR))
        if band:
            ax.axhspan(deepest * FLOOR_ROW ** 1.2, ERROR_FLOOR, color="0.93", zorder=0)
            ax.text(0.02, 0.02, f"below {ERROR_FLOOR:g}: round-off", transform=ax.transAxes, color="0.35")
        ax.set_ylim(deepest * FLOOR_ROW ** 1.2 if band else None, 3)
        ax.set_title(f"{title} over the points")
    label_axes(fig, axes, axes[:1], cost_label(rows), "relative Pi1 error")
    handles = [Line2D([], [], ms=5, label=clipped(lb), **style) for lb, style in shown.items()]
    if crowd:
        handles.append(Line2D([], [], marker="o", ms=2.5, color="tab:blue", lw=0.6, label=(
            f"{len(labels)} configurations, too many to tell apart: each point a setting (report.html names it)")))
    handles += [Line2D([], [], color="k", lw=7, alpha=0.12, label="Pareto front, every solver"),
                Line2D([], [], color="0.85", lw=0.8, label="the other solvers")]
    if hollow:
        handles.append(Line2D([], [], ls="", marker="o", color="0.3", markerfacecolor="white",
                              label="hollow: some runs failed or did not resolve"))
    if spread:
        handles.append(Line2D([], [], ls="-", marker="|", color="0.3", label="bar: low–high of the repetitions"))
    legend_below(fig, handles, columns=columns)
    fig.suptitle(clipped(f"{family}: {panel}", title_room(fig)))
    return save(fig, out_dir, f"wp-{family}-{slug(panel)}", vector=False)


def wp_diagrams(summary, out_dir, families=None, styles=None):
    """Every family's diagrams (of `families`, where given): [(family, [(panel, figure path)])].
    `styles`: each configuration's (setting_styles; by default, of the summary)."""
    styles = styles or setting_styles(summary)
    out = []
    for family, rows in by_family(summary).items():
        if families is not None and family not in families:
            continue
        lines, panels = panels_of(rows)
        out.append((family, [(panel, wp_diagram(family, panel, labels, lines, rows, out_dir, styles))
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


# A figure of spectra has a column per (pulse, Pi5) up to this many: a study's have two to four,
# and past eight a column is too narrow to read at the page's width.
MAX_PANELS = 8


def spectrum_panels(rows):
    """The panels of a family's spectra: one per (pulse, Pi5), sine first."""
    return sorted({(r["pulse"], r.get("pi5", "")) for r in rows}, reverse=True)


def spectrum_curve(crow, truth):
    """A configuration's finished runs of one panel, by Pi2: its Pi1, and its relative error
    against the truth where the truth's Pi1 is positive (at least ERROR_FLOOR)."""
    crow = sorted((r for r in crow if r["status"] == "ok"), key=lambda r: num(r, "pi2"))
    exact = [num(truth[r["point"]], "pi1") for r in crow]
    pi1 = ([num(r, "pi2") for r in crow], [num(r, "pi1") for r in crow])
    err = ([num(r, "pi2") for r, e in zip(crow, exact) if e > 0],
           [max(abs(num(r, "pi1") - e) / e, ERROR_FLOOR) for r, e in zip(crow, exact) if e > 0])
    return pi1, err


def wp_spectrum(family, panel, labels, by_label, truth, n, out_dir, styles):
    """One family's spectra of one panel's configurations (by_label: each one's rows): Pi1
    against Pi2 over the truth, a column per (pulse, Pi5), their relative error below; the
    legend below at text size. More than MAX_LINES configurations are drawn as a crowd, in one
    colour, without a legend entry each."""
    frows = [r for lb in labels for r in by_label[lb]]
    panels = spectrum_panels(frows)
    shown = panels[:MAX_PANELS]
    crowd = len(labels) > MAX_LINES
    lined = {} if crowd else {lb: dict(line_style(styles[lb]), lw=1.3, ms=3.5) for lb in labels}
    width = figure_width(len(shown))
    columns = legend_columns(width, crowd)
    fig, axes, new = reused_figure(("wp-spectrum", len(shown)), width, 5.6, (1 if crowd else len(labels)) + 2,
                                   (2, len(shown)), columns, wspace=0.38, hspace=0.12, sharex=True,
                                   gridspec_kw=dict(height_ratios=[3, 2]))
    for pi, (pulse, pi5) in enumerate(shown):
        mine = defaultdict(list)
        for r in frows:
            if r["pulse"] == pulse and r.get("pi5", "") == pi5:
                mine[config_label(r)].append(r)
        refs = sorted({r["point"]: truth[r["point"]] for rows in mine.values() for r in rows}.values(),
                      key=lambda r: num(r, "pi2"))
        refs = [r for r in refs if r["status"] == "ok"]
        top, bottom = axes[0][pi], axes[1][pi]
        if new:
            bottom.set_xscale("log")
            bottom.set_yscale("log")
            for ax in (top, bottom):
                ax.grid(True, which="major", alpha=0.25)
        x = [num(r, "pi2") for r in refs]
        top.plot(x, [num(r, "pi1_no_contact") for r in refs], color="0.6", lw=1, ls="--", label="no contact")
        top.plot(x, [num(r, "pi1") for r in refs], color="k", lw=2.4, label="reference (rigid, 100x tighter)")
        curves = {label: spectrum_curve(mine[label], truth) for label in labels if mine.get(label)}
        if crowd:
            for ax, part in ((top, 0), (bottom, 1)):
                ax.plot(*joined(c[part] for c in curves.values()), color="tab:blue", lw=0.6, alpha=0.35,
                        label=f"{len(labels)} configurations, too many to tell apart (report.html names each)")
        for label, (pi1, err) in curves.items():
            if label in lined and pi1[0]:
                top.plot(*pi1, label=clipped(label), **lined[label])
                bottom.plot(*err, **lined[label])
        top.set_title(clipped(f"{pulse}" + (f", Pi5 = {pi5}" if pi5 else ""), 40))
        top.set_yscale("log" if log_spans([num(r, "pi1") for r in refs]) else "linear")
    label_axes(fig, axes[1], [axes[0][0]], "Π₂ = ω₀/ωₚ", "Π₁")
    ylabel_beside(fig, [axes[1][0]], f"relative Pi1 error\n(below {ERROR_FLOOR:g}: at it)")
    handles, names = axes[0][0].get_legend_handles_labels()
    for ax in axes[0][1:]:  # a configuration missing from the first panel
        for h, name in zip(*ax.get_legend_handles_labels()):
            if name not in names:
                handles.append(h)
                names.append(name)
    legend_below(fig, handles, names, columns=columns)
    title = f"{clipped(family)}: {panel}" + (f", at N = {n}" if n else "")
    if len(panels) > len(shown):
        title += f" (the first {len(shown)} of {len(panels)} pulse and Pi5 panels)"
    fig.suptitle(clipped(title, title_room(fig)))
    return save(fig, out_dir, f"wp-spectra-{family}-{slug(panel)}", vector=False)


def wp_spectra(points, out_dir, families=None, styles=None):
    """Each family's spectra (of `families`, where given), a figure per panel of
    configurations: [(family, N, [(panel, path)])]. `styles`: each configuration's
    (setting_styles; by default, of the points)."""
    n, truth, chosen = spectra_rows(points)
    styles = styles or setting_styles(chosen)
    out = []
    for family, frows in by_family(chosen).items():
        if families is not None and family not in families:
            continue
        by_label = defaultdict(list)
        for r in frows:
            by_label[config_label(r)].append(r)
        panels = defaultdict(list)
        for label in sorted(by_label):
            if any(r["status"] == "ok" for r in by_label[label]):
                panels[panel_of(by_label[label][0])].append(label)
        ordered = sorted(panels.items(), key=lambda p: panel_rank(p[0]))
        out.append((family, n, [(panel, wp_spectrum(family, panel, labels, by_label, truth, n, out_dir, styles))
                                for panel, labels in ordered]))
    return out
