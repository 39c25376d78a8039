// SPDX-License-Identifier: Apache-2.0
// The names of DFU states, status codes and progress phases (usb-dfu-facts.md §5.3), and what
// each status means in a message (dfu_messages.hpp).
#include <cstdio>

#include "dfu/dfu_messages.hpp"
#include "palp/dfu.hpp"

namespace palp::dfu {

const char* phase_name(Progress::Phase phase) {
  switch (phase) {
    case Progress::Phase::erase: return "erase";
    case Progress::Phase::download: return "download";
    case Progress::Phase::verify: return "verify";
    case Progress::Phase::manifest: return "manifest";
  }
  return "?";
}

std::string state_name(std::uint8_t state) {
  static const char* const names[] = {
      "appIDLE",          "appDETACH",      "dfuIDLE",
      "dfuDNLOAD-SYNC",   "dfuDNBUSY",      "dfuDNLOAD-IDLE",
      "dfuMANIFEST-SYNC", "dfuMANIFEST",    "dfuMANIFEST-WAIT-RESET",
      "dfuUPLOAD-IDLE",   "dfuERROR"};
  if (state < sizeof names / sizeof names[0]) return names[state];
  return "state " + std::to_string(state);
}

namespace {
struct StatusText {
  const char* name;
  const char* meaning;
};
// Names: facts §5.3. Meanings: DFU 1.1's descriptions, DfuSe's where AN2662 gives one (§5.5).
constexpr StatusText kStatus[] = {
    {"OK", "no error"},
    {"errTARGET", "the address is not one the device supports"},
    {"errFILE", "the device rejected the data"},
    {"errWRITE", "the flash could not be written"},
    {"errERASE", "the flash could not be erased"},
    {"errCHECK_ERASED", "the memory was not erased before programming"},
    {"errPROG", "the program-memory function failed"},
    {"errVERIFY", "the programmed memory failed verification"},
    {"errADDRESS", "the address is out of range"},
    {"errNOTDONE", "the download ended before it was complete"},
    {"errFIRMWARE", "the device's firmware is corrupt"},
    {"errVENDOR", "vendor error; on an STM32: read protection is active"},
    {"errUSBR", "unexpected USB reset"},
    {"errPOR", "unexpected power-on reset"},
    {"errUNKNOWN", "unknown error"},
    {"errSTALLEDPKT", "the device stalled an unexpected request"},
};
}  // namespace

std::string status_name(std::uint8_t status) {
  if (status < sizeof kStatus / sizeof kStatus[0]) return kStatus[status].name;
  char buf[24];
  std::snprintf(buf, sizeof buf, "status 0x%02x", status);
  return buf;
}

namespace internal {

std::string status_meaning(std::uint8_t status) {
  if (status < sizeof kStatus / sizeof kStatus[0]) return kStatus[status].meaning;
  return "a status DFU does not define";
}

std::string hex32(std::uint32_t value) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08X", value);
  return buf;
}

}  // namespace internal
}  // namespace palp::dfu
