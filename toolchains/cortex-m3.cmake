# Cortex-M3, soft float, on QEMU mps2-an385 (4 MiB code SRAM at 0, 4 MiB SSRAM at 0x20000000).
set(KESTREL_ARM_FLAGS "-mcpu=cortex-m3 -mfloat-abi=soft")
set(KESTREL_QEMU_MACHINE mps2-an385)
set(KESTREL_QEMU_CPU cortex-m3)
set(KESTREL_FLASH 0x00000000)
set(KESTREL_FLASH_SIZE 0x00400000)
set(KESTREL_RAM 0x20000000)
set(KESTREL_RAM_SIZE 0x00400000)
include("${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-picolibc.cmake")
