#pragma once
// The restitution of a run's isolated impacts, -g'(after) / g'(before) of each impact that no
// other contact shared: how many there were and their range (Result::isolated_impacts,
// restitution_low, restitution_high), for the solvers that measure it themselves.

#include <algorithm>
#include <limits>

#include "kit/solver.hpp"

namespace pb {

struct IsolatedRestitution {
  long count = 0;
  double low = std::numeric_limits<double>::infinity(), high = -std::numeric_limits<double>::infinity();

  void add(double e) {
    low = std::min(low, e);
    high = std::max(high, e);
    ++count;
  }
  // The count, and the range (NaN where no impact was isolated).
  void write(Result& r) const {
    r.isolated_impacts = count;
    r.restitution_low = count > 0 ? low : std::numeric_limits<double>::quiet_NaN();
    r.restitution_high = count > 0 ? high : std::numeric_limits<double>::quiet_NaN();
  }
};

}  // namespace pb
