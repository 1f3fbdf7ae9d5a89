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
  p.no_contact = reference_solver().solve_buildings(assemble(apart), limits);
  return p;
}

std::optional<std::vector<BuildingsPoint>> sweep_buildings(std::span<const BuildingCase> points,
                                                           const SolverInfo& solver, const Settings& settings,
                                                           int threads, const std::atomic<bool>& cancel,
                                                           const std::function<void(std::size_t done)>& done) {
  std::vector<BuildingsPoint> out(points.size());
  Settings run = settings;
  run.stop = &cancel;
  std::atomic<std::size_t> next{0};
  std::mutex report;
  std::size_t finished = 0;
  const auto work = [&] {
    for (std::size_t i; !cancel && (i = next++) < points.size();) {
      out[i] = solve_buildings_point(points[i].scene, solver, run);
      const std::lock_guard lock(report);
      if (done) done(++finished);
    }
  };
  const auto n = static_cast<std::size_t>(std::max(1, threads));
  std::vector<std::jthread> workers;
  for (std::size_t t = 1; t < std::min(n, points.size()); ++t) workers.emplace_back(work);
  work();
  workers.clear();  // joins
  if (cancel) return std::nullopt;
  return out;
}

}  // namespace pb
