# SPDX-License-Identifier: Apache-2.0
# Included by the QEMU runners (run_qemu_image.cmake, run_firmware_smoke.cmake): finds
# qemu-system-arm and timeout and checks that IMAGE exists, failing with what to do (HINT names the
# build command for a missing image). Sets QEMU and TIMEOUT.
if(NOT DEFINED HINT)
  set(HINT "")
endif()
find_program(QEMU qemu-system-arm)
find_program(TIMEOUT timeout)
if(NOT QEMU)
  message(FATAL_ERROR "qemu-system-arm not found: run scripts/install-deps "
                      "(or apt-get install --no-install-recommends qemu-system-arm)")
endif()
if(NOT TIMEOUT)
  message(FATAL_ERROR "timeout (coreutils) not found")
endif()
if(NOT EXISTS "${IMAGE}")
  message(FATAL_ERROR "firmware image ${IMAGE} does not exist: ${HINT}")
endif()
