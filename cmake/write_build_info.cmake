cmake_minimum_required(VERSION 3.25)
# Writes the build's identity (version, git revision) into OUTPUT from TEMPLATE; run at every
# build by the grip_build_info target, so that the revision follows commits without a new
# configure. configure_file() leaves OUTPUT alone when nothing changed, so nothing recompiles.
# Outside a git checkout (a source tarball) the revision is "unknown".
execute_process(
  COMMAND git -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
  OUTPUT_VARIABLE GRIP_REVISION OUTPUT_STRIP_TRAILING_WHITESPACE
  RESULT_VARIABLE git_result ERROR_QUIET)
if(NOT git_result EQUAL 0 OR GRIP_REVISION STREQUAL "")
  set(GRIP_REVISION "unknown")
endif()
set(GRIP_VERSION "${VERSION}")
configure_file("${TEMPLATE}" "${OUTPUT}" @ONLY)
