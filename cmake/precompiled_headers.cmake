# Precompiled headers for the third-party headers that most sources include: parsing nlohmann/json
# alone costs about 1.3 s of CPU per source, gtest 1 s, fmt 0.5 s (g++ 12, measured on this machine);
# precompiling them cuts the library's compile time by about 30 % with g++.
# g++ only: CMake passes clang the header as `-Xclang -include -Xclang <absolute path>`, which
# ccache 4.7 does not make relative, so a clang build with precompiled headers never hits the cache
# from another clone; there ccache (cmake/ccache.cmake) serves more than precompiling would save.
function(inertest_precompile_headers target)
  if(INERTEST_PRECOMPILED_HEADERS AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
