#pragma once
// The external protocol's two documents for the buildings scene (cases/buildings.hpp;
// docs/external.md, "The buildings scene"; their schemas are the `buildings` branches of
// docs/external/case.schema.json and answer.schema.json). The case carries what a program needs
// to solve the scene without re-deriving anything: per building its floor masses, storey
// stiffnesses and its damping matrix C with the rule it came from; the contacts by building and
// floor with the gap; eps; the load as the single oscillators' document carries it; t_end, the
// step asked for and the limits. The answer is a BuildingsResult: per floor the peak |u|, per
// storey the peak drift, per contact its impacts. Same protocol and version as the single
// oscillators' documents: the case says its scene ("scene": "buildings"), which a program that
// knows only the oscillators refuses as an unknown key (or a missing "bodies").

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "programs/protocol.hpp"

namespace pb::programs {

inline constexpr std::string_view kBuildingsSceneName = "buildings";

// The case of `model` solved with `settings`, the step h a time-stepper should take (NaN: none
// was asked for, the program's own): "" and the text (one line, ending in '\n'), or an error for
// a model JSON cannot carry (a number not finite).
CaseDocument buildings_case_document(const BuildingModel& model, const Settings& settings,
                                     double step = std::numeric_limits<double>::quiet_NaN());

// The answer read into `result` (its step kept unless the answer gives one): "" or "answer:
// field: why", the result then untouched. Refused, naming the field: a key not of a buildings
// answer, a key twice, nesting too deep, a message over 10,000 bytes; with status ok, a floor
// or storey without its peak, or contacts not one per contact of the case; a peak that is not a
// number >= 0, a count that is not whole, a time outside the run, a contact that names other
// floors or buildings than the case's; a document still being read at `deadline`.
std::string read_buildings_answer(std::string_view text, const BuildingModel& model, buildings::BuildingsResult& result,
                                  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

}  // namespace pb::programs
