#pragma once
// Case-set files of the `buildings` scene (cases/README.md, "Buildings"): [[family]] tables
// with scene = "buildings", given floor by floor (buildings = [{masses, stiffnesses}, ...],
// gap in m) or, for uniform buildings, in Pi terms (storeys, pi2, pi3, pi5, pi6). Lists of
// values expand to points as the single oscillators' families do.
//
// A file of buildings families holds no family of the single oscillators' scenes (one point
// numbering, and the sweeps that read those files solve no buildings yet): load_case_set
// refuses a buildings family, naming `run` as what solves it, and this reader refuses the
// other scenes. Errors are CaseSetError, one line, "<file>:<line>: <field>: <reason>".

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cases/buildings.hpp"
#include "cases/case.hpp"

namespace pb {

// One point of a buildings family: the scene as a solver receives it (validated), and what
// the file gave for it, for the summary and for the Pi-term results.
struct BuildingCase {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::string family;
  BuildingScene scene;
  PulseShape pulse = PulseShape::sine;
  Directivity directivity = Directivity::normal;
  std::string record;  // the record's file as read ("" for a pulse)
  // The Pi-term form: the storey counts (left, right) and the terms; its results are reported
  // as Pi terms too (x w_p^2 / a_p, v w_p / a_p). NaN and 0 for a case given floor by floor.
  bool pi_terms = false;
  int storeys_left = 0, storeys_right = 0;
  double pi2 = kNone, pi3 = kNone, pi5 = kNone, pi6 = kNone;
};

struct BuildingsSet {
  std::string name;
  std::string description;
  std::vector<BuildingCase> points;  // families in file order, each expanded (pi2 innermost)
};

// Whether the TOML text's families are of the buildings scene: nullopt when no family says
// scene = "buildings" (the file is the single oscillators' and load_case_set reads it);
// otherwise the set, every point built and validated. Throws CaseSetError.
std::optional<BuildingsSet> parse_buildings_set(std::string_view toml_text, std::string_view source_name);
std::optional<BuildingsSet> load_buildings_set(const std::filesystem::path& file);

// The scene's name in case sets, and what load_case_set says of a buildings family.
inline constexpr std::string_view kBuildingsScene = "buildings";
std::string buildings_not_here_reason();

}  // namespace pb
