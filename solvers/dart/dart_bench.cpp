// Cost of the DART solver per run and per step, for each variant on wall, pair and row3 (the
// ODE benchmark's cases: Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1, eps = 0.5,
// cosine, normal) at N = 64, against moreau_jean::solve on the same cases.
//
// Counters as in ode_bench.cpp: time_per_step, steps, impacts, and x_moreau_jean, the run's
// CPU time over moreau_jean::solve's on the same case and N, measured right after the timed
// loop. N = 64 only: a step's cost does not depend on N (a run's set-up is a few percent of
// it, solvers/dart/README.md), and the main job runs every benchmark. BM_DartChain/bodies:<n>:
// dantzig-faithful on the alternating chain of ode_bench.cpp, N = 64.
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#ifdef POUNDBENCH_HAVE_DART

#include <benchmark/benchmark.h>

#include "kit/benchmarking.hpp"
#include "solvers/moreau_jean/versus.hpp"
#include "solvers/dart/dart_solver.hpp"

namespace {

const bool dart_registered = pb::bench::register_vs_moreau_jean(
    "BM_Dart", &pb::dart::solve,
    {{"dantzig_faithful", "dantzig-faithful"}, {"pgs_faithful", "pgs-faithful"}, {"default", "default"}}, {64});

void BM_DartChain(benchmark::State& state) { pb::bench::time_chain(state, &pb::dart::solve); }

BENCHMARK(BM_DartChain)->ArgName("bodies")->ArgsProduct({{2, 10, 100}})->Unit(benchmark::kMillisecond);

}  // namespace

#endif  // POUNDBENCH_HAVE_DART
