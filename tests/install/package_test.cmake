# The Debian packages (ctest runs this with cmake -P): CPack makes grip and grip-dev, and each
# declares what it needs from Debian and holds what it should.
#   -DBUILD_DIR=the build tree  -DWORK_DIR=scratch
cmake_minimum_required(VERSION 3.25)

include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

function(expect what text pattern)
  if(NOT text MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: no match for '${pattern}' in:\n${text}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
run(cpack --config ${BUILD_DIR}/CPackConfig.cmake -B ${WORK_DIR})
file(GLOB runtime ${WORK_DIR}/grip_*.deb)
file(GLOB development ${WORK_DIR}/grip-dev_*.deb)
if(NOT runtime OR NOT development)
  message(FATAL_ERROR "CPack made no grip and grip-dev packages in ${WORK_DIR}")
endif()

run(dpkg-deb --field ${runtime} Depends)
expect("grip's dependencies" "${out}" "libddsc0debian")
expect("grip's dependencies" "${out}" "libyaml-cpp")
expect("grip's dependencies" "${out}" "libsystemd0")
run(dpkg-deb --contents ${runtime})
expect("grip's files" "${out}" "\\./usr/bin/grip\n")
expect("grip's files" "${out}" "\\./usr/lib/grip/libgrip_alloc_counter\\.so\n")
expect("grip's files" "${out}" "\\./usr/share/man/man1/grip\\.1\\.gz\n")
expect("grip's files" "${out}" "\\./usr/lib/systemd/system/grip-planner\\.service\n")
expect("grip's files" "${out}" "\\./usr/share/grip/systemd/grip-planner\\.env\n")
expect("grip's files" "${out}" "\\./usr/share/grip/vehicles/car\\.yaml\n")

run(dpkg-deb --field ${development} Depends)
expect("grip-dev's dependencies" "${out}" "libeigen3-dev")
run(dpkg-deb --contents ${development})
expect("grip-dev's files" "${out}" "\\./usr/lib/cmake/grip/gripConfig\\.cmake\n")
expect("grip-dev's files" "${out}" "\\./usr/include/grip/planner/planner\\.hpp\n")
