// SPDX-License-Identifier: Apache-2.0
// Health counters: every buffering stage between the control tick and the application, so a
// lost sample always has a named place where it was lost (DESIGN.md, protocol principles).
#pragma once

#include <cstdint>
#include <string>

namespace palp {

struct HealthCounters {
  // --- device side (the device's Health reply; zero until the first one arrives) ---
  std::uint64_t device_time_us = 0;
  std::uint32_t device_frames_rx = 0;
  std::uint32_t device_frames_tx = 0;
  std::uint32_t device_rx_rejected = 0;       ///< frames the device rejected, all reasons
  std::uint32_t isr_queue_overflows = 0;      ///< samples lost at the control ISR's queue
  std::uint32_t stream_backlog_max = 0;       ///< deepest the device's stream backlog has been
  std::uint32_t stream_samples_lost = 0;      ///< samples lost in the device's stream backlog
  std::uint32_t usb_in_not_drained = 0;       ///< frames the device dropped, IN not drained
  std::uint32_t tx_frames_dropped = 0;
  std::uint32_t control_overruns = 0;
  std::uint32_t device_stream_gaps = 0;       ///< EventStreamGap events the device emitted
  bool device_valid = false;                  ///< a Health reply has been received

  // --- host side (this connection, since it opened) ---
  std::uint64_t host_frames_rx = 0;           ///< frames accepted from the device
  std::uint64_t host_rx_rejected = 0;         ///< frames from the device rejected (CRC, COBS...)
  std::uint64_t host_samples_received = 0;    ///< samples decoded
  std::uint64_t host_samples_missing = 0;     ///< samples reported missing (all gap records)
  std::uint64_t host_queue_dropped = 0;       ///< samples dropped because the host queue was full
  std::uint64_t host_queue_max = 0;           ///< deepest the host queue has been
  std::uint64_t host_gaps = 0;                ///< gap records delivered
  std::uint64_t reconnects = 0;               ///< sessions restored after a lost link
  std::uint64_t requests_resent = 0;          ///< read-only/idempotent requests sent again
                                              ///< (same seq) because their reply was lost
};

/// One line: "device rx 12 tx 340 rejected 0, backlog max 3, lost 0 ...; host rx ...".
std::string describe(const HealthCounters& h);

}  // namespace palp
