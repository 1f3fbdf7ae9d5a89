#include "sweep/stopwatch.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <limits>

namespace pb {

namespace {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Stopwatch::Stopwatch() : cpu0_(thread_cpu_seconds()), wall0_(wall_seconds()) {}

Elapsed Stopwatch::raw() const {
  Elapsed e;
  e.wall = wall_seconds() - wall0_;
  e.cpu = thread_cpu_seconds() - cpu0_;
  return e;
}

const Elapsed& Stopwatch::clock_cost() {
  static const Elapsed cost = [] {
    Elapsed least{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    for (int i = 0; i < kCalibrations; ++i) {
      const Elapsed e = Stopwatch().raw();
      least.wall = std::min(least.wall, e.wall);
      least.cpu = std::min(least.cpu, e.cpu);
    }
    return least;
  }();
  return cost;
}

Elapsed Stopwatch::elapsed() const {
  const Elapsed e = raw();
  const Elapsed& cost = clock_cost();
  return {std::max(0.0, e.wall - cost.wall), std::max(0.0, e.cpu - cost.cpu)};
}

}  // namespace pb
