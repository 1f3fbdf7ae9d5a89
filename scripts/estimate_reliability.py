#!/usr/bin/env python3
"""How far the verdict's error estimate can be trusted (issue 48): random wall and pair cases
at coarse steps, each fixed-step solver's verdict against the reference's Pi1.

A heavy sweep, not a test (two solvers x 14 steps x 200 cases, each with its companion solve
at 2h). The cases are drawn with a fixed seed, so a rerun draws the same ones:

  scene        wall or pair, even odds
  pulse        sine or cosine; directivity normal or reverse
  Pi2          log-uniform over [0.2, 5]     Pi3  uniform over [0, 1]
  eps          uniform over [0, 1]
  Pi5, Pi6     (pair) log-uniform over [0.25, 4]
  xi = 0.05, n_free = 3 (the defaults)

Each solver (moreau-jean, ode: their default variants) runs every case at N = 3 .. 16 steps
per shortest period with `spectrum --monitor --estimate-error` (the verdict's every
criterion, the target 1 %). Per solver it counts the runs that ended ok, those resolved and
among them those more than 10 % off the reference (goal: under 2 % of the resolved), those
unresolved and among them those within 1 % of it (goal: under 20 % of the unresolved), and
those not judged (none expected: every measurement is taken).

  estimate_reliability.py [--poundbench build/poundbench] [--out reports/estimate-reliability.csv]

--out writes the counts as CSV and the build's provenance beside it (FILE's name with
-provenance.json), which reports/readme.py turns into README's block `estimate`; without it
the counts go to stdout."""

import argparse
import csv
import io
import math
import os
import random
import subprocess
import sys
import tempfile

SEED = 48
CASES = 200
STEPS = range(3, 17)
SOLVERS = ["moreau-jean", "ode"]
OFF = 0.10     # a resolved run this far off the reference is a miss
WITHIN = 0.01  # an unresolved run this close to it was flagged for nothing
FIELDS = ["solver", "cases", "steps", "runs", "ok", "resolved", "resolved_off", "unresolved", "unresolved_within",
          "not_judged", "resolved_off_share", "unresolved_within_share", "off", "within", "target", "seed"]


def log_uniform(rng, low, high):
    return math.exp(rng.uniform(math.log(low), math.log(high)))


def case_set(rng):
    """The case-set file's text: one family per case, drawn as the docstring says."""
    lines = ['name = "estimate-reliability"', f'description = "{CASES} random wall and pair cases, seed {SEED}"', ""]
    for k in range(CASES):
        scene = rng.choice(["wall", "pair"])
        lines += ["[[family]]", f'name = "case-{k:03d}"', f'scene = "{scene}"',
                  f'pulse = "{rng.choice(["sine", "cosine"])}"', f'directivity = "{rng.choice(["normal", "reverse"])}"',
                  f"pi2 = {log_uniform(rng, 0.2, 5.0)!r}", f"pi3 = {rng.uniform(0.0, 1.0)!r}",
                  f"eps = {rng.uniform(0.0, 1.0)!r}"]
        if scene == "pair":
            lines += [f"pi5 = {log_uniform(rng, 0.25, 4.0)!r}", f"pi6 = {log_uniform(rng, 0.25, 4.0)!r}"]
        lines.append("")
    return "\n".join(lines)


def spectrum(poundbench, cases, *flags):
    """The rows of `spectrum` over the cases, as dicts by column."""
    out = subprocess.run([poundbench, "spectrum", cases, "--threads", "2", *flags], check=True, capture_output=True,
                         text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def counts(solver, rows, reference):
    c = dict(solver=solver, cases=CASES, steps=f"{STEPS.start}-{STEPS.stop - 1}", runs=len(rows), ok=0, resolved=0,
             resolved_off=0, unresolved=0, unresolved_within=0, not_judged=0, off=OFF, within=WITHIN, target=0.01,
             seed=SEED)
    for r in rows:
        if r["status"] != "ok":
            continue
        c["ok"] += 1
        ref = reference[r["point"]]
        error = abs(float(r["pi1"]) - ref) / ref
        if r["resolved"] == "true":
            c["resolved"] += 1
            c["resolved_off"] += error > OFF
        elif r["resolved"] == "false":
            c["unresolved"] += 1
            c["unresolved_within"] += error <= WITHIN
        else:
            c["not_judged"] += 1
    c["resolved_off_share"] = round(c["resolved_off"] / c["resolved"], 4) if c["resolved"] else ""
    c["unresolved_within_share"] = round(c["unresolved_within"] / c["unresolved"], 4) if c["unresolved"] else ""
    return c


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--poundbench", default="build/poundbench")
    p.add_argument("--out", help="write the counts to this CSV file (and its provenance beside it)")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        cases = os.path.join(tmp, "cases.toml")
        with open(cases, "w") as f:
            f.write(case_set(random.Random(SEED)))
        reference = {r["point"]: float(r["pi1"]) for r in spectrum(a.poundbench, cases)}
        table = []
        for solver in SOLVERS:
            rows = []
            for n in STEPS:
                rows += spectrum(a.poundbench, cases, "--solver", solver, "--steps", str(n), "--monitor",
                                 "--estimate-error")
            table.append(counts(solver, rows, reference))
            print(f"estimate_reliability: {solver}: {table[-1]}", file=sys.stderr)
    text = io.StringIO()
    writer = csv.DictWriter(text, FIELDS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(table)
    if not a.out:
        sys.stdout.write(text.getvalue())
        return
    build = os.path.dirname(os.path.abspath(a.poundbench))
    provenance = subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "..", "reports",
                                                              "provenance.py"), "--build-dir", build],
                                check=True, capture_output=True, text=True).stdout
    # Both files whole or neither: each written beside its name and renamed into place.
    for path, content in ((a.out, text.getvalue()), (os.path.splitext(a.out)[0] + "-provenance.json", provenance)):
        with open(path + ".part", "w") as f:
            f.write(content)
        os.replace(path + ".part", path)


if __name__ == "__main__":
    main()
