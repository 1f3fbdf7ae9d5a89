#pragma once
// How `run` gets its one case: from flags (--scene ... --eps ...), or as one point of a
// case-set file (--case-file FILE --point K).

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

#include "cases/case.hpp"

namespace pb::app {

struct CaseFlags {
  std::string scene, pulse, directivity;
  double pi2 = 0, pi3 = 0, eps = 0, pi5 = 0, pi6 = 0, pi7 = 0, pi8 = 0;
  double xi = Case{}.xi, n_free = Case{}.n_free, a_p = Case{}.a_p, w_p = Case{}.w_p;
  int bodies = 0;  // chain only
  double kick = 0;  // chain only
  std::string case_file;
  long long point = 0;
};

void add_case_flags(CLI::App& command, CaseFlags& flags);

struct ChosenCase {
  Case input;
  std::size_t point = 0;  // index in the case file (0 for a case given by flags)
  std::string case_file;  // empty for a case given by flags
};

// The case the flags describe, validated; throws BadInput or CaseSetError.
ChosenCase chosen_case(const CLI::App& command, const CaseFlags& flags);

// "field: reason" from pb::validate with the field turned into its flag ("--n-free: ...").
std::string case_flag_message(const std::string& field_reason);

}  // namespace pb::app
