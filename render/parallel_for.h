#pragma once
// Runs body(begin, end) over [0, count) in chunks of `grain` on `threads`
// threads (0: all cores) with oneTBB: idle threads steal chunks, since rays
// cost very different amounts and static partitions would idle.

#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

namespace passtrace {

template <typename Body>
void parallelFor(size_t count, size_t grain, unsigned threads, const Body& body) {
  tbb::task_arena arena(threads ? int(threads) : tbb::task_arena::automatic);
  arena.execute([&] {
    // simple_partitioner: chunks of exactly `grain`, which callers chose.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, grain ? grain : 1),
                      [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); },
                      tbb::simple_partitioner());
  });
}

}  // namespace passtrace
