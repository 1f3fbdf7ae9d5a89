#!/usr/bin/python3
"""Turns poundbench result rows (CSV from `poundbench spectrum`) into reports/README.md
and its figures. Run by scripts/main.sh; uses Debian's python3-matplotlib.

    reports/make_report.py RESULTS.csv [...] --out reports
"""

import argparse
import datetime
import os
import platform
import subprocess
from collections import defaultdict

import matplotlib
import matplotlib.pyplot as plt

import stability
from rows import config_label, load, num, save, settings_fields, steps_of, write_page

# Columns that label a curve of a spectrum (everything that is neither the abscissa nor a result).
CASE_KEYS = ["scene", "pulse", "directivity", "eps", "pi3", "pi5", "pi6", "pi7", "pi8", "xi", "n_free", "a_p", "w_p"]


def varying(rows, keys):
    return [k for k in keys if len({r[k] for r in rows}) > 1]


def sort_key(label):
    """Curve labels in numeric order where their values are numbers."""
    out = []
    for v in label:
        try:
            out.append((0, float(v), ""))
        except ValueError:
            out.append((1, 0.0, v))
    return out


def plot_family(family, rows, out_dir):
    """Pi1 against Pi2: rows of panels per pulse, columns per directivity, a line per case."""
    pulses = sorted({r["pulse"] for r in rows}, reverse=True)  # sine first, as in the paper
    directivities = sorted({r["directivity"] for r in rows})
    keys = [k for k in varying(rows, CASE_KEYS) if k not in ("pulse", "directivity")]
    fig, axes = plt.subplots(len(pulses), len(directivities), figsize=(5.6 * len(directivities), 3.9 * len(pulses)),
                             squeeze=False, sharex=True)
    for pi, pulse in enumerate(pulses):
        for di, direc in enumerate(directivities):
            ax = axes[pi][di]
            curves = defaultdict(list)
            for r in rows:
                if r["pulse"] == pulse and r["directivity"] == direc:
                    curves[(r["solver"],) + tuple(r[k] for k in keys)].append(r)
            drawn = set()
            for ci, label in enumerate(sorted(curves, key=sort_key)):
                crow = sorted(curves[label], key=lambda r: num(r, "pi2"))
                x = [num(r, "pi2") for r in crow]
                free = tuple(num(r, "pi1_no_contact") for r in crow)
                if free not in drawn:  # curves of the same body 0 share one no-contact line
                    drawn.add(free)
                    ax.plot(x, free, color="0.55", lw=1.0, alpha=0.6)
                text = ", ".join(f"{k}={v}" for k, v in zip(keys, label[1:])) or label[0]
                ax.plot(x, [num(r, "pi1") for r in crow], color=f"C{ci % 10}", lw=1.5, label=text)
            ax.set_xscale("log")
            ax.set_title(f"{pulse} pulse, {direc} directivity", fontsize=10)
            ax.grid(True, which="both", alpha=0.25)
            if pi == len(pulses) - 1:
                ax.set_xlabel(r"$\Pi_2 = \omega_0/\omega_p$")
            if di == 0:
                ax.set_ylabel(r"$\Pi_1 = u_{0,\max}\,\omega_p^2/a_p$")
    axes[0][-1].legend(fontsize=7, loc="upper right")
    fig.suptitle(f"{family}: Pi-spectra of body 0 (colour: with contact, grey: no contact)", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    return save(fig, out_dir, f"spectrum-{family}")



# ---------------------------------------------------------------- work-precision study

TARGETS = [1e-1, 1e-2, 1e-3, 1e-4]
MIDDLE_N = 64  # the step count whose spectra and errors along Pi2 are drawn


def is_event_driven(row):
    """The reference, or another solver's event-driven variant (siconos event-driven-lsodar)."""
    return row["solver"] == "event-driven" or row.get("variant", "").startswith("event-driven")


STYLE = {"moreau-jean": "-", "ode": "--", "bullet": ":", "siconos": "-.", "event-driven": ""}
ERROR_FLOOR = 1e-13  # errors below this are round-off; drawn on the floor


def wp_diagrams(summary, out_dir):
    figures = []
    for family in dict.fromkeys(r["family"] for r in summary):
        rows = [r for r in summary if r["family"] == family]
        lines = defaultdict(list)
        for r in rows:
            lines[config_label(r)].append(r)
        fig, axes = plt.subplots(1, 2, figsize=(13, 6.8), sharey=True)
        colors = plt.get_cmap("tab20").colors
        for ax, key, title in ((axes[0], "err_median", "median"), (axes[1], "err_p95", "95th percentile")):
            for i, (label, lrows) in enumerate(sorted(lines.items())):
                lrows = [r for r in lrows if num(r, key) == num(r, key)]  # drop all-failed settings
                lrows.sort(key=lambda r: num(r, "cpu_median_s"))
                if not lrows:
                    continue
                x = [1e6 * num(r, "cpu_median_s") for r in lrows]
                y = [max(num(r, key), ERROR_FLOOR) for r in lrows]
                style = STYLE.get(lrows[0]["solver"], "-") + ("o" if len(lrows) > 1 else "s")
                ax.plot(x, y, style, color=colors[i % 20], ms=3.5, lw=1.3, label=label)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("CPU time per run, median (us)")
            ax.set_title(f"{family}: {title} of the relative Pi1 error", fontsize=10)
            ax.grid(True, which="both", alpha=0.25)
        axes[0].set_ylabel(r"$|\Pi_1 - \Pi_{1,\mathrm{ref}}| / \Pi_{1,\mathrm{ref}}$ "
                           f"(below {ERROR_FLOOR:g}: drawn at {ERROR_FLOOR:g})")
        handles, labels = axes[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7.5, frameon=False)
        fig.tight_layout(rect=(0, 0.17, 1, 1))
        figures.append((family, save(fig, out_dir, f"wp-{family}")))
    return figures


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
        fig, axes = plt.subplots(2, len(panels), figsize=(4.6 * len(panels), 7.6), squeeze=False, sharex=True)
        for pi, (pulse, pi5) in enumerate(panels):
            prows = [r for r in frows if r["pulse"] == pulse and r["pi5"] == pi5]
            refs = sorted((reference[r["point"]] for r in prows if r["point"] in reference), key=lambda r: num(r, "pi2"))
            refs = list({r["point"]: r for r in refs}.values())
            top, bottom = axes[0][pi], axes[1][pi]
            top.plot([num(r, "pi2") for r in refs], [num(r, "pi1_no_contact") for r in refs], color="0.7", lw=1,
                     ls="--")
            top.plot([num(r, "pi2") for r in refs], [num(r, "pi1") for r in refs], color="k", lw=2.2,
                     label="reference")
            by_config = defaultdict(list)
            for r in prows:
                by_config[config_label(r)].append(r)
            for i, (label, crow) in enumerate(sorted(by_config.items())):
                crow.sort(key=lambda r: num(r, "pi2"))
                ok = [r for r in crow if r["status"] == "ok"]
                x = [num(r, "pi2") for r in ok]
                color = plt.get_cmap("tab20").colors[i % 20]
                top.plot(x, [num(r, "pi1") for r in ok], color=color, lw=1, label=label)
                err = [max(abs(num(r, "pi1") - num(reference[r["point"]], "pi1")) / num(reference[r["point"]], "pi1"),
                           ERROR_FLOOR) for r in ok]
                bottom.plot(x, err, color=color, lw=1)
            title = f"{pulse} pulse" + (f", Pi5 = {pi5}" if pi5 else "")
            top.set_title(title, fontsize=10)
            bottom.set_xscale("log")
            bottom.set_yscale("log")
            bottom.set_xlabel(r"$\Pi_2 = \omega_0/\omega_p$")
            for ax in (top, bottom):
                ax.grid(True, which="both", alpha=0.25)
        axes[0][0].set_ylabel(r"$\Pi_1$")
        axes[1][0].set_ylabel("relative Pi1 error")
        axes[0][-1].legend(fontsize=6, loc="upper right")
        fig.suptitle(f"{family}: spectra at N = {MIDDLE_N} steps per shortest period (dashed grey: no contact), "
                     "and their error along Pi2", fontsize=10)
        fig.tight_layout(rect=(0, 0, 1, 0.96))
        figures.append((family, save(fig, out_dir, f"wp-spectra-{family}")))
    return figures


def recommendation(summary, time_steppers_only=False):
    """For each target error: the cheapest setting that meets it on every family."""
    settings = defaultdict(dict)
    for r in summary:
        if not (time_steppers_only and is_event_driven(r)):
            settings[(r["solver"], r["variant"], r["settings"])][r["family"]] = r
    families = set(r["family"] for r in summary)
    lines = ["| target | by median error | CPU per run (us) | by 95th percentile | CPU per run (us) |",
             "|---:|---|---:|---|---:|"]
    for target in TARGETS:
        cells = []
        for key in ("err_median", "err_p95"):
            best = None
            for per_family in settings.values():
                if set(per_family) != families:
                    continue
                if any(int(r["failed"]) > 0 or not num(r, key) <= target for r in per_family.values()):
                    continue
                cost = max(num(r, "cpu_mean_s") for r in per_family.values())
                if best is None or cost < best[0]:
                    some = next(iter(per_family.values()))
                    best = (cost, config_label(some) + (f", N = {steps_of(some)}" if steps_of(some) else ""))
            cells.append(("none", "") if best is None else (best[1], f"{1e6 * best[0]:.1f}"))
        lines.append(f"| {target:g} | {cells[0][0]} | {cells[0][1]} | {cells[1][0]} | {cells[1][1]} |")
    return lines


def cost_table(summary):
    """CPU time per run at N = MIDDLE_N (and the reference), as a ratio to Moreau-Jean theta = 1/2."""
    lines = ["| family | solver setting | CPU per run, mean (us) | ratio to moreau-jean theta=0.5 |",
             "|---|---|---:|---:|"]
    for family in dict.fromkeys(r["family"] for r in summary):
        rows = [r for r in summary if r["family"] == family]
        base = [r for r in rows if r["solver"] == "moreau-jean" and steps_of(r) == MIDDLE_N
                and settings_fields(r)["theta"] == 0.5]
        if not base:
            continue
        b = num(base[0], "cpu_mean_s")
        for r in rows:
            n = steps_of(r)
            if n not in (None, MIDDLE_N) or (is_event_driven(r) and settings_fields(r).get("tol_scale") != 1):
                continue
            lines.append(f"| {family} | {config_label(r)}{'' if n is None else f', N = {n}'} | "
                         f"{1e6 * num(r, 'cpu_mean_s'):.1f} | {num(r, 'cpu_mean_s') / b:.2f} |")
    return lines


def stability_section(summary, points, out_dir):
    """Where each solver breaks: the stress set's checks per family and setting, and the
    figures against w_max h and the chain's size."""
    tol = stability.tolerances()
    lines = ["## Stability on stiff and extreme cases", "",
             "Every case of the stress set (`cases/sets/stress.toml`: stiffness and mass contrasts of 1e-2 and "
             "1e2, bodies touching at rest, eps = 0 and 1, pulse scales 1e-3 to 1e3, 100 free periods, chains "
             "of up to 100 bodies, a Newton's cradle) through every setting of `cases/settings/stress.toml`, "
             "the time-steppers at w_max h = 0.5, 2, 10 and 100. Four checks per family and setting "
             "(tolerances in `studies/stress.hpp`):", "",
             "* **finite**: every run ends with status ok and a finite Pi1 (a failed run is shown as ok/runs);",
             "* **energy**: the mechanical energy never exceeds the start's energy plus the work of the ground "
             f"load, to {tol['kEnergyTolerance']:g} of the energy scale (largest excess shown);",
             f"* **gap**: a time-stepper overlaps by at most one step of travel (to {tol['kPenetrationSteps'] - 1:.0e}, room for round-off) "
             "at its fastest gap rate, h max|g'| (worst overlap shown in such steps); the reference, by at most "
             f"{tol['kReferencePenetration']:g} of the gap;",
             f"* **restitution**: every isolated impact restitutes eps to {tol['kRestitutionTolerance']:g} "
             "(worst |e - eps| shown).", "",
             "`pass`: no check failed; `-`: nothing to judge (no run finished). Energy, gap and restitution "
             "judge the finished runs only, so a diverged run counts once. The numbers of every cell are in "
             "`stability.csv`; every run's row in `poundbench stress --points`.", "",
             "Reading it: ODE and Bullet apply the ground load sampled at the start of each step, which "
             "makes energy to first order in h, so they fail the energy check at any step (the excess says "
             "how much, and shrinks with h: `tests/ode_test.cpp`, `tests/bullet_test.cpp`); as explicit "
             "schemes they diverge from w_max h = 2 on, the stability limit of their semi-implicit Euler step. Where Moreau-Jean makes energy (a plastic impulse on a "
             "separating contact at theta = 1/2, elastic contacts held closed at theta = 1) is derived in "
             "`solvers/moreau_jean/README.md`. Siconos' MoreauJeanOSI samples the load at the step's ends "
             "instead of averaging it over the step, and the work of that sampled load is not the ground's: "
             "it fails the energy check at every step (`solvers/siconos/README.md`).", ""]
    lines += ["In short, per solver configuration over every family and step:", ""]
    lines += stability.stability_summary(summary)
    lines += ["", "Per family and step:", ""]
    lines += stability.stability_table(summary)
    lines.append("")
    if points:
        figure = stability.large_step_figure(points, out_dir)
        if figure:
            lines += ["### Against the step", "", f"![large steps]({figure})", ""]
        figure = stability.chain_cost_figure(points, out_dir)
        if figure:
            lines += ["### Chain: cost against the number of bodies", "", f"![chain cost]({figure})", ""]
    return lines


def bench_section(path):
    import json

    with open(path) as f:
        data = json.load(f)
    rate = {b["name"]: b.get("points_per_s") for b in data.get("benchmarks", [])
            if b["name"].startswith("BM_SweepFig4Reference") and b.get("aggregate_name", "median") == "median"}
    one = next((v for k, v in rate.items() if "threads:1" in k), None)
    two = next((v for k, v in rate.items() if "threads:2" in k), None)
    speedup = ([f"Whole spectra through the sweep runner: {two / one:.2f}x faster on 2 threads than on 1 "
                "(`BM_SweepFig4Reference`, the Fig. 4 families through the reference).", ""] if one and two else [])
    lines = ["## Benchmarks", "", "Google Benchmark medians (`build/bench/poundbench_bench`, "
             f"{data.get('context', {}).get('num_cpus', '?')} CPUs, "
             f"{data.get('context', {}).get('mhz_per_cpu', '?')} MHz):", "",
             "| benchmark | time | counters |", "|---|---:|---|"]
    lines = speedup + lines
    rows = [b for b in data.get("benchmarks", []) if b.get("aggregate_name", "median") == "median"]
    for b in rows:
        counters = ", ".join(f"{k}={v:.4g}" for k, v in b.items()
                             if isinstance(v, (int, float)) and k not in (
                                 "real_time", "cpu_time", "iterations", "repetitions", "repetition_index",
                                 "threads", "family_index", "per_family_instance_index"))
        name = b["name"].replace("_median", "")
        lines.append(f"| {name} | {b['real_time']:.4g} {b.get('time_unit', 'ns')} | {counters} |")
    return lines + [""]


def command_output(cmd):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def footer():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    lines = [
        f"- machine: {platform.machine()}, {os.cpu_count()} cores, {cpu}",
        f"- system: {platform.platform()}",
        f"- compiler: {command_output(['c++', '--version']).splitlines()[0] if command_output(['c++', '--version']) != 'unknown' else 'unknown'}",
        f"- libraries: Eigen {command_output(['dpkg-query', '-W', '-f=${Version}', 'libeigen3-dev'])}, "
        f"toml++ {command_output(['dpkg-query', '-W', '-f=${Version}', 'libtomlplusplus-dev'])}, "
        f"matplotlib {matplotlib.__version__}",
        f"- commit: {command_output(['git', 'rev-parse', '--short', 'HEAD'])}",
        f"- date: {datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}",
    ]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="+", help="result CSV files from `poundbench spectrum` (paper case set)")
    parser.add_argument("--workprecision", help="summary CSV from `poundbench workprecision`")
    parser.add_argument("--points", help="per-run CSV from `poundbench workprecision --points`")
    parser.add_argument("--bench", help="Google Benchmark JSON (--benchmark_out) of poundbench_bench")
    parser.add_argument("--stress", help="summary CSV from `poundbench stress --out`")
    parser.add_argument("--stress-points", help="per-run CSV from `poundbench stress --points`")
    parser.add_argument("--out", default="reports", help="folder for README.md and figures/")
    args = parser.parse_args()

    rows = load(args.results)
    os.makedirs(os.path.join(args.out, "figures"), exist_ok=True)
    families = defaultdict(list)
    for r in rows:
        families[r["family"]].append(r)

    text = ["# poundbench report", ""]
    text.append("Generated by `scripts/main.sh` (one command: build, sweeps, benchmarks, this page). "
                "Errors are relative to the event-driven reference solved with 100x tighter tolerances; "
                "times are CPU time of the solve alone, per run, on this project's 2-core machine.")
    text.append("")
    text += ["## How to read this", "",
             "* **Solvers and impact laws.** `event-driven` is the reference (exact between events, Poisson's "
             "law through compression and expansion LCPs). `moreau-jean`, `ode` and `bullet` are time-steppers "
             "with Newton's law at the velocity level. For one contact the two laws coincide; they differ for "
             "simultaneous impacts in `row3`, where every time-stepper is measured against Poisson's law.",
             "* **Siconos.** `siconos` runs the same cases through Siconos itself: `moreau-jean-*` is its "
             "MoreauJeanOSI (the in-house scheme, but with the load of a step sampled at its ends: "
             "`solvers/siconos/README.md`), `event-driven-lsodar` its event-driven LSODAR scheme with Newton's "
             "law, which fails where impacts accumulate (counted as failed runs).",
             "* **Faithful and default.** A *faithful* engine variant is set so that restitution is exactly eps "
             "and nothing else touches an impact; a *default* one is the engine's own defaults with only the "
             "restitution set. Every setting is named in the `settings` column of `workprecision.csv` and in "
             "`solvers/ode/README.md`, `solvers/bullet/README.md`.",
             "* **Precision.** Bullet from Debian (`libbullet-dev`, pkg-config `bullet`) is single precision: "
             "its Pi1 carries float round-off of about 1e-7 to 1e-6 of the peak, which is its floor. All other "
             "solvers are double precision.",
             "* **N** is the number of steps per shortest period (`h = T_min / N`).", ""]
    if args.workprecision:
        summary = load([args.workprecision])
        text += ["## Which solver for which accuracy", "",
                 "For each target, the cheapest setting whose relative Pi1 error (median, or 95th percentile, "
                 "over the points of a family) meets the target on every family of "
                 "`cases/sets/workprecision.toml` (wall, pair, symmetric row3) with no failed run. Its cost is "
                 "its mean CPU time per run on its most expensive family.", "",
                 "Among every solver, the reference included (it is a solver too, for this problem):", ""]
        text += recommendation(summary)
        text += ["", "Among the time-steppers only (what a general multibody code would use):", ""]
        text += recommendation(summary, time_steppers_only=True)
        text += ["", "## Work-precision diagrams", "",
                 "Relative Pi1 error against CPU time per run; each line is one solver configuration over "
                 "its step counts N (steps per shortest period: 8, 16, ...). Settings that failed on every "
                 "point are left out; failed runs are counted in `workprecision.csv`.", ""]
        for family, figure in wp_diagrams(summary, args.out):
            text += [f"### {family}", "", f"![work-precision {family}]({figure})", ""]
        text += ["## Cost per run", "", f"At N = {MIDDLE_N}, as a ratio to the in-house Moreau-Jean stepper "
                 "(theta = 1/2) on the same points:", ""]
        text += cost_table(summary)
        text.append("")
    if args.points:
        points = load([args.points])
        text += ["## Spectra and where they go wrong", "",
                 f"Each solver at N = {MIDDLE_N} over the reference (black), and its error along Pi2.", ""]
        for family, figure in wp_spectra(points, args.out):
            text += [f"### {family}", "", f"![spectra {family}]({figure})", ""]
    if args.stress:
        text += stability_section(load([args.stress]), load([args.stress_points]) if args.stress_points else [],
                                  args.out)
    if args.bench:
        text += bench_section(args.bench)

    text.append("## The paper case set")
    text.append("")
    text.append("| family | solver | points | failed | impacts (median) | CPU per point, median (us) | total CPU (s) |")
    text.append("|---|---|---:|---:|---:|---:|---:|")
    for family, frows in families.items():
        by_solver = defaultdict(list)
        for r in frows:
            by_solver[(r["solver"], r["variant"])].append(r)
        for (solver, variant), srows in by_solver.items():
            secs = sorted(num(r, "cpu_seconds") for r in srows)
            imps = sorted(num(r, "impacts") for r in srows)
            failed = sum(r["status"] != "ok" for r in srows)
            text.append(f"| {family} | {solver} {variant} | {len(srows)} | {failed} | {imps[len(imps) // 2]:.0f} | "
                        f"{1e6 * secs[len(secs) // 2]:.1f} | {sum(secs):.2f} |")
    text.append("")
    text.append("### Reference Pi-spectra")
    text.append("")
    text.append("Pi1 of body 0 against Pi2 for every family of the paper's case set, from the event-driven "
                "reference. Grey lines: the same case with every contact removed.")
    text.append("")
    for family, frows in families.items():
        frows = [r for r in frows if r["solver"] == "event-driven"]
        if len({r["pi2"] for r in frows}) <= len({r["pi6"] for r in frows}):
            continue  # not a spectrum over Pi2 (fig10 sweeps Pi6)
        figure = plot_family(family, frows, args.out)
        text.append(f"#### {family}")
        text.append("")
        text.append(f"![{family}]({figure})")
        text.append("")
    text.append("## Where this ran")
    text.append("")
    text.append(footer())
    text.append("")
    write_page(args.out, text, "make_report.py")


if __name__ == "__main__":
    main()
