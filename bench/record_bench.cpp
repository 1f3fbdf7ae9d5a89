// Cost of one run on a recorded ground motion (issue 21): the shipped 40 s record at 0.005 s
// (cases/records/mp-noise-40s.csv, 8001 samples), its Pi terms on its 1 s pulse, on a pair
// with impacts (Pi2 = 1, Pi3 = 0.5, Pi5 = 0.5, eps = 0.5). The reference takes each sample as
// an event: one with no event inside by its exact recurrence (solvers/event_driven/
// DERIVATION.md §11: 7997 of the 8004 here), the others by its full event loop; each
// time-stepper reads the record through its LoadCursor at its default N = 64 (5504 steps of
// h = T_min / 64 = 0.0078 s, T_min the 0.5 s period of body 1, over t_end = 43 s): Moreau-Jean
// the exact step mean, the engines a_g at their steps. Measured (CPU per run, medians of 9,
// the Test build's -O2, a shared 2-core machine, in one run): the reference 0.228 ms (8004
// events, 28.5 ns each; BM_RecordSolveFullEventLoop, every sample through the full loop as
// before the recurrence: 3.33 ms, 416 ns each); moreau-jean 0.070 ms (12.7 ns a step, the
// cursor's lookup included). Earlier (RelWithDebInfo): end-samples 0.12; ode 2.1; bullet 1.1;
// siconos 19; mujoco 4.3. A solver not built here is skipped.

#include <benchmark/benchmark.h>

#include <numbers>
#include <string>

#include "cases/record.hpp"
#include "cases/system.hpp"
#include "kit/solver.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/registry.hpp"

namespace {

pb::System record_system() {
  pb::Case c;
  c.scene = pb::Scene::pair;
  c.pulse = pb::PulseShape::record;
  c.samples = pb::read_record(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/mp-noise-40s.csv");
  c.record = c.samples->source;
  c.a_p = c.samples->peak;
  c.w_p = 2.0 * std::numbers::pi;  // T_p = 1 s
  c.pi2 = 1.0;
  c.pi3 = 0.5;
  c.pi5 = 0.5;
  c.pi6 = 1.0;
  c.eps = 0.5;
  return pb::make_system(c);
}

void BM_RecordSolve(benchmark::State& state, const char* solver, const char* variant) {
  const pb::SolverInfo* info = pb::find_solver(solver);
  if (info == nullptr) {
    state.SkipWithError("solver not built");
    return;
  }
  const pb::System s = record_system();
  pb::Settings settings;
  settings.variant = variant;
  settings.monitor = false;  // as a sweep times its runs
  long steps = 0;
  for (auto _ : state) {
    const pb::Result r = info->solve(s, settings);
    steps = r.steps;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["steps_or_events"] = static_cast<double>(steps);
}
BENCHMARK_CAPTURE(BM_RecordSolve, event_driven, "event-driven", "")->Unit(benchmark::kMillisecond);

// The reference with every sample through its full event loop (frame rebuilt, every search
// run): what the recurrence saves, in the same run.
void BM_RecordSolveFullEventLoop(benchmark::State& state) {
  const pb::System s = record_system();
  pb::Settings settings;
  settings.monitor = false;
  long steps = 0;
  for (auto _ : state) {
    const pb::Result r = pb::event_driven::detail::solve_searching_every_sample(s, settings);
    steps = r.steps;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["steps_or_events"] = static_cast<double>(steps);
}
BENCHMARK(BM_RecordSolveFullEventLoop)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecordSolve, moreau_jean, "moreau-jean", "")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecordSolve, moreau_jean_end_samples, "moreau-jean", "end-samples")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecordSolve, ode, "ode", "")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecordSolve, bullet, "bullet", "")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecordSolve, siconos, "siconos", "")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecordSolve, mujoco, "mujoco", "")->Unit(benchmark::kMillisecond);

}  // namespace
