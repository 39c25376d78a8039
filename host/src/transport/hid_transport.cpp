// Placeholder until the hid transport lands: refuses with a clear error.
#include "palp/error.hpp"
#include "transport/factories.hpp"

namespace palp::detail {
std::unique_ptr<Transport> open_hid_transport(const Uri& uri, std::chrono::milliseconds) {
  throw ConnectionError("transport URI '" + uri.text + "': the hid transport is not built yet");
}
}  // namespace palp::detail
