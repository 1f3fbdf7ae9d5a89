#pragma once
// Rows that another program wrote, read for `poundbench compare`: a file needs only the
// columns that say which case a row is and what its answer was (minimal_columns): scene,
// pulse, directivity, the case numbers its scene uses that have no default (pi2, pi3, eps;
// pi5, pi6 with a body 1; pi7, pi8 with a body 2; bodies for a chain) and pi1. These make
// the row key (case_key, rows/row.hpp) with pi1 the one number compared.
//
// A column the full reader (rows/row_read.hpp) requires but the file leaves out reads as:
// family empty, point the row's index among the rows, xi, n_free, a_p and w_p a Case's
// defaults (as in a case-set file), solver, variant and settings empty, status ok. Every
// other column is read as read_csv reads it, with the same checks; a file with every
// column reads exactly as read_csv reads it.

#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "rows/row_read.hpp"

namespace pb {

// The columns a file must have, those a scene may not use included, in header order.
std::vector<std::string_view> minimal_columns();

// RowReadError "<source>:<line>: <column>: <reason>" for a missing column or a bad row.
RowFile read_minimal_csv(std::istream& in, std::string_view source);
RowFile read_minimal_csv_file(const std::string& path);

}  // namespace pb
