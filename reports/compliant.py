"""The compliant-contact study (issue 18: cases/settings/compliant.toml on
cases/sets/compliant.toml): each element's model error against the rigid reference over its
stiffness K, the integration error of CVODE and Newmark against the element's own exact or
tight reference, what its isolated impacts restitute, how deep it penetrates and what a run
costs; and the answer to "at what stiffness and step is a compliant model as accurate as
Moreau-Jean at N = 64, and at what price". No matplotlib at import (the figure is drawn in
figure()), so that README's block is checked in a blink."""

import math
from collections import defaultdict

import robust
from rows import median, num, settings_fields, sound, steps_of, unresolved

MODELS = ["kelvin-voigt", "hunt-crossley", "jankowski", "hertz"]
# The in-house stepper the compliant models are held against, on the same cases.
BENCHMARK_N = 64


def kind(row):
    """What a row of the study is: ('reference', model, K) for a model's own reference (the
    exact Kelvin-Voigt solution, CVODE at rtol 1e-12 for the Hertz family), ('cvode', model, K),
    ('newmark', model, K, N), ('moreau-jean', N), or None (the rigid truth, anything else)."""
    fields = settings_fields(row)
    if row["solver"] == "event-driven" and fields.get("contact") == "kelvin-voigt":
        return ("reference", "kelvin-voigt", fields["stiffness"])
    if row["solver"] == "compliant":
        model, K = fields["variant"], fields["stiffness"]
        if fields.get("integrator") == "newmark":
            return ("newmark", model, K, steps_of(row))
        if fields.get("rtol") == 1e-12 and model != "kelvin-voigt":
            return ("reference", model, K)
        if fields.get("method", "bdf") == "bdf" and fields.get("rtol") == 1e-8:
            return ("cvode", model, K)
    if row["solver"] == "moreau-jean" and fields.get("theta") == 0.5:
        return ("moreau-jean", steps_of(row))
    return None


def by_kind(summary):
    """Summary rows grouped by kind(), each group a dict family -> row."""
    out = defaultdict(dict)
    for r in summary:
        k = kind(r)
        if k is not None:
            out[k][r["family"]] = r
    return out


def applies(row):
    """Whether the setting modelled this family (the Hertz element fails every inelastic case)."""
    return int(row["failed"]) < int(row["points"])


def worst(rows, key):
    values = [num(r, key) for r in rows]
    return max(values) if values and not any(math.isnan(v) for v in values) else float("nan")


def fmt(x):
    return "–" if math.isnan(x) else f"{x:.2g}"


def cost(rows):
    """The median CPU time per run over the families' medians where the setting applies (their
    middle), and the spread."""
    rows = [r for r in rows if applies(r)]
    return (median([num(r, "cpu_median_s") for r in rows]), median([num(r, "cpu_median_low_s") for r in rows]),
            median([num(r, "cpu_median_high_s") for r in rows]))


def fmt_cost(c):
    return f"{1e6 * c[0]:.3g} ({1e6 * c[1]:.3g}–{1e6 * c[2]:.3g})"


def shortfall(rows, target):
    """How far the setting falls short of `target`'s accuracy: the largest excess of its median
    or 95th-percentile error over target's, on every family where the setting models the
    cases and target has a row; NaN where it has a failed or unresolved run there, or no such
    family. The setting is as accurate when this is <= 0."""
    shared = [f for f in rows if f in target and applies(rows[f])]
    if not shared or not all(sound(rows[f]) for f in shared):
        return float("nan")
    excess = [num(rows[f], key) - num(target[f], key) for f in shared for key in ("err_median", "err_p95")]
    return float("nan") if any(math.isnan(x) for x in excess) else max(excess)


def meets(rows, target):
    """Whether, on every family where the setting models the cases and target has a row, it
    has no failed or unresolved run and meets target's median and 95th-percentile error."""
    return shortfall(rows, target) <= 0


def least_steps(groups, keys, target):
    """Among Newmark's keys of one element and stiffness, the least N as accurate as `target`
    by the one rule (robust.py): it and every larger N of the study are; None where none is."""
    scores = robust.robust([("one line", k[3], shortfall(groups[k], target)) for k in keys])
    return min((k for k, s in zip(keys, scores) if s <= 0), key=lambda k: k[3], default=None)


def answer_lines(summary):
    """The answer, from the summary table alone (README's block and the report's): per element
    through CVODE the least stiffness that is as accurate as Moreau-Jean at N = 64, and per
    stiffness through Newmark the least step count, with what a run then costs."""
    groups = by_kind(summary)
    mj = groups.get(("moreau-jean", BENCHMARK_N))
    if not mj:
        return [f"(no moreau-jean theta=0.5 N = {BENCHMARK_N} in the compliant study)"]
    mj_cost = cost(list(mj.values()))[0]
    lines = [f"Against the in-house Moreau–Jean at N = {BENCHMARK_N} on the same cases (median / 95th-percentile "
             "relative Pi1 error against the rigid reference: "
             + ", ".join(f"{f} {fmt(num(r, 'err_median'))} / {fmt(num(r, 'err_p95'))}" for f, r in mj.items())
             + f"; {fmt_cost(cost(list(mj.values())))} us per run). A compliant setting is as accurate when it "
             "meets both on every family where its element applies, with no failed run and no unresolved one (here: "
             "a contact shorter than 4 steps of the integrator, `kit/verdict.hpp`); a step count N of Newmark is, "
             "as everywhere in this report (`reports/robust.py`), as accurate only when every larger N of the study "
             "is too.", "",
             "| element | integrator | as accurate from | CPU per run (us) | times Moreau–Jean's |",
             "|---|---|---|---:|---:|"]

    def row(model, integrator, where, k):
        if k is None:
            return f"| {model} | {integrator} | {where} | | |"
        c = cost(list(groups[k].values()))
        return f"| {model} | {integrator} | {where} | {fmt_cost(c)} | {c[0] / mj_cost:.3g} |"

    for model in MODELS:
        ks = sorted((k for k in groups if k[0] == "cvode" and k[1] == model), key=lambda k: k[2])
        if ks:
            found = next((k for k in ks if meets(groups[k], mj)), None)
            lines.append(row(model, "cvode", f"K = {fmt(found[2])}" if found else
                             f"none of K = {fmt(ks[0][2])} to {fmt(ks[-1][2])}", found))
        for K in sorted({k[2] for k in groups if k[0] == "newmark" and k[1] == model}):
            ks = sorted((k for k in groups if k[0] == "newmark" and k[1] == model and k[2] == K), key=lambda k: k[3])
            found = least_steps(groups, ks, mj)
            lines.append(row(model, "newmark", f"K = {fmt(K)}: N = {found[3]}" if found else
                             f"K = {fmt(K)}: none of N = {ks[0][3]} to {ks[-1][3]}", found))
    return lines


def model_table(summary, points):
    """Per element and stiffness: the model's error, CVODE's integration error, what isolated
    impacts restitute, the deepest penetration, CVODE's cost."""
    groups = by_kind(summary)
    runs = defaultdict(list)
    for r in points:
        k = kind(r)
        if k is not None and k[0] == "reference" and r["status"] == "ok":
            runs[k].append(r)
    lines = ["| element | K | model error: median | p95 | worst | CVODE's integration error: median | p95 | "
             "isolated impacts: largest abs(e - eps) | deepest penetration (a_p/w_p^2) | CVODE CPU per run (us) |",
             "|---|---:|---:|---:|---:|---:|---:|---|---:|---:|"]
    for model in MODELS:
        for k in sorted((k for k in groups if k[0] == "reference" and k[1] == model), key=lambda k: k[2]):
            ref = [r for r in groups[k].values() if applies(r)]
            cv = [r for r in groups.get(("cvode", model, k[2]), {}).values() if applies(r)]
            miss = [max(abs(num(r, "restitution_low") - num(r, "eps")), abs(num(r, "restitution_high") - num(r, "eps")))
                    for r in runs[k] if not math.isnan(num(r, "restitution_low"))]
            depth = [-num(r, "min_gap") * num(r, "w_p") ** 2 / num(r, "a_p") for r in runs[k]
                     if not math.isnan(num(r, "min_gap"))]
            lines.append(f"| {model} | {fmt(k[2])} | {fmt(worst(ref, 'err_median'))} | {fmt(worst(ref, 'err_p95'))} | "
                         f"{fmt(worst(ref, 'err_max'))} | {fmt(worst(cv, 'int_err_median'))} | "
                         f"{fmt(worst(cv, 'int_err_p95'))} | "
                         + (f"{max(miss):.2g}" if miss else "–")
                         + f" | {fmt(max(depth)) if depth else '–'} | {fmt_cost(cost(cv)) if cv else '–'} |")
    return lines


def newmark_table(summary, points):
    """Kelvin-Voigt through Newmark per stiffness and step count: errors, failures, cost."""
    groups = by_kind(summary)
    statuses = defaultdict(lambda: defaultdict(int))
    for r in points:
        k = kind(r)
        if k is not None and k[0] == "newmark" and r["status"] != "ok":
            statuses[k][r["status"]] += 1
    lines = ["| K | N | error against rigid: median | p95 | against its exact model: median | p95 | "
             "runs not ok | unresolved (ok) | CPU per run (us) |", "|---:|---:|---:|---:|---:|---:|---|---:|---:|"]
    for k in sorted((k for k in groups if k[0] == "newmark"), key=lambda k: (k[2], k[3])):
        rows = list(groups[k].values())
        bad = ", ".join(f"{n} {s}" for s, n in sorted(statuses[k].items())) or "0"
        lines.append(f"| {fmt(k[2])} | {k[3]} | {fmt(worst(rows, 'err_median'))} | {fmt(worst(rows, 'err_p95'))} | "
                     f"{fmt(worst(rows, 'int_err_median'))} | {fmt(worst(rows, 'int_err_p95'))} | {bad} | "
                     f"{sum(unresolved(r) for r in rows)} | {fmt_cost(cost(rows))} |")
    return lines


def restitution_lines(rows):
    """README's table of what each element restitutes (solvers/compliant/restitution_table_main.cpp's
    measurements, reports/restitution.csv): one row per element and damping rule, one column
    per eps, each cell the measured restitution and the damping parameter that gave it."""
    eps_values = sorted({num(r, "eps") for r in rows if r["element"] != "hertz"})
    rules = list(dict.fromkeys((r["element"], r["rule"]) for r in rows if r["element"] != "hertz"))
    cell = {(r["element"], r["rule"], num(r, "eps")): r for r in rows}
    methods = [r["measured_by"] for r in rows]
    usual = max(set(methods), key=methods.count)
    other = sorted(set(methods) - {usual})
    lines = ["Restitution of one free impact, nothing but the element acting (`solvers/compliant/restitution_table_main.cpp`), and "
             f"in brackets the damping parameter that gives it. Measured by {usual}"
             + (f"; rows marked * by {', '.join(other)} (closed forms that are no variant of the solver)" if other
                else "") + ".", "",
             "| element | damping | " + " | ".join(f"eps = {e:g}" for e in eps_values) + " |",
             "|---|---|" + "---:|" * len(eps_values)]
    for element, rule in rules:
        cells = []
        for e in eps_values:
            r = cell.get((element, rule, e))
            cells.append(f"{num(r, 'restitution'):.4f} ({r['parameter']} {num(r, 'value'):.4g})" if r else "")
        marked = any(r["measured_by"] != usual for r in rows if (r["element"], r["rule"]) == (element, rule))
        lines.append(f"| `{element}` | {rule}{' *' if marked else ''} | " + " | ".join(cells) + " |")
    for r in rows:
        if r["element"] == "hertz":
            lines += ["", f"`hertz` is elastic (eps = 1 only): it restitutes {num(r, 'restitution'):.4f}."]
    return lines


def figure(summary, out_dir):
    """Model error (worst family's p95) against K per element, with Moreau-Jean N = 64's, and
    Newmark's integration error against N per K; returns the figure's path in out_dir."""
    from figure import figure_width, plt, save

    groups = by_kind(summary)
    fig, (left, right) = plt.subplots(1, 2, figsize=(figure_width(2), 4.6), layout="constrained")
    for model in MODELS:
        keys = sorted((k for k in groups if k[0] == "reference" and k[1] == model), key=lambda k: k[2])
        pts = [(k[2], worst([r for r in groups[k].values() if applies(r)], "err_p95")) for k in keys]
        pts = [(x, y) for x, y in pts if not math.isnan(y)]
        if pts:
            left.loglog(*zip(*pts), marker="o", label=model)
    mj = groups.get(("moreau-jean", BENCHMARK_N))
    if mj:
        left.axhline(worst(list(mj.values()), "err_p95"), color="grey", linestyle="--",
                     label=f"moreau-jean N = {BENCHMARK_N}")
    left.set_xlabel("contact stiffness K (Pi term)")
    left.set_ylabel("model error: 95th percentile, worst family")
    left.set_title("the model against rigid contact")
    left.legend(loc="lower left", frameon=False)
    for K in sorted({k[2] for k in groups if k[0] == "newmark"}):
        keys = sorted((k for k in groups if k[0] == "newmark" and k[2] == K), key=lambda k: k[3])
        pts = [(k[3], worst(list(groups[k].values()), "int_err_p95")) for k in keys]
        pts = [(x, y) for x, y in pts if not math.isnan(y) and y > 0]
        if pts:
            right.loglog(*zip(*pts), marker="s", label=f"K = {K:g}")
    right.set_xlabel("Newmark steps per shortest period N")
    right.set_ylabel("integration error: 95th percentile, worst family")
    right.set_title("Kelvin–Voigt by Newmark\nagainst its exact solution")
    right.legend(loc="lower left", frameon=False)
    return save(fig, out_dir, "compliant")


def section(summary, points, out_dir):
    """The report's section."""
    fig = figure(summary, out_dir)
    return ["## Compliant contact against the rigid answer", "",
            "Contact elements as earthquake engineers model pounding (`solvers/compliant/README.md`): each over "
            "eight decades of its stiffness K (a Pi term: `cases/README.md`), on `cases/sets/compliant.toml`. A "
            "setting's *model error* is its own model's exact answer (`event-driven --contact kelvin-voigt`; for "
            "the Hertz family CVODE at rtol 1e-12) against the rigid reference; its *integration error*, the "
            "setting against that answer. Errors are relative Pi1 errors over a family's points, the worst family "
            "shown; the Hertz element is elastic and is measured on the eps = 1 family only.", "",
            *answer_lines(summary), "",
            "### Each element over its stiffness", "",
            "CVODE at its default tolerance (rtol 1e-8, BDF). Restitution: over the isolated impacts of every "
            "point of the model's exact or tight answer, the largest distance between the rebound's restitution e "
            "and the eps the element was calibrated to (the bodies' springs and the pulse act during a contact, "
            "more so the softer it is: a soft element can return more than it took); penetration: the deepest "
            "over every point.", "",
            *model_table(summary, points), "",
            "### Kelvin–Voigt through OpenSees-style Newmark", "",
            "Average acceleration with Newton iterations at h = T_min / N, where the contact's own period is not "
            "in T_min. A run whose steps do not resolve the contact shows it here rather than being hidden: "
            "*unresolved* counts the runs that ended ok with a contact shorter than 4 steps of the integrator "
            "(`kit/verdict.hpp`; the study runs without the monitor, so energy made is not judged here), and "
            "no table ranks such a setting.", "",
            *newmark_table(summary, points), "",
            f"![compliant contact]({fig})", ""]
