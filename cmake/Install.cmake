# What `cmake --install` puts where (GNU directories), and the Debian packages CPack makes of it:
#   runtime     (package grip):     bin/grip, its private library in lib/grip, the man page,
#                                   share/grip/{idl,dds}: the contract and the loopback config,
#                                   share/grip/vehicles: example parameter files,
#                                   the grip-planner systemd unit and its options' example;
#   development (package grip-dev): the planner core (grip::core, grip::base), its headers and
#                                   the CMake package, for a vehicle team that embeds the planner
#                                   in its own process: find_package(grip) and link grip::core.
include(CMakePackageConfigHelpers)

install(TARGETS grip RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(TARGETS grip_alloc_counter LIBRARY DESTINATION ${GRIP_PRIVATE_LIBDIR} COMPONENT runtime)
file(GLOB GRIP_IDL_FILES ${PROJECT_SOURCE_DIR}/idl/*.idl)
install(FILES ${GRIP_IDL_FILES} ${PROJECT_SOURCE_DIR}/idl/README.md
        DESTINATION ${CMAKE_INSTALL_DATADIR}/grip/idl COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/platform/dds/config/loopback.xml
        DESTINATION ${CMAKE_INSTALL_DATADIR}/grip/dds COMPONENT runtime)
# Parameter files of the built-in vehicles (`grip params --robot R` prints them) and of a car
# that is not the paper's, for a new vehicle's file to start from.
file(GLOB GRIP_VEHICLE_FILES ${PROJECT_SOURCE_DIR}/tools/params/examples/*.yaml)
install(FILES ${GRIP_VEHICLE_FILES} DESTINATION ${CMAKE_INSTALL_DATADIR}/grip/vehicles
        COMPONENT runtime)
# The unit names /usr/bin/grip: the Debian package's prefix.
install(FILES ${PROJECT_SOURCE_DIR}/platform/systemd/grip-planner.service
        DESTINATION lib/systemd/system COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/platform/systemd/grip-planner.env
        DESTINATION ${CMAKE_INSTALL_DATADIR}/grip/systemd COMPONENT runtime)

# The man page, from `grip --help` and every subcommand's (help2man, Debian's). A sanitized
# build does not make one: it is never installed.
find_program(GRIP_HELP2MAN help2man)
if(GRIP_HELP2MAN AND NOT GRIP_SANITIZE AND NOT GRIP_SANITIZE_THREAD)
  set(GRIP_MAN_PAGE ${CMAKE_BINARY_DIR}/man/grip.1)
  add_custom_command(
    OUTPUT ${GRIP_MAN_PAGE} ${GRIP_MAN_PAGE}.gz
    COMMAND ${CMAKE_COMMAND} -DGRIP=$<TARGET_FILE:grip> -DHELP2MAN=${GRIP_HELP2MAN}
            -DOUTPUT=${GRIP_MAN_PAGE} -P ${PROJECT_SOURCE_DIR}/cmake/write_man_page.cmake
    DEPENDS grip ${PROJECT_SOURCE_DIR}/cmake/write_man_page.cmake
    COMMENT "Writing the man page grip(1)")
  add_custom_target(grip_man_page ALL DEPENDS ${GRIP_MAN_PAGE})
  install(FILES ${GRIP_MAN_PAGE}.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT runtime)
else()
  message(STATUS "help2man not found (or a sanitized build): no man page")
endif()

install(TARGETS grip_base grip_core EXPORT gripTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/ ${PROJECT_SOURCE_DIR}/core/base/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT development)
set(GRIP_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/grip)
install(EXPORT gripTargets NAMESPACE grip:: DESTINATION ${GRIP_CMAKE_DIR}
        COMPONENT development)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gripConfig.cmake.in
  ${CMAKE_BINARY_DIR}/gripConfig.cmake INSTALL_DESTINATION ${GRIP_CMAKE_DIR})
# Before 1.0 a minor version may change the core's interface.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/gripConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/gripConfig.cmake ${CMAKE_BINARY_DIR}/gripConfigVersion.cmake
        DESTINATION ${GRIP_CMAKE_DIR} COMPONENT development)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME grip)
set(CPACK_PACKAGE_VENDOR "The grip developers")
set(CPACK_PACKAGE_CONTACT "The grip developers <grip@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "GRIP real-time kinodynamic replanning runtime")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_COMPONENTS_ALL runtime development)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME grip)
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION
    "GRIP real-time kinodynamic replanning runtime\n The grip command: the GRIP planner (Bekris and Kavraki, ICRA 2007) as a Cyclone DDS\n participant on a deadline-scheduled thread, a vehicle simulator, and benchmarks.")
# Shared-library dependencies are read off the binaries (dpkg-shlibdeps; it follows the RUNPATH
# to the private library).
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
# `grip stress --load` runs stress-ng, `grip bench dds` runs ddsperf.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "stress-ng, cyclonedds-tools")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME grip-dev)
set(CPACK_DEBIAN_DEVELOPMENT_DESCRIPTION
    "GRIP planner core for embedding\n The planner core of grip as a static library with its headers and CMake package\n (find_package(grip), target grip::core).")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS "libeigen3-dev (>= 3.4)")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_ARCHITECTURE amd64)
include(CPack)
