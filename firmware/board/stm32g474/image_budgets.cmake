# Budgets of palp-probe-controller.elf in bytes, enforced after its link (firmware/CMakeLists.txt)
# and by ctest (tests/firmware), about 25 % over what the image measured (NOTES.md, "Image":
# flash 75244 B, RAM 73628 B with the 16 KiB stack, CCM 15320 B): flash 92 KiB, RAM 90 KiB of
# the 96 KiB, CCM SRAM 19 KiB of the 32 KiB.
set(PALP_STM32_IMAGE_BUDGETS -DFLASH_BUDGET=94208 -DRAM_BUDGET=92160 -DCCM_BUDGET=19456)

# The control tick's interrupt (board_irqs.cpp), the indirect call it makes (the app's
# TickHandler; the board's on_tick_irq() is inlined into the handler), and the limit on its stack
# bound (cmake/check_isr_stack.cmake; measured 592 B).
set(PALP_STM32_TICK_IRQ ADC1_2_IRQHandler)
set(PALP_STM32_TICK_INDIRECT "ADC1_2_IRQHandler->palp::app::App<palp::stm32::StmBoard>::tick_entry")
set(PALP_STM32_TICK_STACK_LIMIT 1024)
