#include "sweep/mpi_job.hpp"

#include <mpi.h>
#include <signal.h>

#include <cstdlib>
#include <stdexcept>

namespace pb::mpi {

Job::Job(int& argc, char**& argv) {
  // MPI_Init starts OpenMPI's own threads. They must not take SIGINT or SIGTERM, whose
  // default action would end the rank: the sweep's watcher (output/sweep_watch.hpp) turns
  // them into a clean stop, and it can only do so if every other thread blocks them. A
  // thread inherits the mask of its creator, so the two are blocked while MPI starts.
  sigset_t stop_signals, before;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, &before);
  int provided = MPI_THREAD_SINGLE;
  const int started = MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  if (started != MPI_SUCCESS) throw std::runtime_error("MPI_Init_thread failed");
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw std::runtime_error("the MPI library does not support threads (MPI_THREAD_FUNNELED)");
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  // The ranks that share this node's cores (and memory).
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &node_size_);
  MPI_Comm_free(&node);
}

Job::~Job() { MPI_Finalize(); }

Failure Job::first_failure(const Failure& mine) const {
  const int candidate = mine.code != 0 ? rank_ : size_;
  int first = size_;
  MPI_Allreduce(&candidate, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == size_) return {};
  Failure out = rank_ == first ? mine : Failure{};
  int length = static_cast<int>(out.message.size());
  MPI_Bcast(&out.code, 1, MPI_INT, first, MPI_COMM_WORLD);
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  out.message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(out.message.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  return out;
}

void Job::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; this tells the compiler so
}

}  // namespace pb::mpi
