#include "stream/stream_compaction.h"

#include <string>
#include <vector>

namespace passtrace {
namespace {

// Whole 4x4 blocks: the compact stream is at least as wide as `rays`, a multiple of 4.
int blocksPerRow(const InOutStream& rays) { return (rays.width() + 3) / 4; }

int compactHeight(const InOutStream& rays) {
  const uint64_t blocks = (rays.elementCount() + 15) / 16;
  const uint64_t perRow = uint64_t(blocksPerRow(rays));
  return int(4 * ((blocks + perRow - 1) / perRow));
}

std::vector<int> allSurfaces(const InOutStream& s) {
  std::vector<int> all;
  for (int k = 0; k < s.surfaceCount(); ++k) all.push_back(k);
  return all;
}

std::vector<std::string> defines(const InOutStream& s) { return {"SURFACES " + std::to_string(s.surfaceCount())}; }

}  // namespace

StreamCompaction::StreamCompaction(InOutStream& rays, int stateSurface)
    : rays_(rays),
      blocksPerRow_(blocksPerRow(rays)),
      compact_(4 * blocksPerRow_, compactHeight(rays), rays.surfaceCount()),
      homes_("compaction slots"),
      slots_("compaction slot per element"),
      index_("compact_index", "compact/compact_index.frag"),
      gather_("compact_gather", "compact/compact_gather.frag", StreamKernel::Depth::Test, defines(rays)),
      scatter_("compact_scatter", "compact/compact_scatter.frag", StreamKernel::Depth::Test, defines(rays)),
      cull_("cull", "cull.frag", StreamKernel::Depth::Cull) {
  homes_.reserve(1 + rays.elementCount());
  slots_.reserve(rays.elementCount());
  for (StreamKernel* k : {&index_, &gather_, &scatter_}) {
    k->bindStorage(0, homes_);
    k->bindStorage(1, slots_);
    k->set("uHomeWidth", uint32_t(rays.width()));
    k->set("uBlocksPerRow", uint32_t(blocksPerRow_));
  }
  for (int k = 0; k < rays.surfaceCount(); ++k) {
    const std::string sampler = "uSurface" + std::to_string(k);
    gather_.bindInput(sampler.c_str(), rays, k);
    scatter_.bindInput(sampler.c_str(), compact_, k);
  }
  cull_.bindInput("uState", compact_, stateSurface);
}

void StreamCompaction::gather(uint64_t live) {
  rays_.enable();
  homes_.zero(1);
  rays_.setWriteSurfaces({});  // the index pass writes only the storage buffers
  index_.execute();

  const uint64_t blocks = (live + 15) / 16;
  const int rows = int(4 * ((blocks + uint64_t(blocksPerRow_) - 1) / uint64_t(blocksPerRow_)));
  compact_.setRowLimit(rows == 0 ? 4 : rows);  // 0 would mean every row
  compact_.enable();
  compact_.clearDepth(1.0f);
  compact_.setWriteSurfaces(allSurfaces(compact_));
  gather_.set("uLive", uint32_t(live));
  gather_.execute();
  retire();  // the padding after the last live ray
}

void StreamCompaction::scatter() {
  rays_.enable();
  rays_.setWriteSurfaces(allSurfaces(rays_));
  scatter_.execute();
}

}  // namespace passtrace
