#pragma once

#include <functional>
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
// A QuietScope may carry a watch: a function called at every write the scope drops, before it
// is dropped. Simbody's impulse solvers write their trace at every iteration (Debian's build),
// and no other code of this project runs inside them: model.cpp's time limit watches there.
//
// One difference remains: fflush(stdout) empties the filter, not the original FILE behind
// it, so a program that must deliver its output before _exit (a forked child) calls
// fflush(nullptr), which empties every stream; exit() and a terminal's line buffering
// deliver as before.

namespace pb::simbody {

class QuietScope {
 public:
  // watch: called at each write dropped while this scope is open (null: none, or the watch of
  // the scope it is inside); it must not throw (glibc's printf holds its stream's lock around the write:
  // unwinding through it left the lock taken, measured).
  explicit QuietScope(const std::function<void()>* watch = nullptr);
  ~QuietScope();
  QuietScope(const QuietScope&) = delete;
  QuietScope& operator=(const QuietScope&) = delete;

 private:
  const std::function<void()>* outer_;  // the watch of the scope this one is inside
};

// Whether the filters are in place (false only if fopencookie failed).
bool stdout_filtered();

}  // namespace pb::simbody
