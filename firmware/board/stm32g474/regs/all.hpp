// Every register definition of the STM32G474 board, in one list the SVD cross-check walks
// (tests/stm32). A definition added under regs/ must be added here.
#pragma once

#include "crs.hpp"
#include "flash.hpp"
#include "gpio.hpp"
#include "pwr.hpp"
#include "rcc.hpp"

namespace palp::stm32 {

inline constexpr const Register* kAllRegisters[] = {
    &rcc::Cr::reg,   &rcc::Cfgr::reg,  &rcc::Pllcfgr::reg, &rcc::Apb1enr1::reg,
    &rcc::Ccipr::reg, &rcc::Crrcr::reg, &flash::Acr::reg,   &pwr::Cr1::reg,
    &pwr::Cr5::reg,  &crs::Cr::reg,    &crs::Cfgr::reg,   &rcc::Ahb2enr::reg,
    &gpio::ModerA::reg, &gpio::BsrrA::reg,
};

}  // namespace palp::stm32
