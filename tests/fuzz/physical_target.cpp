#include "tests/fuzz/physical_target.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <set>
#include <string_view>

#include <nlohmann/json.hpp>

#include "cases/physical.hpp"
#include "tests/fuzz/harness.hpp"

namespace pb::fuzz {

namespace {

// A physical flag, the scenes that use it, and a value in its domain.
struct Flag {
  const char* name;
  std::vector<std::string_view> scenes;  // empty: every scene
  const char* value;
};

const std::vector<Flag>& physical_flags() {
  static const std::vector<Flag> flags = {
      {"--t0", {}, "0.5"},
      {"--gap", {}, "0.01"},
      {"--m0", {}, "2e5"},
      {"--t1", {"pair", "row3", "chain"}, "0.8"},
      {"--m1", {"pair", "row3", "chain"}, "1e5"},
      {"--t2", {"row3"}, "0.3"},
      {"--m2", {"row3"}, "3e5"},
      {"--uy0", {"wall", "pair", "row3"}, "0.02"},
      {"--uy1", {"pair", "row3"}, "0.03"},
      {"--uy2", {"row3"}, "0.02"},
      {"--uy", {"chain"}, "0.02"},
  };
  return flags;
}

// The values the campaign of issue 46 tried, and the edges of the masses' domain.
const std::vector<std::string>& hostile_values() {
  static const std::vector<std::string> values = {"nan", "NaN", "-nan", "inf", "-inf", "1e-308", "1e308", "5e-324",
                                                  "1e-300", "1e300", "-1", "-0.5", "0", "-0", "1e30", "1e-30",
                                                  "1e31", "1e-31", "1e-12", "1e12"};
  return values;
}

bool used(const Flag& f, std::string_view scene) {
  return f.scenes.empty() || std::find(f.scenes.begin(), f.scenes.end(), scene) != f.scenes.end();
}

std::string value_for(const char* sane, Rng& rng) { return rng.one_in(4) ? rng.pick(hostile_values()) : sane; }

// The pulse's scale: --a-p and --tp (or --w-p), each left out or made hostile now and then.
void add_scale(std::vector<std::string>& args, bool record, Rng& rng) {
  if (!rng.one_in(record ? 2 : 8)) args.insert(args.end(), {"--a-p", value_for("3", rng)});
  if (rng.one_in(4)) args.insert(args.end(), {"--w-p", value_for("6", rng)});
  else if (!rng.one_in(record ? 2 : 8)) args.insert(args.end(), {"--tp", value_for("1", rng)});
}

void add_solver(std::vector<std::string>& args, Rng& rng) {
  switch (rng.below(4)) {
    case 0: break;  // the reference
    case 1: args.insert(args.end(), {"--solver", "moreau-jean", "--steps", "32"}); break;
    default: args.insert(args.end(), {"--solver", "compliant"});
  }
  // --k-contact mostly with the compliant solver, and now and then where it has no use.
  if (rng.one_in(3)) args.insert(args.end(), {"--k-contact", value_for("1e9", rng)});
}

// What a value must be for a flag: its domain, as cases/physical.hpp and docs/cli.md give it.
// Returns why `value` lies outside, or nothing.
std::optional<std::string> physical_domain_problem(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double x = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || *end) return std::nullopt;
  const bool yield = flag.starts_with("--uy"), mass = flag.starts_with("--m");
  const bool physical = std::any_of(physical_flags().begin(), physical_flags().end(),
                                    [&](const Flag& f) { return flag == f.name; });
  if (!physical && flag != "--a-p" && flag != "--tp" && flag != "--w-p" && flag != "--k-contact") return std::nullopt;
  if (std::isnan(x)) return "NaN";
  if (x < 0.0) return "negative";
  if (std::isinf(x) && !yield) return "infinite";
  if (x == 0.0 && flag != "--gap") return "zero";
  if (mass && !(x >= kMinMass && x <= kMaxMass)) return "a mass outside [1e-30, 1e30] kg";
  return std::nullopt;
}

// The flag an exit-2 line names ("poundbench: --t0: reason"), and its reason.
std::pair<std::string, std::string> named_flag(const std::string& err) {
  const std::string line = err.substr(std::string_view("poundbench: ").size());
  const std::size_t colon = line.find(':');
  if (colon == std::string::npos) return {"", line};
  return {line.substr(0, colon), line.substr(colon + 1)};
}

std::optional<std::string> check_refusal(const ChildOutcome& o, const std::vector<std::string>& args) {
  if (auto bad = one_line_problem(o.err, o.err_size, "stderr")) return "exit 2: " + *bad;
  if (!o.err.starts_with("poundbench: ")) return "exit 2: stderr does not start with 'poundbench: ': " + excerpt(o.err);
  if (o.out_size) return "exit 2: stdout not empty: " + excerpt(o.out);
  const auto [flag, reason] = named_flag(o.err);
  const bool given = std::find(args.begin(), args.end(), flag) != args.end();
  if (!flag.starts_with("--")) return "exit 2: names no flag: " + excerpt(o.err);
  if (!given && !reason.starts_with(" required"))
    return "exit 2: names " + flag + ", which the command line did not give: " + excerpt(o.err);
  return std::nullopt;
}

bool number(const nlohmann::json& row, const char* key) { return row.contains(key) && row[key].is_number(); }

// An ok row's numbers (the property above); `compliant`: the solver was the compliant one.
std::optional<std::string> check_row(const ChildOutcome& o, bool compliant) {
  const nlohmann::json row = nlohmann::json::parse(o.out, nullptr, false);
  if (!row.is_object()) return "stdout is no JSON object: " + excerpt(o.out);
  const bool ok = row.value("status", "") == "ok";
  if (ok != (o.exit_code == 0)) return o.describe() + " with status " + row.value("status", "?");
  if (!ok) return std::nullopt;
  if (!number(row, "pi1") || !(row["pi1"].get<double>() >= 0.0)) return "ok with pi1 " + row.value("pi1", nlohmann::json()).dump();
  if (!number(row, "peak_m")) return "ok with peak_m " + row.value("peak_m", nlohmann::json()).dump();
  if (compliant && !number(row, "contact_force_max"))
    return "ok through the compliant solver with contact_force_max " + row.value("contact_force_max", nlohmann::json()).dump();
  if (number(row, "impact_velocity") != number(row, "impact_velocity_pi"))
    return "ok with impact_velocity " + row.value("impact_velocity", nlohmann::json()).dump() + " but impact_velocity_pi " +
           row.value("impact_velocity_pi", nlohmann::json()).dump();
  return std::nullopt;
}

}  // namespace

std::vector<std::string> make_physical_args(Rng& rng) {
  static const std::vector<std::string> scenes = {"wall", "pair", "row3", "chain"};
  const std::string scene = rng.pick(scenes);
  const bool record = rng.one_in(6);
  std::vector<std::string> args = {"run", "--scene", scene, "--pulse", record ? "record" : (rng.one_in(2) ? "sine" : "cosine")};
  if (record) args.insert(args.end(), {"--record", "rec.at2"});
  if (scene == "chain") args.insert(args.end(), {"--bodies", "3"});
  if (rng.one_in(3)) args.insert(args.end(), {"--directivity", rng.one_in(2) ? "normal" : "reverse"});
  args.insert(args.end(), {"--eps", "0.5"});
  for (const Flag& f : physical_flags()) {
    const std::string_view name = f.name;
    const bool required = name == "--t0" || name == "--gap" || name == "--t1" || name == "--t2";
    const bool yield = name.starts_with("--uy"), mass = name.starts_with("--m");
    if (!used(f, scene)) {
      if (rng.one_in(12)) args.insert(args.end(), {f.name, f.value});  // a flag the scene has no body for
      continue;
    }
    // A required one left out now and then (a missing companion); the others given now and then.
    const bool give = required ? !rng.one_in(8) : rng.one_in(yield ? 4 : mass ? 3 : 2);
    if (give) args.insert(args.end(), {f.name, value_for(f.value, rng)});
  }
  add_scale(args, record, rng);
  add_solver(args, rng);
  args.insert(args.end(), {"--json", "--time-limit", "2"});
  return args;
}

std::optional<std::string> check_physical(const std::vector<std::string>& args, const ChildLimits& limits) {
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() /
                       ("poundbench-fuzz-physical-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(fs::path(POUNDBENCH_SOURCE_DIR) / "cases/records/real/AZF225.AT2", dir / "rec.at2");
  const std::set<std::string> before = listing(dir);
  const ChildOutcome o = run_program(POUNDBENCH_EXE, args, dir, limits);
  const std::set<std::string> after = listing(dir);
  fs::remove_all(dir);

  if (!o.exited || !sanitizer_line(o.err).empty())
    return o.describe() + (o.err.empty() ? "" : "; stderr: " + excerpt(o.err, 300));
  if (after != before) return o.describe() + ": left a file behind";
  if (o.exit_code == 2) return check_refusal(o, args);
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (auto why = physical_domain_problem(args[i], args[i + 1]))
      return "accepted " + args[i] + " " + args[i + 1] + " (" + *why + "; " + o.describe() + "): it must exit 2";
  if (o.exit_code != 0 && o.exit_code != 1) return o.describe() + "; stderr: " + excerpt(o.err, 300);
  const bool compliant = std::find(args.begin(), args.end(), "compliant") != args.end();
  return check_row(o, compliant);
}

}  // namespace pb::fuzz
