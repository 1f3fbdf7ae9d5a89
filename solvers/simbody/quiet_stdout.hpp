#pragma once
// Keeps Debian's Simbody from writing on stdout.
//
// Debian builds Simbody 3.7 without NDEBUG, and then its SemiExplicitEulerTimeStepper and
// impulse solvers print a trace of every step (printf and std::cout: "DYNAMICS PHASE",
// the constraint errors, the impulses, ...): kilobytes a step, into the stdout that carries
// poundbench's own output. Redirecting file descriptor 1 would take poundbench's output with
// it, and from every thread of a sweep at once. Instead the two ways Simbody writes are
// filtered per thread:
//
//  - C's `stdout` FILE is replaced by an unbuffered one (fopencookie) that passes what it
//    is given on to the original FILE, whose buffer and buffering mode stay as they were,
//    except on a thread inside a QuietScope;
//  - std::cout's buffer is replaced by one that passes everything to the original buffer,
//    except on a thread inside a QuietScope.
//
// Both are installed once, before main (a static object in quiet_stdout.cpp, which every
// program that links this solver runs): no other thread exists then, so nothing races with
// the swap. Outside a QuietScope, output is unchanged and in order (std::cout keeps its
// buffer, C's stdout its original FILE's). Inside
// one, what the thread writes to stdout is dropped; other threads write as before.
//
// One difference remains: fflush(stdout) empties the filter, not the original FILE behind
// it, so a program that must deliver its output before _exit (a forked child) calls
// fflush(nullptr), which empties every stream; exit() and a terminal's line buffering
// deliver as before.

namespace pb::simbody {

class QuietScope {
 public:
  QuietScope();
  ~QuietScope();
  QuietScope(const QuietScope&) = delete;
  QuietScope& operator=(const QuietScope&) = delete;
};

// Whether the filters are in place (false only if fopencookie failed).
bool stdout_filtered();

}  // namespace pb::simbody
