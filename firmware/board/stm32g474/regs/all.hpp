// SPDX-License-Identifier: Apache-2.0
// Every register definition of the STM32G474 board, in one list the SVD cross-check walks
// (tests/stm32). A definition added under regs/ must be added here.
#pragma once

#include "adc.hpp"
#include "crs.hpp"
#include "dma.hpp"
#include "flash.hpp"
#include "gpio.hpp"
#include "iwdg.hpp"
#include "pwr.hpp"
#include "rcc.hpp"
#include "tim.hpp"
#include "usart.hpp"
#include "usb.hpp"

namespace palp::stm32 {

inline constexpr const Register* kAllRegisters[] = {
    &rcc::Cr::reg,   &rcc::Cfgr::reg,  &rcc::Pllcfgr::reg, &rcc::Apb1enr1::reg,
    &rcc::Ccipr::reg, &rcc::Crrcr::reg, &flash::Acr::reg,   &pwr::Cr1::reg,
    &pwr::Cr5::reg,  &crs::Cr::reg,    &crs::Cfgr::reg,   &rcc::Ahb2enr::reg,
    &gpio::ModerA::reg, &gpio::BsrrA::reg,
    // Timers and watchdog (timers.hpp).
    &rcc::Apb2enr::reg, &tim1::Cr1::reg, &tim1::Cr2::reg, &tim1::Ccmr1::reg, &tim1::Ccmr2::reg,
    &tim1::Ccer::reg, &tim1::Psc::reg, &tim1::Arr::reg, &tim1::Rcr::reg, &tim1::Ccr1::reg,
    &tim1::Ccr2::reg, &tim1::Ccr4::reg, &tim1::Bdtr::reg, &tim1::Egr::reg, &tim2::Cr1::reg,
    &tim2::Smcr::reg, &tim2::Ccmr1::reg, &tim2::Ccer::reg, &tim2::Cnt::reg, &tim2::Arr::reg,
    &tim2::Egr::reg, &iwdg::Kr::reg, &iwdg::Pr::reg, &iwdg::Rlr::reg, &iwdg::Sr::reg,
    // The host link over LPUART1 (link_uart.hpp).
    &rcc::Apb1enr2::reg, &lpuart1::Cr1::reg, &lpuart1::Cr2::reg,
    &lpuart1::Cr3::reg, &lpuart1::Brr::reg, &lpuart1::Isr::reg, &lpuart1::Icr::reg,
    &lpuart1::Rdr::reg, &lpuart1::Tdr::reg, &lpuart1::Presc::reg,
    // ADC1 injected + ADC2 regular scan with DMA (adc.hpp).
    &rcc::Ahb1enr::reg, &adc::Isr::adc1, &adc::Isr::adc2, &adc::Ier::adc1,
    &adc::Cr::adc1, &adc::Cr::adc2, &adc::Cfgr::adc1, &adc::Cfgr::adc2, &adc::Smpr1::adc2,
    &adc::Smpr2::adc1, &adc::Sqr1::adc2, &adc::Sqr2::adc2, &adc::Dr::adc2, &adc::Jsqr::adc1,
    &adc::Jdr1::adc1, &adc::Jdr2::adc1, &adc::Ccr::reg, &dma::Ccr1::reg, &dma::Cndtr1::reg,
    &dma::Cpar1::reg, &dma::Cmar1::reg, &dma::Dmamux0::reg,
    // The pin table (pins.hpp); GPIOA's MODER is gpio::ModerA above.
    &gpio::ModerB::reg, &gpio::ModerC::reg, &gpio::PortA::otyper, &gpio::PortA::ospeedr,
    &gpio::PortA::pupdr, &gpio::PortA::afrl, &gpio::PortA::afrh, &gpio::PortB::otyper,
    &gpio::PortB::ospeedr, &gpio::PortB::pupdr, &gpio::PortB::afrl, &gpio::PortB::afrh,
    &gpio::PortC::otyper, &gpio::PortC::ospeedr, &gpio::PortC::pupdr, &gpio::PortC::afrl,
    &gpio::PortC::afrh,
    // The flash controller for calibration storage (flash_driver.hpp); FLASH_ACR is above.
    &flash::Keyr::reg, &flash::Sr::reg, &flash::Cr::reg, &flash::Eccr::reg, &flash::Optr::reg,
    // The USB device peripheral (usb_fsdev.hpp); BCDR is not in the SVD (regs/usb.hpp).
    &usb::Epr::regs[0], &usb::Epr::regs[1], &usb::Epr::regs[2], &usb::Epr::regs[3],
    &usb::Epr::regs[4], &usb::Epr::regs[5], &usb::Epr::regs[6], &usb::Epr::regs[7],
    &usb::Cntr::reg, &usb::Istr::reg, &usb::Fnr::reg, &usb::Daddr::reg, &usb::Btable::reg,
    // The board class (stm_board.hpp): the µs clock, nFAULT, contact line, driver enable.
    &tim5::Cr1::reg, &tim5::Egr::reg, &tim5::Cnt::reg, &tim5::Psc::reg, &tim5::Arr::reg,
    &gpio::IdrC::reg, &gpio::BsrrC::reg,
};

}  // namespace palp::stm32
