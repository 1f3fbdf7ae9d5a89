// Cost of the Bullet solver per run and per step, for every variant, on the three scenes
// at one Fig. 4 point (Pi2 = 1, Pi3 = 0.5, Pi5 = 0.5, Pi6 = 1, eps = 0.5, cosine, normal;
// row3 symmetric), N = 64 and 256; and of moreau-jean on the same runs, for the ratio.
//
//   BM_Bullet/<variant>/<scene>/N     one pb::bullet::solve per iteration (world set-up
//                                     included: it is part of every run)
//   BM_BulletMoreauJean/<scene>/N     one pb::moreau_jean::solve per iteration
//
// Counters: time_per_step (CPU seconds per step), steps, impacts, and on BM_Bullet
// vs_moreau_jean: the CPU time of these Bullet runs over the CPU time of as many
// moreau-jean runs of the same case, timed right after them in the same process (so the
// ratio is read from one run even on a loaded machine).
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

#include <time.h>

#include <string>

#include "bench/support.hpp"
#include "cases/system.hpp"
#include "solvers/bullet/bullet_solver.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"

namespace {

// CPU seconds of this thread: the ratio below compares two CPU times, which a loaded
// machine disturbs less than wall times.
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void bullet_solve(benchmark::State& state, const pb::bullet::Config& config, pb::Scene scene) {
  const pb::System s = pb::bench::fig4_point(scene);
  pb::Settings settings;
  settings.variant = std::string(config.name);
  settings.steps = static_cast<int>(state.range(0));
  long steps = 0, impacts = 0;
  const double started = thread_seconds();
  for (auto _ : state) {
    const pb::Result r = pb::bullet::solve(s, settings);
    steps = r.steps;
    impacts = r.impacts;
    benchmark::DoNotOptimize(r.pi1);
  }
  const double bullet_seconds = thread_seconds() - started;

  pb::Settings mj;
  mj.steps = settings.steps;
  const double mj_started = thread_seconds();
  for (benchmark::IterationCount i = 0; i < state.iterations(); ++i) benchmark::DoNotOptimize(pb::moreau_jean::solve(s, mj).pi1);
  const double mj_seconds = thread_seconds() - mj_started;

  state.counters["time_per_step"] = pb::bench::per_step(steps);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["vs_moreau_jean"] = mj_seconds > 0.0 ? bullet_seconds / mj_seconds : 0.0;
}

pb::System chain_point(int bodies) {
  pb::Case c;
  c.scene = pb::Scene::chain;
  c.bodies = bodies;
  c.pulse = pb::PulseShape::cosine;
  c.pi2 = 1.0;
  c.pi3 = 0.5;
  c.pi5 = 0.5;
  c.pi6 = 1.0;
  c.eps = 0.5;
  return pb::make_system(c);
}

void BM_BulletChain(benchmark::State& state) {
  const int bodies = static_cast<int>(state.range(0));
  const pb::System s = chain_point(bodies);
  pb::Result r;
  for (auto _ : state) {
    r = pb::bullet::solve(s, pb::Settings{});
    benchmark::DoNotOptimize(r.pi1);
  }
  if (r.status != pb::Status::ok) state.SkipWithError(r.message.c_str());
  state.counters["time_per_step"] = pb::bench::per_step(r.steps);
  state.counters["time_per_body_step"] = pb::bench::per_step(r.steps * bodies);
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["impacts"] = static_cast<double>(r.impacts);
}
BENCHMARK(BM_BulletChain)->ArgName("bodies")->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Arg(100)->Unit(benchmark::kMillisecond);

void moreau_jean_solve(benchmark::State& state, pb::Scene scene) {
  pb::bench::time_solve(state, &pb::moreau_jean::solve, scene);
}

const bool registered = [] {
  for (pb::Scene scene : {pb::Scene::wall, pb::Scene::pair, pb::Scene::row3}) {
    const std::string scene_name(pb::name(scene));
    for (const pb::bullet::Config& config : pb::bullet::variants())
      benchmark::RegisterBenchmark(("BM_Bullet/" + std::string(config.name) + "/" + scene_name).c_str(),
                                   [config, scene](benchmark::State& st) { bullet_solve(st, config, scene); })
          ->ArgName("N")
          ->Arg(64)
          ->Arg(256)
          ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("BM_BulletMoreauJean/" + scene_name).c_str(),
                                 [scene](benchmark::State& st) { moreau_jean_solve(st, scene); })
        ->ArgName("N")
        ->Arg(64)
        ->Arg(256)
        ->Unit(benchmark::kMicrosecond);
  }
  return true;
}();

}  // namespace

#endif  // POUNDBENCH_HAVE_BULLET
