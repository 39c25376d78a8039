// The suites' environment (bench.hpp): a palp-sim child process by default, or the bench that
// PALP_BENCH_URI names, checked once; the Scenario fixture; main().
#include "bench.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <thread>

namespace palp::hil {

Bench& Bench::get() {
  static Bench* bench = new Bench;  // owned by GoogleTest once registered
  return *bench;
}

void Bench::SetUp() {
  const char* env = std::getenv("PALP_BENCH_URI");
  if (env != nullptr && *env != '\0') {
    check_bench(env);
  } else {
    start_simulator();
  }
  if (const char* robot = std::getenv("PALP_ROBOT_URI"); robot != nullptr && *robot != '\0')
    std::cout << "[  BENCH   ] PALP_ROBOT_URI=" << robot << " is set; no suite uses a robot yet\n";
  if (!failure_.empty()) std::cout << "[  BENCH   ] unusable: " << failure_ << "\n";
  else if (!skip_.empty()) std::cout << "[  BENCH   ] every scenario is skipped: " << skip_ << "\n";
}

void Bench::TearDown() {
  if (child_ > 0) {
    ::kill(child_, SIGTERM);
    ::waitpid(child_, nullptr, 0);
    child_ = -1;
  }
}

// palp-sim on ephemeral loopback ports; its first line names them:
// "palp-sim listening on tcp://127.0.0.1:P (device protocol), control on tcp://127.0.0.1:C".
void Bench::start_simulator() {
  int out[2];
  if (::pipe(out) != 0) {
    failure_ = std::string("cannot start palp-sim: pipe: ") + std::strerror(errno);
    return;
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive a crashed suite
    ::dup2(out[1], STDOUT_FILENO);
    ::close(out[0]);
    ::close(out[1]);
    const char* argv[] = {PALP_SIM_BINARY, "--port", "0", "--control-port", "0",
                          "--pace", "fast", nullptr};
    ::execv(argv[0], const_cast<char* const*>(argv));
    std::_Exit(127);
  }
  ::close(out[1]);
  if (pid < 0) {
    ::close(out[0]);
    failure_ = std::string("cannot start palp-sim: fork: ") + std::strerror(errno);
    return;
  }
  child_ = pid;
  std::string line;
  pollfd p{out[0], POLLIN, 0};
  while (line.find('\n') == std::string::npos && ::poll(&p, 1, 5000) == 1) {
    char buf[256];
    const ssize_t n = ::read(out[0], buf, sizeof buf);
    if (n <= 0) break;
    line.append(buf, static_cast<std::size_t>(n));
  }
  ::close(out[0]);  // palp-sim ignores SIGPIPE: its last words are lost, nothing else
  const std::string key = "listening on tcp://";
  const std::size_t at = line.find(key);
  const std::size_t end = at == std::string::npos ? at : line.find(' ', at + key.size());
  if (end == std::string::npos) {
    failure_ = std::string("palp-sim (" PALP_SIM_BINARY ") did not start: ") +
               (line.empty() ? "no banner within 5 s" : line);
    TearDown();
    return;
  }
  uri_ = "sim://" + line.substr(at + key.size(), end - at - key.size());
  std::cout << "[  BENCH   ] palp-sim started by the suites at " << uri_ << " (--pace fast)\n";
}

void Bench::check_bench(const std::string& uri) {
  uri_ = uri;
  const std::string who = "PALP_BENCH_URI=" + uri;
  try {
    ConnectOptions o;
    o.reconnect = false;
    Probe probe(uri, o);
    const DeviceInfo& d = probe.info();
    std::cout << "[  BENCH   ] " << who << ": " << d.board << " " << d.serial << ", firmware "
              << d.firmware_version << ", protocol " << d.protocol_major << "."
              << d.protocol_minor << (d.has(proto::Capability::simulated) ? " (simulated)" : "")
              << "\n";
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
  // palp-sim serves one client and may not have seen the previous scenario's close yet (it then
  // refuses the newcomer); a USB device can take a moment to reopen. Retry briefly.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (!probe_) {
    try {
      probe_ = std::make_unique<Probe>(bench.uri());
    } catch (const ConnectionError&) {
      if (std::chrono::steady_clock::now() > give_up) throw;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  saved_ = probe_->params();
  const FaultInfo f = probe_->fault();
  if (f.reason != proto::FaultReason::none) {
    std::cout << "[  BENCH   ] cleared a fault latched before this scenario: " << f.text << "\n";
    probe_->clear_fault();
  }
}

void Scenario::TearDown() {
  if (!probe_) return;
  // leave the device as found: nothing running, the parameters back, no fault latched
  try {
    if (probe_->program_status().state == proto::ProgramState::running) probe_->stop();
    if (probe_->status().streaming) probe_->stop_stream();
    probe_->set_params(saved_);
    if (probe_->fault().reason != proto::FaultReason::none) probe_->clear_fault();
  } catch (const Error& e) {
    ADD_FAILURE() << "could not restore the device after the scenario: " << e.what();
  }
  probe_->close();
  probe_.reset();
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

}  // namespace palp::hil

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(&palp::hil::Bench::get());
  return RUN_ALL_TESTS();
}
