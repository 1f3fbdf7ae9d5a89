// Cases given in physical units (cases/physical.hpp) and the results in them
// (rows/result_fields.hpp), through the command line as a user gives them (issue 35).

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cases/case_set.hpp"
#include "cases/physical.hpp"
#include "rows/result_fields.hpp"
#include "rows/row_read.hpp"
#include "cases/system.hpp"
#include "studies/settings_list.hpp"
#include "sweep/sweep.hpp"
#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace physical_units_tests {

const std::string kElCentroFile = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/real/B-ELC000.AT2";
const std::string kBuildings = " --scene pair --directivity normal --t0 0.5 --t1 1 --gap 0.01 --eps 0.6";

// `run ... --json` as a user types it, in the fixture's directory of its own.
class PhysicalCli : public Cli {
 protected:
  nlohmann::json run_json(const std::string& args) const {
    const Outcome o = run("run" + args + " --json");
    EXPECT_EQ(o.exit_code, 0) << args << "\n" << o.err;
    return o.exit_code == 0 ? nlohmann::json::parse(o.out) : nlohmann::json::object();
  }
};

double num(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j.at(key).is_number() ? j.at(key).get<double>() : std::nan("");
}

// The issue's question as typed: two buildings in seconds and metres under a real record, no
// --tp and no Pi term. The Pi terms it maps to, typed as such, must solve the same case: the
// reference finds its event times to an ulp, so only the round-off of w0 = Pi2 w_p against
// 2 pi / t0 may separate the two (1e-9, the reference's baseline tolerance).
TEST_F(PhysicalCli, PhysicalRecordCaseEqualsItsPiTermCase) {
  // The issue's command exactly (no --directivity either: normal, the record as recorded); at
  // 5 cm these buildings do not pound under this record, at 1 cm they do.
  for (const char* gap : {"0.05", "0.01"}) {
    const nlohmann::json phys = run_json(
        " --scene pair --pulse record --record " + kElCentroFile + " --t0 0.5 --t1 1 --gap " + gap + " --eps 0.6");
    ASSERT_FALSE(phys.empty());
    EXPECT_EQ(phys.at("t0").get<double>(), 0.5);
    EXPECT_EQ(phys.at("directivity"), "normal");
    const double w_p = num(phys, "w_p"), a_p = num(phys, "a_p");
    EXPECT_NEAR(num(phys, "pi2"), 2.0 * std::numbers::pi / 0.5 / w_p, 1e-14 * num(phys, "pi2"));
    EXPECT_NEAR(num(phys, "pi3"), std::stod(gap) * w_p * w_p / a_p, 1e-14 * num(phys, "pi3"));
    EXPECT_DOUBLE_EQ(num(phys, "pi5"), 2.0);  // w0 / w1 = t1 / t0
    EXPECT_DOUBLE_EQ(num(phys, "pi6"), 1.0);
    EXPECT_NEAR(num(phys, "peak_m"), num(phys, "pi1") * a_p / (w_p * w_p), 1e-15);
    EXPECT_TRUE(phys.at("h_s").is_null());  // the reference has no step
    if (std::string(gap) == "0.01") {
      EXPECT_GT(phys.at("impacts").get<long>(), 0);
      EXPECT_GT(num(phys, "impact_velocity"), 0.0);
      EXPECT_DOUBLE_EQ(num(phys, "impact_velocity_pi"), num(phys, "impact_velocity") * w_p / a_p);
      EXPECT_GE(num(phys, "first_impact_s"), 0.0);
    } else {
      EXPECT_EQ(phys.at("impacts").get<long>(), 0);
      EXPECT_TRUE(phys.at("impact_velocity").is_null());
    }

    char pi_terms[512];
    std::snprintf(pi_terms, sizeof pi_terms, " --pi2 %.17g --pi3 %.17g --pi5 %.17g --pi6 1 --a-p %.17g --w-p %.17g",
                  num(phys, "pi2"), num(phys, "pi3"), num(phys, "pi5"), a_p, w_p);
    const nlohmann::json pi = run_json(
        " --scene pair --directivity normal --eps 0.6 --pulse record --record " + kElCentroFile + pi_terms);
    ASSERT_FALSE(pi.empty());
    EXPECT_NEAR(num(pi, "pi1"), num(phys, "pi1"), 1e-9 * num(phys, "pi1"));
    EXPECT_NEAR(num(pi, "peak_m"), num(phys, "peak_m"), 1e-9 * num(phys, "peak_m"));
    EXPECT_EQ(pi.at("impacts"), phys.at("impacts"));
    if (phys.at("impacts").get<long>() > 0) {
      EXPECT_NEAR(num(pi, "impact_velocity"), num(phys, "impact_velocity"), 1e-9 * num(phys, "impact_velocity"));
    }
    EXPECT_FALSE(pi.contains("t0"));  // a Pi-term case has no physical values to carry
  }
}

// The same buildings with a physical contact stiffness under two normalisations of one record
// (its mean period's w_p, and --tp 2; a_p is its peak in both, as --a-p is refused beside a
// record in physical units): the model is the same, so the peak in metres is. CVODE integrates
// the same physical system in both, but its absolute tolerance is on the Pi terms' length unit,
// which moves here: the two runs differ by their integration errors (2e-4 allowed on the peak;
// the largest force is sampled at CVODE's accepted steps: 2e-3).
TEST_F(PhysicalCli, KContactGivesTheSamePeakUnderTwoNormalisationsOfARecord) {
  for (const char* variant : {"kelvin-voigt", "hunt-crossley"}) {
    const std::string args = kBuildings + " --pulse record --record " + kElCentroFile +
                             " --m0 2e6 --m1 1e6 --solver compliant --variant " + variant +
                             (std::string(variant) == "kelvin-voigt" ? " --k-contact 5e9" : " --k-contact 2e11");
    const nlohmann::json a = run_json(args);
    const nlohmann::json b = run_json(args + " --tp 2");
    ASSERT_FALSE(a.empty() || b.empty()) << variant;
    EXPECT_NE(num(a, "pi3"), num(b, "pi3")) << variant;  // two units indeed
    EXPECT_NEAR(num(a, "peak_m"), num(b, "peak_m"), 2e-4 * num(a, "peak_m")) << variant;
    EXPECT_NEAR(num(a, "contact_force_max"), num(b, "contact_force_max"), 2e-3 * num(a, "contact_force_max"))
        << variant;
    EXPECT_GT(num(a, "contact_force_max"), 0.0) << variant;
  }
}

// --k-contact in N/m is --stiffness K = k / (m0 w0^2) for the linear element: the same run.
TEST_F(PhysicalCli, KContactOfALinearElementIsTheStiffnessPiTerm) {
  const std::string pulse = " --pulse sine --a-p 3 --tp 1 --m0 4e5 --solver compliant";
  const double w0 = 2.0 * std::numbers::pi / 0.5, K = 1e9 / (4e5 * w0 * w0);
  const nlohmann::json a = run_json(kBuildings + pulse + " --k-contact 1e9");
  char stiffness[64];
  std::snprintf(stiffness, sizeof stiffness, " --stiffness %.17g", K);
  const nlohmann::json b = run_json(kBuildings + pulse + stiffness);
  ASSERT_FALSE(a.empty() || b.empty());
  EXPECT_NEAR(a.at("settings").at("stiffness").get<double>(), K, 1e-14 * K);
  EXPECT_NEAR(num(a, "pi1"), num(b, "pi1"), 1e-9 * num(b, "pi1"));
}

// Self-similarity of the physical inputs (cases/README.md): the same buildings with every time
// twice as long and the pulse three times as strong (lengths a_p T^2: twelve times) are the
// same Pi terms, so the same Pi1; the results in metres and seconds scale with them. Moreau-
// Jean's step is a fixed fraction of T_min, so its run is the same sequence of operations up to
// the round-off of the scales (1e-12).
TEST_F(PhysicalCli, PhysicalInputsAreSelfSimilar) {
  const nlohmann::json a = run_json(
      " --scene pair --directivity normal --pulse sine --t0 0.5 --t1 1 --gap 0.02 --eps 0.6 --a-p 3 --tp 1"
             " --solver moreau-jean");
  const nlohmann::json b = run_json(
      " --scene pair --directivity normal --pulse sine --t0 1 --t1 2 --gap 0.24 --eps 0.6 --a-p 9 --tp 2"
             " --solver moreau-jean");
  ASSERT_FALSE(a.empty() || b.empty());
  ASSERT_GT(a.at("impacts").get<long>(), 0);
  EXPECT_NEAR(num(b, "pi1"), num(a, "pi1"), 1e-12 * num(a, "pi1"));
  EXPECT_NEAR(num(b, "peak_m"), 12.0 * num(a, "peak_m"), 1e-12 * num(b, "peak_m"));
  EXPECT_NEAR(num(b, "h_s"), 2.0 * num(a, "h_s"), 1e-12 * num(b, "h_s"));
  EXPECT_NEAR(num(b, "first_impact_s"), 2.0 * num(a, "first_impact_s"), 1e-12 * num(b, "first_impact_s"));
  EXPECT_NEAR(num(b, "impact_velocity"), 6.0 * num(a, "impact_velocity"), 1e-11 * num(b, "impact_velocity"));
  EXPECT_NEAR(num(b, "impact_velocity_pi"), num(a, "impact_velocity_pi"), 1e-11 * num(a, "impact_velocity_pi"));
  // A row3 given in physical units, masses as ratios (m0 unit): the Pi terms it maps to.
  const nlohmann::json r = run_json(
      " --scene row3 --directivity normal --pulse cosine --t0 1 --t1 0.5 --t2 2 --m1 2 --m2 0.5 --gap 0.1"
             " --eps 0.5 --a-p 2 --tp 1.5");
  ASSERT_FALSE(r.empty());
  EXPECT_DOUBLE_EQ(num(r, "pi5"), 0.5);  // t1 / t0
  EXPECT_DOUBLE_EQ(num(r, "pi6"), 0.5);
  EXPECT_DOUBLE_EQ(num(r, "pi7"), 2.0);
  EXPECT_DOUBLE_EQ(num(r, "pi8"), 2.0);
  EXPECT_NEAR(num(r, "pi2"), 1.5, 1e-15);
}

// Never both ways in one case, and a physical case states what its units need.
TEST_F(PhysicalCli, PhysicalUnitsRefuseMixingAndMissingValues) {
  const auto refuses = [&](const std::string& args, const std::string& says) {
    const Outcome o = run("run" + args);
    EXPECT_EQ(o.exit_code, 2) << args;
    EXPECT_EQ(line_count(o.err), 1u) << o.err;
    EXPECT_NE(o.err.find(says), std::string::npos) << o.err;
  };
  refuses(kBuildings + " --pulse sine --a-p 3 --tp 1 --pi2 1", "--pi2: not with --t0");
  refuses(kBuildings + " --pulse sine --a-p 3 --tp 1 --pi6 1", "--pi6: not with --t0");
  refuses(kBuildings + " --pulse sine --tp 1", "--a-p: required");
  refuses(kBuildings + " --pulse sine --a-p 3", "--tp: required");
  refuses(" --scene pair --directivity normal --pulse sine --a-p 3 --tp 1 --t0 0.5 --gap 0.05 --eps 0.6", "--t1: required");
  refuses(kBuildings + " --pulse sine --a-p 3 --tp 1 --t2 1", "--t2: not used by scene pair");
  refuses(" --scene pair --pulse sine --a-p 3 --tp 1 --t0 0.5 --t1 1 --eps 0.6 --gap -1", "--gap: must be finite and >= 0");
  refuses(" --scene pair --directivity normal --pulse sine --pi2 1 --pi3 0.5 --eps 0.5 --pi5 1 --pi6 1"
          " --solver compliant --k-contact 1e9", "--k-contact: needs a case in physical units");
  refuses(kBuildings + " --pulse sine --a-p 3 --tp 1 --solver compliant --k-contact 1e9 --stiffness 10",
          "--k-contact: not with --stiffness");
  // The reference has no contact stiffness: the flag given is named (issue 46: it said --stiffness).
  refuses(kBuildings + " --pulse sine --a-p 3 --tp 1 --k-contact 1e9", "poundbench: --k-contact: gives --stiffness K = ");
  refuses(kBuildings + " --pulse sine --a-p 3 --tp 1 --k-contact 1e9 --solver moreau-jean",
          "poundbench: --k-contact: not used by moreau-jean");
}

// Issue 46 (8): NaN is a physical field's "not given", and `--uy0 nan` ran elastic, `--m0 nan`
// as 1 kg, as if the flag were not there (while --pi-y0 nan was refused). A value outside its
// field's domain is refused under the flag given.
TEST_F(PhysicalCli, ANanOrInfinitePhysicalValueIsRefusedNamingItsFlag) {
  const std::string pulse = " --pulse sine --a-p 3 --tp 1";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --uy0 nan", "poundbench: --uy0: must be > 0 (inf: elastic) (got nan)\n"},
      {" --uy1 -nan", "poundbench: --uy1: must be > 0 (inf: elastic) (got nan)\n"},
      {" --m0 nan", "poundbench: --m0: must be in [1e-30, 1e+30] kg (got nan)\n"},
      {" --m1 NaN", "poundbench: --m1: must be in [1e-30, 1e+30] kg (got nan)\n"},
      {" --m0 inf", "poundbench: --m0: must be in [1e-30, 1e+30] kg\n"},
      {" --m1 1e31", "poundbench: --m1: must be in [1e-30, 1e+30] kg\n"},
  };
  for (const auto& [extra, says] : cases) {
    const Outcome o = run("run" + kBuildings + pulse + extra + " --json");
    EXPECT_EQ(o.exit_code, 2) << extra << "\n" << o.out;
    EXPECT_EQ(o.err, says) << extra;
  }
  for (const std::string flag : {"--t0", "--t1", "--gap"}) {
    std::string args = " --scene pair --directivity normal --eps 0.6" + pulse;
    for (const std::string other : {"--t0", "--t1", "--gap"}) args += " " + other + (other == flag ? " nan" : " 0.5");
    const Outcome o = run("run" + args);
    EXPECT_EQ(o.exit_code, 2) << flag << "\n" << o.out;
    EXPECT_TRUE(o.err.starts_with("poundbench: " + flag + ": must be finite and ")) << o.err;
  }
  // inf is a yield displacement's "elastic", as pi_y's: the elastic case's Pi1 exactly.
  const nlohmann::json elastic = run_json(kBuildings + pulse), inf = run_json(kBuildings + pulse + " --uy0 inf");
  EXPECT_EQ(num(inf, "pi1"), num(elastic, "pi1"));
}

// Issue 46 (8): a value that makes a Pi term leave the domain was named by the Pi flag
// (`--t0 1e-308` said --pi2, `--gap 1e308` --pi3, `--a-p 1e-300` blamed the gap): it is named
// by the flag the user gave, with the Pi term it gave.
TEST_F(PhysicalCli, AValueThatTakesAPiTermOutOfTheDomainIsNamedByTheFlagGiven) {
  const std::string row3 = " --scene row3 --directivity normal --eps 0.6 --pulse sine";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --t0 1e-308 --t1 1 --t2 1 --gap 0.01 --a-p 3 --tp 1",
       "poundbench: --t0: gives pi2 = 2 pi / (t0 w_p) = inf (pi2: must be finite and > 0)"},
      {" --t0 0.5 --t1 1 --t2 1 --gap 1e308 --a-p 3 --tp 1",
       "poundbench: --gap: gives pi3 = gap w_p^2 / a_p = inf (pi3: gap must be finite and >= 0)"},
      {" --t0 0.5 --t1 1 --t2 1 --gap 0.01 --a-p 1e-300 --tp 1", "poundbench: --a-p: must be in [1e-12, 1e12]"},
      {" --t0 0.5 --t1 1 --t2 1 --gap 0.01 --a-p 3 --tp 1e-300", "poundbench: --tp: gives w_p = 6.28319e+300 (w_p: "},
      {" --t0 0.5 --t1 5e-324 --t2 1 --gap 0.01 --a-p 3 --tp 1", "poundbench: --t1: gives pi5 = t1 / t0 = "},
      {" --t0 0.5 --t1 1 --t2 1e5 --gap 0.01 --a-p 3 --tp 1", "poundbench: --t2: gives pi7 = t2 / t0 = 200000 (pi7: "},
      {" --t0 0.5 --t1 1 --t2 1 --m0 1 --m2 1e-20 --gap 0.01 --a-p 3 --tp 1", "poundbench: --m2: gives pi8 = m0 / m2"},
      {" --t0 0.5 --t1 1 --t2 1 --uy0 1e-300 --gap 0.01 --a-p 3 --tp 1", "poundbench: --uy0: gives pi_y0 = "},
  };
  for (const auto& [args, says] : cases) {
    const Outcome o = run("run" + row3 + args);
    EXPECT_EQ(o.exit_code, 2) << args << "\n" << o.out;
    EXPECT_EQ(line_count(o.err), 1u) << o.err;
    EXPECT_TRUE(o.err.starts_with(says)) << args << "\n" << o.err;
    EXPECT_EQ(o.err.find(": --pi"), std::string::npos) << o.err;
  }
  // The same in Pi terms names the Pi flag and --w-p itself.
  const Outcome pi = run("run" + row3 + " --pi2 1 --pi3 0.5 --pi5 1 --pi6 1 --pi7 1 --pi8 1 --w-p 1e300");
  EXPECT_TRUE(pi.err.starts_with("poundbench: --w-p: must be in")) << pi.err;
}

// Issue 46 (8): `--m0 1e308` through the compliant solver ended ok with contact_force_max null:
// the force in N (the run's, times m0) overflowed. The masses have a domain; within it the
// force is a number.
TEST_F(PhysicalCli, AMassBeyondTheDomainIsRefusedAndACompliantRunReportsItsForce) {
  const std::string args = kBuildings + " --pulse sine --a-p 3 --tp 1 --solver compliant";
  const Outcome o = run("run" + args + " --m0 1e308 --json");
  EXPECT_EQ(o.exit_code, 2) << o.out;
  EXPECT_EQ(o.err, "poundbench: --m0: must be in [1e-30, 1e+30] kg\n");
  const nlohmann::json unit = run_json(args), heavy = run_json(args + " --m0 1e30 --m1 1e30");
  ASSERT_GT(num(unit, "impacts"), 0);
  EXPECT_GT(num(unit, "contact_force_max"), 0.0);
  EXPECT_EQ(heavy.value("status", ""), "ok");
  EXPECT_NEAR(num(heavy, "contact_force_max"), 1e30 * num(unit, "contact_force_max"),
              1e-9 * 1e30 * num(unit, "contact_force_max"));
}

// The error a case set's text is refused with, or "no error".
std::string case_set_error(const std::string& toml) {
  try {
    parse_case_set(toml, "bad.toml");
  } catch (const CaseSetError& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}

// Issue 46 (8): a case set's `uy0 = nan` and `m0 = nan` ran as if not given, and `t0 = 1e-308`
// was refused as pi2 with no line. Each is refused at its value's line, under its key.
TEST(PhysicalCaseSets, ABadPhysicalValueIsRefusedAtItsLineUnderItsKey) {
  const std::string family = "name = \"b\"\n[[family]]\nname = \"f\"\nscene = \"pair\"\npulse = \"sine\"\n"
                             "directivity = \"normal\"\neps = 0.5\na_p = 1\ntp = 1\nt1 = 1\ngap = 0.1\n";  // 11 lines
  EXPECT_EQ(case_set_error(family + "t0 = 1\nuy0 = nan\n"), "bad.toml:13: family[0].uy0: must be > 0 (inf: elastic) (got nan)");
  EXPECT_EQ(case_set_error(family + "t0 = 1\nm0 = [1, nan]\n"), "bad.toml:13: family[0].m0[1]: must be in [1e-30, 1e+30] kg (got nan)");
  EXPECT_EQ(case_set_error(family + "t0 = 1\nm0 = 1e308\n"), "bad.toml:13: family[0].m0: must be in [1e-30, 1e+30] kg (got 1e+308)");
  EXPECT_EQ(case_set_error(family + "t0 = [0.5,\n  1e-308]\n"),
            "bad.toml:13: family[0].t0[1]: gives pi2 = 2 pi / (t0 w_p) = inf (pi2: must be finite and > 0) (got 1e-308)");
  const std::string gap = case_set_error(family + "t0 = 1\nm1 = 1e-20\n");
  EXPECT_TRUE(gap.starts_with("bad.toml:13: family[0].m1: gives pi6 = m0 / m1 = 1e+20 (pi6: ")) << gap;
}

// A case-set family in physical units expands to the Pi terms its values give, its periods
// and gap as axes like the Pi terms they replace; a family's own Pi term beside them is an error.
TEST(PhysicalCaseSets, AFamilyInPhysicalUnitsExpandsToItsPiTerms) {
  const CaseSet set = parse_case_set(R"(name = "phys"
[defaults]
pi3 = 0.5
[[family]]
name = "buildings"
scene = "pair"
pulse = "sine"
directivity = "normal"
eps = 0.6
a_p = 3
tp = 2
t1 = 1
m0 = 2e6
m1 = 1e6
gap = [0.01, 0.05]
t0 = [0.25, 0.5]
[[family]]
name = "two-sided"
scene = "row3"
symmetric = true
pulse = "cosine"
directivity = "normal"
eps = 0.5
pi3 = 1
pi2 = 1
pi5 = 2
pi6 = 1
)", "phys.toml");
  ASSERT_EQ(set.cases.size(), 5u);
  const double w_p = std::numbers::pi;  // tp = 2
  for (std::size_t i = 0; i < 4; ++i) {
    const Case& c = set.cases[i];
    const double t0 = i % 2 == 0 ? 0.25 : 0.5, gap = i < 2 ? 0.01 : 0.05;  // t0 innermost
    EXPECT_EQ(c.physical.t0, t0);
    EXPECT_EQ(c.physical.gap, gap);
    EXPECT_NEAR(c.pi2, 2.0 * std::numbers::pi / t0 / w_p, 1e-15 * c.pi2);
    EXPECT_NEAR(c.pi3, gap * w_p * w_p / 3.0, 1e-15 * c.pi3);
    EXPECT_DOUBLE_EQ(c.pi5, 1.0 / t0);
    EXPECT_DOUBLE_EQ(c.pi6, 2.0);
  }
  EXPECT_EQ(set.cases[4].pi3, 1.0);  // the Pi-term family keeps its own, and [defaults]' Pi terms
  EXPECT_TRUE(std::isnan(set.cases[4].physical.t0));

  const std::string family = "name = \"b\"\n[[family]]\nname = \"f\"\nscene = \"pair\"\npulse = \"sine\"\n"
                             "directivity = \"normal\"\neps = 0.5\na_p = 1\ntp = 1\nt1 = 1\n";
  EXPECT_NE(case_set_error(family + "t0 = 1\ngap = 0.1\npi2 = 1\n").find("pi2: not with"), std::string::npos);
  EXPECT_NE(case_set_error(family + "t0 = 1\n").find("gap: required by a family in physical units"), std::string::npos);
  EXPECT_NE(case_set_error(family + "t0 = 1\ngap = -0.1\n").find("gap"), std::string::npos);
  // Yield displacements (m) as keys too: Pi_y = u_y w_p^2 / a_p (here w_p = 2 pi, a_p = 1),
  // never beside their Pi terms; a symmetric row3's uy2 is its uy1.
  const CaseSet yielding = parse_case_set(family + "t0 = 1\ngap = 0.1\nuy0 = 0.02\nuy1 = [0.01, 0.03]\n", "y.toml");
  ASSERT_EQ(yielding.cases.size(), 2u);
  const double to_pi = 4.0 * std::numbers::pi * std::numbers::pi;
  EXPECT_EQ(yielding.cases[0].physical.uy0, 0.02);
  EXPECT_NEAR(yielding.cases[0].pi_y0, 0.02 * to_pi, 1e-15 * 0.02 * to_pi);
  EXPECT_NEAR(yielding.cases[1].pi_y1, 0.03 * to_pi, 1e-15 * 0.03 * to_pi);
  EXPECT_TRUE(std::isinf(yielding.cases[0].pi_y2));
  EXPECT_NE(case_set_error(family + "t0 = 1\ngap = 0.1\npi_y0 = 1\n").find("pi_y0: not with"), std::string::npos);
  EXPECT_NE(case_set_error(family + "t0 = 1\ngap = 0.1\nuy = 1\n").find("uy"), std::string::npos);  // a chain's key
}

// Rows carry the physical values given and the results in them, after every older column, and
// read back to the same values.
TEST(PhysicalRows, PhysicalValuesAndResultsReadBack) {
  Row row;
  row.input.scene = Scene::pair;
  row.input.physical.t0 = 0.5;
  row.input.physical.gap = 0.05;
  row.input.physical.m0 = 2.0;
  row.input.a_p = 3.0;
  row.input.w_p = 2.0;
  row.solver = "event-driven";
  row.settings = "{}";
  row.length_scale = 0.75;
  row.result.pi1 = 1.5;
  row.result.step = 0.01;
  row.result.first_impact = 0.25;
  row.result.impact_velocity_max = 0.3;
  row.result.contact_force_max = 7.0;
  row.result.min_gap = -0.075;
  const Row back = parse_row(split_csv(csv_line(row)));
  EXPECT_EQ(back.input.physical.t0, 0.5);
  EXPECT_EQ(back.input.physical.gap, 0.05);
  EXPECT_TRUE(std::isnan(back.input.physical.t1));
  const auto value = [](std::string_view field, const Row& r) { return find_result_field(field)->number(r); };
  for (const ResultField& f : kResultFields) {
    if (f.place != Place::physical) continue;
    EXPECT_DOUBLE_EQ(value(f.name, back), value(f.name, row)) << f.name;
  }
  EXPECT_DOUBLE_EQ(value("peak_m", row), 1.5 * 0.75);
  EXPECT_DOUBLE_EQ(value("contact_force_max", row), 14.0);  // times m0
  EXPECT_DOUBLE_EQ(value("penetration_m", row), 0.075);
  EXPECT_DOUBLE_EQ(value("impact_velocity_pi", row), 0.3 * 2.0 / 3.0);
}

// Issue 39's yielding in physical units: --uy0 (m) is Pi_y0 = u_y0 w_p^2 / a_p, the case
// its Pi twin (pi2, pi3, pi5, pi6 and pi_y0 typed as the numbers they map to). The same
// Case, so the reference's Pi1 equals to round-off (1e-9, its baseline tolerance, as the
// elastic twin above); the yield displacement is stored as given, and mixing is refused.
TEST_F(PhysicalCli, AYieldDisplacementInMetresEqualsItsPiTwin) {
  const std::string buildings = " --scene pair --pulse sine --a-p 3 --tp 1 --t0 0.5 --t1 1 --gap 0.02 --eps 0.6"
                                " --alpha 0.1";
  const nlohmann::json phys = run_json(buildings + " --uy0 0.01");
  ASSERT_FALSE(phys.empty());
  EXPECT_EQ(num(phys, "uy0"), 0.01);
  const double w_p = num(phys, "w_p"), a_p = num(phys, "a_p");
  EXPECT_NEAR(num(phys, "pi_y0"), 0.01 * w_p * w_p / a_p, 1e-15 * num(phys, "pi_y0"));
  std::ostringstream pi;
  pi << std::setprecision(17) << " --scene pair --directivity normal --pulse sine --a-p 3 --tp 1 --eps 0.6 --alpha 0.1"
     << " --pi2 " << num(phys, "pi2") << " --pi3 " << num(phys, "pi3") << " --pi5 " << num(phys, "pi5")
     << " --pi6 " << num(phys, "pi6") << " --pi-y0 " << num(phys, "pi_y0");
  const nlohmann::json twin = run_json(pi.str());
  ASSERT_FALSE(twin.empty());
  EXPECT_GT(num(phys, "pi1"), 0.01 * w_p * w_p / a_p);  // it yields: the bilinear law is in play
  EXPECT_NEAR(num(phys, "pi1"), num(twin, "pi1"), 1e-9 * num(twin, "pi1"));
  const Outcome mixed = run("run" + buildings + " --pi-y0 1");
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_NE(mixed.err.find("--pi-y0: not with --t0"), std::string::npos) << mixed.err;
  const Outcome bad = run("run" + buildings + " --uy0 -1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--uy0: must be > 0"), std::string::npos) << bad.err;
  const Outcome chain = run("run --scene chain --bodies 3 --pulse sine --a-p 3 --tp 1 --t0 0.5 --t1 1 --gap 0.02"
                            " --eps 0.6 --uy0 0.01");
  EXPECT_EQ(chain.exit_code, 2);
  EXPECT_NE(chain.err.find("--uy0: not used by scene chain"), std::string::npos) << chain.err;
}

// The engineer's search (issue 35): `workprecision` over the one case run's flags give, with
// the shipped list of settings in seconds and N/m. The setting the answer picks for 1 % (the
// cheapest whose error meets it) must really meet it: its row's step, run again by `run` with
// the Pi form it was mapped to, against the reference's peak. 1 %: the target itself; the
// two runs of one setting agree to round-off (the same solver on the same case), so the
// check fails only if the study measured the wrong error or mapped the wrong step.
TEST_F(PhysicalCli, TheSearchPicksASettingThatMeetsOnePercent) {
  const std::string buildings = " --scene pair --pulse record --record " + kElCentroFile +
                                " --t0 0.5 --t1 1 --m0 1e6 --m1 1e6 --gap 0.01 --eps 0.6";
  const Outcome o = run("workprecision --settings " + std::string(POUNDBENCH_SOURCE_DIR) +
                        "/cases/settings/physical.toml --repetitions 1 --out table.csv --points points.csv" + buildings);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  CsvTable table(read_text(file("table.csv")));
  CsvTable points(read_text(file("points.csv")));
  ASSERT_FALSE(table.rows.empty());
  // The rows of the list's Moreau-Jean runs carry the step as given; the cheapest meeting 1 %.
  std::size_t best = table.rows.size();
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    if (table.at(i, "solver") != "moreau-jean") continue;
    EXPECT_FALSE(table.at(i, "h_s").empty());
    if (std::stod(table.at(i, "err_median")) > 0.01) continue;
    if (best == table.rows.size() || std::stod(table.at(i, "cpu_median_s")) < std::stod(table.at(best, "cpu_median_s")))
      best = i;
  }
  ASSERT_LT(best, table.rows.size()) << "no Moreau-Jean step met 1 %";
  const double h_s = std::stod(table.at(best, "h_s"));
  // Its point row: the same settings; its step in seconds is the one the list gave.
  std::size_t row = points.rows.size();
  for (std::size_t i = 0; i < points.rows.size(); ++i)
    if (points.at(i, "solver") == "moreau-jean" && points.at(i, "settings") == table.at(best, "settings")) row = i;
  ASSERT_LT(row, points.rows.size());
  EXPECT_NEAR(std::stod(points.at(row, "h_s")), h_s, 1e-12 * h_s);
  const nlohmann::json reference = run_json(buildings);
  const nlohmann::json again = run_json(buildings + " --solver moreau-jean --wh " + points.at(row, "wh"));
  ASSERT_FALSE(reference.empty());
  ASSERT_FALSE(again.empty());
  EXPECT_LE(std::abs(num(again, "pi1") - num(reference, "pi1")) / num(reference, "pi1"), 0.01);
  EXPECT_NEAR(num(again, "pi1"), std::stod(points.at(row, "pi1")), 1e-12 * num(again, "pi1"));
  // The compliant elements' rows carry their stiffness in N/m as given.
  bool compliant = false;
  for (std::size_t i = 0; i < table.rows.size(); ++i)
    if (table.at(i, "solver") == "compliant") compliant = compliant || !table.at(i, "k_contact").empty();
  EXPECT_TRUE(compliant);
}

TEST_F(PhysicalCli, WorkPrecisionRefusesACaseBothByFileAndByFlags) {
  write("set.toml", kTinySet);
  const Outcome o = run("workprecision set.toml --settings " + std::string(POUNDBENCH_SOURCE_DIR) +
                        "/cases/settings/physical.toml --t0 0.5");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(line_count(o.err), 1u) << o.err;
  EXPECT_NE(o.err.find("--t0: not with CASESET"), std::string::npos) << o.err;
}

// A [[run]] gives its step and stiffness in seconds and N/m or in Pi terms, never both; a bad
// value is named by file, field and why.
TEST(PhysicalSettingsLists, MixedOrInvalidPhysicalEntriesAreRefused) {
  const auto refuses = [](const std::string& run, const std::string& says) {
    try {
      parse_settings_list("[[run]]\n" + run, "list.toml");
      ADD_FAILURE() << run << " was accepted";
    } catch (const SettingsListError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_EQ(what.rfind("list.toml:", 0), 0u) << what;
      EXPECT_NE(what.find(says), std::string::npos) << what;
    }
  };
  refuses("solver = \"moreau-jean\"\nh_s = 0.001\nsteps = 64\n", "run[0].h_s: not with steps");
  refuses("solver = \"moreau-jean\"\nwh = 0.5\nh_s = 0.001\n", "run[0].h_s: not with wh");
  refuses("solver = \"compliant\"\nk_contact = 1e9\nstiffness = 10\n", "run[0].k_contact: not with stiffness");
  refuses("solver = \"moreau-jean\"\nh_s = -1\n", "run[0].h_s: must be > 0");
  refuses("solver = \"compliant\"\nk_contact = [1e9, 0]\n", "run[0].k_contact: must be > 0");
  refuses("solver = \"moreau-jean\"\nk_contact = 1e9\n", "run[0].k_contact: not used");
  refuses("solver = \"event-driven\"\nh_s = 0.001\n", "run[0].h_s: the event-driven solver takes no step");
}

// A settings list in seconds and N/m is its Pi twin: h_s = T_min / 64 is steps = 64 and
// k_contact = K m0 w0^2 is stiffness = K, so each run's peak must agree to round-off (1e-12
// relative: the step h_s against T_min / 64 differs in its last bits, and a time-stepper's
// peak moves by about as much). The list keeps them as given (Settings::h_s, k_contact); each
// case's run takes its Pi term from them, which needs a case in physical units for k_contact.
TEST(PhysicalSettingsLists, APhysicalSettingsListEqualsItsPiTwin) {
  const CaseSet set = parse_case_set(R"(name = "one"
[[family]]
name = "pair"
scene = "pair"
pulse = "sine"
directivity = "normal"
a_p = 3
tp = 1
t0 = 0.5
t1 = 1
m0 = 2e5
m1 = 4e5
gap = 0.02
eps = 0.6
)", "one.toml");
  ASSERT_EQ(set.cases.size(), 1u);
  const Case& c = set.cases.front();
  const System system = make_system(c);
  const double h_s = system.t_min / 64, k0 = 2e5 * system.bodies[static_cast<std::size_t>(system.ref)].k;
  std::ostringstream physical, twin;
  physical << std::setprecision(17) << "[[run]]\nsolver = \"moreau-jean\"\nh_s = " << h_s
           << "\n[[run]]\nsolver = \"compliant\"\nvariant = \"kelvin-voigt\"\nk_contact = " << 30 * k0 << "\n";
  twin << "[[run]]\nsolver = \"moreau-jean\"\nsteps = 64\n[[run]]\nsolver = \"compliant\"\n"
          "variant = \"kelvin-voigt\"\nstiffness = 30\n";
  SettingsList a = parse_settings_list(physical.str(), "physical.toml");
  const SettingsList b = parse_settings_list(twin.str(), "twin.toml");
  resolve_physical_settings(a, set.cases, "physical.toml");
  ASSERT_EQ(a.runs.size(), b.runs.size());
  EXPECT_DOUBLE_EQ(a.physical.at(0).h_s, h_s);  // stored as given
  EXPECT_DOUBLE_EQ(a.runs.at(0).settings.h_s, h_s);
  EXPECT_DOUBLE_EQ(a.runs.at(1).settings.k_contact, 30 * k0);
  EXPECT_NEAR(stiffness_pi_term(c, 30 * k0, false), 30.0, 1e-12 * 30);
  for (std::size_t k = 0; k < a.runs.size(); ++k) {
    const Row pa = run_sweep(set.cases, *a.runs[k].solver, a.runs[k].settings).at(0);
    const Row pb = run_sweep(set.cases, *b.runs[k].solver, b.runs[k].settings).at(0);
    ASSERT_EQ(pa.result.status, Status::ok) << pa.result.message;
    EXPECT_GT(pa.result.impacts, 0);  // the gap closes: the stiffness matters
    EXPECT_NEAR(pa.result.pi1, pb.result.pi1, 1e-12 * pb.result.pi1) << a.runs[k].solver->name;
  }
  // A stiffness in N/m over a case in Pi terms has no unit of mass: refused.
  Case pi = c;
  pi.physical = {};
  SettingsList again = parse_settings_list(physical.str(), "physical.toml");
  const std::vector<Case> cases = {pi};
  EXPECT_THROW(resolve_physical_settings(again, cases, "physical.toml"), SettingsListError);
}

}  // namespace physical_units_tests
}  // namespace pb
