#include "inertest/core/sha256.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "inertest/core/error.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// FIPS 180-2 appendix B.1 and B.2: the digests of "abc" and of the 448-bit two-block message.
TEST(Sha256, PublishedExamples) {
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

// A file read in blocks digests as its bytes do: FIPS 180-2 appendix B.3, one million 'a' (the
// blocks of 1 MiB end inside the message), and an empty file.
TEST(Sha256, FileOfAMillionAIsTheAppendixDigest) {
  testing::ScratchDirectory scratch;
  const std::string path = scratch.path() + "/a.txt";
  std::ofstream(path, std::ios::binary) << std::string(1000000, 'a');
  const FileDigest digest = file_sha256(path);
  EXPECT_EQ(digest.sha256, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(digest.bytes, 1000000u);
  std::ofstream(scratch.path() + "/empty.txt", std::ios::binary);
  EXPECT_EQ(file_sha256(scratch.path() + "/empty.txt").sha256,
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_THROW(file_sha256(scratch.path() + "/missing.txt"), Error);
}

}  // namespace
}  // namespace inertest
