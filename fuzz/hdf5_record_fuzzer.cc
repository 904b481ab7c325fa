// Fuzzes the HDF5 reader (libhdf5): any bytes must open and stream, or give an inertest::Error.
#include "channel_record_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_channel_record(data, size, inertest::ChannelRecordFormat::kHdf5);
}
