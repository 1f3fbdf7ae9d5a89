#include "programs/protocol.hpp"
#include "programs/json_reading.hpp"

#include <algorithm>
#include <chrono>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/load.hpp"
#include "cases/physical.hpp"
#include "cases/record.hpp"
#include "cases/text.hpp"
#include "rows/result_fields.hpp"

namespace pb::programs {

// The reading of a document with its fields named (programs/json_reading.hpp), shared with the
// buildings scene's answer (programs/buildings_answer.cpp).
namespace reading {

// How deep a document may nest (parse_object), and how long an answer's message may be: a
// message is shown in a row, and a program's message of 100 MB was 528 MB resident.
constexpr int kMaxDepth = 16;  // (kMaxMessageBytes: json_reading.hpp)

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------- reading, with field names

[[noreturn]] void bad(const std::string& field, const std::string& why) { throw std::invalid_argument(field + ": " + why); }

const Json& member(const Json& object, const std::string& key, const std::string& field) {
  const auto it = object.find(key);
  if (it == object.end()) bad(field, "missing");
  return *it;
}

double number(const Json& j, const std::string& field) {
  if (!j.is_number()) bad(field, "must be a number");
  const double x = j.get<double>();
  if (!std::isfinite(x)) bad(field, "must be finite");
  return x;
}

long whole(const Json& j, const std::string& field) {
  if (!j.is_number_integer() || j.get<long long>() < 0) bad(field, "must be a whole number >= 0");
  return static_cast<long>(j.get<long long>());
}

// An optional number: absent or null is nullopt.
// (By string_view: a literal key made a std::string per look-up, 15 an answer.)
std::optional<double> maybe_number(const Json& object, std::string_view key) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  if (it->is_number())
    if (const double x = it->get<double>(); std::isfinite(x)) return x;
  return number(*it, std::string(key));  // throws, naming the field
}

void check_version(const Json& doc) {
  if (const auto it = doc.find("protocol"); it != doc.end() && *it != kProtocol)
    bad("protocol", "must be \"" + std::string(kProtocol) + "\"");
  const Json& version = member(doc, "version", "version");
  if (!version.is_number_integer() || version.get<long long>() != kVersion)
    bad("version", "must be " + std::to_string(kVersion) + " (it is " + clip(version.dump()) + ")");
}

// The DOM of a document, built from nlohmann's parser's events (its SAX interface) as its own
// DOM parser builds it, with parse_object's checks made as the events come: a key seen twice
// in its object, a level too deep, and, every 4096 events, the deadline. The parser's callback
// made them before, on a DOM its callback parser built: a JSON value made for every key to
// call it with, and a hashed set of the keys per object, 16,000 instructions for an answer of
// four keys (a persistent sweep through a program that answers at once: issue 46). Here an
// object's keys are looked up in the object itself. The events counted and the order of the
// checks are the callback's.
class CheckedDom {
 public:
  CheckedDom(Json& root, const char* what, Clock::time_point deadline, std::size_t bytes)
      : root_(root), what_(what), deadline_(deadline), bytes_(bytes) {}

  bool null() { return value(nullptr); }
  bool boolean(bool b) { return value(b); }
  bool number_integer(Json::number_integer_t n) { return value(n); }
  bool number_unsigned(Json::number_unsigned_t n) { return value(n); }
  bool number_float(Json::number_float_t x, const Json::string_t&) { return value(x); }
  bool string(Json::string_t& text) { return value(text); }
  bool binary(Json::binary_t& bytes) { return value(std::move(bytes)); }
  bool start_object(std::size_t) { return open(Json::value_t::object); }
  bool key(Json::string_t& key) {
    event();
    Json& object = *stack_.back();
    if (object.contains(key)) bad(what_, "key \"" + clip(key) + "\" given twice in one object");
    element_ = &object[key];
    return true;
  }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(Json::value_t::array); }
  bool end_array() { return close(); }
  // The parser's own error, thrown as its DOM parser throws it (the same message).
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception& error) {
    throw error;
  }

 private:
  void event() {
    if (++events_ % 4096 == 0 && Clock::now() > deadline_)
      bad(what_, "still being read at the time limit (" + std::to_string(bytes_) + " bytes)");
  }
  // Where a value goes: the root, the end of the open array, or the key just read.
  template <class Value>
  Json* place(Value&& v) {
    if (stack_.empty()) {
      root_ = Json(std::forward<Value>(v));
      return &root_;
    }
    if (stack_.back()->is_array()) {
      stack_.back()->push_back(Json(std::forward<Value>(v)));
      return &stack_.back()->back();
    }
    *element_ = Json(std::forward<Value>(v));
    return element_;
  }
  template <class Value>
  bool value(Value&& v) {
    event();
    place(std::forward<Value>(v));
    return true;
  }
  bool open(Json::value_t type) {
    event();
    if (static_cast<int>(stack_.size()) >= kMaxDepth)
      bad(what_, "nested more than " + std::to_string(kMaxDepth) + " levels deep");
    stack_.push_back(place(type));
    return true;
  }
  bool close() {
    event();
    stack_.pop_back();
    return true;
  }

  Json& root_;
  const char* what_;
  Clock::time_point deadline_;
  std::size_t bytes_;
  std::vector<Json*> stack_;  // the open objects and arrays
  Json* element_ = nullptr;   // the value of the key just read
  std::size_t events_ = 0;
};

// A document as the protocol reads it: one JSON object, no key twice in an object
// (nlohmann keeps the last one, and "status":"failed","status":"ok" read as ok), nested at
// most kMaxDepth deep (a document's own depth is 3 or 4: a 40 MB answer of nested arrays
// took 13.7 s and 1.5 GB to parse), and parsed by `deadline` (a long answer is read within
// the run's time limit, not after it). CheckedDom sees every event, so the parse stops at
// the first key seen twice, the first level too deep, or the first look at the clock past
// the deadline.
Json parse_object(std::string_view text, const char* what, Clock::time_point deadline) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
    bad(what, "empty (one JSON document is expected)");
  Json doc;
  CheckedDom dom(doc, what, deadline, text.size());
  try {
    Json::sax_parse(text, &dom);
  } catch (const Json::exception& e) {
    bad(what, "not one JSON document (" + clip(e.what(), kMaxEchoedReason) + ")");
  }
  if (!doc.is_object()) bad(what, "must be a JSON object");
  return doc;
}

}  // namespace reading

namespace {

using namespace reading;
using Ordered = nlohmann::ordered_json;

// NaN and infinity have no JSON spelling: null says "no value".
Ordered number_or_null(double x) { return std::isfinite(x) ? Ordered(x) : Ordered(nullptr); }

// ---------------------------------------------------------------- the answer

// Whether key is one of an answer's: its own (protocol, version, history) or a result field's
// (rows/result_fields.hpp). Anything else is a typo that would go unseen (a "pi_1").
bool answer_key(std::string_view key) {
  if (key == "protocol" || key == "version" || key == "history") return true;
  return std::any_of(kResultFields.begin(), kResultFields.end(), [&](const ResultField& f) { return f.answer == key; });
}

struct U0History {
  std::vector<double> t, u0;
};

U0History read_history(const Json& h) {
  if (!h.is_object()) bad("history", "must be an object with arrays t and u0");
  for (const auto& [key, value] : h.items())
    if (key != "t" && key != "u0") bad("history." + clip(key), "unknown key (version 1 has t and u0)");
  U0History out;
  for (const char* key : {"t", "u0"}) {
    const std::string field = std::string("history.") + key;
    const Json& values = member(h, key, field);
    if (!values.is_array()) bad(field, "must be an array of numbers");
    const bool u0 = std::string_view(key) == "u0";
    auto& into = u0 ? out.u0 : out.t;
    into.reserve(values.size());
    // A null u0: a value the program does not have (a NaN); Pi1 is never taken from one.
    for (const Json& x : values) into.push_back(u0 && x.is_null() ? kNaN : number(x, field));
  }
  if (out.t.size() != out.u0.size())
    bad("history", "t and u0 must have the same length (" + std::to_string(out.t.size()) + " and " +
                       std::to_string(out.u0.size()) + ")");
  return out;
}

void fill_answer(const Json& doc, const System& s, const Settings& settings, Result& r) {
  for (const auto& [key, value] : doc.items())
    if (!answer_key(key)) bad(clip(key), "unknown key (docs/external.md lists an answer's keys)");
  check_version(doc);
  const Json& status = member(doc, "status", "status");
  const std::optional<Status> parsed = status.is_string() ? parse_status(status.get<std::string>()) : std::nullopt;
  if (!parsed || *parsed == Status::penetration || *parsed == Status::energy)
    bad("status", "must be one of ok, diverged, nan, step_cap, time-limit, failed (it is " + clip(status.dump()) + ")");
  r.status = *parsed;
  if (const auto it = doc.find("message"); it != doc.end() && !it->is_null()) {
    if (!it->is_string()) bad("message", "must be a string");
    r.message = it->get<std::string>();
    if (r.message.size() > kMaxMessageBytes)
      bad("message", std::to_string(r.message.size()) + " bytes, more than " + std::to_string(kMaxMessageBytes) +
                         " (a message is shown in a row: put long output on stderr)");
  }
  // The numbers and counts of the result fields an answer carries, as the solver has them.
  for (const ResultField& f : kResultFields) {
    if (f.answer.empty() || !(f.real || f.whole)) continue;
    const std::string key(f.answer);
    const auto it = doc.find(key);
    if (it == doc.end() || it->is_null()) continue;
    if (f.whole)
      r.*f.whole = whole(*it, key);
    else
      r.*f.real = number(*it, key);
  }
  // A yielding case's answer says what the bilinear law left (never an elastic answer
  // passed off as the yielding one): a program that does not apply it answers failed.
  if (s.yields() && r.status == Status::ok && (std::isnan(r.residual) || std::isnan(r.hysteretic)))
    bad("residual", "a yielding case (bodies[].u_y) needs residual and hysteretic with status ok; a program that "
                    "does not apply the bilinear law answers status failed");
  if (!std::isnan(r.solve_seconds) && !(r.solve_seconds >= 0.0 && std::isfinite(r.solve_seconds)))
    bad("solve_seconds", "must be a number of seconds >= 0");
  if (const auto step = doc.find("step"); step != doc.end() && !step->is_null() && !(r.step > 0.0 && r.step <= s.t_end))
    bad("step", "must be > 0 and at most t_end (a step of the run)");

  // Times of the run: 0 to t_end, and a time-stepper's last step may end past t_end by up to
  // a step (the fixed_step.hpp shell's rule), so a Pi1 is never taken from outside the run.
  const double t_last = s.t_end + (std::isfinite(r.step) ? r.step : 0.0) + 1e-9 * s.t_end;
  const auto in_run = [&](double t) { return t >= 0.0 && t <= t_last; };
  const auto run_times = [&] {  // made only for an error: t_end's shortest text is 1,000 instructions
    return "must be within the run, 0 to t_end = " + format_number(s.t_end) +
           (std::isfinite(r.step) ? " (plus one step)" : "");
  };
  U0History history;
  if (const auto it = doc.find("history"); it != doc.end() && !it->is_null()) history = read_history(*it);
  for (std::size_t i = 0; i < history.t.size(); ++i) {
    const auto field = [i] { return "history.t[" + std::to_string(i) + "]"; };
    if (!in_run(history.t[i])) bad(field(), run_times() + " (it is " + format_number(history.t[i]) + ")");
    if (i > 0 && history.t[i] < history.t[i - 1])
      bad(field(), "goes back from the time before it (times must not fall)");
  }
  if (!std::isnan(r.t_max) && !in_run(r.t_max)) bad("t_max", run_times() + " (it is " + format_number(r.t_max) + ")");
  if (std::isnan(r.pi1) && !history.u0.empty() && r.status == Status::ok) {
    if (std::any_of(history.u0.begin(), history.u0.end(), [](double u) { return !std::isfinite(u); }))
      bad("history.u0", "status ok needs a finite u0 at every time to take pi1 from");
    const auto peak = std::max_element(history.u0.begin(), history.u0.end(),
                                       [](double a, double b) { return std::abs(a) < std::abs(b); });
    r.pi1 = s.pi1(std::abs(*peak));
    r.t_max = history.t[static_cast<std::size_t>(peak - history.u0.begin())];
  }
  if (r.status == Status::ok && !(r.pi1 >= 0.0))
    bad("pi1", "status ok needs pi1 >= 0, or a history of u0 to take it from");
  // A run that did not end ok has no Pi1, whatever the program says (as every solver).
  if (r.status != Status::ok) r.pi1 = r.t_max = kNaN;

  if (settings.history_samples > 0 && !history.t.empty()) {
    // Version 1 carries u0 alone: the other columns of the history are unknown (NaN).
    History& h = r.history;
    h.n_bodies = s.n_bodies();
    h.n_contacts = s.n_contacts();
    const auto width = static_cast<std::size_t>(h.row_size());
    h.data.assign(history.t.size() * width, kNaN);
    for (std::size_t i = 0; i < history.t.size(); ++i) {
      h.data[i * width] = history.t[i];
      h.data[i * width + 1 + static_cast<std::size_t>(s.ref)] = history.u0[i];
    }
  }
}

// ---------------------------------------------------------------- the case, read back

std::optional<PulseShape> shape_of(const Json& j) {
  return j.is_string() ? parse_pulse(j.get<std::string>()) : std::nullopt;
}

void read_bodies(const Json& doc, System& s) {
  const Json& bodies = member(doc, "bodies", "bodies");
  if (!bodies.is_array() || bodies.empty()) bad("bodies", "must be a non-empty array");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string field = "bodies[" + std::to_string(i) + "]";
    const Json& b = bodies[i];
    if (!b.is_object()) bad(field, "must be an object");
    Body body{};
    body.m = number(member(b, "m", field + ".m"), field + ".m");
    body.k = number(member(b, "k", field + ".k"), field + ".k");
    body.c = number(member(b, "c", field + ".c"), field + ".c");
    body.w = number(member(b, "w", field + ".w"), field + ".w");
    if (!(body.m > 0.0)) bad(field + ".m", "must be > 0");
    if (const auto u_y = maybe_number(b, "u_y")) {
      if (!(*u_y > 0.0)) bad(field + ".u_y", "must be > 0 (absent: elastic)");
      body.u_y = *u_y;
    }
    s.bodies.push_back(body);
    s.u_start.push_back(number(member(b, "u", field + ".u"), field + ".u"));
    s.v_start.push_back(number(member(b, "v", field + ".v"), field + ".v"));
  }
  const Json& ref = member(doc, "reference", "reference");
  if (!ref.is_number_integer() || ref.get<long long>() < 0 ||
      ref.get<long long>() >= static_cast<long long>(bodies.size()))
    bad("reference", "must be the index of a body");
  s.ref = ref.get<int>();
}

// The contacts of a System: a wall's first (left null), then each body with its right
// neighbour, all with one gap. A program may take any list; poundbench writes these.
void read_contacts(const Json& doc, System& s) {
  const Json& contacts = member(doc, "contacts", "contacts");
  if (!contacts.is_array()) bad("contacts", "must be an array");
  s.wall = !contacts.empty() && contacts[0].is_object() && contacts[0].contains("left") && contacts[0]["left"].is_null();
  if (static_cast<int>(contacts.size()) != s.n_contacts())
    bad("contacts", "poundbench's systems join each body to its right neighbour (and body 0 of a wall scene to "
                    "the wall): " + std::to_string(s.n_contacts()) + " contacts here");
  for (int j = 0; j < s.n_contacts(); ++j) {
    const std::string field = "contacts[" + std::to_string(j) + "]";
    const Json& c = contacts[static_cast<std::size_t>(j)];
    if (!c.is_object()) bad(field, "must be an object");
    const Json& left = member(c, "left", field + ".left");
    const Json& right = member(c, "right", field + ".right");
    const bool left_ok = s.left(j) == kWall ? left.is_null() : left == s.left(j);
    if (!left_ok || right != s.right(j))
      bad(field, "must join bodies " + (s.left(j) == kWall ? std::string("null (the wall)") : std::to_string(s.left(j))) +
                     " and " + std::to_string(s.right(j)));
    const double gap = number(member(c, "gap", field + ".gap"), field + ".gap");
    if (j > 0 && gap != s.delta) bad(field + ".gap", "every contact of a poundbench system has the same gap");
    s.delta = gap;
  }
}

std::vector<double> numbers(const Json& j, const std::string& field) {
  if (!j.is_array()) bad(field, "must be an array of numbers");
  std::vector<double> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) out.push_back(number(j[i], field + "[" + std::to_string(i) + "]"));
  return out;
}

// {"kind": "record", "t": [...], "a": [...]}: the samples, a_g signed and in the case's units.
void read_record_load(const Json& load, System& s) {
  s.pulse.shape = PulseShape::record;
  s.pulse.amplitude = 1.0;
  s.pulse.w = number(member(load, "w", "load.w"), "load.w");
  if (!(s.pulse.w > 0.0)) bad("load.w", "must be > 0");
  const auto source = load.find("source");
  const std::string name = source != load.end() && source->is_string() ? source->get<std::string>() : "load";
  try {
    s.pulse.record = std::make_shared<const Record>(record_from_samples(
        numbers(member(load, "t", "load.t"), "load.t"), numbers(member(load, "a", "load.a"), "load.a"), name));
  } catch (const RecordError& e) {
    bad("load.t", e.what());
  }
}

// {"kind": "sinusoids", "shape": ..., "w": w_p, "duration": T, "terms": [{"w", "sin", "cos"}]}.
void read_sinusoid_load(const Json& load, System& s) {
  const std::optional<PulseShape> shape = shape_of(member(load, "shape", "load.shape"));
  if (!shape || paper_pulse(*shape) || *shape == PulseShape::record)
    bad("load.shape", "must be makris-a, makris-b, makris-c or mp");
  s.pulse.shape = *shape;
  s.pulse.amplitude = number(member(load, "amplitude", "load.amplitude"), "load.amplitude");
  s.pulse.w = number(member(load, "w", "load.w"), "load.w");
  if (!(s.pulse.w > 0.0)) bad("load.w", "must be > 0");
  s.pulse.length = number(member(load, "duration", "load.duration"), "load.duration");
  if (!(s.pulse.length > 0.0)) bad("load.duration", "must be > 0");
  const Json& terms = member(load, "terms", "load.terms");
  if (!terms.is_array() || terms.empty() || terms.size() > static_cast<std::size_t>(kMaxSinusoids))
    bad("load.terms", "must be an array of 1 to " + std::to_string(kMaxSinusoids) + " terms");
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const std::string field = "load.terms[" + std::to_string(i) + "]";
    if (!terms[i].is_object()) bad(field, "must be an object");
    Sinusoid& w = s.pulse.waves[i];
    w.w = number(member(terms[i], "w", field + ".w"), field + ".w");
    if (!(w.w > 0.0)) bad(field + ".w", "must be > 0");
    w.s = number(member(terms[i], "sin", field + ".sin"), field + ".sin");
    w.c = number(member(terms[i], "cos", field + ".cos"), field + ".cos");
  }
  s.pulse.n_waves = static_cast<int>(terms.size());
  // The model's own parameters, for what the case was (the terms are the load).
  if (load.contains("cycles") && load["cycles"].is_number_integer()) s.pulse.cycles = load["cycles"].get<int>();
  if (load.contains("mp_gamma")) s.pulse.mp_gamma = number(load["mp_gamma"], "load.mp_gamma");
  if (load.contains("mp_nu")) s.pulse.mp_nu = number(load["mp_nu"], "load.mp_nu");
}

void read_load(const Json& doc, System& s) {
  const Json& load = member(doc, "load", "load");
  if (!load.is_object()) bad("load", "must be an object");
  const Json& kind = member(load, "kind", "load.kind");
  if (kind == "record") return read_record_load(load, s);
  if (kind == "sinusoids") return read_sinusoid_load(load, s);
  if (kind != "pulse")
    bad("load.kind", clip(kind.dump()) + " is not a kind this program knows (it knows \"pulse\", \"sinusoids\", \"record\")");
  const std::optional<PulseShape> shape = shape_of(member(load, "shape", "load.shape"));
  if (!shape || !paper_pulse(*shape)) bad("load.shape", "must be \"sine\" or \"cosine\"");
  s.pulse.shape = *shape;
  s.pulse.amplitude = number(member(load, "amplitude", "load.amplitude"), "load.amplitude");
  s.pulse.w = number(member(load, "w", "load.w"), "load.w");
  if (!(s.pulse.w > 0.0)) bad("load.w", "must be > 0");
}

// ---------------------------------------------------------------- the case's schema and domain

// The keys case.schema.json allows, per object: anything else is refused, as the schema's
// additionalProperties false says (a misspelt "eps " would leave the program's default).
void only_keys(const Json& object, const std::string& field, std::initializer_list<std::string_view> keys) {
  if (!object.is_object()) return;  // the readers say what it must be
  for (const auto& [key, value] : object.items())
    if (std::find(keys.begin(), keys.end(), key) == keys.end())
      bad((field.empty() ? "" : field + ".") + clip(key), "unknown key (docs/external/case.schema.json)");
}

void check_case_keys(const Json& doc) {
  only_keys(doc, "", {"protocol", "version", "bodies", "reference", "contacts", "eps", "xi", "load", "a_p",
                      "length_scale", "t_end", "t_min", "step", "steps_per_period", "step_cap", "time_limit",
                      "history_samples", "monitor", "alpha"});
  if (const auto b = doc.find("bodies"); b != doc.end() && b->is_array())
    for (std::size_t i = 0; i < b->size(); ++i)
      only_keys((*b)[i], "bodies[" + std::to_string(i) + "]", {"m", "k", "c", "w", "u", "v", "u_y"});
  if (const auto c = doc.find("contacts"); c != doc.end() && c->is_array())
    for (std::size_t i = 0; i < c->size(); ++i)
      only_keys((*c)[i], "contacts[" + std::to_string(i) + "]", {"left", "right", "gap"});
  if (const auto load = doc.find("load"); load != doc.end() && load->is_object()) {
    const auto kind = load->find("kind");
    if (kind != load->end() && *kind == "record") only_keys(*load, "load", {"kind", "source", "w", "t", "a"});
    else if (kind != load->end() && *kind == "sinusoids")
      only_keys(*load, "load", {"kind", "shape", "amplitude", "w", "duration", "terms", "cycles", "mp_gamma", "mp_nu"});
    else only_keys(*load, "load", {"kind", "shape", "amplitude", "w", "duration"});
  }
}

// Equal to what poundbench writes, up to a hand-written document's rounding.
bool close_to(double x, double expected) { return std::abs(x - expected) <= 1e-9 * std::abs(expected); }

// The valid domain of cases (cases/README.md), in the document's physical terms: a document
// is answered only when it describes a case poundbench itself could send. Outside it the
// engines fail in ways no answer can report (ODE aborted on a mass of 5e-324, Siconos on
// a_p = 0, LSODAR on a_p = 1e300; w_p = 1e300 gave "ok" with no Pi1).
void check_case_domain(const Json& doc, const System& s) {
  for (const char* key : {"length_scale", "step", "steps_per_period", "step_cap", "time_limit", "history_samples",
                          "monitor"})
    member(doc, key, key);  // required, as the schema has them (null where it allows null)
  if (!(s.eps >= 0.0 && s.eps <= 1.0)) bad("eps", "must be in [0, 1]");
  if (!(s.xi >= 0.0 && s.xi < 1.0)) bad("xi", "must be in [0, 1)");
  if (!(s.a_p >= kMinAp && s.a_p <= kMaxAp)) bad("a_p", "must be in [1e-12, 1e12] (the valid domain, cases/README.md)");
  const double w_p = s.pulse.w;
  if (!(w_p >= kMinWp && w_p <= kMaxWp)) bad("load.w", "must be in [1e-6, 1e6] (the valid domain, cases/README.md)");
  const double length = s.a_p / (w_p * w_p);
  if (!close_to(number(doc.at("length_scale"), "length_scale"), length)) bad("length_scale", "must be a_p / w_p^2");
  if (!(s.delta >= 0.0)) bad("contacts.gap", "must be >= 0");
  if (s.delta > kMaxPi3 * length) bad("contacts.gap", "must be at most 1e6 a_p / w_p^2 (Pi3 <= 1e6)");
  double w_lo = w_p, w_hi = w_p, m_lo = s.bodies.front().m, m_hi = m_lo;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Body& b = s.bodies[i];
    const std::string field = "bodies[" + std::to_string(i) + "]";
    if (!(b.w > 0.0)) bad(field + ".w", "must be > 0");
    if (!close_to(b.k, b.m * b.w * b.w)) bad(field + ".k", "must be m w^2");
    if (!close_to(b.c, 2.0 * s.xi * b.m * b.w)) bad(field + ".c", "must be 2 xi m w");
    if (std::abs(s.u_start[i]) > 1e6 * length) bad(field + ".u", "must be within 1e6 a_p / w_p^2 of rest");
    if (std::abs(s.v_start[i]) > kMaxKick * s.a_p / w_p) bad(field + ".v", "must be within 1e6 a_p / w_p");
    w_lo = std::min(w_lo, b.w), w_hi = std::max(w_hi, b.w), m_lo = std::min(m_lo, b.m), m_hi = std::max(m_hi, b.m);
  }
  if (w_hi / w_lo > kMaxFrequencyContrast)
    bad("bodies", "the frequencies and w_p span a contrast of " + format_number(w_hi / w_lo) + ", more than 1e4");
  if (m_hi / m_lo > kMaxMassContrast)
    bad("bodies", "the masses span a contrast of " + format_number(m_hi / m_lo) + ", more than 1e6");
  // poundbench's masses are m0 = 1 and its contrasts; a program's own may be in kg.
  if (!(m_lo >= 1e-12 && m_hi <= 1e12)) bad("bodies", "masses must be in [1e-12, 1e12]");
  const double t_p = 2.0 * std::numbers::pi / w_p, t_min = std::min(t_p, 2.0 * std::numbers::pi / w_hi);
  if (!close_to(s.t_min, t_min)) bad("t_min", "must be min(T_p, the shortest natural period)");
  if (s.t_end / s.t_min > kMaxPeriodsPerRun) bad("t_end", "must be at most 1e6 t_min (the valid domain)");
  const Pulse& p = s.pulse;
  if (p.paper()) {
    if (!close_to(std::abs(p.amplitude), s.a_p)) bad("load.amplitude", "must be a_p or -a_p");
    if (!close_to(number(member(doc.at("load"), "duration", "load.duration"), "load.duration"), t_p))
      bad("load.duration", "must be 2 pi / w");
  } else if (!p.record) {
    if (p.length > s.t_end) bad("load.duration", "must be within the run (at most t_end)");
    for (int j = 0; j < p.n_waves; ++j) {
      const Sinusoid& wave = p.waves[static_cast<std::size_t>(j)];
      const std::string field = "load.terms[" + std::to_string(j) + "]";
      if (wave.w > kMaxFrequencyContrast * w_p || wave.w * kMaxFrequencyContrast < w_p)
        bad(field + ".w", "must be within a factor 1e4 of w_p");
      if (std::abs(wave.s) > 10.0 * s.a_p || std::abs(wave.c) > 10.0 * s.a_p)
        bad(field, "sin and cos must be at most 10 a_p (the models' are at most a_p)");
    }
  }
  if (p.record) {
    if (!(p.record->peak >= kMinRecordPeak * s.a_p && p.record->peak <= kMaxRecordPeak * s.a_p))
      bad("load.a", "the record's peak must be within a factor 1e6 of a_p (the valid domain)");
    if (p.record->length() > s.t_end) bad("load.t", "must end within the run (at most t_end)");
  }
}

}  // namespace

// read_case without its guard against the JSON library's own exceptions.
static CaseRead read_case_document(std::string_view text);

// case_document: programs/case_document.cpp.

std::string read_answer(std::string_view text, const System& system, const Settings& settings, Result& result,
                        std::chrono::steady_clock::time_point deadline) {
  Result r;
  r.step = result.step;  // the step sent, unless the answer says otherwise
  try {
    fill_answer(parse_object(text, "stdout", deadline), system, settings, r);
  } catch (const std::invalid_argument& e) {
    return std::string("answer: ") + e.what();
  } catch (const Json::exception& e) {  // a type the reader did not foresee
    return "answer: " + clip(e.what(), kMaxEchoedReason);
  }
  result = std::move(r);
  return {};
}

std::string ready_line_problem(std::string_view line) {
  std::string why;
  try {
    const Json doc = parse_object(line, "ready line");
    const auto ready = doc.find("ready");
    const auto version = doc.find("version");
    if (ready == doc.end() || *ready != true) why = "\"ready\" must be true";
    else if (version == doc.end() || *version != kVersion) why = "\"version\" must be " + std::to_string(kVersion);
  } catch (const std::invalid_argument& e) {
    why = e.what();
  }
  if (why.empty()) return {};
  return "its first line must be {\"version\": 1, \"ready\": true} (persistent mode), not '" + clip(line, 200) +
         "': " + why;
}

namespace {

// The code point of the UTF-8 sequence at text[i], its length in `size`; -1 where the bytes
// there are no valid UTF-8 (a stray continuation byte, a sequence cut short, an overlong
// form, a surrogate, a value past U+10FFFF), `size` then 1.
long next_code_point(std::string_view text, std::size_t i, std::size_t& size) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  size = 1;
  if (lead < 0x80) return lead;
  std::size_t length = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 0;
  if (length == 0 || lead > 0xF4 || i + length > text.size()) return -1;
  long cp = lead & (0x7F >> length);
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return -1;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  constexpr long kShortest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kShortest[length] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return -1;
  size = length;
  return cp;
}

// What a row must not carry even as valid UTF-8: control characters, line and paragraph
// separators, and format characters that change how the text around them shows.
bool unprintable(long cp) {
  return cp < 0x20 || (cp >= 0x7F && cp <= 0x9F) || (cp >= 0x200B && cp <= 0x200F) ||
         (cp >= 0x2028 && cp <= 0x202E) || (cp >= 0x2060 && cp <= 0x206F) || cp == 0xFEFF;
}

}  // namespace

std::string printable_line(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0, size = 1; i < text.size(); i += size) {
    const long cp = next_code_point(text, i, size);
    if (cp < 0) out += "\xEF\xBF\xBD";  // U+FFFD
    else if (unprintable(cp)) out += '?';
    else out.append(text.substr(i, size));
  }
  return out;
}

CaseRead read_case(std::string_view text) {
  try {
    return read_case_document(text);
  } catch (const Json::exception& e) {  // a type the reader did not foresee: still one line
    bad("stdin", clip(e.what(), kMaxEchoedReason));
  }
}

static CaseRead read_case_document(std::string_view text) {
  const Json doc = parse_object(text, "stdin");
  check_case_keys(doc);
  check_version(doc);
  CaseRead out;
  System& s = out.system;
  read_bodies(doc, s);
  read_contacts(doc, s);
  read_load(doc, s);
  s.eps = number(member(doc, "eps", "eps"), "eps");
  s.xi = number(member(doc, "xi", "xi"), "xi");
  s.alpha = maybe_number(doc, "alpha").value_or(0.0);
  if (!(s.alpha >= 0.0 && s.alpha < 1.0)) bad("alpha", "must be in [0, 1)");
  s.a_p = number(member(doc, "a_p", "a_p"), "a_p");
  s.t_end = number(member(doc, "t_end", "t_end"), "t_end");
  s.t_min = number(member(doc, "t_min", "t_min"), "t_min");
  if (!(s.t_end > 0.0)) bad("t_end", "must be > 0");
  if (!(s.t_min > 0.0)) bad("t_min", "must be > 0");

  Settings& set = out.settings;
  if (const auto n = doc.find("steps_per_period"); n != doc.end() && !n->is_null()) {
    if (!n->is_number_integer() || n->get<long long>() < 1 || n->get<long long>() > 1'000'000'000)
      bad("steps_per_period", "must be a whole number from 1 to 1e9, or null");
    set.steps = n->get<int>();
  } else if (const auto h = maybe_number(doc, "step")) {
    if (!(*h > 0.0)) bad("step", "must be > 0, or null");
    set.wh = step_pi_term(s, *h);
  }
  if (const auto cap = doc.find("step_cap"); cap != doc.end()) set.step_cap = whole(*cap, "step_cap");
  if (const auto limit = maybe_number(doc, "time_limit")) {
    if (!(*limit >= 0.0 && *limit <= 1e9)) bad("time_limit", "must be in [0, 1e9] seconds (0: none)");
    set.time_limit = *limit;
  }
  if (const auto samples = doc.find("history_samples"); samples != doc.end()) {
    const long n = whole(*samples, "history_samples");
    if (n > 1'000'000) bad("history_samples", "must be <= 1e6");
    set.history_samples = static_cast<int>(n);
  }
  if (const auto monitor = doc.find("monitor"); monitor != doc.end()) {
    if (!monitor->is_boolean()) bad("monitor", "must be true or false");
    set.monitor = monitor->get<bool>();
  }
  check_case_domain(doc, s);
  return out;
}

std::string answer_document(const Result& r, const System& s) {
  Ordered j;
  j["protocol"] = kProtocol;
  j["version"] = kVersion;
  j["status"] = name(r.status);
  j["message"] = r.message;
  // The result fields an answer carries (rows/result_fields.hpp); residual and hysteretic
  // only for a yielding case.
  for (const ResultField& f : kResultFields) {
    if (f.answer.empty() || !(f.real || f.whole)) continue;
    if (!s.yields() && (f.real == &Result::residual || f.real == &Result::hysteretic)) continue;
    if (f.whole)
      j[std::string(f.answer)] = r.*f.whole;
    else
      j[std::string(f.answer)] = number_or_null(r.*f.real);
  }
  const History& h = r.history;
  if (h.rows() > 0 && h.n_bodies == s.n_bodies()) {
    Ordered t = Ordered::array(), u0 = Ordered::array();
    const auto width = static_cast<std::size_t>(h.row_size());
    for (std::size_t i = 0; i < h.rows(); ++i) {
      t.push_back(h.data[i * width]);
      u0.push_back(number_or_null(h.data[i * width + 1 + static_cast<std::size_t>(s.ref)]));
    }
    j["history"] = {{"t", std::move(t)}, {"u0", std::move(u0)}};
  }
  return j.dump(-1, ' ', false, Ordered::error_handler_t::replace) + '\n';
}

}  // namespace pb::programs
