#pragma once
// The MPI job a sweep runs on (built only when MPI is found: POUNDBENCH_HAVE_MPI). MPI is
// initialised for MPI_THREAD_FUNNELED: every MPI call of poundbench is made by the thread
// that constructed the Job (the main thread), while the sweep's worker threads only solve.
// The header does not include mpi.h, so nothing outside sweep/mpi_*.cpp depends on it.

#include <string>

namespace pb::mpi {

// A failure one rank had, as every rank learns it (Job::first_failure).
struct Failure {
  int code = 0;  // 0: no rank failed
  std::string message;
};

class Job {
 public:
  Job(int& argc, char**& argv);  // MPI_Init_thread; throws std::runtime_error
  ~Job();                        // MPI_Finalize
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  int ranks_on_this_node() const { return node_size_; }

  // Collective: every rank passes its own failure (code 0: none) and gets back the one of
  // the lowest rank that failed, or code 0 when none did.
  Failure first_failure(const Failure& mine) const;

  // Ends every rank of the job with `code` (MPI_Abort).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  int node_size_ = 1;
};

}  // namespace pb::mpi
