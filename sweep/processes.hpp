#pragma once
// The processes a command runs on: this one alone, or every rank of an MPI job.
//
// poundbench joins an MPI job only when it was built with MPI (POUNDBENCH_HAVE_MPI) and an
// MPI launcher started it: mpirun or mpiexec (OpenMPI sets OMPI_COMM_WORLD_SIZE), or a
// scheduler's launcher speaking PMIx or PMI (srun sets PMIX_RANK or PMI_RANK). Run any
// other way it does not touch MPI at all, so a plain `poundbench ...` behaves exactly as a
// build without MPI does. A build without MPI that a launcher starts as several processes
// refuses to run: each would run the whole sweep and write the same files.
//
// In a job, every rank parses the same flags and reads the same input files; rank 0, the
// leader, alone checks and writes the outputs and the partial file, prints, and hands out
// the sweep's tasks (sweep/mpi_sweep.hpp). Before the first message of a sweep the ranks
// agree on the inputs (agree), so that a bad input ends every rank with the same exit code
// and no rank waits for one that has already left.
//
// It lives in sweep/ beside the MPI sweep it wraps, so that the command line (app/) calls
// down into one sweep layer; which failure means which exit code stays the caller's
// (agree takes it as a function).

#include <cstddef>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <memory>
#include <span>
#include <vector>

#include "cases/case.hpp"
#include "cases/case_list.hpp"
#include "rows/row.hpp"
#include "sweep/sweep.hpp"

namespace pb::mpi {
class Job;
}

namespace pb {

// A failure that every process of the job has, so each one exits with `code` and only
// the leader prints it (the first process's failure, as Processes::agree finds it).
struct SharedFailure : std::runtime_error {
  SharedFailure(int exit_code, const std::string& message) : std::runtime_error(message), code(exit_code) {}
  int code;
};

class Processes {
 public:
  // Joins the MPI job when launched as one (see above); throws std::runtime_error for a
  // build without MPI launched as several processes.
  Processes(int& argc, char**& argv);
  Processes(const Processes&) = delete;
  Processes& operator=(const Processes&) = delete;

  bool leader() const;
  int count() const;
  // Threads per process when --threads is not given: this node's cores shared among the
  // processes of the job on it.
  unsigned default_threads() const;

  // Every process runs `check`. Alone, its exceptions pass through unchanged. In a job, if
  // it threw on any process, every process throws a SharedFailure with the failure of the
  // lowest rank that failed, and the exit code exit_code(exception) gave on that rank.
  using ExitCodeOf = int (*)(const std::exception&);
  void agree(const std::function<void()>& check, ExitCodeOf exit_code) const;

  // Runs the sweep's tasks `todo` (the leader's list) on every process: run_sweep alone,
  // mpi::run_sweep in a job. The leader gets every new row, the other processes none.
  std::vector<Row> sweep(const CaseList& cases, std::span<const SweepRun> runs,
                         std::span<const std::size_t> todo, SweepOptions options) const;

  // After a failure of this process alone: in a job, ends every rank (MPI_Abort) so that
  // none waits for this one; alone, returns.
  void abort_others(int code) const;

 private:
  // Null: this process alone. A shared_ptr, whose deleter is fixed where the Job is made,
  // so a build without MPI needs no Job destructor.
  std::shared_ptr<const mpi::Job> job_;
};

}  // namespace pb
