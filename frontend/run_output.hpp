#pragma once
// What `run` reports of a solved case, shared by the command line and the Python module
// (python/): the object `run --json` prints, the columns of `run --history`, and the check of
// `--samples`.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frontend/case_flags.hpp"
#include "rows/row.hpp"

namespace pb::app {

// The JSON object of `run --json` (docs/cli.md); a row of a case file names it and its point.
nlohmann::ordered_json row_json(const Row& row, const ChosenCase& chosen);

// What a record case's w_p is: "mean period" when it is the record's 2 pi / T_m (the default,
// or a w_p or tp given equal to it), "given" otherwise; empty for every other pulse, and for
// a case without its samples.
std::string w_p_source(const Case& c);

// The columns of a history: t, then u, v of each body and g, lambda of each contact, labelled
// as in the paper (pair: t,u1,u0,v1,v0,g1,lambda1).
std::vector<std::string> history_columns(const Case& c);

// --samples N for the case's history: bounded so that a history fits in memory; throws BadInput.
void check_samples(int samples, const Case& c);

}  // namespace pb::app
