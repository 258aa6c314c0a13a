# Runs one libFuzzer harness (seed SEED) for a bounded time (called by CTest, see
# CMakeLists.txt): new inputs go to a scratch folder, the committed seed
# corpus is only read.  Fails on any finding; the reproducer (crash-*,
# timeout-*, oom-*) stays in WORK.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/corpus")
# Reproducers of past findings (REGRESSIONS): libFuzzer runs each file given
# as an argument once; any of them failing fails the test.
if(REGRESSIONS)
  file(GLOB_RECURSE replays LIST_DIRECTORIES false "${REGRESSIONS}/*")
  if(replays)
    execute_process(
      COMMAND "${FUZZER}" -timeout=${TIMEOUT_S} -rss_limit_mb=${RSS_MB} ${replays}
      WORKING_DIRECTORY "${WORK}"
      RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "fuzzer ${FUZZER}: a regression reproducer under ${REGRESSIONS} fails (exit ${rc})")
    endif()
  endif()
endif()
execute_process(
  COMMAND "${FUZZER}" -seed=${SEED} -max_total_time=${SECONDS} -timeout=${TIMEOUT_S}
          -rss_limit_mb=${RSS_MB} -malloc_limit_mb=${RSS_MB} -print_final_stats=1
          -artifact_prefix=${WORK}/ "${WORK}/corpus" "${CORPUS}"
  WORKING_DIRECTORY "${WORK}"
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(GLOB found "${WORK}/crash-*" "${WORK}/timeout-*" "${WORK}/oom-*" "${WORK}/leak-*" "${WORK}/slow-unit-*")
  message(FATAL_ERROR "fuzzer ${FUZZER} failed (exit ${rc}); reproducers: ${found}")
endif()
