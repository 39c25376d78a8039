// SPDX-License-Identifier: Apache-2.0
#include "palp/health.hpp"

#include <sstream>

namespace palp {

std::string describe(const HealthCounters& h) {
  std::ostringstream s;
  if (h.device_valid) {
    s << "device t=" << h.device_time_us << " us rx " << h.device_frames_rx << " tx "
      << h.device_frames_tx << " rejected " << h.device_rx_rejected << ", isr overflows "
      << h.isr_queue_overflows << ", backlog max " << h.stream_backlog_max << " lost "
      << h.stream_samples_lost << ", usb_in dropped " << h.usb_in_not_drained << ", tx dropped "
      << h.tx_frames_dropped << ", overruns " << h.control_overruns << ", gaps "
      << h.device_stream_gaps << "; ";
  } else {
    s << "device counters not read; ";
  }
  s << "host rx " << h.host_frames_rx << " rejected " << h.host_rx_rejected << ", samples "
    << h.host_samples_received << " missing " << h.host_samples_missing << " (queue dropped "
    << h.host_queue_dropped << ", queue max " << h.host_queue_max << "), gaps " << h.host_gaps
    << ", reconnects " << h.reconnects << ", requests resent " << h.requests_resent;
  return s.str();
}

}  // namespace palp
