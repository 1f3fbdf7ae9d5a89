#include "tests/fuzz/callables.hpp"

#include "tests/fuzz/targets.hpp"

namespace pb::fuzz {

namespace {

// Runs the callable read from stdin (its source defines f, and STUDY = True for a study too)
// over three points at a time limit of 0.3 s, in a fresh directory, and ends with one line:
// "RESULT OK" or "RESULT BAD <why>" (os._exit: whatever f left behind is not torn down).
constexpr const char* kCallableScript = R"(
import math, os, sys, tempfile, time
SOURCE = sys.stdin.read()
LIMIT = 0.3
THREE = """name = "three"
[[family]]
name = "wall-sine"
scene = "wall"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi2 = { from = 0.5, to = 2, points = 3, spacing = "linear" }
"""

def result(text):
    sys.stdout.write("\nRESULT " + text.replace("\n", " ")[:400] + "\n")
    sys.stdout.flush()
    os._exit(0)

def busy(seconds):
    start = time.monotonic()
    while time.monotonic() - start < seconds:
        pass

class Weird(Exception):
    def __str__(self):
        raise RuntimeError("str() of this exception raises")

os.chdir(tempfile.mkdtemp())
with open("three.toml", "w") as out:
    out.write(THREE)
import poundbench
env = {"poundbench": poundbench, "time": time, "math": math, "busy": busy, "Weird": Weird, "SET": "three.toml"}
exec(compile(SOURCE, "callable.py", "exec"), env)
f = env["f"]
calls = []  # (seconds, the exception's type or None), one per call

def timed(case):
    start = time.monotonic()
    raised = None
    try:
        return f(case)
    except BaseException as e:
        raised = type(e).__name__
        raise
    finally:
        calls.append((time.monotonic() - start, raised))

def sweep(run):
    calls.clear()
    try:
        out = run()
    except KeyboardInterrupt:
        if any(r == "KeyboardInterrupt" for _, r in calls):
            return None  # f raised it: the sweep stopped, as it must
        result("BAD KeyboardInterrupt out of the sweep, and f raised none")
    except BaseException as e:
        result("BAD the sweep raised " + type(e).__name__ + ": " + str(e)[:200])
    if any(r == "KeyboardInterrupt" for _, r in calls):
        result("BAD f raised KeyboardInterrupt and the sweep went on")
    for seconds, _ in calls:
        if seconds > 15:  # 30 s unstopped; a tenth of a second stopped, ten times that on a slow machine
            result("BAD a call ran %.2f s: its limit of %g s did not stop it" % (seconds, LIMIT))
    return out

rows = sweep(lambda: poundbench.spectrum("three.toml", solver=timed, time_limit=LIMIT))
if rows is not None:
    if len(rows) != 3 or len(calls) != 3:
        result("BAD %d rows and %d calls for 3 points" % (len(rows), len(calls)))
    for row, (seconds, raised) in zip(rows, calls):
        message = row.get("message")
        if not isinstance(message, str) or "\n" in message or "\r" in message:
            result("BAD a row's message is not one line: %r" % (message,))
        if seconds > LIMIT and row["status"] != "time-limit":
            result("BAD a call of %.2f s past its limit of %g s is a row %s: %s" % (seconds, LIMIT, row["status"], message))
        if row["status"] == "ok" and not (isinstance(row["pi1"], float) and math.isfinite(row["pi1"]) and row["pi1"] >= 0):
            result("BAD an ok row with pi1 %r" % (row["pi1"],))
if env.get("STUDY"):
    table = sweep(lambda: poundbench.workprecision(
        "three.toml", settings=[{"solver": "mine", "steps": [16], "time_limit": LIMIT}], solvers={"mine": timed},
        repetitions=1))
    if table is not None and sum(r["points"] for r in table if r["solver"] == "external") != 3:
        result("BAD the study counted %r points of 3" % ([r["points"] for r in table],))
result("OK")
)";

// What a call does before it returns. The sleeps in C are past the limit or not; the loops in
// Python (busy) run 30 s unless interrupted.
const std::vector<std::string>& actions() {
  static const std::vector<std::string> v = {
      "pass",
      "time.sleep(0.05)",
      "time.sleep(0.45)",
      "time.sleep(0.9)",
      "busy(30.0)",
      "try:\n    busy(30.0)\nexcept BaseException:\n    pass",
      "try:\n    busy(30.0)\nexcept poundbench.TimeLimitExceeded:\n    time.sleep(0.1)",
      "poundbench.run(scene='wall', pulse='sine', directivity='normal', pi2=1, pi3=0.5, eps=0.5, "
      "solver='moreau-jean', steps=16)",
      "poundbench.run(scene='pair', pulse='cosine', directivity='normal', pi2=0.8, pi3=0.5, eps=0.5, pi5=0.5, "
      "pi6=1, solver='external', command='no-such-program-here')",
      "poundbench.spectrum(SET, solver=lambda c: {'status': 'ok', 'pi1': 1.0})",
      "poundbench.spectrum(SET, solver=lambda c: time.sleep(0.1))",
      "poundbench.run(scene='nope')",
      "case.clear()",
      "case['bodies'] = None",
      "print('noise on stdout', flush=True)",
      "raise ValueError('bad')",
      "raise ZeroDivisionError()",
      "raise RuntimeError('two\\nlines\\r\\x1b[31m')",
      "raise KeyError('\\ud800')",
      "raise Weird()",
      "raise SystemExit(3)",
      "raise KeyboardInterrupt()",
      "raise poundbench.TimeLimitExceeded()",
      "raise MemoryError()",
  };
  return v;
}

// What a call returns: answers right and wrong, no answer, huge documents.
const std::vector<std::string>& returns() {
  static const std::vector<std::string> v = {
      "{'status': 'ok', 'pi1': 1.0}",
      "{'status': 'ok', 'pi1': 1.0, 't_max': 2.0, 'impacts': 1, 'solve_seconds': 0.001}",
      "{'status': 'ok'}",
      "{'status': 'ok', 'pi1': float('nan')}",
      "{'status': 'ok', 'pi1': float('inf')}",
      "{'status': 'ok', 'pi1': -1.0}",
      "{'status': 'ok', 'pi1': 'x'}",
      "{'status': 'ok', 'pi1': 10**400}",
      "{'status': 'ok', 'pi1': 1.0, 'solve_seconds': -5}",
      "{'status': 5}",
      "{'status': 'time-limit', 'message': 'mine'}",
      "{'status': 'failed', 'message': 'x' * 100000}",
      "{'status': 'failed', 'message': 'one\\ntwo\\r\\x1b[31m\\ud800'}",
      "{'version': 2, 'status': 'ok', 'pi1': 1.0}",
      "{'status': 'ok', 'history': {'t': [0.0, 1.0], 'u0': [0.0]}}",
      "{'status': 'ok', 'history': {'t': [0.01 * i for i in range(100000)], 'u0': [0.5] * 100000}}",
      "{'status': 'ok', 'pi1': 1.0, **{('k%d' % i): i for i in range(2000)}}",
      "{'status': 'ok', 'pi1': 1.0, 'extra': eval('[' * 300 + ']' * 300)}",
      "None",
      "42",
      "'ok'",
      "[1, 2]",
      "case",
  };
  return v;
}

std::string indented(const std::string& text, const std::string& by) {
  std::string out = by;
  for (char c : text) {
    out += c;
    if (c == '\n') out += by;
  }
  return out + "\n";
}

}  // namespace

std::string make_callable(Rng& rng) {
  std::string out = rng.one_in(4) ? "STUDY = True\n" : "";
  out += "calls = [0]\n\ndef f(case):\n    i = calls[0] % 3\n    calls[0] += 1\n";
  for (int k = 0; k < 3; ++k) {
    out += "    if i == " + std::to_string(k) + ":\n";
    out += indented(rng.pick(actions()), "        ");
    out += "        return " + rng.pick(returns()) + "\n";
  }
  return out;
}

std::optional<std::string> check_callable(const std::string& program, const ChildLimits& limits) {
#ifdef POUNDBENCH_PYTHON_DIR
  const ChildOutcome o = run_program(POUNDBENCH_PYTHON, {"-c", kCallableScript}, POUNDBENCH_SOURCE_DIR, limits,
                                     {program, {std::string("PYTHONPATH=") + POUNDBENCH_PYTHON_DIR}});
  if (!o.exited || o.exit_code != 0) return o.describe() + (o.err.empty() ? "" : "; stderr: " + o.err.substr(0, 300));
  const std::size_t at = o.out.rfind("\nRESULT ");
  if (at == std::string::npos) return "no result reported; stderr: " + o.err.substr(0, 300);
  const std::string line = o.out.substr(at + 8, o.out.find('\n', at + 8) - (at + 8));
  if (line != "OK") return line.rfind("BAD ", 0) == 0 ? line.substr(4) : "result: " + line;
  return std::nullopt;
#else
  (void)program;
  (void)limits;
  return std::nullopt;
#endif
}

}  // namespace pb::fuzz
