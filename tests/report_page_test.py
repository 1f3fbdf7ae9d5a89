#!/usr/bin/python3
"""`poundbench report` on a study of its own in a real browser: a case set and a settings
list that no shipped file has (a recorded ground motion and a sine pulse on a pair, a wall;
Moreau-Jean, an engine and the loosened reference), through `poundbench workprecision`, then
`poundbench report`; its report.html loaded from the file in Debian's headless Chromium
(driven by python3-selenium and chromium-driver, with no network) must

  - load without an error on the browser's console (a script error, a missing resource);
  - answer every scene, target and error measure of the markdown answer table with the
    same setting, cost and family, through its chooser (computed in the page);
  - do so by the one rule (reports/robust.py, page.js's robustErrors) on the same study with
    errors rewritten so that Moreau-Jean's coarse N = 16 meets 1 % and its N = 32 does not:
    the markdown and the page both answer N = 64;
  - show, when a point of a work-precision diagram is hovered, that point's setting, N,
    error and cost as the study's summary CSV has them;
  - hide a line when its legend entry is clicked.

    report_page_test.py POUNDBENCH SOURCE_DIR

Exit 77 (skipped, saying so) where Chromium, chromedriver or selenium is missing:
scripts/setup.sh installs chromium, chromium-driver and python3-selenium."""

import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
SKIP = 77

CASES = """name = "my-buildings"
description = "a user's own study: two buildings under a record and a pulse, a wall"

[defaults]
eps = 0.6
pi3 = 0.3
directivity = "normal"
pulse = "sine"
pi2 = { from = 0.2, to = 4, points = 4, spacing = "log" }

[[family]]
name = "east-block-record"
scene = "pair"
pulse = "record"
record = "RECORD"
tp = 2
pi5 = [0.6, 1.7]
pi6 = 0.8
pi2 = { from = 0.3, to = 3, points = 3, spacing = "log" }

[[family]]
name = "east-block-sine"
scene = "pair"
pi5 = 0.6
pi6 = 0.8

[[family]]
name = "abutment"
scene = "wall"
pulse = ["sine", "cosine"]
"""

SETTINGS = """name = "my-settings"
reference_tol_scale = 0.01

[[run]]
solver = "moreau-jean"
theta = 0.5
steps = [8, 16, 32, 64, 128]

[[run]]
solver = "ode"
variant = "dantzig-faithful"
steps = [16, 64]

[[run]]
solver = "event-driven"
tol_scale = 100
"""


def skip(why):
    print(f"report_page_test: skipped: {why} (scripts/setup.sh installs chromium, chromium-driver and "
          "python3-selenium)")
    sys.exit(SKIP)


def fail(why):
    print(f"report_page_test: FAILED: {why}")
    sys.exit(1)


def answer_rows(readme):
    """The markdown answer tables: (measure, scene, target) -> (setting, cost, family)."""
    rows, measure = {}, None
    for line in readme.splitlines():
        m = re.match(r"By the (.*) of the error:$", line)
        if m:
            measure = m.group(1)
        elif measure and line.startswith("| ") and not line.startswith("| scene"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            rows[(measure, cells[0].strip("*"), cells[1])] = (cells[2], cells[3], cells[4])
        elif measure and line.startswith("## "):
            break
    return rows


def browser(profile):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    # This machine's network is closed: without these Chromium waits on lookups it cannot make.
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 f"--user-data-dir={profile}", "--window-size=1200,1000"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)


def chooser_agrees(driver, expected):
    """The page's chooser against the markdown, answer by answer: each choice made as a user
    makes it (the option chosen, a change event), in one script so that they cost one round trip."""
    answers = driver.execute_script("""
        const pick = (id, text) => {
          const s = document.getElementById(id);
          const o = [...s.options].find((o) => o.text === text);
          if (!o) return false;
          s.value = o.value;
          s.dispatchEvent(new Event("change"));
          return true;
        };
        return arguments[0].map(([m, scene, t]) =>
          pick("chooser-measure", m) && pick("chooser-scope", scene) && pick("chooser-target", t)
            ? ["chooser-setting", "chooser-cost", "chooser-family"].map(
                (id) => document.getElementById(id).textContent)
            : null);""", [list(k) for k in expected])
    for ((m, scene, t), (setting, cost, family)), got in zip(expected.items(), answers):
        want = [setting, cost or "–", family or "–"]
        if got != want:
            fail(f"chooser for {scene}, {t}, {m}: {got}; the markdown table: {want}")


# Moreau-Jean theta = 1/2's errors by N in the lucky study: N = 16 meets 1 %, N = 32 does not.
LUCKY = {8: 0.5, 16: 0.008, 32: 0.012, 64: 0.004, 128: 0.001}


def lucky_report(pb, tmp, summary):
    """The report of the study's summary with Moreau-Jean theta = 1/2's errors replaced by LUCKY
    on every family and every other setting's by 0.5 (none answers 1 % but Moreau-Jean); its
    folder."""

    rows = []
    for r in summary:
        fields = json.loads(r["settings"] or "{}")
        mine = r["solver"] == "moreau-jean" and fields.get("theta") == 0.5
        err = LUCKY[fields["steps"]] if mine else 0.5
        rows.append(dict(r, err_median=repr(err), err_p95=repr(err), err_max=repr(err), failed="0", unresolved="0"))
    path = os.path.join(tmp, "lucky.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, list(summary[0]), lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
    made = subprocess.run([pb, "report", path, "--out", "lucky"], cwd=tmp, capture_output=True, text=True)
    if made.returncode != 0:
        fail(f"poundbench report of the lucky study exited {made.returncode}: {made.stderr}")
    return os.path.join(tmp, "lucky")


def require_browser():
    """Skips the test where Chromium, chromedriver or selenium is missing."""
    for program in (CHROMIUM, CHROMEDRIVER):
        if not os.access(program, os.X_OK):
            skip(f"{program} not found")
    try:
        import selenium  # noqa: F401
    except ImportError:
        skip("python3-selenium not found")


def make_study(pb, src, tmp):
    """The case set and settings list through `poundbench workprecision` and `poundbench report`
    in tmp: the report's folder, and the study's summary rows."""
    with open(os.path.join(tmp, "mine.toml"), "w") as f:
        f.write(CASES.replace("RECORD", os.path.join(src, "cases", "records", "mp-noise-20s.csv")))
    settings = SETTINGS
    built = subprocess.run([pb, "solvers"], capture_output=True, text=True, check=True).stdout
    if not re.search(r"^ode ", built, re.M):
        settings = settings.replace('solver = "ode"\nvariant = "dantzig-faithful"\nsteps = [16, 64]', "solver = "
                                    '"moreau-jean"\ntheta = 1.0\nsteps = [16, 64]')
    with open(os.path.join(tmp, "my-list.toml"), "w") as f:
        f.write(settings)
    subprocess.run([pb, "workprecision", "mine.toml", "--settings", "my-list.toml", "--repetitions", "1",
                    "--out", "wp.csv", "--points", "wp-points.csv"], cwd=tmp, check=True,
                   stderr=subprocess.DEVNULL)
    made = subprocess.run([pb, "report", "wp.csv", "--points", "wp-points.csv", "--out", "report"], cwd=tmp,
                          capture_output=True, text=True)
    if made.returncode != 0:
        fail(f"poundbench report exited {made.returncode}: {made.stderr}")
    with open(os.path.join(tmp, "wp.csv"), newline="") as f:
        summary = list(csv.DictReader(f))
    return os.path.join(tmp, "report"), summary


def markdown_answers(out):
    """The report's markdown answers, checked for their number and the record's scope."""
    with open(os.path.join(out, "README.md")) as f:
        expected = answer_rows(f.read())
    # 2 measures; pair (the pulse), pair records (the record: a scope of its own, never merged
    # into the pulse's), wall, all scenes, its time-steppers; 4 targets
    if len(expected) != 2 * 5 * 4:
        fail(f"the markdown has {len(expected)} answers, not 2 x 5 scopes x 4 targets")
    if not any(scene == "pair records" for _, scene, _ in expected):
        fail("the record's family is not a scope of its own (pair records)")
    return expected


def no_console_errors(driver):
    errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
    if errors:
        fail(f"console errors: {errors}")


def one_rule_agrees(driver, pb, tmp, summary):
    """The one rule (reports/robust.py) in the page as in the markdown: a study where
    Moreau-Jean's coarse N = 16 meets 1 % and its finer N = 32 does not."""
    lucky_out = lucky_report(pb, tmp, summary)
    with open(os.path.join(lucky_out, "README.md")) as f:
        lucky = answer_rows(f.read())
    picks = {k: v[0] for k, v in lucky.items() if k[2] == "0.01"}
    if not picks or any(p != "moreau-jean theta=0.5, N = 64" for p in picks.values()):
        fail(f"the markdown's answers at 1 % on the lucky study: {picks}; want N = 64 (N = 16 is lucky)")
    driver.get("file://" + os.path.join(lucky_out, "report.html"))
    chooser_agrees(driver, lucky)


def hover(driver, point):
    """The tooltip's lines over a point. The chart is scrolled into view first (by the caller),
    so that moving to a point does not scroll the page under the pointer; a move that still
    leaves no tooltip (the page laid out again under it) is made once more."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    tooltip = driver.find_element(By.ID, "tooltip")
    for _ in range(3):
        ActionChains(driver).move_to_element(point).perform()
        text = tooltip.text if tooltip.is_displayed() else ""
        if text:
            return text.split("\n")
        time.sleep(0.2)
    fail(f"hovering the point at {point.rect} shows no tooltip")


def tooltips_agree(driver, summary, points):
    """Hovering points of the first family's diagram: each tooltip against the CSV. The
    settings seen."""
    from answer import cost_cell
    from rows import setting_label
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select

    family = Select(driver.find_element(By.ID, "wp-family")).first_selected_option.text
    if len(points) < 5:
        fail(f"{len(points)} points in {family}'s diagram")
    driver.execute_script("document.getElementById('wp-chart').scrollIntoView()")
    seen = set()
    for point in points[::2]:
        lines = hover(driver, point)
        rows = [r for r in summary if r["family"] == family and setting_label(r) == lines[0]]
        if len(rows) != 1:
            fail(f"the tooltip names {lines[0]!r}, which {family} has {len(rows)} times")
        r = rows[0]
        n = re.search(r"N = (\d+)", lines[0])
        if n and lines[1] != f"N = {n.group(1)}":
            fail(f"tooltip {lines}: N")
        shown = float(lines[2].split(": ")[1])
        if abs(shown - float(r["err_median"])) > 5e-3 * abs(float(r["err_median"])) + 1e-300 and \
                not (float(r["err_median"]) < 1e-13 and shown < 1e-13):
            fail(f"tooltip {lines}: error {shown}, the CSV's {r['err_median']} (3 digits)")
        if lines[3] != f"CPU per run: {cost_cell(r)} us":
            fail(f"tooltip {lines}: cost, the CSV's {cost_cell(r)}")
        seen.add(lines[0])
    if len(seen) < 3:
        fail(f"hovering {len(points[::2])} points showed {len(seen)} settings")
    return seen


def legend_hides_a_line(driver, points):
    from selenium.webdriver.common.by import By

    item = driver.find_element(By.CSS_SELECTOR, "#wp-legend .item")
    item.click()
    after = driver.find_elements(By.CSS_SELECTOR, "#wp-chart circle.pt")
    if not len(after) < len(points):
        fail(f"clicking {item.text!r} left {len(after)} of {len(points)} points")


def main():
    pb, src = sys.argv[1], sys.argv[2]
    require_browser()
    from selenium.common.exceptions import WebDriverException
    from selenium.webdriver.common.by import By

    sys.path.insert(0, os.path.join(src, "reports"))
    tmp = tempfile.mkdtemp(prefix="poundbench-page-")
    try:
        out, summary = make_study(pb, src, tmp)
        expected = markdown_answers(out)
        try:
            driver = browser(os.path.join(tmp, "profile"))
        except WebDriverException as e:
            fail(f"Chromium did not start: {e.msg}")
        try:
            driver.get("file://" + os.path.join(out, "report.html"))
            no_console_errors(driver)
            chooser_agrees(driver, expected)
            one_rule_agrees(driver, pb, tmp, summary)
            driver.get("file://" + os.path.join(out, "report.html"))
            points = driver.find_elements(By.CSS_SELECTOR, "#wp-chart circle.pt")
            seen = tooltips_agree(driver, summary, points)
            legend_hides_a_line(driver, points)
            no_console_errors(driver)
        finally:
            driver.quit()
        print(f"report_page_test: {len(expected)} answers as the markdown's, {len(seen)} hovered settings as the "
              "CSV's, no console error")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
