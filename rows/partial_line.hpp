#pragma once
// A row's line with its run: the record of a sweep's partial file (output/partial_rows.hpp)
// and the line that carries a row from an MPI rank to rank 0 (sweep/mpi_sweep.hpp), which
// reads back bit for bit. It is the CSV line of rows/row.hpp with, in a sweep of several runs
// (a work-precision or stress study), the run's index as a first column. It lives here, below
// the sweep and the output room, so that both write and read the one format.

#include <string>
#include <string_view>

#include "rows/row.hpp"

namespace pb {

// Without a line end. with_run: the `run` column first.
std::string partial_header(bool with_run);
std::string partial_line(const Row& row, bool with_run);
// The row of one partial_line record (the run column read into Row::run); throws
// RowReadError.
Row parse_partial_line(std::string_view record, bool with_run);

}  // namespace pb
