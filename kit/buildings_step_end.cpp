#include "kit/buildings_step_end.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cases/text.hpp"

namespace pb::buildings {

bool end_step(const BuildingModel& model, long k, long n, double h, const double* u, const double* v,
              FloorPeaks& peaks, Deadline* deadline, BuildingsResult& r) {
  const double t = static_cast<double>(k + 1) * h;
  bool finite = true;
  double largest = 0.0;
  for (int i = 0; i < model.n_floors; ++i) {
    finite = finite && std::isfinite(u[i]) && std::isfinite(v[i]);
    largest = std::max(largest, std::abs(u[i]));
  }
  const auto stop = [&](Status status, const std::string& why) {
    r.status = status;
    r.message = why + " at step " + std::to_string(k + 1) + " (t = " + format_number(t) + ")";
    return false;
  };
  if (!finite) return stop(Status::nan, "non-finite state");
  if (!(largest <= 1e6 * model.length_scale())) return stop(Status::diverged, "|u| above 1e6 a_p/w_p^2");
  peaks.sample(t, u);
  if (deadline && k + 1 < n && deadline->passed(k + 1)) {
    r.status = Status::time_limit;
    r.message = deadline->reason() + " at t = " + format_number(t);
    return false;
  }
  return true;
}

}  // namespace pb::buildings
