// The record files a piece of work reads, noted where inertest opens them (a mapped text or binary
// file, a MAT, HDF5 or TDMS record): a campaign step's records are those its procedure opened,
// listed files included, which results.json names with their digests (campaign.cc). Noting costs
// nothing when no collector is active (the CLI's single commands, Python).
#pragma once

#include <string>
#include <vector>

namespace inertest {

// Collects, on the calling thread and while it lives, the paths noted (lexically normal, each
// once, in the order first opened). Collectors nest: the innermost collects.
class RecordsRead {
 public:
  RecordsRead();
  ~RecordsRead();
  RecordsRead(const RecordsRead&) = delete;
  RecordsRead& operator=(const RecordsRead&) = delete;

  const std::vector<std::string>& paths() const { return paths_; }

 private:
  friend void note_record_read(const std::string& path);
  RecordsRead* outer_;
  std::vector<std::string> paths_;
};

// Notes that path is read, for the calling thread's collector if one is active.
void note_record_read(const std::string& path);

}  // namespace inertest
