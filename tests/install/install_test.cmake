# The install as a user meets it (ctest runs this with cmake -P): `cmake --install` into an
# empty prefix, the installed `grip` run from an empty folder (it must find its private library
# beside itself, not in the build tree), and a project outside the tree that finds the package,
# links grip::core and solves a plan.
#   -DBUILD_DIR=the build tree  -DCONSUMER_DIR=tests/install/consumer  -DWORK_DIR=scratch
cmake_minimum_required(VERSION 3.25)

include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/empty)
set(RUN_DIRECTORY ${WORK_DIR}/empty)  # nothing of the build tree around the installed grip
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

foreach(file bin/grip share/grip/dds/loopback.xml share/grip/idl/plan.idl
             share/grip/vehicles/car.yaml share/grip/vehicles/compact-car.yaml
             share/man/man1/grip.1.gz include/grip/planner/planner.hpp
             include/grip/common/result.hpp lib/cmake/grip/gripConfig.cmake)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()

run(readelf -d ${prefix}/bin/grip)
if(NOT out MATCHES "RUNPATH[^\n]*\\[\\$ORIGIN/[^]\n]*\\]")
  message(FATAL_ERROR "the installed grip's RUNPATH is not relative to it:\n${out}")
endif()
run(${prefix}/bin/grip --version)
if(NOT out MATCHES "^grip [0-9]+\\.[0-9]+\\.[0-9]+ \\(revision [^)]+\\)")
  message(FATAL_ERROR "grip --version printed: ${out}")
endif()
run(${prefix}/bin/grip plan --scene meandros --robot dd-vel --seed 1)
# The installed example parameter files read back.
run(${prefix}/bin/grip params --params ${prefix}/share/grip/vehicles/compact-car.yaml)

run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/consumer -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
run(${WORK_DIR}/consumer/grip_consumer)
message(STATUS "the consumer's plan: ${out}")
