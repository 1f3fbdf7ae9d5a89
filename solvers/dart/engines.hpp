#pragma once
// The two DART models behind the shared step loop (solvers/fixed_step.hpp), one per kind of
// variant: faithful.cpp (one skeleton, a GapConstraint per contact) and default_model.cpp
// (a box per building, FCL's contacts). Each builds its world in its constructor and throws
// std::runtime_error if DART refuses it.

#include <memory>

#include "solvers/dart/variants.hpp"
#include "solvers/fixed_step.hpp"

namespace pb::dart {

std::unique_ptr<StepEngine> make_faithful(const System& sys, const Config& config, const Settings& set, double h);
std::unique_ptr<StepEngine> make_default(const System& sys, const Config& config, double h);

}  // namespace pb::dart
