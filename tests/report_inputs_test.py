#!/usr/bin/python3
"""`poundbench report` on hostile study outputs (issue 46, items 5 and 9), on a work-precision
study of its own (a wall and a pair family, three points each, Moreau-Jean at N = 16, 32, 64
and the loosened reference):

  - an input that lies in --out under a name the report writes (README.md, report.html, a
    figure's) is refused in one line, exit 2, before anything is written: the input is
    unchanged and nothing new is in --out;
  - families named with '|', '/', a line end or 5,000 characters give a whole report: exit 0,
    nothing on stderr, every answer row with its six cells, every figure linked and written;
  - a value outside its column's domain (a negative or NaN error, a negative cost, more
    failed runs than runs, a settings field that is no JSON object...) is refused in one line
    naming the file, the line and the column, exit 2, and no --out folder appears;
  - the answer and the page's data read each summary row a bounded number of times, whatever
    the number of families (a measure of work, not a time: ten times the families is at most
    ten times the row visits, where it was a hundred);
  - a diagram of thousands of settings is drawn in a few artists, not one per point.

    report_inputs_test.py POUNDBENCH SOURCE_DIR

Exit 77 (skipped, saying so) where this interpreter has no matplotlib."""

import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

POUNDBENCH, SOURCE = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SOURCE, "reports"))
SKIP = 77

CASES = """name = "two"
[[family]]
name = "wall"
scene = "wall"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi2 = [0.5, 1, 2]

[[family]]
name = "pair"
scene = "pair"
pulse = "cosine"
directivity = "reverse"
eps = 1
pi3 = 0.5
pi5 = 1.33
pi6 = 2
pi2 = [0.5, 1, 2]
"""

SETTINGS = """name = "three"
reference_tol_scale = 0.01
[[run]]
solver = "moreau-jean"
theta = 0.5
steps = [16, 32, 64]
[[run]]
solver = "event-driven"
tol_scale = 100
"""


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows


def write(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


def listing(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, files in os.walk(folder) for f in files)


class Study(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        for name, text in (("two.toml", CASES), ("three.toml", SETTINGS)):
            with open(os.path.join(d, name), "w") as f:
                f.write(text)
        subprocess.run([POUNDBENCH, "workprecision", "two.toml", "--settings", "three.toml", "--out", "wp.csv",
                        "--points", "points.csv", "--threads", "1", "--repetitions", "1"],
                       cwd=d, check=True, capture_output=True, timeout=300)
        cls.summary, cls.points = read(os.path.join(d, "wp.csv")), read(os.path.join(d, "points.csv"))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def setUp(self):
        self.dir = tempfile.mkdtemp(dir=self.tmp.name)

    def tearDown(self):
        shutil.rmtree(self.dir)

    def path(self, *parts):
        return os.path.join(self.dir, *parts)

    def report(self, *args):
        return subprocess.run([POUNDBENCH, "report", *args], capture_output=True, text=True, timeout=600,
                              cwd=self.dir)

    def refused(self, out, *args, saying=""):
        """The report of args is exit 2 with one poundbench line holding `saying`."""
        self.assertEqual(out.returncode, 2, f"report {args}: {out.stderr}")
        lines = out.stderr.splitlines()
        self.assertEqual(len(lines), 1, out.stderr)
        self.assertTrue(lines[0].startswith("poundbench: ") and saying in lines[0], lines[0])
        self.assertNotIn("Traceback", out.stderr)

    def study_files(self, summary=None, points=None):
        write(self.path("s.csv"), summary or self.summary)
        write(self.path("p.csv"), points or self.points)
        return self.path("s.csv"), self.path("p.csv")

    # ---------------------------------------------------------------- item 5

    def test_an_input_in_out_under_a_name_the_report_writes_is_refused_before_writing(self):
        study, points = self.study_files()
        first = self.report(study, "--points", points, "--out", self.path("first"))
        self.assertEqual(first.returncode, 0, first.stderr)
        figure = sorted(os.listdir(self.path("first", "figures")))[0]
        for flag, name in (("STUDY", "README.md"), ("--points", "report.html"), ("--points", f"figures/{figure}")):
            out = self.path(f"out-{name.replace('/', '-')}")
            os.makedirs(os.path.dirname(os.path.join(out, name)), exist_ok=True)
            target = os.path.join(out, name)
            shutil.copy(study if flag == "STUDY" else points, target)
            with open(target, "rb") as f:
                before = f.read()
            args = [target, "--points", points] if flag == "STUDY" else [study, "--points", target]
            result = self.report(*args, "--out", out)
            self.refused(result, *args, saying=f"{flag}: {target}: would be overwritten by --out's {name}")
            with open(target, "rb") as f:
                self.assertEqual(f.read(), before, f"{name} was overwritten")
            self.assertEqual(listing(out), [name], f"the refused report left files in {out}")
            self.assertEqual([n for n in os.listdir(self.dir) if n.endswith(".tmp")], [])

    def test_a_study_beside_its_report_in_out_is_read_and_kept(self):
        study, points = self.study_files()
        result = self.report(study, "--points", points, "--out", self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(read(study), self.summary)
        self.assertTrue(os.path.isfile(self.path("README.md")) and os.path.isfile(self.path("report.html")))
        self.assertEqual([n for n in os.listdir(self.dir) if n.startswith(".")], [], "a staging folder was left")

    # ---------------------------------------------------------------- item 9: names

    def test_family_names_with_separators_and_5000_characters_give_a_whole_report(self):
        names = {"wall": "east|west/" + "L" * 5000, "pair": "pair\nwith a line end [and] a/b|c"}
        summary = [dict(r, family=names[r["family"]]) for r in self.summary]
        points = [dict(r, family=names[r["family"]]) for r in self.points]
        study, pts = self.study_files(summary, points)
        for args in ([study, "--points", pts], [study]):
            out = self.path("out" + str(len(args)))
            result = self.report(*args, "--out", out)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertEqual(result.stderr, "")
            with open(os.path.join(out, "README.md")) as f:
                readme = f.read()
            rows = [line for line in readme.splitlines() if re.match(r"\| [^|].* \| 0\.1 \| ", line)]
            self.assertTrue(rows, readme[:2000])
            for line in rows:  # six cells: five unescaped '|' inside the row's two ends
                self.assertEqual(len(re.findall(r"(?<!\\)\|", line)), 7, line[:200])
            figures = re.findall(r"!\[.*\]\((figures/[^)]+)\)", readme)
            self.assertTrue(figures)
            for figure in figures:
                self.assertTrue(os.path.isfile(os.path.join(out, figure)), figure)
            with open(os.path.join(out, "report.html")) as f:
                page = f.read()
            data = json.loads(re.search(r'id="report-data">(.*?)</script>', page, re.S).group(1).replace("<\\/", "</"))
            self.assertEqual(set(data["answer"]["families"]), set(names.values()))

    # ---------------------------------------------------------------- item 9: domains

    def test_values_outside_their_domain_are_refused_naming_line_and_column(self):
        bad = [("summary", 3, "err_median", "-1", "must be a number >= 0"),
               ("summary", 2, "err_p95", "nan", "must be a number >= 0"),
               ("summary", 4, "cpu_median_s", "-1e-06", "must be a finite number >= 0"),
               ("summary", 2, "cpu_median_s", "inf", "must be a finite number >= 0"),
               ("summary", 5, "failed", "99", "must be at most points (3)"),
               ("summary", 2, "points", "2.5", "must be a whole number >= 0"),
               ("summary", 3, "settings", "{\"steps\": 1.5}", "steps: must be a whole number >= 1"),
               ("summary", 3, "settings", "[1, 2]", "not a JSON object"),
               ("points", 4, "pi2", "-1", "must be a finite number > 0"),
               ("points", 6, "pi1", "-0.5", "must be a number >= 0"),
               ("points", 7, "cpu_seconds", "nan", "must be a finite number >= 0")]
        from study import InputError, Study as Read

        for i, (which, line, column, value, why) in enumerate(bad):
            summary, points = [dict(r) for r in self.summary], [dict(r) for r in self.points]
            (summary if which == "summary" else points)[line - 2][column] = value
            study, pts = self.study_files(summary, points)
            saying = f"{study if which == 'summary' else pts}:{line}: {column}: {why}"
            if i < 2:  # the command: exit 2, one line, no folder
                out = self.path("out")
                self.refused(self.report(study, "--points", pts, "--out", out), column, value, saying=saying)
                self.assertFalse(os.path.exists(out), f"{column} = {value}: the refused report made its folder")
            else:  # the reader the command runs first, in this process (a second a run saved)
                with self.assertRaises(InputError, msg=f"{column} = {value}") as refusal:
                    Read(study, pts)
                self.assertIn(saying, str(refusal.exception))

    # ---------------------------------------------------------------- item 9: scale

    def test_the_answer_and_the_page_read_each_row_a_bounded_number_of_times(self):
        import answer
        import page
        import wp

        def visits(families):
            rows = Visited(synthetic_summary(families, 10))
            answer.answer_tables(rows, {})
            answer.beats_table(rows)
            answer.cost_table(rows)
            p = page.Page("t")
            p.answer(rows, answer.scopes(rows, {}), None)
            p.diagrams(rows, wp.panels_of)
            return rows.visits

        small, large = visits(20), visits(200)
        # Linear work is 10x the visits for 10x the rows; each scope's scan of every row (the
        # old answer) made it 100x.
        self.assertLessEqual(large, 12 * small, f"{small} row visits at 20 families, {large} at 200")

    def test_a_diagram_of_thousands_of_settings_is_drawn_in_a_few_artists(self):
        import wp

        drawn = []  # each figure's axes' titles and artist counts as it was saved (a figure is drawn again)
        saved = wp.save
        wp.save = lambda fig, out_dir, stem, vector=True: drawn.append(
            [(ax.get_title(), len(ax.lines) + len(ax.collections)) for ax in fig.axes]) or f"figures/{stem}.png"
        try:
            # one family: 2,000 Moreau-Jean configurations of one setting each (a crowd), and one
            # ODE configuration of 2,000 step counts (a line)
            rows = synthetic_summary(1, 2000, configurations=2000) + synthetic_summary(1, 2000, solver="ode")
            wp.wp_diagrams(rows, self.dir)
        finally:
            wp.save = saved
        self.assertTrue(drawn)
        for axes in drawn:
            for title, artists in axes:
                # a line, two kinds of marker and the bars per configuration up to wp.MAX_LINES (18),
                # else a crowd of three; the other solvers; the Pareto front
                self.assertLessEqual(artists, 4 * 18 + 4, f"{artists} artists on {title}")

    def test_a_solver_of_ones_own_is_labelled_by_the_name_its_user_gave(self):
        # The in-house stepper's rows as a Python callable's (`solvers={"mine": f}`), both in the
        # summary and the points: the report names it "mine", in its tables and its figures.
        def own(rows):
            for r in rows:
                if r["solver"] == "moreau-jean":
                    steps = json.loads(r["settings"])["steps"]
                    r.update(solver="external", settings=json.dumps({"command": "python mine", "steps": steps}))
            return rows

        write(self.path("wp.csv"), own([dict(r) for r in self.summary]))
        write(self.path("points.csv"), own([dict(r) for r in self.points]))
        out = self.report("wp.csv", "--points", "points.csv", "--out", "report")
        self.assertEqual(out.returncode, 0, out.stderr)
        with open(self.path("report", "README.md")) as f:
            readme = f.read()
        self.assertIn("| mine, N = 16 |", readme)
        self.assertNotIn("external", readme)
        for family in ("wall", "pair"):
            self.assertIn(f"figures/wp-{family}-mine.png", readme)
            self.assertTrue(os.path.isfile(self.path("report", "figures", f"wp-{family}-mine.png")))
        import rows
        label = lambda settings: rows.config_label(dict(solver="external", variant="", settings=json.dumps(settings)))
        # a name given with the run's settings; a program's own command, so that two programs never share a line
        self.assertEqual(label({"command": "my_solver --fast", "name": "fast one"}), "fast one")
        self.assertEqual(label({"command": "sh my_solver.sh --rtol 1e-6"}), "sh my_solver.sh --rtol 1e-6")
        self.assertNotEqual(label({"command": "sh a.sh"}), label({"command": "sh b.sh"}))

    def test_each_setting_has_its_own_colour_and_dash_the_page_s_too_in_figures_of_readmes_width(self):
        import styles
        import wp

        # 60 configurations of one solver: no two alike in both colour and dash (nor in marker
        # and dash: the lines read without their colours)
        chosen = wp.setting_styles(synthetic_summary(1, 60, configurations=60))
        self.assertEqual(len({(s["color"], s["dash"]) for s in chosen.values()}), 60)
        self.assertEqual(len({(s["marker"], s["dash"]) for s in chosen.values()}), 60)
        out = self.report(os.path.join(self.tmp.name, "wp.csv"), "--points", os.path.join(self.tmp.name, "points.csv"),
                          "--out", "report")
        self.assertEqual(out.returncode, 0, out.stderr)
        with open(self.path("report", "report.html")) as f:
            data = json.loads(re.search(r'id="report-data">(.*?)</script>', f.read(), re.S).group(1).replace("<\\/", "</"))
        expected = wp.setting_styles(self.summary)
        series = {s["name"] for family in data["diagrams"].values() for s in family}
        self.assertTrue(series)
        for name in series:  # the page draws each setting as the figures do
            self.assertEqual(data["styles"][name], dict(color=expected[name]["color"],
                                                        dash=styles.svg_dash(expected[name]["dash"])))
        self.assertEqual(len({(s["color"], s["dash"]) for s in data["styles"].values()}), len(data["styles"]))
        # README's column on GitHub is some 830 px: a figure no wider is shown at its own size
        pngs = [f for f in listing(self.path("report")) if f.endswith(".png")]
        self.assertTrue(pngs)
        for png in pngs:
            with open(self.path("report", png), "rb") as f:
                self.assertLessEqual(int.from_bytes(f.read(24)[16:20], "big"), 830, png)


class Visited(list):
    """A summary's rows that count how many are visited (a row yielded by iteration)."""

    def __init__(self, rows):
        super().__init__(rows)
        self.visits = 0

    def __iter__(self):
        for r in super().__iter__():
            self.visits += 1
            yield r


def synthetic_summary(families, settings, configurations=1, solver="moreau-jean"):
    """Summary rows: `settings` settings of `configurations` configurations of `solver` (theta
    apart) on each family, errors falling and costs rising with N."""
    rows = []
    for f in range(families):
        for s in range(settings):
            theta = 0.5 + 0.5 * (s % configurations) / max(configurations, 1)
            n = 8 + s // configurations
            rows.append(dict(family=f"f{f}", solver=solver, variant="",
                             settings=json.dumps({"steps": n, "theta": theta}), points="5", failed="0",
                             err_median=repr(1.0 / n ** 2), err_p95=repr(2.0 / n ** 2), err_max=repr(3.0 / n ** 2),
                             cpu_median_s=repr(1e-7 * n), cpu_median_low_s="", cpu_median_high_s="",
                             unresolved="0", cost="cpu_seconds"))
    return rows


if __name__ == "__main__":
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print(f"{sys.executable} has no matplotlib (Debian: python3-matplotlib): skipped")
        sys.exit(SKIP)
    unittest.main(argv=sys.argv[:1])
