# ASan + UBSan for the debug preset. UBSan findings abort so that tests fail on them.
if(GRIP_SANITIZE AND GRIP_SANITIZE_THREAD)
  message(FATAL_ERROR "GRIP_SANITIZE and GRIP_SANITIZE_THREAD exclude each other: "
                      "ThreadSanitizer cannot run beside AddressSanitizer")
endif()
if(GRIP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
# ThreadSanitizer for the ci-tsan preset: the lock-free hand-offs and the participants' threads.
# Cyclone (Debian's libddsc) is not instrumented: cmake/tsan_suppressions.txt names it alone.
if(GRIP_SANITIZE_THREAD)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
