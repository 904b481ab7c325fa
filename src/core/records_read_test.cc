#include "inertest/core/records_read.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

namespace inertest {
namespace {

// Each path once, lexically normal, in the order first read; the innermost collector collects, and
// another thread's reads are not this one's (a step's records are those it read).
TEST(RecordsRead, CollectsEachPathOnceOnItsThread) {
  note_record_read("before.csv");  // no collector: nothing to note it
  RecordsRead outer;
  note_record_read("day1/./a.csv");
  {
    RecordsRead inner;
    note_record_read("day1/b.csv");
    std::thread([] { note_record_read("other_thread.csv"); }).join();
    EXPECT_EQ(inner.paths(), std::vector<std::string>{"day1/b.csv"});
  }
  note_record_read("day1/x/../a.csv");
  note_record_read("c.f64");
  EXPECT_EQ(outer.paths(), (std::vector<std::string>{"day1/a.csv", "c.f64"}));
}

}  // namespace
}  // namespace inertest
