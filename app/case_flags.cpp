#include "app/case_flags.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string_view>

#include "app/errors.hpp"
#include "cases/case_set.hpp"

namespace pb::app {

namespace {

// Every flag that describes a case, in the order they are checked.
constexpr std::array<std::string_view, 16> kCaseFlags = {
    "--scene", "--pulse", "--directivity", "--pi2", "--pi3",   "--eps", "--pi5", "--pi6",
    "--pi7",   "--pi8",   "--bodies",      "--kick", "--xi", "--n-free", "--a-p", "--w-p"};

bool given(const CLI::App& command, std::string_view flag) { return command.count(std::string(flag)) > 0; }

template <class T>
T parsed(std::string_view flag, const std::string& text, std::optional<T> value, std::string_view choices) {
  if (!value)
    throw BadInput(std::string(flag) + ": unknown value '" + clip(text) + "' (one of " + std::string(choices) + ")");
  return *value;
}

ChosenCase case_from_file(const CLI::App& command, const CaseFlags& flags) {
  for (std::string_view flag : kCaseFlags)
    if (given(command, flag)) throw BadInput(std::string(flag) + ": cannot be combined with --case-file");
  const CaseSet set = load_case_set(flags.case_file);
  const std::size_t n = set.cases.size();
  const std::string file = flags.case_file;
  if (n == 0) throw BadInput(file + ": no cases");
  std::size_t point = 0;
  if (given(command, "--point")) {
    if (flags.point < 0 || static_cast<std::size_t>(flags.point) >= n)
      throw BadInput("--point: " + std::to_string(flags.point) + " is out of range (" + file + " has points 0.." +
                     std::to_string(n - 1) + ")");
    point = static_cast<std::size_t>(flags.point);
  } else if (n > 1) {
    throw BadInput("--point: " + file + " has " + std::to_string(n) + " cases; choose one with --point 0.." +
                   std::to_string(n - 1));
  }
  const Case& c = set.cases[point];
  if (auto bad = validate(c)) throw BadInput(file + ": point " + std::to_string(point) + ": " + *bad);
  return {c, point, file};
}

ChosenCase case_from_flags(const CLI::App& command, const CaseFlags& flags) {
  if (given(command, "--point")) throw BadInput("--point: only used with --case-file");
  for (std::string_view flag : {"--scene", "--pulse", "--directivity", "--pi2", "--pi3", "--eps"})
    if (!given(command, flag)) throw BadInput(std::string(flag) + ": required (or give --case-file)");

  Case c;
  c.scene = parsed("--scene", flags.scene, parse_scene(flags.scene), "wall, pair, row3, chain");
  c.pulse = parsed("--pulse", flags.pulse, parse_pulse(flags.pulse), "sine, cosine");
  c.directivity =
      parsed("--directivity", flags.directivity, parse_directivity(flags.directivity), "normal, reverse");
  const std::string scene(name(c.scene));
  const auto body_flags = [&](bool used, std::string_view a, std::string_view b) {
    for (std::string_view flag : {a, b}) {
      if (used && !given(command, flag)) throw BadInput(std::string(flag) + ": required by scene " + scene);
      if (!used && given(command, flag)) throw BadInput(std::string(flag) + ": not used by scene " + scene);
    }
  };
  body_flags(uses_body1(c.scene), "--pi5", "--pi6");
  body_flags(uses_body2(c.scene), "--pi7", "--pi8");
  const bool chain = c.scene == Scene::chain;
  if (chain && !given(command, "--bodies")) throw BadInput("--bodies: required by scene chain");
  for (std::string_view flag : {"--bodies", "--kick"})
    if (!chain && given(command, flag)) throw BadInput(std::string(flag) + ": not used by scene " + scene);

  c.pi2 = flags.pi2;
  c.pi3 = flags.pi3;
  c.eps = flags.eps;
  if (uses_body1(c.scene)) {
    c.pi5 = flags.pi5;
    c.pi6 = flags.pi6;
  }
  if (uses_body2(c.scene)) {
    c.pi7 = flags.pi7;
    c.pi8 = flags.pi8;
  }
  if (chain) {
    c.bodies = flags.bodies;
    c.kick = flags.kick;
  }
  c.xi = flags.xi;
  c.n_free = flags.n_free;
  c.a_p = flags.a_p;
  c.w_p = flags.w_p;
  if (auto bad = validate(c)) throw BadInput(case_flag_message(*bad));
  return {c, 0, {}};
}

}  // namespace

void add_case_flags(CLI::App& command, CaseFlags& f) {
  command.add_option("--scene", f.scene, "Scene: wall, pair, row3 or chain");
  command.add_option("--pulse", f.pulse, "Pulse: sine or cosine");
  command.add_option("--directivity", f.directivity, "Directivity: normal or reverse");
  command.add_option("--pi2", f.pi2, "Pi2 = w0 / w_p");
  command.add_option("--pi3", f.pi3, "Pi3 = delta w_p^2 / a_p (gap)");
  command.add_option("--eps", f.eps, "Coefficient of restitution, in [0, 1]");
  command.add_option("--pi5", f.pi5, "Pi5 = w0 / w1 (pair, row3; chain: the odd bodies)");
  command.add_option("--pi6", f.pi6, "Pi6 = m0 / m1 (pair, row3; chain: the odd bodies)");
  command.add_option("--pi7", f.pi7, "Pi7 = w0 / w2 (row3)");
  command.add_option("--pi8", f.pi8, "Pi8 = m0 / m2 (row3)");
  command.add_option("--bodies", f.bodies, "Chain: number of bodies N, 2 to " + std::to_string(kMaxChainBodies));
  command.add_option("--kick", f.kick, "Chain: start velocity of body 0 (the left end) towards +x, times w_p / a_p")
      ->capture_default_str();
  command.add_option("--xi", f.xi, "Damping ratio of every body")->capture_default_str();
  command.add_option("--n-free", f.n_free, "Free-vibration periods T_max after the pulse")->capture_default_str();
  command.add_option("--a-p", f.a_p, "Pulse amplitude a_p (Pi1 does not depend on it)")->capture_default_str();
  command.add_option("--w-p", f.w_p, "Pulse circular frequency w_p (Pi1 does not depend on it)")
      ->capture_default_str();
  command.add_option("--case-file", f.case_file, "Take the case from a case-set file instead of the flags above");
  command.add_option("--point", f.point, "Which case of --case-file (0-based; needed when it has several)");
}

ChosenCase chosen_case(const CLI::App& command, const CaseFlags& flags) {
  return given(command, "--case-file") ? case_from_file(command, flags) : case_from_flags(command, flags);
}

std::string case_flag_message(const std::string& field_reason) {
  const std::size_t colon = field_reason.find(':');
  if (colon == std::string::npos) return field_reason;
  std::string flag = "--" + field_reason.substr(0, colon);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag + field_reason.substr(colon);
}

}  // namespace pb::app
