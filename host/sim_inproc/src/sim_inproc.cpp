// SPDX-License-Identifier: Apache-2.0
// The in-process simulator (palp/sim_inproc.hpp): an Instrument behind a Transport whose read()
// runs virtual time.
#include "palp/sim_inproc.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <vector>

#include "palp/error.hpp"
#include "palp/plant/phantom.hpp"
#include "palp/sim/instrument.hpp"

namespace palp::sim {

struct InprocSimulator::Core final : Serving {
  using Clock = std::chrono::steady_clock;

  explicit Core(const InprocOptions& o) : instrument(instrument_options(o)) {
    if (o.robot) {
      try {
        robot = std::make_unique<ModbusServer>("127.0.0.1", 0);
      } catch (const std::exception& e) {
        throw ConnectionError(std::string("the in-process simulator's robot bridge: ") + e.what());
      }
    }
  }

  static InstrumentOptions instrument_options(const InprocOptions& o) {
    InstrumentOptions i;
    i.phantom = o.phantom;
    i.mount_mm = o.mount_mm;
    i.seed = o.seed;
    i.hold_timeout_ms = o.hold_timeout_ms;
    i.reaction_latency_ms = o.reaction_latency_ms;
    i.serial = o.serial;
    i.board = o.board;
    i.git_hash = "inproc";
    i.robot = o.robot;
    i.world.bridge.seed = o.seed;
    i.world.input_latency_ms = o.robot_input_latency_ms;
    return i;
  }

  /// The watchdogs' clock: wall time since the simulator was made (hil/README.md).
  std::uint64_t wall_us() const {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count());
  }

  // Serving
  std::string set_pace(double) override {
    return "the in-process simulator runs as fast as its reader reads; pacing against wall "
           "time is palp-sim's (sim://)";
  }
  double pace() const override { return 0; }
  bool device_client() const override { return link_open; }
  ModbusServer* robot_server() override { return robot.get(); }

  /// Hands queued host bytes to the core and serves the robot's socket (every 0.2 ms of wall
  /// time at most, as palp-sim). Called with mu held.
  void serve_host() {
    Simulation& sim = instrument.simulation();
    const std::uint64_t now = wall_us();
    if (!inbox.empty()) {
      sim.host_bytes(inbox.data(), inbox.size(), now);
      inbox.clear();
    }
    if (robot) {
      instrument.world()->set_wall_us(now);
      if (now - last_robot_poll_us >= 200) {
        robot->poll(*instrument.world(), now);
        last_robot_poll_us = now;
      }
    }
  }

  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mu);
    Simulation& sim = instrument.simulation();
    const std::uint32_t rate = sim.controller().control_rate_Hz();
    const std::uint64_t budget = static_cast<std::uint64_t>(timeout.count()) * rate / 1000;
    const auto wall_deadline = Clock::now() + timeout;
    std::uint64_t ran = 0;
    // as a palp-sim step: the host's bytes go in, up to 1 ms of virtual time runs, the device's
    // bytes come out (so a reply comes back a chunk of virtual time after its request, as over
    // the socket, and never in the same tick as the request after it)
    while (pending.empty()) {
      serve_host();
      std::uint32_t n = 0;
      if (ran < budget) {
        n = sim.run(static_cast<std::uint32_t>(std::min<std::uint64_t>(rate / 1000, budget - ran)),
                    wall_us());
        ran += n;
      }
      const std::vector<std::uint8_t> out = sim.take_device_bytes();
      pending.insert(pending.end(), out.begin(), out.end());
      if (!pending.empty() || ran >= budget) break;
      if (n == 0 && sim.holding()) {
        // a contact event holds virtual time until the host reacts: wait for it in wall time
        if (Clock::now() >= wall_deadline) break;
        host_cv.wait_for(lock, std::chrono::microseconds(200));
      }
    }
    const std::size_t n = std::min(buf.size(), pending.size());
    std::copy_n(pending.begin(), n, buf.begin());  // (memcpy from an empty vector's null data is UB)
    pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }

  void write(std::span<const std::uint8_t> bytes) {
    std::lock_guard lock(mu);
    inbox.insert(inbox.end(), bytes.begin(), bytes.end());
    host_cv.notify_all();
  }

  std::mutex mu;  // guards everything below
  std::condition_variable host_cv;  // host bytes came
  Instrument instrument;
  std::unique_ptr<ModbusServer> robot;
  Clock::time_point t0 = Clock::now();
  std::uint64_t last_robot_poll_us = 0;
  std::vector<std::uint8_t> inbox;    // host bytes not yet handed to the core
  std::vector<std::uint8_t> pending;  // device bytes not yet read (they stall virtual time)
  bool link_open = false;
};

namespace {

class InprocTransport final : public Transport {
 public:
  InprocTransport(std::shared_ptr<InprocSimulator::Core> core, std::string uri)
      : core_(std::move(core)), uri_(std::move(uri)) {}
  ~InprocTransport() override {
    std::lock_guard lock(core_->mu);
    core_->link_open = false;
    core_->pending.clear();  // as palp-sim drops what a closed socket did not take
  }
  void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds) override {
    core_->write(bytes);
  }
  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) override {
    return core_->read(buf, timeout);
  }
  // as sim:// (the simulation stalls rather than drops)
  std::uint32_t max_device_bytes_per_s() const override { return 100'000'000u; }
  const std::string& uri() const override { return uri_; }

 private:
  std::shared_ptr<InprocSimulator::Core> core_;
  std::string uri_;
};

std::unique_ptr<Transport> open_link(const std::shared_ptr<InprocSimulator::Core>& core,
                                     std::string uri) {
  std::lock_guard lock(core->mu);
  if (core->link_open)
    throw ConnectionError("the in-process simulator " + uri +
                          " already has a device transport open (it serves one, as palp-sim)");
  core->link_open = true;
  return std::make_unique<InprocTransport>(core, std::move(uri));
}

std::string uri_of(const InprocOptions& o) { return "sim+inproc://" + o.phantom; }

double number(const Uri& uri, const std::string& key, const std::string& value) {
  double v = 0;
  const auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (ec != std::errc{} || p != value.data() + value.size() || value.empty())
    throw ConfigError("transport URI '" + uri.text + "': " + key + " '" + value +
                      "' is not a number");
  return v;
}

std::shared_ptr<InprocSimulator::Core> make_core(const InprocOptions& options) {
  try {
    return std::make_shared<InprocSimulator::Core>(options);
  } catch (const plant::PhantomError& e) {
    throw ConfigError("the in-process simulator: " + std::string(e.what()));
  }
}

std::unique_ptr<Transport> open_uri(const Uri& uri, std::chrono::milliseconds) {
  return open_link(make_core(InprocOptions::from_uri(uri)), uri.text);
}

}  // namespace

InprocOptions InprocOptions::from_uri(const Uri& uri) {
  if (uri.scheme != Uri::Scheme::sim_inproc)
    throw ConfigError("transport URI '" + uri.text + "' is not a sim+inproc:// URI");
  InprocOptions o;
  o.phantom = uri.phantom;
  for (const auto& [key, value] : uri.parameters) {
    if (key == "seed") {
      const double s = number(uri, key, value);
      if (s < 0 || s != static_cast<double>(static_cast<std::uint64_t>(s)))
        throw ConfigError("transport URI '" + uri.text + "': seed '" + value +
                          "' is not a whole number >= 0");
      o.seed = static_cast<std::uint64_t>(s);
    } else if (key == "mount_mm") {
      std::size_t at = 0;
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t comma = value.find(',', at);
        if ((k < 2) == (comma == std::string::npos))
          throw ConfigError("transport URI '" + uri.text + "': mount_mm '" + value +
                            "' is not x,y,z in mm");
        o.mount_mm[k] = number(uri, key, value.substr(at, comma - at));
        at = comma + 1;
      }
    } else if (key == "hold_timeout_ms" || key == "reaction_latency_ms") {
      const double v = number(uri, key, value);
      if (v < 0)
        throw ConfigError("transport URI '" + uri.text + "': " + key + " must be >= 0");
      (key == "hold_timeout_ms" ? o.hold_timeout_ms : o.reaction_latency_ms) = v;
    } else if (key == "serial") {
      o.serial = value;
    } else if (key == "board") {
      o.board = value;
    } else {
      throw ConfigError("transport URI '" + uri.text + "': unknown parameter '" + key +
                        "' (known: seed, mount_mm, hold_timeout_ms, reaction_latency_ms, serial, board)");
    }
  }
  return o;
}

InprocSimulator::InprocSimulator(InprocOptions options)
    : core_(make_core(options)), uri_(uri_of(options)) {}

InprocSimulator::~InprocSimulator() = default;

std::unique_ptr<Transport> InprocSimulator::transport() { return open_link(core_, uri_); }

std::string InprocSimulator::control(const std::string& line) {
  std::lock_guard lock(core_->mu);
  return core_->instrument.control(line, *core_);
}

std::string InprocSimulator::robot_uri() const {
  if (!core_->robot) return "";
  return "modbus://127.0.0.1:" + std::to_string(core_->robot->port());
}

double InprocSimulator::virtual_s() const {
  std::lock_guard lock(core_->mu);
  return core_->instrument.simulation().virtual_s();
}

// sim+inproc:// URIs open here wherever this library is linked
namespace {
[[maybe_unused]] const bool g_registered = (set_sim_inproc_factory(&open_uri), true);
}  // namespace

}  // namespace palp::sim
