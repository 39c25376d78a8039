# SPDX-License-Identifier: Apache-2.0
# Budgets of palp-stm32-bringup.elf in bytes, enforced after its link (firmware/CMakeLists.txt)
# and by ctest (tests/firmware): flash 8 KiB; RAM 17 KiB, i.e. the 16 KiB stack + 1 KiB; CCM SRAM
# 1 KiB. The reset handler's and the default handler's frames: at most 32 B each.
set(PALP_STM32_BRINGUP_BUDGETS -DFLASH_BUDGET=8192 -DRAM_BUDGET=17408 -DCCM_BUDGET=1024)
set(PALP_STM32_STARTUP_FRAME_LIMIT 32)
