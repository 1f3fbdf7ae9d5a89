#!/usr/bin/python3
"""Turns the main job's results into reports/README.md, its figures and report.html, commits
the small result files README's numbers come from (workprecision.csv,
workprecision-families.csv, workprecision-impacting.csv, stability.csv, measured.csv,
provenance.json) beside it, and with --readme writes README's generated blocks from them
(readme.py). The work-precision and stress studies' sections are report.py's, the report of
any study (`poundbench report`); this adds the main job's own. Run by scripts/main.sh; uses
Debian's python3-matplotlib.

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

import compliant
import measured
import provenance
import readme
import report as report_of
from rows import load, write_page
from study import InputError, Study, scope_of, spectrum_summary, write_impacting

# The figure modules (spectra, wp, stability: matplotlib) are imported where a figure is drawn,
# so that --check, which draws none, starts in a blink.


# ---------------------------------------------------------------- the sections
# The studies' sections are report.py's (the report of any study); this file adds what only
# the main job has: how to read its solvers, the compliant study, the benchmarks, the
# records and the paper case set.

STRESS_ABOUT = ("Every case of the stress set (`cases/sets/stress.toml`: stiffness and mass contrasts of 1e-2 and "
                "1e2, bodies touching at rest, eps = 0 and 1, pulse scales 1e-3 to 1e3, 100 free periods, chains of "
                "up to 100 bodies, a Newton's cradle; and the recorded ground motion of "
                "`cases/sets/stress-records.toml`; and the yielding bodies of `cases/sets/stress-yielding.toml`: "
                "elastic-perfectly plastic at large steps, yielding at t = 0+, a touching chain of yielding bodies, "
                "where a solver that cannot take the bilinear law ends every run failed, saying why, and the energy "
                "and gap checks have nothing to judge, as the monitor's energy is elastic) through every setting of `cases/settings/stress.toml`, the "
                "time-steppers at w_max h from resolved to a hundred radians ({steps}).")
STRESS_READING = [
    "Reading it: ODE and Bullet apply the ground load sampled at the start of each step, which makes energy to first "
    "order in h, so they fail the energy check at any step (the excess says how much, and shrinks with h: "
    "`solvers/ode/ode_test.cpp`, `solvers/bullet/bullet_test.cpp`); as explicit schemes they diverge from w_max h = 2 on, the "
    "stability limit of their semi-implicit Euler step. Where Moreau-Jean makes energy (a plastic impulse on a "
    "separating contact at theta = 1/2, elastic contacts held closed at theta = 1) is derived in "
    "`solvers/moreau_jean/README.md`. Siconos' MoreauJeanOSI samples the load at the step's ends instead of averaging "
    "it over the step, and the work of that sampled load is not the ground's: it fails the energy check at every step "
    "(`solvers/siconos/README.md`).", ""]


def stress_section(study, out):
    import stability

    return report_of.stress_sections(study, out, STRESS_ABOUT.format(steps=stability.steps_sentence(study.rows)),
                                     STRESS_READING)


def bench_section(path, quoted, summary, stress, measured_on):
    """README's measured table (the same rows), then every benchmark's median (from the
    benchmarks' JSON, when this run has it)."""
    lines = ["## Benchmarks", "", "What README quotes (`measured.csv`; the benchmark medians over their "
             "repetitions):", "", *measured.table(quoted, summary, stress, measured_on), ""]
    if not path:
        return lines + ["Every benchmark's median: in the main job's own run (`scripts/main.sh`), from its "
                        "benchmarks' JSON.", ""]
    with open(path) as f:
        data = json.load(f)
    runs = data.get("benchmarks", [])
    medians = [b for b in runs if b.get("aggregate_name") == "median"] or \
        [b for b in runs if b.get("run_type") != "aggregate"]
    lines += ["Every benchmark: Google Benchmark medians (`build/bench/poundbench_bench`, "
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
    for s in spectrum_summary(rows):
        text.append(f"| {s['family']} | {s['solver']} {s['variant']} | {s['points']} | {s['failed']} | "
                    f"{s['impacts']:.0f} | {1e6 * s['cpu']:.1f} | {s['total_cpu']:.2f} |")
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
                         (args.compliant, readme.COMPLIANT), (args.restitution, readme.RESTITUTION),
                         (args.records_wp, readme.RECORDS_WP), (args.yielding_wp, readme.YIELDING_WP)):
        if source and os.path.abspath(source) != os.path.abspath(target(name)):
            shutil.copyfile(source, target(name))
    return measured_on


def write_families(points, path):
    """The scene of every family of the work-precision study, from its per-run rows, as the
    answer tables group them (study.scope_of: a record's family is "<scene> records")."""
    with open(path, "w") as f:
        f.write("family,scene\n")
        for family, scene in dict.fromkeys((r["family"], scope_of(r)) for r in points):
            f.write(f"{family},{scene}\n")


def studies(args):
    """The main job's studies as report.py reads any study, checked before anything is
    written; exits 2 naming the file where one is not what it should be."""
    try:
        wp = Study(args.workprecision, args.points) if args.workprecision else None
        stress = Study(args.stress, args.stress_points) if args.stress else None
    except InputError as e:
        print(f"make_report.py: {e}", file=sys.stderr)
        sys.exit(2)
    return wp, stress


def report(args):
    rows = load(args.results)
    wp_study, stress_study = studies(args)
    os.makedirs(os.path.join(args.out, "figures"), exist_ok=True)
    measured_on = commit_results(args)
    summary = wp_study.rows if wp_study else []
    stress = stress_study.rows if stress_study else []
    quoted = []
    if args.bench or args.timings:
        quoted = (measured.from_bench(args.bench) if args.bench else []) + \
            (measured.from_timings(args.timings, sum(r["solver"] == "event-driven" for r in rows))
             if args.timings else [])
        measured.write(os.path.join(args.out, readme.MEASURED), quoted)
    if os.path.exists(os.path.join(args.out, readme.MEASURED)):
        quoted = load([os.path.join(args.out, readme.MEASURED)])  # as README reads it back
    out = report_of.Output(args.out, "poundbench report")

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
             "(*Failed runs*).",
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
    text += ["The studies to explore in a browser (the answer for any scene and target, the diagrams and spectra "
             "with every value on hover): [report.html](report.html), one file that works offline, written "
             "by the main job beside this page and committed with it (download it and open it: it carries the "
             "data and `page.js`/`page.css` inline, whose sources are here).", ""]
    if wp_study:
        write_families(wp_study.points, os.path.join(args.out, readme.FAMILIES))
        for section in report_of.SECTIONS["workprecision"]:
            text += section(wp_study, out)
        write_impacting(out.impacting, os.path.join(args.out, readme.IMPACTING))
    if args.compliant:
        text += compliant.section(load([args.compliant]), load([args.compliant_points]), args.out)
    if stress_study:
        text += stress_section(stress_study, out)
    if quoted:
        text += bench_section(args.bench, quoted, summary, stress, measured_on)
    if args.records:
        import records
        text += records.section(load(args.records), args.out)
    if args.yielding:
        import yielding
        text += yielding.section(load(args.yielding), args.out)
    if args.records_real:
        import records_real
        text += records_real.section(load([args.records_real]), args.out)
    if args.records_wp:
        import records_wp
        text += records_wp.section(load([args.records_wp]))
    if args.yielding_wp:
        import yielding_wp
        text += yielding_wp.section(load([args.yielding_wp]))
    if args.records_step:
        import records_step
        runs = records_step.compact(load([args.records_step]))
        records_step.write(os.path.join(args.out, records_step.SUMMARY), runs)
        text += records_step.section(runs)
    if args.buildings:
        import buildings
        text += buildings.section(load(args.buildings), args.out,
                                  load(args.buildings_stress) if args.buildings_stress else None)
    if args.separation:
        import separation
        text += separation.section(load([args.separation]), args.out)
    text += paper_set_section(rows, args.out)
    text += ["## Where this ran", "", footer(measured_on), ""]
    out.page.provenance([f"- measured at: {provenance.describe(measured_on)}"])
    out.page.write(os.path.join(args.out, "report.html"))
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
    parser.add_argument("--yielding", nargs="+", help="rows of `poundbench spectrum cases/sets/yielding.toml` "
                        "through the reference and Moreau-Jean (scripts/main.sh: results/yielding-*.csv)")
    parser.add_argument("--records-real", help="rows of `poundbench spectrum cases/sets/records-real.toml --solver "
                        "event-driven` (scripts/main.sh: results/real-records-event-driven.csv)")
    parser.add_argument("--records-wp", help="summary CSV of the time-steppers on the real record suite (`poundbench "
                        "workprecision cases/sets/workprecision-records.toml --settings cases/settings/records.toml`)")
    parser.add_argument("--yielding-wp", help="summary CSV of the time-steppers on yielding bodies (`poundbench "
                        "workprecision cases/sets/workprecision-yielding.toml --settings cases/settings/yielding.toml`)")
    parser.add_argument("--records-step", help="points CSV of the step rules on real records (`poundbench "
                        "workprecision cases/sets/records-step.toml --settings cases/settings/records-step.toml --points`; "
                        "reduced to reports/records-step.csv)")
    parser.add_argument("--buildings", nargs="+", help="rows of `poundbench spectrum cases/sets/buildings.toml` "
                        "through the reference and the other solvers of the scene (one file each)")
    parser.add_argument("--buildings-stress", nargs="+", help="rows of `poundbench spectrum "
                        "cases/sets/buildings-stress.toml` through the solvers of the scene (one file each)")
    parser.add_argument("--separation", help="per-case table of `poundbench separation cases/sets/separation.toml "
                        "--gap-fractions ...` (scripts/main.sh: results/separation.csv)")
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
