// SPDX-License-Identifier: Apache-2.0
// Turns SampleBatch and EventStreamGap messages into the ordered stream the application sees:
// samples with 64-bit indices and SI values, and one Gap record for every run of missing
// indices, attributed to the device stage that reported it or, when no device event covers it,
// to the transport. Pure: no I/O, no threads (the probe's I/O thread owns one).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "palp/protocol/messages.hpp"
#include "palp/protocol/stream.hpp"
#include "palp/stream.hpp"

namespace palp::detail {

class StreamAssembler {
 public:
  /// A new stream (StreamStart): the next batch starts at wire index 0 and host index 0.
  void restart();
  /// The link was lost and the session restored with a new StreamStart: the next batch is
  /// preceded by one reconnect Gap, sized from device time when the device clock ran on, or of
  /// unknown size (count_known = false) when it restarted. Host indices continue.
  void reconnected();

  /// A device-reported loss; kept until the batches show where it falls.
  void device_gap(const proto::EventStreamGap& g);

  /// Appends the batch's items (gaps first, then samples) to out; to_host maps device seconds to
  /// host seconds. Returns false and appends nothing for a malformed batch or one that goes
  /// backwards over indices already delivered (counted in rejected(); never repeated).
  bool batch(const proto::SampleBatch& b, const std::function<double(double)>& to_host,
             std::vector<StreamItem>& out);

  std::uint64_t rejected() const { return rejected_; }
  /// The host index the next sample is expected to have.
  std::uint64_t expected() const { return expected_; }

 private:
  struct Pending {
    std::uint32_t wire_first;
    std::uint32_t count;
    proto::GapStage stage;
    double t_s;
  };
  void emit_gaps(std::uint32_t wire_upto, std::vector<StreamItem>& out);

  std::uint64_t expected_ = 0;     // host index of the next sample
  std::uint32_t wire_expected_ = 0;  // its wire index
  double next_t_s_ = 0;            // device time of the next sample, when known
  double period_s_ = 0;
  bool any_ = false;               // a batch arrived since restart()
  bool reconnect_pending_ = false;
  double t_before_reconnect_s_ = 0;
  std::deque<Pending> pending_;
  std::uint64_t rejected_ = 0;
};

/// A sample's SI values from its wire integers.
Sample to_sample(const proto::RawSample& raw, std::uint64_t index, double t_device_s,
                 double t_host_s);

}  // namespace palp::detail
