// The body shared by the fuzz targets of the readers of named channels (.mat, HDF5, TDMS): the
// bytes become an in-memory file (memfd, opened by its /proc path, as the libraries want a path);
// opening it and streaming every numeric channel must succeed or give an inertest::Error, never a
// crash or another exception.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "inertest/core/error.h"
#include "inertest/io/channel_record.h"

inline int fuzz_channel_record(const std::uint8_t* data, std::size_t size, inertest::ChannelRecordFormat format) {
  const int fd = memfd_create("fuzz_record", MFD_CLOEXEC);
  if (fd < 0) __builtin_trap();
  if (size > 0 && write(fd, data, size) != static_cast<ssize_t>(size)) __builtin_trap();
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  try {
    const auto record = inertest::open_channel_record(path, format);
    for (std::size_t i = 0; i < record->channels().size(); ++i) {
      if (!record->channels()[i].numeric) continue;
      try {
        std::size_t seen = 0;
        const std::size_t count =
            inertest::stream_channel(*record, i, [&](std::span<const double> chunk) { seen += chunk.size(); });
        if (count != seen) __builtin_trap();
      } catch (const inertest::Error&) {
      }
    }
  } catch (const inertest::Error&) {
  }
  close(fd);
  return 0;
}
