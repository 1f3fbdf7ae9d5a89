"""Which setting to use: for each target error, the cheapest setting of the work-precision
study that meets it (by the one rule of robust.py: it and every finer step of its solver and
variant), per scene and over every family. Read off the study's summary rows
(workprecision.csv); no matplotlib, so README's check runs in a blink."""

import heapq
from collections import defaultdict

import robust
from rows import by_family, config_label, md_cell, num, setting_label, settings_fields, steps_of

MIDDLE_N = 64  # the step count of the cost table and of the spectra drawn against the reference
TARGETS = [1e-1, 1e-2, 1e-3, 1e-4]
ERRORS = (("err_median", "median"), ("err_p95", "95th percentile"))


def is_event_driven(row):
    """The reference, or another solver's event-driven variant (siconos event-driven-lsodar)."""
    return row["solver"] == "event-driven" or row.get("variant", "").startswith("event-driven")


def has_spread(row, key="cpu_median"):
    """Whether a row carries the low and high of its timing repetitions (KEY_low_s, KEY_high_s)."""
    return row.get(f"{key}_low_s", "") not in ("", None) and row.get(f"{key}_high_s", "") not in ("", None)


def us(seconds):
    """Microseconds to three significant digits, without an exponent."""
    v = 1e6 * seconds
    return f"{v:.0f}" if v >= 100 else f"{v:.1f}" if v >= 10 else f"{v:.2f}"


def cost_cell(row):
    """A row's median CPU time per run in us, with the low-high of its repetitions when the
    row has them (none is drawn otherwise)."""
    text = us(num(row, "cpu_median_s"))
    if has_spread(row):
        text += f" ({us(num(row, 'cpu_median_low_s'))}–{us(num(row, 'cpu_median_high_s'))})"
    return text


CONTACT_NAMES = {"kelvin-voigt": "Kelvin–Voigt"}


def answer_label(row):
    """A setting as the answer names it; the reference's settings say so, and the exact
    solution of a compliant model says whose reference it is (its model's own, not the
    rigid one every error is measured against)."""
    label = setting_label(row)
    if row["solver"] != "event-driven":
        return label
    contact = settings_fields(row).get("contact", "rigid")
    if contact == "rigid":
        return label + " (the reference)"
    return label + f" (the exact {CONTACT_NAMES.get(contact, contact)} solution: its model's own reference)"


def indexed_by_family(summary):
    """Each family's rows with their places in the summary: (index, row), in the file's order."""
    groups = defaultdict(list)
    for i, r in enumerate(summary):
        groups[r["family"]].append((i, r))
    return groups


def settings_over(groups, families, time_steppers_only=False):
    """The rows of each setting (solver, variant, settings) on the given families, for the
    settings that ran on all of them; `groups` is indexed_by_family(summary). The settings
    and each one's rows come in the summary's order (the rule's ties go to the first): only
    the scope's rows are read, where a scan of the whole summary per scope, target and
    measure cost a report of 1,000 families (100,000 rows) 8 x 10^8 row visits."""
    rows = (groups.get(families[0], []) if len(families) == 1 else
            heapq.merge(*(groups.get(f, []) for f in families), key=lambda p: p[0]))
    by_setting = defaultdict(dict)
    for _, r in rows:
        if not (time_steppers_only and is_event_driven(r)):
            by_setting[(r["solver"], r["variant"], r["settings"])][r["family"]] = r
    return [per_family for per_family in by_setting.values() if len(per_family) == len(families)]


def candidates(settings, robust_by_key):
    """What the rule reads of each setting (each its rows by family), once for every target:
    its rows, its worst robust error by measure (robust.robust_errors: the largest over it and
    every finer step of its solver and variant, NaN where one of them failed or is
    unresolved), its costliest row. `robust_by_key` maps each error measure the settings are
    ranked by to robust.robust_errors(summary, measure), computed once over the whole study."""
    out = []
    for per_family in settings:
        rows = list(per_family.values())
        out.append(dict(rows=per_family,
                        worst={key: worst_robust(rows, errors) for key, errors in robust_by_key.items()},
                        costliest=max(rows, key=lambda r: num(r, "cpu_median_s"))))
    return out


def worst_robust(rows, robust_errors):
    """The largest robust error over a setting's rows; NaN where one is NaN (it meets no target)."""
    values = [robust_errors[robust.row_key(r)] for r in rows]
    return float("nan") if any(v != v for v in values) else max(values)


def cheapest(settings, key, target):
    """Among candidates(settings), those that meet the target on every family by the one rule
    (robust.py: they and every finer step of their solver and variant have no failed or
    unresolved run and an error `key` <= target); the cheapest by its median CPU time per run
    on its most expensive family. Returns that candidate, or None. page.js's cheapest is its
    twin."""
    best = None
    for c in settings:
        if not c["worst"][key] <= target:
            continue
        if best is None or num(c["costliest"], "cpu_median_s") < num(best["costliest"], "cpu_median_s"):
            best = c
    return best


def scopes(summary, scenes):
    """What the answer is given for, in order: each scene (its families; `scenes` maps family
    to scene, and without it each family is a scope of its own), then every scene at once,
    among every solver and among the time-steppers only. Each a dict: name, families,
    time_steppers_only."""
    families = list(dict.fromkeys(r["family"] for r in summary))
    groups = defaultdict(list)
    known = all(f in scenes for f in families)
    for family in families:
        groups[scenes[family] if known else family].append(family)
    return [dict(name=name, families=members, time_steppers_only=False) for name, members in groups.items()] + [
        dict(name=ALL, families=families, time_steppers_only=False),
        dict(name=ALL_TIME_STEPPERS, families=families, time_steppers_only=True)]


ALL = "all scenes"
ALL_TIME_STEPPERS = "all scenes, time-steppers only"


def error_cell(per_family, key, impacting):
    """The chosen setting's error on the worst family of the scope: over every point, and
    (when the points are known) over the points where the truth has an impact, in Pi1 and in
    the largest impact velocity (the second accuracy measure; – where the rows predate it)."""
    text = f"{max(num(r, key) for r in per_family.values()):.2g}"
    if impacting is not None:
        for measure in (key, key.replace("err_", "vel_")):
            values = [impacting.get((r["family"], r["solver"], r["variant"], r["settings"]), {}).get(measure, float("nan"))
                      for r in per_family.values()]
            finite = [v for v in values if v == v]
            text += " / " + (f"{max(finite):.2g}" if finite else "–")
    return text


def answer_table(summary, scenes, key, impacting=None):
    """Markdown: for each scope (scopes()) and target, the cheapest setting by error `key`,
    its cost, the family that sets that cost, and its error on the worst family."""
    errors = ("every point / impacting points / impact velocity, impacting points" if impacting is not None
              else "every point")
    lines = [f"| scene | target | cheapest setting | CPU per run (us) | cost set by | error, worst family: {errors} |",
             "|---|---:|---|---:|---|---:|"]
    groups = indexed_by_family(summary)
    robust_by_key = {key: robust.robust_errors(summary, key)}
    for scope in scopes(summary, scenes):
        settings = candidates(settings_over(groups, scope["families"], scope["time_steppers_only"]), robust_by_key)
        name = md_cell(scope["name"]) if scope["name"] not in (ALL, ALL_TIME_STEPPERS) else f"**{scope['name']}**"
        for target in TARGETS:
            best = cheapest(settings, key, target)
            if best is None:
                lines.append(f"| {name} | {target:g} | none | | | |")
                continue
            row = best["costliest"]
            lines.append(f"| {name} | {target:g} | {md_cell(answer_label(row))} | {cost_cell(row)} | "
                         f"{md_cell(row['family'])} | {error_cell(best['rows'], key, impacting)} |")
    return lines


def answer_tables(summary, scenes, impacting=None):
    """The answer: a table per error measure (the median, the 95th percentile)."""
    lines = []
    for key, measure in ERRORS:
        lines += [f"By the {measure} of the error:", "", *answer_table(summary, scenes, key, impacting), ""]
    return lines[:-1]


def rule(summary, impacting=True):
    """The sentence that says how the tables are read off the rows."""
    spread = any(has_spread(r) for r in summary)
    return ("A setting meets a target when its relative Pi1 error against the reference solved 100x tighter "
            "(the median, or the 95th percentile, over the points of a family) is at most the target on every "
            "family of the scene (of the study, for *all scenes*), with no failed run and no unresolved one (a run "
            "that finished but whose own measurements say it did not resolve what it solved: `kit/verdict.hpp`), "
            "and every finer step of the same solver and variant in the study (the same settings apart from the "
            "step: N, w_max h or h) meets it too: an error need not fall with the step, and a lucky coarse step "
            "whose finer neighbours fail is never the answer. Every table of this report that picks a setting by "
            "a target reads it so (`reports/robust.py`). Its cost is its median CPU time per run on its most "
            "expensive family, named under *cost set by*" +
            (" (in brackets, the lowest and highest of the timing repetitions)" if spread else "") +
            ". Its error is given on the scene's worst family" +
            (", over every point and over the points where the reference has an impact (where it has none, "
             "the answer is the ground's motion through a free oscillator, which every scheme follows to its order), "
             "and the relative error in the largest impact velocity over those impacting points"
             if impacting else "") +
            ". The reference is a setting like any other: it is exact up to its tolerances, so it wins where it "
            "is cheapest. `none`: no setting of the study meets the target.")


IN_HOUSE = "moreau-jean"


def step_of(row):
    """(its kind, how fine) of a setting's fixed step (robust.step_split: N, or w h and h in
    seconds counted negative so that finer is larger); None for a solver without one."""
    fields = settings_fields(row)
    kind = next((k for k in robust.STEP_KEYS if k in fields), None)
    return None if kind is None else (kind, robust.step_split(fields)[1])


def step_text(row):
    """A setting's step as the tables print it: N = 64, w h = 0.5, h = 0.002 s."""
    fields = settings_fields(row)
    if "h_s" in fields:
        return f"h = {float(fields['h_s']):g} s"
    if "wh" in fields:
        return f"w h = {float(fields['wh']):g}"
    return f"N = {steps_of(row)}"


def beats_table(summary, key="err_median"):
    """Markdown: per family and target, the in-house Moreau-Jean's cheapest setting that meets
    the target by the one rule (robust.py: it and every finer step, error `key`, no failed or
    unresolved run), and every other time-stepper configuration that meets it either at less CPU
    per run or with a coarser step than the in-house one's coarsest (steps given alike: N, w h or
    h in seconds). The steps compare the schemes apart from what their code costs a step
    (Siconos' steps cost ~300 times the in-house one's). Where no other configuration beats it,
    the row says so. The same rule and the same rows as answer_table, so the two agree on where
    the in-house scheme meets a target."""
    lines = ["| family | target | in-house Moreau-Jean: cheapest | its coarsest step | beats it in CPU per run | "
             "beats it in steps (coarsest) |", "|---|---:|---|---:|---|---|"]
    robust_errors = robust.robust_errors(summary, key)
    for family, frows in by_family(summary).items():
        rows = [r for r in frows if not is_event_driven(r) and step_of(r) is not None]
        configs = defaultdict(list)
        for r in rows:
            configs[(r["solver"], config_label(r))].append(r)
        for target in TARGETS:
            def meets(r):
                return robust_errors[robust.row_key(r)] <= target
            mine = [r for r in rows if r["solver"] == IN_HOUSE and meets(r)]
            if not mine:
                lines.append(f"| {md_cell(family)} | {target:g} | none | | | |")
                continue
            best = min(mine, key=lambda r: num(r, "cpu_median_s"))
            coarsest = min(mine, key=lambda r: step_of(r)[1])
            by_cpu, by_steps = [], []
            for (solver, label), crows in configs.items():
                ok = [r for r in crows if meets(r)]
                if solver == IN_HOUSE or not ok:
                    continue
                cheap = min(ok, key=lambda r: num(r, "cpu_median_s"))
                if num(cheap, "cpu_median_s") < num(best, "cpu_median_s"):
                    by_cpu.append(f"{md_cell(label)}, {step_text(cheap)} ({us(num(cheap, 'cpu_median_s'))} us)")
                alike = [r for r in ok if step_of(r)[0] == step_of(coarsest)[0]]
                if alike:
                    theirs = min(alike, key=lambda r: step_of(r)[1])
                    if step_of(theirs)[1] < step_of(coarsest)[1]:
                        by_steps.append(f"{md_cell(label)} ({step_text(theirs)})")
            lines.append(f"| {md_cell(family)} | {target:g} | {md_cell(setting_label(best))} "
                         f"({us(num(best, 'cpu_median_s'))} us) | "
                         f"{step_text(coarsest)} | {'; '.join(by_cpu) or 'none'} | {'; '.join(by_steps) or 'none'} |")
    return lines


def failure_table(points):
    """Markdown: every setting with runs that did not end ok, per family: how many, their
    statuses, and the message of the first (the cause a solver names)."""
    failed = defaultdict(list)
    total = defaultdict(int)
    for r in points:
        key = (r["solver"], r["variant"], r["settings"], r["family"])
        total[key] += 1
        if r["status"] != "ok":
            failed[key].append(r)
    lines = ["| setting | family | failed | statuses | the first one's message |", "|---|---|---:|---|---|"]
    for key, frows in failed.items():
        statuses = ", ".join(sorted({r["status"] for r in frows}))
        message = frows[0].get("message", "").replace("|", "/")
        message = message if len(message) <= 240 else message[:237] + "..."
        lines.append(f"| {md_cell(setting_label(frows[0]))} | {md_cell(key[3])} | {len(frows)} of {total[key]} | "
                     f"{md_cell(statuses)} | {md_cell(message)} |")
    return lines if failed else []


def unresolved_table(points):
    """Markdown: every setting with runs that finished without resolving what they solved, per
    family: how many, and the first one's reasons (kit/verdict.hpp). Empty when none."""
    found = defaultdict(list)
    total = defaultdict(int)
    for r in points:
        key = (r["solver"], r["variant"], r["settings"], r["family"])
        total[key] += 1
        if r.get("resolved") == "false":
            found[key].append(r)
    lines = ["| setting | family | unresolved | the first one's reasons |", "|---|---|---:|---|"]
    for key, urows in found.items():
        why = urows[0].get("unresolved", "").replace("|", "/")
        lines.append(f"| {md_cell(setting_label(urows[0]))} | {md_cell(key[3])} | {len(urows)} of {total[key]} | "
                     f"{md_cell(why)} |")
    return lines if found else []


def ratio(a, b):
    """a / b to two decimals; '–' where b is 0 (a setting timed at 0 s: no ratio to it)."""
    return f"{a / b:.2f}" if b != 0 else "–"


def cost_table(summary):
    """Markdown: CPU time per run at N = MIDDLE_N (and the reference at its own tolerance), as
    a ratio to the in-house Moreau-Jean stepper (theta = 1/2) on the same family."""
    lines = ["| family | solver setting | CPU per run, median (us) | ratio to moreau-jean theta=0.5 |",
             "|---|---|---:|---:|"]
    for family, rows in by_family(summary).items():
        base = [r for r in rows if r["solver"] == "moreau-jean" and steps_of(r) == MIDDLE_N
                and settings_fields(r).get("theta") == 0.5]
        if not base:
            continue
        for r in rows:
            if steps_of(r) not in (None, MIDDLE_N) or (is_event_driven(r) and settings_fields(r).get("tol_scale") != 1):
                continue
            lines.append(f"| {md_cell(family)} | {md_cell(setting_label(r))} | {cost_cell(r)} | "
                         f"{ratio(num(r, 'cpu_median_s'), num(base[0], 'cpu_median_s'))} |")
    return lines
