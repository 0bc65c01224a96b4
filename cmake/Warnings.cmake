# Strict warnings for the project's own targets; third-party headers come in as SYSTEM.
add_library(grip_warnings INTERFACE)
target_compile_options(grip_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow
  -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
  -Wnull-dereference -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough)
# GCC's ThreadSanitizer instrumentation makes -Wnull-dereference report paths that do not exist
# in inlined library code (CLI11's); the other builds keep the warning.
if(GRIP_SANITIZE_THREAD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(grip_warnings INTERFACE -Wno-null-dereference)
endif()
if(GRIP_WERROR)
  target_compile_options(grip_warnings INTERFACE -Werror)
endif()
