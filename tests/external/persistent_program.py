"""A persistent external program for tests/external_persistent_test.py, whose behaviour per
case is its first argument:

    answer   answers every case (pi1 = 1 + the case's eps), its solve_seconds 0.001
    hang     answers the first case, then sleeps on every case after its first (never answers)
    die      answers the first case, then exits with code 3 on the second (and after a restart
             answers again, once, and so on)
    late     sleeps 0.3 s before its ready line
    noready  writes an answer where the ready line belongs

It appends a line to the file in its second argument each time it starts, so that the test
counts its starts: "start" and the cores it may run on (its affinity, as it started).
"""
import os
import json
import sys
import time

mode, starts = sys.argv[1], sys.argv[2]
with open(starts, "a") as f:
    f.write("start " + ",".join(map(str, sorted(os.sched_getaffinity(0)))) + "\n")
if mode == "late":
    time.sleep(0.3)
if mode == "noready":
    print(json.dumps({"version": 1, "status": "ok", "pi1": 1.0}), flush=True)
else:
    print(json.dumps({"version": 1, "ready": True}), flush=True)
answered = 0
for line in sys.stdin:
    case = json.loads(line)
    if answered and mode == "hang":
        time.sleep(1000)
    if answered and mode == "die":
        print("dying on purpose", file=sys.stderr, flush=True)
        sys.exit(3)
    print(json.dumps({"version": 1, "status": "ok", "pi1": 1.0 + case["eps"], "solve_seconds": 0.001}), flush=True)
    answered += 1
