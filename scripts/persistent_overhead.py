#!/usr/bin/env python3
"""What a point costs through the persistent external protocol itself (docs/external.md):
a sweep of a case set through a program that answers every case at once
(bench/instant_answer.cpp), on one thread, a few times. Prints, as medians over the sweeps:
the exchange per point (the rows' `seconds`: the case written, the answer read and checked),
the whole sweep's wall time per point (poundbench's start, every point's case, no-contact Pi1,
row and CSV included) beside the same sweep through the reference (its solve instead of the
exchange: the difference bounds what the protocol adds to a point of a sweep, the program's
own time included), and the program's start-up (`startup_seconds`, reported once per worker).

    scripts/persistent_overhead.py [--poundbench build/poundbench] [--answer build/bench/poundbench_instant_answer]
                                   [--set cases/sets/workprecision.toml] [--sweeps 5]
"""
import argparse
import csv
import io
import statistics
import subprocess
import sys
import time


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--poundbench", default="build/poundbench")
    p.add_argument("--answer", default="build/bench/poundbench_instant_answer")
    p.add_argument("--set", default="cases/sets/workprecision.toml")
    p.add_argument("--sweeps", type=int, default=5)
    a = p.parse_args()
    exchange, per_point, reference, startup = [], [], [], []

    def sweep(*flags):
        start = time.perf_counter()
        out = subprocess.run([a.poundbench, "spectrum", a.set, "--threads", "1", *flags],
                             capture_output=True, text=True, check=True).stdout
        return out, time.perf_counter() - start

    for _ in range(a.sweeps):
        out, wall = sweep()
        reference.append(wall / len(list(csv.DictReader(io.StringIO(out)))))
        out, wall = sweep("--solver", "external", "--persistent", "--command", a.answer)
        rows = list(csv.DictReader(io.StringIO(out)))
        if not rows or any(r["status"] != "ok" for r in rows):
            sys.exit("persistent_overhead: a point did not answer ok: " + next(r["message"] for r in rows if r["status"] != "ok"))
        exchange.append(statistics.median(float(r["seconds"]) for r in rows))
        per_point.append(wall / len(rows))
        startup += [float(r["startup_seconds"]) for r in rows if r["startup_seconds"]]
    print(f"persistent protocol, {len(rows)} points of {a.set}, {a.sweeps} sweeps on one thread (medians):")
    print(f"  exchange per point (rows' seconds): {1e6 * statistics.median(exchange):.1f} us")
    print(f"  sweep wall time per point: {1e6 * statistics.median(per_point):.1f} us, "
          f"through the reference {1e6 * statistics.median(reference):.1f} us")
    print(f"  program start-up (startup_seconds, {len(startup)} starts): {1e6 * statistics.median(startup):.0f} us")


if __name__ == "__main__":
    main()
