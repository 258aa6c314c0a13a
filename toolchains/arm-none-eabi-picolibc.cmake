# Common part of the bare-metal Arm Cortex-M toolchains: Debian's
# gcc-arm-none-eabi with picolibc (and picolibc's libstdc++ for the tests),
# semihosting for output and exit status, run on QEMU's MPS2 boards.
#
# The including file sets, before include():
#   KESTREL_ARM_FLAGS     -mcpu/-mfpu/-mfloat-abi flags
#   KESTREL_QEMU_MACHINE  QEMU machine (mps2-an385, ...)
#   KESTREL_QEMU_CPU      QEMU cpu
#   KESTREL_FLASH / KESTREL_FLASH_SIZE / KESTREL_RAM / KESTREL_RAM_SIZE
#                         memory map handed to picolibc's linker script
# A flight build that only needs the library can use these files as they
# are: the link and emulator settings only matter to executables.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_AR arm-none-eabi-ar CACHE FILEPATH "")
set(CMAKE_NM arm-none-eabi-nm CACHE FILEPATH "")
set(CMAKE_OBJDUMP arm-none-eabi-objdump CACHE FILEPATH "")
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_C_FLAGS_INIT "${KESTREL_ARM_FLAGS} -mthumb --specs=picolibc.specs")
set(CMAKE_CXX_FLAGS_INIT "${KESTREL_ARM_FLAGS} -mthumb --specs=picolibcpp.specs")
set(CMAKE_EXE_LINKER_FLAGS_INIT
  "--oslib=semihost --crt0=semihost -Wl,--gc-sections \
-Wl,--defsym=__flash=${KESTREL_FLASH} -Wl,--defsym=__flash_size=${KESTREL_FLASH_SIZE} \
-Wl,--defsym=__ram=${KESTREL_RAM} -Wl,--defsym=__ram_size=${KESTREL_RAM_SIZE} \
-Wl,--defsym=__stack_size=0x10000")
# __stack_size: the region picolibc's linker script reserves for the stack
# below the top of RAM (its default is 2 KiB); 64 KiB keeps the heap that
# GoogleTest uses well away from a 4 KiB-per-function flight budget.

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

set(CMAKE_CROSSCOMPILING_EMULATOR
  qemu-system-arm -M ${KESTREL_QEMU_MACHINE} -cpu ${KESTREL_QEMU_CPU}
  -nographic -monitor none -serial none
  -semihosting-config enable=on,target=native -kernel)
