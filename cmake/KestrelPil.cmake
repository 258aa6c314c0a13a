# Processor-in-the-loop (docs/pil.md): the host build also builds the FSW
# programs the harness runs under QEMU, each as an external project of this
# same source tree with a target toolchain file (only the flight library and
# the one program are built there):
#
#   pil/aarch64-linux/flight/posix/kestrel-fsw          qemu-aarch64 (qemu-user)
#   pil/armhf-linux/flight/posix/kestrel-fsw            qemu-arm (qemu-user)
#   pil/cortex-m4f/flight/m4f/kestrel-fsw-m4f.elf        qemu-system-arm mps2-an386, fsw_real double
#   pil/cortex-m4f-float/flight/m4f/kestrel-fsw-m4f.elf  the same, fsw_real float
#
# Their paths are compiled into the harness (harness/src/link/pil.cpp) as the
# defaults of `kestrel run --fsw pil:TARGET`; `--pil-bin FILE` overrides.
# A target whose cross compiler or emulator is missing is left out (its
# default path is then empty and the harness says so).
include(ExternalProject)

# Default: on in the Release GCC host build without sanitizers (host-release,
# where harness_pil_test runs); the other host presets skip the four cross
# builds (-DKESTREL_BUILD_PIL=ON to have them anyway).
set(_pil_default OFF)
if(CMAKE_SYSTEM_NAME STREQUAL "Linux" AND CMAKE_BUILD_TYPE STREQUAL "Release" AND CMAKE_C_COMPILER_ID STREQUAL "GNU"
   AND NOT KESTREL_SANITIZE AND NOT KESTREL_COVERAGE)
  set(_pil_default ON)
endif()
option(KESTREL_BUILD_PIL "Build the cross-compiled FSW programs for processor-in-the-loop runs" ${_pil_default})

set(KESTREL_PIL_TARGETS "")
# Extra arguments: more targets of the same build (built with the program).
function(kestrel_pil_target name toolchain real subdir program compiler emulator)
  find_program(_cc_${name} ${compiler})
  find_program(_emu_${name} ${emulator})
  set(_bin "")
  if(KESTREL_BUILD_PIL AND _cc_${name} AND _emu_${name})
    set(_dir "${PROJECT_BINARY_DIR}/pil/${name}")
    ExternalProject_Add(pil_${name}
      SOURCE_DIR "${PROJECT_SOURCE_DIR}"
      BINARY_DIR "${_dir}"
      CMAKE_GENERATOR "${CMAKE_GENERATOR}"
      CMAKE_ARGS
        -DCMAKE_TOOLCHAIN_FILE=${PROJECT_SOURCE_DIR}/toolchains/${toolchain}
        -DCMAKE_BUILD_TYPE=Release
        -DKESTREL_REAL=${real}
        -DKESTREL_WERROR=${KESTREL_WERROR}
        -DKESTREL_FSW_MAX_RW=${KESTREL_FSW_MAX_RW}
        -DKESTREL_FSW_MAX_THR=${KESTREL_FSW_MAX_THR}
        -DKESTREL_BUILD_TESTS=OFF -DKESTREL_BUILD_SIM=OFF -DKESTREL_BUILD_HARNESS=OFF
        -DKESTREL_BUILD_BENCHMARKS=OFF -DKESTREL_INSTALL=OFF
      BUILD_COMMAND ${CMAKE_COMMAND} --build <BINARY_DIR> --target ${program} ${ARGN}
      INSTALL_COMMAND ""
      BUILD_ALWAYS ON)
    set(_bin "${_dir}/${subdir}")
    set(KESTREL_PIL_TARGETS ${KESTREL_PIL_TARGETS} pil_${name} PARENT_SCOPE)
  endif()
  string(TOUPPER "${name}" _up)
  string(REPLACE "-" "_" _up "${_up}")
  set(KESTREL_PIL_BIN_${_up} "${_bin}" PARENT_SCOPE)
endfunction()

kestrel_pil_target(aarch64-linux aarch64-linux-gnu.cmake double flight/posix/kestrel-fsw kestrel_fsw
                   aarch64-linux-gnu-gcc qemu-aarch64)
kestrel_pil_target(armhf-linux arm-linux-gnueabihf.cmake double flight/posix/kestrel-fsw kestrel_fsw
                   arm-linux-gnueabihf-gcc qemu-arm)
# (with the instruction counter's self-check, bench/target/, run by the test
# m4f_instruction_counter)
kestrel_pil_target(cortex-m4f cortex-m4f.cmake double flight/m4f/kestrel-fsw-m4f.elf kestrel_fsw_m4f
                   arm-none-eabi-gcc qemu-system-arm m4f_counter_check)
set(KESTREL_PIL_M4F_COUNTER_CHECK "")
if(KESTREL_PIL_BIN_CORTEX_M4F)
  set(KESTREL_PIL_M4F_COUNTER_CHECK "${PROJECT_BINARY_DIR}/pil/cortex-m4f/bench/target/m4f-counter-check.elf")
endif()
kestrel_pil_target(cortex-m4f-float cortex-m4f.cmake float flight/m4f/kestrel-fsw-m4f.elf kestrel_fsw_m4f
                   arm-none-eabi-gcc qemu-system-arm)

if(TARGET harness_link)
  target_compile_definitions(harness_link PRIVATE
    KESTREL_PIL_BIN_AARCH64_LINUX="${KESTREL_PIL_BIN_AARCH64_LINUX}"
    KESTREL_PIL_BIN_ARMHF_LINUX="${KESTREL_PIL_BIN_ARMHF_LINUX}"
    KESTREL_PIL_BIN_CORTEX_M4F="${KESTREL_PIL_BIN_CORTEX_M4F}"
    KESTREL_PIL_BIN_CORTEX_M4F_FLOAT="${KESTREL_PIL_BIN_CORTEX_M4F_FLOAT}")
  if(KESTREL_PIL_TARGETS)
    add_dependencies(harness_link ${KESTREL_PIL_TARGETS})
  endif()
endif()
