"""The time-steppers on yielding bodies (issue 39): the summary of `poundbench workprecision
cases/sets/workprecision-yielding.toml --settings cases/settings/yielding.toml` (scripts/main.sh:
results/workprecision-yielding.csv, committed as reports/workprecision-yielding.csv), read as the
real records' study is (records_wp.py: each setting's error at its default N, the N it needs for
1 % and 0.1 %, the answer tables), its families a scope of their own: `yield-wall` is
"wall yielding" and `yield-pair` "pair yielding", never merged into the pulses' `wall` and
`pair`. README's block and the report's section are written from the same lines. No
matplotlib here."""

import records_wp

SUMMARY = "workprecision-yielding.csv"


def scope_of(row):
    """yield-<scene> -> "<scene> yielding" (the set's family names: cases/sets/workprecision-yielding.toml)."""
    return row["family"].removeprefix("yield-") + " yielding"


def lines(summary):
    families = list(dict.fromkeys(r["family"] for r in summary))
    points = {r["family"]: r["points"] for r in summary}
    intro = [f"The yielding families (`cases/sets/workprecision-yielding.toml`): "
             + ", ".join(f"`{f}` ({points[f]} points)" for f in families)
             + ", a wall and a flexible and a stiff pair with body 0 strongly yielding (Pi_y0 = 0.1 and 0.25, "
             "where its elastic Pi1 is 1 to 3), alpha 0, 0.05 and 0.2, both pulses, Pi2 = 0.5, 1 and 2; errors "
             "relative to the reference solved 100x tighter. A solver whose engine owns the spring ends every "
             "run failed (`yielding: why`), never with an elastic answer."]
    return records_wp.lines(summary, intro, scope_of)


def section(summary):
    return ["## Time-steppers on yielding bodies", "",
            "A yield is a kink in the restoring force: a step that crosses one is first order at best, and "
            "alpha = 0 leaves a yielding body with no stiffness at all. So what a time-stepper needs on a "
            "yielding body is measured apart from the elastic scenes.", "",
            *lines(summary), ""]
