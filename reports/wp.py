"""The work-precision part of the report: the diagrams (relative Pi1 error against CPU time
per run, a panel per solver family, the Pareto front over every solver) and the spectra at
one step count against the reference. Reads what `poundbench workprecision` writes: the
summary (--out) and the per-run rows (--points). Used by make_report.py."""

import math
from collections import defaultdict

from matplotlib.lines import Line2D

from answer import MIDDLE_N, has_spread
from figure import MARKERS, colors, plt, save, solver_styles
from rows import config_label, num, settings_fields, sound, steps_of

ERROR_FLOOR = 1e-13  # errors below this are round-off: drawn in a band under it, one row per setting
FLOOR_ROW = 10 ** -0.6  # the factor between two rows of that band
STYLE = {"moreau-jean": "-", "ode": "--", "bullet": ":", "siconos": "-.", "mujoco": (0, (5, 1, 1, 1)),
         "compliant": (0, (3, 1)), "event-driven": "-"}
# The panels of a diagram: one per solver family, the in-house stepper with the reference;
# Siconos in two, its Moreau–Jean integrators apart from its other ones, so that no panel
# carries more lines than can be told apart.
PANELS = {"moreau-jean": "in-house: Moreau–Jean, reference",
          "event-driven": "in-house: Moreau–Jean, reference",
          "ode": "ODE (libode)", "bullet": "Bullet (libbullet, single precision)",
          "siconos": "Siconos: Moreau–Jean and its projections",
          "siconos-other": "Siconos: its other integrators",
          "mujoco": "MuJoCo (libmujoco, soft contacts)",
          "compliant": "Compliant contact elements (CVODE, Newmark) and their exact model"}
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


def wp_diagram(family, rows, out_dir):
    """One family's diagram: rows of panels per solver family, columns the median and the 95th
    percentile of the error; in every panel the other solvers in grey and the Pareto front."""
    lines = defaultdict(list)
    for r in rows:
        lines[config_label(r)].append(r)
    for lrows in lines.values():
        lrows.sort(key=lambda r: num(r, "cpu_median_s"))
    panels = defaultdict(list)
    for label in sorted(lines):
        if all(int(r["failed"]) == int(r["points"]) for r in lines[label]):
            continue  # nothing to draw: the report's table of failures names it
        panels[panel_of(lines[label][0])].append(label)
    panels = dict(sorted(panels.items(), key=lambda p: list(dict.fromkeys(PANELS.values())).index(p[0])
                         if p[0] in PANELS.values() else len(PANELS)))
    # the rows of the floor band: one per configuration of a panel that has a point under the floor
    floor_rows = {}
    for labels in panels.values():
        under = [lb for lb in labels if any(num(r, k) < ERROR_FLOOR for r in lines[lb] for k, _ in ERRORS)]
        floor_rows.update({lb: ERROR_FLOOR * FLOOR_ROW ** (i + 1) for i, lb in enumerate(under)})
    deepest = min(floor_rows.values(), default=ERROR_FLOOR)
    spread = any(has_spread(r) for r in rows)
    hollow = any(not sound(r) for r in rows)

    fig, axes = plt.subplots(len(panels), 2, figsize=(15, 3.5 * len(panels) + 1.2), sharex=True, sharey=True,
                             squeeze=False, layout="constrained")
    for row, (panel, labels) in enumerate(panels.items()):
        palette = colors(len(labels))
        styles = {lb: dict(color=palette[i], marker=MARKERS[i % len(MARKERS)],
                           ls=STYLE.get(lines[lb][0]["solver"], "-")) for i, lb in enumerate(labels)}
        for col, (key, title) in enumerate(ERRORS):
            ax = axes[row][col]
            for label, lrows in lines.items():  # the other solvers, for context
                if label not in labels:
                    ok = [r for r in lrows if num(r, key) >= ERROR_FLOOR]
                    ax.plot([1e6 * num(r, "cpu_median_s") for r in ok], [num(r, key) for r in ok], color="0.8",
                            lw=0.8, zorder=1)
            front = pareto_front(rows, key)
            ax.plot([1e6 * num(r, "cpu_median_s") for r in front],
                    [num(r, key) if num(r, key) >= ERROR_FLOOR else floor_rows[config_label(r)] for r in front],
                    color="k", lw=8, alpha=0.12, solid_capstyle="round", zorder=2)
            for label in labels:
                _draw_setting(ax, [r for r in lines[label] if math.isfinite(num(r, key))], key, styles[label],
                              floor_rows.get(label, ERROR_FLOOR))
            ax.axhspan(deepest * FLOOR_ROW ** 1.2, ERROR_FLOOR, color="0.93", zorder=0)
            ax.set_ylim(deepest * FLOOR_ROW ** 1.2, 3)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="major", alpha=0.3)
            if row == 0:
                ax.set_title(f"{title} of the relative Pi1 error over the points", fontsize=10)
            if row == len(panels) - 1:
                ax.set_xlabel("CPU time per run, median over the points (us)")
            if col == 0:
                ax.set_ylabel(f"{panel}\n" + r"$|\Pi_1 - \Pi_{1,\mathrm{ref}}| / \Pi_{1,\mathrm{ref}}$", fontsize=9)
                if floor_rows:
                    ax.text(0.01, 0.02, f"below {ERROR_FLOOR:g} (round-off): one row per setting",
                            transform=ax.transAxes, fontsize=7, color="0.35")
        handles = [Line2D([], [], ls=styles[lb]["ls"], marker=styles[lb]["marker"], color=styles[lb]["color"], ms=4.5,
                          label=lb) for lb in labels]
        handles += [Line2D([], [], color="k", lw=8, alpha=0.12, label="Pareto front, every solver"),
                    Line2D([], [], color="0.8", lw=0.8, label="the other solvers")]
        if hollow:
            handles.append(Line2D([], [], ls="", marker="o", color="0.3", markerfacecolor="white",
                                  label="hollow: some runs failed or did not resolve"))
        if spread:
            handles.append(Line2D([], [], ls="-", marker="|", color="0.3", label="bar: low–high of the repetitions"))
        axes[row][1].legend(handles=handles, loc="center left", bbox_to_anchor=(1.02, 0.5), fontsize=7.5,
                            frameon=False)
    fig.suptitle(f"{family}: work against precision (a line: one configuration over its step counts N = 8, 16, ...)",
                 fontsize=11)
    # PNG only: with every setting's line and spread the SVG was 24 000 lines and drawing it
    # took a quarter of the report's time (main.sh's report step, 47 s).
    return save(fig, out_dir, f"wp-{family}", vector=False)


def wp_diagrams(summary, out_dir):
    return [(family, wp_diagram(family, [r for r in summary if r["family"] == family], out_dir))
            for family in dict.fromkeys(r["family"] for r in summary)]


def wp_spectra(points, out_dir):
    """At N = MIDDLE_N: each solver's spectrum over the reference, and its error along Pi2."""
    reference = {}
    for r in points:
        if r["solver"] == "event-driven" and settings_fields(r)["tol_scale"] == 0.01:
            reference.setdefault(r["point"], r)
    figures = []
    for family in dict.fromkeys(r["family"] for r in points):
        frows = [r for r in points if r["family"] == family and steps_of(r) == MIDDLE_N]
        if not frows:
            continue
        panels = sorted({(r["pulse"], r["pi5"]) for r in frows}, reverse=True)
        styles = solver_styles(frows)
        fig, axes = plt.subplots(2, len(panels), figsize=(4.2 * len(panels) + 3.2, 7.6), squeeze=False, sharex=True,
                                 layout="constrained")
        for pi, (pulse, pi5) in enumerate(panels):
            prows = [r for r in frows if r["pulse"] == pulse and r["pi5"] == pi5]
            refs = sorted((reference[r["point"]] for r in prows if r["point"] in reference),
                          key=lambda r: num(r, "pi2"))
            refs = list({r["point"]: r for r in refs}.values())
            top, bottom = axes[0][pi], axes[1][pi]
            top.plot([num(r, "pi2") for r in refs], [num(r, "pi1_no_contact") for r in refs], color="0.6", lw=1,
                     ls="--", label="no contact")
            top.plot([num(r, "pi2") for r in refs], [num(r, "pi1") for r in refs], color="k", lw=2.2,
                     label="reference")
            by_config = defaultdict(list)
            for r in prows:
                by_config[config_label(r)].append(r)
            for label, crow in sorted(by_config.items()):
                crow.sort(key=lambda r: num(r, "pi2"))
                ok = [r for r in crow if r["status"] == "ok" and r["point"] in reference]
                x = [num(r, "pi2") for r in ok]
                style = dict(styles[label], marker=None, lw=1.2)
                top.plot(x, [num(r, "pi1") for r in ok], label=label, **style)
                err = [max(abs(num(r, "pi1") - num(reference[r["point"]], "pi1")) / num(reference[r["point"]], "pi1"),
                           ERROR_FLOOR) for r in ok]
                bottom.plot(x, err, **style)
            top.set_title(f"{pulse} pulse" + (f", Pi5 = {pi5}" if pi5 else ""), fontsize=10)
            bottom.set_xscale("log")
            bottom.set_yscale("log")
            bottom.set_xlabel(r"$\Pi_2 = \omega_0/\omega_p$")
            for ax in (top, bottom):
                ax.grid(True, which="both", alpha=0.25)
        axes[0][0].set_ylabel(r"$\Pi_1$")
        axes[1][0].set_ylabel(f"relative Pi1 error (below {ERROR_FLOOR:g}: drawn at it)")
        handles, names = axes[0][0].get_legend_handles_labels()
        axes[0][-1].legend(handles, names, loc="upper left", bbox_to_anchor=(1.03, 1.0), fontsize=7.5, frameon=False)
        fig.suptitle(f"{family}: spectra at N = {MIDDLE_N} steps per shortest period, and their error along Pi2",
                     fontsize=10)
        figures.append((family, save(fig, out_dir, f"wp-spectra-{family}")))
    return figures
