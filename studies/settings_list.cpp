#include "studies/settings_list.hpp"

#include <toml++/toml.h>

#include <array>
#include <cmath>
#include <sstream>
#include <tuple>

#include "cases/case.hpp"
#include "cases/text.hpp"
#include "cases/toml_input.hpp"
#include "programs/process.hpp"
#include "kit/settings_fields.hpp"
#include "solvers/registry.hpp"

namespace pb {

namespace {

// Steps per shortest period: Settings::steps is an int, and 1e9 steps per period already
// means hours per run. Checked before the doubling loop, so the loop cannot overflow.
constexpr long long kMaxSteps = 1'000'000'000;

// Settings a list may expand to: every one runs every point of the case set, and the
// summary has a row per family and setting. The largest shipped list (default.toml) has
// 133; 10,000 settings even over the 40-point smoke set are 400,000 runs. Beyond that
// the list is a typo (a product of long lists), refused as case sets refuse theirs.
constexpr std::size_t kMaxSettings = 10'000;

class Reader {
 public:
  explicit Reader(std::string_view source) : source_(source) {}

  [[noreturn]] void fail(const toml::node* at, const std::string& field, const std::string& why) const {
    std::ostringstream out;
    out << source_;
    if (at && at->source().begin.line) out << ':' << at->source().begin.line;
    // A field is built from the file's own keys: clipped, so a huge key cannot flood the line.
    out << ": " << clip(field) << ": " << why;
    throw SettingsListError(out.str());
  }

  // One value or a list of them, as doubles.
  std::vector<double> numbers(const toml::node& n, const std::string& field) const {
    std::vector<double> out = one_or_list<double>(n, field, [&](const toml::node& v) {
      if (const auto* i = v.as_integer()) return static_cast<double>(i->get());
      if (const auto* f = v.as_floating_point()) return f->get();
      fail(&v, field, "must be a number");
    });
    for (double x : out)
      if (!std::isfinite(x)) fail(&n, field, "must be finite");
    return out;
  }

  std::vector<std::string> strings(const toml::node& n, const std::string& field) const {
    return one_or_list<std::string>(n, field, [&](const toml::node& v) {
      if (const auto* s = v.as_string()) return s->get();
      fail(&v, field, "must be a string");
    });
  }

  // One value or a non-empty list of them, each read by `one`.
  template <typename T, typename One>
  std::vector<T> one_or_list(const toml::node& n, const std::string& field, One one) const {
    std::vector<T> out;
    if (const auto* a = n.as_array()) {
      for (const toml::node& v : *a) out.push_back(one(v));
      if (out.empty()) fail(&n, field, "empty list");
    } else {
      out.push_back(one(n));
    }
    return out;
  }

  // An integer, a list of them, or { from, to }: powers of two apart.
  std::vector<double> steps(const toml::node& n, const std::string& field) const {
    const std::string range = "must be a whole number from 1 to " + std::to_string(kMaxSteps);
    if (const auto* t = n.as_table()) {
      long long from = 0, to = 0;
      for (auto&& [k, v] : *t) {
        const std::string f = field + "." + std::string(k.str());
        if (k.str() != "from" && k.str() != "to") fail(&v, f, "unknown key");
        const auto* i = v.as_integer();
        if (!i) fail(&v, f, range);
        if (i->get() < 1 || i->get() > kMaxSteps) fail(&v, f, range + " (got " + std::to_string(i->get()) + ")");
        (k.str() == "from" ? from : to) = i->get();
      }
      if (from == 0 || to == 0) fail(&n, field, "a doubling range needs from and to");
      if (to < from) fail(&n, field, "to must be >= from");
      std::vector<double> out;
      for (long long s = from; s <= to; s *= 2) out.push_back(static_cast<double>(s));
      return out;
    }
    std::vector<double> out = numbers(n, field);
    for (double x : out)
      if (x < 1 || x != std::floor(x) || x > static_cast<double>(kMaxSteps)) fail(&n, field, range);
    return out;
  }

 private:
  std::string source_;
};

// The top-level keys into `list`; the [[run]] tables.
const toml::array& read_top_level(const Reader& r, const toml::table& doc, SettingsList& list) {
  const toml::array* runs = nullptr;
  for (auto&& [key, node] : doc) {
    const std::string k(key.str());
    if (k == "name" || k == "description") {
      const auto* s = node.as_string();
      if (!s) r.fail(&node, k, "must be a string");
      (k == "name" ? list.name : list.description) = s->get();
    } else if (k == "reference_tol_scale") {
      const double v = r.numbers(node, k).at(0);
      if (!(v > 0.0) || node.is_array()) r.fail(&node, k, "must be one number > 0");
      list.reference_tol_scale = v;
    } else if (k == "reference_time_limit") {
      const double v = r.numbers(node, k).at(0);
      if (!(v >= 0.0) || node.is_array()) r.fail(&node, k, "must be one number >= 0 (seconds; 0: none)");
      list.reference_time_limit = v;
    } else if (k == "run") {
      runs = node.as_array();
      if (!runs) r.fail(&node, k, "must be [[run]] tables");
    } else {
      r.fail(&node, k, "unknown key");
    }
  }
  if (!runs || runs->empty()) r.fail(nullptr, "run", "no [[run]] tables");
  return *runs;
}

// One [[run]] table as read: its solver, and the values of each axis of its product.
struct RunTable {
  const toml::table* table = nullptr;
  const toml::node* node = nullptr;  // the table's, for the errors of the whole run
  std::string field;                 // "run[i]"
  std::string solver;
  const toml::node* solver_node = nullptr;
  std::vector<std::string> variants = {""};
  // Every number of Settings (kit/settings_fields.hpp) may be a list; unset, its
  // default. The rules below are the list's own: the solver's check() judges the rest.
  std::array<std::vector<double>, kSettingFields.size()> values;
  std::array<std::vector<std::string>, kSettingFields.size()> names;  // a name's values
  std::array<const toml::node*, kSettingFields.size()> given{};
  bool monitor = Settings{}.monitor;
  // The physical forms (studies/physical_settings.hpp): 0, not given.
  std::vector<double> h_s = {0.0}, k_contact = {0.0};
  const toml::node *h_s_node = nullptr, *k_contact_node = nullptr;
  // The solvers' own settings given (SolverInfo::own_settings): an axis each, beside the variant.
  struct OwnKey {
    std::string name;
    const toml::node* node = nullptr;
    std::vector<double> values;
  };
  std::vector<OwnKey> own;

  std::size_t axis_size(std::size_t j) const { return kSettingFields[j].text ? names[j].size() : values[j].size(); }
};

// A key of Settings (every other key of a [[run]] is read by read_run_key).
void read_setting(const Reader& r, const std::string& k, std::size_t j, const toml::node& v, const std::string& f,
                  RunTable& run) {
  if (kSettingFields[j].text) {
    run.names[j] = r.strings(v, f);
  } else if (k == "steps") {
    run.values[j] = r.steps(v, f);
  } else if (k == "step_cap") {
    const auto* n = v.as_integer();
    if (!n || n->get() < 1) r.fail(&v, f, "must be an integer >= 1");
    run.values[j] = {static_cast<double>(n->get())};
  } else if (k == "time_limit") {
    const auto* n = v.as_integer();
    const auto* x = v.as_floating_point();
    const double seconds = n ? static_cast<double>(n->get()) : x ? x->get() : -1.0;
    if (!(seconds > 0.0) || !std::isfinite(seconds)) r.fail(&v, f, "must be one number of seconds > 0");
    run.values[j] = {seconds};
  } else {
    run.values[j] = r.numbers(v, f);
    for (double x : run.values[j])
      if (!kSettingFields[j].number && x != std::floor(x)) r.fail(&v, f, "must be a whole number");
    if (k == "wh")
      for (double x : run.values[j])
        if (!(x > 0.0)) r.fail(&v, f, "must be > 0 (the step as w_max h)");
  }
  run.given[j] = &v;
}

// One key of a [[run]] table into `run`.
void read_run_key(const Reader& r, const std::string& k, const toml::node& v, RunTable& run) {
  const std::string f = run.field + "." + k;
  if (k == "solver") {
    const auto* s = v.as_string();
    if (!s) r.fail(&v, f, "must be a string");
    run.solver = s->get();
    run.solver_node = &v;
  } else if (k == "variant") {
    run.variants = r.strings(v, f);
  } else if (k == "persistent") {
    // The external solver's persistent variant (docs/external.md), as `--persistent`.
    const auto* b = v.as_boolean();
    if (!b) r.fail(&v, f, "must be true or false");
    if (run.table->contains("variant")) r.fail(&v, f, "give persistent or variant, not both");
    if (b->get()) run.variants = {std::string(programs::kPersistent)};
  } else if (k == "h_s" || k == "k_contact") {
    std::vector<double>& physical = k == "h_s" ? run.h_s : run.k_contact;
    physical = r.numbers(v, f);
    for (double x : physical)
      if (!(x > 0.0))
        r.fail(&v, f, k == "h_s" ? "must be > 0 (the step in seconds)" : "must be > 0 (N/m; N/m^1.5 for the Hertz family)");
    (k == "h_s" ? run.h_s_node : run.k_contact_node) = &v;
  } else if (k == "monitor") {
    const auto* b = v.as_boolean();
    if (!b) r.fail(&v, f, "must be true or false");
    run.monitor = b->get();
  } else if (const auto j = setting_field_index(k)) {
    read_setting(r, k, *j, v, f, run);
  } else if (is_own_setting(k)) {
    run.own.push_back({k, &v, r.numbers(v, f)});
  } else {
    r.fail(&v, f, "unknown key");
  }
}

RunTable read_run(const Reader& r, const toml::node& rn, std::size_t i) {
  RunTable run;
  run.node = run.solver_node = &rn;
  run.field = "run[" + std::to_string(i) + "]";
  run.table = rn.as_table();
  if (!run.table) r.fail(&rn, run.field, "must be a table");
  for (std::size_t j = 0; j < kSettingFields.size(); ++j) {
    if (kSettingFields[j].text) run.names[j] = {Settings{}.*kSettingFields[j].text};
    else run.values[j] = {kSettingFields[j].get(Settings{})};
  }
  for (auto&& [key, v] : *run.table) read_run_key(r, std::string(key.str()), v, run);
  return run;
}

// A [[run]] gives its step one way (steps, wh or h_s) and its stiffness one way (stiffness or
// k_contact).
void check_one_form_each(const Reader& r, const RunTable& run) {
  const std::size_t steps = *setting_field_index("steps"), wh = *setting_field_index("wh");
  if (run.given[steps] && run.given[wh])
    r.fail(run.given[wh], run.field + ".wh", "give steps or wh, not both (one [[run]] each)");
  const std::size_t stiffness = *setting_field_index("stiffness");
  for (const auto& [node, key, pi_node, pi_key] :
       {std::tuple{run.h_s_node, "h_s", run.given[steps] ? run.given[steps] : run.given[wh],
                   run.given[steps] ? "steps" : "wh"},
        std::tuple{run.k_contact_node, "k_contact", run.given[stiffness], "stiffness"}})
    if (node && pi_node)
      r.fail(node, run.field + "." + key,
             "not with " + std::string(pi_key) +
                 " (a [[run]] gives its step and stiffness in physical units or in Pi terms, not both)");
}

// The order of the product: variant outermost, then the numbers in the table's order,
// the step (steps or w_max h) innermost, so that one setting's step sizes are adjacent.
std::vector<std::size_t> product_axes() {
  const std::size_t steps = *setting_field_index("steps"), wh = *setting_field_index("wh");
  std::vector<std::size_t> axes;
  for (std::size_t j = 0; j < kSettingFields.size(); ++j)
    if (j != steps && j != wh) axes.push_back(j);
  axes.push_back(steps);
  axes.push_back(wh);
  return axes;
}

// The settings a run expands to. Counted before anything is expanded; the product so far is
// at most kMaxSettings when the next list's length (bounded by the file's size) multiplies
// it, so it cannot overflow.
std::size_t count_settings(const Reader& r, const RunTable& run, const std::vector<std::size_t>& axes,
                           std::size_t listed) {
  std::size_t product = run.variants.size() * run.h_s.size() * run.k_contact.size();
  for (const RunTable::OwnKey& own : run.own) product *= own.values.size();
  for (std::size_t j : axes) {
    product *= run.axis_size(j);
    if (listed + product > kMaxSettings)
      r.fail(run.node, run.field, "the list expands to more than " + std::to_string(kMaxSettings) +
                                      " settings (the product of its lists' lengths); split the study");
  }
  return product;
}

// A physical value is mapped per case (resolve_physical_settings); here its Pi form stands
// in as a valid one (w_max h = 1, K = 1), so that the check says whether the variant uses it
// at all.
void check_physical_forms(const Reader& r, const SolverInfo& info, const RunTable& run, const Settings& settings,
                          double h, double k) {
  Settings probe = settings;
  if (h > 0.0) probe.wh = 1.0;
  if (k > 0.0) probe.stiffness = 1.0;
  if (std::string bad = info.check(probe); !bad.empty()) {
    const bool step = h > 0.0 && (k == 0.0 || bad.rfind("wh: ", 0) == 0);
    // The reason names the Pi form the value stood in for: the field says which it is.
    const std::string_view pi_form = step ? "wh: " : "stiffness: ";
    if (bad.rfind(pi_form, 0) == 0) bad.erase(0, pi_form.size());
    r.fail(step ? run.h_s_node : run.k_contact_node, run.field + (step ? ".h_s" : ".k_contact"),
           clip(bad, kMaxEchoedReason));
  }
}

// Every combination of the run's own settings, as Settings::own (NaN: not given); the last
// key turns fastest. Throws where the solver does not declare a key.
std::vector<std::array<double, kMaxOwnSettings>> own_combinations(const Reader& r, const SolverInfo& info,
                                                                  const RunTable& run) {
  std::vector<std::array<double, kMaxOwnSettings>> out(1, Settings{}.own);
  for (const RunTable::OwnKey& own : run.own) {
    const auto i = own_setting_index(info.own_settings, own.name);
    if (!i) r.fail(own.node, run.field + "." + own.name, "not used by solver " + std::string(info.name) + " (another solver's own setting)");
    std::vector<std::array<double, kMaxOwnSettings>> next;
    for (const auto& base : out)
      for (double x : own.values) {
        next.push_back(base);
        next.back()[*i] = x;
      }
    out = std::move(next);
  }
  return out;
}

// The run's product into list.runs (and list.physical), each setting checked by its solver.
void expand_run(const Reader& r, const SolverInfo* info, const RunTable& run, SettingsList& list) {
  const std::vector<std::size_t> axes = product_axes();
  const std::size_t product = count_settings(r, run, axes, list.runs.size());
  std::vector<std::size_t> at(axes.size(), 0);
  // The own settings and k_contact beside the variant, h_s innermost: it is the step.
  const auto owns = own_combinations(r, *info, run);
  const std::size_t numbers = product / (run.variants.size() * owns.size() * run.h_s.size() * run.k_contact.size());
  for (const std::string& variant : run.variants)
    for (const auto& own : owns)
      for (double k : run.k_contact)
        for (std::size_t n = 0; n < numbers; ++n) {
          SweepRun spec{info, {}};
          spec.settings.variant = variant;
          spec.settings.own = own;
          spec.settings.monitor = run.monitor;
          for (std::size_t a = 0; a < axes.size(); ++a) {
            const SettingField& sf = kSettingFields[axes[a]];
            if (sf.text) spec.settings.*sf.text = run.names[axes[a]][at[a]];
            else sf.set(spec.settings, run.values[axes[a]][at[a]]);
          }
          for (std::size_t a = axes.size(); a-- > 0;) {  // odometer: the last axis turns fastest
            if (++at[a] < run.axis_size(axes[a])) break;
            at[a] = 0;
          }
          // The check refuses a key the variant does not use, by its value (pb::unused_setting):
          // a [[run]]'s key applies to each variant of its list, and at its default it changes
          // nothing for those that do not use it (theta 1/2 beside d1-minus-linear).
          if (const std::string bad = info->check(spec.settings); !bad.empty())
            r.fail(run.node, run.field, clip(bad, kMaxEchoedReason));  // it may echo the file's own values
          for (double h : run.h_s) {
            check_physical_forms(r, *info, run, spec.settings, h, k);
            list.runs.push_back(spec);
            list.physical.push_back({h, k});
          }
        }
}

}  // namespace

SettingsList parse_settings_list(std::string_view text, std::string_view source) {
  const Reader r(source);
  const toml::table doc = parse_toml<SettingsListError>(text, source);
  SettingsList list;
  const toml::array& runs = read_top_level(r, doc, list);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunTable run = read_run(r, *runs.get(i), i);
    const SolverInfo* info = find_solver(run.solver);
    if (const std::string_view needs = left_out_needs(run.solver); !needs.empty()) {
      list.left_out.push_back(run.field + ": " + run.solver + " (needs " + std::string(needs) + ")");
      continue;
    }
    if (run.solver.empty()) r.fail(run.node, run.field + ".solver", "missing");
    if (!info) r.fail(run.solver_node, run.field + ".solver", "unknown solver '" + clip(run.solver) + "'");
    check_one_form_each(r, run);
    expand_run(r, info, run, list);
  }
  if (list.runs.empty())
    r.fail(nullptr, "run", "every [[run]] names an engine this build left out: " + list.left_out.front());
  return list;
}

SettingsList load_settings_list(const std::filesystem::path& file) {
  return parse_settings_list(read_input_file<SettingsListError>(file), file.string());
}

}  // namespace pb
