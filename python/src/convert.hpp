// SPDX-License-Identifier: Apache-2.0
// Conversions the bindings share: the SDK's JSON to Python objects and back, the catalogue's enums
// as their names, and the wait that lets Ctrl-C through while the GIL is released.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "palp/error.hpp"
#include "palp/protocol/messages.hpp"

namespace palp_python {

namespace py = pybind11;

/// A JSON value as the Python object json.loads gives (dict, list, str, float, int, bool, None).
py::object to_python(const nlohmann::json& j);
/// A Python object as JSON (through json.dumps: what it cannot encode is a palp.ConfigError).
nlohmann::json to_json(py::handle o);

/// A timeout in seconds as milliseconds (rounded); ConfigError when not >= 0.
std::chrono::milliseconds timeout_of(double seconds);

/// A catalogue enum value's name ("idle"), or "unknown (<value>)".
template <class E>
std::string enum_text(E value) {
  const char* n = palp::proto::enum_name(value);
  return n ? n : "unknown (" + std::to_string(static_cast<unsigned>(value)) + ")";
}
/// A catalogue enum from its name; ConfigError listing the names otherwise.
template <class E>
E enum_of(const std::string& name, const char* what) {
  std::string names;
  for (const auto& v : palp::proto::EnumInfo<E>::values) {
    if (name == v.name) return static_cast<E>(v.value);
    names += names.empty() ? "" : ", ";
    names += v.name;
  }
  throw palp::ConfigError(std::string(what) + ": unknown value \"" + name + "\" (one of " + names + ")");
}

/// Ctrl-C while the GIL is released: the SDK's `cancelled` callbacks and the wait loops call
/// poll(), which at most every 50 ms takes the GIL briefly and runs Python's signal handlers
/// (PyErr_CheckSignals). When a handler raised (KeyboardInterrupt), poll() keeps that exception
/// and returns true from then on; the binding lets the SDK return safely (coil at 0 A) and then
/// calls rethrow_if_interrupted(), which raises it in Python. Used from the thread that called
/// into the binding (the signal handlers run only in the main thread; elsewhere poll() only
/// reports an earlier interrupt).
class Interrupt {
 public:
  Interrupt() = default;
  ~Interrupt();
  Interrupt(const Interrupt&) = delete;
  Interrupt& operator=(const Interrupt&) = delete;
  bool poll();
  bool interrupted() const { return hit_; }
  /// Raises the kept exception (with the GIL held), if any.
  void rethrow_if_interrupted();
  std::function<bool()> callback() {
    return [this] { return poll(); };
  }
  /// Calls a Python callback from the SDK's thread (taking the GIL). Ctrl-C that lands while
  /// Python runs it raises KeyboardInterrupt inside it: that is kept as poll()'s (the SDK then sees
  /// cancelled() turn true and stops safely) instead of thrown through the SDK as an error; any
  /// other exception propagates.
  template <class... A>
  void call(const py::object& f, A&&... args) {
    py::gil_scoped_acquire gil;
    try {
      f(std::forward<A>(args)...);
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_KeyboardInterrupt)) throw;
      keep(e);
    }
  }

 private:
  void keep(py::error_already_set& e);
  std::chrono::steady_clock::time_point last_{};
  bool hit_ = false;
  PyObject *type_ = nullptr, *error_ = nullptr, *trace_ = nullptr;
};

}  // namespace palp_python
