#pragma once
// How `run` gets its one case: from flags (--scene ... --eps ...), or as one point of a
// case-set file (--case-file FILE --point K).

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "cases/case.hpp"
#include "cases/case_set.hpp"
#include "cases/fields.hpp"

namespace pb {
struct BuildingCase;  // cases/buildings_set.hpp
}

namespace pb::app {

struct CaseFlags {
  std::string scene, pulse, directivity;
  Case numbers;  // the flags of cases/fields.hpp write into their members; defaults are Case's
  std::array<double, kCaseAliases.size()> aliases{};  // the flags of kCaseAliases (--tp), in its order
  std::string case_file;
  long long point = 0;
};

void add_case_flags(CLI::App& command, CaseFlags& flags);

struct ChosenCase {
  Case input;
  std::size_t point = 0;  // index in the case file (0 for a case given by flags)
  std::string case_file;  // empty for a case given by flags
  // A point of a buildings case set (cases/buildings_set.hpp), which `input` does not
  // describe; null for every other case. Only chosen_case_or_buildings gives one.
  std::shared_ptr<const BuildingCase> building{};
};

// The case the flags describe, validated; throws BadInput or CaseSetError.
ChosenCase chosen_case(const CLI::App& command, const CaseFlags& flags);
// The same, with `given(flag)` saying which flags ("--pi3") were given: the Python module's
// keywords take this path, so that they are checked with the command line's messages.
using GivenFlag = std::function<bool(std::string_view flag)>;
ChosenCase chosen_case(const GivenFlag& given, const CaseFlags& flags);
// The same, where a point of a buildings case set is taken too (`run`, poundbench.run): it is
// in `building`. chosen_case refuses one, saying what solves it.
ChosenCase chosen_case_or_buildings(const GivenFlag& given, const CaseFlags& flags);

// Every case of a case-set file validated ("FILE: point K: field: reason"); throws BadInput.
void validate_case_set(const CaseList& cases, const std::string& file);
inline void validate_case_set(const CaseSet& set, const std::string& file) { validate_case_set(set.cases, file); }

// "field: reason" from pb::validate with the field turned into its flag ("--n-free: ...").
std::string case_flag_message(const std::string& field_reason);

}  // namespace pb::app
