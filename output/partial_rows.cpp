#include "output/partial_rows.hpp"

#include <algorithm>
#include <array>

#include "rows/row_read.hpp"

namespace pb {

namespace {

// The columns that say which task a row is: its case and its solver's settings.
constexpr std::array kTaskColumns = {"family", "scene", "pulse", "directivity", "pi2",  "pi3",     "eps",
                                     "pi5",    "pi6",   "pi7",   "pi8",         "xi",   "n_free",  "a_p",
                                     "w_p",    "solver", "variant", "settings", "bodies", "kick",
                                     "cycles", "mp_gamma", "mp_nu", "record"};

// Checks each record against the task it names, field for field as csv_line writes them.
class TaskCheck {
 public:
  TaskCheck(const CaseList& cases, std::span<const SweepRun> runs) : cases_(cases), runs_(runs) {
    const std::vector<std::string> header = split_csv(csv_header());
    for (const char* column : kTaskColumns)
      columns_.push_back(static_cast<std::size_t>(std::find(header.begin(), header.end(), column) - header.begin()));
    for (const SweepRun& run : runs) settings_.push_back(run.solver->describe(run.settings));
  }

  // "" when the row is the task's; otherwise why not. A row read back prints the line it
  // was read from, so its fields are compared as printed (`printed`: csv_line(row)).
  std::string mismatch(const Row& row, const std::string& printed) const {
    const std::string which =
        "point " + std::to_string(row.point) + (runs_.size() > 1 ? " of run " + std::to_string(row.run) : "");
    if (row.run >= runs_.size()) return "run " + std::to_string(row.run) + ": this sweep has " +
                                        std::to_string(runs_.size()) + " runs";
    if (row.point >= cases_.size())
      return which + ": this sweep has " + std::to_string(cases_.size()) + " points";
    Row expected;
    expected.input = cases_[row.point];
    const SweepRun& run = runs_[row.run];
    expected.solver = std::string(run.solver->name);
    expected.variant = run.settings.variant;
    expected.settings = settings_[row.run];
    const std::vector<std::string> fields = split_csv(printed);
    const std::vector<std::string> want = split_csv(csv_line(expected));
    for (std::size_t k = 0; k < columns_.size(); ++k) {
      const std::size_t i = columns_[k];
      if (fields[i] != want[i])
        return which + ": " + kTaskColumns[k] + " is \"" + fields[i] + "\" there, \"" + want[i] + "\" here";
    }
    return {};
  }

 private:
  const CaseList& cases_;
  std::span<const SweepRun> runs_;
  std::vector<std::size_t> columns_;   // of kTaskColumns in the header
  std::vector<std::string> settings_;  // describe() of each run
};

}  // namespace

std::vector<Row> read_partial_rows(std::istream& in, std::string_view file, const CaseList& cases,
                                   std::span<const SweepRun> runs) {
  std::vector<Row> rows;
  for_each_partial_row(in, file, cases, runs, [&](Row&& row) { rows.push_back(std::move(row)); });
  std::sort(rows.begin(), rows.end(), task_order);
  return rows;
}

void for_each_partial_row(std::istream& in, std::string_view file, const CaseList& cases,
                          std::span<const SweepRun> runs, const std::function<void(Row&&)>& each,
                          PartialFileShape* shape) {
  PartialFileShape seen_shape;
  if (!shape) shape = &seen_shape;
  *shape = PartialFileShape{};
  const bool with_run = runs.size() > 1;
  const std::string afresh = " (remove the file to start afresh)";
  std::string record;
  std::size_t line = 1;  // of the record's first line
  const auto fail = [&](const std::string& reason) -> PartialRowsError {
    return PartialRowsError(std::string(file) + ":" + std::to_string(line) + ": " + reason);
  };
  if (!read_csv_record(in, record)) return;  // empty, or cut within the header
  if (record != partial_header(with_run))
    throw fail("not the partial file of this sweep: its header is not this sweep's" + afresh);
  // Past the last whole record: the header's end, then each record and its line end counted (a
  // tellg() per record was a system call each). A stream that cannot say is rewritten.
  if (const std::streamoff at = in.tellg(); at < 0) shape->as_printed = false;
  else shape->whole_bytes = static_cast<std::uint64_t>(at);

  const TaskCheck check(cases, runs);
  std::vector<std::size_t> seen(cases.size() * runs.size(), 0);  // each task's line; 0: none yet
  for (line += 1; read_csv_record(in, record); line += 1 + static_cast<std::size_t>(std::ranges::count(record, '\n'))) {
    Row row;
    try {
      row = parse_partial_line(record, with_run);
    } catch (const RowReadError& e) {
      // Only an edit or a damaged disk makes one: poundbench writes rows that pass the
      // same check. Refused rather than rerun, so that nothing is recomputed unasked.
      throw fail(std::string("not a row: ") + e.what() + " (delete the line to run that point again, or remove the file to start afresh)");
    }
    const std::string printed = csv_line(row);
    if (const std::string why = check.mismatch(row, printed); !why.empty())
      throw fail(why + ": the file is from another sweep" + afresh);
    // Two rows of one task (files joined, or two sweeps on one output) may differ, and
    // keeping either would be a silent choice.
    std::size_t& first = seen[row.run * cases.size() + row.point];
    if (first != 0)
      throw fail("point " + std::to_string(row.point) + (with_run ? " of run " + std::to_string(row.run) : "") +
                 ": a second row (the first is on line " + std::to_string(first) + "); delete one of the two lines");
    first = line;
    row.input = cases[row.point];  // exactly the case, also in the columns the CSV leaves empty
    // The line a rewrite would write (the case's columns printed from the case itself).
    shape->as_printed = shape->as_printed && record == partial_line(row, with_run);
    each(std::move(row));
    shape->whole_bytes += record.size() + 1;  // exact where as_printed holds: the lines end in '\n' alone
  }
}

}  // namespace pb
