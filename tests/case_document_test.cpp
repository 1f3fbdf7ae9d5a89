// The case document (programs/case_document.cpp) is written straight out as text; these tests
// hold it to the bytes it had as an nlohmann::ordered_json built up and dumped (the builder
// below is that code, kept as the reference), on every shipped case set and on numbers and
// strings the sets do not have.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/case_set.hpp"
#include "cases/load.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "programs/protocol.hpp"
#include "cases/buildings_set.hpp"
#include "kit/testing.hpp"

namespace pb {
namespace {

using Ordered = nlohmann::ordered_json;

// ---------------------------------------------------------------- the document as it was built

Ordered load_as_built(const Pulse& p) {
  if (p.paper())
    return {{"kind", "pulse"}, {"shape", name(p.shape)}, {"amplitude", p.amplitude}, {"w", p.w}, {"duration", p.duration()}};
  if (p.record) {
    std::vector<double> a(p.record->a.size());
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = p.amplitude * p.record->a[i];
    return {{"kind", "record"}, {"source", p.record->source}, {"w", p.w}, {"t", p.record->t}, {"a", a}};
  }
  Ordered terms = Ordered::array();
  for (std::size_t i = 0; i < static_cast<std::size_t>(p.n_waves); ++i)
    terms.push_back({{"w", p.waves[i].w}, {"sin", p.waves[i].s}, {"cos", p.waves[i].c}});
  Ordered j = {{"kind", "sinusoids"}, {"shape", name(p.shape)}, {"amplitude", p.amplitude},
               {"w", p.w},         {"duration", p.duration()}, {"terms", terms}};
  if (p.shape == PulseShape::makris_c) j["cycles"] = p.cycles;
  if (p.shape == PulseShape::mp) {
    j["mp_gamma"] = p.mp_gamma;
    j["mp_nu"] = p.mp_nu;
  }
  return j;
}

std::string document_as_built(const System& s, const Settings& settings) {
  const auto nb = static_cast<std::size_t>(s.n_bodies());
  Ordered j;
  j["protocol"] = programs::kProtocol;
  j["version"] = programs::kVersion;
  Ordered bodies = Ordered::array();
  for (std::size_t i = 0; i < nb; ++i) {
    const Body& b = s.bodies[i];
    bodies.push_back({{"m", b.m},
                      {"k", b.k},
                      {"c", b.c},
                      {"w", b.w},
                      {"u", s.u_start.empty() ? 0.0 : s.u_start[i]},
                      {"v", s.v_start.empty() ? 0.0 : s.v_start[i]}});
    if (b.yields()) bodies.back()["u_y"] = b.u_y;
  }
  j["bodies"] = std::move(bodies);
  j["reference"] = s.ref;
  Ordered contacts = Ordered::array();
  for (int c = 0; c < s.n_contacts(); ++c)
    contacts.push_back({{"left", s.left(c) == kWall ? Ordered(nullptr) : Ordered(s.left(c))},
                        {"right", s.right(c)},
                        {"gap", s.delta}});
  j["contacts"] = std::move(contacts);
  j["eps"] = s.eps;
  j["xi"] = s.xi;
  if (s.yields()) j["alpha"] = s.alpha;
  j["load"] = load_as_built(s.pulse);
  j["a_p"] = s.a_p;
  j["length_scale"] = s.length_scale();
  j["t_end"] = s.t_end;
  j["t_min"] = s.t_min;
  const bool stepped = settings.steps > 0 || settings.wh > 0.0;
  j["step"] = stepped ? Ordered(time_step(s, settings, 1)) : Ordered(nullptr);
  j["steps_per_period"] = settings.steps > 0 ? Ordered(settings.steps) : Ordered(nullptr);
  j["step_cap"] = settings.step_cap;
  j["time_limit"] = settings.time_limit;
  j["history_samples"] = settings.history_samples;
  j["monitor"] = settings.monitor;
  return j.dump(-1, ' ', false, Ordered::error_handler_t::replace) + '\n';
}

// The settings a document carries: none, a step count, a step as wh with every limit.
std::vector<Settings> settings_kinds() {
  Settings none, steps, wh;
  steps.steps = 64;
  wh.wh = 0.3;
  wh.step_cap = 123456789;
  wh.time_limit = 2.5;
  wh.history_samples = 10;
  wh.monitor = false;
  return {none, steps, wh};
}

void expect_as_built(const System& s, const std::string& what) {
  for (const Settings& settings : settings_kinds()) {
    const programs::CaseDocument doc = programs::case_document(s, settings);
    ASSERT_EQ(doc.error, "") << what;
    ASSERT_EQ(doc.text, document_as_built(s, settings)) << what;
  }
}

// ---------------------------------------------------------------- the tests

TEST(CaseDocument, IsTheOrderedJsonDumpByteForByteOnEveryShippedSet) {
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets")) {
    if (entry.path().extension() != ".toml") continue;
    if (load_buildings_set(entry.path())) continue;  // no case document for buildings yet (issue 50)
    const CaseSet set = load_case_set(entry.path());
    // Every set's first and last points and some 40 between (the paper set has 23,820).
    const std::size_t n = set.cases.size(), stride = std::max<std::size_t>(1, n / 40);
    for (std::size_t i = 0; i < n; i = (i + 1 < n && i + stride >= n) ? n - 1 : i + stride) {
      expect_as_built(make_system(set.cases[i]), entry.path().filename().string() + " point " + std::to_string(i));
      ++compared;
    }
  }
  EXPECT_GT(compared, 400);
}

// Numbers the sets do not have: negative zero, the shortest form's switch to an exponent at
// both ends, the extremes of a double, a subnormal; and strings the library must escape.
TEST(CaseDocument, IsTheOrderedJsonDumpOnEdgeNumbersAndStrings) {
  Case c = test::make_case(Scene::row3, PulseShape::cosine, 0.7, 1.3, 0.25);
  c.kick = 0.5;
  System s = make_system(c);
  const std::vector<double> edges = {-0.0,    0.0,     1e-5,   1e-4,    0.0001234, 1e15,   1e16,
                                     1.2e17,  1e17,    1e21,   1e22,    -1e-7,     0.1,    1.0 / 3,
                                     2.0 / 3, 5e-324,  1e-300, 2.2250738585072014e-308, std::numeric_limits<double>::max(),
                                     100.0,   -2.5};  // three a system, all of them
  for (std::size_t i = 0; i + 2 < edges.size(); i += 3) {
    s.u_start = {edges[i], edges[i + 1], edges[i + 2]};
    s.v_start = {edges[i + 2], edges[i], edges[i + 1]};
    s.delta = edges[i + 1];
    expect_as_built(s, "edges from " + std::to_string(i));
  }

  const std::string records_set = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/records.toml";
  const System records = make_system(load_case_set(records_set).cases.at(0));
  ASSERT_TRUE(records.pulse.record);
  for (const std::string source : {"plain.csv", "a \"quoted\" name.csv", "back\\slash.csv", "tab\there\n.csv",
                                   "\x01\x1f\x7f.csv", "caf\xc3\xa9.csv", "bad \xff\xfe utf-8.csv", "cut \xe2\x82"}) {
    System named = records;
    auto record = std::make_shared<Record>(*records.pulse.record);
    record->source = source;
    named.pulse.record = record;
    expect_as_built(named, "source " + source);
  }
}

}  // namespace
}  // namespace pb
