# AddressSanitizer + UndefinedBehaviorSanitizer over the whole build (INERTEST_SANITIZE), and the
# libFuzzer coverage instrumentation the fuzz targets need (INERTEST_BUILD_FUZZERS, clang only).
# Included before any target is defined, so the library, the CLI and the tests are all instrumented.
# -O1 keeps the instrumented suite fast enough for CI; the first UB finding aborts
# (-fno-sanitize-recover), so CI cannot pass over one.
add_compile_options(-O1 -gline-tables-only -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all)
add_link_options(-fsanitize=address,undefined)
if(INERTEST_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "INERTEST_BUILD_FUZZERS needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
