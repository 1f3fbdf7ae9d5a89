#include "tests/fuzz/persistent.hpp"

#include <vector>

namespace pb::fuzz {

namespace {

// Runs the program read from stdin (its source) as a persistent external program over four
// points at --time-limit 1, in a fresh directory, and ends with one line: "RESULT OK" or
// "RESULT BAD <why>". argv[1] is poundbench.
constexpr const char* kDriver = R"PY(
import csv, io, os, shutil, signal, subprocess, sys, tempfile, unicodedata
POUNDBENCH = sys.argv[1]
SOURCE = sys.stdin.read()
POINTS, LIMIT, BOUND = 4, 1, 90
STATUSES = {"ok", "diverged", "nan", "step_cap", "time-limit", "failed", "penetration", "energy"}
# What a row's message must not hold (docs/external.md): control characters, line and paragraph
# separators, bidirectional controls.
BIDI = set("\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")
FOUR = """name = "four"
[[family]]
name = "pair"
scene = "pair"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi5 = 0.75
pi6 = 1
pi2 = { from = 0.5, to = 2, points = 4, spacing = "linear" }
"""

def result(text):
    os.chdir("/")
    shutil.rmtree(WORK, ignore_errors=True)
    sys.stdout.write("\nRESULT " + text.replace("\n", " ")[:400] + "\n")
    sys.stdout.flush()
    os._exit(0)

def end_children():
    """The children the program left behind, still sleeping: poundbench cannot end one that
    left its group, and the harness must not leave them."""
    try:
        pids = [int(p) for p in open("children").read().split()]
    except (OSError, ValueError):
        return
    for pid in pids:
        try:
            with open("/proc/%d/cmdline" % pid, "rb") as f:
                if f.read().split(b"\0")[:2] == [b"sleep", b"100"]:
                    os.kill(pid, signal.SIGKILL)
        except OSError:
            pass

def unprintable(message):
    return [c for c in message if unicodedata.category(c) in ("Cc", "Zl", "Zp") or c in BIDI]

WORK = tempfile.mkdtemp(prefix="pb-persistent-fuzz-")
os.chdir(WORK)
with open("four.toml", "w") as out:
    out.write(FOUR)
with open("program.py", "w") as out:
    out.write(SOURCE)
threads = "2" if "THREADS = 2" in SOURCE else "1"
try:
    run = subprocess.run([POUNDBENCH, "spectrum", "four.toml", "--solver", "external", "--persistent", "--command",
                          sys.executable + " program.py", "--threads", threads, "--time-limit", str(LIMIT),
                          "--out", "rows.csv"], stdin=subprocess.DEVNULL, capture_output=True, timeout=BOUND)
except subprocess.TimeoutExpired:
    end_children()
    result("BAD no end within %d s (%d points, a limit of %d s each)" % (BOUND, POINTS, LIMIT))
end_children()
if run.returncode != 0:
    result("BAD exit %d: %r" % (run.returncode, run.stderr[:300]))
try:
    text = open("rows.csv", "rb").read().decode("utf-8")
except UnicodeDecodeError as e:
    result("BAD the rows are not UTF-8: " + str(e))
rows = list(csv.DictReader(io.StringIO(text, newline="")))
if len(rows) != POINTS:
    result("BAD %d rows for %d points" % (len(rows), POINTS))
for row in rows:
    if row.get("status") not in STATUSES:
        result("BAD a row's status is %r" % (row.get("status"),))
    message = row.get("message") or ""
    if unprintable(message):
        result("BAD a row's message holds %r: %r" % (unprintable(message)[:5], message[:200]))
    if row["status"] == "ok" and "NO_READY = True" in SOURCE:
        result("BAD an ok row from a program whose first line is no ready line: %r" % (message[:200],))
    # The program's answer to a case is its pi2 (answer(), below); a second line, or the answer
    # to another case, taken for this case's answer is not.
    if row["status"] == "ok" and not abs(float(row["pi1"]) - float(row["pi2"])) <= 1e-9 * float(row["pi2"]):
        result("BAD an ok row's Pi1 %s is not its case's answer %s: %r" % (row["pi1"], row["pi2"], message[:200]))
result("OK")
)PY";

// The program's head: what its actions call.
constexpr const char* kHead = R"PY(import json, os, subprocess, sys, time

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

)PY";

const std::string kReady = "out(json.dumps({\"version\": 1, \"ready\": True}) + \"\\n\")";

// Before the first case: the ready line, right or wrong (true: no ready line, so that no row may
// be ok; the driver sees NO_READY = True in the program).
const std::vector<std::pair<std::string, bool>>& ready_actions() {
  static const std::vector<std::pair<std::string, bool>> v = {
      {kReady, false},
      {kReady, false},
      {kReady, false},
      {"out('{\"version\": 1, \"ready\": false}\\n')", true},
      {"out('\"ready\"\\n')", true},
      {"out('ready\\n')", true},
      {kReady + "\n" + kReady, false},
      {"out('{\"version\": 1, \"re')\ntime.sleep(0.3)\nout('ady\": true}\\n')", false},
      {"time.sleep(1.5)\n" + kReady, false},
      {"raw(b'{\"version\": 1, \"ready\": true, \"x\": \"\\xff\\x1b[2J\"}\\n')", true},
      {"leave('setsid', 'sleep', '100')\n" + kReady, false},
      {"sys.exit(0)", true},
  };
  return v;
}

// What the program does with a case.
const std::vector<std::string>& case_actions() {
  static const std::vector<std::string> v = {
      "out(answer(case) + '\\n')",
      "out(answer(case) + '\\n')",
      // A second line, late or at once; the next case is read 2 s later, so that the line
      // surely comes before it is read (one written just before the program reads it is not
      // told from an answer: docs/external.md).
      "out(answer(case) + '\\n')\ntime.sleep(0.05)\nout(answer(case, 99.0) + '\\n')\ntime.sleep(2)",
      "out(answer(case) + '\\n' + answer(case, 99.0) + '\\n')",
      "out(answer(case)[:20])\ntime.sleep(0.2)\nout(answer(case)[20:] + '\\n')",
      "out(answer(case)[:20])\nsys.exit(0)",
      "sys.exit(0)",
      "out(answer(case) + '\\n')\nsys.exit(0)",
      "os.kill(os.getpid(), 9)",
      "time.sleep(3)",
      "raw(b'{\"version\": 1, \"status\": \"failed\", \"message\": \"\\xff\\xfe\\x1b[2J\"}\\n')",
      "out(answer(case, message='esc \\x1b[31m nul \\x00 sep \\u2028 rlo \\u202e c1 \\x85 nl \\n') + '\\n')",
      "sys.stderr.buffer.write(b'\\xff\\x1b[2J bad\\n\\x85\\n')\nsys.stderr.flush()\nsys.exit(3)",
      "out('{\"version\": 1, \"status\": \"ok\", \"pi1\": 1' + ''.join(', \"k%d\": 0' % k for k in range(200000)) + "
      "', \"k0\": 1}\\n')",
      "out(answer(case, message='x' * 100000) + '\\n')",
      "leave('setsid', 'sleep', '100')\ntime.sleep(3)",
      "leave('setsid', 'sleep', '100')\nsys.exit(0)",
      "leave('sleep', '100')\nsys.exit(0)",
      "os.close(1)\ntime.sleep(3)",
      "out('\\n')",
      "out('not json at all\\n')",
      "out('x' * 2000000)\nsys.exit(0)",
  };
  return v;
}

}  // namespace

bool persistent_available() {
#ifdef POUNDBENCH_PYTHON3
  return true;
#else
  return false;
#endif
}

std::string make_persistent_program(Rng& rng) {
  std::string out = rng.one_in(4) ? "THREADS = 2\n" : "";
  out += kHead;
  const auto& [ready, no_ready] = rng.pick(ready_actions());
  if (no_ready) out += "NO_READY = True\n";
  out += ready + "\ncalls = 0\nfor line in sys.stdin:\n    case = json.loads(line)\n";
  out += "    i = calls % 3\n    calls += 1\n";
  for (int k = 0; k < 3; ++k) {
    out += "    if i == " + std::to_string(k) + ":\n";
    for (const std::string& line : split_lines(rng.pick(case_actions()))) out += "        " + line + "\n";
  }
  return out;
}

std::optional<std::string> check_persistent(const std::string& source, const ChildLimits& limits) {
#ifdef POUNDBENCH_PYTHON3
  const ChildOutcome o = run_program(POUNDBENCH_PYTHON3, {"-c", kDriver, POUNDBENCH_EXE}, POUNDBENCH_SOURCE_DIR,
                                     limits, {source, {}});
  const std::string err = o.err.substr(0, 300);
  if (!o.exited || o.exit_code != 0) return o.describe() + (err.empty() ? "" : "; stderr: " + err);
  // The driver's last line: RESULT OK, or RESULT BAD and the property.
  const std::vector<std::string> lines = split_lines(o.out);
  const std::string last = lines.empty() ? "" : lines.back();
  if (last == "RESULT OK") return std::nullopt;
  if (last.starts_with("RESULT BAD ")) return last.substr(11);
  return "the driver reported nothing; stderr: " + err;
#else
  (void)source;
  (void)limits;
  return std::nullopt;
#endif
}

}  // namespace pb::fuzz
