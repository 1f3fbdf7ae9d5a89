#pragma once
// The cores of a sweep's workers, where the external solver's persistent programs run
// (docs/external.md, "Threads, repetitions, one pass").
//
// A persistent program answers a case in microseconds, so every point is two wake-ups: the
// program's, when the case is written, and the worker's, when the answer is. Left to the
// scheduler, the woken one often lands on the other, idle, virtual CPU, which must first
// wake: a trivial program cost 74 us a point unpinned on this project's idle 2-vCPU machine,
// 16 us with poundbench and the program on one core (scripts/persistent_overhead.py). So
// where a sweep runs a persistent program and has no more workers than cores, worker k runs
// on the k-th core of poundbench's affinity, and its program with it (posix_spawn's child
// starts with the calling thread's affinity: nothing to set between fork and exec).
//
// Nothing else is pinned: a sweep of in-process solvers gains nothing from it (they never
// wait on another process) and would lose the scheduler's freedom to move a worker off a
// core another program is using; an MPI job's ranks share a node's cores and are placed by
// mpiexec (SweepOptions::pin_persistent is off there).

#include <sched.h>

#include <span>
#include <vector>

#include "sweep/sweep.hpp"

namespace pb {

// The cores the sweep's workers are pinned to, worker k to cores[k]; empty: none is pinned.
std::vector<int> worker_cores(std::span<const SweepRun> runs, unsigned threads, bool pin_persistent);

// Pins the calling thread to `core` for its lifetime and puts its affinity back after (a
// sweep of one thread runs on its caller: a Python interpreter's, a command's main thread).
// core < 0: does nothing.
class PinnedThread {
 public:
  explicit PinnedThread(int core);
  PinnedThread(const PinnedThread&) = delete;
  PinnedThread& operator=(const PinnedThread&) = delete;
  ~PinnedThread();

 private:
  bool pinned_ = false;
  cpu_set_t before_{};
};

}  // namespace pb
