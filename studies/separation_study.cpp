#include "studies/separation_study.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cases/physical.hpp"
#include "rows/line_builder.hpp"
#include "studies/stats.hpp"

namespace pb {

// Named, not anonymous: a unity build puts this file beside others with helpers of these names.
namespace separation_study {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double rule_gap(const Row& row, std::string_view rule) {
  return rule == "abs" ? row.separation_abs : rule == "srss" ? row.separation_srss : row.separation_ddc;
}

std::string fraction_label(double f) {
  LineBuilder b;
  b.number(f);
  return b.take();
}

}  // namespace separation_study

using separation_study::fraction_label;
using separation_study::kNaN;
using separation_study::rule_gap;

double required_gap(const Row& row) {
  if (row.result.status != Status::ok) return kNaN;
  return std::max(row.separation, row.separation_reversed);
}

double rule_ratio(const Row& row, std::string_view rule) {
  const double required = required_gap(row);
  return required > 0.0 ? rule_gap(row, rule) / required : kNaN;
}

std::vector<Case> fraction_cases(std::span<const Row> given, std::span<const double> fractions) {
  std::vector<Case> out;
  out.reserve(given.size() * fractions.size());
  for (const Row& row : given)
    for (const double f : fractions) {
      Case c = row.input;
      if (std::isfinite(row.separation) && row.separation > 0.0) c.pi3 = f * row.separation;
      // The gap is given as a Pi term now: a physical gap would be the old one.
      c.physical.gap = std::isnan(c.physical.gap) ? c.physical.gap : c.pi3 * length_unit(c);
      out.push_back(std::move(c));
    }
  return out;
}

std::vector<RuleSummary> summarise_rules(std::span<const Row> given) {
  std::vector<std::string> families;
  for (const Row& row : given)
    if (std::find(families.begin(), families.end(), row.input.family) == families.end())
      families.push_back(row.input.family);
  std::vector<RuleSummary> out;
  for (const std::string& family : families)
    for (const std::string_view rule : kSeparationRules) {
      std::vector<double> ratios;
      for (const Row& row : given)
        if (row.input.family == family && std::isfinite(rule_ratio(row, rule))) ratios.push_back(rule_ratio(row, rule));
      RuleSummary s{family, std::string(rule)};
      s.cases = ratios.size();
      s.median = percentile(ratios, 50);
      s.p16 = percentile(ratios, 16);
      s.p84 = percentile(ratios, 84);
      s.unconservative = ratios.empty() ? kNaN
                                        : static_cast<double>(std::count_if(ratios.begin(), ratios.end(),
                                                                            [](double r) { return r < 1.0; })) /
                                              static_cast<double>(ratios.size());
      out.push_back(std::move(s));
    }
  return out;
}

void write_separation_table(std::ostream& out, std::span<const Row> given, std::span<const Row> at_fraction,
                            std::span<const double> fractions) {
  LineBuilder head;
  for (const char* c : {"family", "point", "scene", "pulse", "record", "directivity", "pi2", "pi5", "pi6", "xi",
                        "period_ratio", "status", "required_m", "required_pi", "separation_m", "separation_reversed_m"})
    head.text(c);
  for (const std::string_view rule : kSeparationRules) head.text(rule);
  for (const std::string_view rule : kSeparationRules) head.text(std::string(rule) + "_m");
  for (const double f : fractions) head.text("amplification_" + fraction_label(f));
  out << head.take() << '\n';
  for (std::size_t p = 0; p < given.size(); ++p) {
    const Row& row = given[p];
    const Case& c = row.input;
    const double unit = length_unit(c);
    LineBuilder line;
    line.text(c.family);
    line.count(static_cast<long long>(row.point));
    line.text(name(c.scene));
    line.text(name(c.pulse));
    line.text(c.record);
    line.text(name(c.directivity));
    line.number(c.pi2);
    line.number(c.scene == Scene::wall ? kNaN : c.pi5);
    line.number(c.scene == Scene::wall ? kNaN : c.pi6);
    line.number(c.xi);
    // T_1 / T_0 = w0 / w1 = Pi5: the neighbour's period over body 0's.
    line.number(c.scene == Scene::wall ? kNaN : c.pi5);
    line.text(name(row.result.status));
    line.number(required_gap(row) * unit);
    line.number(required_gap(row));
    line.number(row.separation * unit);
    line.number(row.separation_reversed * unit);
    for (const std::string_view rule : kSeparationRules) line.number(rule_ratio(row, rule));
    for (const std::string_view rule : kSeparationRules) line.number(rule_gap(row, rule) * unit);
    for (std::size_t k = 0; k < fractions.size(); ++k) {
      const std::size_t i = p * fractions.size() + k;
      const Row* r = i < at_fraction.size() ? &at_fraction[i] : nullptr;
      line.number(r && r->result.status == Status::ok ? r->result.pi1 / r->pi1_no_contact : kNaN);
    }
    out << line.take() << '\n';
  }
}

void write_rule_summary(std::ostream& out, std::span<const RuleSummary> summary) {
  out << "family,rule,cases,median,p16,p84,unconservative\n";
  for (const RuleSummary& s : summary) {
    LineBuilder line;
    line.text(s.family);
    line.text(s.rule);
    line.count(static_cast<long long>(s.cases));
    for (const double x : {s.median, s.p16, s.p84, s.unconservative}) line.number(x);
    out << line.take() << '\n';
  }
}

}  // namespace pb
