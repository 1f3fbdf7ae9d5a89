#include "tests/fuzz/mutator.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>

namespace pb::fuzz {

std::uint64_t Rng::next() {
  // splitmix64 (Steele, Lea, Flood 2014): tiny, and the same numbers everywhere.
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t input_seed(std::uint64_t campaign_seed, std::string_view target, std::uint64_t index) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a over the target's name
  for (char c : target) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  Rng rng(campaign_seed ^ h ^ (index * 0x9e3779b97f4a7c15ULL));
  return rng.next();
}

namespace {

std::string numbers(double from, double to, std::size_t count) {
  std::string out;
  char text[40];
  for (std::size_t i = 0; i < count; ++i) {
    const double t = count > 1 ? static_cast<double>(i) / static_cast<double>(count - 1) : 0.0;
    std::snprintf(text, sizeof text, "%.17g", from + (to - from) * t);
    if (i) out += ", ";
    out += text;
  }
  return out;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += line + '\n';
  return out;
}

// Lines that set a key ("key = value"), the ones a value mutation can aim at.
std::vector<std::size_t> assignments(const std::vector<std::string>& lines) {
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t eq = lines[i].find('=');
    if (eq != std::string::npos && lines[i].rfind('#', 0) != 0) at.push_back(i);
  }
  return at;
}

const std::vector<std::string>& toml_keys() {
  static const std::vector<std::string> keys = {
      // case sets
      "name", "description", "scene", "bodies", "kick", "pulse", "directivity", "eps", "pi2", "pi3", "pi5",
      "pi6", "pi7", "pi8", "symmetric", "xi", "n_free", "a_p", "w_p", "from", "to", "points", "spacing",
      // settings lists
      "solver", "variant", "steps", "wh", "theta", "gamma", "tol_scale", "step_cap", "time_limit", "monitor",
      "reference_tol_scale", "reference_time_limit"};
  return keys;
}

const std::vector<std::string>& headers() {
  static const std::vector<std::string> h = {"[[family]]", "[[run]]", "[defaults]", "[family]", "[[defaults]]",
                                             "[run]",      "[run.x]", "[[family.x]]"};
  return h;
}

}  // namespace

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      if (start < text.size()) lines.emplace_back(text.substr(start));
      break;
    }
    lines.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

void insert_line(std::vector<std::string>& lines, std::size_t where, std::string line) {
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(where), std::move(line));
}

void repeat_line(std::vector<std::string>& lines, std::size_t where, Rng& rng) {
  if (!lines.empty()) insert_line(lines, where, rng.pick(lines));
}

void remove_line(std::vector<std::string>& lines, Rng& rng) {
  if (!lines.empty()) lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(rng.below(lines.size())));
}

void splice_line(std::vector<std::string>& lines, std::size_t where, const std::vector<std::string>& seeds, Rng& rng) {
  const std::vector<std::string> other = split_lines(rng.pick(seeds));
  if (!other.empty()) insert_line(lines, where, rng.pick(other));
}

const std::vector<std::string>& toml_values() {
  static const std::vector<std::string> values = [] {
    std::vector<std::string> v = {
        "\"\"", "0", "-0.0", "-1", "1", "nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "1e-300", "1e100",
        "9223372036854775807", "-9223372036854775808", "1099511627776", "2147483648", "100000", "100001",
        "1e8", "0.5", "true", "false", "[]", "{}", "[[]]", "[1, \"a\"]", "\"wall\"", "\"chain\"", "\"sine\"",
        "\"reverse\"", "\"moreau-jean\"", "\"event-driven\"", "\"nope\"", "1979-05-27", "\"\\u0000\"",
        "{ from = 1, to = 9223372036854775807 }", "{ from = 1, to = 1099511627776 }",
        "{ from = 0, to = 0 }", "{ from = 9223372036854775807, to = 9223372036854775807 }",
        "{ from = 0.1, to = 10, points = 100000, spacing = \"log\" }",
        "{ from = 1e-300, to = 1e308, points = 7, spacing = \"log\" }",
        "{ from = -1, to = 1, points = 3, spacing = \"log\" }",
        "{ from = 1, to = 1, points = 9223372036854775807, spacing = \"linear\" }",
        "{ from = 1, to = 2, points = 1, spacing = \"linear\" }",
        "{ from = 1, to = 2, points = 2, spacing = \"cubic\" }"};
    v.push_back('"' + std::string(100'000, 'x') + '"');
    v.push_back('[' + numbers(0.5, 1.0, 3000) + ']');
    v.push_back('[' + numbers(1, 3000, 3000) + ']');
    return v;
  }();
  return values;
}

const std::vector<std::string>& number_values() {
  static const std::vector<std::string> values = {"",      "0",     "-0",   "-1",   "nan",  "inf",  "-inf",
                                                  "1e308", "-1e308", "1e-320", "1e-300", "1e100", "1e8", "0.5",
                                                  "9223372036854775807", "1099511627776", "2147483648"};
  return values;
}

const std::vector<std::string>& arg_values() {
  static const std::vector<std::string> values = {
      "", "0", "-0", "-1", "1", "2", "0.5", "nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "1e-300", "1e100",
      "1e200", "1e8", "9223372036854775807", "9223372036854775808", "1099511627776", "2147483648", "0x10", "1,2",
      " 1", "x", std::string(5000, 'x'), "-", "--", "wall", "pair", "row3", "chain", "sine", "cosine",
      "reverse", "moreau-jean", "event-driven", "ode", "bullet", "tiny.toml", "tiny-settings.toml", "missing.toml",
      "/", ".", "out.csv", "sub/dir/out.csv", "/dev/null",
      // issue 33: inputs that are not regular files, records, outputs onto inputs, huge steps, engines
      "fifo", "/dev/zero", "tiny.toml.partial", "record", "siconos", "mujoco", "compliant", "external",
      "kelvin-voigt", "newmark", "1e11", "1e293", "rec.at2", "rec.csv"};
  return values;
}

std::string expand_generators(std::string_view text) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t open = text.find('@', at);
    if (open == std::string_view::npos) break;
    const std::size_t paren = text.find('(', open);
    const std::size_t close = text.find(")@", open);
    const std::string_view name = text.substr(open + 1, paren == std::string_view::npos ? 0 : paren - open - 1);
    if (paren == std::string_view::npos || close == std::string_view::npos || (name != "REPEAT" && name != "SEQ")) {
      out += text.substr(at, open + 1 - at);
      at = open + 1;
      continue;
    }
    out += text.substr(at, open - at);
    const std::string args(text.substr(paren + 1, close - paren - 1));
    const std::size_t comma = args.rfind(',');
    if (comma == std::string::npos) throw std::invalid_argument("generator without a count: " + args);
    const auto count = static_cast<std::size_t>(std::stoull(args.substr(comma + 1)));
    if (name == "REPEAT") {
      const std::string piece = args.substr(0, comma);
      out.reserve(out.size() + piece.size() * count);
      for (std::size_t i = 0; i < count; ++i) out += piece;
    } else {
      const std::size_t first = args.find(',');
      out += numbers(std::stod(args.substr(0, first)), std::stod(args.substr(first + 1, comma - first - 1)), count);
    }
    at = close + 2;
  }
  out += text.substr(std::min(at, text.size()));
  return out;
}

std::string mutate_toml(std::string_view seed, const std::vector<std::string>& all_seeds, Rng& rng) {
  std::vector<std::string> lines = split_lines(seed);
  const bool truncate = mutate_lines(lines, rng, [&](std::size_t where) {
    switch (rng.below(10)) {
      case 0:
      case 1:
      case 2: {  // the value of a key replaced by an interesting one (the most useful mutation)
        const std::vector<std::size_t> at = assignments(lines);
        if (at.empty()) break;
        std::string& line = lines[rng.pick(at)];
        line = line.substr(0, line.find('=') + 1) + ' ' + rng.pick(toml_values());
        break;
      }
      case 3: {  // a key added: known (so maybe duplicated or out of place) or a huge unknown one
        const std::string key =
            rng.one_in(4) ? std::string(1 + rng.below(100'000), 'k') : rng.pick(toml_keys());
        insert_line(lines, where, key + " = " + rng.pick(toml_values()));
        break;
      }
      case 4:  // a line duplicated (a duplicate key, or a table header twice)
        repeat_line(lines, where, rng);
        break;
      case 5:  // a line removed (a required key gone)
        remove_line(lines, rng);
        break;
      case 6:  // a line spliced in from another seed (a settings key in a case set, and so on)
        splice_line(lines, where, all_seeds, rng);
        break;
      case 7:  // a table header added
        insert_line(lines, where, rng.pick(headers()));
        break;
      case 8: {  // bytes: one flipped, or a TOML-significant character inserted, or a few deleted
        if (lines.empty()) break;
        std::string& line = lines[rng.below(lines.size())];
        const std::size_t pos = line.empty() ? 0 : rng.below(line.size());
        static constexpr std::string_view kSignificant = "[]{}=\"',.#\\\t -+e_\x7f\xff";
        switch (rng.below(3)) {
          case 0:
            if (!line.empty()) line[pos] = static_cast<char>(line[pos] ^ (1 << rng.below(8)));
            break;
          case 1: line.insert(pos, 1, kSignificant[rng.below(kSignificant.size())]); break;
          default:
            if (!line.empty()) line.erase(pos, 1 + rng.below(8));
        }
        break;
      }
      default:  // cut short, as a half-written file is
        return true;
    }
    return false;
  });
  std::string text = join_lines(lines);
  if (truncate && !text.empty()) text.resize(rng.below(text.size()));
  return text;
}

namespace {

const std::vector<std::string>& known_flags() {
  static const std::vector<std::string> flags = {
      "--scene", "--pulse", "--directivity", "--pi2", "--pi3", "--eps", "--pi5", "--pi6", "--pi7", "--pi8",
      "--bodies", "--kick", "--xi", "--n-free", "--a-p", "--w-p", "--case-file", "--point", "--solver",
      "--variant", "--steps", "--wh", "--theta", "--gamma", "--tol-scale", "--step-cap", "--json", "--history",
      "--samples", "--out", "--points", "--threads", "--settings", "--tolerance", "--same-setting", "--baseline",
      "--help", "--check", "--update",
      // issue 33: records, every solver's settings, the studies' flags
      "--record", "--tp", "--cycles", "--mp-gamma", "--mp-nu", "--stiffness", "--contact", "--integrator",
      "--method", "--rtol", "--contact-steps", "--command", "--lcp", "--projection-tol", "--repetitions",
      "--max-error"};
  return flags;
}

bool is_flag(const std::string& arg) { return arg.size() > 2 && arg.rfind("--", 0) == 0; }

bool is_protected_value(const std::vector<std::string>& args, std::size_t i,
                        const std::vector<std::string>& protected_flags) {
  for (const std::string& flag : protected_flags)
    if (args[i] == flag || (i > 0 && args[i - 1] == flag)) return true;
  return false;
}

}  // namespace

std::vector<std::string> mutate_args(std::vector<std::string> args, const std::vector<std::string>& protected_flags,
                                     Rng& rng) {
  const std::size_t mutations = 1 + rng.below(3);
  for (std::size_t m = 0; m < mutations; ++m) {
    // Index 0 is the subcommand: kept (swapping it mostly tests CLI11, not poundbench).
    std::vector<std::size_t> values, flags;
    for (std::size_t i = 1; i < args.size(); ++i) {
      if (is_protected_value(args, i, protected_flags)) continue;
      (is_flag(args[i]) ? flags : values).push_back(i);
    }
    switch (rng.below(8)) {
      case 0:
      case 1:
      case 2:
      case 3: {  // a value replaced by an interesting one; a number's by an extreme number mostly
        if (values.empty()) break;
        const std::size_t i = rng.pick(values);
        const bool number = args[i].find_first_not_of("0123456789.e-+") == std::string::npos;
        args[i] = number && !rng.one_in(4) ? rng.pick(number_values()) : rng.pick(arg_values());
        break;
      }
      case 4:  // a flag added with an interesting value (or none: then the next word is its value)
        args.push_back(rng.pick(known_flags()));
        if (!rng.one_in(4)) args.push_back(rng.pick(arg_values()));
        break;
      case 5:  // an argument removed
        if (!values.empty() || !flags.empty()) {
          const std::size_t i = rng.one_in(2) && !flags.empty() ? rng.pick(flags)
                                                                : (values.empty() ? rng.pick(flags) : rng.pick(values));
          args.erase(args.begin() + static_cast<std::ptrdiff_t>(i));
        }
        break;
      case 6:  // a flag and its value repeated
        if (!flags.empty()) {
          const std::size_t i = rng.pick(flags);
          args.push_back(args[i]);
          if (i + 1 < args.size() - 1 && !is_flag(args[i + 1])) args.push_back(args[i + 1]);
        }
        break;
      default:  // a flag renamed (a value meant for one flag given to another)
        if (!flags.empty()) args[rng.pick(flags)] = rng.pick(known_flags());
    }
  }
  return args;
}

}  // namespace pb::fuzz
