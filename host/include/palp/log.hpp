// SPDX-License-Identifier: Apache-2.0
// The SDK's log: what it recovers from on its own, reported instead of kept silent.
//
// The SDK keeps a session going through link trouble: a request whose reply was lost goes out
// again, a lost link is reopened and the stream restarted, missing samples become a Gap in the
// stream, a robot bridge that stopped answering is reconnected. Each of these reaches the
// program's log handler as one line of text; without a handler nothing is reported (and nothing
// changes: the same counters stay in Probe::health() and the stream's Gap items).
//
//   palp::set_log_handler([](palp::LogLevel level, const std::string& message) {
//     std::cerr << palp::log_level_name(level) << ": " << message << '\n';
//   });
//
// What is reported, with its level:
//   info     connected to a probe (URI, serial, firmware); the probe link restored; a robot
//            bridge reconnected
//   warning  the probe link lost (reconnecting); a request resent after its reply was lost; a
//            gap in the stream (how many samples, from which index, why: transport, device,
//            host queue, reconnect); the robot link lost (reconnecting)
//   error    the probe link could not be restored (the session is over; the next call throws)
#pragma once

#include <functional>
#include <string>

namespace palp {

enum class LogLevel { info, warning, error };

/// "info", "warning", "error".
const char* log_level_name(LogLevel level);

/// Receives the SDK's log lines. Called from the SDK's I/O threads (a probe's reader, the
/// caller's own thread for a robot), possibly from several at once: it must be thread-safe,
/// quick, and must not call back into the Probe or Robot that reports.
using LogHandler = std::function<void(LogLevel level, const std::string& message)>;

/// Installs the process-wide handler (replacing any before it); an empty handler turns the log
/// off, which is the default.
void set_log_handler(LogHandler handler);

}  // namespace palp
