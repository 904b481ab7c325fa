// SHA-256 (FIPS PUB 180-4), through OpenSSL's libcrypto (the SHA extensions where the processor has
// them: 1 GiB of cached record in 0.71 s on the 2-core CI machine, where coreutils' sha256sum takes
// 3.0 s). The archive's content identity of a campaign, and the digest results.json gives of every
// record a step read, which a lab can check with `sha256sum`.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace inertest {

// The digest of data as 64 lower-case hex digits.
std::string sha256_hex(std::string_view data);

// The digest of a file's bytes, read in blocks; its size in bytes beside it. An error naming the
// file when it cannot be read.
struct FileDigest {
  std::string sha256;
  std::uintmax_t bytes = 0;
};
FileDigest file_sha256(const std::string& path);

}  // namespace inertest
