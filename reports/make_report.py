#!/usr/bin/python3
"""Turns poundbench result rows into reports/README.md and its figures, commits the small
result files README's numbers come from (workprecision.csv, workprecision-families.csv,
stability.csv, measured.csv, provenance.json) beside it, and with --readme writes README's
generated blocks from them (readme.py). Run by scripts/main.sh; uses Debian's
python3-matplotlib.

    reports/make_report.py RESULTS.csv [...] --workprecision WP.csv --points WP-POINTS.csv ... --out reports
    reports/make_report.py --check        README's blocks against reports/: exit 1 and the diff if they differ
    reports/make_report.py --blocks-only  rewrite README's blocks from reports/ alone
"""

import argparse
import json
import os
import platform
import shutil
import sys
from collections import defaultdict

import answer
import compliant
import measured
import provenance
import readme
from rows import load, median, num, write_page

# The figure modules (spectra, wp, stability: matplotlib) are imported where a figure is drawn,
# so that --check, which draws none, starts in a blink.


# ---------------------------------------------------------------- the sections

def answer_section(summary, scenes):
    return ["## Which solver for which accuracy", "", answer.rule(summary), "",
            "Per scene of `cases/sets/workprecision.toml`:", "", *answer.scene_table(summary, scenes), "",
            "Over every family at once, among every solver:", "", *answer.overall_table(summary), "",
            "Among the time-steppers only (what a general multibody code would use):", "",
            *answer.overall_table(summary, time_steppers_only=True), ""]


def beats_section(summary, points):
    """Where another time-stepper beats the in-house Moreau-Jean, and the settings whose runs
    failed, with the cause each solver gives."""
    lines = ["## Where another scheme beats the in-house Moreau–Jean", "",
             "Per family and target (the median of the relative Pi1 error, no failed or unresolved run), the in-house "
             "`moreau-jean`'s cheapest setting that meets it and its least step count N, against every other "
             "time-stepper configuration of the study: those that meet the target at less CPU per run, and those "
             "that meet it with fewer steps per shortest period. The step counts compare the schemes apart from "
             "what their code costs a step (the libraries' steps cost 10 to 300 times the in-house one's: "
             "*Cost per run* below).", "", *answer.beats_table(summary), ""]
    failures = answer.failure_table(points)
    if failures:
        lines += ["### Settings with failed runs", "",
                  "Every setting of the study with runs that did not end ok, and the message of the first: the "
                  "cause its solver names (`solvers/*/README.md` say more). A setting that failed on every point "
                  "has no line in the diagrams.", "", *failures, ""]
    unresolved = answer.unresolved_table(points)
    if unresolved:
        lines += ["### Settings with unresolved runs", "",
                  "Every setting with runs that ended ok but whose own measurements say they did not resolve what "
                  "they solved (`resolved` false in their rows, `solvers/verdict.hpp`), and the reasons of the first. "
                  "No table above ranks them; the diagrams draw them hollow.", "", *unresolved, ""]
    return lines


def workprecision_section(summary, out_dir):
    import wp

    text = ["## Work-precision diagrams", "",
            "Relative Pi1 error against median CPU time per run, over the points of a family; each line is one "
            "solver configuration over its step counts N (steps per shortest period: 8, 16, ...). A row of panels "
            "per solver family, the other solvers in light grey behind it; the thick grey band is the Pareto "
            "front over every solver (the settings no other setting beats in both cost and error; settings with "
            "failed or unresolved runs are not candidates, and are drawn hollow). Errors below "
            f"{wp.ERROR_FLOOR:g} are round-off: they are drawn in the shaded band under it, one row per setting, "
            "so that none hides another. Settings that failed on every point are left out; failed runs are "
            "counted in `workprecision.csv`" + (" Horizontal bars: the lowest and highest CPU time of the timing "
                                                "repetitions." if any(answer.has_spread(r) for r in summary)
                                                else ".") + "", ""]
    for family, figure in wp.wp_diagrams(summary, out_dir):
        text += [f"### {family}", "", f"![work-precision {family}]({figure})", ""]
    text += ["## Cost per run", "", f"At N = {answer.MIDDLE_N}, as a ratio to the in-house Moreau-Jean stepper "
             "(theta = 1/2) on the same points (median CPU time per run"
             + (", in brackets the low-high of the repetitions" if any(answer.has_spread(r) for r in summary) else "")
             + "):", ""]
    return text + answer.cost_table(summary) + [""]


def spectra_section(points, out_dir):
    import wp

    text = ["## Spectra and where they go wrong", "",
            f"Each solver at N = {answer.MIDDLE_N} over the reference (black), and its error along Pi2.", ""]
    for family, figure in wp.wp_spectra(points, out_dir):
        text += [f"### {family}", "", f"![spectra {family}]({figure})", ""]
    return text


def stability_section(summary, points, out_dir):
    """Where each solver breaks: the stress set's checks per family and setting, and the
    figures against w_max h and the chain's size."""
    import stability

    tol = stability.tolerances()
    checks = stability.checks_of(summary)
    lines = ["## Stability on stiff and extreme cases", "",
             "Every case of the stress set (`cases/sets/stress.toml`: stiffness and mass contrasts of 1e-2 and "
             "1e2, bodies touching at rest, eps = 0 and 1, pulse scales 1e-3 to 1e3, 100 free periods, chains "
             "of up to 100 bodies, a Newton's cradle) through every setting of `cases/settings/stress.toml`, "
             f"the time-steppers at w_max h from resolved to a hundred radians ({stability.steps_sentence(summary)}). "
             f"{len(checks)} checks per family and setting (tolerances in `studies/stress.hpp`):", "",
             "* **finite**: every run ends with status ok and a finite Pi1;",
             "* **energy**: the mechanical energy never exceeds the start's energy plus the work of the ground "
             f"load, to {tol['kEnergyTolerance']:g} of the energy scale;",
             "* **gap**: a time-stepper overlaps by at most one step of travel (to "
             f"{tol['kPenetrationSteps'] - 1:.0e}, room for round-off) at its fastest gap rate, h max|g'|; the "
             f"reference, by at most {tol['kReferencePenetration']:g} a_p/w_p^2;",
             f"* **restitution**: every isolated impact restitutes eps to {tol['kRestitutionTolerance']:g}"
             + (";" if "accuracy" in checks else "."),
             *(["* **accuracy**: Pi1 and the impacts against the truth's (the rule: `studies/stress.hpp`; the worst "
                "95th percentile of the Pi1 error shown)."]
               if "accuracy" in checks else []), "",
             "Energy, gap and restitution judge the finished runs only, so a diverged run counts once.", "",
             "Reading it: ODE and Bullet apply the ground load sampled at the start of each step, which "
             "makes energy to first order in h, so they fail the energy check at any step (the excess says "
             "how much, and shrinks with h: `tests/ode_test.cpp`, `tests/bullet_test.cpp`); as explicit "
             "schemes they diverge from w_max h = 2 on, the stability limit of their semi-implicit Euler step. "
             "Where Moreau-Jean makes energy (a plastic impulse on a "
             "separating contact at theta = 1/2, elastic contacts held closed at theta = 1) is derived in "
             "`solvers/moreau_jean/README.md`. Siconos' MoreauJeanOSI samples the load at the step's ends "
             "instead of averaging it over the step, and the work of that sampled load is not the ground's: "
             "it fails the energy check at every step (`solvers/siconos/README.md`).", ""]
    lines += ["In short, per solver configuration over every family and step (worst values over the failing "
              "cells):", ""]
    lines += stability.stability_summary(summary)
    lines += ["", "Per family and setting:", "", f"![stress verdicts]({stability.verdict_figure(summary, out_dir)})",
              "", "The numbers behind every cell (runs, finished runs, worst energy excess, penetration and "
              "restitution error, errors and cost): [`stability.csv`](stability.csv), one line per family and "
              "setting; every run's row in `poundbench stress --points`. Penetration has one scale there and in "
              "every row, `a_p / w_p^2` (`penetration_max`, the rows' `penetration` and `min_gap`), and the "
              "gap check's per-step overlap besides (`penetration_steps_max`: over one step of travel, `h max|g'|`, "
              "which the figure below plots).", ""]
    if points:
        figure = stability.large_step_figure(points, out_dir)
        if figure:
            lines += ["### Against the step", "", f"![large steps]({figure})", ""]
        figure = stability.chain_cost_figure(points, out_dir)
        if figure:
            lines += ["### Chain: cost against the number of bodies", "", f"![chain cost]({figure})", ""]
    return lines


def bench_section(path, quoted, summary, stress, measured_on):
    """README's measured table (the same rows), then every benchmark's median."""
    with open(path) as f:
        data = json.load(f)
    runs = data.get("benchmarks", [])
    medians = [b for b in runs if b.get("aggregate_name") == "median"] or \
        [b for b in runs if b.get("run_type") != "aggregate"]
    lines = ["## Benchmarks", "", "What README quotes (`measured.csv`; the benchmark medians over their "
             "repetitions):", "", *measured.table(quoted, summary, stress, measured_on), "",
             "Every benchmark: Google Benchmark medians (`build/bench/poundbench_bench`, "
             f"{data.get('context', {}).get('num_cpus', '?')} CPUs, "
             f"{data.get('context', {}).get('mhz_per_cpu', '?')} MHz):", "",
             "| benchmark | time | counters |", "|---|---:|---|"]
    for b in medians:
        counters = ", ".join(f"{k}={v:.4g}" for k, v in b.items()
                             if isinstance(v, (int, float)) and k not in (
                                 "real_time", "cpu_time", "iterations", "repetitions", "repetition_index",
                                 "threads", "family_index", "per_family_instance_index"))
        lines.append(f"| {b.get('run_name', b['name'])} | {b['real_time']:.4g} {b.get('time_unit', 'ns')} | "
                     f"{counters} |")
    return lines + [""]


def paper_set_section(rows, out_dir):
    import spectra

    families = defaultdict(list)
    for r in rows:
        families[r["family"]].append(r)
    text = ["## The paper case set", "",
            "| family | solver | points | failed | impacts (median) | CPU per point, median (us) | total CPU (s) |",
            "|---|---|---:|---:|---:|---:|---:|"]
    for family, frows in families.items():
        by_solver = defaultdict(list)
        for r in frows:
            by_solver[(r["solver"], r["variant"])].append(r)
        for (solver, variant), srows in by_solver.items():
            secs = [num(r, "cpu_seconds") for r in srows]
            failed = sum(r["status"] != "ok" for r in srows)
            text.append(f"| {family} | {solver} {variant} | {len(srows)} | {failed} | "
                        f"{median([num(r, 'impacts') for r in srows]):.0f} | {1e6 * median(secs):.1f} | "
                        f"{sum(secs):.2f} |")
    text += ["", "### Reference Pi-spectra", "",
             "Pi1 of body 0 against Pi2 for every family of the paper's case set, from the event-driven "
             "reference. Dashed grey lines: the same case with every contact removed.", ""]
    for family, frows in families.items():
        frows = [r for r in frows if r["solver"] == "event-driven"]
        if len({r["pi2"] for r in frows}) <= len({r["pi6"] for r in frows}):
            continue  # not a spectrum over Pi2 (fig10 sweeps Pi6)
        figure, note = spectra.plot_family(family, frows, out_dir)
        text += [f"#### {family}", "", f"![{family}]({figure})", ""] + ([note, ""] if note else [])
    return text


def footer(measured_on):
    """Where the results were measured (provenance.py), and the libraries the report used."""
    import matplotlib

    return "\n".join([
        f"- measured at: {provenance.describe(measured_on)}",
        f"- system: {platform.machine()}, {platform.platform()}",
        f"- libraries: Eigen {provenance.command_output(['dpkg-query', '-W', '-f=${Version}', 'libeigen3-dev'])}, "
        f"toml++ {provenance.command_output(['dpkg-query', '-W', '-f=${Version}', 'libtomlplusplus-dev'])}, "
        f"matplotlib {matplotlib.__version__}",
    ])


# ---------------------------------------------------------------- committing the results

def commit_results(args):
    """Copies or writes into args.out the small files README's numbers come from; returns the
    provenance of the results."""
    def target(name):
        return os.path.join(args.out, name)

    if args.provenance:
        with open(args.provenance) as f:
            measured_on = json.load(f)
    else:  # measured now: the report runs right after the results (tests/report_smoke.sh)
        measured_on = provenance.measure("build")
    with open(target(readme.PROVENANCE), "w") as f:
        json.dump(measured_on, f, indent=2)
        f.write("\n")
    for source, name in ((args.workprecision, readme.WORKPRECISION), (args.stress, readme.STABILITY),
                         (args.compliant, readme.COMPLIANT), (args.restitution, readme.RESTITUTION)):
        if source and os.path.abspath(source) != os.path.abspath(target(name)):
            shutil.copyfile(source, target(name))
    return measured_on


def write_families(points, path):
    """The scene of every family of the work-precision study, from its per-run rows."""
    with open(path, "w") as f:
        f.write("family,scene\n")
        for family, scene in dict.fromkeys((r["family"], r["scene"]) for r in points):
            f.write(f"{family},{scene}\n")


def report(args):
    rows = load(args.results)
    os.makedirs(os.path.join(args.out, "figures"), exist_ok=True)
    measured_on = commit_results(args)
    summary = load([args.workprecision]) if args.workprecision else []
    stress = load([args.stress]) if args.stress else []
    quoted = []
    if args.bench or args.timings:
        quoted = (measured.from_bench(args.bench) if args.bench else []) + \
            (measured.from_timings(args.timings, sum(r["solver"] == "event-driven" for r in rows))
             if args.timings else [])
        measured.write(os.path.join(args.out, readme.MEASURED), quoted)
        quoted = load([os.path.join(args.out, readme.MEASURED)])  # as README reads it back

    text = ["# poundbench report", "",
            "Generated by `scripts/main.sh` (one command: build, sweeps, benchmarks, this page). "
            "Errors are relative to the event-driven reference solved with 100x tighter tolerances; "
            "times are CPU time of the solve alone, per run, the clocks' own cost taken off "
            f"(`sweep/stopwatch.hpp`), measured at {provenance.describe(measured_on)}.", ""]
    text += ["## How to read this", "",
             "* **Solvers and impact laws.** `event-driven` is the reference (exact between events, Poisson's "
             "law through compression and expansion LCPs). `moreau-jean`, `ode` and `bullet` are time-steppers "
             "with Newton's law at the velocity level. For one contact the two laws coincide; they differ for "
             "simultaneous impacts in `row3`, where every time-stepper is measured against Poisson's law.",
             "* **Siconos.** `siconos` runs the same cases through Siconos itself: `moreau-jean-*` is its "
             "MoreauJeanOSI (the in-house scheme, but with the load of a step sampled at its ends: "
             "`solvers/siconos/README.md`), `event-driven-lsodar` its event-driven LSODAR scheme with Newton's "
             "law, which fails where impacts accumulate (counted as failed runs); `schatzman-paoli`, "
             "`d1-minus-linear`, `combined-projection` and `direct-projection` its other one-step integrators, "
             "and `bilbao` and `newmark-alpha` two that fail on every run in Siconos 4.4, each naming why "
             "(*Settings with failed runs*).",
             "* **MuJoCo.** `mujoco` has soft contacts (spring-dampers, no restitution law): its faithful "
             "variants calibrate each contact to eps (the clamped oscillator's damping ratio, a time constant "
             "of `--contact-steps` steps), so an isolated impact restitutes eps only up to a scatter with the "
             "phase of the step and the bodies overlap during a contact; it fails the gap and restitution "
             "checks by design (`solvers/mujoco/README.md`).",
             "* **Faithful and default.** A *faithful* engine variant is set so that restitution is exactly eps "
             "and nothing else touches an impact; a *default* one is the engine's own defaults with only the "
             "restitution set. Every setting is named in the `settings` column of `workprecision.csv` and in "
             "`solvers/ode/README.md`, `solvers/bullet/README.md`, `solvers/mujoco/README.md`.",
             "* **Precision.** Bullet from Debian (`libbullet-dev`, pkg-config `bullet`) is single precision: "
             "its Pi1 carries float round-off of about 1e-7 to 1e-6 of the peak, which is its floor. All other "
             "solvers are double precision.",
             "* **N** is the number of steps per shortest period (`h = T_min / N`).", ""]
    if summary:
        points = load([args.points])
        write_families(points, os.path.join(args.out, readme.FAMILIES))
        text += answer_section(summary, {r["family"]: r["scene"] for r in points})
        text += beats_section(summary, points)
        text += workprecision_section(summary, args.out)
        text += spectra_section(points, args.out)
    if args.compliant:
        text += compliant.section(load([args.compliant]), load([args.compliant_points]), args.out)
    if stress:
        text += stability_section(stress, load([args.stress_points]) if args.stress_points else [], args.out)
    if args.bench:
        text += bench_section(args.bench, quoted, summary, stress, measured_on)
    if args.records:
        import records
        text += records.section(load(args.records), args.out)
    text += paper_set_section(rows, args.out)
    text += ["## Where this ran", "", footer(measured_on), ""]
    write_page(args.out, text, "make_report.py")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="*", help="result CSV files from `poundbench spectrum` (paper case set)")
    parser.add_argument("--workprecision", help="summary CSV from `poundbench workprecision` (needs --points)")
    parser.add_argument("--points", help="per-run CSV from `poundbench workprecision --points`")
    parser.add_argument("--bench", help="Google Benchmark JSON (--benchmark_out) of poundbench_bench")
    parser.add_argument("--timings", help="the main job's step times (scripts/main.sh: results/timings.csv)")
    parser.add_argument("--provenance", help="where the results were measured (reports/provenance.py's JSON); "
                        "default: this machine now")
    parser.add_argument("--stress", help="summary CSV from `poundbench stress --out`")
    parser.add_argument("--compliant", help="summary CSV of the compliant-contact study (`poundbench workprecision "
                        "cases/sets/compliant.toml --settings cases/settings/compliant.toml`; needs --compliant-points)")
    parser.add_argument("--compliant-points", help="its per-run CSV (--points)")
    parser.add_argument("--restitution", help="what each compliant element restitutes, measured "
                        "(build/bench/poundbench_restitution's CSV): README's table")
    parser.add_argument("--stress-points", help="per-run CSV from `poundbench stress --points`")
    parser.add_argument("--records", nargs="+", help="rows of `poundbench spectrum cases/sets/records.toml` through "
                        "the reference and the time-steppers (scripts/main.sh: results/records-*.csv)")
    parser.add_argument("--out", default=here, help="folder for README.md, figures/ and the committed result files")
    parser.add_argument("--readme", help="also write the generated blocks of this README (scripts/main.sh: README.md)")
    parser.add_argument("--check", action="store_true", help="write nothing: exit 1, with the diff, when README's "
                        "generated blocks differ from what --out's result files give (README: --readme, default "
                        "the repository's)")
    parser.add_argument("--blocks-only", action="store_true", help="write README's generated blocks from --out's "
                        "result files, and nothing else")
    args = parser.parse_args()
    if args.check or args.blocks_only:
        path = args.readme or os.path.join(os.path.dirname(here), "README.md")
        if args.check:
            sys.exit(readme.check(path, args.out))
        readme.write(path, args.out)
        return
    if not args.results:
        parser.error("the paper case set's result CSVs are needed (or --check / --blocks-only)")
    if args.workprecision and not args.points:
        parser.error("--workprecision needs --points (the scene of each family)")
    if args.compliant and not args.compliant_points:
        parser.error("--compliant needs --compliant-points (restitution and penetration per run)")
    report(args)
    if args.readme:
        readme.write(args.readme, args.out)


if __name__ == "__main__":
    main()
