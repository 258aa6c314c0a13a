# Cortex-M4F, single-precision FPU fpv4-sp-d16, hard-float ABI, on QEMU mps2-an386.
set(KESTREL_ARM_FLAGS "-mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
set(KESTREL_QEMU_MACHINE mps2-an386)
set(KESTREL_QEMU_CPU cortex-m4)
set(KESTREL_FLASH 0x00000000)
set(KESTREL_FLASH_SIZE 0x00400000)
set(KESTREL_RAM 0x20000000)
set(KESTREL_RAM_SIZE 0x00400000)
include("${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-picolibc.cmake")
