# run(COMMAND...): execute_process that fails the script with the command's
# output when it exits non-zero; LAST_OUTPUT holds its stdout.  Started in
# RUN_DIR when that is set.  Included by the package test scripts.
function(run)
  set(wd)
  if(RUN_DIR)
    set(wd WORKING_DIRECTORY "${RUN_DIR}")
  endif()
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err ${wd})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message("${out}")
  set(LAST_OUTPUT "${out}" PARENT_SCOPE)
endfunction()
