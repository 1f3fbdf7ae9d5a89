#include "sweep/worker_cores.hpp"

#include <pthread.h>

#include <algorithm>

#include "programs/process.hpp"

namespace pb {

std::vector<int> worker_cores(std::span<const SweepRun> runs, unsigned threads, bool pin_persistent) {
  const bool persistent = std::any_of(runs.begin(), runs.end(), [](const SweepRun& run) {
    return run.solver && run.solver->name == "external" && run.settings.variant == programs::kPersistent &&
           !run.settings.in_process;
  });
  if (!pin_persistent || !persistent) return {};
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return {};
  std::vector<int> cores;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &allowed)) cores.push_back(cpu);
  // More workers than cores: two would share one core, where the scheduler would spread them.
  // One core: there is nothing to choose.
  if (cores.size() < 2 || threads > cores.size()) return {};
  cores.resize(threads);
  return cores;
}

PinnedThread::PinnedThread(int core) {
  if (core < 0 || pthread_getaffinity_np(pthread_self(), sizeof before_, &before_) != 0) return;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(core, &one);
  pinned_ = pthread_setaffinity_np(pthread_self(), sizeof one, &one) == 0;
}

PinnedThread::~PinnedThread() {
  if (pinned_) pthread_setaffinity_np(pthread_self(), sizeof before_, &before_);
}

}  // namespace pb
