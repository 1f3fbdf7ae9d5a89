"""A persistent external program (docs/external.md) that checks each case document it is sent
against docs/external/case.schema.json and answers, as a failed row's message, what it found:
"valid: KIND SHAPE" or "invalid: PATH: WHY". tests/case_schema_test.py runs it over the shipped
case sets.

    python3 tests/external/schema_checker.py SCHEMA
"""
import json
import sys

import jsonschema  # Debian: python3-jsonschema (scripts/setup.sh installs it)

validator = jsonschema.Draft202012Validator(json.load(open(sys.argv[1])))
print(json.dumps({"version": 1, "ready": True}), flush=True)
for line in sys.stdin:
    case = json.loads(line)
    errors = sorted(validator.iter_errors(case), key=lambda e: list(e.absolute_path))
    if errors:
        where = "/".join(str(p) for p in errors[0].absolute_path)
        message = f"invalid: {where}: {errors[0].message[:300]}"
    else:
        message = f"valid: {case['load']['kind']} {case['load'].get('shape', '')}".rstrip()
    print(json.dumps({"version": 1, "status": "failed", "message": message}), flush=True)
