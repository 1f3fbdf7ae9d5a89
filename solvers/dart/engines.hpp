#pragma once
// The two DART models behind the shared step loop (kit/fixed_step.hpp), one per kind of
// variant: faithful.cpp (a skeleton per building, a GapConstraint per contact) and default_model.cpp
// (a box per building, FCL's contacts). Each builds its world in its constructor and throws
// std::runtime_error if DART refuses it, OutOfTime if the run's limit passes meanwhile; each
// step stops at the limit inside DART's step too (run_limit.hpp).

#include <memory>

#include "solvers/dart/run_limit.hpp"
#include "solvers/dart/variants.hpp"
#include "kit/fixed_step.hpp"

namespace pb::dart {

std::unique_ptr<StepEngine> make_faithful(const System& sys, const Config& config, const Settings& set, double h,
                                          RunLimit& limit);
std::unique_ptr<StepEngine> make_default(const System& sys, const Config& config, double h, RunLimit& limit);

}  // namespace pb::dart
