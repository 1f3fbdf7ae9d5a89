"""A persistent external program for tests/external_persistent_test.py, whose behaviour per
case is its first argument:

    answer       answers every case (pi1 = 1 + the case's eps), its solve_seconds 0.001
    hang         answers the first case, then sleeps on every case after its first (never answers)
    die          answers the first case, then exits with code 3 on the second (and after a restart
                 answers again, once, and so on)
    late         sleeps 0.3 s before its ready line
    noready      writes an answer where the ready line belongs
    ready-line   writes its third argument where the ready line belongs, then answers
    twice        answers, waits 50 ms and writes a second answer (pi1 = 99) to the same case
    twice-slow   the same, then waits 5 s before it reads the next case (so that its second
                 line surely arrives while that case sits unread)
    exit-between answers a case, then exits with code 0 (before the next case)
    fork-exit    on a case, leaves a child (sleep 300, its pid in STARTS.grandchild) holding its
                 stdout and stderr, and exits with code 0 without answering
    setsid-hang  after its ready line, leaves a child in a session of its own (setsid sleep 300,
                 its pid in STARTS.grandchild) holding its stdout and stderr, and never answers
    noisy        answers with a message of escape sequences, control characters and separators;
                 after a restart, fails: writes bytes that are not UTF-8 to stderr and exits 3

It appends a line to the file in its second argument each time it starts, so that the test
counts its starts: "start" and the cores it may run on (its affinity, as it started).
"""
import os
import json
import subprocess
import sys
import time

mode, starts = sys.argv[1], sys.argv[2]
with open(starts, "a") as f:
    f.write("start " + ",".join(map(str, sorted(os.sched_getaffinity(0)))) + "\n")
restarted = sum(1 for _ in open(starts)) > 1


def leave_a_child(*command):
    """Starts `command` with this program's stdout and stderr, and notes its pid for the test."""
    child = subprocess.Popen(command, stdin=subprocess.DEVNULL)
    with open(starts + ".grandchild", "a") as f:
        f.write(f"{child.pid}\n")


def answer(case, pi1=None, solve_seconds=0.001):
    pi1 = 1.0 + case["eps"] if pi1 is None else pi1
    print(json.dumps({"version": 1, "status": "ok", "pi1": pi1, "solve_seconds": solve_seconds}), flush=True)


def busy(seconds):
    """Spends `seconds` of this process's CPU time, and says how much it spent."""
    start = time.process_time()
    while time.process_time() - start < seconds:
        pass
    return time.process_time() - start


if mode == "late":
    time.sleep(0.3)
if mode == "noready":
    print(json.dumps({"version": 1, "status": "ok", "pi1": 1.0}), flush=True)
elif mode == "ready-line":
    print(sys.argv[3], flush=True)
else:
    print(json.dumps({"version": 1, "ready": True}), flush=True)
if mode == "setsid-hang":
    leave_a_child("setsid", "sleep", "300")
answered = 0
for line in sys.stdin:
    case = json.loads(line)
    if answered and mode == "hang" or mode == "setsid-hang":
        time.sleep(1000)
    if answered and mode == "die":
        print("dying on purpose", file=sys.stderr, flush=True)
        sys.exit(3)
    if mode == "fork-exit":
        leave_a_child("sleep", "300")
        sys.exit(0)
    if mode == "noisy" and restarted:
        sys.stderr.buffer.write(b"bad bytes \xff\xfe\xc3( and \x1b[31mred\x1b[0m\n")
        sys.stderr.flush()
        sys.exit(3)
    if mode == "noisy":
        message = "esc \x1b[31mred\x1b[0m nul \x00 bell \x07 line\nend \u2028 c1 \x85 rlo \u202e done"
        print(json.dumps({"version": 1, "status": "ok", "pi1": 1.0, "message": message}), flush=True)
        sys.exit(0)  # the next point restarts it, and the restarted one fails
    if mode in ("liar", "honest"):
        spent = busy(0.05)
        answer(case, solve_seconds=1e-9 if mode == "liar" else spent)
        continue
    answer(case)
    answered += 1
    if mode in ("twice", "twice-slow"):
        time.sleep(0.05)
        answer(case, 99.0)
        if mode == "twice-slow":
            time.sleep(5)
    if mode == "exit-between":
        sys.exit(0)
