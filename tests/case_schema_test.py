"""Every case document poundbench sends an external program is valid against
docs/external/case.schema.json: the documents of every family of the shipped case sets
(cases/sets/*.toml), sent through the persistent external protocol to a program that checks
them with jsonschema (tests/external/schema_checker.py). Every document of most sets; in the
record sets (SAMPLED), the first of each shape of document (each
record's file apart) and one in 20 of the others, and every family has documents checked;
the sets of thousands of points at one Pi2 (ONE_PI2). The one-shot protocol's documents (the same text) are checked over the
smoke set.

    python3 tests/case_schema_test.py POUNDBENCH SOURCE_DIR
"""
import csv
import glob
import io
import os
import re
import subprocess
import sys
import tempfile
import unittest

POUNDBENCH, SOURCE = sys.argv[1], sys.argv[2]
try:
    import jsonschema  # noqa: F401
except ImportError as e:
    print(f"skipped: {e} (Debian: python3-jsonschema; scripts/setup.sh installs it)")
    sys.exit(77)
SCHEMA = os.path.join(SOURCE, "docs/external/case.schema.json")
CHECKER = f"{sys.executable} {SOURCE}/tests/external/schema_checker.py {SCHEMA}"
# The sets sampled (schema_checker.py --sample: 0.44 ms a pulse's document, 50 ms a real
# record's), and how.
SAMPLED = {"records.toml", "records-real.toml", "records-step.toml", "workprecision-records.toml", "separation.toml"}
ONE_IN = 20
# A spectrum's Pi2 and directivities change no document's shape, only its numbers, whose range
# the smaller sets span (stress.toml's extremes, workprecision-full.toml's 64 Pi2 a family): the
# sets of thousands of points are checked at one Pi2 and one directivity, every family still
# (from a copy whose record paths are absolute). The real-record suite sends every record's
# samples in every document: its 2,250 points took 390 s here, 75 so; the paper's sets and the
# yielding set sent 33,000 documents, 25 s of a core, of which some 300 remain.
ONE_PI2 = {"records-real.toml", "paper.toml", "paper-report.toml", "yielding.toml"}


def at_one_pi2(case_set, folder):
    text = open(case_set).read()
    text = re.sub(r"^pi2 = \{[^}]*\}$", "pi2 = 1", text, flags=re.M)
    text = re.sub(r"^directivity = \[[^]]*\]$", 'directivity = "reverse"', text, flags=re.M)
    records = os.path.join(os.path.dirname(os.path.abspath(case_set)), "..", "records")
    text = text.replace('"../records/', f'"{os.path.normpath(records)}/')
    out = os.path.join(folder, os.path.basename(case_set))
    with open(out, "w") as f:
        f.write(text)
    return out


def rows(case_set, persistent, reduced=False):
    if os.path.basename(case_set) in ONE_PI2 and not reduced:
        with tempfile.TemporaryDirectory() as folder:
            return rows(at_one_pi2(case_set, folder), persistent, reduced=True)
    command = CHECKER + (" --persistent" if persistent else "")
    if persistent and os.path.basename(case_set) in SAMPLED:
        command += f" --sample {ONE_IN}"
    # A sampled set on one thread: the checker samples per process, and two families whose
    # documents have one shape share its first check, so which family gets a check depended on
    # how the sweep's dynamic schedule split the points between two programs (CI failed on it).
    threads = "1" if persistent and os.path.basename(case_set) in SAMPLED else "2"
    flags = ["--persistent"] if persistent else []
    run = subprocess.run([POUNDBENCH, "spectrum", case_set, "--solver", "external", "--command", command,
                          "--threads", threads, *flags], capture_output=True, text=True)
    if run.returncode != 0:
        raise AssertionError(f"{os.path.basename(case_set)}: exit {run.returncode}: {run.stderr[-2000:]}")
    return list(csv.DictReader(io.StringIO(run.stdout)))


class CaseSchema(unittest.TestCase):
    def test_every_family_of_every_shipped_set_sends_valid_documents(self):
        # The buildings scene's sets: the test below, every point (its documents are the schema's
        # buildings branch).
        sets = sorted(f for f in glob.glob(os.path.join(SOURCE, "cases/sets/*.toml"))
                      if 'scene = "buildings"' not in open(f, encoding="utf-8").read())
        self.assertGreater(len(sets), 3)
        kinds = set()
        for case_set in sets:
            with self.subTest(case_set=os.path.basename(case_set)):
                got = rows(case_set, True)
                self.assertTrue(got)
                for r in got:
                    self.assertRegex(r["message"], "^(valid|unchecked): ", f"{r['family']} point {r['point']}")
                    kinds.add(r["message"].split()[1])
                # Every family has documents checked, not only sampled past.
                checked = {r["family"] for r in got if r["message"].startswith("valid: ")}
                self.assertEqual({r["family"] for r in got} - checked, set(), "families with no document checked")
        # The three kinds of load a shipped set has: a program that validates its input takes them all.
        self.assertEqual(kinds, {"pulse", "sinusoids", "record"})

    def test_every_point_of_the_buildings_sets_sends_a_valid_buildings_document(self):
        # Every point (not sampled): a document is a few kB, a record's the samples' size. The
        # stress set adds three buildings in a row, modal damping and contact at some floors.
        kinds = set()
        for name, least in (("buildings.toml", 30), ("buildings-stress.toml", 8)):
            run = subprocess.run([POUNDBENCH, "spectrum", os.path.join(SOURCE, "cases/sets", name), "--solver",
                                  "external", "--command", CHECKER + " --persistent", "--persistent", "--threads", "2"],
                                 capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, run.stderr[-2000:])
            got = list(csv.DictReader(io.StringIO(run.stdout)))
            self.assertGreaterEqual(len({r["point"] for r in got}), least, name)
            for r in got:
                self.assertRegex(r["message"], "^valid: ", f"{name}: {r['family']} point {r['point']}")
                kinds.add(r["message"].split()[1])
        self.assertEqual(kinds, {"pulse", "record"})

    def test_one_shot_documents_are_the_persistent_ones(self):
        # A program a point (each a Python start with jsonschema, 0.1 s): every family of the
        # smoke set at one Pi2.
        with tempfile.TemporaryDirectory() as folder:
            got = rows(at_one_pi2(os.path.join(SOURCE, "cases/sets/smoke.toml"), folder), False)
        self.assertTrue(got)
        for r in got:
            self.assertTrue(r["message"].startswith("valid: "), r["message"])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
