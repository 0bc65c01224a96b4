cmake_minimum_required(VERSION 3.25)
# Writes grip(1) with help2man: the synopsis and options from `grip --help`, and a COMMANDS
# section with the --help of every subcommand, found by reading the "Subcommands:" lists that
# CLI11 prints, so that a new command is documented without an edit here.
function(grip_help out_var)
  execute_process(COMMAND ${GRIP} ${ARGN} --help OUTPUT_VARIABLE text RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "`grip ${ARGN} --help` failed (${result})")
  endif()
  string(REPLACE "${GRIP}" "grip" text "${text}")  # the usage line names the binary's path
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# The subcommands listed in a --help text: the first word of each indented line after
# "Subcommands:".
function(grip_subcommands text out_var)
  set(names "")
  string(FIND "${text}" "Subcommands:" at)
  if(at GREATER -1)
    string(SUBSTRING "${text}" ${at} -1 tail)
    string(REPLACE "\n" ";" lines "${tail}")
    list(POP_FRONT lines)
    foreach(line IN LISTS lines)
      if(line MATCHES "^  ([a-z][a-z0-9-]*)( |$)")
        list(APPEND names ${CMAKE_MATCH_1})
      elseif(NOT line STREQUAL "" AND NOT line MATCHES "^ ")
        break()
      endif()
    endforeach()
  endif()
  set(${out_var} ${names} PARENT_SCOPE)
endfunction()

set(sections "[COMMANDS]\n")
function(grip_document_command)
  grip_help(text ${ARGN})
  grip_subcommands("${text}" children)
  string(REPLACE ";" " " name "${ARGN}")
  # roff: a backslash is written \e, and a line that begins with a dot or quote is protected.
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  string(APPEND sections ".SS grip ${name}\n.nf\n${text}\n.fi\n")
  foreach(child IN LISTS children)
    grip_document_command(${ARGN} ${child})
  endforeach()
  set(sections "${sections}" PARENT_SCOPE)
endfunction()

grip_help(top)
grip_subcommands("${top}" commands)
foreach(command IN LISTS commands)
  grip_document_command(${command})
endforeach()
set(sections "${sections}[SEE ALSO]\nThe README and docs/ of the grip sources; the DDS contract in\n/usr/share/grip/idl.\n")
get_filename_component(dir "${OUTPUT}" DIRECTORY)
file(WRITE "${dir}/grip-man-sections.h2m" "${sections}")
execute_process(
  COMMAND ${HELP2MAN} --no-info --no-discard-stderr
          --name "GRIP real-time kinodynamic replanning runtime"
          --include "${dir}/grip-man-sections.h2m" --output "${OUTPUT}" ${GRIP}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "help2man failed (${result})")
endif()
# Debian installs man pages compressed.
file(ARCHIVE_CREATE OUTPUT "${OUTPUT}.gz" PATHS "${OUTPUT}" FORMAT raw COMPRESSION GZip)
