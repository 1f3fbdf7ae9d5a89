#pragma once
// What ends a run before t_end, for every solver's loop (the reference's searches, CVODE's
// steps, the time-steppers'): divergence, judged on the energy, and the time limit.

#include <atomic>
#include <chrono>
#include <string>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb {

// A time-stepper's run has diverged once its mechanical energy passes this many times
// System::energy_scale(). Exact dynamics stay within a few tens of it (the pulse's work,
// and resonance, on top of the start), so nothing short of a runaway gets there, while a
// displacement bound alone lets a stiff body's energy grow by ten or more orders of
// magnitude before it trips (a body 100 times stiffer moves 1e4 times less).
inline constexpr double kDivergedEnergy = 1e6;

// Why a finite state counts as diverged (|u| beyond 1e6 a_p / w_p^2, or the mechanical
// energy beyond kDivergedEnergy times its scale), or nullptr.
const char* runaway(const System& sys, const double* u, const double* v);

// How an event loop's run ends on its state (u, v) at time t: nan where the state is not
// finite, diverged where it ran away (with runaway's reason), each with its message "... at
// t = T"; ok (message untouched) otherwise.
Status state_end(const System& sys, bool finite, const double* u, const double* v, double t, std::string& message);

// Settings::time_limit (and Settings::stop) in a step loop. The clock is read about once
// per millisecond of steps, whatever a step costs: a fixed stride would overshoot by
// seconds where a step takes tens of milliseconds (a 100-body chain through an MLCP), or
// read the clock more often than it steps where a step takes 100 ns.
class Deadline {
 public:
  explicit Deadline(const Settings& settings);  // time_limit 0 and no stop flag: never passes

  // After step k (k >= 1): true once the limit has passed or the stop flag is set.
  // Inline up to the next look: the reference's searches call tick() a few times per
  // evaluation, and the call itself was 1 % of their time.
  bool passed(long k) { return k >= next_ && look(k); }
  // The same for a loop that counts nothing itself (the reference's searches): one call
  // per unit of work.
  bool tick() { return passed(++ticks_); }
  // The units of work tick() has counted: a search's windows, which tests hold to a budget.
  long ticks() const { return ticks_; }
  // Why it passed, for Result::message.
  std::string reason() const;

 private:
  double limit_;
  double shown_;  // the limit as given, for reason(): the point's, not what was left of it
  const std::atomic<bool>* stop_;
  std::chrono::steady_clock::time_point start_;
  bool look(long k);
  long next_ = 1;  // the step after which the clock is read next (never without a limit or a stop flag)
  long ticks_ = 0;
};

}  // namespace pb
