"""The two external programs of examples/external/, through poundbench's external solver.

    python3 tests/external_examples_test.py POUNDBENCH SOURCE_DIR

- scipy_adapter.py (SciPy's DOP853 between located events, Newton's law at impacts) agrees
  with the reference on Pi1 over wall, pair, row3 and chain cases with eps 0, 0.5 and 1,
  persistent contact, an accumulation of impacts and touching bodies (Pi3 = 0), run as a
  sweep on two threads.
- poundbench_adapter.sh (poundbench answering as an external program) gives the rows of the
  solver it wraps, Pi1 bit for bit, over the smoke set.
- `run --history` takes the history of u0 from the Python program.
"""
import csv
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest

POUNDBENCH, SOURCE = sys.argv[1], sys.argv[2]
try:
    import numpy  # noqa: F401  (what scipy_adapter.py needs)
    import scipy  # noqa: F401
except ImportError as e:
    print(f"skipped: {e} (Debian: python3-numpy python3-scipy; scripts/setup.sh installs them)")
    sys.exit(77)  # ctest's SKIP_RETURN_CODE
PYTHON = sys.executable
SCIPY = f"{PYTHON} {SOURCE}/examples/external/scipy_adapter.py"
WRAPPER = f"sh {SOURCE}/examples/external/poundbench_adapter.sh"
BUILDINGS = f"{SOURCE}/cases/sets/buildings.toml"
BUILDINGS_POINTS = (0, 6)
# Every floor's peak |u| and storey's peak drift of the SciPy program against the buildings'
# exact reference (relative): measured at most 1.5e-9 on BUILDINGS_POINTS at rtol 1e-10; 1e-7 leaves
# room for another SciPy's step choices, as SCIPY_TOLERANCE.
BUILDINGS_TOLERANCE = 1e-7

# Pi1 of the SciPy program against the reference: measured at most 7e-10 (relative) on
# these cases at its default rtol 1e-10; 1e-7 leaves room for another SciPy's step choices.
SCIPY_TOLERANCE = 1e-7

CASES = """name = "external-examples"
[defaults]
pulse = ["sine", "cosine"]
directivity = "reverse"
pi3 = 0.5
eps = [0, 0.5]
pi5 = 0.5
pi6 = 1
pi2 = 1
[[family]]
name = "wall"
scene = "wall"
pi3 = [0, 1]
eps = [0, 1]
[[family]]
name = "pair"
scene = "pair"
[[family]]
name = "accumulation"
scene = "pair"
pulse = "cosine"
pi3 = 0.1
eps = 0.5
pi5 = 4
pi6 = 0.5
pi2 = 2
[[family]]
name = "row3"
scene = "row3"
pi7 = 0.5
pi8 = 1
[[family]]
name = "chain"
scene = "chain"
bodies = 5
pulse = "sine"
directivity = "normal"
pi3 = 0.1
eps = 0.8
pi5 = 1
"""


def poundbench(*args, stdin=None):
    # In a directory of its own: a sweep to stdout keeps its partial file and lock in the
    # working directory, which other tests running at the same time share.
    with tempfile.TemporaryDirectory() as cwd:
        done = subprocess.run([POUNDBENCH, *args], capture_output=True, text=True, input=stdin, cwd=cwd)
    if done.returncode != 0:
        raise AssertionError(f"poundbench {' '.join(args)}: exit {done.returncode}: {done.stderr}")
    return done.stdout


def rows(text):
    return list(csv.DictReader(io.StringIO(text)))


class ExternalExamples(unittest.TestCase):
    def test_scipy_adapter_agrees_with_the_reference(self):
        with tempfile.TemporaryDirectory() as tmp:
            cases = os.path.join(tmp, "cases.toml")
            with open(cases, "w") as f:
                f.write(CASES)
            reference = rows(poundbench("spectrum", cases, "--threads", "2"))
            scipy = rows(poundbench("spectrum", cases, "--threads", "2", "--solver", "external",
                                    "--command", SCIPY))
        self.assertEqual(len(scipy), 18)
        worst = 0.0
        for ref, row in zip(reference, scipy):
            what = f"point {row['point']} ({row['family']} {row['pulse']} pi3={row['pi3']} eps={row['eps']})"
            self.assertEqual(row["status"], "ok", f"{what}: {row['message']}")
            error = abs(float(row["pi1"]) - float(ref["pi1"])) / float(ref["pi1"])
            worst = max(worst, error)
            self.assertLess(error, SCIPY_TOLERANCE, what)
            # Persistent contact is found where the reference finds it (counts of impacts differ
            # in an accumulation: each solver stops counting below its own speed).
            self.assertEqual(int(row["contact_phases"]) > 0, int(ref["contact_phases"]) > 0, what)
            self.assertEqual(row["settings"], '{"command":"%s"}' % SCIPY)
        print(f"worst relative Pi1 error of scipy_adapter.py: {worst:.1e}")
        # Persistent (one Python per worker): the same answers, bit for bit, each with the
        # program's own solve time, and the start reported once per worker.
        with tempfile.TemporaryDirectory() as tmp:
            cases = os.path.join(tmp, "cases.toml")
            with open(cases, "w") as f:
                f.write(CASES)
            persistent = rows(poundbench("spectrum", cases, "--threads", "2", "--solver", "external", "--persistent",
                                         "--command", SCIPY + " --persistent"))
        self.assertEqual([r["pi1"] for r in persistent], [r["pi1"] for r in scipy])
        self.assertTrue(all(float(r["solve_seconds"]) > 0 for r in persistent))
        self.assertTrue(all(float(r["solve_seconds"]) <= float(r["seconds"]) for r in persistent))
        self.assertIn(sum(1 for r in persistent if r["startup_seconds"]), (1, 2))
        one_shot = sorted(float(r["seconds"]) for r in scipy)[9]
        kept = sorted(float(r["seconds"]) for r in persistent)[9]
        print(f"scipy_adapter.py per point, medians: one-shot {1e3 * one_shot:.1f} ms, persistent {1e3 * kept:.1f} ms")

    def test_scipy_adapter_solves_buildings_points(self):
        # Issue 50: the buildings document through the SciPy program (events per contact, Newton's
        # law over the contacts closing together) against the scene's exact reference, floor by
        # floor and storey by storey: a 3-storey against a 6-storey building under a sine pulse,
        # and a stiff 3-storey against a flexible 8-storey one under a cosine (points 0 and 6).
        worst = 0.0
        for point in BUILDINGS_POINTS:
            where = ["--case-file", BUILDINGS, "--point", str(point), "--json"]
            ref = json.loads(poundbench("run", *where))
            got = json.loads(poundbench("run", *where, "--solver", "external", "--command", SCIPY))
            self.assertEqual(got["status"], "ok", got["message"])
            for key in ("floor_peak_m", "drift_peak_m"):
                self.assertEqual([len(b) for b in got[key]], [len(b) for b in ref[key]])
                for b, (mine, theirs) in enumerate(zip(got[key], ref[key])):
                    for i, (x, y) in enumerate(zip(mine, theirs)):
                        error = abs(x - y) / y
                        worst = max(worst, error)
                        self.assertLess(error, BUILDINGS_TOLERANCE, f"point {point} {key} building {b} floor {i + 1}")
            # The same contacts pound, first at the same time.
            for mine, theirs in zip(got["contacts"], ref["contacts"]):
                self.assertEqual(mine["impacts"] > 0, theirs["impacts"] > 0, f"point {point} floor {mine['floor']}")
                if theirs["impacts"]:
                    self.assertAlmostEqual(mine["first_impact_s"], theirs["first_impact_s"], delta=1e-6 * ref["t_end_s"])
        print(f"worst relative floor or drift peak error of scipy_adapter.py on buildings: {worst:.1e}")

    def test_poundbench_adapter_gives_the_wrapped_solvers_rows(self):
        smoke = f"{SOURCE}/cases/sets/smoke.toml"
        os.environ["POUNDBENCH"] = POUNDBENCH  # the binary the wrapper runs
        direct = rows(poundbench("spectrum", smoke, "--threads", "2", "--solver", "moreau-jean", "--steps", "64"))
        wrapped = rows(poundbench("spectrum", smoke, "--threads", "2", "--solver", "external", "--steps", "64",
                                  "--command", f"{WRAPPER} moreau-jean"))
        self.assertEqual(len(wrapped), 40)
        for a, b in zip(direct, wrapped):
            for column in ("status", "pi1", "impacts", "contact_phases", "steps", "min_gap", "wh", "energy_excess"):
                self.assertEqual(a[column], b[column], f"point {a['point']}: {column}")

    def test_run_history_takes_u0_from_the_program(self):
        with tempfile.TemporaryDirectory() as tmp:
            history = os.path.join(tmp, "history.csv")
            poundbench("run", "--scene", "pair", "--pulse", "sine", "--directivity", "normal", "--pi2", "1",
                       "--pi3", "0.5", "--eps", "0.5", "--pi5", "0.5", "--pi6", "1", "--solver", "external",
                       "--command", SCIPY, "--history", history, "--samples", "101")
            with open(history) as f:
                table = list(csv.DictReader(f))
        self.assertEqual(len(table), 101)
        self.assertEqual(list(table[0].keys()), ["t", "u1", "u0", "v1", "v0", "g1", "lambda1"])
        self.assertEqual(float(table[0]["u0"]), 0.0)
        self.assertEqual(table[0]["u1"], "")  # version 1 carries u0 alone
        self.assertGreater(max(abs(float(r["u0"])) for r in table), 1.0)

    def test_documents_have_the_keys_of_their_json_schemas(self):
        schemas = {}
        for name in ("case", "answer"):
            with open(f"{SOURCE}/docs/external/{name}.schema.json") as f:
                schemas[name] = json.load(f)
        def case_of(*extra):
            with tempfile.TemporaryDirectory() as tmp:
                path = os.path.join(tmp, "case.json")
                # tee keeps the case (and its echo is refused as an answer: the run fails, exit 1)
                subprocess.run([POUNDBENCH, "run", "--scene", "wall", "--pulse", "sine", "--directivity", "normal",
                                "--pi2", "1", "--pi3", "1", "--eps", "0.5", "--solver", "external", "--steps", "16",
                                *extra, "--command", f"tee {path}"], capture_output=True, check=False)
                with open(path) as f:
                    return f.read()
        text = case_of()
        case = json.loads(text)
        # Each schema is a choice of its scenes' branches ($defs): the oscillators' here.
        oscillators, answers = schemas["case"]["$defs"]["oscillators"], schemas["answer"]["$defs"]["oscillators"]
        body = oscillators["properties"]["bodies"]["items"]
        self.assertEqual(set(case), set(oscillators["required"]))
        self.assertEqual(set(case["bodies"][0]), set(body["required"]))
        self.assertEqual(set(case["load"]), set(schemas["case"]["$defs"]["load"]["oneOf"][0]["required"]))
        answer = json.loads(poundbench("adapter", "--solver", "moreau-jean", stdin=text))
        self.assertEqual(answer["status"], "ok")
        self.assertLessEqual(set(answer), set(answers["properties"]))
        # A yielding case adds the optional keys (bodies[].u_y, alpha): then every key of the
        # schema is there, and the answer carries residual and hysteretic.
        text = case_of("--pi-y0", "0.5", "--alpha", "0.05")
        case = json.loads(text)
        self.assertEqual(set(case), set(oscillators["properties"]))
        self.assertEqual(set(case["bodies"][0]), set(body["properties"]))
        answer = json.loads(poundbench("adapter", "--solver", "moreau-jean", stdin=text))
        self.assertEqual(answer["status"], "ok")
        self.assertLessEqual({"residual", "hysteretic"}, set(answer))
        self.assertLessEqual(set(answer), set(answers["properties"]))
        # A buildings point: every key of its branch (the rayleigh rule's a0 and a1 too), and the
        # SciPy program's answer within the keys of the buildings answer.
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "case.json")
            subprocess.run([POUNDBENCH, "run", "--case-file", BUILDINGS, "--point", "0", "--solver", "external",
                            "--steps", "16", "--command", f"tee {path}"], capture_output=True, check=False)
            with open(path) as f:
                text = f.read()
        case, branch = json.loads(text), schemas["case"]["$defs"]["buildings"]
        self.assertEqual(set(case), set(branch["required"]))
        self.assertEqual(set(case["buildings"][0]), set(branch["properties"]["buildings"]["items"]["properties"]))
        self.assertEqual(set(case["buildings"][0]["damping"]),
                         set(branch["properties"]["buildings"]["items"]["properties"]["damping"]["properties"]))
        self.assertEqual(set(case["contacts"][0]), set(branch["properties"]["contacts"]["items"]["required"]))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
