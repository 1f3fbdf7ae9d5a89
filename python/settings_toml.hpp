#pragma once
// A settings list given to the Python module as a list of dicts, one per [[run]]
// (studies/settings_list.hpp), written as the TOML text the command line's file would hold, so
// that one parser checks both: a str as a TOML string, a bool, an int, a float, a list of them,
// and a dict (steps = {"from": 8, "to": 4096}) as an inline table.

#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

namespace pb::python {

inline std::string toml_value(const pybind11::handle& v, const std::string& key) {
  namespace py = pybind11;
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) {
    const std::string text = py::str(py::repr(v));
    if (text == "nan" || text == "inf" || text == "-inf") return text;
    return text;
  }
  if (py::isinstance<py::str>(v))  // JSON's string is TOML's basic string for what a key holds
    return py::str(py::module_::import("json").attr("dumps")(v));
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::string out = "[";
    for (const py::handle& x : v) out += (out.size() > 1 ? ", " : "") + toml_value(x, key);
    return out + "]";
  }
  if (py::isinstance<py::dict>(v)) {
    std::string out = "{";
    for (const auto& [k, x] : v.cast<py::dict>())
      out += (out.size() > 1 ? ", " : "") + std::string(py::str(k)) + " = " + toml_value(x, key);
    return out + "}";
  }
  throw py::type_error("settings: " + key + ": a " + std::string(py::str(py::type::of(v).attr("__name__"))) +
                       " is not a value of a settings list (str, bool, int, float, list or dict)");
}

}  // namespace pb::python
