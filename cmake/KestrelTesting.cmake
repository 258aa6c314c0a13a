# Test helpers shared by every test directory.
#
# kestrel_add_gtest(<name> SOURCES <src>... [LIBS <lib>...] [LABELS <label>...])
#   One GoogleTest executable = one CTest test.  On cross builds CTest runs it
#   through CMAKE_CROSSCOMPILING_EMULATOR (QEMU), so the same call gives host
#   and target tests.  Links kestrel_test_main (gtest, main(), the FSW assert
#   hook and, on bare metal, the picolibc stubs GoogleTest needs).
function(kestrel_add_gtest name)
  cmake_parse_arguments(A "" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE kestrel_assert_hook kestrel_test_main ${A_LIBS})
  target_compile_options(${name} PRIVATE ${KESTREL_SANITIZE_FLAGS})
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    # same rounding as the library on every target (no FMA contraction)
    target_compile_options(${name} PRIVATE -ffp-contract=off)
  endif()
  target_link_options(${name} PRIVATE ${KESTREL_SANITIZE_FLAGS})
  add_test(NAME ${name} COMMAND ${name})
  if(NOT A_TIMEOUT)
    set(A_TIMEOUT 600)
  endif()
  set_tests_properties(${name} PROPERTIES TIMEOUT ${A_TIMEOUT} LABELS "${A_LABELS}")
  if(KESTREL_COVERAGE AND "fsw" IN_LIST A_LABELS)
    # counters zeroed before, reported after every FSW test (test/CMakeLists.txt)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED fsw_coverage)
  endif()
endfunction()
