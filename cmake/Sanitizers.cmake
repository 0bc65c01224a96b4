# ASan + UBSan for the debug preset. UBSan findings abort so that tests fail on them.
# float-cast-overflow is not part of GCC's -fsanitize=undefined: a double converted to an
# integer it does not fit (hostile map geometry, a stamp far in the future) is undefined
# behaviour the world code must never reach (grip/common/saturating_cast.hpp), so it is on too.
if(GRIP_SANITIZE OR GRIP_FUZZ)
  add_compile_options(-fsanitize=address,undefined,float-cast-overflow
                      -fno-sanitize-recover=undefined,float-cast-overflow -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined,float-cast-overflow)
endif()
# The fuzz build (tests/fuzz, clang): every library instrumented for libFuzzer's coverage.
if(GRIP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "GRIP_FUZZ needs clang (libFuzzer): configure with the fuzz preset")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
if(GRIP_SANITIZE_THREAD AND (GRIP_SANITIZE OR GRIP_FUZZ))
  message(FATAL_ERROR "GRIP_SANITIZE_THREAD excludes GRIP_SANITIZE and GRIP_FUZZ: "
                      "ThreadSanitizer cannot run beside AddressSanitizer")
endif()
# ThreadSanitizer for the ci-tsan preset: the lock-free hand-offs and the participants' threads.
# Cyclone (Debian's libddsc) is not instrumented: cmake/tsan_suppressions.txt names it alone.
if(GRIP_SANITIZE_THREAD)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
