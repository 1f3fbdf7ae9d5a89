#pragma once
// The sweep that `spectrum`, `workprecision` and `stress` share: resumed from its partial
// file, run on every process of the job (sweep/processes.hpp), each new row appended to the
// partial file within 0.6 s of reaching the leader (in batches: resumable_sweep.cpp says
// why and what an interrupt loses).
//
// The partial file is named after the output (partial_file_name). A rerun with the same
// output reads it (read_earlier_rows), refuses it with a BadInput if its rows are not this
// sweep's (sweep/partial_rows.hpp), and runs only the tasks it lacks. The file is rewritten
// with the rows it had (a torn last line dropped) before new rows are appended. When the
// sweep is complete the command writes its outputs and then removes the partial file, so
// there is always one place that holds every finished row.

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "app/output_lock.hpp"
#include "sweep/processes.hpp"
#include "cases/case.hpp"
#include "rows/row.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

// "<out>.partial", or "poundbench-<command>.partial.csv" in the current directory when
// the output is stdout.
std::string partial_file_name(const std::string& out, std::string_view command);

// Leader only, while checking inputs and before read_earlier_rows: the lock of the output
// `out` ("" for stdout) and its partial file (app/output_lock.hpp); BadInput when another
// sweep holds it.
OutputLock take_output_lock(const std::string& out, std::string_view command, const std::string& partial);

// Leader only, while checking inputs: throws BadInput unless the partial file can be
// written and holds nothing but rows of this sweep; returns them (none if it does not
// exist). Creates nothing.
std::vector<Row> read_earlier_rows(const std::string& partial, std::span<const Case> cases,
                                   std::span<const SweepRun> runs);

// Runs the tasks that `earlier` (the leader's) lacks, on `threads` threads per process
// (0: Processes::default_threads), with progress and interrupts as SweepWatch has them
// (`command` names the sweep in the progress lines).
// `lock` is the leader's lock of the output (app/output_lock.hpp; empty elsewhere),
// released before a second signal ends the process at once.
// On the leader, returns every row (earlier and new, sorted by run then point), or nullopt
// when interrupted: then one line on stderr says how many tasks are done and where. The
// other processes return an empty list. `lines`, when given (the leader's), receives each
// new row's line of the partial file by task (run * cases + point), "" for the earlier rows:
// a sweep of one run writes its output from them instead of formatting every row again.
// keep_rows false: no row is held in memory, on any process (SweepOptions::keep_rows); the
// leader returns an empty list once every task is done, and its output is built from the
// partial file (app/partial_output.hpp).
std::optional<std::vector<Row>> run_resumable(std::string_view command, const Processes& processes,
                                              std::span<const Case> cases, std::span<const SweepRun> runs,
                                              const std::string& partial, OutputLock& lock, std::vector<Row> earlier,
                                              unsigned threads, std::vector<std::string>* lines = nullptr,
                                              bool keep_rows = true);

// Runs `write` (the command's outputs), then removes the partial file, which is no longer
// needed. A failure to write keeps it, and the error says so: its rows are the result.
void write_outputs(const std::string& partial, const std::function<void()>& write);

}  // namespace pb::app
