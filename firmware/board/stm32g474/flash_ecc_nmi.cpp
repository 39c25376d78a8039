// SPDX-License-Identifier: Apache-2.0
// The board's NMI handler: a flash double ECC error raised by a calibration read is recorded and
// returned from (flash_driver.hpp, handle_ecc_nmi: why that is safe); any other NMI is fatal and
// goes to the default handler (vectors.cpp), as before this file existed. Defining the board's
// one EccFaultLog here means every image that uses the flash driver links this strong
// NMI_Handler over vectors.cpp's weak alias.
#include "flash_driver.hpp"

namespace palp::stm32::flash {

namespace {
constinit EccFaultLog board_ecc_fault_log;  // written by the NMI, read by FlashDriver::read
}  // namespace

EccFaultLog& ecc_fault_log() { return board_ecc_fault_log; }

}  // namespace palp::stm32::flash

#if defined(__arm__)
extern "C" void palp_default_handler();  // vectors.cpp

extern "C" void NMI_Handler() {
  palp::stm32::Mmio io;
  if (!palp::stm32::flash::handle_ecc_nmi(io, palp::stm32::flash::ecc_fault_log())) {
    palp_default_handler();
  }
}
#endif
