"""Every case document poundbench sends an external program is valid against
docs/external/case.schema.json: every point of every family of the shipped case sets
(cases/sets/*.toml), sent through the persistent external protocol to a program that checks it
with jsonschema (tests/external/schema_checker.py), and the protocol's one-shot documents the
same (the documents are the same text; one set checks it).

    python3 tests/case_schema_test.py POUNDBENCH SOURCE_DIR
"""
import csv
import glob
import io
import os
import subprocess
import sys
import unittest

POUNDBENCH, SOURCE = sys.argv[1], sys.argv[2]
try:
    import jsonschema  # noqa: F401
except ImportError as e:
    print(f"skipped: {e} (Debian: python3-jsonschema; scripts/setup.sh installs it)")
    sys.exit(77)
SCHEMA = os.path.join(SOURCE, "docs/external/case.schema.json")
CHECKER = f"{sys.executable} {SOURCE}/tests/external/schema_checker.py {SCHEMA}"


def rows(case_set, *flags):
    out = subprocess.run([POUNDBENCH, "spectrum", case_set, "--solver", "external", "--command", CHECKER,
                          "--threads", "2", *flags], capture_output=True, text=True, check=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


class CaseSchema(unittest.TestCase):
    def test_every_family_of_every_shipped_set_sends_valid_documents(self):
        sets = sorted(glob.glob(os.path.join(SOURCE, "cases/sets/*.toml")))
        self.assertGreater(len(sets), 3)
        kinds = set()
        for case_set in sets:
            with self.subTest(case_set=os.path.basename(case_set)):
                got = rows(case_set, "--persistent")
                families = {r["family"] for r in got}
                self.assertTrue(families)
                for r in got:
                    self.assertTrue(r["message"].startswith("valid: "), f"{r['family']} point {r['point']}: {r['message']}")
                    kinds.add(r["message"].split()[1])
        # The three kinds of load a shipped set has: a program that validates its input takes them all.
        self.assertEqual(kinds, {"pulse", "sinusoids", "record"})

    def test_one_shot_documents_are_the_persistent_ones(self):
        got = rows(os.path.join(SOURCE, "cases/sets/smoke.toml"))
        self.assertTrue(got)
        for r in got:
            self.assertTrue(r["message"].startswith("valid: "), r["message"])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
