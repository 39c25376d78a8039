// SPDX-License-Identifier: Apache-2.0
// palp.Error and its subclasses, mirroring host/include/palp/error.hpp, with the C++ message and
// the error's own fields as attributes. palp.ConnectionError and palp.TimeoutError also derive
// from Python's built-in ConnectionError and TimeoutError, palp.ConfigError from ValueError, so
// code that catches the built-ins catches them too.
#include "bindings.hpp"

namespace palp_python {

namespace {

struct Classes {
  py::object error, config, connection, timeout, version, device, fault, protocol, recording,
      data, robot_rejected, robot_fault, flash, robot_link;
};
Classes* classes = nullptr;  // created once by bind_errors, alive as long as the module

py::object make_class(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("palp.") + name;
  PyObject* c = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (c == nullptr) throw py::error_already_set();
  py::object cls = py::reinterpret_steal<py::object>(c);
  m.attr(name) = cls;
  return cls;
}

void raise(const py::object& cls, const std::exception& e, const py::dict& attrs) {
  py::object instance = cls(e.what());
  for (auto item : attrs) py::setattr(instance, item.first, item.second);
  PyErr_SetObject(cls.ptr(), instance.ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
  classes = new Classes;  // NOLINT: lives as long as the interpreter (exception translators use it)
  Classes& c = *classes;
  const py::module_ builtins = py::module_::import("builtins");
  c.error = make_class(m, "Error", py::make_tuple(builtins.attr("Exception")),
                       "Base of everything the palp SDK raises; str(e) is the SDK's message.");
  const auto sub = [&](const char* name, const char* doc, py::object extra = py::none()) {
    return make_class(m, name, extra.is_none() ? py::make_tuple(c.error) : py::make_tuple(c.error, extra), doc);
  };
  c.config = sub("ConfigError", "A bad argument, URI, option or setting; nothing was sent.",
                 builtins.attr("ValueError"));
  c.connection = sub("ConnectionError", "The device could not be reached, or the link was lost.",
                     builtins.attr("ConnectionError"));
  c.timeout = sub("TimeoutError",
                  "A reply or an event did not come in time (waited_for, timeout_s).",
                  builtins.attr("TimeoutError"));
  c.version = sub("VersionError", "The handshake found the device incompatible.");
  c.device = sub("DeviceError", "The device refused a request (request, code, field_index, detail).");
  c.fault = sub("FaultError", "The device's fault latch tripped (reason: proto FaultReason value).");
  c.protocol = sub("ProtocolError", "The device sent bytes the SDK cannot accept.");
  c.recording = sub("RecordingError", "A recording file is malformed (file, line, problem).");
  c.data = sub("DataError", "The data cannot give the result asked of it.");
  c.robot_rejected = sub("RobotRejectedError", "The robot bridge refused a command (result, register_address).");
  c.robot_fault = sub("RobotFaultError", "The robot faulted or was safety-stopped during a motion.");
  c.flash = sub("FlashError", "A firmware update failed after the device left its application (erased).");
  c.robot_link = make_class(m, "RobotLinkError", py::make_tuple(c.connection),
                            "The robot bridge is unreachable or its heartbeat stopped.");

  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    const Classes& k = *classes;
    try {
      std::rethrow_exception(p);
    } catch (const palp::ConfigError& e) {
      raise(k.config, e, {});
    } catch (const palp::RobotLinkError& e) {
      raise(k.robot_link, e, {});
    } catch (const palp::ConnectionError& e) {
      raise(k.connection, e, {});
    } catch (const palp::TimeoutError& e) {
      raise(k.timeout, e, py::dict(py::arg("waited_for") = e.waited_for(), py::arg("timeout_s") = e.timeout_s()));
    } catch (const palp::VersionError& e) {
      raise(k.version, e, {});
    } catch (const palp::DeviceError& e) {
      raise(k.device, e,
            py::dict(py::arg("request") = e.request(), py::arg("code") = e.code(),
                     py::arg("field_index") = e.field_index(), py::arg("detail") = e.detail()));
    } catch (const palp::FaultError& e) {
      raise(k.fault, e, py::dict(py::arg("reason") = e.reason()));
    } catch (const palp::ProtocolError& e) {
      raise(k.protocol, e, {});
    } catch (const palp::RecordingError& e) {
      raise(k.recording, e,
            py::dict(py::arg("file") = e.file(), py::arg("line") = e.line(), py::arg("problem") = e.problem()));
    } catch (const palp::DataError& e) {
      raise(k.data, e, {});
    } catch (const palp::RobotRejectedError& e) {
      raise(k.robot_rejected, e,
            py::dict(py::arg("result") = e.result(), py::arg("register_address") = e.register_address()));
    } catch (const palp::RobotFaultError& e) {
      raise(k.robot_fault, e, {});
    } catch (const palp::FlashError& e) {
      raise(k.flash, e, py::dict(py::arg("erased") = e.erased()));
    } catch (const palp::Error& e) {
      raise(k.error, e, {});
    }
  });
}

}  // namespace palp_python
