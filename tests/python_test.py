"""The Python module (python/poundbench_module.cpp): `import poundbench`.

    PYTHONPATH=build/python python3 tests/python_test.py POUNDBENCH SOURCE_DIR

Its keywords are the command line's flags, its answers those of `run --json` and `spectrum`
(the same numbers, bit for bit), its errors the command line's messages.
"""
import csv
import io
import json
import subprocess
import sys
import os
import tempfile
import unittest
import xml.etree.ElementTree as ET

POUNDBENCH, SOURCE = sys.argv[1], sys.argv[2]
import numpy as np  # noqa: E402
import poundbench  # noqa: E402

CASE = dict(scene="pair", pulse="cosine", directivity="normal", pi2=0.8, pi3=0.5, eps=0.5, pi5=0.5, pi6=1.0)
FLAGS = ["--scene", "pair", "--pulse", "cosine", "--directivity", "normal", "--pi2", "0.8", "--pi3", "0.5",
         "--eps", "0.5", "--pi5", "0.5", "--pi6", "1"]


def cli(*args):
    """poundbench's exit code, stdout and stderr, run in a directory of its own: a sweep to
    stdout keeps its partial file and lock in the working directory, which other tests
    running at the same time share."""
    with tempfile.TemporaryDirectory() as cwd:
        done = subprocess.run([POUNDBENCH, *args], capture_output=True, text=True, cwd=cwd)
    return done.returncode, done.stdout, done.stderr


class Run(unittest.TestCase):
    def test_run_gives_the_command_lines_answer_bit_for_bit(self):
        result = poundbench.run(**CASE, solver="moreau-jean", steps=64)
        code, out, _ = cli("run", *FLAGS, "--solver", "moreau-jean", "--steps", "64", "--json")
        self.assertEqual(code, 0)
        expected = json.loads(out)
        for key in expected:
            if key not in ("seconds", "cpu_seconds"):
                self.assertEqual(result[key], expected[key], key)
        self.assertNotIn("history", result)
        # Its no-contact Pi1 comes from the module's cache from the second call on: the same double.
        self.assertEqual(poundbench.run(**CASE, solver="moreau-jean", steps=64)["pi1_no_contact"],
                         expected["pi1_no_contact"])

    def test_the_dict_is_run_jsons_object_key_for_key_in_its_order(self):
        # Issue 36: run() builds its dict without JSON between; it must stay --json's object: the
        # same keys in the same order, each value equal and of the same type (an int stays an
        # int, null None), the settings too. seconds alone is the run's own clock.
        record = os.path.join(SOURCE, "cases", "records", "real", "B-ELC000.AT2")
        calls = [
            (dict(CASE, solver="moreau-jean", steps=64), [*FLAGS, "--solver", "moreau-jean", "--steps", "64"]),
            (dict(CASE), [*FLAGS]),
            (dict(scene="wall", pulse="cosine", directivity="normal", pi2=1.0, pi3=0.5, eps=0.5, solver="compliant",
                  integrator="newmark"),
             ["--scene", "wall", "--pulse", "cosine", "--directivity", "normal", "--pi2", "1", "--pi3", "0.5",
              "--eps", "0.5", "--solver", "compliant", "--integrator", "newmark"]),
            (dict(scene="pair", pulse="record", record=record, t0=0.5, t1=1, gap=0.01, eps=0.6, m0=2e6,
                  solver="compliant", k_contact=5e9),
             ["--scene", "pair", "--pulse", "record", "--record", record, "--t0", "0.5", "--t1", "1", "--gap", "0.01",
              "--eps", "0.6", "--m0", "2e6", "--solver", "compliant", "--k-contact", "5e9"]),
            (dict(scene="chain", bodies=4, pulse="sine", directivity="reverse", pi2=1.5, pi3=0.2, eps=0.8,
                  pi5=1.2, pi6=0.8, kick=0.0, solver="moreau-jean", wh=0.05),
             ["--scene", "chain", "--bodies", "4", "--pulse", "sine", "--directivity", "reverse", "--pi2", "1.5",
              "--pi3", "0.2", "--eps", "0.8", "--pi5", "1.2", "--pi6", "0.8", "--kick", "0", "--solver", "moreau-jean", "--wh", "0.05"]),
        ]
        for keywords, flags in calls:
            with self.subTest(flags=" ".join(flags)):
                for _ in range(2):  # the second call: the module's kept keys and settings
                    result = poundbench.run(**keywords)
                    code, out, err = cli("run", *flags, "--json")
                    self.assertEqual(code, 0, err)
                    expected = json.loads(out)
                    self.assertEqual(list(result), list(expected))
                    for key in expected:
                        if key not in ("seconds", "cpu_seconds"):
                            self.assertEqual(result[key], expected[key], key)
                            self.assertIs(type(result[key]), type(expected[key]), key)
                    self.assertEqual(list(result["settings"]), list(expected["settings"]))
                    result["settings"]["steps"] = -1  # a row's settings are its own
                    self.assertNotEqual(poundbench.run(**keywords)["settings"], result["settings"])

    def test_the_verdict_is_in_the_dict(self):
        # Issue 32: a run that finished without resolving what it solved says so (Newmark at
        # its defaults on the wall case), as run --json does; the reference's resolves.
        wall = dict(scene="wall", pulse="cosine", directivity="normal", pi2=1.0, pi3=0.5, eps=0.5)
        result = poundbench.run(**wall, solver="compliant", integrator="newmark")
        self.assertEqual(result["status"], "ok")
        self.assertIs(result["resolved"], False)
        self.assertIn("a contact lasted", result["unresolved"])
        self.assertIs(poundbench.run(**wall)["resolved"], True)

    def test_monitor_asks_for_the_monitored_pass_as_the_flag_does(self):
        # Issue 36: a point is solved once unless monitor=True (--monitor) asks for the second,
        # monitored pass, whose measurements then come back as the command line's.
        self.assertIsNone(poundbench.run(**CASE, solver="moreau-jean", monitor=False)["energy_excess"])
        self.assertIsNotNone(poundbench.run(**CASE, solver="moreau-jean")["energy_excess"])  # its one solve
        result = poundbench.run(**CASE, solver="moreau-jean", monitor=True)
        code, out, _ = cli("run", *FLAGS, "--solver", "moreau-jean", "--json", "--monitor")
        self.assertEqual(code, 0)
        self.assertIsNotNone(result["energy_excess"])
        self.assertEqual(result["energy_excess"], json.loads(out)["energy_excess"])

    def test_ctrl_c_stops_a_call_with_keyboard_interrupt(self):
        # The solve runs on the calling thread; SIGINT sets its stop flag (the module's handler,
        # installed on the first call) and is then handed to Python's handler. The paper set at N = 4096 on one
        # thread takes many seconds: the call must end long before.
        import signal
        import threading
        import time
        timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
        started = time.monotonic()
        timer.start()
        with self.assertRaises(KeyboardInterrupt):
            poundbench.spectrum(os.path.join(SOURCE, "cases/sets/paper.toml"), solver="moreau-jean",
                                steps=4096, threads=1)
        timer.join()
        self.assertLess(time.monotonic() - started, 30.0)  # minutes if the interruption is lost
        self.assertIs(signal.getsignal(signal.SIGINT), signal.default_int_handler)

    def test_a_loop_over_the_case_checks_each_calls_solver_keywords(self):
        # run() keeps its last call's solver checks while only the case's numbers change (a loop
        # over Pi2); a solver keyword changed or added is checked again.
        for pi2 in (0.5, 0.8, 2.0):
            self.assertEqual(poundbench.run(**dict(CASE, pi2=pi2), solver="moreau-jean", steps=64)["status"], "ok")
        with self.assertRaisesRegex(ValueError, "--steps: must be >= 1"):
            poundbench.run(**CASE, solver="moreau-jean", steps=-1)
        with self.assertRaisesRegex(ValueError, "--stiffness: not used by moreau-jean"):
            poundbench.run(**CASE, solver="moreau-jean", steps=64, stiffness=10.0)
        self.assertEqual(poundbench.run(**CASE, solver="moreau-jean", steps=64, theta=1.0)["status"], "ok")
        with self.assertRaisesRegex(ValueError, "--theta: must be in"):
            poundbench.run(**CASE, solver="moreau-jean", steps=64, theta=0.25)
        self.assertEqual(poundbench.run(**CASE, solver="moreau-jean", steps=64)["status"], "ok")

    def test_a_loop_over_pi_terms_gives_each_calls_case(self):
        # run() keeps its last case's checks by name while the names, scene, pulse and directivity
        # stay (a loop over Pi terms): each call's case is still its own values, bit for bit as
        # the command line's, and a bad value is still the command line's error.
        for pi2, eps, pi6 in ((0.5, 0.5, 1.0), (2.0, 0.8, 0.5), (0.8, 0.0, 2.0)):
            case = dict(CASE, pi2=pi2, eps=eps, pi6=pi6)
            result = poundbench.run(**case, solver="moreau-jean", steps=64)
            flags = [f for key, value in case.items() for f in ("--" + key, str(value))]
            code, out, err = cli("run", *flags, "--solver", "moreau-jean", "--steps", "64", "--json")
            self.assertEqual(code, 0, err)
            expected = json.loads(out)
            for key in expected:
                if key not in ("seconds", "cpu_seconds"):
                    self.assertEqual(result[key], expected[key], (pi2, eps, key))
        for bad, message in ((dict(eps=1.5), "--eps: "), (dict(pi2=float("nan")), "--pi2: "), (dict(scene="wall"), "--pi5: ")):
            with self.assertRaisesRegex(ValueError, "^" + message):
                poundbench.run(**dict(CASE, **bad), solver="moreau-jean", steps=64)
        self.assertEqual(poundbench.run(**CASE, solver="moreau-jean", steps=64)["pi2"], CASE["pi2"])

    def test_ctrl_c_between_calls_goes_to_pythons_handler(self):
        # The module's SIGINT handler stays installed after a call and hands a SIGINT that comes
        # between calls to the handler it replaced (KeyboardInterrupt); a handler the program
        # sets afterwards gets the next one.
        import signal
        import time
        poundbench.run(**CASE)
        with self.assertRaises(KeyboardInterrupt):
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(2)  # Python runs its handler at the next instruction
        got = []
        previous = signal.signal(signal.SIGINT, lambda *_: got.append(True))
        try:
            poundbench.run(**CASE)
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.1)
            self.assertEqual(got, [True])
        finally:
            signal.signal(signal.SIGINT, previous)

    def test_history_is_one_numpy_array_per_column_of_run_history(self):
        result = poundbench.run(**CASE, samples=101)
        history = result["history"]
        self.assertEqual(list(history), ["t", "u1", "u0", "v1", "v0", "g1", "lambda1"])
        for column in history.values():
            self.assertIsInstance(column, np.ndarray)
            self.assertEqual(column.shape, (101,))
        # Pi1 is the largest |u0| over the run (a_p = w_p = 1): the 101 samples see at most it,
        # and at least 90 % of it (a sample every 1/100 of the run).
        peak = np.max(np.abs(history["u0"]))
        self.assertLessEqual(peak, result["pi1"] * (1 + 1e-12))
        self.assertGreater(peak, 0.9 * result["pi1"])
        self.assertEqual(len(poundbench.run(**CASE, history=True)["history"]["t"]), 2000)

    def test_errors_carry_the_command_lines_messages(self):
        cases = [
            (dict(scene="pair", pulse="cosine", directivity="normal", pi2=0.8), []),
            (dict(CASE, scene="wall"), []),
            (dict(CASE, eps=1.5), []),
            (dict(CASE, solver="no-such-solver"), ["--solver", "no-such-solver"]),
            (dict(CASE, solver="event-driven", steps=8), ["--solver", "event-driven", "--steps", "8"]),
            (dict(CASE, solver="external"), ["--solver", "external"]),
            (dict(CASE, samples=1), ["--history", "h.csv", "--samples", "1"]),
        ]
        for keywords, extra in cases:
            flags = []
            for key, value in keywords.items():
                flags += ["--" + key.replace("_", "-"), str(value)]
            if extra:
                flags = [f for f in FLAGS] + extra
            code, _, err = cli("run", *flags)
            self.assertEqual(code, 2, err)
            with self.assertRaises(ValueError) as raised:
                poundbench.run(**keywords)
            self.assertEqual("poundbench: " + str(raised.exception) + "\n", err, keywords)

    def test_unknown_keywords_and_wrong_types_are_type_errors(self):
        with self.assertRaisesRegex(TypeError, "unexpected keyword argument 'pi9'"):
            poundbench.run(**CASE, pi9=1)
        with self.assertRaisesRegex(TypeError, "steps: must be an int"):
            poundbench.run(**CASE, solver="moreau-jean", steps=6.4)
        with self.assertRaisesRegex(TypeError, "unexpected keyword argument 'pi2'"):
            poundbench.spectrum(f"{SOURCE}/cases/sets/smoke.toml", pi2=1)

    def test_keywords_are_the_flags_of_the_field_tables(self):
        for name in ("n_free", "a_p", "w_p", "tol_scale", "step_cap", "time_limit", "command", "record", "tp",
                     "cycles", "mp_gamma", "mp_nu"):
            self.assertIn(f"    {name}: ", poundbench.run.__doc__)

    def test_a_record_and_a_pulse_model_give_the_command_lines_answers(self):
        record = os.path.join(SOURCE, "cases", "records", "mp-noise-20s.at2")
        loads = [(dict(pulse="record", record=record, tp=2), ["--pulse", "record", "--record", record, "--tp", "2"]),
                 (dict(pulse="mp", mp_gamma=2.5, mp_nu=30), ["--pulse", "mp", "--mp-gamma", "2.5", "--mp-nu", "30"])]
        base = {k: v for k, v in CASE.items() if k != "pulse"}
        flags = [f for i, f in enumerate(FLAGS) if FLAGS[i - 1] != "--pulse" and f != "--pulse"]
        for keywords, load_flags in loads:
            result = poundbench.run(**base, **keywords)
            code, out, _ = cli("run", *flags, *load_flags, "--json")
            self.assertEqual(code, 0)
            self.assertEqual(result["pi1"], json.loads(out)["pi1"])
        # Without tp, the record's mean frequency 2 pi / T_m, as on the command line.
        result = poundbench.run(**base, pulse="record", record=record)
        code, out, _ = cli("run", *flags, "--pulse", "record", "--record", record, "--json")
        self.assertEqual(code, 0)
        self.assertEqual(result["pi1"], json.loads(out)["pi1"])
        self.assertEqual(result["w_p"], json.loads(out)["w_p"])


    def test_physical_keywords_and_k_contact_give_the_command_lines_answers(self):
        record = os.path.join(SOURCE, "cases", "records", "real", "B-ELC000.AT2")
        keywords = dict(scene="pair", pulse="record", record=record, t0=0.5, t1=1, gap=0.01, eps=0.6, m0=2e6,
                        solver="compliant", k_contact=5e9)
        flags = ["--scene", "pair", "--pulse", "record", "--record", record, "--t0", "0.5", "--t1", "1", "--gap",
                 "0.01", "--eps", "0.6", "--m0", "2e6", "--solver", "compliant", "--k-contact", "5e9"]
        result = poundbench.run(**keywords)
        code, out, err = cli("run", *flags, "--json")
        self.assertEqual(code, 0, err)
        expected = json.loads(out)
        for key in ("pi1", "pi2", "pi3", "peak_m", "impact_velocity", "first_impact_s", "contact_force_max", "t0",
                    "gap", "settings"):
            self.assertEqual(result[key], expected[key], key)
        with self.assertRaisesRegex(ValueError, "--pi3: not with --t0"):
            poundbench.run(**{**keywords, "pi3": 1})


class Buildings(unittest.TestCase):
    def test_a_buildings_point_is_run_jsons_object_as_a_dict(self):
        # Issue 49: run(case_file=..., point=...) on a buildings set solves it with the scene's
        # reference; its dict is --json's object, key for key, but the run's own clocks.
        buildings = f"{SOURCE}/cases/sets/buildings.toml"
        for point in (0, 10):
            result = poundbench.run(case_file=buildings, point=point)
            code, out, _ = cli("run", "--case-file", buildings, "--point", str(point), "--json")
            self.assertEqual(code, 0)
            expected = json.loads(out)
            self.assertEqual(list(result), list(expected))
            for key in expected:
                if key not in ("seconds", "cpu_seconds"):
                    self.assertEqual(result[key], expected[key], key)
            self.assertEqual(len(result["floor_peak_m"]), 2)
            self.assertEqual(result["contacts"][0]["left"], 0)
        self.assertIn("floor_peak_pi", result)  # point 10 is in Pi terms

    def test_spectrum_of_a_buildings_set_gives_a_row_per_floor(self):
        rows = poundbench.spectrum(f"{SOURCE}/cases/sets/buildings.toml", threads=2)
        point0 = poundbench.run(case_file=f"{SOURCE}/cases/sets/buildings.toml", point=0)
        first = [r for r in rows if r["point"] == 0]
        self.assertEqual(len(first), sum(len(b) for b in point0["floor_peak_m"]))
        for r in first:
            self.assertEqual(r["floor_peak_m"], point0["floor_peak_m"][r["building"]][r["floor"] - 1])
            self.assertEqual(r["floor_peak_no_contact_m"], point0["floor_peak_no_contact_m"][r["building"]][r["floor"] - 1])

    def test_another_solver_is_refused_by_name(self):
        with self.assertRaisesRegex(ValueError, r"no-such does not solve the buildings scene \(these do: .*external"):
            poundbench.run(case_file=f"{SOURCE}/cases/sets/buildings.toml", point=0, solver="no-such")

    def test_a_callable_solves_a_buildings_point_from_its_document(self):
        # Issue 50: solver=f gets the scene's case document as a dict and returns its answer;
        # run() reports what f said, and spectrum() makes its rows, as for any solver.
        buildings = f"{SOURCE}/cases/sets/buildings.toml"
        seen = []

        def stiffness_over_mass(case):
            seen.append(case)
            # A made-up "solver": each floor's peak its storey's k / m over 1e6 (m), something f
            # computes from the document, so that a lost or reordered number shows.
            peaks = [[k / m / 1e6 for k, m in zip(b["stiffnesses"], b["masses"])] for b in case["buildings"]]
            return {"status": "ok", "message": "made up", "floor_peak": peaks, "drift_peak": peaks,
                    "contacts": [{"impacts": c["floor"], "impact_velocity_max": 0.5, "first_impact": 0.25}
                                 for c in case["contacts"]]}

        result = poundbench.run(case_file=buildings, point=0, solver=stiffness_over_mass)
        case = seen[0]
        self.assertEqual(case["scene"], "buildings")
        self.assertEqual(len(case["buildings"]), 2)
        self.assertEqual(len(case["buildings"][1]["C"]), 6)  # 6 storeys: C is 6 x 6
        self.assertEqual(case["buildings"][0]["damping"]["rule"], "rayleigh")
        self.assertEqual(result["status"], "ok", result["message"])
        self.assertEqual(result["message"], "made up")
        self.assertEqual(result["floor_peak_m"], [[6.6e8 / 3e5 / 1e6] * 3, [5.7e8 / 3e5 / 1e6] * 6])
        self.assertEqual([c["impacts"] for c in result["contacts"]], [1, 2, 3])
        self.assertEqual(result["contacts"][2]["first_impact_s"], 0.25)
        self.assertEqual(result["solver"], "external")
        # spectrum(): a row per floor with the callable's peaks, on one thread.
        with tempfile.TemporaryDirectory() as tmp:
            one = os.path.join(tmp, "one.toml")
            with open(buildings) as f:
                text = f.read()
            with open(one, "w") as f:  # the first family alone, one pulse and directivity
                f.write(text.split("# 5 storeys against 8")[0].replace('pulse = ["sine", "cosine"]', 'pulse = "sine"')
                        .replace('directivity = ["normal", "reverse"]', 'directivity = "normal"')
                        .replace("../records/", f"{SOURCE}/cases/records/"))
            rows = poundbench.spectrum(one, solver=stiffness_over_mass)
        self.assertEqual(len(rows), 9)
        self.assertEqual(rows[8]["floor_peak_m"], 5.7e8 / 3e5 / 1e6)
        self.assertEqual(rows[0]["settings"], json.dumps({"command": "python Buildings.test_a_callable_solves_a_buildings_point_from_its_document.<locals>.stiffness_over_mass"}, separators=(",", ":")))

    def test_run_takes_a_callable_on_the_single_oscillators_too(self):
        seen = []
        result = poundbench.run(**CASE, solver=lambda case: seen.append(case) or {"status": "ok", "pi1": 1.5})
        self.assertEqual(result["status"], "ok", result["message"])
        self.assertEqual(result["pi1"], 1.5)
        self.assertNotIn("scene", seen[0])  # the oscillators' document
        self.assertEqual(len(seen[0]["bodies"]), 2)

    def test_a_callables_bad_answer_or_exception_is_the_points_failure(self):
        buildings = f"{SOURCE}/cases/sets/buildings.toml"
        result = poundbench.run(case_file=buildings, point=0, solver=lambda case: {"status": "ok", "floor_peak": [[1]]})
        self.assertEqual(result["status"], "failed")
        self.assertTrue(result["message"].startswith("answer: floor_peak: must be an array of 2 arrays"), result["message"])
        self.assertEqual(result["floor_peak_m"], [])

        def broken(case):
            raise ZeroDivisionError("division by zero")
        result = poundbench.run(case_file=buildings, point=0, solver=broken)
        self.assertEqual(result["status"], "failed")
        self.assertIn("ZeroDivisionError: division by zero", result["message"])


class Spectrum(unittest.TestCase):
    def test_spectrum_gives_the_rows_of_the_command_line(self):
        smoke = f"{SOURCE}/cases/sets/smoke.toml"
        rows = poundbench.spectrum(smoke, solver="moreau-jean", steps=32, threads=2)
        code, out, _ = cli("spectrum", smoke, "--solver", "moreau-jean", "--steps", "32", "--threads", "2")
        self.assertEqual(code, 0)
        expected = list(csv.DictReader(io.StringIO(out)))
        self.assertEqual(len(rows), len(expected))
        for row, line in zip(rows, expected):
            self.assertEqual(row["point"], int(line["point"]))
            self.assertEqual(row["case_file"], smoke)
            self.assertEqual(row["pi1"], float(line["pi1"]))  # the CSV's text reads back to the same double
            self.assertEqual(row["status"], line["status"])
            self.assertEqual(row["impacts"], int(line["impacts"]))

    def test_a_bad_case_set_is_the_command_lines_value_error(self):
        code, _, err = cli("spectrum", "no-such-file.toml")
        self.assertEqual(code, 2)
        with self.assertRaises(ValueError) as raised:
            poundbench.spectrum("no-such-file.toml")
        self.assertEqual("poundbench: " + str(raised.exception) + "\n", err)
        with self.assertRaisesRegex(ValueError, "^--threads: must be >= 1$"):
            poundbench.spectrum(f"{SOURCE}/cases/sets/smoke.toml", threads=0)


def same_field(value, text):
    """A dict's value is the CLI's CSV field: an empty field is None, a number reads back to
    the same double (both are the same row's text), text is text."""
    if value is None:
        return text == ""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        try:
            return float(text) == value
        except ValueError:
            return False
    return str(value) == text


# The timing columns: measured anew by every run, so never the same twice.
TIMING = ("seconds", "cpu_seconds", "solve_seconds", "startup_seconds", "cpu_median_s", "cpu_median_low_s",
          "cpu_median_high_s")


def csv_rows(path):
    """A CSV file's rows, without the comment lines a baseline file starts with."""
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


class Studies(unittest.TestCase):
    """stress, baseline and compare from Python return what the command writes for the same
    input: the same rows, in the same order, field for field (the timing columns aside)."""

    SMOKE = f"{SOURCE}/cases/sets/smoke.toml"
    SETTINGS = [{"solver": "moreau-jean", "wh": [0.5, 100]}]
    SETTINGS_TOML = 'name = "python"\n[[run]]\nsolver = "moreau-jean"\nwh = [0.5, 100]\n'

    def assert_same_rows(self, rows, expected):
        self.assertEqual(len(rows), len(expected))
        self.assertGreater(len(rows), 0)
        for row, line in zip(rows, expected):
            self.assertEqual(list(row), list(line))  # the same columns, in the same order
            for key, text in line.items():
                if key not in TIMING:
                    self.assertTrue(same_field(row[key], text), f"{key}: {row[key]!r} against the CLI's {text!r}")

    def cli_study(self, command, *flags):
        """The CSV rows `poundbench COMMAND SMOKE --settings (SETTINGS) --out FILE FLAGS` writes."""
        with tempfile.TemporaryDirectory() as d:
            settings = os.path.join(d, "settings.toml")
            with open(settings, "w") as f:
                f.write(self.SETTINGS_TOML)
            out = os.path.join(d, "out.csv")
            code, _, err = cli(command, self.SMOKE, "--settings", settings, "--out", out, *flags)
            self.assertEqual(code, 0, err)
            return csv_rows(out)

    def test_stress_gives_the_rows_of_the_command_line(self):
        expected = self.cli_study("stress", "--repetitions", "1")
        rows = poundbench.stress(self.SMOKE, settings=self.SETTINGS, repetitions=1)
        self.assert_same_rows(rows, expected)
        self.assertTrue(any(r["accuracy"] == "fail" for r in rows))  # wh = 100 misses the impacts

    def test_baseline_gives_the_rows_the_command_line_stores(self):
        expected = self.cli_study("baseline")
        rows = poundbench.baseline(self.SMOKE, settings=self.SETTINGS)
        self.assert_same_rows(rows, expected)
        self.assertEqual({r["solver"] for r in rows}, {"event-driven", "moreau-jean"})

    def test_compare_gives_the_lines_of_the_command_line(self):
        # Moreau-Jean's rows at N = 32 against the stored reference: some families pass 2e-2
        # (pair-stiff-elastic 1.0e-2), some do not (wall-touching 6.6e-2), so both verdicts are compared.
        stored = f"{SOURCE}/tests/baselines/smoke.csv"
        with tempfile.TemporaryDirectory() as d:
            rows_file = os.path.join(d, "rows.csv")
            code, _, err = cli("spectrum", self.SMOKE, "--solver", "moreau-jean", "--steps", "32", "--out", rows_file)
            self.assertEqual(code, 0, err)
            junit = os.path.join(d, "compare.xml")
            code, out, err = cli("compare", rows_file, "--baseline", stored, "--tolerance", "2e-2", "--junit", junit)
            self.assertIn(code, (0, 1), err)
            cases = ET.parse(junit).getroot().iter("testcase")
            expected = [(c.get("name"), c.find("failure") is None) for c in cases]
            lines = poundbench.compare(rows_file, baseline=stored, tolerance=2e-2)
        self.assertEqual(len(lines), len(expected))
        self.assertEqual({line["passed"] for line in lines}, {True, False})
        text = out.splitlines()
        for line, (name, passed) in zip(lines, expected):
            self.assertEqual(line["passed"], passed, name)
            self.assertIn(line["family"], name)
            self.assertEqual(line["tolerance"], 2e-2)
            # Its line of the printed table: the family, the counts, the verdict.
            printed = next(t.split() for t in text if t.split()[:1] == [line["family"]])
            self.assertEqual(printed[-1], "pass" if passed else "FAIL")
            if line["compared"]:  # printed to 3 significant digits: within half a unit of the third
                self.assertAlmostEqual(float(printed[-3]), line["max_difference"], delta=5e-3 * line["max_difference"])
            self.assertEqual([int(x) for x in printed[-7:-3]],
                             [line["compared"], line["failed"], line["unmatched"], line["missing"]])
        self.assertEqual(code, 0 if all(line["passed"] for line in lines) else 1)


class Callable(unittest.TestCase):
    """A Python function as the solver, in process (issue 37)."""

    SMOKE = f"{SOURCE}/cases/sets/smoke.toml"

    def test_what_the_function_raises_is_that_points_failed_row_and_the_sweep_goes_on(self):
        calls = []

        def solver(case):
            calls.append(case)
            if len(calls) == 3:
                return 1 / 0
            return {"status": "ok", "pi1": 1.0 + len(calls)}

        rows = poundbench.spectrum(self.SMOKE, solver=solver)
        self.assertEqual(len(rows), 40)  # every point of the set, the ones after the failure too
        self.assertEqual(len(calls), 40)
        failed = [r for r in rows if r["status"] != "ok"]
        self.assertEqual(len(failed), 1)
        self.assertEqual(failed[0]["status"], "failed")
        self.assertIn("ZeroDivisionError: division by zero", failed[0]["message"])
        self.assertIsNone(failed[0]["pi1"])
        self.assertTrue(all(r["pi1"] is not None and r["pi1"] >= 2.0 for r in rows if r["status"] == "ok"))
        # The same in a study: the function's failed row counts as a failed run of its setting.
        calls.clear()
        table = poundbench.workprecision(self.SMOKE, settings=[{"solver": "mine", "steps": [16]}],
                                         solvers={"mine": solver}, repetitions=1)
        mine = [r for r in table if r["solver"] == "external"]
        self.assertEqual(sum(r["points"] for r in mine), 40)
        self.assertEqual(sum(r["failed"] for r in mine), 1)

    def test_a_study_writes_its_table_and_points_for_the_report(self):
        # out= and points= write what the command's --out and --points do, so that a Python user
        # reports the study with `poundbench report`; a place that cannot be written fails first.
        with tempfile.TemporaryDirectory() as folder:
            out, points = os.path.join(folder, "wp.csv"), os.path.join(folder, "points.csv")
            table = poundbench.workprecision(self.SMOKE, settings=[{"solver": "moreau-jean", "steps": [16, 32]}],
                                             repetitions=1, out=out, points=points)
            with open(out, newline="") as f:
                written = list(csv.DictReader(f))
            self.assertEqual(len(written), len(table))
            self.assertEqual([r["settings"] for r in written], [r["settings"] for r in table])
            with open(points, newline="") as f:
                runs = list(csv.DictReader(f))
            self.assertEqual(len(runs), 40 * 3)  # the truth and the two settings, every point
            report = subprocess.run([POUNDBENCH, "report", out, "--points", points, "--out",
                                     os.path.join(folder, "report")], capture_output=True, text=True)
            self.assertEqual(report.returncode, 0, report.stderr)
            with self.assertRaisesRegex(ValueError, "out: "):
                poundbench.workprecision(self.SMOKE, settings=[{"solver": "moreau-jean", "steps": [16]}],
                                         out=os.path.join(folder, "no-such-folder", "wp.csv"))

    def test_ctrl_c_stops_a_sweep_over_a_function_and_writes_nothing(self):
        # A child process sweeps the smoke set (40 points) through a function that takes
        # 0.5 s a call, 20 s in all; SIGINT after its first call must end it with
        # KeyboardInterrupt within 12 s (the call under way finishes, 0.5 s; the rest is the
        # sweep winding down and the interpreter's exit: about a second, ten times that on a
        # slow or loaded machine), and leave no file behind in its working directory (no
        # partial file, no lock).
        import signal
        import time
        child = f"""
import sys, time
import poundbench
def slow(case):
    print("called", flush=True)
    time.sleep(0.5)
    return {{"status": "ok", "pi1": 1.0}}
if sys.argv[1] == "spectrum":
    poundbench.spectrum({self.SMOKE!r}, solver=slow)
else:
    poundbench.workprecision({self.SMOKE!r}, settings=[{{"solver": "slow", "steps": [16]}}], solvers={{"slow": slow}},
                             repetitions=1)
print("finished", flush=True)
"""
        for function in ("spectrum", "workprecision"):
            with tempfile.TemporaryDirectory() as cwd:
                process = subprocess.Popen([sys.executable, "-c", child, function], cwd=cwd, stdout=subprocess.PIPE,
                                           stderr=subprocess.PIPE, text=True)
                self.assertEqual(process.stdout.readline(), "called\n")
                process.send_signal(signal.SIGINT)
                sent = time.monotonic()
                out, err = process.communicate(timeout=30)
                elapsed = time.monotonic() - sent
                self.assertNotEqual(process.returncode, 0, function)
                self.assertIn("KeyboardInterrupt", err, function)
                self.assertNotIn("finished", out, function)
                self.assertLess(elapsed, 12.0, function)
                self.assertEqual(os.listdir(cwd), [], function)

    # Three wall points, for the tests whose calls take seconds each.
    THREE = """name = "three"
[[family]]
name = "wall-sine"
scene = "wall"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi2 = { from = 0.5, to = 2, points = 3, spacing = "linear" }
"""

    def test_a_call_past_its_time_limit_is_that_points_time_limit_row(self):
        # Issue 46: a 2 s solve at time_limit=0.5 gave every row ok. A call still running at
        # its limit is interrupted (poundbench.TimeLimitExceeded raised in it, which `except
        # Exception` does not take); one in C code (time.sleep) takes it when it returns, and
        # one that swallows it is judged by its time. Each is its point's time-limit row, with
        # its time; a quick call under the same limit stays ok.
        import time

        def busy(case):
            start = time.monotonic()
            try:
                while time.monotonic() - start < 20.0:
                    pass
            except Exception:  # not TimeLimitExceeded
                pass
            return {"status": "ok", "pi1": 1.0}

        def sleepy(case):
            time.sleep(0.7)
            return {"status": "ok", "pi1": 1.0}

        def stubborn(case):
            start = time.monotonic()
            while time.monotonic() - start < 0.7:
                try:
                    while time.monotonic() - start < 0.7:
                        pass
                except BaseException:
                    pass
            return {"status": "ok", "pi1": 1.0}

        with tempfile.TemporaryDirectory() as d:
            three = os.path.join(d, "three.toml")
            with open(three, "w") as f:
                f.write(self.THREE)
            for solver, how in ((busy, "was interrupted"), (sleepy, "after"), (stubborn, "after")):
                rows = poundbench.spectrum(three, solver=solver, time_limit=0.5)
                self.assertEqual(len(rows), 3, solver.__name__)
                for row in rows:
                    self.assertEqual(row["status"], "time-limit", (solver.__name__, row["message"]))
                    self.assertIn("s of wall time: the function", row["message"], solver.__name__)
                    self.assertIn(how, row["message"], solver.__name__)
                    self.assertIsNone(row["pi1"])
                    # The call's CPU on its thread: a sleeping call spends next to none.
                    if solver is sleepy:
                        self.assertLess(row["solve_seconds"], 0.45)
                    self.assertNotIn("\n", row["message"])
                    if solver is busy:  # stopped, not run out: 20 s a call otherwise
                        self.assertLess(row["solve_seconds"], 10.0)
            quick = poundbench.spectrum(three, solver=lambda case: {"status": "ok", "pi1": 1.0}, time_limit=0.5)
            self.assertEqual([r["status"] for r in quick], ["ok"] * 3)
            # A study's run takes its time_limit from its settings.
            table = poundbench.workprecision(three, settings=[{"solver": "mine", "steps": [16], "time_limit": 0.5}],
                                             solvers={"mine": busy}, repetitions=1)
            mine = [r for r in table if r["solver"] == "external"]
            self.assertEqual(sum(r["points"] for r in mine), 3)
            self.assertEqual(sum(r["failed"] for r in mine), 3)
        self.assertTrue(issubclass(poundbench.TimeLimitExceeded, BaseException))
        self.assertFalse(issubclass(poundbench.TimeLimitExceeded, Exception))

    def test_ctrl_c_inside_a_nested_poundbench_call_stops_the_outer_sweep(self):
        # A function that calls poundbench.run itself: Ctrl-C during that inner run (the
        # inner call stops and raises KeyboardInterrupt in the function), or after it (Python
        # code of the function), must stop the outer sweep with KeyboardInterrupt. Before, the
        # inner call left the module's handler without a sweep to stop: the first case became
        # the point's failed row and the sweep went on (40 calls of seconds each), the second
        # likewise. 20 s is a hang bound: the sweep ends within a second of the signal.
        import signal
        child = f"""
import sys, time
import poundbench
def f(case):
    print("called", flush=True)
    steps = 32768 if sys.argv[1] == "inside" else 64  # seconds, or a moment
    poundbench.run(scene="pair", pulse="cosine", directivity="normal", pi2=0.8, pi3=0.5, eps=0.5, pi5=0.5,
                   pi6=1.0, solver="moreau-jean", steps=steps, n_free=1000)
    time.sleep(0.5)
    return {{"status": "ok", "pi1": 1.0}}
poundbench.spectrum({self.SMOKE!r}, solver=f)
print("finished", flush=True)
"""
        for when in ("inside", "after"):
            with tempfile.TemporaryDirectory() as cwd:
                process = subprocess.Popen([sys.executable, "-c", child, when], cwd=cwd, stdout=subprocess.PIPE,
                                           stderr=subprocess.PIPE, text=True)
                self.assertEqual(process.stdout.readline(), "called\n")
                if when == "after":
                    import time
                    time.sleep(0.2)  # the inner run has returned (64 steps a period): the function sleeps
                process.send_signal(signal.SIGINT)
                try:
                    out, err = process.communicate(timeout=20)
                except subprocess.TimeoutExpired:
                    process.kill()
                    out, err = process.communicate()
                    self.fail(f"{when}: the sweep went on after Ctrl-C")
                self.assertNotEqual(process.returncode, 0, when)
                self.assertIn("KeyboardInterrupt", err, when)
                self.assertNotIn("finished", out, when)
                self.assertEqual(out.count("called"), 0, when)  # no further point was started


class WithoutNumPy(unittest.TestCase):
    def test_a_history_without_numpy_is_one_line_naming_the_package(self):
        # NumPy hidden from the import (a None entry in sys.modules makes `import numpy` fail
        # as when it is not installed): the module loads, a run without history works, and
        # one with a history raises ImportError in one line that names the package.
        child = f"""
import sys
sys.modules["numpy"] = None
import poundbench
case = {CASE!r}
assert poundbench.run(**case)["status"] == "ok"
try:
    poundbench.run(**case, history=True)
except ImportError as e:
    print(e)
"""
        done = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        lines = done.stdout.splitlines()
        self.assertEqual(len(lines), 1, done.stdout)
        self.assertIn("NumPy", lines[0])
        self.assertIn("python3-numpy", lines[0])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
