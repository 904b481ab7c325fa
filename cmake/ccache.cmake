# ccache (Debian's `ccache`) keeps compiled objects between builds. Paths are made relative to the
# source tree (CCACHE_BASEDIR) and the build directory is left out of the hash (CCACHE_NOHASHDIR),
# so that a fresh clone anywhere on the machine, as CI makes, reuses the objects of an earlier
# build. The sloppiness lets ccache serve the sources compiled with precompiled headers
# (cmake/precompiled_headers.cmake). Set before any target exists: targets copy the launcher.
option(INERTEST_CCACHE "Compile through ccache when it is installed" ON)
find_program(INERTEST_CCACHE_PROGRAM ccache)
if(INERTEST_CCACHE AND INERTEST_CCACHE_PROGRAM AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  set(CMAKE_CXX_COMPILER_LAUNCHER
      ${CMAKE_COMMAND} -E env
      CCACHE_BASEDIR=${PROJECT_SOURCE_DIR} CCACHE_NOHASHDIR=true
      CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
      ${INERTEST_CCACHE_PROGRAM})
endif()
