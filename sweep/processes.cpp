#include "sweep/processes.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

#include "sweep/mpi_job.hpp"  // the class alone: its functions exist only in a build with MPI

#ifdef POUNDBENCH_HAVE_MPI
#include "sweep/mpi_sweep.hpp"
#endif

namespace pb {

namespace {

bool launched_by_mpi() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(variable)) return true;
  return false;
}

}  // namespace

#ifdef POUNDBENCH_HAVE_MPI

Processes::Processes(int& argc, char**& argv) {
  if (launched_by_mpi()) job_ = std::make_shared<const mpi::Job>(argc, argv);
}

#else

namespace {

// The number of processes a launcher started, where it says (1 where it does not).
long launched_size() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* value = std::getenv(variable)) return std::strtol(value, nullptr, 10);
  return 1;
}

}  // namespace

Processes::Processes(int&, char**&) {
  if (launched_by_mpi() && launched_size() > 1)
    throw std::runtime_error("this poundbench was built without MPI, so " + std::to_string(launched_size()) +
                             " processes would each run the whole sweep; build it with libopenmpi-dev installed");
}

#endif

bool Processes::leader() const { return !job_ || job_->rank() == 0; }

int Processes::count() const { return job_ ? job_->size() : 1; }

unsigned Processes::default_threads() const {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (!job_) return cores;
  return std::max(1u, cores / static_cast<unsigned>(job_->ranks_on_this_node()));
}

void Processes::agree(const std::function<void()>& check, ExitCodeOf exit_code) const {
  if (!job_) return check();
#ifdef POUNDBENCH_HAVE_MPI
  mpi::Failure mine;
  try {
    check();
  } catch (const std::exception& e) {
    mine = {exit_code(e), e.what()};
  }
  const mpi::Failure first = job_->first_failure(mine);
  if (first.code != 0) throw SharedFailure(first.code, first.message);
#else
  (void)exit_code;
#endif
}

std::vector<Row> Processes::sweep(const CaseList& cases, std::span<const SweepRun> runs,
                                  std::span<const std::size_t> todo, SweepOptions options) const {
#ifdef POUNDBENCH_HAVE_MPI
  if (job_) return mpi::run_sweep(*job_, cases, runs, todo, options);
#endif
  options.next_task = tasks_from(todo);
  return run_sweep(cases, runs, options);
}

void Processes::abort_others(int code) const {
#ifdef POUNDBENCH_HAVE_MPI
  if (job_ && job_->size() > 1) job_->abort(code);
#endif
  (void)code;
}

}  // namespace pb
