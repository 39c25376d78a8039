// SPDX-License-Identifier: Apache-2.0
#include "palp/error.hpp"
#include "palp/transport.hpp"
#include "transport/factories.hpp"

#include <atomic>

namespace palp {
namespace {
std::atomic<TransportFactory> g_sim_inproc{nullptr};
}  // namespace

void set_sim_inproc_factory(TransportFactory factory) { g_sim_inproc = factory; }

std::unique_ptr<Transport> open_transport(const Uri& uri, std::chrono::milliseconds timeout) {
  switch (uri.scheme) {
    case Uri::Scheme::usb: return detail::open_usb_transport(uri, timeout);
    case Uri::Scheme::hid: return detail::open_hid_transport(uri, timeout);
    case Uri::Scheme::tcp:
    case Uri::Scheme::sim_tcp:
    case Uri::Scheme::sim_unix: return detail::open_socket_transport(uri, timeout);
    case Uri::Scheme::serial: return detail::open_serial_transport(uri, timeout);
    case Uri::Scheme::sim_inproc:
      if (const TransportFactory f = g_sim_inproc.load()) return f(uri, timeout);
      throw ConfigError("transport URI '" + uri.text +
                        "': the in-process simulator is not linked into this program: link the "
                        "palp_sim_inproc library (built with palp-sim), or start palp-sim and "
                        "use sim://host:port");
  }
  throw ConfigError("transport URI '" + uri.text + "': unknown scheme");
}

std::unique_ptr<Transport> open_transport(const std::string& uri,
                                          std::chrono::milliseconds timeout) {
  return open_transport(parse_uri(uri), timeout);
}

}  // namespace palp
