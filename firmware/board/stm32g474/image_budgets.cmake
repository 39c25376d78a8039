# SPDX-License-Identifier: Apache-2.0
# Budgets of palp-probe-controller.elf in bytes, enforced after its link (firmware/CMakeLists.txt)
# and by ctest (tests/firmware), over what the image measured with the USB device and the flash
# journal (NOTES.md, "Board class": flash 88468 B, RAM 77336 B with the 16 KiB stack, CCM
# 15344 B): flash 110 KiB (25 % over) of the 256 KiB bank, RAM 90 KiB of the 96 KiB (the part's
# limit less 6 KiB), CCM SRAM 19 KiB of the 32 KiB.
set(PALP_STM32_IMAGE_BUDGETS -DFLASH_BUDGET=112640 -DRAM_BUDGET=92160 -DCCM_BUDGET=19456)

# The control tick's interrupt (board_irqs.cpp), the indirect call it makes (the app's
# TickHandler; the board's on_tick_irq() is inlined into the handler), and the limit on its stack
# bound (cmake/check_isr_stack.cmake; measured 592 B).
set(PALP_STM32_TICK_IRQ ADC1_2_IRQHandler)
set(PALP_STM32_TICK_INDIRECT "ADC1_2_IRQHandler->palp::app::App<palp::stm32::StmBoard>::tick_entry")
set(PALP_STM32_TICK_STACK_LIMIT 1024)
