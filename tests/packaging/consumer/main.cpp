// SPDX-License-Identifier: Apache-2.0
// Built against an installed palp: the public headers (the protocol's included through probe.hpp)
// and palp::sdk with its link dependencies must all come from the installed package.
#include <cstdio>

#include "palp/probe.hpp"
#include "palp/transport.hpp"

int main() {
  const palp::Uri uri = palp::parse_uri("sim://127.0.0.1:7070");
  std::printf("sdk %s\n", palp::sdk_version());
  std::printf("uri host=%s port=%u sim_tcp=%d\n", uri.host.c_str(), unsigned{uri.port},
              uri.scheme == palp::Uri::Scheme::sim_tcp ? 1 : 0);
  std::printf("protocol %u.%u\n", unsigned{palp::proto::kProtocolMajor},
              unsigned{palp::proto::kProtocolMinor});
  return 0;
}
