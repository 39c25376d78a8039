// SPDX-License-Identifier: Apache-2.0
// palpctl monitor: live values a few times a second until Ctrl-C or --seconds. Each line is the
// mean over the interval of the streamed samples, with the device's state and fault. With
// --plot, the same stream goes to a live view in the browser instead (live_server.hpp: the
// local HTTP server, live_page.hpp: the page, live_stream.hpp: the events it pushes).
#include <array>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <thread>
#include <variant>
#include <vector>

#include "common.hpp"
#include "live_page.hpp"
#include "live_server.hpp"
#include "live_stream.hpp"

namespace palpctl {

namespace {
struct MonitorOptions {
  double seconds = 0;
  double interval_s = 0.25;
  double rate_Hz = 1000;
  bool plot = false;
  int port = 0;  // checked 0..65535, then live.port
  LiveServerOptions live;
};

// Stops the stream it was given on every way out of a monitor (the end, Ctrl-C, an error).
class StreamRunning {
 public:
  explicit StreamRunning(palp::Probe& probe) : probe_(probe) { probe_.start_stream(); }
  ~StreamRunning() {
    try {
      probe_.stop_stream();
    } catch (const std::exception&) {  // the link is gone: there is no stream left to stop
    }
  }
  StreamRunning(const StreamRunning&) = delete;
  StreamRunning& operator=(const StreamRunning&) = delete;

 private:
  palp::Probe& probe_;
};

struct Means {
  std::size_t n = 0;
  std::uint64_t missing = 0;
  double i_cmd_A = 0, i_A = 0, z_mm = 0;
  std::array<double, 6> p_Pa{};
};

Means average(const std::vector<palp::StreamItem>& items) {
  Means m;
  for (const auto& item : items) {
    if (const auto* g = std::get_if<palp::Gap>(&item)) {
      m.missing += g->count;
      continue;
    }
    const auto& s = std::get<palp::Sample>(item);
    ++m.n;
    m.i_cmd_A += s.i_cmd_A;
    m.i_A += s.i_A;
    m.z_mm += mm_from_m(s.z_m);
    for (std::size_t k = 0; k < 6; ++k) m.p_Pa[k] += s.p_Pa[k];
  }
  if (m.n > 0) {
    const double n = static_cast<double>(m.n);
    m.i_cmd_A /= n;
    m.i_A /= n;
    m.z_mm /= n;
    for (auto& p : m.p_Pa) p /= n;
  }
  return m;
}

// --plot: the server listens (a refused --bind or a missing libjs-dygraphs ends palpctl before
// the device is touched), then the stream starts and the URL is printed.
int monitor_plot(const Context& ctx, const MonitorOptions& o) {
  LiveServerOptions live = o.live;
  live.port = static_cast<std::uint16_t>(o.port);
  LiveServer server(live, live_page_html(load_dygraphs()));
  auto probe = ctx.connect();
  catch_interrupts();  // Ctrl-C ends the loop; the stream is stopped on the way out
  probe.configure_stream({.rate_Hz = o.rate_Hz});
  const StreamRunning stream(probe);
  if (ctx.json)
    print_json(
        {{"url", server.url()}, {"port", server.port()}, {"events", server.url() + "events"}},
        true);
  else
    std::printf("live view: %s (Ctrl-C ends it)\n", server.url().c_str());
  std::fflush(stdout);
  const LiveStreamTotals t =
      run_live_stream(probe, server, {.seconds = o.seconds, .rate_Hz = o.rate_Hz});
  if (ctx.json)
    print_json({{"seconds", t.seconds},
                {"samples", t.samples},
                {"samples_missing", t.samples_lost},
                {"gaps", t.gaps},
                {"pushes", t.pushes},
                {"slow_clients_dropped", server.slow_clients_dropped()}},
               true);
  else
    std::printf("live view ended after %.1f s: %llu samples, %llu lost in %llu gaps\n", t.seconds,
                static_cast<unsigned long long>(t.samples),
                static_cast<unsigned long long>(t.samples_lost),
                static_cast<unsigned long long>(t.gaps));
  return kOk;  // Ctrl-C is how a monitor normally ends
}

int monitor(const Context& ctx, const MonitorOptions& o) {
  if (o.plot) return monitor_plot(ctx, o);
  auto probe = ctx.connect();
  catch_interrupts();  // Ctrl-C ends the loop; the stream is stopped on the way out
  probe.configure_stream({.rate_Hz = o.rate_Hz});
  const StreamRunning stream(probe);
  if (!ctx.json)
    std::printf("%10s %-9s %-14s %8s %8s %9s %8s %8s %8s %8s %8s %8s\n", "t_device_s", "state",
                "fault", "i_cmd_A", "i_A", "z_mm", "p1_Pa", "p2_Pa", "p3_Pa", "p4_Pa", "p5_Pa",
                "p6_Pa");
  const auto t0 = std::chrono::steady_clock::now();
  const auto interval = std::chrono::duration<double>(o.interval_s);
  auto next = t0;
  std::vector<palp::StreamItem> items;
  while (!interrupted()) {
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(interval);
    std::this_thread::sleep_until(next);
    items.clear();
    probe.drain(items);
    const Means m = average(items);
    const auto st = probe.status();
    if (ctx.json) {
      json j = {{"t_device_s", st.t_device_s}, {"state", name_of(st.state)},
                {"fault", name_of(st.fault)},  {"program", name_of(st.program)},
                {"samples", m.n},              {"samples_missing", m.missing}};
      if (m.n > 0) {
        j["i_cmd_A"] = m.i_cmd_A;
        j["i_A"] = m.i_A;
        j["z_mm"] = m.z_mm;
        j["p_Pa"] = m.p_Pa;
      } else {
        for (const char* k : {"i_cmd_A", "i_A", "z_mm", "p_Pa"}) {
          j[k] = nullptr;
          j[std::string(k) + "_reason"] = "no samples in this interval";
        }
      }
      print_json(j, true);
    } else {
      std::printf("%10.3f %-9s %-14s %8.4f %8.4f %9.4f %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f%s\n",
                  st.t_device_s, name_of(st.state).c_str(), name_of(st.fault).c_str(),
                  m.i_cmd_A, m.i_A, m.z_mm, m.p_Pa[0], m.p_Pa[1], m.p_Pa[2], m.p_Pa[3],
                  m.p_Pa[4], m.p_Pa[5], m.missing > 0 ? "  (samples lost)" : "");
      std::fflush(stdout);
    }
    if (o.seconds > 0 &&
        std::chrono::steady_clock::now() - t0 >= std::chrono::duration<double>(o.seconds))
      break;
  }
  return kOk;  // Ctrl-C is how a monitor normally ends
}
}  // namespace

void add_monitor_command(CLI::App& app, Context& ctx) {
  auto o = std::make_shared<MonitorOptions>();
  auto* cmd = app.add_subcommand(
      "monitor", "Print live values (means over each interval: i_cmd_A, i_A, z_mm, p1..p6_Pa, "
                 "state, fault) until Ctrl-C or --seconds; --json prints one object per line.\n"
                 "--plot: a live view in the browser instead (plots of i_cmd, i, z, p1..p6 at " +
                 fmt(kPushHz) +
                 " pushes/s, pause, last N s, gap and fault markers); palpctl prints the URL "
                 "to open (with --json as {\"url\": ...}). It serves 127.0.0.1 only, unless "
                 "--bind and --allow-remote say otherwise. Needs Debian's libjs-dygraphs.");
  cmd->add_option("--seconds", o->seconds, "Stop after this long, s (0: until Ctrl-C)")
      ->check(kNonNegative)
      ->capture_default_str();
  auto* interval = cmd->add_option("--interval-s", o->interval_s, "Time between lines, s")
      ->check(CLI::Range(0.05, 60.0))
      ->capture_default_str();
  cmd->add_option("--rate-Hz", o->rate_Hz,
                  "Stream sample rate the means are taken over, Hz (divides the control rate)")
      ->check(kPositive)
      ->capture_default_str();
  auto* plot = cmd->add_flag("--plot", o->plot,
                             "Serve a live view in the browser (GET / the page, GET /events the "
                             "server-sent events) instead of printing lines")
                   ->excludes(interval);  // the page is refreshed at its own rate
  cmd->add_option("--port", o->port, "The live view's TCP port (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str()
      ->needs(plot);
  cmd->add_option("--bind", o->live.bind_address,
                  "The live view's IPv4 address; one outside 127.0.0.0/8 needs --allow-remote")
      ->capture_default_str()
      ->needs(plot);
  cmd->add_flag("--allow-remote", o->live.allow_remote,
                "Allow a --bind address other than loopback (the page has no authentication)")
      ->needs(plot);
  cmd->callback([&ctx, o] { ctx.action = [&ctx, o] { return monitor(ctx, *o); }; });
}

}  // namespace palpctl
