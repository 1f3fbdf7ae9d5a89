# issue 46, item 9: the duplicate-key check was quadratic (120,000 keys: 11.9 s); here 200,000 keys, one twice
import json, os, subprocess, sys, time

def answer(case, pi1=None, **more):
    """The answer to this case: its pi2, the reference body's w over w_p (the driver checks it)."""
    pi2 = case["bodies"][case["reference"]]["w"] / case["load"]["w"]
    doc = {"version": 1, "status": "ok", "pi1": pi2 if pi1 is None else pi1}
    doc.update(more)
    return json.dumps(doc)

def out(text):
    sys.stdout.write(text)
    sys.stdout.flush()

def raw(data):
    sys.stdout.buffer.write(data)
    sys.stdout.buffer.flush()

def leave(*command):
    """A child holding this program's stdout and stderr; its pid for the driver to end."""
    child = subprocess.Popen(command, stdin=subprocess.DEVNULL)
    with open("children", "a") as f:
        f.write("%d\n" % child.pid)

out(json.dumps({"version": 1, "ready": True}) + "\n")
calls = 0
for line in sys.stdin:
    case = json.loads(line)
    i = calls % 3
    calls += 1
    if i == 0:
        out('{"version": 1, "status": "ok", "pi1": 1' + ''.join(', "k%d": 0' % k for k in range(200000)) + ', "k0": 1}\n')
    if i == 1:
        out(answer(case) + '\n')
    if i == 2:
        out('x' * 2000000)
        sys.exit(0)
