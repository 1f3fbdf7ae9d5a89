"""The study's one answer rule (issue 48, item 2): a setting meets a target when it AND every
finer step of the same solver and variant in the study (the same settings apart from the step:
`steps` N, `wh` or `h_s`) meet it, on the same family. A time-stepper's error is not monotone in
its step: on a real record, Moreau-Jean at h = 0.016 s met 1 % with 0.73 % while h = 0.008 s
gave 1.37 % and 0.004 s 1.08 %; "the cheapest setting that meets the target" chose the lucky
coarse step, a setting whose own refinement says the error is not under control.

Every section that picks a setting by a target reads it here: the answer tables and the
beats table (answer.py), the N needed on real records and yielding bodies (records_wp.py,
records_step.py), the compliant answer (compliant.py), README's physical search (readme.py);
page.js's robustErrors is its twin in the page (tests/report_page_test.py holds the two to the
same answers). No matplotlib here."""

import functools
import json
import math
from collections import defaultdict

from rows import num, settings_fields, sound

# The settings that set a fixed step, and which way is finer: more steps per shortest period
# (N), or a shorter step (w_max h, or h in seconds as a physical settings list gives it).
STEP_KEYS = {"steps": 1.0, "wh": -1.0, "h_s": -1.0}


@functools.cache
def _split_text(settings):
    # A study's rows share a few hundred settings texts (rows._parsed_settings): each split once.
    return step_split(settings_fields(dict(settings=settings)))


def step_split(fields):
    """(the settings apart from the step as canonical JSON, how fine the step is) for a
    setting's named values; fineness None for a setting without a fixed step (the
    reference, CVODE), which is then a line of its own."""
    steps = [k for k in STEP_KEYS if k in fields]
    if not steps:
        return json.dumps(dict(fields), sort_keys=True), None
    key = steps[0]
    rest = {k: v for k, v in fields.items() if k != key}
    return json.dumps(rest, sort_keys=True), STEP_KEYS[key] * float(fields[key])


def robust(items):
    """The rule itself. items: (line, fineness, error) triples, `line` any hashable naming
    what is compared (a family and a setting apart from its step), `error` NaN where the run
    meets no target (failed, unresolved, not measured). Returns, in the items' order, each
    one's robust error: the largest error of it and of every item of its line at least as
    fine; NaN when any of those is NaN. An item with fineness None is judged alone. A setting
    meets a target exactly when its robust error is <= the target."""
    items = list(items)
    out = [float("nan")] * len(items)
    lines = defaultdict(list)
    for i, (line, fineness, _) in enumerate(items):
        if fineness is None:
            out[i] = items[i][2]
        else:
            lines[line].append(i)
    for members in lines.values():
        # finest first, so that one running maximum carries every finer step's error
        members.sort(key=lambda i: -items[i][1])
        running = -math.inf
        for i in members:
            e = items[i][2]
            running = max(running, e) if not (math.isnan(e) or math.isnan(running)) else float("nan")
            out[i] = running
    return out


def row_key(row):
    """A summary row's identity: its family and setting (one row each in a study's summary)."""
    return (row["family"], row["solver"], row.get("variant") or "", row["settings"])


def robust_errors(summary, key):
    """{row_key(row): robust error `key`} for a study's summary rows: a row with a failed or
    unresolved run (not rows.sound) counts as NaN, for it and every coarser step."""
    keys, items = [], []
    for r in summary:  # one pass: a report reads each row a bounded number of times
        rest, fineness = _split_text(r["settings"])
        keys.append(row_key(r))
        items.append((keys[-1][:3] + (rest,), fineness, num(r, key) if sound(r) else float("nan")))
    return dict(zip(keys, robust(items)))

