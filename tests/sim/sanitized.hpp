// SPDX-License-Identifier: Apache-2.0
// Whether the test is built with AddressSanitizer: the longest simulations skip there (they run
// in the release build).
#pragma once

namespace palp::sim::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace palp::sim::test
