// The reference cone query: the exact test against every triangle.
#include "accel/cone/cone_traversal.h"

namespace passtrace {
namespace {

class BruteForceCone final : public ConeTraversal {
 public:
  explicit BruteForceCone(std::span<const Triangle> tris) : tris_(tris) { stats_.name = "brute-force"; }
  void query(const Cone& cone, const ConeQueryConfig& config, ConeScratch&, ConeResult& result) const override {
    ConeHitList list(result.hits, config);
    result.nodes = 0;
    result.triangleTests = uint32_t(tris_.size());
    for (uint32_t id = 0; id < tris_.size(); ++id) {
      float t;
      if (coneMeetsTriangle(cone, tris_[id], t)) list.insert({t, id});
    }
    list.finish();
  }
  const AccelStats& stats() const override { return stats_; }

 private:
  std::span<const Triangle> tris_;
  AccelStats stats_;
};

}  // namespace

std::unique_ptr<ConeTraversal> makeBruteForceCone(std::span<const Triangle> tris) {
  return std::make_unique<BruteForceCone>(tris);
}

}  // namespace passtrace
