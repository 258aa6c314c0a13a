# Install like a tool (docs/install.md), driven by test/package/CMakeLists.txt:
#  1. `cmake --install` of the components fsw and tools into a fresh prefix;
#  2. the installed `kestrel list`, started from another working directory
#     with no KESTREL_SCENARIO_DIR, lists every shipped scenario from
#     PREFIX/share/kestrel/scenarios (the line it ends with names the folder);
#  3. the installed `kestrel run NAME` runs a shipped scenario by its name for
#     DURATION simulated seconds and writes its summary;
#  4. the installed kestrel-fsw and the schema are there;
#  5. a C program with no assertion hook of its own links the installed flight
#     library plus the default hook with find_package (kestrel::fsw_assert_default)
#     and with pkg-config (kestrel-fsw-assert-default), and runs.
include("${CMAKE_CURRENT_LIST_DIR}/run_command.cmake")

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
set(elsewhere "${WORK_DIR}/elsewhere")
file(MAKE_DIRECTORY "${elsewhere}")
set(RUN_DIR "${elsewhere}")  # every command starts there: not the source or build tree
foreach(component fsw tools)
  run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}" --component ${component})
endforeach()
unset(ENV{KESTREL_SCENARIO_DIR})

# 2. kestrel list finds the installed scenarios
set(kestrel "${prefix}/bin/kestrel")
run("${kestrel}" list)
set(listed "${LAST_OUTPUT}")
file(GLOB shipped RELATIVE "${SOURCE_DIR}/scenarios" "${SOURCE_DIR}/scenarios/*.yaml")
list(LENGTH shipped n)
if(n LESS 10)
  message(FATAL_ERROR "expected the source tree's scenarios, found ${n}")
endif()
foreach(f IN LISTS shipped)
  if(NOT EXISTS "${prefix}/share/kestrel/scenarios/${f}")
    message(FATAL_ERROR "${f} was not installed")
  endif()
  string(FIND "${listed}" "${f}" at)
  if(at LESS 0)
    message(FATAL_ERROR "kestrel list did not list the installed ${f}")
  endif()
endforeach()
string(FIND "${listed}" "(invalid" bad)
if(NOT bad LESS 0)
  message(FATAL_ERROR "an installed scenario does not validate")
endif()
string(FIND "${listed}" "${n} scenarios in ${prefix}/share/kestrel/scenarios" where)
if(where LESS 0)
  message(FATAL_ERROR "kestrel list did not read ${prefix}/share/kestrel/scenarios")
endif()

# 3. a shipped scenario run by its name, briefly
run("${kestrel}" run s1_sun_pointing --set duration=${DURATION} -o run_s1)
string(FIND "${LAST_OUTPUT}" "s1_sun_pointing: ${DURATION} s simulated" said)
if(said LESS 0)
  message(FATAL_ERROR "the installed kestrel run did not say it simulated ${DURATION} s")
endif()
foreach(out manifest.json results.h5 summary.txt report.html)
  if(NOT EXISTS "${elsewhere}/run_s1/${out}")
    message(FATAL_ERROR "the installed kestrel run wrote no ${out}")
  endif()
endforeach()
file(READ "${elsewhere}/run_s1/manifest.json" manifest)
string(JSON t GET "${manifest}" scenario duration)
string(JSON src GET "${manifest}" source)
if(NOT t EQUAL DURATION OR NOT src MATCHES "share/kestrel/scenarios/s1_sun_pointing.yaml")
  message(FATAL_ERROR "the run's manifest: duration ${t} (asked for ${DURATION}), source ${src}")
endif()

# 4. the other installed files
foreach(f "bin/kestrel-fsw" "share/kestrel/kestrel-scenario.schema.json" "share/kestrel/icd/packets.yaml"
        "share/kestrel/icd/kestrel_dictionary.json" "share/kestrel/icd/kestrel.xtce.xml"
        "share/kestrel/icd/cosmos/cmd.txt" "share/kestrel/icd/cosmos/tlm.txt")
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "${f} was not installed")
  endif()
endforeach()

# 5. the flight library links on the first try with the default hook
run(${CMAKE_COMMAND} -S "${CONSUMER_DIR}" -B "${WORK_DIR}/consumer" -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build "${WORK_DIR}/consumer")
run("${WORK_DIR}/consumer/assert_default_consumer")
run("${WORK_DIR}/consumer/assert_default_minimal")
if(PKG_CONFIG)
  file(GLOB_RECURSE pcs "${prefix}/*/kestrel-fsw-assert-default.pc")
  list(GET pcs 0 pc)
  get_filename_component(pcdir "${pc}" DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} "${pcdir}")
  run(${PKG_CONFIG} --cflags --libs kestrel-fsw-assert-default)
  separate_arguments(flags UNIX_COMMAND "${LAST_OUTPUT}")
  foreach(prog main minimal)
    run(${CC} -std=c99 -pedantic -Wall -Werror "${CONSUMER_DIR}/${prog}.c" ${flags} -o "${WORK_DIR}/${prog}_pc")
    run("${WORK_DIR}/${prog}_pc")
  endforeach()
endif()
