// SPDX-License-Identifier: Apache-2.0
// palp.set_log_handler(handler): the SDK's log (palp/log.hpp) to a Python callable
// handler(level, message), level "info", "warning" or "error": link events, reconnects, resent
// requests, stream gaps. The SDK calls it from its I/O threads: the call takes the GIL; an
// exception it raises is reported as unraisable (sys.unraisablehook) and never reaches the SDK.
// None turns the log off (the default). palp/__init__.py turns it off at exit, before the
// interpreter goes away under a thread that might still report.
#include <memory>

#include "bindings.hpp"
#include "palp/log.hpp"

namespace palp_python {

void bind_log(py::module_& m) {
  m.def(
      "set_log_handler",
      [](const py::object& handler) {
        if (handler.is_none()) {
          palp::set_log_handler({});
          return;
        }
        if (!PyCallable_Check(handler.ptr()))
          throw palp::ConfigError(
              "set_log_handler: a callable handler(level, message) or None, not " +
              py::cast<std::string>(py::type::of(handler).attr("__name__")));
        // the SDK may drop its last copy on an I/O thread: the callable is released with the GIL
        std::shared_ptr<py::object> keep(new py::object(handler), [](py::object* o) {
          py::gil_scoped_acquire gil;
          delete o;
        });
        palp::set_log_handler([keep](palp::LogLevel level, const std::string& message) {
          if (!Py_IsInitialized()) return;
          py::gil_scoped_acquire gil;
          try {
            (*keep)(palp::log_level_name(level), message);
          } catch (py::error_already_set& e) {
            e.discard_as_unraisable("palp log handler");
          }
        });
      },
      py::arg("handler"),
      "Sends the SDK's log lines to handler(level, message) (level: \"info\", \"warning\", "
      "\"error\"), called from the SDK's threads; None turns the log off.");
}

}  // namespace palp_python
