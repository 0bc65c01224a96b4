# run(COMMAND...): runs a command (in RUN_DIRECTORY when set), fails the test with its output
# when it fails, and leaves its standard output in `out`.
function(run)
  set(directory_args)
  if(RUN_DIRECTORY)
    set(directory_args WORKING_DIRECTORY ${RUN_DIRECTORY})
  endif()
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err
                  ${directory_args})
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "`${command}` failed (${result}):\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()
