// The AT2 reader on the files engineers have (issue 34, "The reader"; issue 33, item 3):
// the 25 real records shipped in cases/records/real/ load with the NPTS and DT their headers
// state; the NPTS/DT line is found anywhere in the header in each real spelling; a trailer
// after the values and CRLF or CR CR LF line ends are read; the unit is a word, converted
// (g, gal, cm/s^2, m/s^2) or refused; and a record starting after t = 0 is zero before it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "cases/record.hpp"
#include "cases/system.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace record_suite_tests {

const std::string kReal = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/real/";

using test::record_error;

// Each file's NPTS and DT as its fourth line states them (read off the files, not by the
// reader under test), and its first value in g.
struct Shipped {
  const char* file;
  std::size_t npts;
  double dt;
  double first;
};
const std::vector<Shipped> kShipped = {
    {"A-BEN360.AT2", 7996, 0.005, .4417812E-03},   {"A-PAS180.AT2", 12053, 0.005, .2481284E-04},
    {"A-SON303.AT2", 8000, 0.005, -.5898493E-03},  {"A-ZAK360.AT2", 7996, 0.005, .8240444E-03},
    {"AZF225.AT2", 2060, 0.005, .1361197E-04},     {"B-ELC000.AT2", 8000, 0.005, .1570948E-03},
    {"B-LAD180.AT2", 7984, 0.005, .4734705E-05},   {"CEM000.AT2", 4800, 0.005, .1449237E-04},
    {"CHY028-N.AT2", 18000, 0.005, .7273025E-06},  {"EIL-EW.AT2", 12000, 0.005, -.1998192E-05},
    {"EUR090.AT2", 2200, 0.02, .2152965E-03},      {"FOR090.AT2", 2200, 0.02, .1138791E-02},
    {"GCN-WE.AT2", 8192, 0.00244, -.3289472E-05},  {"HAD-NS.AT2", 12000, 0.005, .1843196E-07},
    {"HOS180.AT2", 10000, 0.01, -.1142490E-03},    {"ISE-WE.AT2", 6557, 0.00244, -.2344583E-05},
    {"PFT135.AT2", 2062, 0.005, .4248236E-04},     {"SHL000.AT2", 1800, 0.02, -.2302583E-02},
    {"TAN350.AT2", 3970, 0.01, .3577387E-05},      {"TCU054-N.AT2", 18000, 0.005, .6472567E-04},
    {"TCU070-N.AT2", 18000, 0.005, -.2588476E-04}, {"TCU101-N.AT2", 9800, 0.005, -.8369972E-04},
    {"TCU120-N.AT2", 18000, 0.005, -.1571180E-04}, {"TCU128-N.AT2", 18000, 0.005, -.1037889E-05},
    {"TRAA179.AT2", 1552, 0.02, .4416576E-02},
};

TEST(RecordSuite, EveryShippedRealRecordLoadsWithTheNptsAndDtOfItsHeader) {
  for (const Shipped& s : kShipped) {
    const auto r = read_record(kReal + s.file);
    ASSERT_EQ(r->t.size(), s.npts) << s.file;
    // t_i = i DT exactly as the product rounds (1e-12 s: a few ulps of the longest, 90 s).
    EXPECT_NEAR(r->t[1], s.dt, 1e-15) << s.file;
    EXPECT_NEAR(r->length(), static_cast<double>(s.npts - 1) * s.dt, 1e-12) << s.file;
    // In g: the first value times the standard gravity, to the value's own rounding.
    EXPECT_NEAR(r->a[0], s.first * kStandardGravity, 1e-15 * std::abs(s.first) * 10) << s.file;
  }
  EXPECT_EQ(kShipped.size(), 25u);
}

// One record, its header written as real files write it: the values must read the same.
TEST(RecordSuite, TheNptsLineIsFoundInEveryRealSpellingAnywhereInTheHeader) {
  const std::string values = "  .1000000E+00  -.2000000E+00   .3000000E+00\n";
  const std::vector<std::string> headers = {
      "PEER\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS=  3, DT= .02000 SEC\n",
      "PEER\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS=   3, dt=  .02000\n",
      "PEER\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS=   3, dt=   .0200 SEC\n",
      "PEER\nEVENT\nUNITS OF G\n    3    .0200    NPTS, DT\n",
      // Later than line 4, after extra header lines; and with no unit named (PEER's g).
      "PEER NGA\nEVENT\nSTATION\nCOMPONENT 090\nPROCESSED 2005\nNPTS=3, DT=0.02 SEC\n",
      "NPTS = 3 , DT = 0.02\n",
  };
  const Record expected = parse_record(headers[0] + values, "a.at2");
  ASSERT_EQ(expected.t.size(), 3u);
  EXPECT_DOUBLE_EQ(expected.a[1], -0.2 * kStandardGravity);
  for (const std::string& h : headers) {
    const Record r = parse_record(h + values, "b.AT2");
    EXPECT_EQ(r.t, expected.t) << h;
    EXPECT_EQ(r.a, expected.a) << h;
  }
}

TEST(RecordSuite, ATrailerAfterTheValuesAndCrlfOrCrCrLfLineEndsAreRead) {
  const std::string lf = "h\nh\nUNITS OF G\nNPTS= 3, DT= .02 SEC\n .1 .2\n .3\n";
  const Record expected = parse_record(lf, "a.at2");
  const auto with_ends = [](std::string text, const std::string& end) {
    std::string out;
    for (char c : text) out += c == '\n' ? end : std::string(1, c);
    return out;
  };
  for (const std::string& text : {lf + "*** End Data ***\n", lf + "\n*** End Data ***\n\n", with_ends(lf, "\r\n"),
                                  with_ends(lf + "*** End Data ***\n", "\r\r\n")}) {
    const Record r = parse_record(text, "a.at2");
    EXPECT_EQ(r.t, expected.t);
    EXPECT_EQ(r.a, expected.a);
  }
}

TEST(RecordSuite, AnythingElseIsRefusedWithItsLineAndReason) {
  struct Bad {
    std::string text;
    const char* expected;  // the start of the message
  };
  const std::string head = "h\nh\nUNITS OF G\nNPTS= 3, DT= .02 SEC\n";
  const std::vector<Bad> bad = {
      {head + " .1 .2\n*** End Data ***\n", "x.at2:6: the values end after 2 of NPTS = 3"},
      {head + " .1 .2 .3\n*** End Data ***\n .4\n", "x.at2:7: more values than NPTS = 3 (line 4)"},
      {head + " .1 .2 .3 .4\n", "x.at2:5: more values than NPTS = 3"},
      {head + " .1 .2 .3 END\n", "x.at2:5: more values than NPTS = 3"},
      {head + " .1 oops .3\n", "x.at2:5: value 2: not a number (\"oops\")"},
      {"h\nNPTS= 3, DT= .02\nNPTS= 3, DT= .02\n .1 .2 .3\n", "x.at2:3: a second NPTS line (the first is line 2)"},
      {"h\nh\nUNITS OF G\n .1 .2 .3\n", "x.at2:4: no NPTS/DT line in the header"},
      {"h\nNPTS= 1, DT= .02\n .1\n", "x.at2:2: NPTS: not a whole number of points from 2"},
      {"h\nNPTS= 3, DT= -.02\n .1 .2 .3\n", "x.at2:2: DT: not a positive time step"},
      {"h\nNPTS= 300000, DT= .02\n .1 .2 .3\n", "x.at2:2: NPTS: not a whole number of points from 2 to 200000"},
      // Old Mac line ends (CR alone) would run the file into one line.
      {"h\rNPTS= 3, DT= .02\r .1 .2 .3\r", "x.at2:1: a CR inside the line: line ends must be LF, CRLF or CR CR LF"},
  };
  for (const Bad& b : bad)
    EXPECT_EQ(record_error(b.text, "x.at2").rfind(b.expected, 0), 0u) << record_error(b.text, "x.at2");
}

// "UNITS OF GAL" passed as g (a substring test) and made a_p 981 times too large.
TEST(RecordSuite, TheUnitIsReadAsAWordAndConvertedOrRefused) {
  const auto first = [](const std::string& unit_line) {
    return parse_record("h\nh\n" + unit_line + "\nNPTS= 2, DT= .01 SEC\n 2.5 1\n", "x.at2").a[0];
  };
  // Per unit: its spellings, and 2.5 of it in m/s^2 (the conversions of cases/README.md).
  const std::vector<std::pair<std::vector<std::string>, double>> units = {
      {{"ACCELERATION TIME HISTORY IN UNITS OF G.", "UNITS: G", "ACCELERATION IN G"}, 2.5 * 9.80665},
      {{"ACCELERATION TIME HISTORY IN UNITS OF GAL", "UNITS OF GALS", "ACCELERATION IN GAL."}, 0.025},
      {{"ACCELERATION IN CM/S/S", "UNITS OF CM/SEC/SEC", "UNITS: cm/s^2", "UNITS OF CM/S**2", "(UNITS CM/SEC2)"},
       0.025},
      {{"ACCELERATION IN M/S/S", "UNITS OF M/SEC^2", "UNITS: m/s^2", "UNITS OF M/S2"}, 2.5},
  };
  for (const auto& [spellings, si] : units)
    for (const std::string& line : spellings) EXPECT_DOUBLE_EQ(first(line), si) << line;
  // A word that merely contains a G is no unit: the station's name is not read.
  EXPECT_DOUBLE_EQ(first("GARIGLIANO-CENTRALE NUCLEARE, GALLERY G-12"), 2.5 * 9.80665);
  for (const char* other : {"ACCELERATION IN UNITS OF IN/S/S", "UNITS OF FT/S^2", "VELOCITY IN CM/S",
                            "UNITS OF MG", "UNITS: KGAL"})
    EXPECT_EQ(record_error(std::string("h\nh\n") + other + "\nNPTS= 2, DT= .01\n 1 2\n", "x.at2").rfind("x.at2:3: units: ", 0), 0u)
        << other << ": " << record_error(std::string("h\nh\n") + other + "\nNPTS= 2, DT= .01\n 1 2\n", "x.at2");
  EXPECT_EQ(record_error("h\nUNITS OF G\nUNITS OF GAL\nNPTS= 2, DT= .01\n 1 2\n", "x.at2"),
            "x.at2:3: units: gal here, g on line 2");
}

// Issue 46 (10): the El Centro file OpenSees ships says "The units are (g)", and the reader
// took the word after "units", "are", for the unit ('are' is not a unit of acceleration);
// the same file with a "*** Begin data ***" line before its NPTS line likewise. The unit is
// the first word after "units" that reads as one; a header naming no known unit is refused.
TEST(RecordSuite, TheUnitIsFoundPastLinkingWordsAsInOpenSeesElCentroHeader) {
  const std::string title = "PACIFIC ENGINEERING AND ANALYSIS STRONG-MOTION DATA\n"
                            " IMPERIAL VALLEY EARTHQUAKE 05/19/40, EL CENTRO, COMPONENT S00E\n";
  const std::string values = "NPTS=  4, DT= .02 SEC\n  .0063 -.0035\n  .0009 .0015\n";
  for (const std::string& before_npts : {std::string(), std::string("*** Begin data ***\n")}) {
    const std::string text = title + "The units are (g)\n" + before_npts + values;
    const Record r = parse_record(text, "elCentro.at2");
    ASSERT_EQ(r.a.size(), 4u) << text;
    EXPECT_DOUBLE_EQ(r.a[0], .0063 * 9.80665) << text;
    EXPECT_DOUBLE_EQ(r.t[1], .02) << text;
  }
  const auto first = [&](const std::string& unit_line) {
    return parse_record(title + unit_line + "\n" + values, "x.at2").a[0];
  };
  EXPECT_DOUBLE_EQ(first("The units are: gal"), .0063 * 0.01);
  EXPECT_DOUBLE_EQ(first("units are in cm/s2"), .0063 * 0.01);
  EXPECT_DOUBLE_EQ(first("Unit is m/s/s."), .0063);
  EXPECT_DOUBLE_EQ(first("units = [g]"), .0063 * 9.80665);
  // Linking words alone are no unit; what stands after them is read, and refused if unknown.
  EXPECT_EQ(record_error(title + "The units are furlongs\n" + values, "x.at2"),
            "x.at2:3: units: 'furlongs' is not a unit of acceleration poundbench reads (g, gal, cm/s^2, m/s^2)");
  EXPECT_EQ(record_error(title + "The units are (ft/s2)\n" + values, "x.at2").rfind("x.at2:3: units: '(ft/s2)'", 0), 0u);
}

// A record in gal, cm/s^2 or m/s^2 gives the same Pi1 as in g (issue 34's "done when"),
// with a_p given in m/s^2: the conversions, not the peak default, make them agree.
TEST(RecordSuite, ARecordInGalCmPerS2OrMPerS2GivesThePi1OfTheSameRecordInG) {
  const std::vector<double> g_values = {0.0, 0.12, -0.31, 0.25, -0.08, 0.02, 0.0};
  const auto file = [&](const char* unit, double per_g) {
    std::string text = std::string("h\nh\nACCELERATION IN ") + unit + "\nNPTS= 7, DT= .05 SEC\n";
    for (double v : g_values) {
      char number[32];
      std::snprintf(number, sizeof number, " %.17g\n", v * per_g);
      text += number;
    }
    return std::make_shared<const Record>(parse_record(text, "x.at2"));
  };
  const auto pi1 = [](std::shared_ptr<const Record> r) {
    Case c = test::make_case(Scene::pair, PulseShape::record, 1.0, 0.2, 0.5);
    c.pi5 = 0.5;
    c.samples = std::move(r);
    c.record = "x.at2";
    c.a_p = 3.0;  // m/s^2
    c.w_p = 2.0 * std::numbers::pi / 0.3;
    const Result res = reference_solver().solve(make_system(c), Settings{});
    EXPECT_EQ(res.status, Status::ok) << res.message;
    return res.pi1;
  };
  const double in_g = pi1(file("G", 1.0));
  EXPECT_GT(in_g, 0.0);
  // The values written to 17 digits and converted back: round-off of the factors, 1e-12.
  EXPECT_NEAR(pi1(file("GAL", kStandardGravity * 100.0)), in_g, 1e-12 * in_g);
  EXPECT_NEAR(pi1(file("CM/S/S", kStandardGravity * 100.0)), in_g, 1e-12 * in_g);
  EXPECT_NEAR(pi1(file("M/S/S", kStandardGravity)), in_g, 1e-12 * in_g);
}

// The load is zero before a record's first sample (cases/README.md): a record that starts at
// t = 1 gave Pi1 = nan; it must give the Pi1 of the same record with a sample (0, 0) before.
TEST(RecordSuite, ARecordStartingAfterTimeZeroIsZeroBeforeItsFirstSample) {
  const auto pi1 = [](const char* text) {
    Case c = test::make_case(Scene::pair, PulseShape::record, 1.0, 0.2, 0.5);
    c.samples = std::make_shared<const Record>(parse_record(text, "x.csv"));
    c.record = "x.csv";
    c.a_p = c.samples->peak;
    c.w_p = 2.0;
    EXPECT_FALSE(validate(c)) << *validate(c);
    const Result res = reference_solver().solve(make_system(c), Settings{});
    EXPECT_EQ(res.status, Status::ok) << res.message;
    return res.pi1;
  };
  const double late = pi1("1,0\n1.5,1\n2,-0.5\n2.5,0\n");
  const double from_zero = pi1("0,0\n1,0\n1.5,1\n2,-0.5\n2.5,0\n");
  ASSERT_TRUE(std::isfinite(late));
  // The same load, one more (empty) event: round-off only.
  EXPECT_NEAR(late, from_zero, 1e-12 * from_zero);
}

}  // namespace record_suite_tests
}  // namespace pb
