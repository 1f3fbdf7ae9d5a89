// Cost of the ODE solver per run and per step, for each variant on wall, pair and row3
// (Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1, eps = 0.5, cosine, normal) at
// N = 64 and 256, against moreau_jean::solve on the same cases.
//
// Counters: time_per_step (CPU seconds per step), steps, impacts, and x_moreau_jean: the
// CPU time of one run over that of moreau_jean::solve on the same case and N, measured
// right after the timed loop so that both see the same machine load (the library prints
// it with an "s" because it is an inverted rate; read it as a plain ratio).
// BM_OdeBaselineMoreauJean times the baseline on its own as well.
//
// BM_OdeChain/bodies:<n>: the default variant on a chain of n = 2 .. 100 bodies,
// alternating (odd bodies Pi5 = 0.5, Pi6 = 1) with a gap (Pi3 = 0.5) under the cosine
// pulse (Pi2 = 1, eps = 0.5), N = 64: the cost per step against n (counters
// time_per_step, time_per_body_step, steps, impacts).
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#include <benchmark/benchmark.h>

#include "kit/benchmarking.hpp"
#include "solvers/moreau_jean/versus.hpp"
#include "solvers/ode/ode_solver.hpp"

namespace {

const bool ode_registered = pb::bench::register_vs_moreau_jean(
    "BM_Ode", &pb::ode::solve,
    {{"dantzig_faithful", "dantzig-faithful"}, {"dantzig_default", "dantzig-default"},
     {"quickstep_faithful", "quickstep-faithful"}, {"quickstep_default", "quickstep-default"}});

void BM_OdeChain(benchmark::State& state) { pb::bench::time_chain(state, &pb::ode::solve); }

BENCHMARK(BM_OdeChain)->ArgName("bodies")->ArgsProduct({{2, 5, 10, 20, 50, 100}})->Unit(benchmark::kMillisecond);

}  // namespace
