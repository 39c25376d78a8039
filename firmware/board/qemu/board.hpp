// SPDX-License-Identifier: Apache-2.0
// The QEMU mps2-an386 board as test images see it: a text console (CMSDK UART0), an exit code
// for the host (semihosting) and the stack's high-water mark. Startup (startup.cpp) has already
// enabled the FPU, initialised memory, painted the stack and enabled the UART when main() runs.
#pragma once

#include <cstddef>

namespace palp::board {

/// Enables UART0's transmitter (startup.cpp calls it before main()).
void console_init();
/// Writes bytes to UART0, waiting while its one-byte transmit buffer is full.
void console_write(const char* data, std::size_t size);

/// Ends the QEMU run with this exit code (semihosting SYS_EXIT_EXTENDED). Needs QEMU started
/// with `-semihosting-config enable=on,target=native`; without it, the BKPT faults.
[[noreturn]] void exit(int code);

/// Fills the unused stack with a pattern (startup.cpp, before main()).
void stack_paint();
/// Bytes of the stack reserved by the linker script.
std::size_t stack_size();
/// Deepest stack use since stack_paint(), in bytes (the high-water mark).
std::size_t stack_used();

}  // namespace palp::board
