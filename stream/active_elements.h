#pragma once
// The compute stage's answer to the depth buffer and the occlusion queries
// (stream/stream_stage.h): which elements of an InOutStream are active.
// Either every element (after reset(true): ray generation, shading), run as
// 8x8 tiles of the stream, or an index list in a storage buffer that the
// cull kernel builds, run by an indirect dispatch of one invocation per
// entry. A list is a header (work groups x, y, z; count) and the indices;
// the cull kernel appends the elements still active to the other list and
// active_list_groups.comp sizes its dispatch, so the count never comes back
// to the CPU unless a caller asks for it.

#include <cstdint>
#include <vector>

#include "stream/storage_buffer.h"

namespace passtrace {

class ActiveElements {
 public:
  ActiveElements(int width, int height);
  ~ActiveElements();
  ActiveElements(const ActiveElements&) = delete;
  ActiveElements& operator=(const ActiveElements&) = delete;

  // The memory per element: the two index lists (the cull reads one and
  // writes the other). A --dynamic two-trees save adds one more list.
  static constexpr double bytesPerElement() { return 2.0 * sizeof(uint32_t); }

  int width() const { return width_; }
  int height() const { return height_; }

  // Every element active (a depth cleared to 1), or none (to 0).
  void reset(bool active);

  // Runs the bound compute-variant `program` over the active elements of the
  // first `rows` rows; a cull (`cull`) replaces the active list by the
  // elements it kept. With `count`, returns how many elements did not
  // discard (the occlusion query's number), else 0.
  uint64_t dispatch(unsigned program, int rows, bool cull, bool count);

  // 1 for an active element, 0 for a finished one (readDepth()'s values).
  std::vector<float> read() const;
  // --dynamic two-trees: the active set, saved and put back.
  void save();
  void restore();

 private:
  int width_, height_;
  bool all_ = true;  // every element active: no list
  StorageBuffer lists_[2];
  int current_ = 0;
  StorageBuffer passed_;
  StorageBuffer saved_;
  bool savedAll_ = true;
  bool haveSaved_ = false;
  unsigned groupsProgram_ = 0;
};

}  // namespace passtrace
