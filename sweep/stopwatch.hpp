#pragma once
// The clocks a solve is timed on (sweep/sweep.hpp), with their own cost taken off.
//
// A solve's CPU time comes from the thread's CPU clock (CLOCK_THREAD_CPUTIME_ID). Reading it
// is a system call, not a vDSO read: about 0.37 us on the machine of the stored results, part
// of it before the clock is read and part after. So an interval between two readings holds
// one whole call on top of what it times. That was 40 % of Moreau-Jean's cheapest runs (0.9 us
// at N = 8 on wall) and 7 % of the reference's. A Stopwatch takes off the clocks' own cost:
// the least of kCalibrations intervals measured around nothing, once per process. What is
// left is that cost's spread (about 10 ns), and an interval is never less than zero.
//
// The wall clock is read inside the CPU clock's readings (CPU, wall ... wall, CPU), so that
// the wall interval holds none of the CPU clock's system calls.

namespace pb {

struct Elapsed {
  double wall = 0.0;  // seconds
  double cpu = 0.0;   // seconds of the calling thread's CPU
};

class Stopwatch {
 public:
  static constexpr int kCalibrations = 200;

  Stopwatch();  // starts, on the calling thread
  // Since the start, the clocks' own cost taken off (the same thread).
  Elapsed elapsed() const;
  // The clocks' own cost: what an interval around nothing measures, at least.
  static const Elapsed& clock_cost();

 private:
  Elapsed raw() const;

  double cpu0_ = 0.0, wall0_ = 0.0;
};

}  // namespace pb
