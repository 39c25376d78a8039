// SPDX-License-Identifier: Apache-2.0
#include "convert.hpp"

namespace palp_python {

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

nlohmann::json to_json(py::handle o) {
  std::string text;
  try {
    text = py::module_::import("json").attr("dumps")(o, py::arg("allow_nan") = false).cast<std::string>();
  } catch (py::error_already_set& e) {
    throw palp::ConfigError(std::string("not convertible to JSON: ") + e.what());
  }
  return nlohmann::json::parse(text);
}

std::chrono::milliseconds timeout_of(double seconds) {
  if (!(seconds >= 0))
    throw palp::ConfigError("a timeout must be >= 0 s, got " + std::to_string(seconds));
  return std::chrono::milliseconds(static_cast<long long>(seconds * 1e3 + 0.5));
}

Interrupt::~Interrupt() {
  if (error_ != nullptr || type_ != nullptr || trace_ != nullptr) {
    py::gil_scoped_acquire gil;
    Py_XDECREF(type_);
    Py_XDECREF(error_);
    Py_XDECREF(trace_);
  }
}

bool Interrupt::poll() {
  if (hit_) return true;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(50)) return false;
  last_ = now;
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) {
    PyErr_Fetch(&type_, &error_, &trace_);
    hit_ = true;
    return true;
  }
  return false;
}

void Interrupt::keep(py::error_already_set& e) {
  if (hit_) return;  // the first interrupt is the one raised
  e.restore();
  PyErr_Fetch(&type_, &error_, &trace_);
  hit_ = true;
}

void Interrupt::rethrow_if_interrupted() {
  if (!hit_) return;
  hit_ = false;
  PyErr_Restore(type_, error_, trace_);
  type_ = error_ = trace_ = nullptr;
  throw py::error_already_set();
}

}  // namespace palp_python
