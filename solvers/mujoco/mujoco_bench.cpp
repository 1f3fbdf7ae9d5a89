// Cost of the MuJoCo solver per run and per step, for each variant on wall, pair and row3
// (the ODE benchmark's cases: Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1, eps = 0.5,
// cosine, normal) at N = 64 and 256, against moreau_jean::solve on the same cases.
//
// Counters as in ode_bench.cpp: time_per_step (CPU seconds of a run over its steps, the
// model's compilation included), steps, impacts, and x_moreau_jean, the run's CPU time over
// moreau_jean::solve's on the same case and N, measured right after the timed loop.
// BM_MujocoCompile/<scene> times what every run pays once before its first step (the MJCF
// text, mj_loadXML from memory, mj_makeData), so that a step's own cost is
// (run - compile) / steps. BM_MujocoChain/bodies:<n>: euler-faithful on the alternating
// chain of ode_bench.cpp, N = 64.
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#ifdef POUNDBENCH_HAVE_MUJOCO

#include <benchmark/benchmark.h>

#include <string>

#include "kit/benchmarking.hpp"
#include "solvers/moreau_jean/versus.hpp"
#include "solvers/mujoco/model.hpp"
#include "solvers/mujoco/mujoco_solver.hpp"

namespace {

const bool mujoco_registered = pb::bench::register_vs_moreau_jean(
    "BM_Mujoco", &pb::mujoco::solve,
    {{"euler_faithful", "euler-faithful"}, {"implicit_faithful", "implicit-faithful"},
     {"rk4_faithful", "rk4-faithful"}, {"default", "default"}});

void BM_MujocoCompile(benchmark::State& state, pb::Scene scene) {
  const pb::System s = pb::bench::fig4_point(scene);
  const pb::mujoco::Config config = *pb::mujoco::kVariants.find("euler-faithful");
  const pb::mujoco::Units units = pb::mujoco::units_of(s, config);
  const double h = s.step(64) / units.time;
  pb::mujoco::prepare_process();
  for (auto _ : state) {
    const pb::mujoco::ContactParameters contact = pb::mujoco::calibrated_contact(s.eps, 2.0, h);
    std::string error;
    pb::mujoco::ModelPtr m = pb::mujoco::compile(pb::mujoco::scene_xml(s, config, units, h, &contact), error);
    pb::mujoco::DataPtr d(mj_makeData(m.get()));
    benchmark::DoNotOptimize(d.get());
  }
}
BENCHMARK_CAPTURE(BM_MujocoCompile, wall, pb::Scene::wall)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MujocoCompile, pair, pb::Scene::pair)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MujocoCompile, row3, pb::Scene::row3)->Unit(benchmark::kMicrosecond);

void BM_MujocoChain(benchmark::State& state) { pb::bench::time_chain(state, &pb::mujoco::solve); }

BENCHMARK(BM_MujocoChain)->ArgName("bodies")->ArgsProduct({{2, 5, 10, 20, 50, 100}})->Unit(benchmark::kMillisecond);

}  // namespace

#endif  // POUNDBENCH_HAVE_MUJOCO
