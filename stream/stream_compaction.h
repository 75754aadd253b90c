#pragma once
// Live-ray compaction (issue 17, item 3). llvmpipe's early depth test skips
// only whole 4x4 blocks whose every element is finished, so live rays
// scattered over the stream cost as much as a full one. gather() packs the
// live elements of a stream into whole 4x4 blocks at the start of a second
// stream of the same surfaces and limits its draws to those rows; the caller
// runs its passes there; scatter() copies every surface back to the elements
// the rays came from. Three fragment passes with a storage-buffer index (an
// atomic counter hands out slots), plus one cull that retires the padding.

#include <cstdint>

#include "stream/inout_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class StreamCompaction {
 public:
  // `rays`: the stream to compact (it must outlive this); `stateSurface`: the
  // surface whose w is 0 once an element is finished (what cull.frag reads).
  StreamCompaction(InOutStream& rays, int stateSurface);

  // Packs the elements of `rays` that pass its depth test (`live` of them, as
  // counted by the caller's cull) into compact(), enabled and with every other
  // element retired. Leaves compact() enabled for the caller's passes.
  void gather(uint64_t live);
  InOutStream& compact() { return compact_; }
  // Memory per element of a stream of `surfaces` surfaces that compaction
  // adds: the compact stream (RGBA32F surfaces and depth) and two indices.
  static double bytesPerElement(int surfaces) { return 16.0 * surfaces + 4 + 8; }
  // Retires finished elements of compact(); returns how many (the cull of
  // compact(), for GpuTraversal::trace).
  uint64_t retire() { return cull_.execute(true); }
  // Copies every surface of the gathered rays back into `rays` (drawn where its
  // depth test passes: the live elements of gather(), so its depth must not
  // change in between). Leaves `rays` enabled.
  void scatter();

 private:
  InOutStream& rays_;
  int blocksPerRow_;
  InOutStream compact_;
  StorageBuffer homes_, slots_;
  StreamKernel index_, gather_, scatter_, cull_;
};

}  // namespace passtrace
