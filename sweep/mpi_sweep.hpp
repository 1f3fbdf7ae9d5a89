#pragma once
// A sweep shared out among the ranks of an MPI job (built only with MPI).
//
// Rank 0 holds the tasks still to run and hands them out on request, in chunks; every
// rank, rank 0 included, solves its tasks on its own threads (run_sweep) and rank 0
// gathers the rows. Run costs differ by orders of magnitude across a case set, so nothing
// is split in advance:
//   - a rank asks for more while it still has as many tasks queued as it has threads, so
//     its threads never wait for the answer;
//   - a chunk is a quarter of what is left divided among the ranks (at least what was
//     asked for), so chunks shrink towards the end and the ranks finish together;
//   - the tasks are handed out in a fixed shuffled order of blocks of 32 consecutive
//     tasks, so that a chunk holds a fair sample of cheap and expensive points rather
//     than one costly family, while a thread still solves neighbouring points in a row.
// Rows travel as their partial-file line (rows/partial_line.hpp), which reads back bit
// for bit; rank 0 passes each one to SweepOptions::on_finished and on_row as it arrives, so
// its partial file holds every row that reached it. A rank that dies takes only its queued and
// running tasks with it (MPI then ends the job); a rerun resumes the rest.
//
// Cancelling on rank 0 (SweepOptions::cancel) stops the handing out and tells every rank
// to drop its queue; the points running everywhere finish and reach rank 0. Cancelling
// another rank (a signal to that process alone) makes it finish its running points and
// leave; its queued tasks are not run and the sweep ends incomplete.
//
// Protocol, all point to point with rank 0 (MPI keeps the order of the messages between
// two ranks): request (how many tasks wanted; 0: leaving) -> tasks (a chunk; empty: no
// more, the last message a rank waits for); row; stop (drop the queue); done (no more
// rows from this rank). A rank leaves only after its empty chunk, so that no message to it
// is left unreceived.

#include <cstddef>
#include <span>
#include <vector>

#include "cases/case.hpp"
#include "cases/case_list.hpp"
#include "sweep/mpi_job.hpp"
#include "rows/row.hpp"
#include "sweep/sweep.hpp"

namespace pb::mpi {

// Collective. todo: the tasks to run (rank 0's list; the others' is not read).
// options.threads, cancel: each rank's own; on_finished, on_row, on_progress: rank 0's (over
// the rows of every rank); next_task: not used. Rank 0 returns every row (sorted by run, then point),
// the other ranks none.
std::vector<Row> run_sweep(const Job& job, const CaseList& cases, std::span<const SweepRun> runs,
                           std::span<const std::size_t> todo, const SweepOptions& options);

}  // namespace pb::mpi
