// SPDX-License-Identifier: Apache-2.0
// The suites' environment (bench.hpp): palp-sim or an image under QEMU as child processes, or
// the bench that PALP_BENCH_URI names, checked once; the Scenario fixture; main().
#include "bench.hpp"

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <thread>

namespace palp::hil {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

/// palp-sim placed like the QEMU image's plant (firmware/board/qemu/plant/README.md): the
/// phantom, and the mount that puts the floating tip (0.5 A) just on its surface.
// clang-format off
const std::vector<std::string> kPlantScene = {"--phantom", "solid_1d",
                                              "--mount-mm", "27", "0", "-25"};
// clang-format on

/// QEMU running the image with its UART0 on a loopback TCP server (firmware/README.md).
std::vector<std::string> qemu_command(const std::string& image, std::uint16_t port) {
  // clang-format off
  return {"qemu-system-arm", "-M", "mps2-an386", "-display", "none", "-monitor", "none",
          "-semihosting-config", "enable=on,target=native",
          "-serial", "tcp:127.0.0.1:" + std::to_string(port) + ",server=on,wait=off",
          "-kernel", image};
  // clang-format on
}

const char* env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? v : nullptr;
}

/// Starts palp-sim (fast pace, free ports, the plant's scene) and reads the device URI from its
/// first line: "palp-sim listening on tcp://127.0.0.1:P (device protocol), control on ...".
/// Returns the URI, or empty with *error set.
std::string start_palp_sim(std::unique_ptr<Child>& child, std::string& error) {
  std::vector<std::string> argv = {PALP_SIM_BINARY, "--port", "0", "--control-port", "0"};
  argv.insert(argv.end(), {"--pace", "fast"});
  argv.insert(argv.end(), kPlantScene.begin(), kPlantScene.end());
  child = std::make_unique<Child>(argv);
  if (!child->running()) {
    error = child->error();
    return {};
  }
  std::string line;
  child->read_line(line, 5s);
  const std::string key = "listening on tcp://";
  const std::size_t at = line.find(key);
  const std::size_t end = at == std::string::npos ? at : line.find(' ', at + key.size());
  if (end == std::string::npos) {
    error = "palp-sim (" + child->command() +
            ") did not start: " + (line.empty() ? "no banner within 5 s" : line) + " " +
            child->stderr_text();
    child.reset();
    return {};
  }
  return "sim://" + line.substr(at + key.size(), end - at - key.size());
}

std::string describe(const DeviceInfo& d) {
  return d.board + " " + d.serial + ", firmware " + d.firmware_version + ", protocol " +
         std::to_string(d.protocol_major) + "." + std::to_string(d.protocol_minor) +
         ", max stream rate " + std::to_string(static_cast<long>(d.max_stream_rate_Hz)) + " Hz" +
         (d.has(proto::Capability::simulated) ? " (simulated)" : "");
}

}  // namespace

Bench& Bench::get() {
  static Bench* bench = new Bench;  // owned by GoogleTest once registered
  return *bench;
}

void Bench::SetUp() {
  if (const char* uri = env("PALP_BENCH_URI")) {
    check_bench(uri);
    specimen_ = env("PALP_BENCH_SPECIMEN") != nullptr;
  } else if (const char* image = env("PALP_QEMU_IMAGE")) {
    start_qemu(image);
    specimen_ = true;
  } else {
    start_simulator();
    specimen_ = true;
  }
  if (const char* ref = env("PALP_REFERENCE_URI")) {
    reference_.reset();
    reference_uri_ = ref;
  }
  if (!reference_uri_.empty())
    std::cout << "[  BENCH   ] reference for the indentation: " << reference_uri_ << "\n";
  if (const char* robot = env("PALP_ROBOT_URI"))
    std::cout << "[  BENCH   ] PALP_ROBOT_URI=" << robot << " is set; no suite uses a robot yet\n";
  if (!failure_.empty())
    std::cout << "[  BENCH   ] unusable: " << failure_ << "\n";
  else if (!skip_.empty())
    std::cout << "[  BENCH   ] every scenario is skipped: " << skip_ << "\n";
}

void Bench::TearDown() {
  device_.reset();  // stops the child
  reference_.reset();
}

void Bench::start_simulator() {
  uri_ = start_palp_sim(device_, failure_);
  if (!uri_.empty())
    std::cout << "[  BENCH   ] palp-sim started by the suites at " << uri_ << " (--pace fast)\n";
}

// QEMU on a port that was free a moment ago (another process may take it first: then QEMU
// exits saying so, and the next port is tried), then the SDK's handshake, retried until
// kQemuAnswer: the image boots in well under a second. Everything that goes wrong fails.
void Bench::start_qemu(const std::string& image) {
  if (!std::filesystem::exists(image)) {
    failure_ = "PALP_QEMU_IMAGE=" + image +
               " does not exist: build it with `cmake --preset "
               "fw-qemu && cmake --build --preset fw-qemu`";
    return;
  }
  const auto give_up = Clock::now() + kQemuAnswer;
  std::string last;
  bool answered = false;
  for (int attempt = 0; attempt < 5 && !answered && failure_.empty() && Clock::now() < give_up;
       ++attempt) {
    const std::uint16_t port = free_loopback_port();
    device_ = std::make_unique<Child>(qemu_command(image, port));
    if (!device_->running()) {
      failure_ = device_->error();
      break;
    }
    uri_ = "tcp://127.0.0.1:" + std::to_string(port);
    while (Clock::now() < give_up) {
      if (device_->exited()) {
        const std::string err = device_->stderr_text();
        if (err.find("Address already in use") != std::string::npos) break;  // the next port
        failure_ = WIFEXITED(device_->exit_status()) && WEXITSTATUS(device_->exit_status()) == 127
                       ? "qemu-system-arm not found: run scripts/install-deps (or apt-get install "
                         "--no-install-recommends qemu-system-arm)"
                       : "QEMU exited (status " + std::to_string(device_->exit_status()) +
                             ") before the image answered (" + device_->command() + "): " + err;
        break;
      }
      try {
        ConnectOptions o;
        o.reconnect = false;
        o.timeout = 1000ms;
        Probe probe(uri_, o);
        std::cout << "[  BENCH   ] QEMU started by the suites at " << uri_ << ": "
                  << describe(probe.info()) << "\n[  BENCH   ] " << device_->command() << "\n";
        answered = true;
        break;
      } catch (const ConnectionError& e) {  // QEMU is not listening yet
        last = e.what();
        std::this_thread::sleep_for(20ms);
      } catch (const TimeoutError& e) {  // listening, the image not answering (yet)
        last = e.what();
      } catch (const Error& e) {
        failure_ = "the image under QEMU answered but cannot be used (" + device_->command() +
                   "): " + e.what();
      }
      if (!failure_.empty()) break;
    }
  }
  if (!answered && failure_.empty())
    failure_ = "the image under QEMU did not answer the handshake within " +
               std::to_string(kQemuAnswer.count()) + " s (" +
               (device_ ? device_->command() : std::string("QEMU")) + "): " + last;
  if (!failure_.empty()) {
    device_.reset();
    return;
  }
  std::string error;
  reference_uri_ = start_palp_sim(reference_, error);
  if (reference_uri_.empty()) failure_ = "the reference palp-sim did not start: " + error;
}

void Bench::check_bench(const std::string& uri) {
  uri_ = uri;
  const std::string who = "PALP_BENCH_URI=" + uri;
  try {
    ConnectOptions o;
    o.reconnect = false;
    Probe probe(uri, o);
    std::cout << "[  BENCH   ] " << who << ": " << describe(probe.info()) << "\n";
  } catch (const ConnectionError& e) {
    skip_ = who + " does not answer: " + e.what();
  } catch (const TimeoutError& e) {
    skip_ = who + " does not answer: " + e.what();
  } catch (const ConfigError& e) {
    failure_ = who + " is not a usable URI: " + e.what();
  } catch (const Error& e) {
    failure_ = who + " answered but cannot be used: " + e.what();
  }
}

void Scenario::SetUp() {
  const Bench& bench = Bench::get();
  if (!bench.failure().empty()) FAIL() << bench.failure();
  if (!bench.skip_reason().empty()) GTEST_SKIP() << bench.skip_reason();
  connect();
  saved_ = probe_->params();
  overruns_at_start_ = probe_->health().control_overruns;
  const FaultInfo f = probe_->fault();
  if (f.reason != proto::FaultReason::none) {
    std::cout << "[  BENCH   ] cleared a fault latched before this scenario: " << f.text << "\n";
    probe_->clear_fault();
  }
}

void Scenario::connect() {
  // palp-sim serves one client and may not have seen the previous connection's close yet (it
  // then refuses the newcomer); a USB device can take a moment to reopen. Retry briefly.
  const auto give_up = Clock::now() + 2s;
  while (!probe_) {
    try {
      probe_ = std::make_unique<Probe>(Bench::get().uri());
    } catch (const ConnectionError&) {
      if (Clock::now() > give_up) throw;
      std::this_thread::sleep_for(20ms);
    }
  }
}

void Scenario::disconnect() {
  if (!probe_) return;
  probe_->close();
  probe_.reset();
}

void Scenario::TearDown() {
  if (!probe_) {
    // a scenario that ended while disconnected: connect again to put the device back
    if (!Bench::get().failure().empty() || !Bench::get().skip_reason().empty()) return;
    try {
      connect();
    } catch (const Error& e) {
      ADD_FAILURE() << "could not reconnect to restore the device after the scenario: " << e.what();
      return;
    }
  }
  // leave the device as found: nothing running, the parameters back, no fault latched
  try {
    // a failure while the device dropped control ticks (it could not keep its tick: under QEMU,
    // the host did not run it) says so: the likely cause is the machine, not the firmware
    const std::uint32_t dropped = probe_->health().control_overruns - overruns_at_start_;
    if (HasFailure() && dropped > 0)
      std::cout << "[  BENCH   ] the device dropped " << dropped
                << " control ticks during this scenario (it could not keep its tick; under QEMU: "
                   "the host did not run QEMU in time, a loaded machine)\n";
    if (probe_->program_status().state == proto::ProgramState::running) probe_->stop();
    if (probe_->status().streaming) probe_->stop_stream();
    probe_->set_params(saved_);
    if (probe_->fault().reason != proto::FaultReason::none) probe_->clear_fault();
  } catch (const Error& e) {
    ADD_FAILURE() << "could not restore the device after the scenario: " << e.what();
  }
  disconnect();
}

std::vector<Sample> samples_until(Probe& probe, double t_end_s, std::vector<Gap>& gaps,
                                  std::chrono::milliseconds patience) {
  std::vector<Sample> out;
  while (auto item = probe.next(patience)) {
    if (const Sample* s = std::get_if<Sample>(&*item)) {
      out.push_back(*s);
      if (s->t_device_s >= t_end_s) break;
    } else {
      gaps.push_back(std::get<Gap>(*item));
    }
  }
  return out;
}

std::string gaps_text(const std::vector<Gap>& gaps) {
  if (gaps.empty()) return "";
  std::uint64_t missing = 0;
  for (const Gap& g : gaps) missing += g.count;
  return std::to_string(gaps.size()) + " gaps, " + std::to_string(missing) +
         " samples; the first: " + std::to_string(gaps[0].count) + " samples at index " +
         std::to_string(gaps[0].first_index) + " (" + gap_source_name(gaps[0].source) + ")";
}

double stream_rate_at_most(const DeviceInfo& d, double wanted_Hz) {
  const double top = std::min(wanted_Hz, d.max_stream_rate_Hz);
  if (top <= 0 || d.control_rate_Hz <= 0) return 0;
  const auto control = static_cast<long>(d.control_rate_Hz);
  for (long decimation = static_cast<long>(std::ceil(d.control_rate_Hz / top));
       decimation <= control; ++decimation)
    if (control % decimation == 0) return static_cast<double>(control / decimation);
  return 0;
}

}  // namespace palp::hil

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], palp::hil::kHostLossChildFlag) == 0)
    return palp::hil::host_loss_child(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(&palp::hil::Bench::get());
  return RUN_ALL_TESTS();
}
