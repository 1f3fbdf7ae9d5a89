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

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

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
using separation_study::rule_gap;

double required_gap(const Row& row) {
  if (row.result.status != Status::ok) return separation_study::kNone;
  return std::max(row.separation, row.separation_reversed);
}

double rule_ratio(const Row& row, std::string_view rule) {
  const double required = required_gap(row);
  return required > 0.0 ? rule_gap(row, rule) / required : separation_study::kNone;
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

std::vector<RuleSummary> summarise_rules(std::span<const RuleRatios> cases) {
  std::vector<std::string> families;
  for (const RuleRatios& c : cases)
    if (std::find(families.begin(), families.end(), c.family) == families.end()) families.push_back(c.family);
  std::vector<RuleSummary> out;
  for (const std::string& family : families)
    for (std::size_t k = 0; k < kSeparationRules.size(); ++k) {
      std::vector<double> ratios;
      for (const RuleRatios& c : cases)
        if (c.family == family && std::isfinite(c.ratio[k])) ratios.push_back(c.ratio[k]);
      RuleSummary s{family, std::string(kSeparationRules[k])};
      s.cases = ratios.size();
      s.median = percentile(ratios, 50);
      s.p16 = percentile(ratios, 16);
      s.p84 = percentile(ratios, 84);
      s.unconservative = ratios.empty() ? separation_study::kNone
                                        : static_cast<double>(std::count_if(ratios.begin(), ratios.end(),
                                                                            [](double r) { return r < 1.0; })) /
                                              static_cast<double>(ratios.size());
      out.push_back(std::move(s));
    }
  return out;
}

std::vector<RuleSummary> summarise_rules(std::span<const Row> given) {
  std::vector<RuleRatios> cases;
  cases.reserve(given.size());
  for (const Row& row : given) {
    RuleRatios c{row.input.family, {}};
    for (std::size_t k = 0; k < kSeparationRules.size(); ++k) c.ratio[k] = rule_ratio(row, kSeparationRules[k]);
    cases.push_back(std::move(c));
  }
  return summarise_rules(std::span<const RuleRatios>(cases));
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
    line.number(c.scene == Scene::wall ? separation_study::kNone : c.pi5);
    line.number(c.scene == Scene::wall ? separation_study::kNone : c.pi6);
    line.number(c.xi);
    // T_1 / T_0 = w0 / w1 = Pi5: the neighbour's period over body 0's.
    line.number(c.scene == Scene::wall ? separation_study::kNone : c.pi5);
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
      line.number(r && r->result.status == Status::ok ? r->result.pi1 / r->pi1_no_contact : separation_study::kNone);
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

double required_gap(const FloorSeparation& s) { return std::max(s.required, s.reversed); }

double rule_ratio(const FloorSeparation& s, std::string_view rule) {
  const double required = required_gap(s);
  const double gap = rule == "abs" ? s.rules.abs : rule == "srss" ? s.rules.srss : s.rules.ddc;
  return required > 0.0 ? gap / required : separation_study::kNone;
}

BuildingsSeparation buildings_separation(const BuildingScene& scene, const buildings::BuildingsResult& free) {
  BuildingsSeparation out;
  out.status = free.status;
  out.message = free.message;
  if (validate(scene).empty()) out.floors = floor_separations(assemble(scene), free);
  return out;
}

std::vector<RuleRatios> buildings_rule_ratios(std::span<const BuildingCase> points,
                                              std::span<const BuildingsSeparation> found) {
  std::vector<RuleRatios> out;
  for (std::size_t p = 0; p < points.size() && p < found.size(); ++p) {
    if (found[p].status != Status::ok) continue;
    for (const FloorSeparation& s : found[p].floors) {
      RuleRatios c{points[p].family, {}};
      for (std::size_t k = 0; k < kSeparationRules.size(); ++k) c.ratio[k] = rule_ratio(s, kSeparationRules[k]);
      out.push_back(std::move(c));
    }
  }
  return out;
}

std::vector<BuildingCase> buildings_fraction_points(std::span<const BuildingCase> points,
                                                    std::span<const BuildingsSeparation> found,
                                                    std::span<const double> fractions) {
  std::vector<BuildingCase> out;
  out.reserve(points.size() * fractions.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    double gap = 0.0;
    if (p < found.size() && found[p].status == Status::ok)
      for (const FloorSeparation& s : found[p].floors) gap = std::max(gap, s.required);
    for (const double f : fractions) {
      BuildingCase c = points[p];
      if (std::isfinite(gap) && gap > 0.0) c.scene.delta = f * gap;  // the scene solved; c.pi3 says what the set gave
      out.push_back(std::move(c));
    }
  }
  return out;
}

void write_buildings_separation_table(std::ostream& out, std::span<const BuildingCase> points,
                                      std::span<const BuildingsSeparation> found,
                                      std::span<const buildings::BuildingsResult> at_fraction,
                                      std::span<const double> fractions) {
  LineBuilder head;
  for (const char* c : {"family", "point", "pulse", "record", "directivity", "left", "right", "floor", "period_ratio",
                        "status", "required_m", "separation_m", "separation_reversed_m"})
    head.text(c);
  for (const std::string_view rule : kSeparationRules) head.text(rule);
  for (const std::string_view rule : kSeparationRules) head.text(std::string(rule) + "_m");
  for (const double f : fractions)
    for (const char* side : {"left", "right"}) head.text(std::string("amplification_") + side + "_" + fraction_label(f));
  out << head.take() << '\n';
  for (std::size_t p = 0; p < points.size() && p < found.size(); ++p) {
    const BuildingCase& c = points[p];
    const bool ok = found[p].status == Status::ok;
    for (const FloorSeparation& s : found[p].floors) {
      LineBuilder line;
      line.text(c.family);
      line.count(static_cast<long long>(p));
      line.text(name(c.pulse));
      line.text(c.record);
      line.text(name(c.directivity));
      line.count(s.left);
      line.count(s.right);
      line.count(s.floor);
      line.number(s.period_ratio);
      line.text(name(found[p].status));
      line.number(ok ? required_gap(s) : separation_study::kNone);
      line.number(ok ? s.required : separation_study::kNone);
      line.number(ok ? s.reversed : separation_study::kNone);
      for (const std::string_view rule : kSeparationRules) line.number(ok ? rule_ratio(s, rule) : separation_study::kNone);
      for (const double x : {s.rules.abs, s.rules.srss, s.rules.ddc}) line.number(ok ? x : separation_study::kNone);
      for (std::size_t k = 0; k < fractions.size(); ++k) {
        const std::size_t i = p * fractions.size() + k;
        const buildings::BuildingsResult* r = i < at_fraction.size() ? &at_fraction[i] : nullptr;
        const auto amplification = [&](int building, double free_peak) {
          const auto b = static_cast<std::size_t>(building), f = static_cast<std::size_t>(s.floor - 1);
          if (!ok || !r || r->status != Status::ok || b >= r->floor_peak.size() || f >= r->floor_peak[b].size())
            return separation_study::kNone;
          return r->floor_peak[b][f] / free_peak;
        };
        line.number(amplification(s.left, s.peak_left));
        line.number(amplification(s.right, s.peak_right));
      }
      out << line.take() << '\n';
    }
  }
}

}  // namespace pb
