// The readers behind open_channel_record, one per format (io/channel_record.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "inertest/io/channel_record.h"

namespace inertest {

std::unique_ptr<ChannelRecord> open_hdf5_record(const std::string& path);
std::unique_ptr<ChannelRecord> open_mat_record(const std::string& path);
std::unique_ptr<ChannelRecord> open_tdms_record(const std::string& path);

// "channel 'name', samples FIRST..LAST: " for messages about a range of a channel.
std::string channel_range_context(const ChannelInfo& channel, std::uint64_t first, std::size_t count);

}  // namespace inertest
