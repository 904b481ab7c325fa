// Large arrays on transparent huge pages: a record of 10^7 samples is 80 MB, 20 000 faults of 4 KB
// pages, and on a virtual machine each fault costs microseconds. Linux backs a range with 2 MB pages
// when it is advised so before it is first touched (THP mode "madvise", Debian's default).
#pragma once

#include <cstddef>
#include <vector>

namespace inertest {

// Advises the 2 MB-aligned part of [data, data + bytes) to use huge pages. Advice only: nothing
// happens where the kernel has none to give, or off Linux.
void advise_huge_pages(void* data, std::size_t bytes);

// v.resize(count) with the new storage advised for huge pages before it is zero-filled.
template <typename T>
void resize_on_huge_pages(std::vector<T>& v, std::size_t count) {
  if (count > v.capacity()) {
    std::vector<T> fresh;
    fresh.reserve(count);
    advise_huge_pages(fresh.data(), count * sizeof(T));
    fresh.assign(v.begin(), v.end());
    v.swap(fresh);
  }
  v.resize(count);
}

}  // namespace inertest
