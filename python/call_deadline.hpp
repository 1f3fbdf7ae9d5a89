#pragma once
// The time limit of a Python callable's call (issue 46: a 2 s solve at time_limit=0.5 gave
// every row ok). A watchdog thread raises an exception in the calling thread once the call has
// run to its deadline (PyThreadState_SetAsyncExc): Python delivers it at the thread's next
// bytecode, so a loop in Python stops there, and a call inside C code (time.sleep, a NumPy
// operation) when that returns. The class of that exception is the module's
// TimeLimitExceeded, a BaseException as KeyboardInterrupt is, so that `except Exception` in
// the callable does not take it.
//
// One thread per CallDeadline, started at its first armed call and joined by its destructor;
// a call arms it and disarms it, each with the GIL held. The watchdog takes the GIL to raise
// (the C API asks for it), and raises only if the same call is still armed when it has it:
// since the calling thread holds the GIL from the moment the callable returns until it
// disarms, an exception is never raised after the call it was meant for; one set in the
// call's last instant and not yet delivered is cleared by disarm().
//
// Rejected: a thread started per call (tens of microseconds a call); Py_AddPendingCall, which
// needs no GIL but runs in the main thread only, where a callable run from another thread would
// not be, and sys.settrace, which slows every line of the callable.

#include <pybind11/pybind11.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace pb::python {

class CallDeadline {
 public:
  // exception: the class raised at the deadline (a Python exception type, kept alive by the
  // module).
  explicit CallDeadline(PyObject* exception) : exception_(exception) {}
  ~CallDeadline() {
    {
      const std::lock_guard lock(mutex_);
      quit_ = true;
    }
    wake_.notify_all();
    if (!watchdog_.joinable()) return;
    // The watchdog may be waiting for the GIL (a deadline met just as a call returned).
    if (PyGILState_Check()) {
      pybind11::gil_scoped_release release;
      watchdog_.join();
    } else {
      watchdog_.join();
    }
  }
  CallDeadline(const CallDeadline&) = delete;
  CallDeadline& operator=(const CallDeadline&) = delete;

  // A call of the calling thread starts, to be interrupted after `seconds` (> 0). GIL held.
  void arm(double seconds) {
    const auto due = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
    {
      const std::lock_guard lock(mutex_);
      if (!watchdog_.joinable()) watchdog_ = std::thread([this] { watch(); });
      target_ = PyThread_get_thread_ident();
      due_ = due;
      armed_ = true;
      fired_ = false;
      ++call_;
    }
    wake_.notify_all();
  }

  // The call has ended. GIL held. True if the deadline interrupted it. An exception raised
  // but not yet delivered is withdrawn.
  bool disarm() {
    bool fired = false;
    {
      const std::lock_guard lock(mutex_);
      armed_ = false;
      fired = fired_;
      ++call_;
    }
    if (fired) PyThreadState_SetAsyncExc(target_, nullptr);
    return fired;
  }

 private:
  void watch() {
    std::unique_lock lock(mutex_);
    while (!quit_) {
      if (!armed_) {
        wake_.wait(lock);
        continue;
      }
      if (std::chrono::steady_clock::now() < due_) {
        wake_.wait_until(lock, due_);
        continue;  // looked at again: disarmed, armed anew, or due
      }
      const long call = call_;
      lock.unlock();
      const PyGILState_STATE gil = PyGILState_Ensure();
      lock.lock();
      if (armed_ && call_ == call && !quit_) {
        PyThreadState_SetAsyncExc(target_, exception_);
        fired_ = true;
        armed_ = false;
      }
      lock.unlock();
      PyGILState_Release(gil);
      lock.lock();
    }
  }

  PyObject* exception_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread watchdog_;
  bool quit_ = false, armed_ = false, fired_ = false;
  long call_ = 0;  // counts arms and disarms: the watchdog raises in the call it saw armed
  unsigned long target_ = 0;
  std::chrono::steady_clock::time_point due_;
};

}  // namespace pb::python
