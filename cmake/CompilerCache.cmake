# ccache, where installed (scripts/bootstrap.sh installs it): CI builds a fresh clone in another
# folder, so paths are hashed relative to the source tree (base_dir) and the build folder is left
# out of the hash (nohashdir); a clone anywhere then reuses what another clone compiled.
find_program(GRIP_CCACHE ccache)
if(GRIP_CCACHE)
  set(grip_ccache_launcher ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${PROJECT_SOURCE_DIR}
      CCACHE_NOHASHDIR=1 ${GRIP_CCACHE})
  set(CMAKE_C_COMPILER_LAUNCHER ${grip_ccache_launcher})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${grip_ccache_launcher})
endif()
