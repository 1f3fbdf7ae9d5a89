#pragma once
// A Python callable as the external solver, in process (issue 37): `poundbench.spectrum(set,
// solver=f)`. f gets the case as a dict (the external protocol's case document,
// docs/external.md) and returns the answer as a dict ("version" may be left out); the
// external solver hands it the document through Settings::in_process, so the row is made by
// the same code as a program's, answer checks included. Its row's solve_seconds is the call
// timed around it, the dict's conversions outside; what f raises is that point's failed row,
// with the exception's type and message. A sweep with a callable runs on one thread: the GIL
// lets one call run at a time, and a second thread's wait for it would be timed as its cost.

#include <pybind11/pybind11.h>

#include <chrono>
#include <stdexcept>
#include <string>

namespace pb::python {

class CallableSolver {
 public:
  explicit CallableSolver(pybind11::object f)
      : f_(std::move(f)), json_(pybind11::module_::import("json")) {}

  // Settings::in_process: called on a sweep's thread, without the GIL.
  std::string operator()(const std::string& case_document, double& call_seconds) const {
    namespace py = pybind11;
    py::gil_scoped_acquire gil;
    try {
      const py::object case_dict = json_.attr("loads")(case_document);
      const auto start = std::chrono::steady_clock::now();
      py::object answer;
      try {
        answer = f_(case_dict);
      } catch (...) {
        call_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        throw;
      }
      call_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!py::isinstance<py::dict>(answer))
        throw std::runtime_error("the solver returned " + std::string(py::str(py::type::of(answer).attr("__name__"))) +
                                 ", not a dict (the answer, docs/external.md)");
      py::dict out(answer.attr("copy")());
      if (!out.contains("version")) out["version"] = 1;
      return py::str(json_.attr("dumps")(out, py::arg("allow_nan") = false));
    } catch (py::error_already_set& e) {
      // The point's failed row says what f raised: "ZeroDivisionError: division by zero".
      const std::string what = std::string(py::str(e.type().attr("__name__"))) + ": " + std::string(py::str(e.value()));
      throw std::runtime_error(what);
    }
  }

 private:
  pybind11::object f_;
  pybind11::module_ json_;
};

}  // namespace pb::python
