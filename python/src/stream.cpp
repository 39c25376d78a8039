// SPDX-License-Identifier: Apache-2.0
// Streaming into numpy: Probe.read(n) returns (samples, gaps), two structured arrays whose field
// names carry SI units (docs/python.md):
//   samples: index u8, t_s (device time), t_host_s, i_cmd_A, i_A, z_m, encoder_counts i4,
//            p1_Pa .. p6_Pa, status u2, v_cmd_V
//   gaps:    first_index u8, count u8, source u1 (an index into palp.GAP_SOURCES), t_s,
//            count_known ?
// A gap record says samples [first_index, first_index + count) are missing; nothing is filled in.
#include <pybind11/numpy.h>

#include "bindings.hpp"
#include "palp/probe.hpp"

namespace palp_python {

struct SampleRow {
  std::uint64_t index;
  double t_s, t_host_s, i_cmd_A, i_A, z_m;
  std::int32_t encoder_counts;
  double p1_Pa, p2_Pa, p3_Pa, p4_Pa, p5_Pa, p6_Pa;
  std::uint16_t status;
  double v_cmd_V;
};

struct GapRow {
  std::uint64_t first_index, count;
  std::uint8_t source;
  double t_s;
  bool count_known;
};

namespace {

SampleRow row_of(const palp::Sample& s) {
  return {s.index,    s.t_device_s, s.t_host_s, s.i_cmd_A,  s.i_A,    s.z_m,    s.encoder_counts,
          s.p_Pa[0],  s.p_Pa[1],    s.p_Pa[2],  s.p_Pa[3],  s.p_Pa[4], s.p_Pa[5], s.status,
          s.v_cmd_V};
}

GapRow row_of(const palp::Gap& g) {
  return {g.first_index, g.count, static_cast<std::uint8_t>(g.source), g.t_device_s, g.count_known};
}

template <class Row>
py::array_t<Row> to_array(const std::vector<Row>& rows) {
  py::array_t<Row> a(static_cast<py::ssize_t>(rows.size()));
  if (!rows.empty()) std::memcpy(a.mutable_data(), rows.data(), rows.size() * sizeof(Row));
  return a;
}

py::tuple read(palp::Probe& probe, std::size_t n, double timeout_s) {
  if (!(timeout_s >= 0)) throw palp::ConfigError("read: timeout_s must be >= 0, got " + std::to_string(timeout_s));
  std::vector<SampleRow> samples;
  std::vector<GapRow> gaps;
  samples.reserve(n);
  Interrupt interrupt;
  {
    py::gil_scoped_release release;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    std::vector<palp::StreamItem> items;
    const auto take = [&](const palp::StreamItem& item) {
      if (const auto* s = std::get_if<palp::Sample>(&item)) samples.push_back(row_of(*s));
      else gaps.push_back(row_of(std::get<palp::Gap>(item)));
    };
    while (samples.size() < n && !interrupt.poll()) {
      items.clear();
      if (probe.drain(items, n - samples.size()) > 0) {
        for (const auto& item : items) take(item);
        continue;
      }
      const auto now = std::chrono::steady_clock::now();
      if (now >= end) break;
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - now);
      if (auto item = probe.next(std::clamp(left, std::chrono::milliseconds(1), std::chrono::milliseconds(50))))
        take(*item);
    }
  }
  interrupt.rethrow_if_interrupted();
  return py::make_tuple(to_array(samples), to_array(gaps));
}

}  // namespace

void bind_stream(py::module_& m) {
  PYBIND11_NUMPY_DTYPE(SampleRow, index, t_s, t_host_s, i_cmd_A, i_A, z_m, encoder_counts, p1_Pa, p2_Pa,
                       p3_Pa, p4_Pa, p5_Pa, p6_Pa, status, v_cmd_V);
  PYBIND11_NUMPY_DTYPE(GapRow, first_index, count, source, t_s, count_known);
  py::list sources;
  for (int k = 0; k <= static_cast<int>(palp::GapSource::reconnect); ++k)
    sources.append(palp::gap_source_name(static_cast<palp::GapSource>(k)));
  m.attr("GAP_SOURCES") = py::tuple(sources);
  m.attr("sample_dtype") = py::dtype::of<SampleRow>();
  m.attr("gap_dtype") = py::dtype::of<GapRow>();

  py::module_ ch = m.def_submodule("channel", "Stream channel bits (Probe.configure_stream).");
  ch.attr("i_cmd") = palp::channel::i_cmd;
  ch.attr("i_meas") = palp::channel::i_meas;
  ch.attr("encoder") = palp::channel::encoder;
  ch.attr("pressure") = palp::channel::pressure;
  ch.attr("status") = palp::channel::status;
  ch.attr("v_cmd") = palp::channel::v_cmd;
  ch.attr("all") = palp::channel::all;

  py::class_<palp::StreamInfo>(m, "StreamInfo", "The stream configuration in force.")
      .def_readonly("rate_Hz", &palp::StreamInfo::rate_Hz)
      .def_readonly("period_s", &palp::StreamInfo::period_s)
      .def_readonly("channels", &palp::StreamInfo::channels)
      .def_readonly("batch_samples", &palp::StreamInfo::batch_samples)
      .def_readonly("wire_bytes_per_s", &palp::StreamInfo::wire_bytes_per_s);

  auto probe = py::class_<palp::Probe, ProbeHolder>(m.attr("Probe"));
  using release = py::call_guard<py::gil_scoped_release>;
  probe
      .def(
          "configure_stream",
          [](palp::Probe& p, double rate_Hz, std::uint16_t channels, std::uint16_t batch_samples) {
            return p.configure_stream({rate_Hz, channels, batch_samples});
          },
          py::arg("rate_Hz") = 1000.0, py::arg("channels") = palp::channel::all,
          py::arg("batch_samples") = 0, release())
      .def("start_stream", &palp::Probe::start_stream, release())
      .def("stop_stream", &palp::Probe::stop_stream, release())
      .def_property_readonly("stream_info", &palp::Probe::stream_info)
      .def("read", &read, py::arg("n"), py::arg("timeout_s") = 10.0,
           "Up to n samples, waiting at most timeout_s: (samples, gaps), structured arrays "
           "(palp.sample_dtype, palp.gap_dtype). Fewer samples when the time ran out.");
}

}  // namespace palp_python
