"""Which setting to use: for each target error, the cheapest setting of the work-precision
study that meets it, per scene and over every family. Read off the study's summary rows
(workprecision.csv); no matplotlib, so README's check runs in a blink."""

from collections import defaultdict

from rows import config_label, num, setting_label, settings_fields, sound, steps_of

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


def settings_over(summary, families, time_steppers_only=False):
    """The rows of each setting (solver, variant, settings) on the given families, for the
    settings that ran on all of them."""
    by_setting = defaultdict(dict)
    for r in summary:
        if r["family"] in families and not (time_steppers_only and is_event_driven(r)):
            by_setting[(r["solver"], r["variant"], r["settings"])][r["family"]] = r
    return [per_family for per_family in by_setting.values() if set(per_family) == set(families)]


def cheapest(settings, key, target):
    """Among settings (each its rows by family), those with no failed or unresolved run and an
    error `key` <= target on every family; the cheapest by its median CPU time per run on its
    most expensive family. Returns that family's row, or None."""
    best = None
    for per_family in settings:
        rows = list(per_family.values())
        if any(not sound(r) or not num(r, key) <= target for r in rows):
            continue
        costliest = max(rows, key=lambda r: num(r, "cpu_median_s"))
        if best is None or num(costliest, "cpu_median_s") < num(best, "cpu_median_s"):
            best = costliest
    return best


def scopes(summary, scenes):
    """What the answer is given for, in order: each scene (its families; `scenes` maps family
    to scene, and without it each family is a scope of its own), then every scene at once,
    among every solver and among the time-steppers only. Each a dict: name, families,
    time_steppers_only."""
    families = list(dict.fromkeys(r["family"] for r in summary))
    groups = defaultdict(list)
    for family in families:
        groups[scenes.get(family, family) if all(f in scenes for f in families) else family].append(family)
    return [dict(name=name, families=members, time_steppers_only=False) for name, members in groups.items()] + [
        dict(name=ALL, families=families, time_steppers_only=False),
        dict(name=ALL_TIME_STEPPERS, families=families, time_steppers_only=True)]


ALL = "all scenes"
ALL_TIME_STEPPERS = "all scenes, time-steppers only"


def choice(summary, scope, key, target):
    """The answer for one scope, error measure and target: the cheapest setting's row on the
    family that sets its cost, and that setting's rows on every family of the scope (None,
    {} where no setting meets it)."""
    settings = settings_over(summary, scope["families"], scope["time_steppers_only"])
    best = cheapest(settings, key, target)
    if best is None:
        return None, {}
    mine = next(per_family for per_family in settings if any(r is best for r in per_family.values()))
    return best, mine


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
    for scope in scopes(summary, scenes):
        for target in TARGETS:
            best, mine = choice(summary, scope, key, target)
            name = scope["name"] if scope["name"] not in (ALL, ALL_TIME_STEPPERS) else f"**{scope['name']}**"
            if best is None:
                lines.append(f"| {name} | {target:g} | none | | | |")
                continue
            lines.append(f"| {name} | {target:g} | {answer_label(best)} | {cost_cell(best)} | {best['family']} | "
                         f"{error_cell(mine, key, impacting)} |")
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
            "that finished but whose own measurements say it did not resolve what it solved: `solvers/verdict.hpp`). "
            "Its cost is its median CPU time per run on its most expensive family, named under *cost set by*" +
            (" (in brackets, the lowest and highest of the timing repetitions)" if spread else "") +
            ". Its error is given on the scene's worst family" +
            (", over every point and over the points where the reference has an impact (where it has none, "
             "the answer is the ground's motion through a free oscillator, which every scheme follows to its order), "
             "and the relative error in the largest impact velocity over those impacting points"
             if impacting else "") +
            ". The reference is a setting like any other: it is exact up to its tolerances, so it wins where it "
            "is cheapest. `none`: no setting of the study meets the target.")


IN_HOUSE = "moreau-jean"


def beats_table(summary, key="err_median"):
    """Markdown: per family and target, the in-house Moreau-Jean's cheapest setting that meets
    the target (error `key`, no failed run), and every other time-stepper configuration that
    meets it either at less CPU per run or with fewer steps per shortest period N than the
    in-house one's least N. The step counts compare the schemes apart from what their code
    costs a step (Siconos' steps cost ~300 times the in-house one's). Where no other
    configuration beats it, the row says so."""
    lines = ["| family | target | in-house Moreau-Jean: cheapest | its least N | beats it in CPU per run | "
             "beats it in steps (least N) |", "|---|---:|---|---:|---|---|"]
    for family in dict.fromkeys(r["family"] for r in summary):
        rows = [r for r in summary if r["family"] == family and not is_event_driven(r) and steps_of(r) is not None]
        configs = defaultdict(list)
        for r in rows:
            configs[(r["solver"], config_label(r))].append(r)
        for target in TARGETS:
            def meets(r):
                return sound(r) and num(r, key) <= target
            mine = [r for r in rows if r["solver"] == IN_HOUSE and meets(r)]
            if not mine:
                lines.append(f"| {family} | {target:g} | none | | | |")
                continue
            best = min(mine, key=lambda r: num(r, "cpu_median_s"))
            least_n = min(steps_of(r) for r in mine)
            by_cpu, by_steps = [], []
            for (solver, label), crows in configs.items():
                ok = [r for r in crows if meets(r)]
                if solver == IN_HOUSE or not ok:
                    continue
                cheap = min(ok, key=lambda r: num(r, "cpu_median_s"))
                if num(cheap, "cpu_median_s") < num(best, "cpu_median_s"):
                    by_cpu.append(f"{label}, N = {steps_of(cheap)} ({us(num(cheap, 'cpu_median_s'))} us)")
                n = min(steps_of(r) for r in ok)
                if n < least_n:
                    by_steps.append(f"{label} (N = {n})")
            lines.append(f"| {family} | {target:g} | {setting_label(best)} ({us(num(best, 'cpu_median_s'))} us) | "
                         f"{least_n} | {'; '.join(by_cpu) or 'none'} | {'; '.join(by_steps) or 'none'} |")
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
        message = frows[0]["message"].replace("|", "/")
        message = message if len(message) <= 240 else message[:237] + "..."
        lines.append(f"| {setting_label(frows[0])} | {key[3]} | {len(frows)} of {total[key]} | {statuses} | "
                     f"{message} |")
    return lines if failed else []


def unresolved_table(points):
    """Markdown: every setting with runs that finished without resolving what they solved, per
    family: how many, and the first one's reasons (solvers/verdict.hpp). Empty when none."""
    found = defaultdict(list)
    total = defaultdict(int)
    for r in points:
        key = (r["solver"], r["variant"], r["settings"], r["family"])
        total[key] += 1
        if r.get("resolved") == "false":
            found[key].append(r)
    lines = ["| setting | family | unresolved | the first one's reasons |", "|---|---|---:|---|"]
    for key, urows in found.items():
        why = urows[0]["unresolved"].replace("|", "/")
        lines.append(f"| {setting_label(urows[0])} | {key[3]} | {len(urows)} of {total[key]} | {why} |")
    return lines if found else []


def cost_table(summary):
    """Markdown: CPU time per run at N = MIDDLE_N (and the reference at its own tolerance), as
    a ratio to the in-house Moreau-Jean stepper (theta = 1/2) on the same family."""
    lines = ["| family | solver setting | CPU per run, median (us) | ratio to moreau-jean theta=0.5 |",
             "|---|---|---:|---:|"]
    for family in dict.fromkeys(r["family"] for r in summary):
        rows = [r for r in summary if r["family"] == family]
        base = [r for r in rows if r["solver"] == "moreau-jean" and steps_of(r) == MIDDLE_N
                and settings_fields(r)["theta"] == 0.5]
        if not base:
            continue
        for r in rows:
            if steps_of(r) not in (None, MIDDLE_N) or (is_event_driven(r) and settings_fields(r).get("tol_scale") != 1):
                continue
            lines.append(f"| {family} | {setting_label(r)} | {cost_cell(r)} | "
                         f"{num(r, 'cpu_median_s') / num(base[0], 'cpu_median_s'):.2f} |")
    return lines
