# Install and export kestrel::fsw so that
#   find_package(kestrel CONFIG REQUIRED)  target_link_libraries(app kestrel::fsw)
# works on the host and in cross builds, plus a relocatable pkg-config file
# (kestrel-fsw.pc) for Make-based flight builds.  Component "fsw": the flight
# library, the optional default assertion hook kestrel::fsw_assert_default
# (kestrel-fsw-assert-default.pc), the headers and the toolchain files: all
# a flight build needs (docs/install.md).  Component "tools" (host builds
# with the harness): the programs kestrel and kestrel-fsw, the reference
# scenarios and their JSON Schema under share/kestrel/.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(KESTREL_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/kestrel")

install(TARGETS fsw fsw_assert_default EXPORT kestrelTargets COMPONENT fsw
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  INCLUDES DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
install(FILES ${FSW_PUBLIC_HEADERS} DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/fsw" COMPONENT fsw)
install(EXPORT kestrelTargets NAMESPACE kestrel:: FILE kestrelTargets.cmake
  DESTINATION "${KESTREL_CMAKE_DIR}" COMPONENT fsw)

configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/kestrelConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/kestrelConfig.cmake" INSTALL_DESTINATION "${KESTREL_CMAKE_DIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/kestrelConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/kestrelConfig.cmake" "${PROJECT_BINARY_DIR}/kestrelConfigVersion.cmake"
  DESTINATION "${KESTREL_CMAKE_DIR}" COMPONENT fsw)

# Toolchain files, so a flight build can cross-compile against the package.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/toolchains/" DESTINATION "${CMAKE_INSTALL_DATADIR}/kestrel/toolchains"
  COMPONENT fsw FILES_MATCHING PATTERN "*.cmake")

# pkg-config: prefix is computed from the .pc file's own location, so the
# installed tree can be moved anywhere (pkg-config's ${pcfiledir}).
set(_pc_dir "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
file(RELATIVE_PATH KESTREL_PC_PREFIX_FROM_PCDIR "/root/${_pc_dir}" "/root")
string(REGEX REPLACE "/$" "" KESTREL_PC_PREFIX_FROM_PCDIR "${KESTREL_PC_PREFIX_FROM_PCDIR}")
set(KESTREL_PC_CFLAGS "")
foreach(_d IN LISTS FSW_PUBLIC_DEFS)
  string(APPEND KESTREL_PC_CFLAGS " -D${_d}")
endforeach()
configure_file("${PROJECT_SOURCE_DIR}/cmake/kestrel-fsw.pc.in" "${PROJECT_BINARY_DIR}/kestrel-fsw.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/kestrel-fsw.pc" DESTINATION "${_pc_dir}" COMPONENT fsw)
configure_file("${PROJECT_SOURCE_DIR}/cmake/kestrel-fsw-assert-default.pc.in"
  "${PROJECT_BINARY_DIR}/kestrel-fsw-assert-default.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/kestrel-fsw-assert-default.pc" DESTINATION "${_pc_dir}" COMPONENT fsw)

# The tools: `kestrel` finds the scenarios at ../share/kestrel/scenarios from
# its own folder (harness/CMakeLists.txt, scenario_dir()).
foreach(_prog kestrel kestrel_fsw)
  if(TARGET ${_prog})
    install(TARGETS ${_prog} RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}" COMPONENT tools)
  endif()
endforeach()
if(TARGET kestrel)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/scenarios/" DESTINATION "${CMAKE_INSTALL_DATADIR}/kestrel/scenarios"
    COMPONENT tools FILES_MATCHING PATTERN "*.yaml")
  install(FILES "${PROJECT_SOURCE_DIR}/scenarios/kestrel-scenario.schema.json"
    DESTINATION "${CMAKE_INSTALL_DATADIR}/kestrel" COMPONENT tools)
endif()
# The packet dictionary (docs/icd.md, "Packet dictionary"): the table and the
# files generated from it (committed, kept current by icd_generated_up_to_date),
# for a ground system beside the programs that speak the link.
if(TARGET kestrel OR TARGET kestrel_fsw)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/icd/generated/" DESTINATION "${CMAKE_INSTALL_DATADIR}/kestrel/icd"
    COMPONENT tools)
  install(FILES "${PROJECT_SOURCE_DIR}/icd/packets.yaml" DESTINATION "${CMAKE_INSTALL_DATADIR}/kestrel/icd"
    COMPONENT tools)
endif()
