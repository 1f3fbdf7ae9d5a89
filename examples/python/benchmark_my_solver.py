#!/usr/bin/env python3
"""Benchmark a solver of your own, written in Python, against poundbench's reference and its
solvers, in process: no program to start per point, its cost its thread's CPU time, on the
same clock as every other solver's.

    PYTHONPATH=build/python python3 examples/python/benchmark_my_solver.py [--set examples/python/pairs.toml]

`my_solver` below is the whole solver: a function that takes the case (a dict: the external
protocol's case document, docs/external.md) and returns the answer (a dict). It is a
symplectic Euler step with Newton's impact law applied to the velocities of the contacts a
step would close (Gauss-Seidel over the contacts), in pure Python. poundbench.workprecision
runs it beside Moreau-Jean at the same steps, measures both against the reference, and
returns the table `poundbench workprecision` writes; the script prints the answer table:
for each error target, the cheapest setting that meets it, and the place of my_solver's.
"""
import argparse
import math
import os
import sys

import poundbench  # the module python/ builds (PYTHONPATH: its directory)


def my_solver(case):
    load = case["load"]
    if load["kind"] != "pulse":
        return {"status": "failed", "message": f"load.kind: {load['kind']!r} is not a kind this solver knows"}
    bodies, contacts = case["bodies"], case["contacts"]
    h = case["step"] or case["t_min"] / 64
    m = [b["m"] for b in bodies]
    u = [b["u"] for b in bodies]
    v = [b["v"] for b in bodies]
    eps, ref, t_end = case["eps"], case["reference"], case["t_end"]
    shape = math.sin if load["shape"] == "sine" else math.cos

    def a_g(t):
        return load["amplitude"] * shape(load["w"] * t) if t <= load["duration"] else 0.0

    def gap(c, x):
        left = x[c["left"]] if c["left"] is not None else 0.0
        return c["gap"] + x[c["right"]] - left

    peak = t_peak = 0.0
    impacts = steps = 0
    t = 0.0
    while t < t_end:
        a = a_g(t + 0.5 * h)
        v = [vi + h * (-(b["c"] * vi + b["k"] * ui) / b["m"] - a) for b, ui, vi in zip(bodies, u, v)]
        # Contacts the step would close: their approach reversed by -eps, by impulses >= 0.
        closing = [c for c in contacts if gap(c, [ui + h * vi for ui, vi in zip(u, v)]) <= 0.0]
        approach = {id(c): gap(c, v) - c["gap"] for c in closing}
        for _ in range(20 if len(closing) > 1 else 1):
            for c in closing:
                rate = gap(c, v) - c["gap"]
                target = -eps * min(approach[id(c)], 0.0)
                if rate >= target:
                    continue
                inverse_mass = 1.0 / m[c["right"]] + (1.0 / m[c["left"]] if c["left"] is not None else 0.0)
                impulse = (target - rate) / inverse_mass
                v[c["right"]] += impulse / m[c["right"]]
                if c["left"] is not None:
                    v[c["left"]] -= impulse / m[c["left"]]
        impacts += sum(1 for c in closing if approach[id(c)] < 0.0)
        u = [ui + h * vi for ui, vi in zip(u, v)]
        t += h
        steps += 1
        if abs(u[ref]) > peak:
            peak, t_peak = abs(u[ref]), min(t, t_end)
    return {"status": "ok", "pi1": peak / case["length_scale"], "t_max": t_peak, "impacts": impacts,
            "steps": steps, "step": h, "message": "symplectic Euler, Newton impacts (examples/python)"}


def answer_table(table, targets=(1e-1, 3e-2, 1e-2)):
    """For each error target: the settings whose every family meets it at the 95th percentile,
    cheapest first (their cost: the median over the runs, the families' worst)."""
    settings = {}
    for row in table:
        key = (row["solver"], row["settings"])
        cost, err = settings.get(key, (0.0, 0.0))
        ok = row["failed"] == 0 and row["err_p95"] is not None
        settings[key] = (max(cost, row["cpu_median_s"]), max(err, row["err_p95"] if ok else math.inf))
    places = {}
    for target in targets:
        meeting = sorted((cost, key) for key, (cost, err) in settings.items() if err <= target)
        print(f"error <= {target:g} at p95: {len(meeting)} settings meet it")
        for place, (cost, (solver, s)) in enumerate(meeting, 1):
            print(f"  {place}. {solver:12s} {s:40s} {1e6 * cost:10.1f} us")
        mine = [place for place, (_, (solver, _)) in enumerate(meeting, 1) if solver == "external"]
        places[target] = mine[0] if mine else None
        print(f"  my_solver's place: {places[target] if mine else 'none of its settings meets it'}")
    return places


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--set", default=os.path.join(here, "pairs.toml"))
    p.add_argument("--steps", type=int, nargs="+", default=[32, 128, 512])
    a = p.parse_args()
    table = poundbench.workprecision(
        a.set,
        settings=[{"solver": "moreau-jean", "steps": a.steps}, {"solver": "mine", "steps": a.steps}],
        solvers={"mine": my_solver}, repetitions=1)
    mine = [r for r in table if r["solver"] == "external"]
    if not mine or any(r["cost"] != "cpu_seconds" for r in mine):
        sys.exit("benchmark_my_solver: the table has no rows of my_solver timed on the CPU clock")
    answer_table(table)


if __name__ == "__main__":
    main()
