// Reading case-set files (format: cases/README.md).
//
// A file is read in three passes: TOML syntax (toml++), then every table's keys into
// Entries, one per key (type and shape checks, each value remembering its line), then each
// family's Entries are resolved against [defaults] and expanded into Cases, which pb::validate
// checks. Errors carry the line of the value that caused them, so the value rules stay
// in one place (validate) and this file only maps a field back to where it was written.
//
// A family expands into one Expansion per scene (its axes and their values); a case is
// built from its point's place on those axes (Reader::build), so that load_case_list can
// build each case on demand and hold no list (a million-point set held 320 MB of Cases:
// issue 36). Every case is still built and checked once as the file loads, so a lazy set
// and a held one refuse a file with the same error.
//
// Rejected: letting toml++'s node_view do lookups (it hides which keys were never read,
// so unknown keys would pass silently).

#include "cases/case_set.hpp"

#include "cases/buildings_set.hpp"
#include "cases/fields.hpp"
#include "cases/nearest_name.hpp"
#include "cases/physical.hpp"
#include "cases/record.hpp"
#include "cases/record_scale.hpp"
#include "cases/text.hpp"
#include "cases/toml_input.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

namespace pb {
namespace {

// Every key a family or [defaults] may hold: the scene, pulse and directivity (names), every
// field of a Case as cases/fields.hpp declares it (in its order: numbers, and the record's
// file as text), two keys of the file's own, symmetric and name, and the aliases of fields
// (tp for w_p). A field added to the table is a key here with nothing more.
using Key = int;
constexpr Key kScene = 0, kPulse = 1, kDirectivity = 2, kFirstNumber = 3;
constexpr Key kSymmetric = kFirstNumber + static_cast<Key>(kCaseFields.size());
constexpr Key kName = kSymmetric + 1;
constexpr Key kFirstAlias = kName + 1;
// The physical units (cases/physical.hpp), after the aliases: numbers and axes like the Pi
// terms they replace, never beside them.
constexpr Key kFirstPhysical = kFirstAlias + static_cast<Key>(kCaseAliases.size());
constexpr int kKeyCount = kFirstPhysical + static_cast<Key>(kPhysicalFields.size());

// Limits that keep a typo (points = 2000000) from exhausting memory.
constexpr std::int64_t kMaxGridPoints = 100'000;
constexpr std::size_t kMaxCases = 1'000'000;

constexpr std::size_t index(Key k) { return static_cast<std::size_t>(k); }

// The number a key sets, or nullptr for the names and the file's own keys.
constexpr const CaseField* number_field(Key k) {
  return k >= kFirstNumber && k < kSymmetric ? &kCaseFields[index(k - kFirstNumber)] : nullptr;
}

constexpr const CaseAlias* alias_of(Key k) {
  return k >= kFirstAlias && k < kFirstPhysical ? &kCaseAliases[index(k - kFirstAlias)] : nullptr;
}

constexpr const PhysicalField* physical_of(Key k) {
  return k >= kFirstPhysical && k < kKeyCount ? &kPhysicalFields[index(k - kFirstPhysical)] : nullptr;
}

constexpr std::string_view key_name(Key k) {
  if (const CaseField* f = number_field(k)) return f->name;
  if (const CaseAlias* a = alias_of(k)) return a->name;
  if (const PhysicalField* f = physical_of(k)) return f->name;
  switch (k) {
    case kScene: return "scene";
    case kPulse: return "pulse";
    case kDirectivity: return "directivity";
    case kSymmetric: return "symmetric";
    default: return "name";
  }
}

std::optional<Key> parse_key(std::string_view s) {
  for (Key k = 0; k < kKeyCount; ++k)
    if (key_name(k) == s) return k;
  return std::nullopt;
}

Key key_of(std::string_view s) { return *parse_key(s); }

bool is_choice(Key k) { return k < kFirstNumber; }
bool is_text(Key k) { return number_field(k) != nullptr && number_field(k)->text != nullptr; }
bool is_number(Key k) {
  return (number_field(k) != nullptr && !is_text(k)) || alias_of(k) != nullptr || physical_of(k) != nullptr;
}
// Which scenes use a key: symmetric speaks of body 2, as pi7 and pi8 do.
FieldUse use_of(Key k) {
  if (const CaseField* f = number_field(k)) return f->use;
  if (const PhysicalField* f = physical_of(k)) return f->use;
  return k == kSymmetric ? FieldUse::body2 : FieldUse::every;
}
bool is_body1(Key k) { return use_of(k) == FieldUse::body1; }
bool is_body2(Key k) { return use_of(k) == FieldUse::body2; }
bool is_chain(Key k) { return use_of(k) == FieldUse::chain; }
bool is_pulse_key(Key k) { return pulse_use(use_of(k)); }
bool pulse_uses(FieldUse use, PulseShape p) {
  return (use == FieldUse::makris_c && p == PulseShape::makris_c) || (use == FieldUse::mp && p == PulseShape::mp) ||
         (use == FieldUse::record && p == PulseShape::record);
}
bool has_chain(Scene s) { return s == Scene::chain; }
// Whether a key is given in physical units, and the Pi term a physical family has instead.
bool is_physical(Key k) { return physical_of(k) != nullptr; }
bool replaced_by_physical(Key k) {
  for (const PhysicalField& f : kPhysicalFields)
    if (number_field(k) && f.pi == number_field(k)->name) return true;
  return false;
}

// The order in which a family's lists expand: scene outermost (not listed: it is the outer
// loop), pi2 innermost, so the points of one spectrum are contiguous. A number not listed
// here expands just outside pi2. Changing this order renumbers the points of every case set.
// The keys of one pulse (record, cycles, mp_gamma, mp_nu) are axes only in families of that
// pulse, so placing them after it renumbers no existing set.
constexpr std::array<std::string_view, 19> kExpansionOrder = {
    "bodies", "kick", "pulse", "record", "cycles", "mp_gamma", "mp_nu", "directivity", "eps", "pi3", "pi5", "pi6",
    "pi7", "pi8", "xi", "n_free", "a_p", "w_p", "pi2"};

const std::vector<Key>& expansion_order() {
  static const std::vector<Key> order = [] {
    std::vector<Key> out;
    for (std::string_view n : kExpansionOrder) out.push_back(key_of(n));
    for (Key k = kFirstNumber; k < kSymmetric; ++k)
      if (std::find(out.begin(), out.end(), k) == out.end()) out.insert(out.end() - 1, k);
    // A physical key expands where its Pi term does (t0 innermost, as pi2); a family has
    // one or the other.
    for (Key k = kFirstPhysical; k < kKeyCount; ++k) {
      const std::string_view pi = physical_of(k)->pi;
      const auto at = pi.empty() ? out.end() - 1 : std::find(out.begin(), out.end(), key_of(pi));
      out.insert(at + 1, k);
    }
    return out;
  }();
  return order;
}

// The body-1 number that a symmetric row3 copies into a body-2 number (pi5 into pi7, pi_y1
// into pi_y2): the same place in the table's list of each.
Key body1_twin(Key body2_key) {
  std::vector<Key> ones, twos;
  for (Key k = kFirstNumber; k < kSymmetric; ++k) {
    if (is_body1(k) || use_of(k) == FieldUse::pair_row3) ones.push_back(k);
    if (is_body2(k)) twos.push_back(k);
  }
  const auto at = std::find(twos.begin(), twos.end(), body2_key) - twos.begin();
  return ones.at(static_cast<std::size_t>(at));
}

// The body-1 key a symmetric row3 copies into a physical body-2 key (t2 from t1, m2 from m1,
// uy2 from uy1).
std::string physical_twin(std::string_view body2_name) { return std::string(body2_name.substr(0, body2_name.size() - 1)) + "1"; }

// The bodies a kind of use describes, as a message says it.
std::string bodies_of(FieldUse use) {
  switch (use) {
    case FieldUse::body1: return "body 1 of pair and row3, and the odd bodies of a chain";
    case FieldUse::body2: return "body 2, of row3 only";
    case FieldUse::chain: return "a chain only";
    case FieldUse::not_chain: return "body 0 of wall, pair and row3 (a chain's bodies: pi_y)";
    case FieldUse::pair_row3: return "body 1 of pair and row3 (a chain's bodies: pi_y)";
    default: return "every case";
  }
}

// The keys of one kind of use, as a message lists them: "pi5/pi6".
std::string keys_of(FieldUse use) {
  std::string out;
  for (Key k = 0; k < kKeyCount; ++k)
    if (use_of(k) == use) out += (out.empty() ? "" : "/") + std::string(key_name(k));
  return out;
}

// One key as written: its values (numbers, or enum values for scene/pulse/directivity),
// and the line of the key and of each value so that a later error can point at it.
struct Entry {
  bool given = false;
  std::string field;  // "family[2].pi5" or "defaults.pi5"
  std::uint32_t line = 0;
  enum class Shape { scalar, list, grid } shape = Shape::scalar;
  std::vector<double> values;
  std::vector<int> choices;
  std::vector<std::uint32_t> value_lines;  // parallel to values, choices or texts
  std::vector<std::string> texts;          // a text field's values (the record's file)
  bool flag = false;
  bool builtin = false;  // the built-in default, not given by the file
  std::string text;

  std::size_t size() const { return !texts.empty() ? texts.size() : choices.empty() ? values.size() : choices.size(); }
};
using Entries = std::array<Entry, kKeyCount>;

std::string one_line(std::string_view s) {
  std::string out(s);
  std::replace(out.begin(), out.end(), '\n', ' ');
  return out;
}

// A number as a message shows it (six significant digits).
std::string brief(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

std::string_view type_phrase(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "a list";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::none: break;
  }
  return "nothing";
}

std::optional<double> as_number(const toml::node& n) {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nullopt;
}

std::uint32_t line_of(const toml::node& n) { return n.source().begin.line; }
std::uint32_t line_of(const toml::key& k) { return k.source().begin.line; }

// "unknown key" with a hint: the nearest allowed key when it is close enough to be a typo.
std::string unknown_key_reason(std::string_view key, const std::vector<std::string_view>& allowed) {
  if (key == "pi4") return "unknown key (Pi4 is written eps)";
  if (key == "pi1") return "unknown key (Pi1 is the response a solver computes, not an input)";
  const std::string_view best = nearest_name(key, allowed);
  if (!best.empty()) return "unknown key (did you mean " + std::string(best) + "?)";
  // Runs of three or more numbered keys as a range (pi5..pi8, pi_y0..pi_y2): the list fits
  // the one line of an error with room for the echoed key.
  const auto numbered = [](std::string_view k, std::string_view& stem) {
    const std::size_t digits = k.find_last_not_of("0123456789") + 1;
    stem = k.substr(0, digits);
    return digits < k.size() && digits > 0 ? std::stoi(std::string(k.substr(digits))) : -1;
  };
  std::string list;
  for (std::size_t i = 0; i < allowed.size();) {
    std::string_view stem, next_stem;
    const int n = numbered(allowed[i], stem);
    std::size_t j = i + 1;
    while (n >= 0 && j < allowed.size() && numbered(allowed[j], next_stem) == n + static_cast<int>(j - i) &&
           next_stem == stem)
      ++j;
    list += (list.empty() ? "" : ", ") + std::string(allowed[i]);
    if (j - i >= 3) {
      list += ".." + std::string(allowed[j - 1]);
      i = j;
    } else {
      ++i;
    }
  }
  // Still too long for one line beside the file, the family and the echoed key (clipped to
  // kMaxEchoed): cut at a key at 140 characters, the rest in the docs.
  constexpr std::size_t kMaxList = 140;
  if (list.size() > kMaxList) list = list.substr(0, list.rfind(", ", kMaxList)) + ", ... (cases/README.md)";
  return "unknown key (expected one of " + list + ")";
}

std::string scene_list(const std::vector<int>& scenes) {
  std::string out;
  for (int s : scenes) {
    if (!out.empty()) out += ", ";
    out += name(static_cast<Scene>(s));
  }
  return out;
}

class Reader {
 public:
  explicit Reader(std::string_view file) : file_(file) {}

  [[noreturn]] void fail(std::uint32_t line, std::string_view field, std::string_view reason) const {
    std::string msg = file_;
    if (line > 0) msg += ":" + std::to_string(line);
    msg += ": ";
    if (!field.empty()) msg += std::string(field) + ": ";
    msg += one_line(reason);
    throw CaseSetError(msg);
  }

  // hold: the cases into set.cases; otherwise each is built, checked and dropped, and
  // case_at builds it again on demand.
  CaseSet read(const toml::table& root, bool hold) {
    CaseSet set;
    const toml::node* families = nullptr;
    std::uint32_t families_line = 0;
    const toml::table* defaults_table = nullptr;
    bool has_name = false;
    for (const auto& [key, node] : root) {
      const std::string_view k = key.str();
      if (k == "name" || k == "description") {
        const auto* s = node.as_string();
        if (s == nullptr) fail(line_of(key), k, "must be a string, got " + std::string(type_phrase(node)));
        (k == "name" ? set.name : set.description) = s->get();
        if (k == "name") {
          has_name = true;
          if (set.name.empty()) fail(line_of(key), k, "must not be empty");
        }
      } else if (k == "defaults") {
        defaults_table = node.as_table();
        if (defaults_table == nullptr)
          fail(line_of(key), k, "must be a table ([defaults]), got " + std::string(type_phrase(node)));
      } else if (k == "family") {
        families = &node;
        families_line = line_of(key);
      } else {
        fail(line_of(key), clip(k), unknown_key_reason(k, {"name", "description", "defaults", "family"}));
      }
    }
    if (!has_name) fail(0, "name", "required (the name of the case set)");

    refuse_buildings(families, defaults_table);
    Entries defaults;
    if (defaults_table != nullptr) defaults = read_settings(*defaults_table, "defaults", true);

    if (families == nullptr) fail(0, "family", "no [[family]] tables: a case set needs at least one");
    const toml::array* list = families->as_array();
    if (list == nullptr)
      fail(families_line, "family", "must be an array of tables (write [[family]]), got " +
                                         std::string(type_phrase(*families)));
    if (list->empty()) fail(families_line, "family", "no families: the list is empty");

    std::vector<std::pair<std::string, std::uint32_t>> seen;  // family names and their lines
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::node& node = *list->get(i);
      const std::string prefix = "family[" + std::to_string(i) + "]";
      const toml::table* t = node.as_table();
      if (t == nullptr) fail(line_of(node), prefix, "must be a table, got " + std::string(type_phrase(node)));
      const Entries own = read_settings(*t, prefix, false);
      const Entry& nm = own[index(kName)];
      if (!nm.given) fail(line_of(*t), prefix + ".name", "required (every family is named)");
      for (const auto& [other, other_line] : seen)
        if (other == nm.text)
          fail(nm.line, nm.field, "duplicate family name \"" + clip(nm.text) + "\" (first used at line " +
                                      std::to_string(other_line) + ")");
      seen.emplace_back(nm.text, nm.line);
      expand(resolve(own, defaults, prefix, line_of(*t)), nm.text, hold ? &set.cases : nullptr);
    }
    return set;
  }

  std::size_t size() const { return points_; }

  // A buildings family has keys of its own (cases/buildings_set.hpp) and is solved by `run`
  // alone: named before its keys would read as unknown ones here.
  void refuse_buildings(const toml::node* families, const toml::table* defaults) const {
    std::vector<std::pair<const toml::node*, std::string>> scenes;
    if (defaults) scenes.emplace_back(defaults->get("scene"), "defaults.scene");
    if (const toml::array* list = families ? families->as_array() : nullptr)
      for (std::size_t i = 0; i < list->size(); ++i)
        if (const toml::table* t = list->get(i)->as_table())
          scenes.emplace_back(t->get("scene"), "family[" + std::to_string(i) + "].scene");
    for (const auto& [scene, field] : scenes)
      if (scene && scene->value<std::string>() == kBuildingsScene) fail(line_of(*scene), field, buildings_not_here_reason());
  }

  // Point i of the set, as read() built it (the file was checked then: nothing here fails).
  Case case_at(std::size_t i) const {
    const auto e = std::upper_bound(expansions_.begin(), expansions_.end(), i,
                                    [](std::size_t p, const Expansion& x) { return p < x.first; }) - 1;
    return build(*e, i - e->first, false);
  }

 private:
  // One scene of one family: its axes (expansion_order), the values of each in `eff`, and the
  // points it holds, first .. first + count - 1 of the set.
  struct Expansion {
    std::shared_ptr<const Entries> eff;
    std::string family;
    Scene scene = Scene::pair;
    std::vector<Key> axes;
    bool symmetric = false, physical = false;
    std::size_t first = 0, count = 0;
  };

  std::string file_;
  std::vector<Expansion> expansions_;  // in point order
  std::size_t points_ = 0;
  // The records the file names, by their path (relative to the working directory), read once.
  mutable std::map<std::string, std::shared_ptr<const Record>> records_;

  Entries read_settings(const toml::table& t, const std::string& prefix, bool is_defaults) const {
    Entries out;
    for (const auto& [key, node] : t) {
      const std::string field = prefix + "." + clip(key.str());
      const std::optional<Key> k = parse_key(key.str());
      if (!k || (is_defaults && *k == kName)) {
        if (k) fail(line_of(key), field, "not allowed in [defaults] (each family names itself)");
        std::vector<std::string_view> allowed;
        for (Key a = 0; a < kKeyCount; ++a)
          if (!(is_defaults && a == kName)) allowed.push_back(key_name(a));
        fail(line_of(key), field, unknown_key_reason(key.str(), allowed));
      }
      Entry& s = out[index(*k)];
      s.given = true;
      s.field = field;
      s.line = line_of(key);
      if (is_choice(*k)) read_choices(*k, node, s);
      else if (is_text(*k)) read_records(node, s);
      else if (is_number(*k)) {
        read_numbers(node, s);
        if (number_field(*k) && number_field(*k)->integer) require_whole_numbers(s);
        if (const CaseAlias* alias = alias_of(*k)) convert_alias(*alias, s);
        if (const PhysicalField* physical = physical_of(*k)) refuse_nan(*physical, s);
        // A scaling target's default is NaN, "not given": a NaN value would scale nothing.
        if (const CaseField* f = number_field(*k); f && f->number && std::isnan(f->get(Case{})))
          refuse_nan_target(s);
      }
      else if (*k == kSymmetric) {
        const auto* b = node.as_boolean();
        if (b == nullptr) fail(s.line, field, "must be true or false, got " + std::string(type_phrase(node)));
        s.flag = b->get();
      } else {
        read_family_name(node, s);
      }
    }
    return out;
  }

  // A record's file, or a list of them: each path is taken relative to the case-set file's
  // folder and read here, once per file however many families and points use it.
  void read_records(const toml::node& node, Entry& s) const {
    auto one = [&](const toml::node& n, const std::string& field) {
      const auto* str = n.as_string();
      if (str == nullptr) fail(line_of(n), field, "must be a string (a file), got " + std::string(type_phrase(n)));
      if (str->get().empty()) fail(line_of(n), field, "must not be empty (the record's file)");
      const std::filesystem::path path =
          (std::filesystem::path(file_).parent_path() / std::filesystem::path(str->get())).lexically_normal();
      const std::string key = path.string();
      if (!records_.contains(key)) {
        try {
          records_.emplace(key, read_record(path));
        } catch (const RecordError& e) {
          fail(line_of(n), field, e.what());
        }
      }
      s.texts.push_back(key);
      s.value_lines.push_back(line_of(n));
    };
    if (const auto* arr = node.as_array()) {
      s.shape = Entry::Shape::list;
      if (arr->empty()) fail(s.line, s.field, "empty list: give at least one file");
      for (std::size_t i = 0; i < arr->size(); ++i) one(*arr->get(i), s.field + "[" + std::to_string(i) + "]");
    } else {
      one(node, s.field);
    }
  }

  // NaN is a physical field's "not given" (cases/physical.hpp): `uy0 = nan` ran elastic and
  // `m0 = nan` as 1 kg, as if the key were not there. Refused at its value.
  void refuse_nan_target(const Entry& s) const {
    for (std::size_t i = 0; i < s.values.size(); ++i)
      if (std::isnan(s.values[i]))
        fail(s.value_lines[i], s.field + (s.shape == Entry::Shape::list ? "[" + std::to_string(i) + "]" : ""),
             "must be finite and > 0 (got nan)");
  }

  void refuse_nan(const PhysicalField& physical, const Entry& s) const {
    for (std::size_t i = 0; i < s.values.size(); ++i) {
      if (!std::isnan(s.values[i])) continue;
      std::string field = s.field;
      if (s.shape == Entry::Shape::list) field += "[" + std::to_string(i) + "]";
      fail(s.value_lines[i], field, physical_rule(physical) + " (got nan)");
    }
  }

  // An alias's values become its field's (tp: w_p = 2 pi / tp); each must be finite and > 0.
  void convert_alias(const CaseAlias& alias, Entry& s) const {
    for (std::size_t i = 0; i < s.values.size(); ++i) {
      if (!(std::isfinite(s.values[i]) && s.values[i] > 0.0)) {
        std::string field = s.field;
        if (s.shape == Entry::Shape::list) field += "[" + std::to_string(i) + "]";
        fail(s.value_lines[i], field, "must be finite and > 0 (got " + brief(s.values[i]) + ")");
      }
      s.values[i] = alias.convert(s.values[i]);
    }
    s.text = std::string(alias.field);
  }

  void read_family_name(const toml::node& node, Entry& s) const {
    const auto* str = node.as_string();
    if (str == nullptr) fail(s.line, s.field, "must be a string, got " + std::string(type_phrase(node)));
    s.text = str->get();
    if (s.text.empty()) fail(s.line, s.field, "must not be empty");
    // Family names become labels in result files and file names of reports.
    for (char c : s.text) {
      const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '_' || c == '.';
      if (!ok) fail(s.line, s.field, "may hold only letters, digits, '-', '_' and '.'");
    }
  }

  void read_choices(Key k, const toml::node& node, Entry& s) const {
    auto one = [&](const toml::node& n, const std::string& field) {
      const auto* str = n.as_string();
      if (str == nullptr) fail(line_of(n), field, "must be a string, got " + std::string(type_phrase(n)));
      const std::string_view v = str->get();
      std::optional<int> parsed;
      std::string_view expected;
      if (k == kScene) {
        if (v == kBuildingsScene) fail(line_of(n), field, buildings_not_here_reason());
        if (auto x = parse_scene(v)) parsed = static_cast<int>(*x);
        expected = "wall, pair, row3 or chain";
      } else if (k == kPulse) {
        if (auto x = parse_pulse(v)) parsed = static_cast<int>(*x);
        expected = "sine, cosine, makris-a, makris-b, makris-c, mp or record";
      } else {
        if (auto x = parse_directivity(v)) parsed = static_cast<int>(*x);
        expected = "normal or reverse";
      }
      if (!parsed)
        fail(line_of(n), field, "unknown " + std::string(key_name(k)) + " \"" + clip(v) +
                                    "\" (expected " + std::string(expected) + ")");
      s.choices.push_back(*parsed);
      s.value_lines.push_back(line_of(n));
    };
    if (const auto* arr = node.as_array()) {
      s.shape = Entry::Shape::list;
      if (arr->empty()) fail(s.line, s.field, "empty list: give at least one value");
      for (std::size_t i = 0; i < arr->size(); ++i)
        one(*arr->get(i), s.field + "[" + std::to_string(i) + "]");
    } else if (node.is_string()) {
      one(node, s.field);
    } else {
      fail(s.line, s.field, "must be a string or a list of strings, got " + std::string(type_phrase(node)));
    }
  }

  void read_numbers(const toml::node& node, Entry& s) const {
    if (auto x = as_number(node)) {
      s.values.push_back(*x);
      s.value_lines.push_back(line_of(node));
    } else if (const auto* arr = node.as_array()) {
      s.shape = Entry::Shape::list;
      if (arr->empty()) fail(s.line, s.field, "empty list: give at least one value");
      for (std::size_t i = 0; i < arr->size(); ++i) {
        const toml::node& n = *arr->get(i);
        const auto v = as_number(n);
        if (!v)
          fail(line_of(n), s.field + "[" + std::to_string(i) + "]",
               "must be a number, got " + std::string(type_phrase(n)));
        s.values.push_back(*v);
        s.value_lines.push_back(line_of(n));
      }
    } else if (const auto* grid = node.as_table()) {
      s.shape = Entry::Shape::grid;
      read_grid(*grid, s);
    } else {
      fail(s.line, s.field,
           "must be a number, a list of numbers or a grid { from, to, points, spacing }, got " +
               std::string(type_phrase(node)));
    }
  }

  // A body count is a number like the others (a list, or a linear grid with a whole step),
  // but every value it takes must be a whole number.
  void require_whole_numbers(const Entry& s) const {
    for (std::size_t i = 0; i < s.values.size(); ++i) {
      if (s.values[i] == std::floor(s.values[i])) continue;
      std::string field = s.field;
      if (s.shape == Entry::Shape::list) field += "[" + std::to_string(i) + "]";
      fail(s.value_lines[i], field, "must be a whole number (got " + brief(s.values[i]) + ")");
    }
  }

  // { from = a, to = b, points = n, spacing = "log" | "linear" }. Both ends are exact;
  // a log grid has a constant ratio between neighbours.
  void read_grid(const toml::table& grid, Entry& s) const {
    std::optional<double> from, to;
    std::optional<std::int64_t> points;
    std::optional<bool> log;
    for (const auto& [key, node] : grid) {
      const std::string field = s.field + "." + clip(key.str());
      const std::string_view k = key.str();
      if (k == "from" || k == "to") {
        const auto v = as_number(node);
        if (!v) fail(line_of(key), field, "must be a number, got " + std::string(type_phrase(node)));
        if (!std::isfinite(*v)) fail(line_of(key), field, "must be finite");
        (k == "from" ? from : to) = *v;
      } else if (k == "points") {
        const auto* i = node.as_integer();
        if (i == nullptr) fail(line_of(key), field, "must be an integer, got " + std::string(type_phrase(node)));
        if (i->get() < 1) fail(line_of(key), field, "must be >= 1 (an empty grid)");
        if (i->get() > kMaxGridPoints)
          fail(line_of(key), field, "must be <= " + std::to_string(kMaxGridPoints));
        points = i->get();
      } else if (k == "spacing") {
        const auto* str = node.as_string();
        if (str == nullptr) fail(line_of(key), field, "must be a string, got " + std::string(type_phrase(node)));
        if (str->get() != "log" && str->get() != "linear")
          fail(line_of(key), field, "must be \"log\" or \"linear\", got \"" + clip(str->get()) + "\"");
        log = str->get() == "log";
      } else {
        fail(line_of(key), field, unknown_key_reason(k, {"from", "to", "points", "spacing"}));
      }
    }
    const std::uint32_t line = line_of(grid);
    if (!from) fail(line, s.field + ".from", "required in a grid");
    if (!to) fail(line, s.field + ".to", "required in a grid");
    if (!points) fail(line, s.field + ".points", "required in a grid");
    if (!log) fail(line, s.field + ".spacing", "required in a grid (\"log\" or \"linear\")");
    if (*log && (*from <= 0.0 || *to <= 0.0))
      fail(line, s.field, "a log grid needs from > 0 and to > 0");
    if (*points == 1 && *from != *to) fail(line, s.field, "a grid of 1 point needs from == to");

    const auto n = static_cast<std::size_t>(*points);
    s.values.resize(n);
    s.value_lines.assign(n, line);
    const double a = *log ? std::log(*from) : *from;
    const double b = *log ? std::log(*to) : *to;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = n == 1 ? a : a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1);
      s.values[i] = *log ? std::exp(x) : x;
    }
    s.values.front() = *from;
    s.values.back() = *to;
  }

  // The family's own keys, else [defaults], else the built-in defaults; and the rules on
  // which keys a family's scenes need.
  Entries resolve(const Entries& own, const Entries& defaults, const std::string& prefix,
                  std::uint32_t line) const {
    Entries eff = merged(own, defaults, prefix, line);
    const bool physical = resolve_physical(own, eff, prefix, line);
    require_every_scene_keys(eff, prefix, line, physical);
    const std::vector<int>& scenes = eff[index(kScene)].choices;
    drop_keys_of_absent_bodies(own, eff, scenes);
    require_chain_keys(eff, scenes, prefix, line);
    resolve_pulse_keys(own, eff, prefix, line, physical);
    apply_symmetry(own, eff);
    require_body_keys(eff, scenes, prefix, line, physical);
    return eff;
  }

  // Each key from the family's own table, else [defaults], else its built-in default; an
  // alias given as its field.
  Entries merged(const Entries& own, const Entries& defaults, const std::string& prefix, std::uint32_t line) const {
    auto builtin = [&](Key k, double v) {
      Entry s;
      s.given = true;
      s.builtin = true;
      s.field = prefix + "." + std::string(key_name(k));
      s.line = line;
      s.values = {v};
      s.value_lines = {line};
      return s;
    };
    Entries eff;
    for (Key k = kFirstNumber; k < kSymmetric; ++k)
      if (!number_field(k)->required) eff[index(k)] = builtin(k, number_field(k)->get(Case{}));
    for (int i = 0; i < kKeyCount; ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (own[u].given) eff[u] = own[u];
      else if (defaults[u].given) eff[u] = defaults[u];
    }
    // An alias gives its field: the family's own (either way) before [defaults]'s, and never
    // both in one table. It is no axis itself.
    for (Key a = kFirstAlias; a < kFirstPhysical; ++a) {
      const Key f = key_of(alias_of(a)->field);
      for (const Entries* table : {&own, &defaults})
        if ((*table)[index(a)].given && (*table)[index(f)].given)
          fail((*table)[index(a)].line, (*table)[index(a)].field,
               "not with " + std::string(key_name(f)) + " (line " + std::to_string((*table)[index(f)].line) +
                   "): give one of them");
      if (own[index(a)].given) eff[index(f)] = own[index(a)];
      else if (!own[index(f)].given && defaults[index(a)].given) eff[index(f)] = defaults[index(a)];
      eff[index(a)] = Entry{};
    }
    return eff;
  }

  // A family in physical units (cases/physical.hpp): never beside the Pi terms they give.
  // Whether it is one.
  bool resolve_physical(const Entries& own, Entries& eff, const std::string& prefix, std::uint32_t line) const {
    const Entry* physical = nullptr;
    for (Key k = kFirstPhysical; k < kKeyCount && !physical; ++k)
      if (eff[index(k)].given) physical = &eff[index(k)];
    if (!physical) return false;
    // A family's own Pi term is a mistake; a default one serves the families in Pi terms.
    for (Key k = kFirstNumber; k < kSymmetric; ++k) {
      if (!replaced_by_physical(k)) continue;
      if (own[index(k)].given)
        fail(own[index(k)].line, own[index(k)].field,
             "not with " + physical->field + " (line " + std::to_string(physical->line) +
                 "): a family is given in Pi terms or in physical units, not both");
      eff[index(k)] = Entry{};
    }
    for (std::string_view key : {"t0", "gap"})
      if (!eff[index(key_of(key))].given)
        fail(line, prefix + "." + std::string(key), "required by a family in physical units");
    return true;
  }

  // The choices, and the numbers every scene needs that have no default.
  void require_every_scene_keys(const Entries& eff, const std::string& prefix, std::uint32_t line,
                                bool physical) const {
    for (Key k = 0; k < kSymmetric; ++k) {
      const bool required = is_choice(k) || (number_field(k)->required && use_of(k) == FieldUse::every);
      if (!required || eff[index(k)].given || (physical && replaced_by_physical(k))) continue;
      const std::string field = prefix + "." + std::string(key_name(k));
      if (key_name(k) == "eps") fail(line, field, "required (the coefficient of restitution is always stated)");
      fail(line, field, "required");
    }
  }

  // A family's own key for a body its scenes lack is a mistake; a default for it is
  // merely not needed here, since [defaults] serves families of every scene.
  void drop_keys_of_absent_bodies(const Entries& own, Entries& eff, const std::vector<int>& scenes) const {
    const std::string used_by = "not used by scene" + std::string(scenes.size() > 1 ? "s " : " ") +
                                scene_list(scenes);
    for (Key k = kFirstNumber; k < kKeyCount; ++k) {
      if (k >= kName && !is_physical(k)) continue;
      if (use_of(k) == FieldUse::every || is_pulse_key(k)) continue;
      const bool used = std::any_of(scenes.begin(), scenes.end(),
                                    [&](int s) { return scene_uses(use_of(k), static_cast<Scene>(s)); });
      if (used) continue;
      const Entry& o = own[index(k)];
      if (o.given) fail(o.line, o.field, used_by + " (" + keys_of(use_of(k)) + " describe " + bodies_of(use_of(k)) + ")");
      eff[index(k)] = Entry{};
    }
  }

  void require_chain_keys(const Entries& eff, const std::vector<int>& scenes, const std::string& prefix,
                          std::uint32_t line) const {
    const bool chain = std::any_of(scenes.begin(), scenes.end(),
                                   [](int s) { return has_chain(static_cast<Scene>(s)); });
    for (Key k = kFirstNumber; k < kSymmetric; ++k)
      if (chain && is_chain(k) && number_field(k)->required && !eff[index(k)].given)
        fail(line, prefix + "." + std::string(key_name(k)), "required by scene chain (" +
                                                                std::string(number_field(k)->help) + ")");
  }

  // symmetric = true sets body 2's keys from body 1's: the family's own are a mistake.
  void apply_symmetry(const Entries& own, Entries& eff) const {
    const Entry& sym = eff[index(kSymmetric)];
    if (!(sym.given && sym.flag)) return;
    for (Key k = kFirstNumber; k < kKeyCount; ++k) {
      if (!is_body2(k) || (k >= kSymmetric && !is_physical(k))) continue;
      const Entry& o = own[index(k)];
      if (o.given)
        fail(o.line, o.field,
             "not allowed with symmetric = true (line " + std::to_string(sym.line) + "), which sets " +
                 std::string(is_physical(k) ? physical_of(k)->name : key_name(k)) + " = " +
                 (is_physical(k) ? physical_twin(physical_of(k)->name)
                                 : std::string(key_name(body1_twin(k)))));
      eff[index(k)] = Entry{};  // a default gives way to the family's symmetry
    }
  }

  // The required keys of the bodies the scenes have (body 2's not with symmetric = true).
  void require_body_keys(const Entries& eff, const std::vector<int>& scenes, const std::string& prefix,
                         std::uint32_t line, bool physical) const {
    const bool body1 = std::any_of(scenes.begin(), scenes.end(),
                                   [](int s) { return uses_body1(static_cast<Scene>(s)); });
    const bool body2 = std::any_of(scenes.begin(), scenes.end(),
                                   [](int s) { return uses_body2(static_cast<Scene>(s)); });
    const Entry& sym = eff[index(kSymmetric)];
    for (Key k = kFirstNumber; k < kKeyCount; ++k) {
      if (k >= kSymmetric && !is_physical(k)) continue;
      // In physical units the periods are required, the masses default to m0.
      const bool required = is_physical(k) ? physical && (physical_of(k)->name == "t1" || physical_of(k)->name == "t2")
                                           : number_field(k)->required && !physical;
      if (!(is_body1(k) || is_body2(k)) || !required) continue;
      const bool needed = is_body1(k) ? body1 : body2 && !(sym.given && sym.flag);
      if (!needed || eff[index(k)].given) continue;
      std::vector<int> users;
      for (int s : scenes)
        if (is_body1(k) ? uses_body1(static_cast<Scene>(s)) : uses_body2(static_cast<Scene>(s)))
          users.push_back(s);
      fail(line, prefix + "." + std::string(key_name(k)),
           "required by scene " + scene_list(users) + (is_body2(k) ? " (or set symmetric = true)" : ""));
    }
  }

  // The keys of one pulse (record, cycles, mp_gamma, mp_nu): a family's pulses all use each
  // of them or none (else a pulse that does not would repeat its cases for each value); one
  // that a family's pulses need is required; a default that they do not use is left out.
  void resolve_pulse_keys(const Entries& own, Entries& eff, const std::string& prefix, std::uint32_t line,
                          bool physical) const {
    const std::vector<int>& pulses = eff[index(kPulse)].choices;
    auto list = [](const std::vector<PulseShape>& ps) {
      std::string out;
      for (PulseShape p : ps) out += (out.empty() ? "" : ", ") + std::string(name(p));
      return out;
    };
    for (Key k = kFirstNumber; k < kSymmetric; ++k) {
      if (!is_pulse_key(k)) continue;
      std::vector<PulseShape> users, others;
      for (int p : pulses) (pulse_uses(use_of(k), static_cast<PulseShape>(p)) ? users : others).push_back(static_cast<PulseShape>(p));
      const std::string field = prefix + "." + std::string(key_name(k));
      const Entry& o = own[index(k)];
      if (users.empty()) {
        if (o.given) fail(o.line, o.field, "not used by pulse " + list(others));
        eff[index(k)] = Entry{};
        continue;
      }
      if (!others.empty() && eff[index(k)].given)
        fail(o.given ? o.line : line, o.given ? o.field : field,
             "used by pulse " + list(users) + " but not by " + list(others) + ": give each its own family");
      if (!eff[index(k)].given && number_field(k)->required)
        fail(line, field, "required by pulse " + list(users) + " (" + std::string(number_field(k)->help) + ")");
    }
    // In physical units a record's w_p defaults to its mean frequency (expand); a pulse's a_p
    // and period are the load itself.
    const bool other = std::any_of(pulses.begin(), pulses.end(),
                                   [](int p) { return static_cast<PulseShape>(p) != PulseShape::record; });
    if (physical && other)
      for (std::string_view key : {"a_p", "w_p"})
        if (eff[index(key_of(key))].builtin)
          fail(line, prefix + "." + std::string(key),
               "required by a family in physical units (the pulse's a_p in m/s^2, and w_p or tp in s)");
    // A record's a_p in physical units would be only its Pi terms' unit, and a user who gave
    // it believing it scaled the record got the record as recorded: the scalings are named.
    const bool recorded = std::any_of(pulses.begin(), pulses.end(),
                                      [](int p) { return static_cast<PulseShape>(p) == PulseShape::record; });
    if (const Entry& a_p = eff[index(key_of("a_p"))]; physical && recorded && a_p.given && !a_p.builtin)
      fail(a_p.line, a_p.field, record_a_p_reason(false));
  }

  // The cartesian product, in Key order (scene outermost, pi2 innermost). Keys a scene
  // does not use are left out of its product, so mixing scenes in one family does not
  // repeat cases. Each case is built and checked here; `out`, when given, keeps them.
  void expand(Entries resolved, const std::string& family, std::vector<Case>* out) {
    const auto eff_ptr = std::make_shared<const Entries>(std::move(resolved));
    const Entries& eff = *eff_ptr;
    const bool symmetric = eff[index(kSymmetric)].given && eff[index(kSymmetric)].flag;
    bool physical = false;
    for (Key k = kFirstPhysical; k < kKeyCount; ++k) physical = physical || eff[index(k)].given;
    for (int scene_value : eff[index(kScene)].choices) {
      Expansion e{eff_ptr, family, static_cast<Scene>(scene_value), {}, symmetric, physical, points_, 1};
      for (Key k : expansion_order()) {
        if (!is_pulse_key(k) && !scene_uses(use_of(k), e.scene)) continue;
        if (is_body2(k) && symmetric) continue;
        if (!eff[index(k)].given) continue;  // a pulse's key for other pulses, a Pi term in physical units
        e.axes.push_back(k);
      }
      for (Key k : e.axes) {
        e.count *= eff[index(k)].size();
        if (e.count + points_ > kMaxCases)
          fail(eff[index(kScene)].line, "family \"" + clip(family) + "\"",
               "expands to more than " + std::to_string(kMaxCases) + " cases in this file");
      }

      // Room for the family at once (and at least doubled, for a set of many families): grown
      // point by point, a 1e6-point family's vector (320 bytes a Case) was copied 20 times, and
      // 1,048,576 of them were held.
      if (out && out->capacity() < out->size() + e.count)
        out->reserve(std::max(out->size() + e.count, 2 * out->capacity()));
      for (std::size_t n = 0; n < e.count; ++n) {
        Case c = build(e, n, true);
        if (out) out->push_back(std::move(c));
      }
      points_ += e.count;
      expansions_.push_back(std::move(e));
    }
  }

  // Case n of an expansion: its place on each axis (the last axis turns fastest), then what
  // the values imply (a record's defaults, the Pi terms of physical units). check: validate
  // it, failing at the value that made it invalid.
  Case build(const Expansion& e, std::size_t n, bool check) const {
    const Entries& eff = *e.eff;
    std::vector<std::size_t> at(e.axes.size(), 0);
    for (std::size_t a = e.axes.size(); a-- > 0;) {
      const std::size_t size = eff[index(e.axes[a])].size();
      at[a] = n % size;
      n /= size;
    }
    Case c;
    c.family = e.family;
    c.scene = e.scene;
    for (std::size_t a = 0; a < e.axes.size(); ++a) set(c, e.axes[a], eff[index(e.axes[a])], at[a]);
    if (e.symmetric && uses_body2(e.scene))
      for (Key k = kFirstNumber; k < kSymmetric; ++k)
        if (is_body2(k)) c.*(number_field(k)->number) = c.*(number_field(body1_twin(k))->number);
    // A record scaled (cases/record_scale.hpp) before its defaults: its a_p defaults to its
    // (scaled) peak (cases/README.md, "Records"), and its w_p to its mean frequency 2 pi / T_m.
    if (auto bad = scale_record(c)) report_invalid(*bad, eff, e.axes, at, e.symmetric);
    if (c.pulse == PulseShape::record && c.samples && eff[index(key_of("a_p"))].builtin) c.a_p = c.samples->peak;
    if (c.pulse == PulseShape::record && c.samples && eff[index(key_of("w_p"))].builtin) {
      if (!std::isfinite(c.samples->t_m)) report_record(eff, e.axes, at, no_mean_period_reason());
      c.w_p = c.samples->mean_frequency();
    }
    if (e.physical) to_pi_terms(c, eff, e.axes, at, e.symmetric);
    if (check)
      if (auto bad = validate(c)) report_invalid(physical_reason(c, *bad), eff, e.axes, at, e.symmetric);
    return c;
  }

  // A case in physical units: its Pi terms, in the unit of a record's mean frequency unless
  // w_p (or tp) is given.
  void to_pi_terms(Case& c, const Entries& eff, const std::vector<Key>& axes, const std::vector<std::size_t>& at,
                   bool symmetric) const {
    if (symmetric && uses_body2(c.scene)) {
      c.physical.t2 = c.physical.t1;
      c.physical.m2 = c.physical.m1;
      c.physical.uy2 = c.physical.uy1;
    }
    if (c.pulse == PulseShape::record && eff[index(key_of("w_p"))].builtin) {
      c.w_p = default_w_p(c);
      if (!std::isfinite(c.w_p))
        fail(eff[index(key_of("t0"))].line, eff[index(key_of("t0"))].field,
             "record " + clip(c.record) + " has no mean period (no Fourier amplitude in 0.25-20 Hz): give w_p or tp");
    }
    if (auto bad = apply_physical(c)) report_invalid(*bad, eff, axes, at, symmetric);
  }

  void set(Case& c, Key k, const Entry& s, std::size_t i) const {
    if (const PhysicalField* p = physical_of(k)) c.physical.*(p->member) = s.values[i];
    else if (k == kPulse) c.pulse = static_cast<PulseShape>(s.choices[i]);
    else if (is_text(k)) {
      c.*(number_field(k)->text) = s.texts[i];
      c.samples = records_.at(s.texts[i]);
    }
    else if (k == kDirectivity) c.directivity = static_cast<Directivity>(s.choices[i]);
    else if (const CaseField* f = number_field(k)) {
      // Clamped so that a huge count stays an int; validate() then rejects it by its value.
      if (f->integer) c.*(f->integer) = static_cast<int>(std::clamp(s.values[i], -1e9, 1e9));
      else c.*(f->number) = s.values[i];
    }
  }

  // A reason about this case's record, at the value of the record key that named it.
  [[noreturn]] void report_record(const Entries& eff, const std::vector<Key>& axes, const std::vector<std::size_t>& at,
                                  const std::string& reason) const {
    for (std::size_t a = 0; a < axes.size(); ++a) {
      if (!is_text(axes[a])) continue;
      const Entry& s = eff[index(axes[a])];
      const std::string field = s.field + (s.shape == Entry::Shape::list ? "[" + std::to_string(at[a]) + "]" : "");
      fail(s.value_lines[at[a]], field, clip(s.texts[at[a]]) + ": " + reason);
    }
    fail(0, "", reason);
  }

  // validate() names the bad field; point at the value of that field that this case used.
  [[noreturn]] void report_invalid(const std::string& bad, const Entries& eff, const std::vector<Key>& axes,
                                   const std::vector<std::size_t>& at, bool symmetric) const {
    const std::size_t colon = bad.find(':');
    const std::string reason = colon == std::string::npos ? bad : bad.substr(colon + 1);
    std::optional<Key> k = parse_key(bad.substr(0, colon));
    if (k && symmetric && is_body2(*k)) k = is_physical(*k) ? key_of(physical_twin(physical_of(*k)->name)) : body1_twin(*k);
    const auto pos = k ? std::find(axes.begin(), axes.end(), *k) : axes.end();
    if (pos == axes.end()) fail(0, "", bad);  // validate checked a field this file does not set
    const Entry& s = eff[index(*k)];
    const auto i = static_cast<std::size_t>(at[static_cast<std::size_t>(pos - axes.begin())]);
    std::string field = s.field;
    if (s.shape == Entry::Shape::list) field += "[" + std::to_string(i) + "]";
    const std::size_t start = reason.find_first_not_of(' ');
    std::string text = start == std::string::npos ? reason : reason.substr(start);
    text += " (got " + (s.texts.empty() ? brief(s.values[i]) : "\"" + clip(s.texts[i]) + "\"") + ")";
    fail(s.value_lines[i], field, text);
  }
};

}  // namespace

CaseSet parse_case_set(std::string_view toml_text, std::string_view source_name) {
  return Reader(source_name).read(parse_toml<CaseSetError>(toml_text, source_name), true);
}

CaseSet load_case_set(const std::filesystem::path& file) {
  return parse_case_set(read_input_file<CaseSetError>(file), file.string());
}

CaseListSet parse_case_list(std::string_view toml_text, std::string_view source_name) {
  const auto reader = std::make_shared<Reader>(source_name);
  CaseSet read = reader->read(parse_toml<CaseSetError>(toml_text, source_name), false);
  return {std::move(read.name), std::move(read.description),
          CaseList(reader->size(), [reader](std::size_t i) { return reader->case_at(i); })};
}

CaseListSet load_case_list(const std::filesystem::path& file) {
  return parse_case_list(read_input_file<CaseSetError>(file), file.string());
}

}  // namespace pb
