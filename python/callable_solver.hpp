#pragma once
// A Python callable as the external solver, in process (issue 37): `poundbench.spectrum(set,
// solver=f)`. f gets the case as a dict (the external protocol's case document,
// docs/external.md) and returns the answer as a dict ("version" may be left out); the
// external solver hands it the document through Settings::in_process, so the row is made by
// the same code as a program's, answer checks included. Its row's solve_seconds is the call's
// CPU time on its thread (the sweep's clock: issue 48), the dict's conversions outside; its
// time limit is wall time, as every solver's. What f raises is that point's failed row,
// with the exception's type and message. A sweep with a callable runs on one thread: the GIL
// lets one call run at a time, and a second thread's wait for it would be timed as its cost.
//
// Its time limit is the case document's time_limit (the point's, what is left of it): a call
// still running then is interrupted (call_deadline.hpp), and a call that took longer, whether
// interrupted or not (a call inside C code sees the interruption only when that returns; a
// callable may catch it), is the point's time-limit row, which says how long it ran. A
// KeyboardInterrupt out of f (Ctrl-C inside a poundbench call that f made, which stops that
// call) stops the sweep (`interrupt`): the point is a stopped row, not f's failure.

#include <pybind11/pybind11.h>

#include <chrono>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cases/text.hpp"
#include "python/call_deadline.hpp"
#include "sweep/stopwatch.hpp"

namespace pb::python {

class CallableSolver {
 public:
  // timeout: the exception class a call is interrupted with; interrupt: stops the sweep.
  CallableSolver(pybind11::object f, PyObject* timeout, void (*interrupt)())
      : f_(std::move(f)), json_(pybind11::module_::import("json")),
        deadline_(std::make_shared<CallDeadline>(timeout)), interrupt_(interrupt) {}

  // Settings::in_process: called on a sweep's thread, without the GIL.
  std::string operator()(const std::string& case_document, double& call_seconds) const {
    namespace py = pybind11;
    py::gil_scoped_acquire gil;
    try {
      const py::object case_dict = json_.attr("loads")(case_document);
      const double limit = time_limit(case_dict);
      py::object answer;
      std::string ended;  // why the call is a time-limit row; "" when it is not
      const Stopwatch cpu;  // the sweep's clock, its own cost taken off
      {
        Call call(*deadline_, limit);
        try {
          answer = f_(case_dict);
        } catch (py::error_already_set& e) {
          call_seconds = cpu.elapsed().cpu;
          ended = call.end();
          if (!ended.empty()) return time_limit_answer(ended);
          if (e.matches(PyExc_KeyboardInterrupt)) {
            interrupt_();
            return time_limit_answer("stopped (the sweep was interrupted): KeyboardInterrupt in the function");
          }
          throw;
        }
        ended = call.end();
      }
      call_seconds = cpu.elapsed().cpu;
      if (!ended.empty()) return time_limit_answer(ended);
      if (!py::isinstance<py::dict>(answer))
        throw std::runtime_error("the solver returned " + std::string(py::str(py::type::of(answer).attr("__name__"))) +
                                 ", not a dict (the answer, docs/external.md)");
      py::dict out(answer.attr("copy")());
      if (!out.contains("version")) out["version"] = 1;
      return py::str(json_.attr("dumps")(out, py::arg("allow_nan") = false));
    } catch (py::error_already_set& e) {
      // The point's failed row says what f raised: "ZeroDivisionError: division by zero".
      throw std::runtime_error(describe(e));
    }
  }

 private:
  // One call of f under its limit (0: none), on the wall clock: end() says whether it was a
  // time-limit row, and the destructor disarms whatever end() was not reached for.
  class Call {
   public:
    Call(CallDeadline& deadline, double limit)
        : deadline_(deadline), limit_(limit), start_(std::chrono::steady_clock::now()) {
      if (limit_ > 0.0) deadline_.arm(limit_);
    }
    ~Call() {
      if (!ended_) end();
    }
    Call(const Call&) = delete;
    Call& operator=(const Call&) = delete;
    // The call has returned or raised: its time, and "" or why it is a time-limit row.
    std::string end() {
      ended_ = true;
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      const bool interrupted = limit_ > 0.0 && deadline_.disarm();
      if (!interrupted && !(limit_ > 0.0 && seconds > limit_)) return {};
      std::ostringstream why;
      why << "more than " << limit_ << " s of wall time: the function " << (interrupted ? "was interrupted" : "returned")
          << " after " << seconds << " s";
      return why.str();
    }

   private:
    CallDeadline& deadline_;
    double limit_;
    std::chrono::steady_clock::time_point start_;
    bool ended_ = false;
  };

  // "ValueError: bad": the exception's type and message in one line of at most 1000 bytes
  // (control characters as '?', text that is not UTF-8 escaped), whatever its str() does (a
  // multi-line message was a row's message of several lines: found by the fuzzer).
  static std::string describe(pybind11::error_already_set& e) {
    namespace py = pybind11;
    const py::object name = py::getattr(e.type(), "__name__", py::str("exception"));
    std::string text = py::isinstance<py::str>(name) ? utf8_text(name.ptr()) : "exception";
    if (PyObject* str = PyObject_Str(e.value().ptr())) {
      text += ": " + utf8_text(str);
      Py_DECREF(str);
    } else {
      PyErr_Clear();
      text += ": (its str() raised)";
    }
    return clip(text, 1000);
  }

  // A str's text as UTF-8, with what is not (a lone surrogate) escaped.
  static std::string utf8_text(PyObject* str) {
    PyObject* bytes = PyUnicode_AsEncodedString(str, "utf-8", "backslashreplace");
    if (bytes == nullptr) {
      PyErr_Clear();
      return "?";
    }
    std::string out(PyBytes_AS_STRING(bytes), static_cast<std::size_t>(PyBytes_GET_SIZE(bytes)));
    Py_DECREF(bytes);
    return out;
  }

  // The case document's time_limit, 0 where it has none.
  static double time_limit(const pybind11::object& case_dict) {
    const pybind11::object limit = case_dict.attr("get")("time_limit", 0.0);
    return pybind11::isinstance<pybind11::float_>(limit) || pybind11::isinstance<pybind11::int_>(limit)
               ? limit.cast<double>()
               : 0.0;
  }

  std::string time_limit_answer(const std::string& message) const {
    pybind11::dict out;
    out["version"] = 1;
    out["status"] = "time-limit";
    out["message"] = message;
    return pybind11::str(json_.attr("dumps")(out));
  }

  pybind11::object f_;
  pybind11::module_ json_;
  std::shared_ptr<CallDeadline> deadline_;  // shared by the copies std::function makes
  void (*interrupt_)();
};

}  // namespace pb::python
