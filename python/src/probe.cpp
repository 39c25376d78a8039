// SPDX-License-Identifier: Apache-2.0
// palp.Probe: one connection to a probe controller or palp-sim (palp/probe.hpp), SI units.
// Every call that talks to the device releases the GIL; the waits (wait, run) wait in slices and
// let Ctrl-C through: the program is stopped (coil to 0 A) and KeyboardInterrupt raised.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "palp/discovery.hpp"
#include "palp/probe.hpp"

namespace palp_python {

namespace {

using palp::Probe;
using release = py::call_guard<py::gil_scoped_release>;

/// Probe::wait in slices of at most half a second, Ctrl-C checked between them: an interrupt
/// stops the program (the coil goes to 0 A) and raises KeyboardInterrupt.
palp::ProgramResult wait_interruptibly(Probe& probe, double timeout_s) {
  Interrupt interrupt;
  const auto end = std::chrono::steady_clock::now() + timeout_of(timeout_s);
  {
    py::gil_scoped_release unlocked;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      try {
        return probe.wait(std::clamp(left, std::chrono::milliseconds(1), std::chrono::milliseconds(500)));
      } catch (const palp::TimeoutError& e) {
        if (std::chrono::steady_clock::now() >= end)
          throw palp::TimeoutError(e.waited_for(), timeout_s, e.health());
      }
      if (interrupt.poll()) {
        probe.stop();
        break;
      }
    }
  }
  interrupt.rethrow_if_interrupted();
  throw palp::Error("unreachable");  // poll() returned true, so rethrow raised
}

template <class P>
void def_program(py::class_<Probe, ProbeHolder>& cls) {
  cls.def("load", [](Probe& p, const P& program) { p.load(program); }, py::arg("program"), release());
  cls.def(
      "run",
      [](Probe& p, const P& program, double timeout_s) {
        {
          py::gil_scoped_release r;
          p.load(program);
          p.start();
        }
        return wait_interruptibly(p, timeout_s);
      },
      py::arg("program"), py::arg("timeout_s"),
      "load + start + wait; Ctrl-C stops the program (coil to 0 A) and raises KeyboardInterrupt.");
}

}  // namespace

void bind_probe(py::module_& m) {
  py::class_<palp::DeviceInfo>(m, "DeviceInfo", "Who the device is (its DeviceInfo).")
      .def_readonly("serial", &palp::DeviceInfo::serial)
      .def_readonly("board", &palp::DeviceInfo::board)
      .def_readonly("git_hash", &palp::DeviceInfo::git_hash)
      .def_readonly("firmware_version", &palp::DeviceInfo::firmware_version)
      .def_readonly("protocol_major", &palp::DeviceInfo::protocol_major)
      .def_readonly("protocol_minor", &palp::DeviceInfo::protocol_minor)
      .def_readonly("schema_hash", &palp::DeviceInfo::schema_hash)
      .def_readonly("capabilities", &palp::DeviceInfo::capabilities)
      .def_readonly("max_current_A", &palp::DeviceInfo::max_current_A)
      .def_readonly("control_rate_Hz", &palp::DeviceInfo::control_rate_Hz)
      .def_readonly("max_stream_rate_Hz", &palp::DeviceInfo::max_stream_rate_Hz)
      .def_readonly("heartbeat_timeout_s", &palp::DeviceInfo::heartbeat_timeout_s)
      .def_readonly("max_payload", &palp::DeviceInfo::max_payload);

  py::class_<palp::Handshake>(m, "Handshake", "The handshake's outcome.")
      .def_readonly("missing_features", &palp::Handshake::missing_features)
      .def_readonly("missing", &palp::Handshake::missing)
      .def_readonly("message", &palp::Handshake::message);

  py::class_<palp::Status>(m, "Status", "The device's status, SI units; enums as their names.")
      .def_readonly("t_device_s", &palp::Status::t_device_s)
      .def_property_readonly("state", [](const palp::Status& s) { return enum_text(s.state); })
      .def_property_readonly("fault", [](const palp::Status& s) { return enum_text(s.fault); })
      .def_property_readonly("program", [](const palp::Status& s) { return enum_text(s.program); })
      .def_property_readonly("program_state", [](const palp::Status& s) { return enum_text(s.program_state); })
      .def_readonly("i_cmd_A", &palp::Status::i_cmd_A)
      .def_readonly("i_A", &palp::Status::i_A)
      .def_readonly("z_m", &palp::Status::z_m)
      .def_readonly("encoder_counts", &palp::Status::encoder_counts)
      .def_readonly("i2t_fraction", &palp::Status::i2t_fraction)
      .def_readonly("streaming", &palp::Status::streaming)
      .def_readonly("status_bits", &palp::Status::status_bits);

  py::class_<palp::HealthCounters>(m, "Health", "Device and host counters (Probe.health).")
#define PALP_PY_HEALTH(name) .def_readonly(#name, &palp::HealthCounters::name)
      PALP_PY_HEALTH(device_time_us) PALP_PY_HEALTH(device_frames_rx) PALP_PY_HEALTH(device_frames_tx)
      PALP_PY_HEALTH(device_rx_rejected) PALP_PY_HEALTH(isr_queue_overflows)
      PALP_PY_HEALTH(stream_backlog_max) PALP_PY_HEALTH(stream_samples_lost)
      PALP_PY_HEALTH(usb_in_not_drained) PALP_PY_HEALTH(tx_frames_dropped)
      PALP_PY_HEALTH(control_overruns) PALP_PY_HEALTH(device_stream_gaps) PALP_PY_HEALTH(device_valid)
      PALP_PY_HEALTH(host_frames_rx) PALP_PY_HEALTH(host_rx_rejected)
      PALP_PY_HEALTH(host_samples_received) PALP_PY_HEALTH(host_samples_missing)
      PALP_PY_HEALTH(host_queue_dropped) PALP_PY_HEALTH(host_queue_max) PALP_PY_HEALTH(host_gaps)
      PALP_PY_HEALTH(reconnects) PALP_PY_HEALTH(requests_resent)
#undef PALP_PY_HEALTH
      .def("__str__", [](const palp::HealthCounters& h) { return palp::describe(h); });

  py::class_<palp::ProgramResult>(m, "ProgramResult", "How a program ended.")
      .def_property_readonly("kind", [](const palp::ProgramResult& r) { return enum_text(r.kind); })
      .def_property_readonly("end", [](const palp::ProgramResult& r) { return enum_text(r.end); })
      .def_readonly("t_device_s", &palp::ProgramResult::t_device_s)
      .def_readonly("repetitions_done", &palp::ProgramResult::repetitions_done);

  py::class_<palp::FaultInfo>(m, "FaultInfo", "The fault latch.")
      .def_property_readonly("reason", [](const palp::FaultInfo& f) { return enum_text(f.reason); })
      .def_readonly("t_device_s", &palp::FaultInfo::t_device_s)
      .def_readonly("detail", &palp::FaultInfo::detail)
      .def_readonly("text", &palp::FaultInfo::text);

  py::class_<palp::DeviceListing>(m, "DeviceListing", "One controller on this machine's USB.")
      .def_readonly("serial", &palp::DeviceListing::serial)
      .def_readonly("firmware_version", &palp::DeviceListing::firmware_version)
      .def_readonly("product", &palp::DeviceListing::product)
      .def_readonly("vid", &palp::DeviceListing::vid)
      .def_readonly("pid", &palp::DeviceListing::pid)
      .def_readonly("uris", &palp::DeviceListing::uris)
      .def_readonly("note", &palp::DeviceListing::note);
  m.def("list_devices", [] { return palp::list_devices(); }, release(),
        "Every palp controller on this machine's USB; [] when there is none.");

  py::class_<Probe, ProbeHolder> cls(
      m, "Probe", "One connection to a probe controller (usb://, hid://, sim://, ...).");
  cls.def(py::init([](const std::string& uri, double timeout_s, bool reconnect) {
            palp::ConnectOptions o;
            o.timeout = timeout_of(timeout_s);
            o.reconnect = reconnect;
            o.host_software = std::string("palp-python ") + palp::sdk_version();
            ProbeHolder p;
            {
              py::gil_scoped_release r;
              p.reset(new Probe(uri, o));
            }
            return p;
          }),
          py::arg("uri"), py::arg("timeout_s") = 2.0, py::arg("reconnect") = true,
          "Connects and runs the handshake (ConfigError, ConnectionError, TimeoutError, VersionError).");
  cls.def_property_readonly("info", &Probe::info)
      .def_property_readonly("handshake", &Probe::handshake)
      .def_property_readonly("uri", &Probe::uri)
      .def("status", &Probe::status, release())
      .def("health", &Probe::health, release())
      .def("params", &Probe::params, release())
      .def("set_params", &Probe::set_params, py::arg("params"), release())
      .def("calibration", &Probe::calibration, release())
      .def("set_calibration", &Probe::set_calibration, py::arg("calibration"), release())
      .def("commit_calibration", &Probe::commit_calibration, release())
      .def("start", &Probe::start, release())
      .def("stop", &Probe::stop, release())
      .def("wait", &wait_interruptibly, py::arg("timeout_s"),
           "Waits for the program's end; Ctrl-C stops it (coil to 0 A) and raises KeyboardInterrupt.")
      .def("program_status", &Probe::program_status, release())
      .def("fault", &Probe::fault, release())
      .def("clear_fault", &Probe::clear_fault, release())
      .def("zero_current_offset", &Probe::zero_current_offset, py::arg("seconds") = 0.5, release())
      .def("zero_pressure", &Probe::zero_pressure, py::arg("seconds") = 0.5, release())
      .def("home", &Probe::home, py::arg("hold_current_A") = -0.3, py::arg("seconds") = 1.0, release())
      .def("make_safe", &Probe::make_safe, release())
      .def("close", &Probe::close, release())
      .def("__enter__", [](Probe& p) -> Probe& { return p; }, py::return_value_policy::reference)
      .def("__exit__", [](Probe& p, const py::args&) { py::gil_scoped_release r; p.close(); });
  def_program<palp::HoldProgram>(cls);
  def_program<palp::RampProgram>(cls);
  def_program<palp::SineProgram>(cls);
  def_program<palp::SweepProgram>(cls);
  def_program<palp::MultisineProgram>(cls);
  def_program<palp::ContactWatchProgram>(cls);
}

}  // namespace palp_python
