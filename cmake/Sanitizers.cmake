# ASan + UBSan for the debug preset. UBSan findings abort so that tests fail on them.
if(GRIP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
