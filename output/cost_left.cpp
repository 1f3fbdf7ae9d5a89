#include "output/cost_left.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pb::app {

namespace {

double steps_per_period(const Settings& s) {
  if (s.wh > 0.0) return 2.0 * std::numbers::pi / s.wh;
  return s.steps > 0 ? static_cast<double>(s.steps) : 0.0;
}

double row_cost(const Row& row) {
  const double cpu = row.cpu_seconds * std::max(row.repetitions, 1);
  return cpu > 0.0 ? cpu : 0.0;  // NaN (a failed row) counts as nothing
}

}  // namespace

CostLeft::CostLeft(std::span<const SweepRun> runs, std::size_t cases, std::span<const std::size_t> todo)
    : cases_(cases) {
  for (const SweepRun& r : runs) runs_.push_back({r.solver, steps_per_period(r.settings)});
  for (std::size_t task : todo)
    if (cases_ && task / cases_ < runs_.size()) ++runs_[task / cases_].left;
}

void CostLeft::add(const Row& row) {
  const std::lock_guard lock(mutex_);
  if (row.run >= runs_.size()) return;
  Run& r = runs_[row.run];
  if (r.left) --r.left;
  ++r.done;
  r.cost += row_cost(row);
  cost_ += row_cost(row);
  ++done_;
}

std::optional<double> CostLeft::seconds_left(double elapsed) const {
  const std::lock_guard lock(mutex_);
  if (done_ == 0 || !(cost_ > 0.0)) return std::nullopt;
  const double overall = cost_ / static_cast<double>(done_);
  double left = 0.0;
  for (const Run& r : runs_) {
    if (!r.left) continue;
    double per_point = overall;
    if (r.done) {
      per_point = r.cost / static_cast<double>(r.done);
    } else {
      // The finished run of the same solver nearest in steps, scaled by the steps.
      const Run* like = nullptr;
      for (const Run& o : runs_)
        if (o.done && o.solver == r.solver && (!like || (o.steps > 0.0 && r.steps > 0.0 &&
                                                         std::abs(o.steps - r.steps) < std::abs(like->steps - r.steps))))
          like = &o;
      if (like) {
        per_point = like->cost / static_cast<double>(like->done);
        if (like->steps > 0.0 && r.steps > 0.0) per_point *= r.steps / like->steps;
      }
    }
    left += per_point * static_cast<double>(r.left);
  }
  return left * elapsed / cost_;
}

}  // namespace pb::app
