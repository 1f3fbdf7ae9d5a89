#pragma once
// The report target of issue 46: `poundbench report` on mutated study outputs, the surface its
// hostile campaign reached and the fuzzer did not (a family named with '|', '/' or 5,000
// characters gave a traceback and a half-written folder; err_median = -1 was ranked cheapest;
// a study named README.md inside --out was overwritten).
//
// An input is a study's files and where they lie, as one text (the corpus's form, corpus/report/):
//
//     @@ study s.csv          the study's file (a summary, or a spectrum's rows) and its name
//     <its CSV>
//     @@ points p.csv         optional: the study's --points
//     <its CSV>
//     @@ out report           the --out folder ("." is the folder the inputs are in)
//     @@ expect 2             optional: the input must be refused (a value outside its
//                             column's domain in a row the report reads)
//
// The mutations change a field (names with separators, a line end, 5,000 and 100,000
// characters; negative, NaN, infinite and huge numbers; settings that are no JSON object),
// remove a column, duplicate or remove a row, cut a file short, drop the points, and put the
// inputs in --out under the names the report writes.
//
// The property: exit 0 or 2, never a traceback, within kReportSeconds; on 2, stderr is one line
// starting "poundbench: ", and nothing is new in the folder the run started in (no --out, no
// folder of its own left); on 0, stderr is empty and --out holds README.md, report.html and
// every figure README.md shows; and never is an input changed. An input that must be refused
// (the mutation that made it put a negative, NaN or non-numeric value into a number column
// the report reads) exits 2.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tests/fuzz/child.hpp"
#include "tests/fuzz/mutator.hpp"

namespace pb::fuzz {

// A report of the corpus's tiny studies takes 1 to 3 s of a core (Python, matplotlib, four
// figures); the bound is for a machine ten times slower (issue 46, item 12: a hang check must
// not fail on a loaded machine), so only a report that never ends meets it.
inline constexpr double kReportSeconds = 120;

// The property `text` (the form above) violates through `poundbench report`, or nothing.
std::optional<std::string> check_report(const std::string& text, const ChildLimits& limits);
// The seeds: corpus/report-seeds/*.csv, poundbench's own outputs for a tiny case set (seeds,
// not findings: the corpus replay leaves them to the campaign and to tests/report_smoke.sh).
std::vector<std::string> report_seeds();
// `seed` changed by one to four mutations.
std::string mutate_report(std::string_view seed, Rng& rng);

}  // namespace pb::fuzz
