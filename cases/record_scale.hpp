#pragma once
// Scaling a record as engineers scale one (cases/README.md, "Scaled records"): by a factor on
// its accelerations (record_scale), to a peak ground acceleration (pga, m/s^2), or to a
// pseudo-spectral acceleration sa = w^2 max|u| of a linear oscillator of period sa_period
// and the case's damping ratio xi (m/s^2). The case's samples become the scaled ones, and
// record_scale the factor, so rows keep it; a record's a_p, when not given, is then the
// scaled peak.

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "cases/case.hpp"
#include "cases/record.hpp"

namespace pb {

// The record's accelerations times factor (shared: a scaled copy is made once per record and
// factor, and kept for the life of the process).
std::shared_ptr<const Record> scaled_record(const std::shared_ptr<const Record>& record, double factor);

// Why a_p is refused beside a record in physical units, where it would be only the Pi terms'
// unit and scale nothing; `flags`: naming the command line's flags rather than the keys.
std::string record_a_p_reason(bool flags);

// Sets c.record_scale from its target (pga, or sa at sa_period) and c.samples to the record
// scaled by it. c.samples must be the record as read (Record::scale 1) or scaled by
// c.record_scale already (then nothing changes). Returns "field: reason" where the scaling
// cannot be made (a target beside a factor, a record whose response is zero).
std::optional<std::string> scale_record(Case& c);

// The pseudo-spectral acceleration w^2 max|u| (m/s^2, the record's units) of a linear
// oscillator of period `period` (s) and damping ratio xi under the record, from rest, over
// the record's length and three periods after it: exact, by the event-driven reference. The
// reference lives above cases/ (solvers/), which defines this function (solvers/registry.cpp).
double pseudo_acceleration(const Record& record, double period, double xi);

}  // namespace pb
