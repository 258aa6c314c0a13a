# Every stage selection of fsw_acs builds with the library's warnings as
# errors (fsw_config.h, FSW_CFG_*): fsw_acs.c and thr_map.c (the module with
# a switch of its own, FSW_CFG_THR_NNLS) compiled once with each stage
# left out alone (with the stages that need it), and once with all of them
# left out in each real type.  Arguments: CC, FLAGS (the library's warning
# and standard flags), INCLUDES, SRC (the sources), OUT (a scratch folder).
set(stages MTQ MTQ_DESAT ORBIT THR_MOM RW_BIAS RW_NULL RW_VOLT SPEED_FILTER LPF PULSE_SCHMITT THR_NNLS)
set(selections ${stages} ALL ALL_FLOAT)
set(inc "")
foreach(d IN LISTS INCLUDES)
  list(APPEND inc "-I${d}")
endforeach()
file(MAKE_DIRECTORY "${OUT}")
set(n 0)
foreach(sel IN LISTS selections)
  if(sel MATCHES "^ALL")
    set(off ${stages})
  else()
    set(off ${sel})
    if(sel STREQUAL "MTQ")
      list(APPEND off MTQ_DESAT)    # FSW_CFG_MTQ_DESAT needs FSW_CFG_MTQ
    elseif(sel STREQUAL "RW_NULL")
      list(APPEND off RW_BIAS)      # FSW_CFG_RW_BIAS needs FSW_CFG_RW_NULL
    endif()
  endif()
  list(TRANSFORM off PREPEND "-DFSW_CFG_")
  list(TRANSFORM off APPEND "=0")
  if(sel STREQUAL "ALL_FLOAT")
    list(APPEND off "-DFSW_USE_FLOAT=1")
  endif()
  foreach(src IN LISTS SRC)
    get_filename_component(base "${src}" NAME_WE)
    execute_process(COMMAND "${CC}" ${FLAGS} ${inc} ${off} -c "${src}" -o "${OUT}/${base}_${sel}.o"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${base}.c does not build with ${off}:\n${out}${err}")
    endif()
    math(EXPR n "${n} + 1")
  endforeach()
endforeach()
message(STATUS "the sources build with every stage selection tried (${n} compilations)")
