// Reading the buildings scene's case-set families (format: cases/README.md, "Buildings").
//
// A family's keys (its own, else [defaults]'s) are read into Axes: a key's values, each with
// the field and line it was written at, so that a point's bad value is named where it was
// written. A family expands into the cartesian product of its axes in kAxisOrder (pi2
// innermost, as the single oscillators' families expand), and every point is built into a
// BuildingScene and validated as the file loads.
//
// Rejected: sharing case_set.cpp's Reader. Its keys are the Case's fields (cases/fields.hpp),
// its points Cases; a building is a list of floors, which no Case field holds, and the scene
// is solved by its own reference with its own results.

#include "cases/buildings_set.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>

#include "cases/case_set.hpp"
#include "cases/input_file.hpp"
#include "cases/load.hpp"
#include "cases/nearest_name.hpp"
#include "cases/record.hpp"
#include "cases/text.hpp"
#include "cases/toml_input.hpp"

namespace pb {

namespace {

// The keys of both forms, those of the floor-by-floor form and those of the Pi-term form.
constexpr std::array<std::string_view, 16> kCommonKeys = {
    "name", "scene", "damping", "xi", "eps", "pulse", "record", "a_p", "w_p", "tp", "directivity",
    "cycles", "mp_gamma", "mp_nu", "contact_floors", "n_free"};
constexpr std::array<std::string_view, 3> kFloorKeys = {"buildings", "gap", "t_end"};
constexpr std::array<std::string_view, 5> kPiKeys = {"storeys", "pi2", "pi3", "pi5", "pi6"};

// The order in which a family's lists expand, outermost first (pi2 innermost: the points of
// one spectrum are contiguous).
constexpr std::array<std::string_view, 18> kAxisOrder = {
    "storeys", "damping", "pulse", "record", "cycles", "mp_gamma", "mp_nu", "directivity", "eps",
    "gap", "pi3", "pi5", "pi6", "xi", "n_free", "a_p", "w_p", "pi2"};

constexpr std::size_t kMaxPoints = 100'000;

template <std::size_t N>
bool key_in(const std::array<std::string_view, N>& keys, std::string_view k) {
  return std::find(keys.begin(), keys.end(), k) != keys.end();
}

std::uint32_t node_line(const toml::node& n) { return n.source().begin.line; }

std::string short_number(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

std::string_view node_kind(const toml::node& n) {
  if (n.is_string()) return "a string";
  if (n.is_integer()) return "an integer";
  if (n.is_floating_point()) return "a float";
  if (n.is_boolean()) return "a boolean";
  if (n.is_table()) return "a table";
  if (n.is_array()) return "a list";
  return "a date or time";
}

std::optional<double> number_of(const toml::node& n) {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nullopt;
}

// One value of a key as written: a number, a name or a file, or storey counts.
struct Item {
  double x = 0.0;
  std::string text;
  std::vector<int> counts;
  std::string field;  // "family[0].pi2[3]"
  std::uint32_t line = 0;
};
using Axis = std::vector<Item>;

// A key of a family as written (its own table's, else [defaults]'s).
struct Given {
  const toml::node* node = nullptr;
  std::string field;
  std::uint32_t line = 0;
};

class BuildingsReader {
 public:
  explicit BuildingsReader(std::string_view file) : file_(file) {}

  [[noreturn]] void fail(std::uint32_t line, std::string_view field, std::string_view reason) const {
    std::string msg = file_;
    if (line > 0) msg += ":" + std::to_string(line);
    msg += ": ";
    if (!field.empty()) msg += std::string(field) + ": ";
    std::string r(reason);
    std::replace(r.begin(), r.end(), '\n', ' ');
    throw CaseSetError(msg + r);
  }

  // Every family of the file, given that one of them is of the buildings scene.
  BuildingsSet read(const toml::table& root, const toml::array& families) {
    BuildingsSet set;
    const toml::table* defaults = nullptr;
    for (const auto& [key, node] : root) {
      if (key.str() == "name" || key.str() == "description") {
        const auto* s = node.as_string();
        if (s == nullptr) fail(key.source().begin.line, key.str(), "must be a string, got " + std::string(node_kind(node)));
        (key.str() == "name" ? set.name : set.description) = s->get();
      } else if (key.str() == "defaults") {
        defaults = node.as_table();
        if (defaults == nullptr) fail(key.source().begin.line, "defaults", "must be a table ([defaults])");
      } else if (key.str() != "family") {
        fail(key.source().begin.line, clip(key.str()), "unknown key (expected name, description, defaults or family)");
      }
    }
    if (set.name.empty()) fail(0, "name", "required (the name of the case set), and not empty");
    if (defaults) check_keys(*defaults, "defaults", true);
    std::vector<std::string> names;
    for (std::size_t i = 0; i < families.size(); ++i) {
      const std::string prefix = "family[" + std::to_string(i) + "]";
      const toml::table* t = families.get(i)->as_table();
      if (t == nullptr) fail(node_line(*families.get(i)), prefix, "must be a table");
      check_scene(*t, defaults, prefix);
      check_keys(*t, prefix, false);
      const std::string name = family_name(*t, prefix);
      if (std::find(names.begin(), names.end(), name) != names.end())
        fail(node_line(*t), prefix + ".name", "duplicate family name \"" + clip(name) + "\"");
      names.push_back(name);
      expand(*t, defaults, prefix, name, set.points);
    }
    return set;
  }

 private:
  std::string file_;
  std::map<std::string, std::shared_ptr<const Record>> records_;

  // Every family of a buildings file is of the scene: one point numbering, and the sweeps
  // that read the single oscillators' files solve no buildings yet.
  void check_scene(const toml::table& t, const toml::table* defaults, const std::string& prefix) const {
    const Given g = given(t, defaults, prefix, "scene");
    if (g.node == nullptr) fail(node_line(t), prefix + ".scene", "required (\"buildings\" in a file of buildings families)");
    const auto* s = g.node->as_string();
    if (s == nullptr || s->get() != kBuildingsScene)
      fail(g.line, g.field,
           "must be \"buildings\" in a file of buildings families (a case set holds the buildings scene or the "
           "single oscillators' scenes, not both)");
  }

  void check_keys(const toml::table& t, const std::string& prefix, bool is_defaults) const {
    std::vector<std::string_view> allowed;
    for (auto keys : {std::span<const std::string_view>(kCommonKeys), std::span<const std::string_view>(kFloorKeys),
                      std::span<const std::string_view>(kPiKeys)})
      for (std::string_view k : keys)
        if (!(is_defaults && k == "name")) allowed.push_back(k);
    for (const auto& [key, node] : t) {
      const std::string_view k = key.str();
      if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
      const std::string field = prefix + "." + clip(k);
      if (is_defaults && k == "name") fail(key.source().begin.line, field, "not allowed in [defaults] (each family names itself)");
      const std::string_view best = nearest_name(k, allowed);
      if (!best.empty()) fail(key.source().begin.line, field, "unknown key (did you mean " + std::string(best) + "?)");
      fail(key.source().begin.line, field,
           "unknown key of the buildings scene (floor by floor: buildings, gap, t_end; Pi terms: storeys, pi2, pi3, "
           "pi5, pi6; either: damping, xi, eps, pulse, a_p, w_p or tp, directivity, contact_floors, n_free; "
           "cases/README.md)");
    }
  }

  std::string family_name(const toml::table& t, const std::string& prefix) const {
    const toml::node* n = t.get("name");
    if (n == nullptr) fail(node_line(t), prefix + ".name", "required (every family is named)");
    const auto* s = n->as_string();
    if (s == nullptr || s->get().empty()) fail(node_line(*n), prefix + ".name", "must be a string, not empty");
    for (char c : s->get())
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.'))
        fail(node_line(*n), prefix + ".name", "may hold only letters, digits, '-', '_' and '.'");
    return s->get();
  }

  // The key from the family's table, else from [defaults].
  Given given(const toml::table& own, const toml::table* defaults, const std::string& prefix, std::string_view key) const {
    if (const toml::node* n = own.get(key)) return {n, prefix + "." + std::string(key), node_line(*n)};
    if (defaults)
      if (const toml::node* n = defaults->get(key)) return {n, "defaults." + std::string(key), node_line(*n)};
    return {};
  }

  // A number, a list of numbers or a grid { from, to, points, spacing }.
  Axis numbers(const Given& g) const {
    Axis out;
    auto one = [&](const toml::node& n, const std::string& field) {
      const auto v = number_of(n);
      if (!v) fail(node_line(n), field, "must be a number, got " + std::string(node_kind(n)));
      out.push_back({*v, {}, {}, field, node_line(n)});
    };
    if (const auto* arr = g.node->as_array()) {
      if (arr->empty()) fail(g.line, g.field, "empty list: give at least one value");
      for (std::size_t i = 0; i < arr->size(); ++i) one(*arr->get(i), g.field + "[" + std::to_string(i) + "]");
    } else if (const auto* grid = g.node->as_table()) {
      for (double x : grid_values(*grid, g)) out.push_back({x, {}, {}, g.field, g.line});
    } else {
      one(*g.node, g.field);
    }
    return out;
  }

  std::vector<double> grid_values(const toml::table& grid, const Given& g) const {
    std::optional<double> from, to;
    std::optional<std::int64_t> points;
    std::optional<bool> log;
    for (const auto& [key, node] : grid) {
      const std::string field = g.field + "." + clip(key.str());
      if (key.str() == "from" || key.str() == "to") {
        const auto v = number_of(node);
        if (!v || !std::isfinite(*v)) fail(node_line(node), field, "must be a finite number");
        (key.str() == "from" ? from : to) = *v;
      } else if (key.str() == "points") {
        const auto* i = node.as_integer();
        if (i == nullptr || i->get() < 1 || i->get() > 100'000)
          fail(node_line(node), field, "must be an integer from 1 to 100000");
        points = i->get();
      } else if (key.str() == "spacing") {
        const auto* s = node.as_string();
        if (s == nullptr || (s->get() != "log" && s->get() != "linear"))
          fail(node_line(node), field, "must be \"log\" or \"linear\"");
        log = s->get() == "log";
      } else {
        fail(node_line(node), field, "unknown key (expected from, to, points, spacing)");
      }
    }
    if (!from || !to || !points || !log) fail(g.line, g.field, "a grid needs from, to, points and spacing");
    if (*log && (*from <= 0.0 || *to <= 0.0)) fail(g.line, g.field, "a log grid needs from > 0 and to > 0");
    if (*points == 1 && *from != *to) fail(g.line, g.field, "a grid of 1 point needs from == to");
    const auto n = static_cast<std::size_t>(*points);
    std::vector<double> v(n);
    const double a = *log ? std::log(*from) : *from, b = *log ? std::log(*to) : *to;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = n == 1 ? a : a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1);
      v[i] = *log ? std::exp(x) : x;
    }
    v.front() = *from;
    v.back() = *to;
    return v;
  }

  // A name or a list of names, each one of `choices`.
  Axis names(const Given& g, std::initializer_list<std::string_view> choices) const {
    Axis out;
    std::string expected;
    for (std::string_view c : choices) expected += (expected.empty() ? "" : ", ") + std::string(c);
    auto one = [&](const toml::node& n, const std::string& field) {
      const auto* s = n.as_string();
      if (s == nullptr) fail(node_line(n), field, "must be a string, got " + std::string(node_kind(n)));
      if (std::find(choices.begin(), choices.end(), s->get()) == choices.end())
        fail(node_line(n), field, "unknown value \"" + clip(s->get()) + "\" (expected " + expected + ")");
      out.push_back({0.0, s->get(), {}, field, node_line(n)});
    };
    if (const auto* arr = g.node->as_array()) {
      if (arr->empty()) fail(g.line, g.field, "empty list: give at least one value");
      for (std::size_t i = 0; i < arr->size(); ++i) one(*arr->get(i), g.field + "[" + std::to_string(i) + "]");
    } else {
      one(*g.node, g.field);
    }
    return out;
  }

  // A record's file or a list of them, relative to the case-set file's folder, read once.
  Axis records(const Given& g) {
    Axis out;
    auto one = [&](const toml::node& n, const std::string& field) {
      const auto* s = n.as_string();
      if (s == nullptr || s->get().empty()) fail(node_line(n), field, "must be a file name (a string)");
      const std::string path =
          (std::filesystem::path(file_).parent_path() / std::filesystem::path(s->get())).lexically_normal().string();
      if (!records_.contains(path)) {
        try {
          records_.emplace(path, read_record(path));
        } catch (const RecordError& e) {
          fail(node_line(n), field, e.what());
        }
      }
      out.push_back({0.0, path, {}, field, node_line(n)});
    };
    if (const auto* arr = g.node->as_array()) {
      if (arr->empty()) fail(g.line, g.field, "empty list: give at least one file");
      for (std::size_t i = 0; i < arr->size(); ++i) one(*arr->get(i), g.field + "[" + std::to_string(i) + "]");
    } else {
      one(*g.node, g.field);
    }
    return out;
  }

  // storeys = [left, right], or a list of such pairs.
  Axis storeys(const Given& g) const {
    Axis out;
    auto pair = [&](const toml::node& n, const std::string& field) {
      const auto* arr = n.as_array();
      const std::string shape = "must be two storey counts [left, right] (the Pi-term form is a pair of buildings)";
      if (arr == nullptr || arr->size() != 2) fail(node_line(n), field, shape);
      Item item{0.0, {}, {}, field, node_line(n)};
      for (std::size_t i = 0; i < 2; ++i) {
        const auto* v = arr->get(i)->as_integer();
        if (v == nullptr || v->get() < 1 || v->get() > kMaxBuildingFloors)
          fail(node_line(*arr->get(i)), field + "[" + std::to_string(i) + "]",
               "must be a whole number of storeys from 1 to " + std::to_string(kMaxBuildingFloors));
        item.counts.push_back(static_cast<int>(v->get()));
      }
      out.push_back(std::move(item));
    };
    const auto* arr = g.node->as_array();
    if (arr && !arr->empty() && arr->get(0)->is_array()) {
      for (std::size_t i = 0; i < arr->size(); ++i) pair(*arr->get(i), g.field + "[" + std::to_string(i) + "]");
    } else {
      pair(*g.node, g.field);
    }
    return out;
  }

  // buildings = [{ masses = [...], stiffnesses = [...] }, ...]: one scene (not an axis).
  std::vector<Building> buildings(const Given& g, std::vector<Item>& where) const {
    const auto* arr = g.node->as_array();
    if (arr == nullptr || arr->size() < 2 || arr->size() > 3)
      fail(g.line, g.field, "must be a list of two or three buildings, left to right, each { masses = [...], "
                            "stiffnesses = [...] }");
    std::vector<Building> out;
    for (std::size_t b = 0; b < arr->size(); ++b) {
      const std::string field = g.field + "[" + std::to_string(b) + "]";
      const auto* t = arr->get(b)->as_table();
      if (t == nullptr) fail(node_line(*arr->get(b)), field, "must be a table { masses = [...], stiffnesses = [...] }");
      Building bd;
      for (const auto& [key, node] : *t) {
        const std::string f = field + "." + clip(key.str());
        if (key.str() != "masses" && key.str() != "stiffnesses")
          fail(node_line(node), f, "unknown key (a building has masses, kg, and stiffnesses, N/m, floor 1 first)");
        const auto* list = node.as_array();
        if (list == nullptr || list->empty()) fail(node_line(node), f, "must be a list of numbers, floor 1 first");
        std::vector<double>& into = key.str() == "masses" ? bd.masses : bd.stiffnesses;
        for (std::size_t i = 0; i < list->size(); ++i) {
          const auto v = number_of(*list->get(i));
          if (!v) fail(node_line(*list->get(i)), f + "[" + std::to_string(i) + "]", "must be a number");
          into.push_back(*v);
        }
      }
      for (std::string_view k : {"masses", "stiffnesses"})
        if (!t->contains(k)) fail(node_line(*t), field + "." + std::string(k), "required");
      where.push_back({0.0, {}, {}, field, node_line(*t)});
      out.push_back(std::move(bd));
    }
    return out;
  }

  std::vector<int> contact_floors(const Given& g) const {
    const auto* arr = g.node->as_array();
    if (arr == nullptr || arr->empty()) fail(g.line, g.field, "must be a list of floors (from 1), e.g. [2, 3]");
    std::vector<int> out;
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const auto* v = arr->get(i)->as_integer();
      if (v == nullptr || v->get() < 1 || v->get() > kMaxBuildingFloors)
        fail(node_line(*arr->get(i)), g.field + "[" + std::to_string(i) + "]", "must be a floor number from 1");
      out.push_back(static_cast<int>(v->get()));
    }
    return out;
  }

  struct Family;
  void drop_unused_pulse_keys(Family& f) const;
  void expand_points(const Family& f, std::vector<BuildingCase>& out) const;
  void check_pulse_keys(const Family& f) const;
  void expand(const toml::table& own, const toml::table* defaults, const std::string& prefix, const std::string& name,
              std::vector<BuildingCase>& out);
  BuildingCase build(const Family& f, const std::vector<std::size_t>& at) const;
  void check_point(const Family& f, const std::vector<std::size_t>& at, const BuildingCase& c) const;
  [[noreturn]] void report(const Family& f, const std::vector<std::size_t>& at, const std::string& bad) const;
  const Item* value(const Family& f, const std::vector<std::size_t>& at, std::string_view key) const;
};

// A family resolved: its form, its axes in kAxisOrder (those given), and the keys that are
// one value for every point.
struct BuildingsReader::Family {
  std::string name, prefix;
  std::uint32_t line = 0;
  bool pi_terms = false;
  std::vector<std::string_view> keys{};  // the axes' keys
  std::vector<Axis> axes{};
  std::vector<Building> buildings{};
  std::vector<Item> building_lines{};  // where each building was written
  std::vector<int> contact_floors{};
  Given contact_floors_at{}, t_end_at{};
  double t_end = 0.0;
  bool a_p_given = false, w_p_given = false;
};

const Item* BuildingsReader::value(const Family& f, const std::vector<std::size_t>& at, std::string_view key) const {
  for (std::size_t a = 0; a < f.keys.size(); ++a)
    if (f.keys[a] == key) return &f.axes[a][at[a]];
  return nullptr;
}

void BuildingsReader::expand(const toml::table& own, const toml::table* defaults, const std::string& prefix,
                             const std::string& name, std::vector<BuildingCase>& out) {
  Family f;
  f.name = name;
  f.prefix = prefix;
  f.line = node_line(own);
  const auto has = [&](std::string_view k) { return given(own, defaults, prefix, k).node != nullptr; };
  // The form: floor by floor or Pi terms, never both (a default of the other form is dropped).
  bool floors = false, pi = false;
  for (std::string_view k : kFloorKeys) floors = floors || own.contains(k);
  for (std::string_view k : kPiKeys) pi = pi || own.contains(k);
  if (!floors && !pi) {
    for (std::string_view k : kFloorKeys) floors = floors || has(k);
    for (std::string_view k : kPiKeys) pi = pi || has(k);
  }
  if (floors && pi) {
    const Given b = given(own, defaults, prefix, has("buildings") ? "buildings" : has("gap") ? "gap" : "t_end");
    fail(b.line, b.field, "not with the Pi-term keys (storeys, pi2, pi3, pi5, pi6): a buildings family is given "
                          "floor by floor or in Pi terms, not both");
  }
  f.pi_terms = pi;
  const std::vector<std::string_view> required =
      pi ? std::vector<std::string_view>{"storeys", "pi2", "pi3", "pi5", "pi6", "eps", "pulse"}
         : std::vector<std::string_view>{"buildings", "gap", "eps", "pulse"};
  for (std::string_view k : required)
    if (!has(k))
      fail(f.line, prefix + "." + std::string(k),
           std::string("required by a buildings family ") + (pi ? "in Pi terms" : "given floor by floor"));
  // tp gives w_p: never both in one table; the family's own (either) before [defaults]'s.
  for (const toml::table* table : {&own, defaults})
    if (table && table->contains("tp") && table->contains("w_p"))
      fail(node_line(*table->get("tp")), (table == &own ? prefix : std::string("defaults")) + ".tp",
           "not with w_p: give one of them");
  const bool tp = own.contains("tp") || (!own.contains("w_p") && has("tp"));
  if (pi && own.contains("t_end"))
    fail(node_line(*own.get("t_end")), prefix + ".t_end",
         "not in the Pi-term form (its duration is T_p + n_free T_1, which scales with the pulse: give n_free)");

  for (std::string_view k : kAxisOrder) {
    const bool of_other_form = pi ? key_in(kFloorKeys, k) : key_in(kPiKeys, k);
    Given g = given(own, defaults, prefix, k == "w_p" && tp ? "tp" : k);
    if (!g.node || of_other_form) continue;
    Axis axis = k == "storeys"       ? storeys(g)
                : k == "damping"     ? names(g, {"rayleigh", "modal"})
                : k == "pulse"       ? names(g, {"sine", "cosine", "makris-a", "makris-b", "makris-c", "mp", "record"})
                : k == "directivity" ? names(g, {"normal", "reverse"})
                : k == "record"      ? records(g)
                                     : numbers(g);
    if (g.field.ends_with(".tp"))
      for (Item& item : axis) {
        if (!(std::isfinite(item.x) && item.x > 0.0))
          fail(item.line, item.field, "must be finite and > 0 (got " + short_number(item.x) + ")");
        item.x = 2.0 * std::numbers::pi / item.x;
      }
    f.keys.push_back(k);
    f.axes.push_back(std::move(axis));
  }
  drop_unused_pulse_keys(f);
  check_pulse_keys(f);
  for (const Item& p : f.axes[static_cast<std::size_t>(std::find(f.keys.begin(), f.keys.end(), std::string_view("pulse")) - f.keys.begin())])
    for (std::string_view k : {"a_p", "w_p"})
      if (!pi && p.text != "record" && !has(k) && !(k == "w_p" && has("tp")))
        fail(f.line, prefix + "." + std::string(k),
             "required by a buildings family given floor by floor with pulse " + p.text +
                 " (its a_p in m/s^2, and w_p in rad/s or tp in s)");
  f.a_p_given = has("a_p");
  f.w_p_given = has("w_p") || has("tp");
  if (!pi) {
    f.buildings = buildings(given(own, defaults, prefix, "buildings"), f.building_lines);
    if (const Given t = given(own, defaults, prefix, "t_end"); t.node) {
      const auto v = number_of(*t.node);
      if (!v || !(std::isfinite(*v) && *v > 0.0)) fail(t.line, t.field, "must be a number of seconds > 0");
      f.t_end = *v;
      f.t_end_at = t;
    }
  }
  if (const Given c = given(own, defaults, prefix, "contact_floors"); c.node) {
    f.contact_floors = contact_floors(c);
    f.contact_floors_at = c;
  }

  expand_points(f, out);
}

// The family's points, the last axis turning fastest, each built and checked.
void BuildingsReader::expand_points(const Family& f, std::vector<BuildingCase>& out) const {
  std::size_t count = 1;
  for (const Axis& a : f.axes) {
    count *= a.size();
    if (count + out.size() > kMaxPoints)
      fail(f.line, f.prefix, "expands to more than " + std::to_string(kMaxPoints) + " buildings points in this file");
  }
  std::vector<std::size_t> at(f.axes.size(), 0);
  for (std::size_t n = 0; n < count; ++n) {
    std::size_t rest = n;
    for (std::size_t a = f.axes.size(); a-- > 0;) {
      at[a] = rest % f.axes[a].size();
      rest /= f.axes[a].size();
    }
    BuildingCase c = build(f, at);
    check_point(f, at, c);
    out.push_back(std::move(c));
  }
}

// The keys of one pulse (record, cycles, mp_gamma, mp_nu), as the single oscillators' families
// have them: a family's pulses all use each or none, one they need is required, and a default
// they do not use is left out.
void BuildingsReader::check_pulse_keys(const Family& f) const {
  const Axis& pulses = f.axes[static_cast<std::size_t>(
      std::find(f.keys.begin(), f.keys.end(), std::string_view("pulse")) - f.keys.begin())];
  for (const auto& [key, pulse] : {std::pair<std::string_view, std::string_view>{"record", "record"},
                                   {"cycles", "makris-c"}, {"mp_gamma", "mp"}, {"mp_nu", "mp"}}) {
    std::string users, others;
    for (const Item& p : pulses) (p.text == pulse ? users : others) += (p.text == pulse ? users : others).empty() ? p.text : ", " + p.text;
    const auto k = std::find(f.keys.begin(), f.keys.end(), key);
    const Item* given = k == f.keys.end() ? nullptr : &f.axes[static_cast<std::size_t>(k - f.keys.begin())][0];
    const bool own = given && !given->field.starts_with("defaults.");
    if (users.empty() && own) fail(given->line, given->field, "not used by pulse " + others);
    if (!users.empty() && !others.empty() && given)
      fail(given->line, given->field, "used by pulse " + users + " but not by " + others + ": give each its own family");
    if (!users.empty() && !given) fail(f.line, f.prefix + "." + std::string(key), "required by pulse " + users);
  }
}

// Which pulse uses a pulse's own key.
std::string_view pulse_of_key(std::string_view key) {
  return key == "record" ? "record" : key == "cycles" ? "makris-c" : key == "mp_gamma" || key == "mp_nu" ? "mp" : "";
}

// A default of a pulse's key that none of the family's pulses uses is left out (it would
// repeat the family's points once per value).
void BuildingsReader::drop_unused_pulse_keys(Family& f) const {
  const Axis& pulses = f.axes[static_cast<std::size_t>(
      std::find(f.keys.begin(), f.keys.end(), std::string_view("pulse")) - f.keys.begin())];
  for (std::size_t a = f.keys.size(); a-- > 0;) {
    const std::string_view pulse = pulse_of_key(f.keys[a]);
    if (pulse.empty() || !f.axes[a][0].field.starts_with("defaults.")) continue;
    if (std::none_of(pulses.begin(), pulses.end(), [&](const Item& p) { return p.text == pulse; })) {
      f.keys.erase(f.keys.begin() + static_cast<std::ptrdiff_t>(a));
      f.axes.erase(f.axes.begin() + static_cast<std::ptrdiff_t>(a));
    }
  }
}

// Point `at` of a family: the load as a Case holds it (cases/load.hpp makes the pulse), then
// the scene, floor by floor or from the Pi terms.
BuildingCase BuildingsReader::build(const Family& f, const std::vector<std::size_t>& at) const {
  BuildingCase c;
  c.family = f.name;
  c.pi_terms = f.pi_terms;
  const auto number = [&](std::string_view key, double fallback) {
    const Item* i = value(f, at, key);
    return i ? i->x : fallback;
  };
  // A pulse that a default of another pulse's key reached is left out (check_pulse_keys).
  Case load;
  load.scene = Scene::wall;
  load.pulse = *parse_pulse(value(f, at, "pulse")->text);
  if (const Item* d = value(f, at, "directivity")) load.directivity = *parse_directivity(d->text);
  if (load.pulse == PulseShape::makris_c) load.cycles = static_cast<int>(std::clamp(number("cycles", 0.0), -1e9, 1e9));
  if (load.pulse == PulseShape::mp) {
    load.mp_gamma = number("mp_gamma", 0.0);
    load.mp_nu = number("mp_nu", 0.0);
  }
  if (load.pulse == PulseShape::record) {
    const Item* r = value(f, at, "record");
    load.record = r->text;
    load.samples = records_.at(r->text);
    load.a_p = load.samples->peak;
    load.w_p = load.samples->mean_frequency();
    if (!f.w_p_given && !std::isfinite(load.w_p)) fail(r->line, r->field, clip(r->text) + ": " + no_mean_period_reason());
  }
  load.a_p = number("a_p", load.a_p);
  load.w_p = number("w_p", load.w_p);
  if (auto bad = validate(load)) report(f, at, *bad);
  const Pulse pulse = make_pulse(load);
  c.pulse = load.pulse;
  c.directivity = load.directivity;
  c.record = load.record;
  const double eps = number("eps", 0.0);
  if (f.pi_terms) {
    const Item* counts = value(f, at, "storeys");
    c.storeys_left = counts->counts[0];
    c.storeys_right = counts->counts[1];
    for (const auto& [key, term] : {std::pair<std::string_view, double*>{"pi2", &c.pi2}, {"pi3", &c.pi3},
                                    {"pi5", &c.pi5}, {"pi6", &c.pi6}}) {
      const Item* i = value(f, at, key);
      *term = i->x;
      const bool ok = key == "pi3" ? std::isfinite(i->x) && i->x >= 0.0 : std::isfinite(i->x) && i->x > 0.0;
      if (!ok) fail(i->line, i->field, std::string("must be finite and ") + (key == "pi3" ? ">= 0" : "> 0") + " (got " + short_number(i->x) + ")");
    }
    c.scene = uniform_pair(c.storeys_left, c.storeys_right, c.pi2, c.pi3, eps, c.pi5, c.pi6, pulse, load.a_p, load.w_p);
  } else {
    c.scene.buildings = f.buildings;
    c.scene.delta = number("gap", 0.0);
    c.scene.eps = eps;
    c.scene.pulse = pulse;
    c.scene.a_p = load.a_p;
    c.scene.w_p = load.w_p;
    c.scene.t_end = f.t_end;
  }
  if (const Item* d = value(f, at, "damping")) c.scene.damping = d->text == "modal" ? BuildingDamping::modal : BuildingDamping::rayleigh;
  c.scene.xi = number("xi", 0.05);
  c.scene.n_free = number("n_free", 3.0);
  c.scene.contact_floors = f.contact_floors;
  return c;
}

// The scene's own rules (pb::validate), and the valid domain's bound on a run's length.
void BuildingsReader::check_point(const Family& f, const std::vector<std::size_t>& at, const BuildingCase& c) const {
  if (std::string bad = validate(c.scene); !bad.empty()) report(f, at, bad);
  const BuildingModel md = assemble(c.scene);
  const double periods = md.t_end / md.t_min;
  if (!(periods <= kMaxPeriodsPerRun)) {
    std::ostringstream why;
    why << "t_end: the run spans " << periods << " of its shortest period (the pulse's or the stiffest mode's), "
        << "more than " << kMaxPeriodsPerRun;
    report(f, at, why.str());
  }
}

// validate()'s "field: reason" at the value of that field this point used.
void BuildingsReader::report(const Family& f, const std::vector<std::size_t>& at, const std::string& bad) const {
  const std::size_t colon = bad.find(": ");
  if (colon == std::string::npos) fail(f.line, f.prefix, bad);
  std::string field = bad.substr(0, colon);
  const std::string reason = bad.substr(colon + 2);
  if (field.starts_with("buildings[") && !f.pi_terms) {
    const auto b = static_cast<std::size_t>(std::stoul(field.substr(10)));
    fail(f.building_lines.at(b).line, f.building_lines.at(b).field, reason);
  }
  if (field == "t_end" && f.t_end_at.node) fail(f.t_end_at.line, f.t_end_at.field, reason);
  if (field == "contact_floors" && f.contact_floors_at.node) fail(f.contact_floors_at.line, f.contact_floors_at.field, reason);
  if (field == "gap" && f.pi_terms) field = "pi3";
  if (field == "t_end" && value(f, at, "n_free")) field = "n_free";
  if (const Item* i = value(f, at, field)) {
    const std::string got = i->text.empty() ? short_number(i->x) : "\"" + clip(i->text) + "\"";
    fail(i->line, i->field, reason + " (got " + got + ")");
  }
  fail(f.line, f.prefix + "." + field, reason);
}

// Whether a family is of the buildings scene (its own scene, else [defaults]'s).
bool is_buildings_family(const toml::node& family, const toml::table* defaults) {
  const toml::table* t = family.as_table();
  const toml::node* scene = t ? t->get("scene") : nullptr;
  if (scene == nullptr && defaults) scene = defaults->get("scene");
  if (scene == nullptr) return false;
  if (const auto* s = scene->as_string()) return s->get() == kBuildingsScene;
  if (const auto* list = scene->as_array())
    for (const toml::node& n : *list)
      if (n.is_string() && *n.value<std::string>() == kBuildingsScene) return true;
  return false;
}

}  // namespace

std::optional<BuildingsSet> parse_buildings_set(std::string_view toml_text, std::string_view source_name) {
  const toml::table root = parse_toml<CaseSetError>(toml_text, source_name);
  const toml::array* families = root.get_as<toml::array>("family");
  if (families == nullptr) return std::nullopt;
  const toml::table* defaults = root.get_as<toml::table>("defaults");
  const bool any = std::any_of(families->begin(), families->end(),
                               [&](const toml::node& n) { return is_buildings_family(n, defaults); });
  if (!any) return std::nullopt;
  return BuildingsReader(source_name).read(root, *families);
}

std::optional<BuildingsSet> load_buildings_set(const std::filesystem::path& file) {
  return parse_buildings_set(read_input_file<CaseSetError>(file), file.string());
}

std::string buildings_not_here_reason() {
  return "buildings: a case of the buildings scene is solved by `poundbench run --case-file FILE --point N` "
         "(and poundbench.run) and `poundbench spectrum FILE`, not yet by the studies";
}

}  // namespace pb
