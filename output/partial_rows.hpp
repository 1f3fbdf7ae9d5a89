#pragma once
// The partial file of a sweep: the rows it has finished, in the order they finished, so
// that an interrupted sweep (Ctrl-C, a crash, a lost MPI rank) resumes where it stopped.
//
// Format: CSV with the columns of rows/row.hpp. A sweep of several runs (a work-precision
// or stress study) puts a `run` column first, the run's index (0 is the truth), since the
// same point appears once per run; a sweep of one run (spectrum) has exactly the output's
// columns. The same line, with the run column, carries a row from an MPI rank to rank 0
// (the line's format: rows/partial_line.hpp).
//
// A partial file is only resumed by the sweep that wrote it: every row must name a task of
// the sweep (a run and a point in range) whose case, solver, variant and settings are the
// ones this sweep would run, field for field as the CSV writes them. One row that does not
// is a PartialRowsError: such a file comes from another case set or other settings, and
// mixing its rows in would give a wrong result. A last line cut short (a write interrupted
// by a crash) is dropped. The solver's step cap and time limit are not in a row, so
// changing them does not invalidate the rows (docs/cli.md says so).

#include <cstdint>
#include <functional>
#include <istream>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cases/case.hpp"
#include "cases/case_list.hpp"
#include "rows/partial_line.hpp"  // partial_header, partial_line, parse_partial_line
#include "rows/row.hpp"
#include "sweep/sweep.hpp"

namespace pb {

// what() is one line: "<file>:<line>: <reason>".
struct PartialRowsError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The rows of a partial file of the sweep (cases, runs), each checked as above and by
// row_problem (rows/row.hpp), sorted by task. An empty input has no rows. Throws
// PartialRowsError naming `file` and the line: for a row of another sweep, a damaged row
// (an ok without a finite Pi1, a negative count), and a second row of one task.
std::vector<Row> read_partial_rows(std::istream& in, std::string_view file, const CaseList& cases,
                                   std::span<const SweepRun> runs);
// What for_each_partial_row saw of the file as written: whether each row's record is the
// line partial_line prints for it, and where the last whole record ends (a torn last line
// starts there). A file whose rows are all as printed is resumed by cutting it there, not
// rewritten: rewriting read every row a second time, 45 % of a resume's instructions.
struct PartialFileShape {
  bool as_printed = true;
  std::uint64_t whole_bytes = 0;  // the header and every whole record; 0: no header
};

// The same rows, checked the same way, each handed to `each` in the file's order and not
// kept: a million rows held were 1.5 GB (issue 36). `shape`, when given, is filled in.
void for_each_partial_row(std::istream& in, std::string_view file, const CaseList& cases,
                          std::span<const SweepRun> runs, const std::function<void(Row&&)>& each,
                          PartialFileShape* shape = nullptr);

}  // namespace pb
