#pragma once
// The sweep that `spectrum`, `workprecision` and `stress` share: resumed from its partial
// file, run on every process of the job (sweep/processes.hpp), each new row appended to the
// partial file within 0.6 s of reaching the leader (in batches: output/partial_writer.hpp says
// why and what an interrupt loses).
//
// The partial file is named after the output (partial_file_name). A rerun with the same
// output reads it (read_earlier_rows), refuses it with a BadInput if its rows are not this
// sweep's (output/partial_rows.hpp), and runs only the tasks it lacks. The file is rewritten
// with the rows it had (a torn last line dropped) before new rows are appended. When the
// sweep is complete the command writes its outputs and then removes the partial file, so
// there is always one place that holds every finished row.

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "output/output_lock.hpp"
#include "output/partial_rows.hpp"
#include "sweep/processes.hpp"
#include "cases/case.hpp"
#include "cases/case_list.hpp"
#include "rows/row.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

// "<out>.partial", or "poundbench-<command>.partial.csv" in the current directory when
// the output is stdout.
std::string partial_file_name(const std::string& out, std::string_view command);

// Leader only, while checking inputs and before read_earlier_rows: the lock of the output
// `out` ("" for stdout) and its partial file (output/output_lock.hpp); BadInput when another
// sweep holds it.
OutputLock take_output_lock(const std::string& out, std::string_view command, const std::string& partial);

// The rows a partial file holds: kept (the studies summarise them), or only which tasks
// they are (`spectrum`, whose output is copied from the file: the rows of a million points
// are 1.5 GB held, and 450 MB of file, which the whole-file reader refuses past 256 MB).
struct EarlierRows {
  std::vector<Row> rows;   // sorted by task; none unless kept
  std::vector<bool> done;  // by task (run * cases + point); empty: none done
  std::size_t count = 0;   // the rows the file holds
  PartialFileShape file;   // as read (output/partial_rows.hpp)
};

// Leader only, while checking inputs: throws BadInput unless the partial file can be
// written and holds nothing but rows of this sweep; returns them, streamed through and
// checked one at a time (none if it does not exist). Creates nothing.
EarlierRows read_earlier_rows(const std::string& partial, const CaseList& cases, std::span<const SweepRun> runs,
                              bool keep = true);

// Runs the tasks that `earlier` (the leader's) lacks, on `threads` threads per process
// (0: Processes::default_threads), with progress and interrupts as SweepWatch has them
// (`command` names the sweep in the progress lines).
// `lock` is the leader's lock of the output (output/output_lock.hpp; empty elsewhere),
// released before a second signal ends the process at once.
// On the leader, returns every row (earlier and new, sorted by run then point), or nullopt
// when interrupted: then one line on stderr says how many tasks are done and where. The
// other processes return an empty list. `lines`, when given (the leader's), receives each
// new row's line of the partial file by task (run * cases + point), "" for the earlier rows:
// a sweep of one run writes its output from them instead of formatting every row again.
// keep_rows false: no row is held in memory, on any process (SweepOptions::keep_rows); the
// leader returns an empty list once every task is done, and its output is built from the
// partial file (output/partial_output.hpp). `earlier` then holds no rows, and the partial file's
// are streamed as it is rewritten.
std::optional<std::vector<Row>> run_resumable(std::string_view command, const Processes& processes,
                                              const CaseList& cases, std::span<const SweepRun> runs,
                                              const std::string& partial, OutputLock& lock, EarlierRows earlier,
                                              unsigned threads, std::vector<std::string>* lines = nullptr,
                                              bool keep_rows = true);

// Runs `write` (the command's outputs), then removes the partial file, which is no longer
// needed. A failure to write keeps it, and the error says so: its rows are the result.
void write_outputs(const std::string& partial, const std::function<void()>& write);

}  // namespace pb::app
