// The Python module: `import poundbench`.
//
//   poundbench.run(scene="pair", pulse="cosine", directivity="normal", pi2=0.8, pi3=0.5,
//                  eps=0.5, pi5=0.5, pi6=1.0, solver="moreau-jean", steps=64)
//   poundbench.spectrum("cases/sets/smoke.toml", solver="moreau-jean", steps=64)
//   poundbench.spectrum("cases/sets/smoke.toml", solver=f)          # f(case: dict) -> dict, in process
//   poundbench.workprecision("cases/sets/smoke.toml", settings=[{"solver": "mine", "steps": [64, 256]}],
//                            solvers={"mine": f})
//
// NumPy is needed for histories alone (run(history=True)), imported there.
//
// Its keywords are the command line's flags, with '_' for '-' (n_free for --n-free), made
// from the same tables (cases/fields.hpp, kit/settings_fields.hpp), and they are checked
// by the same code as the flags (frontend/case_flags.cpp, frontend/solver_flags.cpp): a bad keyword is a
// ValueError with the command line's message ("--pi3: required (or give --case-file)").
// run() returns the object `run --json` prints, as a dict, with the history as NumPy arrays
// when asked; spectrum() a list of such dicts, one per point in point order (a list rather
// than columns: each row keeps its types, and pandas.DataFrame(rows) makes the table).
//
// A solve runs with the GIL released on the calling thread: Ctrl-C stops the sweep (its stop
// flag, set by a SIGINT handler of the module's, installed on the first call and kept) and raises
// KeyboardInterrupt.

#include <thread>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <bit>
#include <chrono>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <csignal>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/case_set.hpp"
#include "cases/fields.hpp"
#include "cases/text.hpp"
#include "frontend/buildings_run.hpp"
#include "frontend/case_flags.hpp"
#include "frontend/errors.hpp"
#include "frontend/run_output.hpp"
#include "frontend/solver_flags.hpp"
#include "cases/physical.hpp"
#include "frontend/contact_stiffness.hpp"
#include "python/callable_solver.hpp"
#include "python/settings_toml.hpp"
#include "rows/row_read.hpp"
#include "rows/minimal_rows.hpp"
#include "studies/baseline.hpp"
#include "studies/settings_list.hpp"
#include "studies/stress.hpp"
#include "studies/workprecision.hpp"
#include "programs/process.hpp"
#include "output/output_files.hpp"
#include "kit/settings_fields.hpp"
#include "sweep/buildings_sweep.hpp"
#include "sweep/sweep.hpp"
#include "solvers/registry.hpp"

namespace py = pybind11;

namespace pb::python {

namespace {

// ---------------------------------------------------------------- keywords

// Where a keyword goes: the case, the solver, or the call itself.
struct Keywords {
  app::CaseFlags case_flags;
  app::SolverFlags solver_flags;
  std::vector<std::string> given;  // the flags the keywords stand for ("--pi3")
  bool history = false;
  std::optional<long long> samples, threads;
  double k_contact = 0.0;
  py::object callable;  // solver=f: a Python callable, the external solver in process (callable_solver.hpp)
  // The solvers' own settings given (SolverInfo::own_settings), set once the solver is known.
  std::vector<std::pair<std::string, double>> own;
  // What app::checked_solver's answer depends on: every keyword, name then value, but for the
  // case's own fields (kCaseFields), whose names alone count. run() keeps its last answer.
  py::list solver_key;
  // No keyword of a case file, an alias or physical units: the case's checks by name (case_of)
  // depend on the names given and the scene, pulse and directivity alone.
  bool by_name_alone = true;

  bool has(std::string_view flag) const {
    for (const std::string& g : given)
      if (g == flag) return true;
    return false;
  }
  app::GivenSolverFlag given_flag() const {
    return [this](std::string_view flag) { return has(flag); };
  }
};

[[noreturn]] void type_error(const std::string& function, std::string_view key, const std::string& why) {
  throw py::type_error(function + "() keyword " + clip(key) + ": " + why);
}

// A str as the bytes it stands for: UTF-8, with the bytes a file name that is not UTF-8 was
// read with (os.fsdecode's surrogateescape) given back, as os.fsencode does; a lone
// surrogate is not text (ValueError).
std::string utf8(const std::string& function, std::string_view key, const py::handle& value) {
  Py_ssize_t size = 0;
  if (const char* text = PyUnicode_AsUTF8AndSize(value.ptr(), &size)) return std::string(text, static_cast<std::size_t>(size));
  PyErr_Clear();  // a surrogate: through the codec, which gives back the bytes it stands for
  PyObject* bytes = PyUnicode_AsEncodedString(value.ptr(), "utf-8", "surrogateescape");
  if (bytes == nullptr) {
    PyErr_Clear();
    throw py::value_error(function + "() keyword " + clip(key) + ": not text (a lone surrogate)");
  }
  std::string out(PyBytes_AS_STRING(bytes), static_cast<std::size_t>(PyBytes_GET_SIZE(bytes)));
  Py_DECREF(bytes);
  return out;
}

std::string text(const std::string& function, std::string_view key, const py::handle& value) {
  if (py::isinstance<py::str>(value)) return utf8(function, key, value);
  if (py::hasattr(value, "__fspath__")) {
    const py::object path = py::module_::import("os").attr("fspath")(value);
    if (py::isinstance<py::str>(path)) return utf8(function, key, path);
    if (py::isinstance<py::bytes>(path)) return path.cast<std::string>();
  }
  type_error(function, key, "must be a str");
}

// A whole number (an int, or anything with __index__ such as NumPy's integers, never a bool):
// one outside a long long's range is out of range for every keyword, a ValueError.
long long whole(const std::string& function, std::string_view key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) type_error(function, key, "must be an int");
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  const long long x = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0)
    throw app::BadInput(flag_of(key) + ": " + (overflow > 0 ? "too large" : "too small") + " (out of range)");
  if (x == -1 && PyErr_Occurred()) throw py::error_already_set();
  return x;
}

// A number: a float (NumPy's float64 is one), or a whole number as whole() takes it; an int
// too large for a double is out of range, a ValueError.
double number(const std::string& function, std::string_view key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) type_error(function, key, "must be a number");
  if (PyFloat_Check(value.ptr())) return PyFloat_AS_DOUBLE(value.ptr());
  if (!PyIndex_Check(value.ptr())) {
    // Other real numbers (NumPy's float32, fractions): through float(), never a str's parse.
    if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || !py::hasattr(value, "__float__"))
      type_error(function, key, "must be a number");
    const double x = PyFloat_AsDouble(value.ptr());
    if (x == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      type_error(function, key, "must be a number");
    }
    return x;
  }
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) throw py::error_already_set();
  const double x = PyLong_AsDouble(index.ptr());
  if (x == -1.0 && PyErr_Occurred()) {
    PyErr_Clear();
    throw app::BadInput(flag_of(key) + ": too large for a double (out of range)");
  }
  return x;
}

int as_int(std::string_view key, long long value) {
  if (value < INT_MIN || value > INT_MAX) throw app::BadInput(flag_of(key) + ": " + std::to_string(value) + " is out of range");
  return static_cast<int>(value);
}

// What a keyword is in run() or spectrum() (`for_run`); the order of the tests is each name's
// precedence (a case's field before a setting of the same name).
enum class Slot : unsigned char {
  unexpected, scene, pulse, directivity, case_field, alias, physical, k_contact, case_file, point,
  history, samples, threads, monitor, solver, persistent, variant, setting, own
};
struct Kind {
  Slot slot = Slot::unexpected;
  std::size_t index = 0;  // in kCaseFields, kCaseAliases, kPhysicalFields or kSettingFields
};

Kind classify(bool for_run, std::string_view name) {
  const auto in = [&](const auto& table) -> std::optional<std::size_t> {
    for (std::size_t j = 0; j < table.size(); ++j)
      if (table[j].name == name) return j;
    return std::nullopt;
  };
  if (for_run && name == "scene") return {Slot::scene};
  if (for_run && name == "pulse") return {Slot::pulse};
  if (for_run && name == "directivity") return {Slot::directivity};
  if (const auto j = in(kCaseFields); for_run && j) return {Slot::case_field, *j};
  if (const auto j = in(kCaseAliases); for_run && j) return {Slot::alias, *j};
  if (const auto j = in(kPhysicalFields); for_run && j) return {Slot::physical, *j};
  if (for_run && name == "k_contact") return {Slot::k_contact};
  if (for_run && name == "case_file") return {Slot::case_file};
  if (for_run && name == "point") return {Slot::point};
  if (for_run && name == "history") return {Slot::history};
  if (for_run && name == "samples") return {Slot::samples};
  if (!for_run && name == "threads") return {Slot::threads};
  if (name == "monitor") return {Slot::monitor};
  if (name == "solver") return {Slot::solver};
  if (name == "persistent") return {Slot::persistent};
  if (name == "variant") return {Slot::variant};
  if (const auto j = setting_field_index(name)) return {Slot::setting, *j};
  if (is_own_setting(name)) return {Slot::own};
  return {};
}

// Every keyword either function takes, classified once per module: a call looks its names up
// in a dict (their hashes are the strs' own, kept by Python). Classifying each name and writing
// its flag per call, read_keywords was 11.6 k of a call's 53 k instructions besides the solve,
// 7.5 k so (callgrind, BM_PythonRun's call).
struct KnownKeyword {
  std::string flag;  // what it stands for in `given` ("--pi3"; persistent: "--variant")
  Kind run, spectrum;
};
struct KeywordTable {
  std::vector<KnownKeyword> keywords;
  py::dict index;  // name -> its place in keywords
};
const KeywordTable& keyword_table() {
  static const KeywordTable* table = [] {
    auto* t = new KeywordTable();  // never freed: its dict would outlive the interpreter
    std::vector<std::string_view> names = {"scene",   "pulse",      "directivity", "k_contact", "case_file",
                                           "point",   "history",    "samples",     "threads",   "monitor",
                                           "solver",  "persistent", "variant"};
    for (const auto& f : kCaseFields) names.push_back(f.name);
    for (const auto& f : kCaseAliases) names.push_back(f.name);
    for (const auto& f : kPhysicalFields) names.push_back(f.name);
    for (const auto& f : kSettingFields) names.push_back(f.name);
    for (const SolverInfo& s : solvers())
      for (const OwnSetting& own : s.own_settings) names.push_back(own.name);
    for (const std::string_view name : names) {
      // Interned, as the names of a call's keywords written in Python source are: found by identity.
      py::str key(name.data(), name.size());
      PyUnicode_InternInPlace(&key.ptr());
      if (t->index.contains(key)) continue;
      t->index[key] = t->keywords.size();
      t->keywords.push_back({name == "persistent" ? "--variant" : flag_of(name), classify(true, name), classify(false, name)});
    }
    return t;
  }();
  return *table;
}

// The keywords of `function` ("run" or "spectrum"); a None value counts as not given.
Keywords read_keywords(const std::string& function, const py::kwargs& kwargs) {
  Keywords k;
  Settings& settings = k.solver_flags.settings;
  const bool for_run = function == "run";
  const KeywordTable& table = keyword_table();
  k.given.reserve(kwargs.size());
  for (const auto& [key_object, value] : kwargs) {
    const std::string key = utf8(function, "name", key_object);
    if (value.is_none()) continue;
    PyObject* place = PyDict_GetItemWithError(table.index.ptr(), key_object.ptr());
    if (place == nullptr && PyErr_Occurred()) throw py::error_already_set();
    const KnownKeyword* known = place ? &table.keywords[PyLong_AsSize_t(place)] : nullptr;
    const Kind kind = known ? (for_run ? known->run : known->spectrum) : Kind{};
    if (PyList_Append(k.solver_key.ptr(), key_object.ptr()) != 0 ||
        PyList_Append(k.solver_key.ptr(), (kind.slot == Slot::case_field ? py::none() : value).ptr()) != 0)
      throw py::error_already_set();
    switch (kind.slot) {
      case Slot::scene: k.case_flags.scene = text(function, key, value); break;
      case Slot::pulse: k.case_flags.pulse = text(function, key, value); break;
      case Slot::directivity: k.case_flags.directivity = text(function, key, value); break;
      case Slot::case_field: {
        const CaseField& f = kCaseFields[kind.index];
        if (f.number)
          k.case_flags.numbers.*f.number = number(function, key, value);
        else if (f.text)
          k.case_flags.numbers.*f.text = text(function, key, value);
        else
          k.case_flags.numbers.*f.integer = as_int(key, whole(function, key, value));
        break;
      }
      case Slot::alias:
        k.case_flags.aliases[kind.index] = number(function, key, value);
        k.by_name_alone = false;
        break;
      case Slot::physical:
        k.case_flags.numbers.physical.*kPhysicalFields[kind.index].member = number(function, key, value);
        k.by_name_alone = false;
        break;
      case Slot::k_contact: k.k_contact = number(function, key, value); break;
      case Slot::case_file:
        k.case_flags.case_file = text(function, key, value);
        k.by_name_alone = false;
        break;
      case Slot::point:
        k.case_flags.point = whole(function, key, value);
        k.by_name_alone = false;
        break;
      case Slot::history:
        if (!py::isinstance<py::bool_>(value)) type_error(function, key, "must be True or False");
        k.history = value.cast<bool>();
        continue;
      case Slot::samples: k.samples = whole(function, key, value); continue;
      case Slot::threads: k.threads = whole(function, key, value); continue;
      case Slot::monitor:
        if (!py::isinstance<py::bool_>(value)) type_error(function, key, "must be True or False");
        settings.monitor = value.cast<bool>();
        break;
      case Slot::solver:
        if (!py::isinstance<py::str>(value) && PyCallable_Check(value.ptr())) {
          k.callable = py::reinterpret_borrow<py::object>(value);
          k.solver_flags.solver = "external";
        } else {
          k.solver_flags.solver = text(function, key, value);
        }
        break;
      case Slot::persistent:
        if (!py::isinstance<py::bool_>(value)) type_error(function, key, "must be True or False");
        if (value.cast<bool>()) settings.variant = std::string(programs::kPersistent);
        break;
      case Slot::variant: settings.variant = text(function, key, value); break;
      case Slot::setting: {
        const SettingField& f = kSettingFields[kind.index];
        if (f.text)
          settings.*f.text = text(function, key, value);
        else if (f.number)
          settings.*f.number = number(function, key, value);
        else if (f.integer)
          settings.*f.integer = as_int(key, whole(function, key, value));
        else
          settings.*f.count = static_cast<long>(whole(function, key, value));
        break;
      }
      case Slot::own: k.own.emplace_back(key, number(function, key, value)); break;
      case Slot::unexpected:
        throw py::type_error(function + "() got an unexpected keyword argument '" + clip(key) + "'");
    }
    k.given.push_back(known->flag);
  }
  for (const auto& [name, x] : k.own) app::set_own_setting(k.solver_flags, name, x);
  return k;
}

// ---------------------------------------------------------------- results

// Text that may hold bytes that are not UTF-8 (a file name, an external program's message),
// each such byte as U+FFFD, as --json writes them: the answer comes out whatever the bytes.
py::str decoded(std::string_view text) {
  PyObject* s = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace");
  if (s == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(s);
}

// A JSON scalar (of nlohmann's json or ordered_json) as a Python object.
template <class Json>
py::object to_python(const Json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::boolean: return py::bool_(j.template get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.template get<long long>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.template get<unsigned long long>());
    case nlohmann::json::value_t::number_float: return py::float_(j.template get<double>());
    case nlohmann::json::value_t::string: return decoded(j.template get_ref<const std::string&>());
    default: return py::none();  // null; a row's settings are flat, and json_to_python takes lists and objects
  }
}

py::dict presized_dict(Py_ssize_t entries) {
  PyObject* d = _PyDict_NewPresized(entries);
  if (d == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::dict>(d);
}

// The object `run --json` prints, built as a dict directly (app::row_fields): the JSON object
// and its conversion cost 101 k instructions a call (callgrind, see run()).
class DictSink final : public app::FieldSink {
 public:
  // Sized for a row's fields (about 50) at once: grown from empty, it was resized four times.
  py::dict dict = presized_dict(64);
  void null(std::string_view key) override { add(key, py::none()); }
  void boolean(std::string_view key, bool x) override { add(key, py::bool_(x)); }
  void integer(std::string_view key, long long x) override { add(key, py::int_(x)); }
  void number(std::string_view key, double x) override { add(key, py::float_(x)); }
  // A key's text is often its last one ("ok", the solver's and the scene's names): kept, as a str.
  void text(std::string_view key, std::string_view x) override {
    Key& k = key_of(key);
    if (!k.last_text || k.text != x) {
      k.last_text = decoded(x);
      k.text = x;
    }
    set(k.name.ptr(), k.last_text);
  }
  // A row's settings: the last one parsed is kept (a loop of calls gives the same settings
  // again), and each row gets a copy of its own.
  void object(std::string_view key, std::string_view json) override {
    static std::string last_json;
    static py::dict* last = nullptr;
    if (!last || json != last_json) {
      py::dict d;
      const nlohmann::json parsed = nlohmann::json::parse(json);
      for (const auto& [name, value] : parsed.items()) d[decoded(name)] = to_python(value);
      if (!last) last = new py::dict();  // never freed: it would outlive the interpreter
      *last = std::move(d);
      last_json = json;
    }
    const py::object copy = py::reinterpret_steal<py::object>(PyDict_Copy(last->ptr()));
    if (!copy) throw py::error_already_set();
    add(key, copy);
  }
  void list(std::string_view key, std::span<const double> xs) override {
    py::list l(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i)
      l[i] = std::isfinite(xs[i]) ? py::object(py::float_(xs[i])) : py::object(py::none());
    add(key, l);
  }

 private:
  struct Key {
    std::string key;
    py::str name;
    std::string text;  // the key's last text value, and that as a str
    py::object last_text;
  };
  // The keys as Python strings, made once (they are the names of --json's fields, a few dozen,
  // and live as long as the module: never freed, they would outlive the interpreter): a row's
  // keys come in the same order every time, so the one after the last is tried first.
  static Key& key_of(std::string_view key) {
    static auto* keys = new std::vector<Key>();
    static std::size_t next = 0;
    for (std::size_t tried = 0; tried < keys->size(); ++tried) {
      if (next >= keys->size()) next = 0;
      if (Key& k = (*keys)[next++]; k.key == key) return k;
    }
    keys->push_back({std::string(key), decoded(key), {}, {}});
    next = 0;
    return keys->back();
  }
  void add(std::string_view key, const py::object& value) { set(key_of(key).name.ptr(), value); }
  void set(PyObject* key, const py::object& value) {
    if (PyDict_SetItem(dict.ptr(), key, value.ptr()) != 0) throw py::error_already_set();
  }
};

py::dict row_dict(const Row& row, const app::ChosenCase& chosen) {
  DictSink sink;
  app::row_fields(row, chosen, sink);
  return std::move(sink.dict);
}

// The history as one NumPy array per column, named as `run --history`'s CSV columns. NumPy is
// needed here alone (Debian: python3-numpy); without it, one line naming the package.
py::dict history_arrays(const Row& row) {
  try {
    py::module_::import("numpy");
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_ImportError)) throw;
    PyErr_SetString(PyExc_ImportError,
                    "poundbench: a history needs NumPy, which is not installed (Debian: python3-numpy; pip: numpy)");
    throw py::error_already_set();
  }
  const std::vector<std::string> columns = app::history_columns(row.input);
  const History& h = row.result.history;
  const std::size_t rows = h.rows(), width = static_cast<std::size_t>(h.row_size());
  py::dict out;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    py::array_t<double> column(static_cast<py::ssize_t>(rows));
    auto values = column.mutable_unchecked<1>();
    for (std::size_t r = 0; r < rows; ++r) values(static_cast<py::ssize_t>(r)) = k < width ? h.data[r * width + k] : 0.0;
    out[py::str(columns[k])] = column;
  }
  return out;
}

// Runs `work` on the calling thread with the GIL released, with SIGINT caught by a handler of
// our own that sets `stop` (its solvers see the flag within milliseconds); when Ctrl-C came,
// the signal is handed to Python's handler afterwards (KeyboardInterrupt, or whatever the
// program's handler does). A thread started per call (std::async, polling Python's signals
// every 50 ms) cost tens of microseconds a call, more than a Moreau-Jean solve; installing
// the handler and putting Python's back per call, three rt_sigaction calls. So ours, once
// installed, stays: between calls it hands a SIGINT to the handler it replaced, and each call
// asks only whether it is still the one installed (one rt_sigaction): where Python's
// signal.signal() installed another, ours replaces that one in turn. Where SIGINT is ignored,
// or the call is not on the main thread (which alone runs Python's handlers), the work runs
// without it.
//
// Calls nest: a Python callable the sweep runs may call poundbench itself. The inner call's
// flag is the target while it runs and the outer's again after it (issue 46: the inner call
// left none, and a Ctrl-C after it raised KeyboardInterrupt inside the callable, which the
// sweep took for the callable's failure and went on); an inner call that was stopped stops
// the outer one too. A KeyboardInterrupt out of a callable stops the sweep that runs it
// (interrupt_sweep), whether SIGINT is caught here or not: `current_stop` is the innermost
// call's flag on this thread.
std::atomic<std::atomic<bool>*> interrupt_target{nullptr};
thread_local std::atomic<bool>* current_stop = nullptr;
struct sigaction replaced {};  // the handler ours replaced: Python's, unless the program set another
unsigned long main_thread = 0;  // threading.main_thread().ident, read when the module loads
extern "C" void on_interrupt(int signal, siginfo_t* info, void* context) {
  if (std::atomic<bool>* stop = interrupt_target.load()) {
    stop->store(true);
  } else if (replaced.sa_flags & SA_SIGINFO) {
    replaced.sa_sigaction(signal, info, context);
  } else if (replaced.sa_handler == SIG_DFL) {
    // As if ours had never been there: the default action, once this handler returns.
    sigaction(SIGINT, &replaced, nullptr);
    raise(SIGINT);
  } else if (replaced.sa_handler != SIG_IGN) {
    replaced.sa_handler(signal);
  }
}

// The sweep under way on this thread is to stop (a KeyboardInterrupt out of a Python callable
// it runs).
void interrupt_sweep() {
  if (current_stop) current_stop->store(true);
}

template <class Work>
void run_interruptibly(std::atomic<bool>& stop, Work&& work) {
  struct sigaction now {};
  sigaction(SIGINT, nullptr, &now);
  const bool ours = (now.sa_flags & SA_SIGINFO) && now.sa_sigaction == on_interrupt;
  const bool catching = (ours || now.sa_handler != SIG_IGN) && PyThread_get_thread_ident() == main_thread;
  std::atomic<bool>* const outer_target = interrupt_target.load();
  std::atomic<bool>* const outer = current_stop;
  current_stop = &stop;
  if (catching) {
    interrupt_target.store(&stop);
    if (!ours) {
      struct sigaction handler {};
      handler.sa_sigaction = on_interrupt;
      handler.sa_flags = SA_RESTART | SA_SIGINFO;
      sigemptyset(&handler.sa_mask);
      replaced = now;
      sigaction(SIGINT, &handler, nullptr);
    }
  }
  std::exception_ptr error;
  {
    py::gil_scoped_release release;
    try {
      std::forward<Work>(work)();
    } catch (...) {
      error = std::current_exception();
    }
  }
  current_stop = outer;
  if (catching) interrupt_target.store(outer_target);
  if (stop.load()) {
    if (outer) outer->store(true);
    if (catching) {
      PyErr_SetInterrupt();  // Python's handler, or the program's, decides
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } else {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
  }
  if (error) std::rethrow_exception(error);
}

// The class a Python callable's call is interrupted with at its time limit
// (call_deadline.hpp), made when the module loads and kept for the process.
PyObject* time_limit_exceeded = nullptr;

// A ValueError whose message may echo bytes that are not UTF-8 (a file's name): as U+FFFD,
// where pybind11's own conversion raised UnicodeDecodeError instead.
[[noreturn]] void raise_value_error(const std::string& message) {
  PyErr_SetObject(PyExc_ValueError, decoded(app::one_line(message)).ptr());
  throw py::error_already_set();
}

// The checks of the command line, raised as ValueError with its message.
template <class Check>
auto checked(Check&& check) {
  try {
    return check();
  } catch (const app::BadInput& e) {
    raise_value_error(e.what());
  } catch (const CaseSetError& e) {
    raise_value_error(e.what());
  } catch (const SettingsListError& e) {
    raise_value_error(e.what());
  }
}

// The same objects, pairwise: each the same object, or of the same type and equal; floats bit
// for bit (-0.0 is not 0.0 here, nor one NaN another).
bool same_objects(const py::list& a, const py::list& b) {
  const Py_ssize_t n = PyList_GET_SIZE(a.ptr());
  if (n != PyList_GET_SIZE(b.ptr())) return false;
  for (Py_ssize_t i = 0; i < n; ++i) {
    PyObject* x = PyList_GET_ITEM(a.ptr(), i);
    PyObject* y = PyList_GET_ITEM(b.ptr(), i);
    if (x == y) continue;
    if (Py_TYPE(x) != Py_TYPE(y)) return false;
    if (PyFloat_CheckExact(x)) {
      if (std::bit_cast<std::uint64_t>(PyFloat_AS_DOUBLE(x)) != std::bit_cast<std::uint64_t>(PyFloat_AS_DOUBLE(y)))
        return false;
      continue;
    }
    const int equal = PyObject_RichCompareBool(x, y, Py_EQ);
    if (equal < 0) throw py::error_already_set();
    if (equal == 0) return false;
  }
  return true;
}

// ---------------------------------------------------------------- the functions

// The case run()'s keywords give, as app::chosen_case gives it. Its checks by name (which
// fields the scene and pulse use, which they require, which must not be given) depend on the
// names given and the scene, pulse and directivity alone: where those are the last call's, in
// Pi terms (not a record's case, whose file is read each time), the case is the last one with
// this call's kCaseFields values (a field not given keeps Case's default in both), validated as
// chosen_case validates it. A loop over Pi terms takes this path: chosen_case was 11 k of a
// call's 53 k instructions besides the solve (callgrind), mostly its flags' strings and lookups.
app::ChosenCase case_of(const Keywords& k) {
  struct Last {
    std::vector<std::string> given;
    std::string scene, pulse, directivity;
    Case input;
  };
  static Last* last = nullptr;  // the last case checked by name, if it may be reused
  const app::CaseFlags& flags = k.case_flags;
  if (last && k.by_name_alone && k.given == last->given && flags.scene == last->scene &&
      flags.pulse == last->pulse && flags.directivity == last->directivity) {
    Case c = last->input;
    for (const CaseField& field : kCaseFields) copy_field(field, flags.numbers, c);
    if (auto bad = validate(c)) throw app::BadInput(app::case_flag_message(*bad));
    return {std::move(c), 0, {}};
  }
  app::ChosenCase chosen = app::chosen_case_or_buildings([&](std::string_view flag) { return k.has(flag); }, flags);
  if (k.by_name_alone && chosen.input.pulse != PulseShape::record && !chosen.building) {
    if (!last) last = new Last();
    *last = {k.given, flags.scene, flags.pulse, flags.directivity, chosen.input};
  } else if (last) {
    delete last;
    last = nullptr;
  }
  return chosen;
}


// JSON as Python objects: numbers, strings, null as None, lists and dicts (in their order).
py::object json_to_python(const nlohmann::ordered_json& j) {
  if (j.is_array()) {
    py::list out;
    for (const auto& x : j) out.append(json_to_python(x));
    return out;
  }
  if (j.is_object()) {
    py::dict out;
    for (const auto& [key, x] : j.items()) out[decoded(key)] = json_to_python(x);
    return out;
  }
  return to_python(j);
}

// The external solver's Settings::in_process, held for one call.
using InProcess = std::optional<std::function<std::string(const std::string&, double&)>>;

// solver=f: the Python callable as the external solver in process, held in `holder` for the
// call (callable_solver.hpp); the rows name it "python QUALNAME". Nothing without a callable.
void attach_callable(Keywords& k, InProcess& holder) {
  if (!k.callable) return;
  if (k.has("--command")) raise_value_error("--command: not with a Python callable as the solver");
  holder = CallableSolver(k.callable, time_limit_exceeded, &interrupt_sweep);
  k.solver_flags.settings.in_process = &*holder;
  k.solver_flags.settings.command = "python " + std::string(py::str(py::getattr(k.callable, "__qualname__", py::repr(k.callable))));
}

// A point of a buildings case set: the object `run --json` prints for it, as a dict
// (frontend/buildings_run.hpp). solver=f: the callable gets the scene's case document as a dict.
py::dict run_buildings(Keywords& k, const app::ChosenCase& chosen) {
  InProcess in_process;
  attach_callable(k, in_process);
  const SolverInfo* solver = checked([&] {
    if (k.has("--k-contact"))
      app::apply_buildings_k_contact(chosen.building->scene, k.solver_flags, k.k_contact, k.has("--stiffness"));
    const SolverInfo* info = &app::check_buildings_solver(k.solver_flags, k.given_flag());
    for (std::string_view flag : {"--target-error", "--monitor"})
      if (k.has(flag)) throw app::BadInput(std::string(flag) + ": not for the buildings scene (yet)");
    if (k.history || k.samples) throw app::BadInput("history: not for the buildings scene (yet)");
    return info;
  });
  std::atomic<bool> stop{false};
  Settings settings = k.solver_flags.settings;
  settings.stop = &stop;
  app::BuildingsRun result;
  run_interruptibly(stop, [&] { result = app::run_buildings(chosen, *solver, settings); });
  return json_to_python(app::buildings_json(result));
}

py::dict run(const py::kwargs& kwargs) {
  Keywords k = checked([&] { return read_keywords("run", kwargs); });
  // A case file is read once: a point of a buildings set is solved by its own path.
  std::optional<app::ChosenCase> from_file;
  if (k.has("--case-file")) {
    from_file = checked([&] { return case_of(k); });
    if (from_file->building) return run_buildings(k, *from_file);
  }
  InProcess in_process;
  attach_callable(k, in_process);
  const bool history = k.history || k.samples.has_value();
  const int samples = k.samples ? static_cast<int>(std::clamp<long long>(*k.samples, INT_MIN, INT_MAX)) : 2000;
  const auto [chosen, solver] = checked([&] {
    const app::ChosenCase c = from_file ? *from_file : case_of(k);
    if (history) {
      app::check_samples(samples, c.input);
      k.solver_flags.settings.history_samples = samples;
    }
    // k_contact as run's --k-contact: the Pi term K of --stiffness (frontend/contact_stiffness.hpp).
    const bool k_contact = k.has("--k-contact");
    if (k_contact)
      app::apply_k_contact(c.input, k.solver_flags.solver, k.solver_flags.settings, k.k_contact, k.has("--stiffness"));
    // The solver's checks of the last call, where its keywords but the case's numbers were the
    // same (a loop over Pi terms): 15 k of a call's 66 k instructions besides the solve
    // (callgrind, BM_PythonRun's call). Not with k_contact, which sets the settings from the case.
    static py::list* last_key = new py::list();  // never freed: it would outlive the interpreter
    static const SolverInfo* last_solver = nullptr;
    const SolverInfo* info = last_solver;
    // (Nor with a callable: the static key would keep it alive.)
    if (k_contact || k.callable || !info || !same_objects(*last_key, k.solver_key)) {
      const app::GivenSolverFlag given = k.given_flag();
      last_solver = nullptr;
      info = &app::checked_solver_k_contact(k.solver_flags, given, k_contact);
      if (!k_contact && !k.callable) {
        *last_key = k.solver_key;
        last_solver = info;
      }
    }
    app::check_step_bound(c.input, k.solver_flags.settings);
    return std::pair<app::ChosenCase, const SolverInfo*>(c, info);
  });
  std::atomic<bool> stop{false};
  Settings settings = k.solver_flags.settings;
  settings.stop = &stop;
  // As `run`: without monitor=True its one solve is monitored; monitor=False: not at all. As
  // `run`, a fixed-step run's error estimate is made (a companion solve at 2h).
  const bool second_pass = settings.monitor;
  if (!k.has("--monitor")) settings.monitor = true;
  Row row;
  // The no-contact Pi1 of the cases run() has seen (sweep/no_contact_cache.hpp: a hit is the
  // value a solve gives, bit for bit; bounded at about 11 MB): a loop over the contact's terms
  // (Pi3, eps, Pi5, Pi6) keeps body 0 and hits it. Solved per call it was 52 k of the call's 255 k
  // instructions besides the solve (callgrind, 2000 calls on the Fig. 4 pair through Moreau-Jean
  // at N = 64): BM_PythonRun's fixed cost, one case called again and again, 25.4 -> 21.6 us.
  static NoContactCache no_contact;
  run_interruptibly(stop, [&] {
    row = run_point(chosen.input, chosen.point, *solver, settings, 1, &no_contact, !second_pass, ErrorEstimate{.on = true});
    add_body_peaks(row, *solver, settings);
  });
  py::dict out = row_dict(row, chosen);
  if (history) out["history"] = history_arrays(row);
  return out;
}

py::list spectrum_buildings(Keywords& k, const BuildingsSet& set);

py::list spectrum(const py::object& case_set, const py::kwargs& kwargs) {
  const std::string file = text("spectrum", "case_set", case_set);
  Keywords k = checked([&] { return read_keywords("spectrum", kwargs); });
  if (const auto buildings = checked([&] { return load_buildings_set(file); }))
    return spectrum_buildings(k, *buildings);
  // A callable solver runs in process on one thread (callable_solver.hpp says why).
  InProcess in_process;
  attach_callable(k, in_process);
  if (k.callable) k.threads = 1;
  const auto [set, solver] = checked([&] {
    CaseSet s = load_case_set(file);
    app::validate_case_set(s, file);
    const SolverInfo* info = &app::checked_solver(k.solver_flags, k.given_flag());
    if (k.threads && *k.threads <= 0) throw app::BadInput("--threads: must be >= 1");
    return std::pair<CaseSet, const SolverInfo*>(std::move(s), info);
  });
  std::atomic<bool> stop{false};
  SweepOptions options;
  options.threads = k.threads ? static_cast<unsigned>(std::min<long long>(*k.threads, 4096)) : 0;
  options.cancel = &stop;
  std::vector<Row> rows;
  run_interruptibly(stop, [&] { rows = run_sweep(set.cases, *solver, k.solver_flags.settings, options); });
  py::list out;
  for (const Row& row : rows) out.append(row_dict(row, {row.input, row.point, file}));
  return out;
}

// What a work-precision study's table is, as the CLI writes it (its CSV), a dict per line, with
// numbers as numbers and empty fields as None.
py::list table_dicts(const std::string& header, const std::vector<std::string>& lines) {
  const std::vector<std::string> columns = split_csv(header);
  py::list out;
  for (const std::string& line : lines) {
    const std::vector<std::string> fields = split_csv(line);
    py::dict d;
    for (std::size_t j = 0; j < columns.size() && j < fields.size(); ++j) {
      const std::string& f = fields[j];
      double x = 0.0;
      const auto [end, error] = std::from_chars(f.data(), f.data() + f.size(), x);
      if (f.empty())
        d[py::str(columns[j])] = py::none();
      else if (error == std::errc{} && end == f.data() + f.size())
        d[py::str(columns[j])] = x == std::floor(x) && f.find_first_of(".eE") == std::string::npos
                                     ? py::object(py::int_(static_cast<long long>(x)))
                                     : py::object(py::float_(x));
      else
        d[py::str(columns[j])] = decoded(f);
    }
    out.append(d);
  }
  return out;
}

// A buildings set: the rows `spectrum` writes for it (rows/buildings_rows.hpp), a dict each.
py::list spectrum_buildings(Keywords& k, const BuildingsSet& set) {
  // A callable: in process, on one thread (callable_solver.hpp), with the scene's documents.
  InProcess in_process;
  attach_callable(k, in_process);
  if (k.callable) k.threads = 1;
  const SolverInfo* solver = checked([&] {
    const SolverInfo* info = &app::check_buildings_solver(k.solver_flags, k.given_flag());
    if (k.threads && *k.threads <= 0) throw app::BadInput("--threads: must be >= 1");
    return info;
  });
  const int threads = k.threads ? static_cast<int>(std::min<long long>(*k.threads, 4096))
                                : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<bool> stop{false};
  std::optional<std::vector<BuildingsPoint>> points;
  run_interruptibly(stop, [&] { points = sweep_buildings(set.points, *solver, k.solver_flags.settings, threads, stop, {}); });
  if (!points) {  // stopped, and the program's handler chose not to raise
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  const std::string settings = solver->describe(k.solver_flags.settings);
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < points->size(); ++i) {
    std::string text;
    append_buildings_rows(text, set.points[i], i, solver->name, settings, (*points)[i]);
    for (std::size_t a = 0, b; (b = text.find('\n', a)) != std::string::npos; a = b + 1) lines.push_back(text.substr(a, b - a));
  }
  std::string header = buildings_csv_header();
  header.pop_back();
  return table_dicts(header, lines);
}

// The program a Python callable's [[run]] names while the settings list is parsed (an
// executable that is there, so that the list's checks pass), followed by this and its name.
constexpr std::string_view kCallableMark = " poundbench-callable:";

// What a study from Python runs: its case set, its settings list (the callables' runs pointing
// at their in-process solvers, which live here), the sweep's options.
struct StudyInput {
  CaseSet set;
  SettingsList list;
  std::vector<std::function<std::string(const std::string&, double&)>> in_process;
  std::optional<long long> threads, repetitions;
  std::string out, points;  // workprecision and stress: where to write the table and every run's row
  bool has_list = false;
};

// The keywords of workprecision, stress and baseline: settings (a settings-list file, or a list of
// dicts, one per [[run]]), solvers (names of callables a run may name as its solver), threads,
// repetitions (not for baseline). settings is optional for baseline alone.
std::unique_ptr<StudyInput> read_study(const std::string& function, const py::object& case_set,
                                       const py::kwargs& kwargs) {
  auto in = std::make_unique<StudyInput>();
  const std::string file = text(function, "case_set", case_set);
  py::object runs;
  py::dict callables;
  for (const auto& [key_object, value] : kwargs) {
    const std::string key = utf8(function, "name", key_object);
    if (value.is_none()) continue;
    if (key == "settings") runs = py::reinterpret_borrow<py::object>(value);
    else if (key == "solvers") {
      if (!py::isinstance<py::dict>(value)) type_error(function, key, "must be a dict of name: callable");
      callables = value.cast<py::dict>();
    } else if (key == "threads") in->threads = whole(function, key, value);
    else if (key == "repetitions" && function != "baseline") in->repetitions = whole(function, key, value);
    else if ((key == "out" || key == "points") && function != "baseline")
      (key == "out" ? in->out : in->points) = text(function, key, value);
    else throw py::type_error(function + "() got an unexpected keyword argument '" + clip(key) + "'");
  }
  for (const auto& [name, f] : callables)
    if (!py::isinstance<py::str>(name) || !PyCallable_Check(f.ptr()))
      type_error(function, "solvers", "must map names (str) to callables");
  const std::string python = py::str(py::module_::import("sys").attr("executable"));
  std::string toml, settings_file;
  if (runs && py::isinstance<py::str>(runs)) {
    settings_file = text(function, "settings", runs);  // its runs name the registry's solvers
  } else if (runs && (py::isinstance<py::list>(runs) || py::isinstance<py::tuple>(runs))) {
    toml = "name = \"python\"\n";
    for (const py::handle& run : runs) {
      if (!py::isinstance<py::dict>(run)) type_error(function, "settings", "must be a list of dicts, one per [[run]]");
      toml += "[[run]]\n";
      for (const auto& [k, v] : run.cast<py::dict>()) {
        const std::string key = py::str(k);
        if (key == "solver" && py::isinstance<py::str>(v) && callables.contains(v)) {
          toml += "solver = \"external\"\ncommand = " +
                  toml_value(py::str(python + std::string(kCallableMark) + std::string(py::str(v))), key) + "\n";
        } else {
          toml += key + " = " + toml_value(v, key) + "\n";
        }
      }
    }
  } else if (runs || function != "baseline") {
    type_error(function, "settings", "required: a settings-list file (str) or a list of dicts, one per [[run]]");
  }
  in->has_list = !settings_file.empty() || !toml.empty();
  checked([&] {
    in->set = load_case_set(file);
    app::validate_case_set(in->set, file);
    if (in->has_list)
      in->list = settings_file.empty() ? parse_settings_list(toml, "settings") : load_settings_list(settings_file);
    if (in->threads && *in->threads <= 0) throw app::BadInput("threads: must be >= 1");
    if (in->repetitions && (*in->repetitions < 1 || *in->repetitions > kMaxRepetitions))
      throw app::BadInput("repetitions: must be from 1 to " + std::to_string(kMaxRepetitions));
    // Checked before the study runs, as the command checks --out and --points: a place that
    // cannot be written fails at once, not after the study.
    if (!in->out.empty()) app::check_output_target(in->out, "out");
    if (!in->points.empty()) app::check_output_target(in->points, "points");
    return 0;
  });
  // The callables' runs: in process, on one thread (callable_solver.hpp says why).
  in->in_process.reserve(in->list.runs.size());
  for (SweepRun& run : in->list.runs) {
    const std::size_t mark = run.settings.command.find(kCallableMark);
    if (mark == std::string::npos || run.settings.command.compare(0, mark, python) != 0) continue;
    const std::string name = run.settings.command.substr(mark + kCallableMark.size());
    in->in_process.emplace_back(CallableSolver(callables[py::str(name)], time_limit_exceeded, &interrupt_sweep));
    run.settings.in_process = &in->in_process.back();
    run.settings.command = "python " + name;
    in->threads = 1;
  }
  return in;
}

SweepOptions sweep_options(const StudyInput& in, std::atomic<bool>& stop) {
  SweepOptions options;
  options.threads = in.threads ? static_cast<unsigned>(std::min<long long>(*in.threads, 4096)) : 0;
  options.cancel = &stop;
  return options;
}

// A study's table, run by run(sweep options) until it finishes or Ctrl-C stops it, as dicts of
// the CSV its command writes (`header`, and line(row) a row).
template <class Run, class Line>
py::list study_dicts(const StudyInput& in, Run run, const std::string& header, Line line) {
  std::atomic<bool> stop{false};
  std::invoke_result_t<Run, const SweepOptions&> rows;
  run_interruptibly(stop, [&] { rows = run(sweep_options(in, stop)); });
  std::vector<std::string> lines;
  for (const auto& row : rows) lines.push_back(line(row));
  return table_dicts(header, lines);
}

// A finished study's files where out= and points= ask for them, each whole or not at all (as the
// command's --out and --points), so that a Python user can report them (`poundbench report`).
void write_study_files(const StudyInput& in, const std::function<void(std::ostream&)>& table,
                       const std::function<void(std::ostream&)>& points) {
  checked([&] {
    if (!in.out.empty()) app::write_atomically(in.out, table);
    if (!in.points.empty()) app::write_atomically(in.points, points);
    return 0;
  });
}

py::list workprecision(const py::object& case_set, const py::kwargs& kwargs) {
  const std::unique_ptr<StudyInput> in = read_study("workprecision", case_set, kwargs);
  StudyOptions study{.model_references = true};
  if (in->repetitions) study.repetitions = static_cast<int>(*in->repetitions);
  WorkPrecision wp;
  py::list table = study_dicts(
      *in,
      [&](const SweepOptions& options) {
        wp = run_work_precision(in->set.cases, in->list, options, study);
        return wp.table;
      },
      work_precision_csv_header(), &work_precision_csv_line);
  write_study_files(*in, [&](std::ostream& out) { write_work_precision_table(out, wp); },
                    [&](std::ostream& out) { write_work_precision_points(out, wp); });
  return table;
}

py::list stress(const py::object& case_set, const py::kwargs& kwargs) {
  const std::unique_ptr<StudyInput> in = read_study("stress", case_set, kwargs);
  const int repetitions = in->repetitions ? static_cast<int>(*in->repetitions) : kStudyRepetitions;
  Stress st;
  py::list table = study_dicts(
      *in,
      [&](const SweepOptions& options) {
        st = run_stress(in->set.cases, in->list, options, repetitions);
        return st.table;
      },
      stability_csv_header(), &stability_csv_line);
  write_study_files(*in, [&](std::ostream& out) { write_stress_table(out, st); },
                    [&](std::ostream& out) { write_stress_points(out, st); });
  return table;
}

// The rows a baseline file holds, as `poundbench baseline --out` writes them (a dict per row).
py::list baseline(const py::object& case_set, const py::kwargs& kwargs) {
  const std::unique_ptr<StudyInput> in = read_study("baseline", case_set, kwargs);
  const SettingsList* list = in->has_list ? &in->list : nullptr;
  return study_dicts(
      *in, [&](const SweepOptions& options) { return run_baseline(in->set.cases, list, options); }, csv_header(),
      &csv_line);
}

// `poundbench compare ROWS --baseline FILE`: a dict per comparison line.
py::list compare(const py::object& rows_file, const py::kwargs& kwargs) {
  const std::string file = text("compare", "rows", rows_file);
  std::string baseline_file;
  std::optional<double> tolerance;
  bool same_setting = false;
  for (const auto& [key_object, value] : kwargs) {
    const std::string key = utf8("compare", "name", key_object);
    if (value.is_none()) continue;
    if (key == "baseline") baseline_file = text("compare", key, value);
    else if (key == "tolerance") tolerance = number("compare", key, value);
    else if (key == "same_setting") same_setting = value.cast<bool>();
    else throw py::type_error("compare() got an unexpected keyword argument '" + clip(key) + "'");
  }
  const auto [rows, stored] = checked([&] {
    if (baseline_file.empty()) throw app::BadInput("--baseline: required");
    if (!same_setting && !tolerance) throw app::BadInput("--tolerance: required (or --same-setting)");
    if (tolerance && !(*tolerance >= 0.0 && std::isfinite(*tolerance))) throw app::BadInput("--tolerance: must be finite and >= 0");
    try {
      return std::pair(read_minimal_csv_file(file), read_csv_file(baseline_file));
    } catch (const RowReadError& e) {
      throw app::BadInput(e.what());
    }
  });
  const Match match = same_setting ? Match::same_setting : Match::reference;
  py::list out;
  for (const Comparison& c : compare_rows(rows.rows, stored.rows, match, tolerance.value_or(std::nan("")))) {
    py::dict d;
    d["family"] = decoded(c.family);
    d["solver"] = decoded(c.solver);
    d["variant"] = decoded(c.variant);
    d["settings"] = decoded(c.settings);
    d["tolerance"] = c.tolerance;
    d["compared"] = c.compared;
    d["failed"] = c.failed;
    d["unmatched"] = c.unmatched;
    d["missing"] = c.missing;
    d["max_difference"] = c.max_difference;
    d["worst_point"] = c.worst_point;
    d["passed"] = c.passed(match);
    out.append(d);
  }
  return out;
}

// "name: help" lines of a field table, for the docstrings.
template <class Table>
std::string keyword_lines(const Table& table) {
  std::string lines;
  for (const auto& f : table) lines += "    " + std::string(f.name) + ": " + std::string(f.help) + "\n";
  return lines;
}

}  // namespace

}  // namespace pb::python

PYBIND11_MODULE(poundbench, m) {
  using namespace pb;
  python::main_thread = py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  python::time_limit_exceeded = PyErr_NewExceptionWithDoc(
      "poundbench.TimeLimitExceeded",
      "Raised inside a Python callable run as a solver once its call has run to its time limit (the\n"
      "point's time_limit): a BaseException, as KeyboardInterrupt is, so that `except Exception` does\n"
      "not take it. The point's row is time-limit, whether the callable lets it through or not.",
      PyExc_BaseException, nullptr);
  if (python::time_limit_exceeded == nullptr) throw py::error_already_set();
  m.attr("TimeLimitExceeded") = py::reinterpret_borrow<py::object>(python::time_limit_exceeded);
  m.doc() = "poundbench: solve pounding cases with the project's solvers (README.md, docs/cli.md).";
  const std::string run_doc =
      "run(**keywords) -> dict\n\n"
      "Solves one case, as `poundbench run --json`: returns its object (status, message, pi1, the counts,\n"
      "the solver and settings, the case). Keywords are the command line's flags with '_' for '-':\n"
      "scene, pulse, directivity (or case_file and point), solver, variant, and\n" +
      python::keyword_lines(kCaseFields) + python::keyword_lines(kCaseAliases) +
      python::keyword_lines(kPhysicalFields) +
      "    k_contact: Compliant: contact stiffness in N/m (linear) or N/m^1.5 (Hertz family), for a case in\n"
      "      physical units; sets stiffness's Pi term K\n" + python::keyword_lines(kSettingFields) +
      "    history: True for the time history, or samples=N (default 2000; a time-stepper records every\n"
      "      step): result['history'] is a dict of NumPy arrays, one per column of `run --history`\n"
      "      (t, u1, u0, ..., lambda1).\n"
      "    monitor: True for one more, untimed solve with the time-steppers' monitor on (as --monitor);\n"
      "      by default the one solve is monitored, False: not at all.\n"
      "solver may be a Python callable f(case: dict) -> dict, the external solver in process (as in\n"
      "spectrum()): a buildings point's case is the scene's document (docs/external.md, \"The buildings\n"
      "scene\"), its answer floor_peak, drift_peak and contacts; what f raises is the failed result.\n"
      "A bad keyword value raises ValueError with the command line's message.";
  m.def("run", &python::run, run_doc.c_str());
  const std::string spectrum_doc =
      "spectrum(case_set, **keywords) -> list of dict\n\n"
      "Solves every point of a case-set file (TOML, cases/README.md) with one solver, as `poundbench\n"
      "spectrum`: one dict per point, in point order, with the keys of run()'s result (and case_file,\n"
      "point); pandas.DataFrame(rows) makes the table. A buildings case set gives one dict per floor of\n"
      "every point, with the columns of `spectrum`'s CSV for it (docs/cli.md, \"The buildings scene\").\n"
      "Keywords: solver, variant, threads (default: every\n"
      "core), monitor (as run()), persistent (True: the external solver's persistent mode), and\n" +
      python::keyword_lines(kSettingFields) +
      "solver may be a Python callable f(case: dict) -> dict, run in process on one thread: it gets the\n"
      "external protocol's case document and returns its answer (docs/external.md; 'version' may be left\n"
      "out; a buildings set's: the scene's document and answer). Each row's solve_seconds is the call's\n"
      "CPU time on its thread; what f raises is that point's failed\n"
      "row, with the exception's type and message; Ctrl-C stops the sweep. A call still running at the\n"
      "point's time limit is interrupted (TimeLimitExceeded raised in it) and, like any call that took\n"
      "longer than the limit, is that point's time-limit row.\n";
  m.def("spectrum", &python::spectrum, py::arg("case_set"), spectrum_doc.c_str());
  m.def("workprecision", &python::workprecision, py::arg("case_set"),
        "workprecision(case_set, settings=[...], solvers={}, threads=None, repetitions=None, out=None,\n"
        "              points=None) -> list of dict\n\n"
        "A work-precision study, as `poundbench workprecision`: the table it writes (its CSV), one dict per\n"
        "line. settings: a settings-list file, or a list of dicts, one per [[run]] (studies/settings_list.hpp:\n"
        "{'solver': 'moreau-jean', 'steps': [64, 256]}). solvers: names of Python callables, each usable as\n"
        "a run's solver ({'solver': 'mine', 'steps': [64, 256]}), run in process as spectrum's solver=f;\n"
        "their rows' cost (cpu_median_s) is the thread's CPU time for each call and its dicts' conversions.\n"
        "out, points: also write the table and every run's row as the command's --out and --points (whole or\n"
        "not at all), for `poundbench report OUT --points POINTS`.");
  m.def("stress", &python::stress, py::arg("case_set"),
        "stress(case_set, settings=[...], solvers={}, threads=None, repetitions=None, out=None, points=None)\n"
        "    -> list of dict\n\n"
        "The stress study, as `poundbench stress`: its table (the stability CSV), one dict per line; settings,\n"
        "solvers, out and points as workprecision's.");
  m.def("baseline", &python::baseline, py::arg("case_set"),
        "baseline(case_set, settings=None, solvers={}, threads=None) -> list of dict\n\n"
        "The rows `poundbench baseline CASESET --settings LIST --out FILE` stores, one dict per row (its CSV's\n"
        "columns); settings and solvers as workprecision's, settings optional (the reference alone).");
  m.def("compare", &python::compare, py::arg("rows"),
        "compare(rows, baseline=FILE, tolerance=None, same_setting=False) -> list of dict\n\n"
        "`poundbench compare ROWS --baseline FILE`: a dict per comparison line (family, solver, variant,\n"
        "settings, tolerance, compared, failed, unmatched, missing, max_difference, worst_point, passed).");
  m.def(
      "solvers",
      [] {
        py::list names;
        for (const SolverInfo& s : solvers()) names.append(py::str(std::string(s.name)));
        return names;
      },
      "The names of the solvers this build has (`poundbench solvers` describes them).");
}
