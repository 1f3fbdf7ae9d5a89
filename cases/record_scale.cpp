#include "cases/record_scale.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <tuple>
#include <utility>

#include "cases/text.hpp"

namespace pb {

namespace {

// A sweep builds its cases on several threads (cases/case_list.hpp), each case of a scaled
// record asking for the same copy and the same spectral value: both are kept, by the record
// as read and the numbers that make them.
struct Kept {
  std::mutex lock;
  std::map<std::pair<const Record*, double>, std::shared_ptr<const Record>> scaled;
  std::map<std::tuple<const Record*, double, double>, double> psa;
  // The records as read that the keys point to, kept alive so that no address is reused.
  std::map<const Record*, std::shared_ptr<const Record>> originals;
};

Kept& kept() {
  static Kept k;
  return k;
}

}  // namespace

std::string record_a_p_reason(bool flags) {
  return flags ? "with a record in physical units a_p is only the unit of the Pi terms and scales nothing: scale the "
                 "record with --pga (or --pga-g, or --sa with --sa-period) or --record-scale"
               : "with a record in physical units a_p is only the unit of the Pi terms and scales nothing: scale the "
                 "record with pga (or pga_g, or sa with sa_period) or record_scale";
}

std::shared_ptr<const Record> scaled_record(const std::shared_ptr<const Record>& record, double factor) {
  if (factor == 1.0) return record;
  Kept& k = kept();
  const std::lock_guard<std::mutex> hold(k.lock);
  auto& out = k.scaled[{record.get(), factor}];
  if (!out) {
    k.originals.emplace(record.get(), record);
    auto copy = std::make_shared<Record>(*record);
    for (double& a : copy->a) a *= factor;
    copy->peak *= factor;
    copy->scale *= factor;
    out = std::move(copy);
  }
  return out;
}

// Named, not anonymous: a unity build puts this file beside others with helpers of that name.
namespace scaling {

// The targets as given, before anything is computed from them: each finite and > 0, and a
// period whose oscillator the reference can solve (w = 2 pi / T within [kMinWp, kMaxWp]).
std::optional<std::string> check_targets(const Case& c) {
  if (!std::isnan(c.pga) && !(std::isfinite(c.pga) && c.pga > 0.0)) return "pga: must be finite and > 0 (m/s^2)";
  if (!std::isnan(c.sa) && !(std::isfinite(c.sa) && c.sa > 0.0)) return "sa: must be finite and > 0 (m/s^2)";
  if (!std::isnan(c.sa_period)) {
    const double w = 2.0 * std::numbers::pi / c.sa_period;
    if (!(std::isfinite(c.sa_period) && c.sa_period > 0.0 && w >= kMinWp && w <= kMaxWp))
      return "sa_period: must be finite and in [" + format_number(2.0 * std::numbers::pi / kMaxWp) + ", " +
             format_number(2.0 * std::numbers::pi / kMinWp) + "] s";
  }
  if (std::isnan(c.sa) != std::isnan(c.sa_period))
    return std::isnan(c.sa) ? "sa: sa_period is its period; give sa too" : "sa_period: required by sa";
  return std::nullopt;
}

}  // namespace scaling

std::optional<std::string> scale_record(Case& c) {
  if (c.pulse != PulseShape::record || !c.samples) return std::nullopt;
  if (auto bad = scaling::check_targets(c)) return bad;
  const bool pga = !std::isnan(c.pga), sa = !std::isnan(c.sa) && !std::isnan(c.sa_period);
  if ((pga || sa) && c.record_scale != 1.0 && c.samples->scale != c.record_scale)
    return std::string("record_scale: not with ") + (pga ? "pga" : "sa") + " (scale the record one way)";
  if (c.samples->scale == c.record_scale && !pga && !sa) return std::nullopt;
  if (c.samples->scale != 1.0) {
    if (c.samples->scale == c.record_scale) return std::nullopt;  // scaled already
    return "record_scale: the record was scaled by " + format_number(c.samples->scale) + " already";
  }
  double factor = c.record_scale;
  if (pga) factor = c.pga / c.samples->peak;
  if (sa) {
    double value = 0.0;
    {
      Kept& k = kept();
      const std::lock_guard<std::mutex> hold(k.lock);
      const auto key = std::make_tuple(c.samples.get(), c.sa_period, c.xi);
      if (const auto it = k.psa.find(key); it != k.psa.end()) value = it->second;
    }
    if (value == 0.0) {
      value = pseudo_acceleration(*c.samples, c.sa_period, c.xi);  // outside the lock: a solve
      Kept& k = kept();
      const std::lock_guard<std::mutex> hold(k.lock);
      k.originals.emplace(c.samples.get(), c.samples);
      k.psa[std::make_tuple(c.samples.get(), c.sa_period, c.xi)] = value;
    }
    if (!(value > 0.0) || !std::isfinite(value))
      return "sa: the record's pseudo-spectral acceleration at " + format_number(c.sa_period) + " s is " + format_number(value) +
             ": it cannot be scaled to one";
    factor = c.sa / value;
  }
  if (!(factor >= 1e-6 && factor <= 1e6))
    return std::string(pga ? "pga" : sa ? "sa" : "record_scale") + ": scales the record by " + format_number(factor) +
           ", outside [1e-6, 1e6]";
  c.record_scale = factor;
  c.samples = scaled_record(c.samples, factor);
  return std::nullopt;
}

}  // namespace pb
