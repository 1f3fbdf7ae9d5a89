#!/usr/bin/env python3
"""What a point costs through the external protocol itself (docs/external.md): a sweep of a
case set through a program that answers every case at once, on one thread, a few times, in
both modes: persistent (bench/instant_answer.cpp: started once, a line each way) and one-shot
(`cat` of a stored answer: a spawn per point). The sweep runs its worker and the worker's
persistent program on one core (sweep/worker_cores.hpp): no message waits for an idle virtual CPU
to wake, which on this project's 2-vCPU machine was most of the cost (74 us a point unpinned on
the idle machine, 16 us on one core). Prints, as medians over the sweeps, the
exchange per point (the rows' `seconds`: the case written, the answer read and checked; one-shot,
the spawn and the wait too) and the persistent program's start-up (`startup_seconds`, reported
once per worker), and the whole sweep's wall time and CPU time (poundbench's and the programs'
it ran) per point, with what of its wall time is outside the exchanges and the start-up
(`outside_us`: poundbench's own start and end, its work per point outside the solve, and any
wait for a core). Over a hundred points the whole sweep is mostly poundbench's own start; on a
set of thousands (cases/sets/paper-report.toml: 3 284) it is the cost a user sees.

With --out FILE (scripts/main.sh: reports/persistent.csv) it also writes these medians, one row
per mode, and the provenance of the build beside it (FILE's name with -provenance.json), from
which reports/make_report.py writes README's block.

    scripts/persistent_overhead.py [--poundbench build/poundbench] [--answer build/bench/poundbench_instant_answer]
                                   [--set cases/sets/workprecision.toml] [--sweeps 5] [--out reports/persistent.csv]
"""
import argparse
import csv
import io
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

COLUMNS = ["mode", "set", "points", "sweeps", "exchange_us", "startup_us", "sweep_us", "sweep_cpu_us", "outside_us"]


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--poundbench", default="build/poundbench")
    p.add_argument("--answer", default="build/bench/poundbench_instant_answer")
    p.add_argument("--set", default="cases/sets/workprecision.toml")
    p.add_argument("--sweeps", type=int, default=5)
    p.add_argument("--out", help="write the medians to this CSV file (and its provenance beside it)")
    a = p.parse_args()

    def sweep(*flags):
        """The rows, and the sweep's wall and CPU seconds (poundbench's and its programs')."""
        cpu, start = children_cpu(), time.perf_counter()
        out = subprocess.run([a.poundbench, "spectrum", a.set, "--threads", "1", "--solver", "external", *flags],
                             capture_output=True, text=True, check=True).stdout
        wall, cpu = time.perf_counter() - start, children_cpu() - cpu
        rows = list(csv.DictReader(io.StringIO(out)))
        if not rows or any(r["status"] != "ok" for r in rows):
            sys.exit("persistent_overhead: a point did not answer ok: " +
                     next((r["message"] for r in rows if r["status"] != "ok"), "no rows"))
        return rows, wall, cpu

    with tempfile.TemporaryDirectory() as work:
        answer = os.path.join(work, "answer.json")
        with open(answer, "w") as f:
            f.write('{"version": 1, "status": "ok", "pi1": 1.0}\n')
        persistent = ["--persistent", "--command", a.answer]
        modes = {"persistent": persistent, "one-shot": ["--command", f"cat {answer}"]}
        measured = {m: dict(exchange=[], startup=[], sweep=[], cpu=[], outside=[]) for m in modes}
        for _ in range(a.sweeps):
            for mode, flags in modes.items():
                rows, wall, cpu = sweep(*flags)
                m = measured[mode]
                m["exchange"].append(statistics.median(float(r["seconds"]) for r in rows))
                startups = [float(r["startup_seconds"]) for r in rows if r["startup_seconds"]]
                m["startup"] += startups
                m["sweep"].append(wall / len(rows))
                m["cpu"].append(cpu / len(rows))
                m["outside"].append((wall - sum(float(r["seconds"]) for r in rows) - sum(startups)) / len(rows))

    out = []
    for mode, m in measured.items():
        out.append(dict(mode=mode, set=a.set, points=len(rows), sweeps=a.sweeps,
                        exchange_us=f"{1e6 * statistics.median(m['exchange']):.1f}",
                        startup_us=f"{1e6 * statistics.median(m['startup']):.0f}" if m["startup"] else "",
                        sweep_us=f"{1e6 * statistics.median(m['sweep']):.1f}",
                        sweep_cpu_us=f"{1e6 * statistics.median(m['cpu']):.1f}",
                        outside_us=f"{1e6 * statistics.median(m['outside']):.1f}"))
    print(f"external protocol, {len(rows)} points of {a.set}, {a.sweeps} sweeps on one thread (medians):")
    for r in out:
        print(f"  {r['mode']}: exchange per point (rows' seconds) {r['exchange_us']} us"
              + (f"; program start-up (startup_seconds) {r['startup_us']} us" if r["startup_us"] else "")
              + f"; the whole sweep {r['sweep_us']} us a point ({r['sweep_cpu_us']} us of CPU), of which"
              f" {r['outside_us']} us outside the exchanges and the start-up")
    if a.out:
        build = os.path.dirname(os.path.abspath(a.poundbench))
        provenance = subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "..", "reports",
                                                                  "provenance.py"), "--build-dir", build],
                                    capture_output=True, text=True, check=True).stdout
        # Written whole to a temporary name, then renamed: never a half-written results file.
        for path, text in ((a.out, None), (os.path.splitext(a.out)[0] + "-provenance.json", provenance)):
            with open(path + ".tmp", "w", newline="") as f:
                if text is None:
                    writer = csv.DictWriter(f, COLUMNS, lineterminator="\n")
                    writer.writeheader()
                    writer.writerows(out)
                else:
                    f.write(text)
            os.replace(path + ".tmp", path)
        print(f"persistent_overhead: wrote {a.out}")


if __name__ == "__main__":
    main()
