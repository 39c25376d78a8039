// Where the HIL suites run, and the fixture every scenario derives from (README.md).
//
//   PALP_BENCH_URI unset   the suites start palp-sim themselves (--port 0 --control-port 0
//                          --pace fast) and run every scenario against it
//   PALP_BENCH_URI=<uri>   the same scenarios against that device (usb://SERIAL, hid://SERIAL,
//                          sim://host:port). It is tried once at start; when it does not answer
//                          (ConnectionError, TimeoutError) every scenario is skipped with
//                          "PALP_BENCH_URI=<uri> does not answer: <why>". Any other problem (a
//                          malformed URI, an incompatible firmware) fails every scenario instead:
//                          the bench answered, and what it said needs a person.
//
// Scenarios use the SDK's public API only: a real bench has no simulator control channel.
#pragma once

#include <gtest/gtest.h>

#include <sys/types.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "palp/probe.hpp"

namespace palp::hil {

class Bench : public ::testing::Environment {
 public:
  /// The one instance (registered by the suites' main()).
  static Bench& get();

  void SetUp() override;
  void TearDown() override;

  /// The device URI scenarios connect to.
  const std::string& uri() const { return uri_; }
  /// True when the suites started palp-sim themselves.
  bool started_simulator() const { return child_ > 0; }
  /// Non-empty when every scenario is skipped: the configured bench did not answer.
  const std::string& skip_reason() const { return skip_; }
  /// Non-empty when every scenario fails: palp-sim did not start, or the bench is unusable.
  const std::string& failure() const { return failure_; }

 private:
  void start_simulator();
  void check_bench(const std::string& uri);

  std::string uri_, skip_, failure_;
  pid_t child_ = -1;
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

 private:
  std::unique_ptr<Probe> probe_;
  Params saved_{};
};

/// The samples streamed up to device time t_end_s (the first sample at or after it included),
/// waiting at most `patience` for each item; gap records go to *gaps.
std::vector<Sample> samples_until(Probe& probe, double t_end_s, std::vector<Gap>& gaps,
                                  std::chrono::milliseconds patience = std::chrono::seconds(5));

}  // namespace palp::hil
