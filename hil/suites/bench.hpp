// SPDX-License-Identifier: Apache-2.0
// Where the HIL suites run, and the fixture every scenario derives from (README.md).
//
//   (nothing set)            the suites start palp-sim themselves (--port 0 --control-port 0
//                            --pace fast, placed like the QEMU plant's scene: kPlantScene) and
//                            run every scenario against it
//   PALP_QEMU_IMAGE=<elf>    the suites start that firmware image under qemu-system-arm on a
//                            free loopback port (the command line of firmware/README.md) and
//                            run every scenario against it, with palp-sim placed like the image's
//                            plant as the reference of the indentation. An image that is missing,
//                            a QEMU that does not start or an image that does not answer the
//                            handshake within kQemuAnswer FAILS every scenario: never a skip
//   PALP_BENCH_URI=<uri>     the same scenarios against that device (usb://SERIAL, hid://SERIAL,
//                            sim://host:port, tcp://host:port). It is tried once at start; when
//                            it does not answer (ConnectionError, TimeoutError) every scenario is
//                            skipped with "PALP_BENCH_URI=<uri> does not answer: <why>". Any
//                            other problem (a malformed URI, an incompatible firmware) fails
//                            every scenario instead: the bench answered, and what it said needs a
//                            person.
//   PALP_REFERENCE_URI=<uri> a device the indentation is repeated on, to compare k and delta0
//                            (a palp-sim placed like the bench's specimen); unset: no comparison
//                            (except under PALP_QEMU_IMAGE, whose reference the suites start)
//   PALP_BENCH_SPECIMEN=1    the bench has a specimen that the floating tip touches: the
//                            indentation runs (palp-sim and QEMU have one; unset on a bench, it
//                            skips saying so)
//
// Scenarios use the SDK's public API only: a real bench has no simulator control channel.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "child.hpp"
#include "palp/probe.hpp"

namespace palp::hil {

/// The stream's current resolution (SPEC.md §9).
inline constexpr double kLsb_A = 0.0002;

/// How long an image under QEMU has to answer the SDK's handshake after QEMU starts.
inline constexpr std::chrono::seconds kQemuAnswer{10};

class Bench : public ::testing::Environment {
 public:
  /// The one instance (registered by the suites' main()).
  static Bench& get();

  void SetUp() override;
  void TearDown() override;

  /// The device URI scenarios connect to.
  const std::string& uri() const { return uri_; }
  /// The reference device for the indentation's comparison, or empty: none configured.
  const std::string& reference_uri() const { return reference_uri_; }
  /// True when the device has a specimen the floating tip touches (see the top of this file).
  bool has_specimen() const { return specimen_; }
  /// True when the suites started the device themselves (palp-sim or QEMU).
  bool started_device() const { return static_cast<bool>(device_); }
  /// Non-empty when every scenario is skipped: the configured bench did not answer.
  const std::string& skip_reason() const { return skip_; }
  /// Non-empty when every scenario fails: palp-sim or QEMU did not start, or the bench is unusable.
  const std::string& failure() const { return failure_; }

 private:
  void start_simulator();
  void start_qemu(const std::string& image);
  void check_bench(const std::string& uri);

  std::string uri_, reference_uri_, skip_, failure_;
  bool specimen_ = false;
  std::unique_ptr<Child> device_, reference_;
};

/// Base fixture: skips (or fails) as Bench says, connects one Probe, keeps the device's
/// parameters and puts them back afterwards, and leaves no fault latched behind, so scenarios
/// never depend on one another's leftovers (a real bench keeps its state between them too).
class Scenario : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  Probe& probe() { return *probe_; }
  /// The parameters in force before the scenario (restored by TearDown).
  const Params& saved_params() const { return saved_; }
  /// Closes this scenario's connection (the device then serves another host) ...
  void disconnect();
  /// ... and opens it again (retrying a refused connection for up to 2 s).
  void connect();

 private:
  std::unique_ptr<Probe> probe_;
  Params saved_{};
  std::uint32_t overruns_at_start_ = 0;  ///< Health.control_overruns when the scenario began
};

/// The samples streamed up to device time t_end_s (the first sample at or after it included),
/// waiting at most `patience` for each item; gap records go to *gaps.
std::vector<Sample> samples_until(Probe& probe, double t_end_s, std::vector<Gap>& gaps,
                                  std::chrono::milliseconds patience = std::chrono::seconds(5));

/// "" for none, else "N gaps, M samples; the first: K samples at index I (source)".
std::string gaps_text(const std::vector<Gap>& gaps);

/// The highest stream rate at most `wanted_Hz` that the device streams (DeviceInfo's
/// max_stream_rate_Hz) and that divides its control rate: `wanted_Hz` itself on palp-sim and a
/// USB bench, less on a slow link (QEMU's UART).
double stream_rate_at_most(const DeviceInfo& d, double wanted_Hz);

/// "" when two messages are equal, else "name: a vs b; ..." for each field that differs (its
/// values when they are numbers), in catalogue order.
template <class M>
std::string field_differences(const M& a, const M& b) {
  std::vector<const void*> theirs;
  b.visit([&](const proto::FieldInfo&, const auto& field) { theirs.push_back(&field); });
  std::string out;
  std::size_t k = 0;
  a.visit([&](const proto::FieldInfo& f, const auto& field) {
    using T = std::remove_cvref_t<decltype(field)>;
    const T& other = *static_cast<const T*>(theirs[k++]);
    if (field == other) return;
    out += std::string(out.empty() ? "" : "; ") + f.name;
    if constexpr (std::is_arithmetic_v<T>) {
      std::ostringstream o;
      o.precision(9);
      o << ": " << +field << " vs " << +other;
      out += o.str();
    }
  });
  return out;
}

/// The flag that makes the suites' executable the host-loss scenario's doomed host instead
/// (watchdog_scenarios.cpp): `palp_hil_suites --host-loss-child URI TIMEOUT_MS CURRENT_A`.
inline constexpr const char* kHostLossChildFlag = "--host-loss-child";
int host_loss_child(int argc, char** argv);

}  // namespace palp::hil
