#pragma once
// The separation study (`poundbench separation`): over a case set of neighbours (pairs of
// buildings over period ratios and records), how the rules engineers use for the gap (ABS,
// SRSS, DDC: kit/separation.hpp) compare with the exact gap that avoids pounding, and how
// much pounding amplifies the peak where the gap is a fraction of that one.
//
// Per case: the required gap (the larger of the load as given and reversed: a building must
// clear its neighbour whichever way the ground first moves) and each rule's gap over it; per
// family and rule, that ratio's median, 16th and 84th percentiles and the share of cases where
// the rule is short of the required gap (unconservative). Where gap fractions are asked, each
// case is solved again at gaps of those fractions of the required gap under the load as given
// (where it pounds), and body 0's peak over its no-contact peak is the amplification; a single
// storey's drift is its displacement, so that is the drift's amplification too.
//
// Buildings are taken per floor level (a contact of the scene is one case): its gap from the
// reference's free watch, the rules from the two floors' own no-contact peaks (DDC with the
// buildings' first modes), and at gap fractions the amplification of both floors' peaks.

#include <array>
#include <cstddef>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cases/buildings_set.hpp"
#include "kit/separation.hpp"
#include "kit/buildings_result.hpp"
#include "rows/row.hpp"

namespace pb {

// The rules, as the study's columns name them.
inline constexpr std::array<std::string_view, 3> kSeparationRules = {"abs", "srss", "ddc"};

// The gap a case must clear whichever way the load acts (over a_p / w_p^2; NaN if unknown).
double required_gap(const Row& row);
// A rule's gap over the required one; `rule` one of kSeparationRules. NaN where no gap is
// required (identical buildings move as one: no rule's gap has a ratio to zero).
double rule_ratio(const Row& row, std::string_view rule);

// Each case again with its gap (Pi3) at each fraction of the gap the load as given needs:
// point p, fraction k is entry p * fractions.size() + k. A case whose required gap is not
// known keeps its own gap (its row will say why in the first solve).
std::vector<Case> fraction_cases(std::span<const Row> given, std::span<const double> fractions);

struct RuleSummary {
  std::string family, rule;
  std::size_t cases = 0;
  double median = 0, p16 = 0, p84 = 0;
  double unconservative = 0;  // share of the cases with ratio < 1
};
// What the summary reads of one case (a single oscillators' row, or one floor level of a
// buildings point): its family and each rule's ratio to the required gap, in the order of
// kSeparationRules (NaN where unknown: the case is left out of that rule's summary).
struct RuleRatios {
  std::string family;
  std::array<double, 3> ratio{};
};
// Per family (in order of first appearance) and rule, over the cases with a finite ratio.
std::vector<RuleSummary> summarise_rules(std::span<const RuleRatios> cases);
// The rows' ratios (those that finished ok).
std::vector<RuleSummary> summarise_rules(std::span<const Row> given);

// The per-case table: the case, the required gaps, the rules' gaps and ratios, and per
// fraction the amplification; `at_fraction` as fraction_cases orders them (empty: none asked).
void write_separation_table(std::ostream& out, std::span<const Row> given, std::span<const Row> at_fraction,
                            std::span<const double> fractions);
void write_rule_summary(std::ostream& out, std::span<const RuleSummary> summary);

// The buildings scene, per floor level (a contact of the scene): the gap it must clear whichever
// way the load acts, max(required, reversed), and a rule's gap over it (NaN where unknown or 0).
double required_gap(const FloorSeparation& s);
double rule_ratio(const FloorSeparation& s, std::string_view rule);

// One point of a buildings set through the free watch: the reference's status and each
// contact's separation (floor_separations of buildings::free_motion).
struct BuildingsSeparation {
  Status status = Status::ok;
  std::string message;
  std::vector<FloorSeparation> floors;
};
BuildingsSeparation buildings_separation(const BuildingScene& scene, const buildings::BuildingsResult& free);

// A case per floor level, for the summary (the levels of points that finished ok).
std::vector<RuleRatios> buildings_rule_ratios(std::span<const BuildingCase> points,
                                              std::span<const BuildingsSeparation> found);
// Each point again with its gap at each fraction of the gap the load as given needs there (the
// largest over its levels, which share the one gap): point p, fraction k is entry
// p * fractions.size() + k. A point whose gap is not known keeps its own.
std::vector<BuildingCase> buildings_fraction_points(std::span<const BuildingCase> points,
                                                    std::span<const BuildingsSeparation> found,
                                                    std::span<const double> fractions);

// The per-contact table: the point (family, index, pulse, record, directivity), the contact
// (left and right building, floor), T_1,right / T_1,left, status, the required gap, the load
// as given and reversed, each rule's ratio and gap; per fraction the amplification of the two
// floors' peaks at that level (with pounding over without), from `at_fraction` (the
// reference's solves of buildings_fraction_points, in its order; empty: none asked).
void write_buildings_separation_table(std::ostream& out, std::span<const BuildingCase> points,
                                      std::span<const BuildingsSeparation> found,
                                      std::span<const buildings::BuildingsResult> at_fraction = {},
                                      std::span<const double> fractions = {});

}  // namespace pb
