"""The time-steppers on real ground motions (issue 34): the summary of `poundbench workprecision
cases/sets/workprecision-records.toml --settings cases/settings/records.toml` (scripts/main.sh:
results/workprecision-records.csv, committed as reports/workprecision-records.csv) read as a
user choosing a solver for a real record asks: each time-stepper's error at its default
setting (N = 64 steps per shortest period), the step count N it needs for 1 % and 0.1 %, and
the answer table of that family, a scope of its own ("pair records", never merged into the
pulses' `pair`). README's block and the report's section are written from the same lines.
No matplotlib here."""

import answer
import robust
from rows import config_label, num, settings_fields, steps_of

DEFAULT_N = 64  # every fixed-step solver's default (kit/fixed_step.hpp)
TARGETS = (1e-2, 1e-3)
SUMMARY = "workprecision-records.csv"


def _configs(summary):
    by = {}
    for r in summary:
        if answer.is_event_driven(r):
            continue
        variant = settings_fields(r).get("variant")
        label = config_label(r) + (f" (default: {variant})" if variant and not r.get("variant") else "")
        by.setdefault(label, []).append(r)
    return by


def needed(rows, key, target):
    """The least N that meets the target by the one rule (robust.py: it and every larger N of
    the study meet it on every point summarised; an error that is erratic in N, as on real
    records, meets it once by luck); None when the largest N does not. With the N it was swept
    to. `rows`: one configuration's rows, on one family or several (each judged on its own)."""
    rows = [r for r in rows if steps_of(r) is not None]
    errors = robust.robust_errors(rows, key)
    by_n = {}
    for r in rows:  # a step count meets only where it meets on every family
        n = steps_of(r)
        by_n[n] = by_n.get(n, True) and errors[robust.row_key(r)] <= target
    return min((n for n, ok in by_n.items() if ok), default=None), max(by_n, default=None)


ESTIMATOR = ("Percentiles (the median, the 95th) are over the points of a family, by linear interpolation "
             "between order statistics: the p-th of n sorted errors is at rank (n - 1) p / 100 counted from 0 "
             "(numpy's default, `studies/stats.cpp`).")


def pct(x):
    return f"{100 * x:.2g} %" if x == x else "–"  # NaN: no run of the setting finished


def lines(summary, intro=None, scope_of=lambda r: "pair records"):
    """README's and the report's text: the defaults' errors, the N needed, the answer. `intro`
    says what the study's families are (the real records' by default), `scope_of` gives a
    summary row its row of the answer tables (a scope of its own, never a pulse scene's)."""
    family = summary[0]["family"]
    configs = _configs(summary)
    points = summary[0]["points"]
    intro = intro or [f"The `{family}` family (`cases/sets/workprecision-records.toml`): {points} points, one record "
                      "of each earthquake of `cases/records/real/` on a flexible and a stiff pair at Pi2 = 0.5 and 2, "
                      "each record's Pi terms on its own peak and mean period; errors relative to the reference "
                      "solved 100x tighter."]
    # The estimator of every percentile below (studies/stats.cpp's, which wrote err_p95).
    intro = [*intro, "", ESTIMATOR]
    text = [*intro, "",
            "Each time-stepper at its default setting (its default variant, N = 64 steps per shortest period; "
            "`–`: no run finished):", "",
            "| setting | median error | 95th percentile | largest | CPU per run (us) | failed / unresolved |",
            "|---|---:|---:|---:|---:|---:|"]
    families = list(dict.fromkeys(r["family"] for r in summary))
    for label, rows in configs.items():
        # A setting with no step (CVODE chooses its own) is at its default as it stands.
        for r in (r for r in rows if steps_of(r) in (DEFAULT_N, None)):
            name = label if len(families) == 1 else f"{label}, `{r['family']}`"
            text.append(f"| {name} | {pct(num(r, 'err_median'))} | {pct(num(r, 'err_p95'))} | {pct(num(r, 'err_max'))} "
                        f"| {answer.us(num(r, 'cpu_median_s'))} | {r['failed']} / {r.get('unresolved') or 0} |")
    text += ["", "The least N from which every finer step of the study meets 1 % and 0.1 % (by the median and the "
             "95th percentile of the error over the points" + (", on every family" if len(families) > 1 else "")
             + "; `beyond N` where the finest step run does not):", "",
             "| setting | 1 %, median | 1 %, 95th | 0.1 %, median | 0.1 %, 95th |", "|---|---:|---:|---:|---:|"]
    for label, rows in configs.items():
        if len({steps_of(r) for r in rows}) < 2:
            continue
        cells = []
        for target in TARGETS:
            for key in ("err_median", "err_p95"):
                least, finest = needed(rows, key, target)
                cells.append(f"N = {least}" if least else f"beyond {finest}")
        text.append(f"| {label} | " + " | ".join(cells) + " |")
    # One scope: the tables' rows for every scene at once would repeat it.
    tables = answer.answer_tables(summary, {r["family"]: scope_of(r) for r in summary})
    text += ["", *(t for t in tables if not t.startswith(f"| **{answer.ALL}"))]
    return text


def section(summary):
    return ["## Time-steppers on real records", "",
            "Real accelerograms are rough loads: a time-stepper averages (Moreau–Jean's exact step mean) or samples "
            "(every engine) the record over its step, and the peak of a long response can move to another cycle "
            "with the step. So its error on a real record is not the smooth, ordered error it has on a pulse.", "",
            *lines(summary), ""]
