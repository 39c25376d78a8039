#include "palp/error.hpp"
#include "palp/transport.hpp"
#include "transport/factories.hpp"

namespace palp {

std::unique_ptr<Transport> open_transport(const Uri& uri, std::chrono::milliseconds timeout) {
  switch (uri.scheme) {
    case Uri::Scheme::usb: return detail::open_usb_transport(uri, timeout);
    case Uri::Scheme::hid: return detail::open_hid_transport(uri, timeout);
    case Uri::Scheme::sim_tcp:
    case Uri::Scheme::sim_unix: return detail::open_sim_transport(uri, timeout);
  }
  throw ConfigError("transport URI '" + uri.text + "': unknown scheme");
}

std::unique_ptr<Transport> open_transport(const std::string& uri,
                                          std::chrono::milliseconds timeout) {
  return open_transport(parse_uri(uri), timeout);
}

}  // namespace palp
