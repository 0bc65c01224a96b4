# The grip-planner unit (platform/systemd), checked as systemd reads it (ctest runs this with
# cmake -P): `systemd-analyze verify` on a copy whose ExecStart runs the build's grip (verify
# wants the executable to exist), any complaint failing the test; and every ${GRIP_*} variable
# of ExecStart has a default in the unit and an entry in the example options file.
#   -DUNIT=grip-planner.service  -DOPTIONS=grip-planner.env  -DGRIP=the build's grip
#   -DSYSTEMD_ANALYZE=systemd-analyze  -DWORK_DIR=scratch
cmake_minimum_required(VERSION 3.25)

file(READ ${UNIT} unit)
string(FIND "${unit}" "ExecStart=/usr/bin/grip " installed_path)
if(installed_path EQUAL -1)
  message(FATAL_ERROR "the unit does not run /usr/bin/grip (the Debian package's prefix)")
endif()
string(REPLACE "ExecStart=/usr/bin/grip " "ExecStart=${GRIP} " unit "${unit}")
file(REMOVE_RECURSE ${WORK_DIR})
get_filename_component(name ${UNIT} NAME)
file(WRITE ${WORK_DIR}/${name} "${unit}")

# --man=no: the man page the unit names is installed by the package, not the build.
execute_process(COMMAND ${SYSTEMD_ANALYZE} verify --man=no ${WORK_DIR}/${name}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT result EQUAL 0 OR NOT "${out}${err}" STREQUAL "")
  message(FATAL_ERROR "systemd-analyze verify ${name} (${result}):\n${out}${err}")
endif()

file(READ ${OPTIONS} options)
string(REGEX MATCH "\nExecStart=[^\n]*" exec_start "${unit}")
string(REGEX MATCHALL "\\$\\{GRIP_[A-Z_]+\\}" variables "${exec_start}")
if(NOT variables)
  message(FATAL_ERROR "ExecStart takes no \${GRIP_*} option")
endif()
foreach(variable ${variables})
  string(REGEX REPLACE "[\${}]" "" variable "${variable}")
  if(NOT unit MATCHES "\nEnvironment=[^\n]*${variable}=")
    message(FATAL_ERROR "${variable}: no default in the unit's Environment=")
  endif()
  if(NOT options MATCHES "\n${variable}=")
    message(FATAL_ERROR "${variable}: not in ${OPTIONS}")
  endif()
endforeach()
