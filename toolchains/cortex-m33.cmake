# Cortex-M33 (Armv8-M mainline), single-precision FPU fpv5-sp-d16, hard-float
# ABI, on QEMU mps2-an505 (secure aliases: SSRAM1 at 0x10000000, SSRAM2 at 0x38000000).
set(KESTREL_ARM_FLAGS "-mcpu=cortex-m33 -mfpu=fpv5-sp-d16 -mfloat-abi=hard")
set(KESTREL_QEMU_MACHINE mps2-an505)
set(KESTREL_QEMU_CPU cortex-m33)
set(KESTREL_FLASH 0x10000000)
set(KESTREL_FLASH_SIZE 0x00400000)
set(KESTREL_RAM 0x38000000)
set(KESTREL_RAM_SIZE 0x00200000)
include("${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-picolibc.cmake")
