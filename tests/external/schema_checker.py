"""An external program (docs/external.md) that checks each case document it is sent against
docs/external/case.schema.json and answers, as a failed row's message, what it found:
"valid: KIND SHAPE", "unchecked: KIND SHAPE" (sampling, below) or "invalid: PATH: WHY".
tests/case_schema_test.py runs it over the shipped case sets.

    python3 tests/external/schema_checker.py SCHEMA [--persistent] [--sample N]

--persistent: answers a stream of cases after a ready line (else one case). --sample N: checks
the first document of each shape of document (load kind and shape, the record's file, bodies,
contacts, whether a step is given) and one in N of the others: Debian's jsonschema takes 0.44 ms
a pulse's document and 50 ms a record's (its samples one by one): the paper sets' 27,000 points
and the records set's 193 took 50 s of the test's 59. A record's samples are checked whole once
(errors_of(), below).
"""
import argparse
import json
import sys

import jsonschema  # Debian: python3-jsonschema (scripts/setup.sh installs it)

p = argparse.ArgumentParser()
p.add_argument("schema")
p.add_argument("--persistent", action="store_true")
p.add_argument("--sample", type=int, default=1)
a = p.parse_args()
validator = jsonschema.Draft202012Validator(json.load(open(a.schema)))
seen = set()
count = 0


# A record's samples, checked whole once: a later document with the same samples (most of a
# record's points: the Pi terms change its w, not its t and a) is checked with the first two
# of each, since the rest are items that were already valid under the same schema.
checked_samples = set()


def errors_of(case):
    load = case["load"]
    samples = (tuple(load["t"]), tuple(load["a"])) if load["kind"] == "record" else None
    if samples in checked_samples:
        case = {**case, "load": {**load, "t": load["t"][:2], "a": load["a"][:2]}}
    errors = sorted(validator.iter_errors(case), key=lambda e: list(e.absolute_path))
    if samples and not errors:
        checked_samples.add(samples)
    return errors


def answer(text):
    global count
    case = json.loads(text)
    load = case["load"]
    what = f"{load['kind']} {load.get('shape', '')}".rstrip()
    # A buildings document ("scene": "buildings") has buildings where the oscillators' has bodies.
    shape = (what, load.get("source"), case.get("scene"), len(case.get("bodies", case.get("buildings", []))),
             len(case["contacts"]), case["step"] is None)
    count += 1
    if shape in seen and count % a.sample:
        message = f"unchecked: {what}"
    else:
        seen.add(shape)
        errors = errors_of(case)
        if errors:
            # The schema is a oneOf of the two scenes: the error of the branch that came closest.
            error = jsonschema.exceptions.best_match(errors)
            where = "/".join(str(p) for p in error.absolute_path)
            message = f"invalid: {where}: {error.message[:300]}"
        else:
            message = f"valid: {what}"
    print(json.dumps({"version": 1, "status": "failed", "message": message}), flush=True)


if a.persistent:
    print(json.dumps({"version": 1, "ready": True}), flush=True)
    for line in sys.stdin:
        answer(line)
else:
    answer(sys.stdin.read())
