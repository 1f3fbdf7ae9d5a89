#include "sweep/buildings_sweep.hpp"

#include <algorithm>
#include <mutex>
#include <thread>

#include "solvers/registry.hpp"
#include "sweep/stopwatch.hpp"

namespace pb {

BuildingsPoint solve_buildings_point(const BuildingScene& scene, const SolverInfo& solver, const Settings& settings) {
  BuildingsPoint p;
  const BuildingModel model = assemble(scene);
  p.a_p = model.a_p;
  p.w_p = model.w_p;
  const Stopwatch clock;
  p.result = solver.solve_buildings(model, settings);
  const Elapsed spent = clock.elapsed();
  p.seconds = spent.wall;
  p.cpu_seconds = spent.cpu;
  BuildingScene apart = scene;
  apart.no_contact = true;
  Settings limits;
  limits.time_limit = settings.time_limit;
  limits.stop = settings.stop;
  p.no_contact = buildings_free_motion(apart, limits);
  if (p.no_contact.status == Status::ok) p.separation = floor_separations(model, p.no_contact);
  return p;
}

namespace buildings_sweep_detail {

// Runs work(i) for every point i < n on `threads` threads, handing points out one at a time;
// false once `cancel` is set (no point starts after it).
bool each_point(std::size_t n, int threads, const std::atomic<bool>& cancel,
                const std::function<void(std::size_t done)>& done, const std::function<void(std::size_t)>& work) {
  std::atomic<std::size_t> next{0};
  std::mutex report;
  std::size_t finished = 0;
  const auto worker = [&] {
    for (std::size_t i; !cancel && (i = next++) < n;) {
      work(i);
      const std::lock_guard lock(report);
      if (done) done(++finished);
    }
  };
  const auto count = static_cast<std::size_t>(std::max(1, threads));
  std::vector<std::jthread> workers;
  for (std::size_t t = 1; t < std::min(count, n); ++t) workers.emplace_back(worker);
  worker();
  workers.clear();  // joins
  return !cancel;
}

}  // namespace buildings_sweep_detail

std::optional<std::vector<BuildingsPoint>> sweep_buildings(std::span<const BuildingCase> points,
                                                           const SolverInfo& solver, const Settings& settings,
                                                           int threads, const std::atomic<bool>& cancel,
                                                           const std::function<void(std::size_t done)>& done) {
  std::vector<BuildingsPoint> out(points.size());
  Settings run = settings;
  run.stop = &cancel;
  const bool finished = buildings_sweep_detail::each_point(points.size(), threads, cancel, done, [&](std::size_t i) {
    out[i] = solve_buildings_point(points[i].scene, solver, run);
  });
  if (!finished) return std::nullopt;
  return out;
}

std::optional<std::vector<buildings::BuildingsResult>> sweep_reference(std::span<const BuildingCase> points,
                                                                       ReferencePass pass, int threads,
                                                                       const std::atomic<bool>& cancel,
                                                                       const std::function<void(std::size_t done)>& done) {
  std::vector<buildings::BuildingsResult> out(points.size());
  Settings limits;
  limits.stop = &cancel;
  const bool finished = buildings_sweep_detail::each_point(points.size(), threads, cancel, done, [&](std::size_t i) {
    out[i] = pass == ReferencePass::free_motion ? buildings_free_motion(points[i].scene, limits)
                                                : reference_solver().solve_buildings(assemble(points[i].scene), limits);
  });
  if (!finished) return std::nullopt;
  return out;
}

}  // namespace pb
