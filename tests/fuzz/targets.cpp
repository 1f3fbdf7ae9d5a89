#include "tests/fuzz/targets.hpp"

#include "tests/fuzz/harness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "cases/case.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "programs/protocol.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"

namespace pb::fuzz {

namespace {

using Json = nlohmann::json;

std::optional<std::string> one_line(const std::string& message, const std::string& what) {
  if (message.empty()) return what + " is empty";
  if (message.find('\n') != std::string::npos) return what + " is more than one line: " + message.substr(0, 160);
  if (message.size() > kMaxMessage)
    return what + " is " + std::to_string(message.size()) + " characters (> 300): " + message.substr(0, 160);
  return std::nullopt;
}

// The case every answer answers: a pair under a sine pulse (its t_end is ~25).
System answered_system() {
  Case c;
  c.scene = Scene::pair;
  c.pulse = PulseShape::sine;
  c.pi2 = 1.0;
  c.pi5 = 0.5;
  return make_system(c);
}

std::shared_ptr<const Record> short_record() {
  return std::make_shared<const Record>(
      parse_record("h\nh\nUNITS OF G\nNPTS= 8, DT= .05 SEC\n 0 .1 -.2 .3\n -.1 .05 0 0\n", "short.at2"));
}

// What a child reports on stdout: "OK ...", "ERR <message>" or "EXC <what>".
template <class Body>
std::optional<std::string> in_child(const Body& body, const ChildLimits& limits) {
  const ChildOutcome o = report_in_child(body, limits);
  if (!o.exited || o.exit_code != 0 || !sanitizer_line(o.err).empty())
    return o.describe() + (o.err.empty() ? "" : "; stderr: " + o.err.substr(0, 300));
  if (o.out.rfind("EXC ", 0) == 0) return "threw: " + o.out.substr(4, 200);
  if (o.out.rfind("ERR ", 0) == 0) return one_line(o.out.substr(4), "message");
  if (o.out.rfind("BAD ", 0) == 0) return o.out.substr(4, 300);
  if (o.out.rfind("OK", 0) != 0) return "no outcome reported; stdout: " + o.out.substr(0, 160);
  return std::nullopt;
}

std::string record_report(const std::string& text) {
  const bool at2 = text.find("NPTS") != std::string::npos;
  const char* source = at2 ? "fuzz.at2" : "fuzz.csv";
  try {
    const Record r = parse_record(text, source);
    return "OK " + std::to_string(r.t.size());
  } catch (const RecordError& e) {
    const std::string message = e.what();
    if (message.rfind(source, 0) != 0) return "BAD message does not start with the file name: " + message.substr(0, 160);
    return "ERR " + message;
  }
}

std::string answer_report(const std::string& text) {
  static const System system = answered_system();
  Settings settings;
  settings.history_samples = 50;
  Result result;
  result.step = system.step(64);
  const std::string bad = programs::read_answer(text, system, settings, result);
  if (!bad.empty()) {
    if (bad.rfind("answer: ", 0) != 0) return "BAD message does not start with 'answer: ': " + bad.substr(0, 160);
    return "ERR " + bad;
  }
  if (result.status == Status::ok) {
    if (!(std::isfinite(result.pi1) && result.pi1 >= 0.0)) return "BAD accepted an ok answer with Pi1 " + std::to_string(result.pi1);
    if (!std::isnan(result.t_max) && !(result.t_max >= 0.0 && result.t_max <= system.t_end * 1.01))
      return "BAD accepted a Pi1 taken outside the run, at t = " + std::to_string(result.t_max);
  }
  return "OK";
}

std::string document_report(const std::string& text, bool every_solver) {
  programs::CaseRead read;
  try {
    read = programs::read_case(text);
  } catch (const std::invalid_argument& e) {
    return std::string("ERR ") + e.what();
  }
  // A campaign's input meets one solver, chosen by the text, so that every engine meets the
  // documents; a corpus entry meets them all.
  static const std::vector<const char*> names = {"event-driven", "moreau-jean", "ode",      "bullet",
                                                 "siconos",      "mujoco",      "compliant", "moreau-jean"};
  std::vector<const SolverInfo*> chosen;
  for (std::size_t k = 0; k < names.size(); ++k)
    if (every_solver || k == text.size() % names.size())
      if (const SolverInfo* s = find_solver(names[k])) chosen.push_back(s);
  for (const SolverInfo* solver : chosen) {
    Settings settings = read.settings;
    settings.time_limit = 2.0;  // the harness's own, as the CLI campaigns' --time-limit 2
    if (!solver->check(settings).empty()) continue;
    const Result r = solver->solve(read.system, settings);
    if (r.status == Status::ok && !(std::isfinite(r.pi1) && r.pi1 >= 0.0))
      return "BAD " + std::string(solver->name) + " said ok with Pi1 " + std::to_string(r.pi1);
  }
  return "OK";
}

// ---------------------------------------------------------------- mutations

const std::vector<std::string>& record_numbers() {
  static const std::vector<std::string> v = {"nan", "inf", "-inf", "1e-320", "4.9e-324", "1e308", "-1e308", "1e999",
                                             "0", "-0", "", "1.5D-03", "+.5", "1e", "--1", "0x10", "1,5",
                                             std::string(5000, '9'), "0.0000000000000000000001"};
  return v;
}

const std::vector<std::string>& record_lines() {
  static const std::vector<std::string> v = {"*** End Data ***", "NPTS= 3, DT= .01 SEC", "NPTS= 0, DT= .01 SEC",
                                             "NPTS= 200001, DT= .01", "NPTS= 5, DT= 1e-320", "NPTS= 5, DT= nan",
                                             "   5   .0100   NPTS, DT", "UNITS OF GAL", "UNITS OF CM/S/S",
                                             "ACCELERATION IN M/S/S", "UNITS OF FURLONGS", "t, a_g", "# comment",
                                             "", "\r", "1e9, 1", "-1, 0", "1, 1, 1", std::string(100'000, 'x')};
  return v;
}

std::string mutate_record(std::string_view seed, const std::vector<std::string>& seeds, Rng& rng) {
  std::vector<std::string> lines = split_lines(seed);
  const bool truncate = mutate_lines(lines, rng, [&](std::size_t where) {
    switch (rng.below(8)) {
      case 0:
      case 1:
      case 2: {  // a number replaced by an interesting one
        if (lines.empty()) break;
        std::string& line = lines[rng.below(lines.size())];
        std::vector<std::size_t> starts;
        for (std::size_t i = 0; i < line.size(); ++i)
          if ((i == 0 || line[i - 1] == ' ' || line[i - 1] == ',') && line[i] != ' ') starts.push_back(i);
        if (starts.empty()) break;
        const std::size_t at = rng.pick(starts);
        const std::size_t end = std::min(line.find_first_of(" ,", at), line.size());
        line.replace(at, end - at, rng.pick(record_numbers()));
        break;
      }
      case 3:
        insert_line(lines, where, rng.pick(record_lines()));
        break;
      case 4:
        remove_line(lines, rng);
        break;
      case 5:
        repeat_line(lines, where, rng);
        break;
      case 6: {  // bytes, or a line from another seed
        if (rng.one_in(2)) {
          splice_line(lines, where, seeds, rng);
        } else if (!lines.empty()) {
          std::string& line = lines[rng.below(lines.size())];
          const std::size_t pos = line.empty() ? 0 : rng.below(line.size());
          static constexpr std::string_view kBytes = "\r\t,.-+eED \x00\x7f\xff";
          line.insert(pos, 1, kBytes[rng.below(kBytes.size())]);
        }
        break;
      }
      default:
        return true;
    }
    return false;
  });
  std::string text;
  const std::string end = rng.one_in(4) ? "\r\n" : rng.one_in(8) ? "\r\r\n" : "\n";
  for (const std::string& line : lines) text += line + end;
  if (truncate && !text.empty()) text.resize(rng.below(text.size()));
  return text;
}

const std::vector<std::string>& json_values() {
  static const std::vector<std::string> v = [] {
    std::vector<std::string> values = {
        "null", "true", "\"\"", "\"ok\"", "\"failed\"", "-1", "0", "1", "2", "0.5", "1e308", "-1e308", "1e-320",
        "5e-324", "1e300", "1e9", "-1e9", "9223372036854775807", "18446744073709551616", "[]", "{}", "[1, 2, 3]",
        "[0, -1, 1e9]", "[1e9, 0]", "{\"t\": [0, 1e9], \"u0\": [1, 2]}", "{\"t\": [5, 1], \"u0\": [1, 2]}",
        "\"\\ud800\"", "\"\xff\xfe\"", "\"a\\u0000b\""};
    values.push_back('"' + std::string(200'000, 'm') + '"');
    std::string many = "[";
    for (int i = 0; i < 20'000; ++i) many += (i ? ",1" : "1");
    values.push_back(many + "]");
    values.push_back(std::string(100'000, '[') + std::string(100'000, ']'));
    return values;
  }();
  return v;
}

// Every value of a document, by JSON pointer.
void pointers(const Json& j, const Json::json_pointer& at, std::vector<Json::json_pointer>& out) {
  out.push_back(at);
  if (j.is_object())
    for (const auto& [key, value] : j.items()) pointers(value, at / key, out);
  if (j.is_array())
    for (std::size_t i = 0; i < std::min<std::size_t>(j.size(), 4); ++i) pointers(j[i], at / i, out);
}

std::string mutate_json(std::string_view seed, Rng& rng) {
  Json doc = Json::parse(seed);
  std::string text;
  const std::size_t mutations = 1 + rng.below(3);
  std::vector<std::string> raw;  // values spliced in as text (not all are valid JSON)
  for (std::size_t m = 0; m < mutations; ++m) {
    std::vector<Json::json_pointer> at;
    pointers(doc, Json::json_pointer(), at);
    const Json::json_pointer& p = at[rng.below(at.size())];
    switch (rng.below(4)) {
      case 0:
      case 1:  // a value replaced (as a placeholder, spliced in as text below)
        if (!p.empty()) {
          raw.push_back(rng.pick(json_values()));
          doc[p] = "@RAW" + std::to_string(raw.size() - 1) + "@";
        }
        break;
      case 2: {  // a key (or an array's element) removed
        if (p.empty()) break;
        Json& parent = doc[p.parent_pointer()];
        if (parent.is_object()) parent.erase(p.back());
        else if (parent.is_array()) parent.erase(static_cast<std::size_t>(std::stoul(p.back())));
        break;
      }
      default: {  // a key added to an object
        Json& object = doc[p.empty() ? p : p.parent_pointer()];
        if (!object.is_object()) break;
        static const std::vector<std::string> keys = {"status", "pi1", "t_max", "history", "message", "eps", "xi",
                                                      "a_p", "load", "bodies", "extra", "time_limit", "step"};
        raw.push_back(rng.pick(json_values()));
        object[rng.pick(keys) + (rng.one_in(3) ? "_" : "")] = "@RAW" + std::to_string(raw.size() - 1) + "@";
      }
    }
  }
  text = doc.dump();
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const std::string mark = "\"@RAW" + std::to_string(i) + "@\"";
    if (const std::size_t at = text.find(mark); at != std::string::npos) text.replace(at, mark.size(), raw[i]);
  }
  switch (rng.below(6)) {
    case 0: {  // a key given twice: a copy of a member first
      const std::size_t colon = text.find("\":");
      if (colon != std::string::npos && text.size() > 1) {
        const std::size_t key = text.rfind('"', colon - 1);
        const std::size_t end = std::min(text.find_first_of(",}", colon), text.size());
        if (key != std::string::npos && key > 0) text.insert(1, text.substr(key, end - key) + ",");
      }
      break;
    }
    case 1:  // a byte flipped
      if (!text.empty()) {
        const std::size_t pos = rng.below(text.size());
        text[pos] = static_cast<char>(text[pos] ^ (1 << rng.below(8)));
      }
      break;
    case 2:  // cut short
      if (!text.empty()) text.resize(rng.below(text.size()));
      break;
    default:
      break;
  }
  return text;
}

}  // namespace

std::optional<std::string> check_document(Document kind, const std::string& text, const ChildLimits& limits,
                                          bool every_solver) {
  switch (kind) {
    case Document::record: return in_child([&] { return record_report(text); }, limits);
    case Document::answer: return in_child([&] { return answer_report(text); }, limits);
    case Document::case_document: return in_child([&] { return document_report(text, every_solver); }, limits);
  }
  return std::nullopt;
}

std::vector<std::string> document_seeds(Document kind) {
  std::vector<std::string> seeds;
  if (kind == Document::record) {
    seeds = {"PEER\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS=  6, DT= .00500 SEC\n .1 .2 -.3 .4 .5\n -.6\n",
             "PEER\nEVENT\nUNITS OF G\nNPTS=   6, dt=  .00500\n .1E-02 .2E-02 -.3E-02\n .4 .5 -.6\n*** End Data ***\n",
             "PEER\nEVENT\nUNITS OF G\n    6    .0050    NPTS, DT\n .1 .2 -.3 .4 .5 -.6\n",
             "PEER\nEVENT\nSTATION\nIN CM/S/S\nNPTS= 4, DT= 0.01\n 1 2 3 4\n",
             "t, a_g\n0, 0\n0.1, 1.5\n0.2, -2\n0.3, 0.5\n",
             "# comment\n0,0\n1,1\n2,0\n"};
    // Three real files' headers and first values (NPTS set to the 40 values kept).
    const std::string real = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/real/";
    for (const char* name : {"TCU054-N.AT2", "CEM000.AT2", "GCN-WE.AT2"}) {
      std::ifstream in(real + name);
      std::string line, text;
      for (int i = 0; i < 12 && std::getline(in, line); ++i) text += (i == 3 ? "NPTS=  40, DT= .00500 SEC" : line) + "\n";
      seeds.push_back(text);
    }
    return seeds;
  }
  if (kind == Document::answer) {
    const System system = answered_system();
    for (const char* solver : {"event-driven", "moreau-jean"}) {
      Settings settings;
      settings.history_samples = 20;
      const Result r = find_solver(solver)->solve(system, settings);
      seeds.push_back(programs::answer_document(r, system));
    }
    seeds.push_back(R"({"version": 1, "status": "ok", "pi1": 2.5, "t_max": 5.4, "impacts": 4, "message": "x"})");
    seeds.push_back(R"({"protocol": "poundbench-external", "version": 1, "status": "failed", "message": "why"})");
    return seeds;
  }
  // Case documents for every scene and load, with and without a step.
  const auto add = [&](Case c, int steps) {
    Settings settings;
    settings.steps = steps;
    settings.history_samples = steps > 0 ? 0 : 10;
    seeds.push_back(programs::case_document(make_system(c), settings).text);
  };
  add({.scene = Scene::wall}, 0);
  add({.scene = Scene::pair, .pulse = PulseShape::cosine, .pi3 = 0.0}, 64);
  add({.scene = Scene::row3, .pulse = PulseShape::makris_c, .cycles = 2}, 32);
  add({.scene = Scene::chain, .pulse = PulseShape::mp, .bodies = 4, .mp_gamma = 2.5}, 0);
  const std::shared_ptr<const Record> record = short_record();
  add({.pulse = PulseShape::record, .a_p = record->peak, .w_p = 10.0, .record = "short.at2", .samples = record}, 16);
  return seeds;
}

std::string mutate_document(Document kind, std::string_view seed, const std::vector<std::string>& seeds, Rng& rng) {
  return kind == Document::record ? mutate_record(seed, seeds, rng) : mutate_json(seed, rng);
}

// ---------------------------------------------------------------- the Python module

bool python_available() {
#ifdef POUNDBENCH_PYTHON_DIR
  return true;
#else
  return false;
#endif
}

namespace {

// Evaluates the keywords (the harness's own text: eval with no builtins but nan, inf, Path
// and object) and reports OK, ERR <type>: <message> for ValueError and TypeError, or EXC
// <type>: <message> for anything else.
constexpr const char* kPythonScript = R"(
import math, pathlib, sys
text = sys.stdin.read()
kw = eval(text, {"__builtins__": {}}, {"nan": math.nan, "inf": math.inf, "Path": pathlib.PurePosixPath, "object": object})
import poundbench
function = kw.pop("__function__", "run")
try:
    if function == "run":
        poundbench.run(**kw)
    else:
        poundbench.spectrum(kw.pop("case_set", None), **kw)
    print("OK")
except (ValueError, TypeError) as e:
    print("ERR " + type(e).__name__ + ": " + str(e).encode("utf-8", "backslashreplace").decode())
except BaseException as e:
    print("EXC " + type(e).__name__ + ": " + str(e).encode("utf-8", "backslashreplace").decode()[:300])
)";

const std::vector<std::string>& python_values() {
  static const std::vector<std::string> v = {
      "None", "True", "False", "''", "'x'", "'\\ud800'", "'\\udcff'", "'\\xff'", "'x' * 100000", "b'bytes'",
      "-1", "0", "1", "2", "0.5", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "2**31", "-2**31 - 1",
      "2**63", "-2**63 - 1", "2**64", "10**400", "-10**400", "[]", "{}", "[1, 2]", "object()",
      "Path('cases/sets/smoke.toml')", "'/dev/zero'", "'/'", "'pair'", "'record'", "'moreau-jean'", "'external'",
      "'siconos'", "'compliant'", "'kelvin-voigt'", "1e11", "1e300"};
  return v;
}

const std::vector<std::string>& python_keys() {
  static const std::vector<std::string> keys = {
      "scene", "pulse", "directivity", "pi2", "pi3", "eps", "pi5", "pi6", "pi7", "pi8", "bodies", "kick", "xi",
      "n_free", "a_p", "w_p", "tp", "record", "cycles", "mp_gamma", "mp_nu", "case_file", "point", "solver",
      "variant", "steps", "wh", "theta", "gamma", "tol_scale", "step_cap", "time_limit", "stiffness", "rtol",
      "integrator", "method", "contact", "contact_steps", "command", "lcp", "projection_tol", "history", "samples",
      "threads", "case_set", "\\ud800", "x" , "__function__"};
  return keys;
}

}  // namespace

std::optional<std::string> check_python(const std::string& keywords, const ChildLimits& limits) {
#ifdef POUNDBENCH_PYTHON_DIR
  const ChildOutcome o =
      run_program(POUNDBENCH_PYTHON, {"-c", kPythonScript}, POUNDBENCH_SOURCE_DIR,
                  limits, {keywords, {std::string("PYTHONPATH=") + POUNDBENCH_PYTHON_DIR}});
  if (!o.exited || o.exit_code != 0) return o.describe() + (o.err.empty() ? "" : "; stderr: " + o.err.substr(0, 300));
  const std::string out = o.out.substr(0, o.out.find('\n'));
  if (out.rfind("EXC ", 0) == 0) return "raised " + out.substr(4);
  if (out.rfind("ERR ", 0) == 0) return one_line(out.substr(out.find(": ") + 2), "message");
  if (out != "OK") return "no outcome reported; stdout: " + o.out.substr(0, 160) + "; stderr: " + o.err.substr(0, 300);
  return std::nullopt;
#else
  (void)keywords;
  (void)limits;
  return std::nullopt;
#endif
}

std::vector<std::string> python_seeds() {
  return {
      "{'scene': 'pair', 'pulse': 'cosine', 'directivity': 'normal', 'pi2': 0.8, 'pi3': 0.5, 'eps': 0.5, "
      "'pi5': 0.5, 'pi6': 1.0, 'solver': 'moreau-jean', 'steps': 64, 'time_limit': 2}",
      "{'scene': 'wall', 'pulse': 'sine', 'directivity': 'reverse', 'pi2': 1, 'pi3': 0, 'eps': 1, 'history': True, "
      "'time_limit': 2}",
      "{'scene': 'pair', 'pulse': 'record', 'record': 'cases/records/real/AZF225.AT2', 'tp': 0.5, "
      "'directivity': 'normal', 'pi2': 1, 'pi3': 0.5, 'eps': 0.5, 'pi5': 2, 'pi6': 1, 'time_limit': 2}",
      "{'case_file': 'cases/sets/smoke.toml', 'point': 3, 'solver': 'event-driven', 'time_limit': 2}",
      "{'__function__': 'spectrum', 'case_set': 'cases/sets/smoke.toml', 'solver': 'moreau-jean', 'steps': 16, "
      "'threads': 1, 'time_limit': 2}",
  };
}

std::string mutate_python(std::string_view seed, Rng& rng) {
  // The seed's items, "'key': value", split at the top-level commas.
  std::string body(seed.substr(1, seed.size() - 2));
  std::vector<std::string> items;
  int depth = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= body.size(); ++i) {
    if (i < body.size() && (body[i] == '(' || body[i] == '[' || body[i] == '{')) ++depth;
    if (i < body.size() && (body[i] == ')' || body[i] == ']' || body[i] == '}')) --depth;
    if (i == body.size() || (body[i] == ',' && depth == 0)) {
      items.push_back(body.substr(start, i - start));
      start = i + 1;
    }
  }
  const std::size_t mutations = 1 + rng.below(3);
  for (std::size_t m = 0; m < mutations; ++m) {
    switch (rng.below(4)) {
      case 0:
      case 1: {  // a value replaced; never the harness's time limit
        std::string& item = items[rng.below(items.size())];
        if (item.find("time_limit") != std::string::npos || item.find("__function__") != std::string::npos) break;
        item = item.substr(0, item.find(':') + 1) + ' ' + rng.pick(python_values());
        break;
      }
      case 2: {  // a keyword added
        const std::string key = rng.pick(python_keys());
        if (key == "time_limit" || key == "__function__") break;
        items.push_back("'" + key + "': " + rng.pick(python_values()));
        break;
      }
      default:  // a keyword removed
        if (items.size() > 1) {
          const std::size_t i = rng.below(items.size());
          if (items[i].find("time_limit") == std::string::npos && items[i].find("__function__") == std::string::npos)
            items.erase(items.begin() + static_cast<std::ptrdiff_t>(i));
        }
    }
  }
  std::string out = "{";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + items[i];
  return out + "}";
}

}  // namespace pb::fuzz
