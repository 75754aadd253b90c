#pragma once
// Runs body(begin, end) over [0, count) in chunks of `grain` on `threads`
// threads, which take chunks from a shared counter as they finish (rays
// cost very different amounts, so static partitions would idle).

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace passtrace {

template <typename Body>
void parallelFor(size_t count, size_t grain, unsigned threads, const Body& body) {
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t begin = next.fetch_add(grain); begin < count; begin = next.fetch_add(grain))
      body(begin, std::min(count, begin + grain));
  };
  std::vector<std::jthread> pool;
  for (unsigned i = 1; i < std::max(1u, threads); ++i) pool.emplace_back(worker);
  worker();
}

}  // namespace passtrace
