// The buildings scene's user-facing paths (issue 49): its case-set families
// (cases/buildings_set.hpp), `run --case-file FILE --point N` and its --json, and the
// refusals of what does not solve it yet.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cases/buildings_set.hpp"
#include "cases/case_set.hpp"
#include "cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_cli_tests {

const std::string kBuildingsSet = kSource + "/cases/sets/buildings.toml";

// A family given floor by floor: the issue's example pair, its pulse as written there.
const std::string kTwoBuildings = R"(name = "t"
[[family]]
name = "two-buildings"
scene = "buildings"
buildings = [ { masses = [3e5, 3e5, 2.4e5], stiffnesses = [6.8e8, 5.4e8, 4.1e8] },
              { masses = [2.5e5, 2.5e5, 2e5], stiffnesses = [2.0e8, 1.6e8, 1.2e8] } ]
damping = "rayleigh"
xi = 0.05
gap = 0.03
eps = 0.6
pulse = "sine"
a_p = 3.0
w_p = 12.566
directivity = "normal"
t_end = 2.5
)";

// The message parse_buildings_set gives for `text` ("" when it reads).
std::string error_of(const std::string& text) {
  try {
    parse_buildings_set(text, "t.toml");
  } catch (const CaseSetError& e) {
    return e.what();
  }
  return "";
}

// A uniform pair in Pi terms, on the pulse scale (a_p, w_p).
std::string pi_family(double a_p, double w_p) {
  return "name = \"pi\"\n[[family]]\nname = \"u\"\nscene = \"buildings\"\nstoreys = [3, 5]\npi2 = [0.6, 1.4]\n"
         "pi3 = 0.3\npi5 = 1.5\npi6 = 0.8\neps = 0.5\nxi = 0.04\npulse = \"cosine\"\na_p = " +
         std::to_string(a_p) + "\nw_p = " + std::to_string(w_p) + "\n";
}

TEST(BuildingsSet, ShippedSetReadsEveryPointFloorByFloorAndInPiTerms) {
  const std::optional<BuildingsSet> set = load_buildings_set(kBuildingsSet);
  ASSERT_TRUE(set.has_value());
  EXPECT_EQ(set->name, "buildings");
  ASSERT_EQ(set->points.size(), 34u);  // 4 + 2 + 2 + 2 + 2 x 12
  EXPECT_EQ(set->points[0].family, "3-and-6-storeys");
  EXPECT_EQ(set->points[0].scene.buildings[1].floors(), 6);
  EXPECT_FALSE(set->points[0].pi_terms);
  EXPECT_EQ(set->points[8].pulse, PulseShape::record);
  const BuildingCase& pi = set->points.back();
  EXPECT_TRUE(pi.pi_terms);
  EXPECT_EQ(pi.storeys_left, 5);
  EXPECT_EQ(pi.storeys_right, 8);
  EXPECT_DOUBLE_EQ(pi.pi2, 4.0);
}

TEST(BuildingsSet, SingleOscillatorSetsAreNotBuildingsAndSweepsRefuseBuildings) {
  EXPECT_FALSE(load_buildings_set(kSource + "/cases/sets/smoke.toml").has_value());
  try {
    load_case_set(kBuildingsSet);
    FAIL() << "a buildings family read as a single oscillator's";
  } catch (const CaseSetError& e) {
    EXPECT_NE(std::string(e.what()).find("buildings.toml:9: defaults.scene: buildings: a case of the buildings scene is solved by"),
              std::string::npos)
        << e.what();
  }
}

TEST(BuildingsSet, TheIssuesExampleReadsAsWritten) {
  const std::optional<BuildingsSet> set = parse_buildings_set(kTwoBuildings, "t.toml");
  ASSERT_TRUE(set && set->points.size() == 1);
  const BuildingScene& s = set->points[0].scene;
  EXPECT_EQ(s.buildings[0].stiffnesses[2], 4.1e8);
  EXPECT_EQ(s.delta, 0.03);
  EXPECT_EQ(s.eps, 0.6);
  EXPECT_EQ(s.t_end, 2.5);
  EXPECT_EQ(s.pulse.amplitude, 3.0);
  EXPECT_EQ(s.pulse.w, 12.566);
}

// [defaults] serves families of every pulse: a record there is left out of a sine family
// (not an axis repeating its points), and the family's own w_p wins over a default tp.
TEST(BuildingsSet, DefaultsGiveWayToWhatTheFamilyUsesAndGives) {
  std::string text = kTwoBuildings;
  text.replace(text.find("[[family]]"), 10,
               "[defaults]\nrecord = [\"../records/real/SHL000.AT2\", \"../records/real/PFT135.AT2\"]\ntp = 0.1\n"
               "[[family]]");
  const std::optional<BuildingsSet> set = parse_buildings_set(text, kSource + "/cases/sets/t.toml");
  ASSERT_TRUE(set.has_value());
  ASSERT_EQ(set->points.size(), 1u);
  EXPECT_EQ(set->points[0].scene.pulse.w, 12.566);
  EXPECT_TRUE(set->points[0].record.empty());
}

TEST(BuildingsSet, EachBadFieldIsOneLineNamingFileLineAndField) {
  const auto with = [](const std::string& from, const std::string& to) {
    std::string t = kTwoBuildings;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  const std::pair<std::string, std::string> cases[] = {
      {with("gap = 0.03", "gapp = 0.03"), "t.toml:9: family[0].gapp: unknown key (did you mean gap?)"},
      {with("masses = [3e5, 3e5, 2.4e5]", "masess = [3e5, 3e5, 2.4e5]"),
       "t.toml:5: family[0].buildings[0].masess: unknown key (a building has masses"},
      {with("[2.5e5, 2.5e5, 2e5]", "[2.5e5, -1, 2e5]"),
       "t.toml:6: family[0].buildings[1]: the mass of floor 2 must be finite and > 0"},
      {with("eps = 0.6", "eps = 1.5"), "t.toml:10: family[0].eps: must be in [0, 1] (got 1.5)"},
      {with("xi = 0.05", "xi = [0.05, 1.0]"), "t.toml:8: family[0].xi[1]: must be in [0, 1) (got 1)"},
      {with("damping = \"rayleigh\"", "damping = \"viscous\""),
       "t.toml:7: family[0].damping: unknown value \"viscous\" (expected rayleigh, modal)"},
      {with("gap = 0.03", "gap = 0.03\npi2 = 1.0"), "family[0].buildings: not with the Pi-term keys"},
      {with("a_p = 3.0\n", ""), "t.toml:2: family[0].a_p: required by a buildings family given floor by floor"},
      {with("pulse = \"sine\"", "pulse = \"sine\"\nrecord = \"x.csv\""), "family[0].record: "},
      {with("t_end = 2.5", "contact_floors = [4]"),
       "family[0].contact_floors: floor 4 is not a floor both buildings 0 and 1 have (1..3)"},
      {pi_family(1, 1) + "[[family]]\nname = \"p\"\nscene = \"pair\"\n",
       "family[1].scene: must be \"buildings\" in a file of buildings families"},
      {pi_family(1, 1).replace(pi_family(1, 1).find("[3, 5]"), 6, "[3]"),
       "t.toml:5: family[0].storeys: must be two storey counts [left, right]"},
      {pi_family(1, 1).replace(pi_family(1, 1).find("pi5 = 1.5"), 9, "pi5 = 0"),
       "t.toml:8: family[0].pi5: must be finite and > 0 (got 0)"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string e = error_of(text);
    EXPECT_NE(e.find(expected), std::string::npos) << "got: " << e << "\nexpected: " << expected;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    EXPECT_TRUE(e.starts_with("t.toml")) << e;
  }
}

// Same Pi terms, two physical scalings: the same Pi results (the model is linear between
// events and every event is located relative to the scales).
TEST_F(Cli, BuildingsInPiTermsAreSelfSimilar) {
  write("a.toml", pi_family(1.0, 1.0));
  write("b.toml", pi_family(3.7, 12.566));
  for (int point : {0, 1}) {
    const std::string p = " --point " + std::to_string(point) + " --json";
    const Outcome a = run("run --case-file a.toml" + p), b = run("run --case-file b.toml" + p);
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ASSERT_EQ(b.exit_code, 0) << b.err;
    const nlohmann::json ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
    for (const char* key : {"floor_peak_pi", "drift_peak_pi"})
      for (std::size_t bd = 0; bd < 2; ++bd)
        for (std::size_t i = 0; i < ja[key][bd].size(); ++i) {
          const double x = ja[key][bd][i], y = jb[key][bd][i];
          EXPECT_NEAR(x, y, 1e-12 * std::abs(x)) << key << " building " << bd << " floor " << i + 1;
        }
    ASSERT_EQ(ja["contacts"].size(), jb["contacts"].size());
    for (std::size_t c = 0; c < ja["contacts"].size(); ++c) {
      EXPECT_EQ(ja["contacts"][c]["impacts"], jb["contacts"][c]["impacts"]);
      if (ja["contacts"][c]["impacts"] == 0) continue;
      const double x = ja["contacts"][c]["impact_velocity_max_pi"], y = jb["contacts"][c]["impact_velocity_max_pi"];
      EXPECT_NEAR(x, y, 1e-12 * std::abs(x));
    }
  }
}

TEST_F(Cli, RunJsonOnABuildingsPointHasEveryKeyInItsShape) {
  const Outcome o = run("run --case-file '" + kBuildingsSet + "' --point 0 --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  for (const char* key : {"status", "message", "events", "energy_error", "seconds", "cpu_seconds", "floor_peak_m",
                          "drift_peak_m", "contacts"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["status"], "ok");
  EXPECT_LT(j["energy_error"].get<double>(), 1e-9);
  EXPECT_FALSE(j.contains("floor_peak_pi"));  // given floor by floor
  for (const char* key : {"floor_peak_m", "drift_peak_m"}) {
    ASSERT_EQ(j[key].size(), 2u) << key;
    EXPECT_EQ(j[key][0].size(), 3u) << key;
    EXPECT_EQ(j[key][1].size(), 6u) << key;
    for (const auto& building : j[key])
      for (const auto& x : building) EXPECT_GT(x.get<double>(), 0.0) << key;
  }
  // The top floor of the 3-storey building moves most of its floors.
  EXPECT_GE(j["floor_peak_m"][0][2].get<double>(), j["floor_peak_m"][0][0].get<double>());
  ASSERT_EQ(j["contacts"].size(), 3u);  // floors 1..3, both buildings have them
  long impacts = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    const nlohmann::json& k = j["contacts"][c];
    EXPECT_EQ(k["left"], 0);
    EXPECT_EQ(k["right"], 1);
    EXPECT_EQ(k["floor"], static_cast<int>(c) + 1);
    for (const char* key : {"impacts", "impact_velocity_max_m_s", "first_impact_s"}) EXPECT_TRUE(k.contains(key)) << key;
    impacts += k["impacts"].get<long>();
    if (k["impacts"] == 0) {
      EXPECT_TRUE(k["first_impact_s"].is_null());
      EXPECT_TRUE(k["impact_velocity_max_m_s"].is_null());
    } else {
      EXPECT_GT(k["first_impact_s"].get<double>(), 0.0);
      EXPECT_GT(k["impact_velocity_max_m_s"].get<double>(), 0.0);
    }
  }
  EXPECT_GT(impacts, 0);  // the shipped pair pounds
  // Per contact, the gap that avoids pounding (the free watch) and the rules: the pair pounds at
  // its gap of 0.02 m, so some level needs more; ABS >= SRSS >= DDC (rho >= 0).
  double required = 0.0;
  for (const auto& k : j["contacts"]) {
    for (const char* key : {"separation_m", "separation_reversed_m", "separation_abs_m", "separation_srss_m",
                            "separation_ddc_m"})
      ASSERT_TRUE(k.contains(key) && k[key].is_number()) << key;
    EXPECT_FALSE(k.contains("separation_pi"));
    required = std::max(required, k["separation_m"].get<double>());
    EXPECT_GE(k["separation_abs_m"].get<double>(), k["separation_srss_m"].get<double>());
    EXPECT_GE(k["separation_srss_m"].get<double>(), k["separation_ddc_m"].get<double>());
    EXPECT_GT(k["separation_ddc_m"].get<double>(), 0.0);
  }
  EXPECT_GT(required, 0.02);

  // A point in Pi terms carries its Pi terms too, in the same shapes.
  const nlohmann::json pi = nlohmann::json::parse(run("run --case-file '" + kBuildingsSet + "' --point 10 --json").out);
  ASSERT_EQ(pi["floor_peak_pi"].size(), 2u);
  EXPECT_EQ(pi["floor_peak_pi"][1].size(), 6u);
  EXPECT_EQ(pi["drift_peak_pi"][0].size(), 3u);
  EXPECT_TRUE(pi["contacts"][0].contains("impact_velocity_max_pi"));
  const double length = pi["a_p"].get<double>() / std::pow(pi["w_p"].get<double>(), 2);
  for (const char* key : {"separation", "separation_reversed", "separation_abs", "separation_srss", "separation_ddc"}) {
    const double m = pi["contacts"][0][std::string(key) + "_m"], term = pi["contacts"][0][std::string(key) + "_pi"];
    EXPECT_NEAR(term * length, m, 1e-15 * m) << key;
  }
}

TEST_F(Cli, RunSummarisesABuildingsPointPerFloorAndContact) {
  const Outcome o = run("run --case-file '" + kBuildingsSet + "' --point 0");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  for (const char* text : {"buildings 3 + 6 storeys", "building 1", "floor 6", "storey 6",
                           "contact  buildings 0-1 floor 3", "status   ok", "gap that avoids pounding 0.0399194 m",
                           "(EC8 0.7 SRSS "})
    EXPECT_NE(o.out.find(text), std::string::npos) << text << "\n" << o.out;
}

TEST_F(Cli, OtherSolversAndStudiesRefuseTheBuildingsSceneByName) {
  // Every registered solver has a buildings solve since issue 50: a name without one (here an
  // unknown one) is refused by the rule, naming those that solve the scene.
  const std::string other = "no-such";
  const Outcome o = run("run --case-file '" + kBuildingsSet + "' --point 0 --solver " + other);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("--solver: " + other + " does not solve the buildings scene (these do: event-driven"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find(", external)"), std::string::npos) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  const Outcome steps = run("run --case-file '" + kBuildingsSet + "' --point 0 --steps 64");
  EXPECT_EQ(steps.exit_code, 2);
  EXPECT_NE(steps.err.find("--steps: the event-driven solver takes no step"), std::string::npos) << steps.err;
  write("list.toml", "[[run]]\nsolver = \"moreau-jean\"\nsteps = 64\n");
  const Outcome study = run("workprecision '" + kBuildingsSet + "' --settings list.toml --out wp.csv");
  EXPECT_EQ(study.exit_code, 2);
  EXPECT_NE(study.err.find("and `poundbench spectrum FILE`, not yet by the studies"), std::string::npos) << study.err;
  const Outcome repeated = run("spectrum '" + kBuildingsSet + "' --repetitions 3");
  EXPECT_EQ(repeated.exit_code, 2);
  EXPECT_NE(repeated.err.find("--repetitions: not for the buildings scene"), std::string::npos) << repeated.err;
  write("bad.toml", kTwoBuildings + "typo = 1\n");
  const Outcome bad = run("run --case-file bad.toml");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.toml:16: family[0].typo: unknown key"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// spectrum over a buildings set: a row per floor of every point, whose peaks are run's for the
// same point, beside the peaks without contact.
TEST_F(Cli, SpectrumOverABuildingsSetWritesARowPerFloorWithRunsPeaks) {
  const Outcome o = run("spectrum '" + kBuildingsSet + "' --out rows.csv --threads 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::optional<BuildingsSet> set = load_buildings_set(kBuildingsSet);
  ASSERT_TRUE(set);
  std::size_t floors = 0;
  for (const BuildingCase& c : set->points)
    for (const Building& b : c.scene.buildings) floors += static_cast<std::size_t>(b.floors());
  CsvTable rows(read_text(file("rows.csv")));
  ASSERT_EQ(rows.rows.size(), floors);
  const nlohmann::json j = nlohmann::json::parse(run("run --case-file '" + kBuildingsSet + "' --point 3 --json").out);
  std::size_t matched = 0;
  for (std::size_t r = 0; r < rows.rows.size(); ++r) {
    if (rows.at(r, "point") != "3") continue;
    const std::size_t b = std::stoul(rows.at(r, "building")), i = std::stoul(rows.at(r, "floor")) - 1;
    EXPECT_EQ(std::stod(rows.at(r, "floor_peak_m")), j["floor_peak_m"][b][i].get<double>());
    EXPECT_EQ(std::stod(rows.at(r, "drift_peak_no_contact_m")), j["drift_peak_no_contact_m"][b][i].get<double>());
    EXPECT_EQ(rows.at(r, "status"), "ok");
    // The gap that avoids pounding with the right neighbour, run's per contact; none for the right building.
    if (b == 0) {
      const nlohmann::json& k = j["contacts"][i];
      ASSERT_EQ(k["floor"], i + 1);
      EXPECT_EQ(std::stod(rows.at(r, "separation_right_m")), k["separation_m"].get<double>());
      EXPECT_EQ(std::stod(rows.at(r, "separation_reversed_right_m")), k["separation_reversed_m"].get<double>());
      EXPECT_EQ(std::stod(rows.at(r, "separation_abs_right_m")), k["separation_abs_m"].get<double>());
      EXPECT_EQ(std::stod(rows.at(r, "separation_srss_right_m")), k["separation_srss_m"].get<double>());
      EXPECT_EQ(std::stod(rows.at(r, "separation_ddc_right_m")), k["separation_ddc_m"].get<double>());
    } else {
      EXPECT_EQ(rows.at(r, "separation_right_m"), "");
      EXPECT_EQ(rows.at(r, "separation_ddc_right_m"), "");
    }
    ++matched;
  }
  EXPECT_EQ(matched, j["floor_peak_m"][0].size() + j["floor_peak_m"][1].size());
}

// `separation` over a buildings set: a row per floor level of every point, its gaps run's, the
// ratios the gaps over the larger of both load signs; the summary per family and rule.
TEST_F(Cli, SeparationOverABuildingsSetWritesARowPerFloorLevel) {
  write("t.toml", kTwoBuildings + "\n" + pi_family(1.0, 1.0).substr(pi_family(1.0, 1.0).find("[[family]]")));
  const Outcome o = run("separation t.toml --out sep.csv --summary sum.csv --threads 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  CsvTable rows(read_text(file("sep.csv")));
  ASSERT_EQ(rows.rows.size(), 3u + 2u * 3u);  // 3 levels of the pair, 3 of each uniform pair (3 and 5 storeys)
  for (const char* key : {"family", "point", "record", "directivity", "left", "right", "floor", "period_ratio",
                          "required_m", "separation_m", "separation_reversed_m", "abs", "srss", "ddc", "abs_m",
                          "srss_m", "ddc_m"})
    EXPECT_NO_THROW(rows.column(key)) << key;
  for (std::size_t r = 0; r < rows.rows.size(); ++r) {
    EXPECT_EQ(rows.at(r, "status"), "ok");
    const double required = std::stod(rows.at(r, "required_m"));
    EXPECT_EQ(required, std::max(std::stod(rows.at(r, "separation_m")), std::stod(rows.at(r, "separation_reversed_m"))));
    for (const char* rule : {"abs", "srss", "ddc"})
      EXPECT_NEAR(std::stod(rows.at(r, rule)), std::stod(rows.at(r, std::string(rule) + "_m")) / required, 1e-15);
  }
  // The uniform pairs: T_1,right / T_1,left = pi5.
  EXPECT_NEAR(std::stod(rows.at(3, "period_ratio")), 1.5, 1e-12);
  const nlohmann::json j = nlohmann::json::parse(run("run --case-file t.toml --point 0 --json").out);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(rows.at(c, "floor"), std::to_string(c + 1));
    EXPECT_EQ(std::stod(rows.at(c, "separation_m")), j["contacts"][c]["separation_m"].get<double>());
    EXPECT_EQ(std::stod(rows.at(c, "ddc_m")), j["contacts"][c]["separation_ddc_m"].get<double>());
  }
  CsvTable summary(read_text(file("sum.csv")));
  ASSERT_EQ(summary.rows.size(), 2u * 3u);  // two families, three rules
  EXPECT_EQ(summary.at(0, "family"), "two-buildings");
  EXPECT_EQ(summary.at(0, "cases"), "3");
  EXPECT_EQ(summary.at(3, "family"), "u");
  EXPECT_EQ(summary.at(5, "rule"), "ddc");
  EXPECT_EQ(summary.at(5, "cases"), "6");
}

// --gap-fractions on a buildings set: each point again through the reference with contacts at
// that fraction of its gap (the largest over its levels), each level's two floor peaks over
// their no-contact peaks: run's on the same scene at that gap.
TEST_F(Cli, SeparationGapFractionsOnBuildingsAmplifyBothFloorsAsRunDoes) {
  write("t.toml", kTwoBuildings);
  const Outcome o = run("separation t.toml --gap-fractions 0.5 --out sep.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  CsvTable rows(read_text(file("sep.csv")));
  ASSERT_EQ(rows.rows.size(), 3u);
  double gap = 0.0;
  for (std::size_t r = 0; r < 3; ++r) gap = std::max(gap, std::stod(rows.at(r, "separation_m")));
  std::string text = kTwoBuildings;
  char given[40];
  std::snprintf(given, sizeof given, "gap = %.17g", 0.5 * gap);
  text.replace(text.find("gap = 0.03"), std::string("gap = 0.03").size(), given);
  write("half.toml", text);
  const nlohmann::json j = nlohmann::json::parse(run("run --case-file half.toml --point 0 --json").out);
  long impacts = 0;
  for (const auto& k : j["contacts"]) impacts += k["impacts"].get<long>();
  EXPECT_GT(impacts, 0);  // at half the gap the pair pounds
  for (std::size_t r = 0; r < 3; ++r)
    for (const auto& [side, b] : {std::pair{"left", 0}, std::pair{"right", 1}}) {
      const double with = j["floor_peak_m"][b][r], without = j["floor_peak_no_contact_m"][b][r];
      EXPECT_NEAR(std::stod(rows.at(r, std::string("amplification_") + side + "_0.5")), with / without, 1e-14)
          << side << " floor " << r + 1;
    }
}

// --k-contact in N/m is --stiffness K times the scene's unit of stiffness (the left building's
// mass times its first mode squared): the same run; a solver without an element refuses it.
TEST_F(Cli, KContactInNewtonsPerMetreIsTheStiffnessTermTimesTheScenesUnit) {
  const std::optional<BuildingsSet> set = load_buildings_set(kBuildingsSet);
  ASSERT_TRUE(set);
  const double unit = contact_element_stiffness(assemble(set->points[0].scene), false);
  char k[64];
  std::snprintf(k, sizeof k, "%.17g", 1e4 * unit);
  const std::string point = "run --case-file '" + kBuildingsSet + "' --point 0 --solver compliant --integrator newmark --steps 64 --json";
  const Outcome pi = run(point + " --stiffness 1e4"), physical = run(point + " --k-contact " + k);
  ASSERT_EQ(pi.exit_code, 0) << pi.err;
  ASSERT_EQ(physical.exit_code, 0) << physical.err;
  const nlohmann::json a = nlohmann::json::parse(pi.out), b = nlohmann::json::parse(physical.out);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(b["floor_peak_m"][0][i].get<double>(), a["floor_peak_m"][0][i].get<double>(),
                1e-9 * a["floor_peak_m"][0][i].get<double>());
  const Outcome rigid = run("run --case-file '" + kBuildingsSet + "' --point 0 --solver moreau-jean --k-contact 1e9");
  EXPECT_EQ(rigid.exit_code, 2);
  EXPECT_NE(rigid.err.find("--k-contact: not used by moreau-jean on the buildings scene"), std::string::npos) << rigid.err;
  const Outcome both = run(point + " --stiffness 1e4 --k-contact 1e9");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--k-contact: not with --stiffness"), std::string::npos) << both.err;
}

// The shipped stress set of the scene: every point ends ok through the reference (--check).
TEST_F(Cli, EveryPointOfTheBuildingsStressSetEndsOkThroughTheReference) {
  const Outcome o = run("spectrum '" + kSource + "/cases/sets/buildings-stress.toml' --check --out stress.csv");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(CsvTable(read_text(file("stress.csv"))).rows.size(), (3u + 6) * 4 + (3 + 6 + 4) * 2 + 9 + 40 * 2 + 28 * 2) << o.err;
}

}  // namespace buildings_cli_tests
}  // namespace pb
