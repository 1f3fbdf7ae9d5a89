#pragma once
// What an LCP solver of pb::lcp reports, shared by enumerate, lemke and pgs.

#include <string_view>

namespace pb::lcp {

enum class Status {
  solved,         // z >= 0, w = A z + q >= 0, z^T w = 0 within the solver's tolerance
  no_solution,    // enumeration found no active set / Lemke ended on a secondary ray
  iteration_cap,  // pivot or sweep cap reached before a solution
  bad_input,      // sizes disagree, non-finite data, or a non-positive PGS diagonal
};

constexpr std::string_view name(Status s) {
  switch (s) {
    case Status::solved: return "solved";
    case Status::no_solution: return "no_solution";
    case Status::iteration_cap: return "iteration_cap";
    case Status::bad_input: return "bad_input";
  }
  return "?";
}

}  // namespace pb::lcp
