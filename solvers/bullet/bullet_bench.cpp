// Cost of the Bullet solver per run and per step, for every variant, on the three scenes
// at one Fig. 4 point (Pi2 = 1, Pi3 = 0.5, Pi5 = 0.5, Pi6 = 1, eps = 0.5, cosine, normal;
// row3 symmetric), N = 64 and 256; and of moreau-jean on the same runs, for the ratio.
//
//   BM_Bullet/<variant>/<scene>/N     one pb::bullet::solve per iteration (world set-up
//                                     included: it is part of every run)
//   BM_BulletMoreauJean/<scene>/N     one pb::moreau_jean::solve per iteration
//
// Counters: time_per_step (CPU seconds per step), steps, impacts, and on BM_Bullet
// vs_moreau_jean: the CPU time of a Bullet run over that of a moreau-jean run of the same
// case, timed right after it in the same process (so the ratio is read from one run even on
// a loaded machine; kit/benchmarking.hpp).
//
//   BM_BulletChain/bodies:<n>         the default variant on a chain of n = 2 .. 100
//                                     bodies, alternating (odd bodies Pi5 = 0.5, Pi6 = 1)
//                                     with a gap (Pi3 = 0.5) under the cosine pulse
//                                     (Pi2 = 1, eps = 0.5), N = 64: cost per step against n
//                                     (counters time_per_step, time_per_body_step, steps,
//                                     impacts)
//
// Use --benchmark_repetitions=9 and read the medians.

#ifdef POUNDBENCH_HAVE_BULLET

#include <benchmark/benchmark.h>

#include <string>

#include "kit/benchmarking.hpp"
#include "cases/system.hpp"
#include "solvers/bullet/bullet_solver.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"

namespace {

void bullet_solve(benchmark::State& state, const pb::bullet::Config& config, pb::Scene scene) {
  const int n = static_cast<int>(state.range(0));
  const double started = pb::bench::thread_seconds();
  pb::bench::time_variant(state, &pb::bullet::solve, std::string(config.name).c_str(), scene, n);
  const double own = pb::bench::thread_seconds() - started;
  const double bullet_seconds = own / static_cast<double>(state.iterations());
  pb::Settings mj;
  mj.steps = n;
  const double mj_seconds = pb::bench::seconds_per_run(&pb::moreau_jean::solve, pb::bench::fig4_point(scene), mj, own);
  state.counters["vs_moreau_jean"] = mj_seconds > 0.0 ? bullet_seconds / mj_seconds : 0.0;
}

void BM_BulletChain(benchmark::State& state) { pb::bench::time_chain(state, &pb::bullet::solve); }
BENCHMARK(BM_BulletChain)->ArgName("bodies")->ArgsProduct({{2, 5, 10, 20, 50, 100}})->Unit(benchmark::kMillisecond);

void moreau_jean_solve(benchmark::State& state, pb::Scene scene) {
  pb::bench::time_solve(state, &pb::moreau_jean::solve, scene);
}

const bool bullet_registered = [] {
  for (pb::Scene scene : {pb::Scene::wall, pb::Scene::pair, pb::Scene::row3}) {
    const std::string scene_name(pb::name(scene));
    for (const pb::bullet::Config& config : pb::bullet::kVariants.configs)
      pb::bench::at_each_n(
          benchmark::RegisterBenchmark(("BM_Bullet/" + std::string(config.name) + "/" + scene_name).c_str(),
                                       [config, scene](benchmark::State& st) { bullet_solve(st, config, scene); }));
    pb::bench::at_each_n(benchmark::RegisterBenchmark(("BM_BulletMoreauJean/" + scene_name).c_str(),
                                                      [scene](benchmark::State& st) { moreau_jean_solve(st, scene); }));
  }
  return true;
}();

}  // namespace

#endif  // POUNDBENCH_HAVE_BULLET
