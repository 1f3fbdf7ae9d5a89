#!/usr/bin/python3
"""The report of one study, whoever's it is: markdown (README.md), figures (figures/*.png)
and a page to explore it in a browser (report.html, one file that works offline). What
`poundbench report` runs, and what the main job's report (make_report.py) is made of for
its own studies: one generator.

    report.py STUDY.csv [--points POINTS.csv] --out DIR [--title TEXT]

STUDY.csv is what a poundbench study wrote: the summary of `poundbench workprecision` or of
`poundbench stress` (--out), with its per-run rows (--points) for the spectra, the scenes,
the errors over impacting points and the failures' messages; or the rows of `poundbench
spectrum`. A section is a function of the study and the output (SECTIONS, by kind), so that
a new measure adds a function to a list."""

import argparse
import datetime
import hashlib
import os
import platform
import sys
import traceback

import answer
import page as html
from out_folder import OutputError, Staging
from rows import by_family, config_label, md_cell, md_text, setting_label, steps_of
from study import InputError, Study, impacting_errors, spectrum_summary


class Output:
    """Where a report goes: its folder (figures/ in it), and the page collecting its parts."""

    def __init__(self, out_dir, title):
        self.dir = out_dir
        self.page = html.Page(title)
        self.impacting = None  # the errors over impacting points, once computed
        self.styles = None  # each configuration's line style (wp.setting_styles), once computed

    def setting_styles(self, summary):
        """Each configuration's line style, the same in every figure and on the page."""
        if self.styles is None:
            import wp
            self.styles = wp.setting_styles(summary)
            self.page.styles(self.styles)
        return self.styles


# A report draws the figures of its first MAX_FAMILY_FIGURES families, in each section that
# has a figure per family: a figure costs some 0.05 s of a core (a 64-figure study's report: 4.3 s,
# its start included), so a study of 1,000 families would spend minutes on figures that nobody
# pages through.
# report.html draws every family from the study's rows.
MAX_FAMILY_FIGURES = 40


def figure_lines(family, figures):
    """A family's figures in markdown: its heading, then each (panel, figure path)."""
    lines = [f"### {md_text(family)}", ""]
    for panel, figure in figures:
        lines += [f"![{md_text(family)}: {md_text(panel)}]({figure})", ""]
    return lines


def left_out_lines(families):
    """What a section says of the families past MAX_FAMILY_FIGURES, if any."""
    left = len(families) - MAX_FAMILY_FIGURES
    return [f"The figures above are the first {MAX_FAMILY_FIGURES} families'; report.html draws the other {left} "
            "from the study's rows (choose a family there).", ""] if left > 0 else []


# ---------------------------------------------------------------- work-precision studies

def answer_section(study, out):
    summary = study.rows
    scenes = study.scenes if study.has_scenes() else {}
    impacting = impacting_errors(study) if study.points else None
    out.impacting = impacting
    lines = ["## Which setting for which accuracy", "", answer.rule(summary, impacting is not None), ""]
    if not scenes:
        lines += ["Without the study's points (--points) the scene of each family is not known: each family is "
                  "a scene of its own here, and the errors over impacting points are not given.", ""]
    lines += [*answer.answer_tables(summary, scenes, impacting), ""]
    out.page.answer(summary, answer.scopes(summary, scenes), impacting)
    return lines


def beats_section(study, out):
    summary = study.rows
    if not any(r["solver"] == answer.IN_HOUSE for r in summary) or \
            not any(r["solver"] != answer.IN_HOUSE and not answer.is_event_driven(r) for r in summary):
        return []
    table = answer.beats_table(summary)
    out.page.table("Where another scheme beats the in-house Moreau–Jean", table)
    return ["## Where another scheme beats the in-house Moreau–Jean", "",
            "Per family and target (the median of the relative Pi1 error, no failed or unresolved run; a step meets "
            "it when every finer step of its configuration does too, as in the answer), the in-house "
            "`moreau-jean`'s cheapest setting that meets it and its coarsest step, against every other "
            "time-stepper configuration of the study: those that meet the target at less CPU per run, and those "
            "that meet it with a coarser step given alike (fewer steps per shortest period N, or a longer step in "
            "seconds). The steps compare the schemes apart from what their code costs a step.", "", *table, ""]


def failures_section(study, out):
    """Every setting with runs that did not end ok: from the points, with the first one's
    message; from the summary alone, the counts."""
    if study.points:
        table = answer.failure_table(study.points)
        why = "and the message of the first: the cause its solver names (`solvers/*/README.md` say more)"
    else:
        failed = [r for r in study.rows if int(r["failed"]) > 0]
        table = ["| setting | family | failed |", "|---|---|---:|"] + [
            f"| {md_cell(setting_label(r))} | {md_cell(r['family'])} | {r['failed']} of {r['points']} |"
            for r in failed] if failed else []
        why = "(the study's --points say why)"
    if not table:
        return ["## Failed runs", "", "Every run of the study finished ok.", ""]
    out.page.table("Failed runs", table)
    return ["## Failed runs", "", f"Every setting of the study with runs that did not end ok, how many, {why}. A "
            "setting that failed on every point has no line in the diagrams.", "", *table, ""]


def unresolved_section(study, out):
    """Every setting with runs that ended ok without resolving what they solved (their rows'
    `resolved` false): how many, and the first one's reasons. Nothing when there are none."""
    table = answer.unresolved_table(study.points) if study.points else []
    if not table:
        return []
    out.page.table("Unresolved runs", table)
    return ["## Unresolved runs", "", "Every setting with runs that ended ok but whose own measurements say they did "
            "not resolve what they solved (`resolved` false in their rows, `kit/verdict.hpp`), and the reasons of "
            "the first. No table above ranks them; the diagrams draw them hollow.", "", *table, ""]


def diagrams_section(study, out):
    import wp

    summary = study.rows
    spread = any(answer.has_spread(r) for r in summary)
    text = ["## Work-precision diagrams", "",
            "Relative Pi1 error against median CPU time per run, over the points of a family; each line is one "
            "solver configuration over its step counts N (steps per shortest period). A figure per family and "
            "solver family, the median of the error on the left and its 95th percentile on the right, the other "
            "solvers in light grey behind; the thick grey band is the Pareto front over every solver (the "
            "settings no other setting beats in both cost and error; settings with failed or unresolved runs are "
            "not candidates, and are drawn hollow). Errors below "
            f"{wp.ERROR_FLOOR:g} are round-off: they are drawn in the shaded band under it, one row per setting, so "
            "that none hides another." + (" Horizontal bars: the lowest and highest CPU time of the timing "
                                         "repetitions." if spread else ""), ""]
    families = list(dict.fromkeys(r["family"] for r in summary))
    styles = out.setting_styles(summary)
    for family, figures in wp.wp_diagrams(summary, out.dir, set(families[:MAX_FAMILY_FIGURES]), styles):
        text += figure_lines(family, figures)
    text += left_out_lines(families)
    out.page.diagrams(summary, wp.panels_of)
    table = answer.cost_table(summary)
    if len(table) > 2:
        text += ["## Cost per run", "", f"At N = {answer.MIDDLE_N}, as a ratio to the in-house Moreau-Jean stepper "
                 "(theta = 1/2) on the same points (median CPU time per run"
                 + (", in brackets the low-high of the repetitions" if spread else "") + "):", "", *table, ""]
        out.page.table("Cost per run", table)
    return text


def spectra_section(study, out):
    if not study.points:
        return []
    import wp

    families = list(dict.fromkeys(r["family"] for r in study.points))
    figures = wp.wp_spectra(study.points, out.dir, set(families[:MAX_FAMILY_FIGURES]),
                            out.setting_styles(study.rows))
    if not figures:
        return []
    n = figures[0][1]
    text = ["## Spectra and where they go wrong", "",
            f"Each configuration at N = {n} steps per shortest period (those without a step at their one setting) "
            "over the reference (black: rigid contact, 100x tighter tolerances), and its relative error along Pi2; "
            "a figure per family and solver family, a column per pulse and Pi5. A Pi1 axis is logarithmic where the "
            "reference spans more than one and a half decades.", ""]
    for family, _, panels in figures:
        text += figure_lines(family, panels)
    text += left_out_lines(families)
    out.page.spectra(study.points, n, wp.panel_of, wp.panel_rank)
    return text


# ---------------------------------------------------------------- stress studies

def stress_sections(study, out, about=None, reading=None):
    """The stress study's checks: the verdicts per family and setting, each configuration's
    failures in short, and (with the points) the figures against w_max h and the chain's size.
    `about`: what the case set and the settings are (the main job's words for its own)."""
    import stability

    summary = study.rows
    tol = stability.tolerances()
    checks = stability.checks_of(summary)
    steps = stability.steps_sentence(summary)

    def bound(name, text, offset=0.0):
        return text.format(tol[name] - offset) if name in tol else "(its bound: `studies/stress.hpp`)"

    lines = ["## Stability on stiff and extreme cases", "",
             (about or f"Every case of `{study.name}`'s case set through every setting of its list"
              + (f", the time-steppers at w_max h ({steps})" if steps else "") + ".")
             + f" {len(checks)} checks per family and setting (tolerances in `studies/stress.hpp`):", "",
             "* **finite**: every run ends with status ok and a finite Pi1;",
             "* **energy**: the mechanical energy never exceeds the start's energy plus the work of the ground "
             "load, to " + bound("kEnergyTolerance", "{:g} of the energy scale") + ";",
             "* **gap**: a time-stepper overlaps by at most one step of travel ("
             + bound("kPenetrationSteps", "to {:.0e}, room for round-off", 1.0) + ") at its fastest gap rate, h max|g'|; "
             "the reference, by at most " + bound("kReferencePenetration", "{:g} a_p/w_p^2") + ";",
             "* **restitution**: every isolated impact restitutes eps to " + bound("kRestitutionTolerance", "{:g}")
             + (";" if "accuracy" in checks else "."),
             *(["* **accuracy**: Pi1 and the impacts against the truth's (the rule: `studies/stress.hpp`; the worst "
                "95th percentile of the Pi1 error shown)."] if "accuracy" in checks else []), "",
             "Energy, gap and restitution judge the finished runs only, so a diverged run counts once.", ""]
    lines += reading or []
    figure, (settings_left, families_left) = stability.verdict_figure(summary, out.dir)
    left = " and ".join(f"{n} more {what}" for n, what in ((settings_left, "settings"), (families_left, "families"))
                        if n)
    lines += ["In short, per solver configuration over every family and step (worst values over the failing "
              "cells):", "", *stability.stability_summary(summary), "",
              "Per family and setting" + (f" (the first of them: the page report.html has the {left})" if left else "")
              + ":", "", f"![stress verdicts]({figure})", "",
              f"The numbers behind every cell (runs, finished runs, worst energy excess, penetration and restitution "
              f"error, errors and cost): `{study.name}`, one line per family and setting"
              + ("; every run's row in `poundbench stress --points`." if about else
                 f"; every run's row in `{os.path.basename(study.points_path)}`." if study.points_path else ".")
              + " Penetration has one scale there and in every row, `a_p / w_p^2` (`penetration_max`, the rows' "
              "`penetration` and `min_gap`), and the gap check's per-step overlap besides (`penetration_steps_max`: "
              "over one step of travel, `h max|g'|`, which the figure against the step plots).", ""]
    out.page.verdicts(summary, checks, stability.table_config)
    if study.points:
        figure = stability.large_step_figure(study.points, out.dir)
        if figure:
            lines += ["### Against the step", "", "Penetration over one step of travel at the run's fastest gap "
                      "rate, h max|g'| (the gap check's measure).", "", f"![large steps]({figure})", ""]
        figure = stability.chain_cost_figure(study.points, out.dir)
        if figure:
            lines += ["### Chain: cost against the number of bodies", "", f"![chain cost]({figure})", ""]
    return lines


# ---------------------------------------------------------------- spectrum rows

def spectrum_sections(study, out):
    """A spectrum's rows: per family, its points, failures, impacts and cost; its spectra (a
    figure per family: a column per directivity, a row per pulse); the failed points."""
    import spectra

    rows = study.rows
    table = ["| family | solver setting | points | failed | impacts (median) | CPU per point, median (us) | "
             "total CPU (s) |", "|---|---|---:|---:|---:|---:|---:|"]
    for s in spectrum_summary(rows):
        setting = config_label(s) if steps_of(s) is None else setting_label(s)
        table.append(f"| {md_cell(s['family'])} | {md_cell(setting)} | "
                     f"{s['points']} | {s['failed']} | {s['impacts']:.0f} | {1e6 * s['cpu']:.1f} | "
                     f"{s['total_cpu']:.2f} |")
    out.page.table("Families", table)
    text = ["## Families", "", *table, ""]
    failures = answer.failure_table(rows)
    if failures:
        text += ["## Failed points", "", *failures, ""]
        out.page.table("Failed points", failures)
    text += ["## Pi-spectra", "", "Pi1 of body 0 against Pi2, per family: a row of panels per pulse, a column per "
             "directivity; dashed grey, the same case with every contact removed.", ""]
    for family, frows in list(by_family(rows).items())[:MAX_FAMILY_FIGURES]:
        if len({r["pi2"] for r in frows}) <= 1:
            continue  # not a spectrum over Pi2
        figure, note = spectra.plot_family(family, frows, out.dir)
        text += [f"### {md_text(family)}", "", f"![{md_text(family)}]({figure})", ""] + ([note, ""] if note else [])
    text += left_out_lines(study.families)
    out.page.curves(rows)
    return text


SECTIONS = {
    "workprecision": [answer_section, beats_section, failures_section, unresolved_section, diagrams_section,
                      spectra_section],
    "stress": [stress_sections],
    "spectrum": [spectrum_sections],
}


# ---------------------------------------------------------------- the whole report

def file_line(path):
    """A file as the provenance names it: its name, size, rows, when it was written, its SHA-256."""
    with open(path, "rb") as f:
        data = f.read()
    written = datetime.datetime.fromtimestamp(os.path.getmtime(path), datetime.timezone.utc)
    rows = max(data.count(b"\n") - 1, 0)
    return (f"`{path}`: {len(data)} bytes, {rows} rows, written "
            f"{written.strftime('%Y-%m-%d %H:%M UTC')}, SHA-256 {hashlib.sha256(data).hexdigest()[:16]}")


def provenance_lines(study, made_by):
    import matplotlib

    lines = ["## Provenance", "", f"- study: {file_line(study.path)}"]
    if study.points_path:
        lines.append(f"- points: {file_line(study.points_path)}")
    lines += [f"- made by: {made_by}, `{os.path.abspath(__file__)}`, on "
              f"{datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}",
              f"- with: Python {platform.python_version()}, matplotlib {matplotlib.__version__}, "
              f"{platform.machine()} {platform.system()}", ""]
    return lines


KIND_TITLES = {"workprecision": "Work-precision study", "stress": "Stress study", "spectrum": "Spectra"}


def intro(study):
    families = len(study.families)
    if study.kind == "spectrum":
        solvers = sorted({config_label(r) for r in study.rows})
        named = ", ".join(f"`{' '.join(s.splitlines())}`" for s in solvers[:20]) + \
            (f" and {len(solvers) - 20} more" if len(solvers) > 20 else "")
        return (f"{len(study.rows)} points in {families} families through {named}. "
                "Pi1 is the peak displacement of body 0 in Pi terms (cases/README.md).")
    settings = len({(r["solver"], r["variant"], r["settings"]) for r in study.rows})
    return (f"{families} families through {settings} solver settings. Errors are relative Pi1 errors "
            "against the study's truth, the reference solved with its settings list's tolerances "
            "(100x tighter than its default unless the list says otherwise); times are CPU time of the solve "
            "alone, per run." + ("" if study.points else " No --points were given: no spectra, scenes or "
                                 "failure messages."))


def write(study, out_dir, title=None, made_by="poundbench report"):
    """The whole report of one study into out_dir: README.md, figures/, report.html. Returns
    how many figures README.md shows."""
    os.makedirs(os.path.join(out_dir, "figures"), exist_ok=True)
    title = title or f"{KIND_TITLES[study.kind]}: {study.name}"
    out = Output(out_dir, title)
    text = [f"# {md_text(title)}", "", intro(study), "",
            "The same study to explore in a browser, hovering, filtering and choosing a target: "
            "[report.html](report.html) (one file, works offline).", ""]
    for section in SECTIONS[study.kind]:
        text += section(study, out)
    text += provenance_lines(study, made_by)
    out.page.provenance(text[text.index("## Provenance") + 2:])
    out.page.write(os.path.join(out_dir, "report.html"))
    from rows import write_page
    write_page(out_dir, text)
    return sum(line.startswith("![") for line in text)


def need_matplotlib():
    """matplotlib for this interpreter, or one line saying what is missing and exit 1."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        sys.exit(f"poundbench: report: {sys.executable} has no matplotlib (Debian: python3-matplotlib; "
                 "scripts/setup.sh installs it)")


def bug_line(e):
    """An exception no input should cause, as one line saying where it was raised."""
    where = traceback.extract_tb(e.__traceback__)[-1]
    text = " ".join(str(e).splitlines())
    return (f"poundbench: report: internal error at {os.path.basename(where.filename)}:{where.lineno}: "
            f"{type(e).__name__}: {text[:160]} (a bug of the report; nothing was written to --out)")


def report(args):
    """Reads the study, writes its report into a folder of its own and moves it into --out
    (out_folder.py). Returns the exit code: 0, 2 (a bad input or --out: one line), 1 (a bug:
    one line)."""
    staging = None
    try:
        study = Study(args.study, args.points)
        staging = Staging(args.out, [("STUDY", args.study), ("--points", args.points)])
        figures = write(study, staging.path, args.title, args.made_by)
        staging.publish()
    except (InputError, OutputError) as e:
        print(f"poundbench: {e}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001: one line instead of a traceback, and --out left as it was
        print(bug_line(e), file=sys.stderr)
        return 1
    finally:
        if staging is not None and staging.path is not None:
            staging.remove()
    print(f"poundbench: report: wrote {os.path.join(args.out, 'README.md')}")
    print(f"poundbench: report: wrote {os.path.join(args.out, 'report.html')} and {figures} figures in "
          f"{os.path.join(args.out, 'figures')}")
    return 0


def main():
    parser = argparse.ArgumentParser(prog="poundbench report", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("study", metavar="STUDY.csv", help="a study's output: `workprecision --out`, `stress --out`, "
                        "or `spectrum`'s rows")
    parser.add_argument("--points", help="the study's per-run rows (`workprecision --points`, `stress --points`)")
    parser.add_argument("--out", required=True, help="the report's folder (created; README.md, figures/, report.html)")
    parser.add_argument("--title", help="the report's title (default: the kind of study and the file's name)")
    parser.add_argument("--made-by", default="reports/report.py", help=argparse.SUPPRESS)
    args = parser.parse_args()
    need_matplotlib()
    sys.exit(report(args))


if __name__ == "__main__":
    main()
