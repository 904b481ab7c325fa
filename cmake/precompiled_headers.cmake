# Precompiled headers for the third-party headers that most sources include: parsing nlohmann/json
# alone costs about 1.3 s of CPU per source, gtest 1 s, fmt 0.5 s (g++ 12, measured on this machine).
function(inertest_precompile_headers target)
  if(INERTEST_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
