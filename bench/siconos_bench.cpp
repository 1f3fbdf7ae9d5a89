// Cost of the Siconos solver per run and per step, on wall, pair and row3 at the Fig. 4 point
// of bench/support.hpp (Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1, eps = 0.5,
// cosine, normal), against the in-house solvers on the same cases. Built only when CMake
// finds Siconos (bench/CMakeLists.txt).
//
//   BM_Siconos/<variant>_<scene>/N           moreau-jean-lemke and moreau-jean-enum, N = 64, 256:
//                                            one pb::siconos::solve per iteration (the model and
//                                            simulation set-up included: part of every run)
//   BM_SiconosEventDriven/<scene>             event-driven-lsodar
//   BM_SiconosChain/bodies:<n>                moreau-jean-lemke on a chain of n bodies,
//                                            alternating (odd bodies Pi5 = 0.5, Pi6 = 1) with
//                                            a gap, N = 64: cost per step against n
//   BM_SiconosBaselineMoreauJean/<scene>/N   moreau_jean::solve alone
//
// Counters: time_per_step (CPU seconds per step; per event for the event-driven variant),
// steps, impacts, and the ratio of CPU time per run to the in-house solver's on the same case
// (x_moreau_jean: moreau-jean, default settings, same N; x_event_driven: the event-driven
// reference), measured right after the timed loop so that both see the same machine load
// (printed with an "s": an inverted rate; read it as a plain ratio).
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#include <benchmark/benchmark.h>

#include <ctime>
#include <string>

#include "bench/support.hpp"
#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/siconos/siconos_solver.hpp"

namespace {

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// CPU seconds per run of solve(s, settings), over >= 20 ms.
double seconds_per_run(pb::SolveFn solve, const pb::System& s, const pb::Settings& settings) {
  long runs = 0;
  const double start = cpu_now();
  double elapsed = 0.0;
  do {
    const pb::Result r = solve(s, settings);
    benchmark::DoNotOptimize(r.pi1);
    ++runs;
    elapsed = cpu_now() - start;
  } while (elapsed < 0.02);
  return elapsed / static_cast<double>(runs);
}

benchmark::Counter ratio_to(double baseline_seconds) {
  return benchmark::Counter(baseline_seconds,
                            benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void report(benchmark::State& state, const pb::Result& r) {
  if (r.status != pb::Status::ok) state.SkipWithError(r.message.c_str());
  state.counters["time_per_step"] = pb::bench::per_step(r.steps);
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["impacts"] = static_cast<double>(r.impacts);
}

void BM_Siconos(benchmark::State& state, const char* variant, pb::Scene scene) {
  const pb::System s = pb::bench::fig4_point(scene);
  pb::Settings settings;
  settings.variant = variant;
  settings.steps = static_cast<int>(state.range(0));
  pb::Result r;
  for (auto _ : state) {
    r = pb::siconos::solve(s, settings);
    benchmark::DoNotOptimize(r.pi1);
  }
  report(state, r);
  pb::Settings in_house;
  in_house.steps = settings.steps;
  state.counters["x_moreau_jean"] = ratio_to(seconds_per_run(&pb::moreau_jean::solve, s, in_house));
}

void BM_SiconosEventDriven(benchmark::State& state, pb::Scene scene) {
  const pb::System s = pb::bench::fig4_point(scene);
  pb::Settings settings;
  settings.variant = "event-driven-lsodar";
  pb::Result r;
  for (auto _ : state) {
    r = pb::siconos::solve(s, settings);
    benchmark::DoNotOptimize(r.pi1);
  }
  report(state, r);
  state.counters["x_event_driven"] = ratio_to(seconds_per_run(&pb::event_driven::solve, s, {}));
}

void BM_SiconosChain(benchmark::State& state) {
  pb::Case c;
  c.scene = pb::Scene::chain;
  c.bodies = static_cast<int>(state.range(0));
  c.pulse = pb::PulseShape::cosine;
  c.pi2 = 1.0;
  c.pi3 = 0.5;
  c.pi5 = 0.5;
  c.pi6 = 1.0;
  c.eps = 0.5;
  const pb::System s = pb::make_system(c);
  pb::Result r;
  for (auto _ : state) {
    r = pb::siconos::solve(s, pb::Settings{});
    benchmark::DoNotOptimize(r.pi1);
  }
  report(state, r);
  state.counters["x_moreau_jean"] = ratio_to(seconds_per_run(&pb::moreau_jean::solve, s, {}));
}

void BM_SiconosBaselineMoreauJean(benchmark::State& state, pb::Scene scene) {
  pb::bench::time_solve(state, &pb::moreau_jean::solve, scene);
}

#define PB_SICONOS_BENCH(fn, label, ...) \
  BENCHMARK_CAPTURE(fn, label, __VA_ARGS__)->ArgName("N")->Arg(64)->Arg(256)->Unit(benchmark::kMicrosecond)

PB_SICONOS_BENCH(BM_Siconos, lemke_wall, "moreau-jean-lemke", pb::Scene::wall);
PB_SICONOS_BENCH(BM_Siconos, lemke_pair, "moreau-jean-lemke", pb::Scene::pair);
PB_SICONOS_BENCH(BM_Siconos, lemke_row3, "moreau-jean-lemke", pb::Scene::row3);
PB_SICONOS_BENCH(BM_Siconos, enum_wall, "moreau-jean-enum", pb::Scene::wall);
PB_SICONOS_BENCH(BM_Siconos, enum_pair, "moreau-jean-enum", pb::Scene::pair);
PB_SICONOS_BENCH(BM_Siconos, enum_row3, "moreau-jean-enum", pb::Scene::row3);
PB_SICONOS_BENCH(BM_SiconosBaselineMoreauJean, wall, pb::Scene::wall);
PB_SICONOS_BENCH(BM_SiconosBaselineMoreauJean, pair, pb::Scene::pair);
PB_SICONOS_BENCH(BM_SiconosBaselineMoreauJean, row3, pb::Scene::row3);
BENCHMARK_CAPTURE(BM_SiconosEventDriven, wall, pb::Scene::wall)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SiconosEventDriven, pair, pb::Scene::pair)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SiconosEventDriven, row3, pb::Scene::row3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SiconosChain)->ArgName("bodies")->Arg(2)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace
