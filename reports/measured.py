"""The numbers README's "Measured" table quotes: picked from the benchmarks' JSON
(results/bench.json) and the main job's step times (results/timings.csv) into a small CSV
that is committed (reports/measured.csv), and the table written from that CSV. No
matplotlib here."""

import csv
import json
import math
import re
from collections import defaultdict

from rows import median, num, settings_fields

COLUMNS = ["name", "measure", "median", "low", "high", "repetitions", "unit"]

# What README quotes: benchmark names (a regular expression on the run's name) and the
# measures of each (cpu_time, or a counter). cpu_time is stored in seconds.
QUOTED = [
    (r"BM_EventDrivenFig4FamilyPerPoint", ("median_us", "points")),
    (r"BM_MoreauJeanStepLoop(Pair|Row3)/monitor:\d", ("time_per_step",)),
    (r"BM_Fig4MoreauJeanToMedianError1e3", ("cpu_time", "steps_N", "median_error", "points")),
    (r"BM_Fig4ReferenceSamePoints", ("cpu_time",)),
    (r"BM_Ode/\w+/N:64", ("x_moreau_jean",)),
    (r"BM_Bullet/[\w-]+/\w+/N:64", ("vs_moreau_jean",)),
    (r"BM_Siconos/\w+/N:64", ("x_moreau_jean",)),
    (r"BM_Mujoco/\w+/N:64", ("x_moreau_jean",)),
    (r"BM_Dart/\w+/N:64", ("x_moreau_jean",)),
    (r"BM_Simbody/\w+/N:64", ("x_moreau_jean",)),
    (r"BM_SimbodyHuntCrossley/\w+", ("x_compliant",)),
    (r"BM_SiconosScheme/\w+/N:64", ("x_moreau_jean", "x_siconos_moreau_jean")),
    (r"BM_SiconosEventDriven/\w+", ("x_event_driven",)),
    (r"BM_SweepFig4Reference/threads:\d(/real_time)?", ("points_per_s",)),
    (r"BM_PaperSetThreadScaling/iterations:1/real_time", ("speedup",)),
    (r"BM_External(PairInProcess|PairThroughAdapter|ProtocolFloor)/real_time", ("real_time",)),
]
UNITS = {"cpu_time": "s", "real_time": "s", "time_per_step": "s", "median_us": "us", "points_per_s": "1/s",
         "x_moreau_jean": "ratio", "vs_moreau_jean": "ratio", "x_event_driven": "ratio",
         "x_siconos_moreau_jean": "ratio", "speedup": "ratio", "x_compliant": "ratio"}
TO_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def value_of(run, measure):
    if measure in ("cpu_time", "real_time"):
        return run[measure] * TO_SECONDS[run.get("time_unit", "ns")]
    return run.get(measure)


def from_bench(path):
    """The quoted measures of every quoted benchmark: the median, lowest and highest over its
    repetitions where the JSON has them (not with --benchmark_report_aggregates_only: then
    only the median aggregate, and no spread)."""
    with open(path) as f:
        runs = [b for b in json.load(f).get("benchmarks", []) if not b.get("error_occurred")]
    repetitions = defaultdict(list)
    aggregates = {}
    for b in runs:
        # A benchmark that sets its own repetitions is named with them ("/repeats:3"): the
        # same benchmark as at the main job's default, under the name the tables quote.
        name = re.sub(r"/repeats:\d+", "", b.get("run_name", b["name"]))
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                aggregates[name] = b
        else:
            repetitions[name].append(b)
    out = []
    for name in dict.fromkeys([*repetitions, *aggregates]):
        measures = next((m for pattern, m in QUOTED if re.fullmatch(pattern, name)), ())
        for measure in measures:
            values = [v for v in (value_of(b, measure) for b in repetitions.get(name, [])) if v is not None]
            if values:
                row = [median(values), min(values), max(values), len(values)]
            elif name in aggregates and value_of(aggregates[name], measure) is not None:
                row = [value_of(aggregates[name], measure), "", "", aggregates[name].get("repetitions", "")]
            else:
                continue
            out.append(dict(zip(COLUMNS, [name, measure, *row, UNITS.get(measure, "")])))
    return out


def from_timings(path, paper_points):
    """The main job's steps (results/timings.csv: step, wall_s; a step run several times has a
    line per run): per step its median wall time with the fastest and slowest run, and the
    sum of its runs (what it added to the main job); the number of points of the paper case
    set beside its sweep."""
    with open(path, newline="") as f:
        walls = {}
        for s in csv.DictReader(f):
            walls.setdefault(s["step"], []).append(float(s["wall_s"]))
    out = []
    for step, runs in walls.items():
        spread = (min(runs), max(runs)) if len(runs) > 1 else ("", "")
        out.append(dict(name=f"main.sh/{step}", measure="wall", median=median(runs), low=spread[0], high=spread[1],
                        repetitions=len(runs), unit="s"))
        out.append(dict(name=f"main.sh/{step}", measure="wall_sum", median=sum(runs), low="", high="", repetitions=1,
                        unit="s"))
    if paper_points:
        out.append(dict(name="main.sh/paper-reference", measure="points", median=paper_points, low="", high="",
                        repetitions=1, unit=""))
    return out


def write(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, COLUMNS, lineterminator="\n")
        writer.writeheader()
        for r in rows:
            writer.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in r.items()})


# ---------------------------------------------------------------- the table

def sig(v, digits=2):
    """v to `digits` significant digits, without an exponent for ordinary magnitudes."""
    if not math.isfinite(v) or v == 0 or not 1e-3 <= abs(v) < 1e6:
        return f"{v:.{digits}g}"
    return f"{float(f'{v:.{digits}g}'):g}"


def spread(row, show):
    """ (median of N runs, low–high) for a row of several runs, each end written by show;
    nothing for one run."""
    if row["low"] == "" or int(row["repetitions"]) < 2:
        return ""
    return f" (median of {row['repetitions']} runs, {show(num(row, 'low'))}–{show(num(row, 'high'))})"


def span(values, digits=2):
    lo, hi = sig(min(values), digits), sig(max(values), digits)
    return lo if lo == hi else f"{lo}–{hi}"


class Measured:
    """The rows of measured.csv by name and measure."""

    def __init__(self, rows):
        self.rows = rows

    def get(self, name, measure):
        return next((num(r, "median") for r in self.rows if r["name"] == name and r["measure"] == measure), None)

    def row(self, name, measure):
        return next((r for r in self.rows if r["name"] == name and r["measure"] == measure), None)

    def matching(self, pattern, measure):
        return [num(r, "median") for r in self.rows if re.fullmatch(pattern, r["name"]) and r["measure"] == measure]


def external_lines(measured):
    """What the external protocol costs a point, against the same solve in process
    (solvers/external/external_bench.cpp, wall time): one sentence, or none without the benchmarks."""
    m = Measured(measured)
    inproc, adapter, floor = (m.get(f"BM_External{n}/real_time", "real_time")
                              for n in ("PairInProcess", "PairThroughAdapter", "ProtocolFloor"))
    if None in (inproc, adapter, floor):
        return ["Not measured: the main job's benchmarks did not run the external solver's."]
    return [f"What the protocol costs a point (`solvers/external/external_bench.cpp`, medians, wall time, the Fig. 4 pair "
            f"through moreau-jean at N = 64): {sig(1e3 * floor)} ms for a program that only answers (a spawn, the "
            f"pipes, both documents, the wait), {sig(1e3 * adapter)} ms for poundbench itself as the program (its "
            f"own start included), against {sig(1e6 * inproc)} us for the same solve in process."]


def study_size(summary, count="points"):
    """The size of a study, from its summary rows: "C cases through S settings", and "and the
    truth" where the truth is not among the rows (work-precision) or is one of them without
    an error against itself (stress)."""
    settings = defaultdict(list)
    for r in summary:
        settings[(r["solver"], r["variant"], r["settings"])].append(r)
    cases = sum(int(r[count]) for r in next(iter(settings.values())))
    truth = [k for k, rows in settings.items() if "pi1_err_median" in rows[0]
             and all(r["pi1_err_median"] == "" for r in rows)]
    return f"{cases} cases through {len(settings) - len(truth)} settings and the truth"


def minutes(seconds):
    return f"{sig(seconds, 2)} s" if seconds < 120 else f"{sig(seconds / 60, 2)} min"


def table(measured, workprecision, stability, provenance):
    """Markdown lines: what was measured, the number, the target where there is one, and
    whether it is met. A row whose numbers are missing from the results is left out."""
    m = Measured(measured)
    rows = []

    def add(what, value, target="", met=None):
        rows.append(f"| {what} | {value} | {target} | {'' if met is None else 'yes' if met else '**no**'} |")

    per_point, points = m.get("BM_EventDrivenFig4FamilyPerPoint", "median_us"), \
        m.get("BM_EventDrivenFig4FamilyPerPoint", "points")
    if per_point is not None:
        add(f"reference, one `pair` point of the Fig. 4 family (median over {points:.0f} points)",
            f"{sig(per_point)} us", "<= 11 us (a third of 33 us)", per_point <= 11)
    wall, paper = m.get("main.sh/paper-reference", "wall"), m.get("main.sh/paper-reference", "points")
    if wall is not None and paper is not None:
        runs = spread(m.row("main.sh/paper-reference", "wall"), lambda v: sig(v, 3))
        add(f"whole paper case set ({paper:.0f} points), `poundbench spectrum` from the shell, reference, "
            f"{provenance['cores']} cores", f"{sig(wall, 3)} s{runs}", "<= 0.3 s", wall <= 0.3)
    pair = m.matching(r"BM_MoreauJeanStepLoopPair/.*", "time_per_step")
    row3 = m.matching(r"BM_MoreauJeanStepLoopRow3/.*", "time_per_step")
    if pair and row3:
        add("Moreau–Jean, `pair` / `row3`, per step (one core; without and with the monitor)",
            f"{span([1e9 * v for v in pair])} / {span([1e9 * v for v in row3])} ns", "<= 20 / 40 ns",
            max(pair) <= 20e-9 and max(row3) <= 40e-9)
    steps = [(m.get(f"BM_MoreauJeanStepLoop{scene}/monitor:1", "time_per_step"),
              m.get(f"BM_MoreauJeanStepLoop{scene}/monitor:0", "time_per_step")) for scene in ("Pair", "Row3")]
    if all(on and off for on, off in steps):
        monitored = [on / off for on, off in steps]
        add("Moreau–Jean, the monitored step over the unmonitored one, `pair` / `row3`",
            f"{monitored[0]:.2f}x / {monitored[1]:.2f}x", "<= 1.5x", max(monitored) <= 1.5)
    mj, ref = m.get("BM_Fig4MoreauJeanToMedianError1e3", "cpu_time"), m.get("BM_Fig4ReferenceSamePoints", "cpu_time")
    if mj is not None and ref is not None:
        steps, err = m.get("BM_Fig4MoreauJeanToMedianError1e3", "steps_N"), \
            m.get("BM_Fig4MoreauJeanToMedianError1e3", "median_error")
        faster = f"{sig(ref / mj)}x faster" if ref >= mj else f"{sig(mj / ref)}x slower"
        add(f"Moreau–Jean at median Pi1 error <= 1e-3 on the Fig. 4 family (the smallest N doubling from 16: "
            f"N = {steps:.0f}, median error {err:.2g}), against the reference on the same "
            f"{m.get('BM_Fig4MoreauJeanToMedianError1e3', 'points'):.0f} points (CPU time)",
            f"{sig(1e3 * mj)} ms vs {sig(1e3 * ref)} ms ({faster})")
    for what, pattern, measure in (("ODE, cost per step as a ratio to Moreau–Jean (every variant on wall, pair, "
                                    "row3; N = 64)", r"BM_Ode/.*", "x_moreau_jean"),
                                   ("Bullet, same", r"BM_Bullet/.*", "vs_moreau_jean"),
                                   ("Siconos' `MoreauJeanOSI`, same (Lemke and enumeration)", r"BM_Siconos/.*",
                                    "x_moreau_jean"),
                                   ("MuJoCo, same (Euler, implicit, RK4 and default; a run's model compilation "
                                    "included)", r"BM_Mujoco/.*", "x_moreau_jean"),
                                   ("DART, same (faithful by Dantzig and PGS, and default)", r"BM_Dart/.*",
                                    "x_moreau_jean"),
                                   ("Simbody, same (faithful by PLUS and PGS, and default)", r"BM_Simbody/.*",
                                    "x_moreau_jean"),
                                   ("Simbody's Hunt–Crossley elements, cost per run as a ratio to the compliant "
                                    "solver's Hunt–Crossley element through CVODE (wall, pair, row3; K = 1e4)",
                                    r"BM_SimbodyHuntCrossley/.*", "x_compliant")):
        values = m.matching(pattern, measure)
        if values:
            add(what, f"{span(values)}x")
    schemes = m.matching(r"BM_SiconosScheme/.*", "x_moreau_jean")
    over_osi = m.matching(r"BM_SiconosScheme/.*", "x_siconos_moreau_jean")
    if schemes and over_osi:
        add("Siconos' other integrators (Schatzman–Paoli, D1MinusLinear, combined and direct projection), same; "
            "and over its `MoreauJeanOSI` (Lemke)", f"{span(schemes)}x; {span(over_osi)}x")
    lsodar = m.matching(r"BM_SiconosEventDriven/.*", "x_event_driven")
    if lsodar:
        wp = [r for r in workprecision
              if r["variant"] == "event-driven-lsodar" and settings_fields(r).get("tol_scale") == 1]
        errors = ""
        if wp:
            failed, runs = sum(int(r["failed"]) for r in wp), sum(int(r["points"]) for r in wp)
            errors = (f"; {sig(max(num(r, 'err_median') for r in wp))}, {sig(max(num(r, 'err_max') for r in wp))}; "
                      f"{failed} of {runs}")
        add("Siconos' event-driven LSODAR, cost per run as a ratio to the reference (wall, pair, row3)"
            + ("; at tol_scale = 1 in the work-precision study, the largest median and max relative Pi1 error of a "
               "family where it runs to the end, and the runs that fail" if wp else ""), f"{span(lsodar)}x{errors}")
    scaling = m.row("BM_PaperSetThreadScaling/iterations:1/real_time", "speedup")
    if scaling:
        speedup = num(scaling, "median")
        add("sweep on 2 threads against 1 (the whole paper set through the reference, the two alternated in one "
            "run; wall time)", f"{speedup:.2f}x{spread(scaling, lambda v: f'{v:.2f}')}", ">= 1.8x", speedup >= 1.8)
    timed = {r["name"].split("/", 1)[1]: num(r, "median") for r in measured
             if r["name"].startswith("main.sh/") and r["measure"] == "wall"}
    spent = {r["name"].split("/", 1)[1]: num(r, "median") for r in measured
             if r["name"].startswith("main.sh/") and r["measure"] == "wall_sum"}
    if "workprecision" in timed and workprecision:
        add(f"work-precision study ({study_size(workprecision)}), {provenance['cores']} cores",
            minutes(timed["workprecision"]))
    if "stress" in timed and stability:
        add(f"stress study ({study_size(stability, 'runs')}), {provenance['cores']} cores", minutes(timed["stress"]))
    if timed:
        total = sum(spent.get(step, wall) for step, wall in timed.items())
        add("`scripts/main.sh`'s sweeps, studies and benchmarks (" + ", ".join(timed) + "; set-up and reports "
            "not included)", minutes(total), "<= 5 min", total <= 300)
    return ["| what | measured | target | met |", "|---|---|---|---|"] + rows
