"""examples/python/benchmark_my_solver.py runs as a user runs it: its pure-Python solver goes
through poundbench.workprecision in process, beside Moreau-Jean, and the answer table it prints
places it. At 512 steps per shortest period its Pi1 is within 1e-1 of the reference's at the
95th percentile (measured 6e-4 on the example's Fig. 4-like pair: a first-order scheme, its
error at 32 steps 3e-2), so it has a place at the 1e-1 target; the rows are timed on the CPU
clock as every solver's (cost cpu_seconds), or the script stops with an error.

    python3 tests/python_example_test.py SOURCE_DIR      (PYTHONPATH: the module's directory)
"""
import os
import re
import subprocess
import sys
import unittest

SOURCE = sys.argv[1]


class PythonExample(unittest.TestCase):
    def test_the_example_places_its_solver_in_the_answer_table(self):
        out = subprocess.run([sys.executable, os.path.join(SOURCE, "examples/python/benchmark_my_solver.py")],
                             capture_output=True, text=True, timeout=600)
        self.assertEqual(out.returncode, 0, out.stderr)
        first = out.stdout.split("error <= 0.03")[0]
        self.assertIn("error <= 0.1 at p95", first)
        place = re.search(r"my_solver's place: (\d+)", first)
        self.assertIsNotNone(place, out.stdout)
        self.assertIn("external", first)
        self.assertIn("moreau-jean", first)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
