#pragma once
// The fuzz target issue 46 asked for: Python callables as the solver (poundbench.spectrum(set,
// solver=f), and a study's solvers={...}), misbehaving. An input is the Python source of a
// function f(case) that does something per call (sleeps or loops past the time limit, swallows
// the interruption, calls poundbench itself, raises any exception, KeyboardInterrupt
// included) and returns anything (a dict, a bad dict, no dict, huge documents, the case
// itself). A sweep of three points runs it at time_limit = 0.3 s in a child Python process,
// which checks:
//
//   * a row per point, each message one line;
//   * the limit honoured: no call timed past the limit is any row but time-limit, and no call
//     outlives 2.5 s (the longest a call sleeps in C is 0.9 s; loops of 3 s in Python must be
//     interrupted);
//   * KeyboardInterrupt out of the sweep exactly when f raised one (it stops the sweep);
//   * a study over f counts every point; no crash, no other exception out of poundbench.
//
// The sleeps bound what one input costs: about 3 s at most, plus the interpreter's start. A
// poundbench call that f makes runs to its own limit (the interruption reaches f when it
// returns): the ones here take a fraction of a second.

#include <optional>
#include <string>
#include <vector>

#include "tests/fuzz/child.hpp"
#include "tests/fuzz/mutator.hpp"

namespace pb::fuzz {

// The property the callable `program` (Python source defining f) violates, or nothing.
// Nothing either where the Python module is not built (python_available()).
std::optional<std::string> check_callable(const std::string& program, const ChildLimits& limits);
// A callable of three calls, each an action and a return drawn from the pools in callables.cpp.
std::string make_callable(Rng& rng);

}  // namespace pb::fuzz
