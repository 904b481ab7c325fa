// SHA-256 (FIPS PUB 180-4, section 6.2), for the archive's content identity of a campaign.
#pragma once

#include <string>
#include <string_view>

namespace inertest::archive {

// The digest of data as 64 lower-case hex digits.
std::string sha256_hex(std::string_view data);

}  // namespace inertest::archive
