// Fuzzes the MATLAB .mat reader (matio: v5, v7 compressed, v7.3): any bytes must open and stream,
// or give an inertest::Error.
//
// matio 1.5.23 allocates what a variable's headers claim before it reads them from the file; the
// level-5 header check (src/io/mat_level5_check.h) refuses the sizes a file cannot hold, but a
// claim that passes it may still ask for gigabytes it never touches. In a release build such an
// allocation fails (matio then reports an error) or stays virtual; here it returns null too,
// instead of ending the run as libFuzzer's malloc limit or ASan's allocator would.
#include <cstdlib>
#include <vector>

#include "channel_record_fuzz.h"

extern "C" const char* __asan_default_options() { return "allocator_may_return_null=1"; }

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  static std::vector<char*> arguments(*argv, *argv + *argc);
  static char malloc_limit[] = "-malloc_limit_mb=1048576";
  arguments.insert(arguments.begin() + 1, malloc_limit);
  arguments.push_back(nullptr);
  *argc = static_cast<int>(arguments.size() - 1);
  *argv = arguments.data();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_channel_record(data, size, inertest::ChannelRecordFormat::kMat);
}
