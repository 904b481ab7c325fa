#include "inertest/core/records_read.h"

#include <algorithm>
#include <filesystem>

namespace inertest {
namespace {

thread_local RecordsRead* active = nullptr;

}  // namespace

RecordsRead::RecordsRead() : outer_(active) { active = this; }

RecordsRead::~RecordsRead() { active = outer_; }

void note_record_read(const std::string& path) {
  if (active == nullptr) return;
  const std::string normal = std::filesystem::path(path).lexically_normal().string();
  if (std::find(active->paths_.begin(), active->paths_.end(), normal) == active->paths_.end()) {
    active->paths_.push_back(normal);
  }
}

}  // namespace inertest
