#pragma once
// The n nearest distinct triangles of a cone query (seed 000 section 3):
// kept sorted by axis distance; once full, the farthest kept t is the
// cut-off past which nodes are culled. n = 0 keeps every triangle met
// (appended, sorted once at the end: insertion into thousands is quadratic).

#include <algorithm>
#include <vector>

#include "accel/cone/cone_tests.h"

namespace passtrace {

class ConeHitList {
 public:
  ConeHitList(std::vector<ConeHit>& storage, const ConeQueryConfig& config) : hits_(storage), config_(config) {
    hits_.clear();
  }

  // Nodes whose nearest axis distance is beyond this cannot add a hit.
  float cutoff() const {
    return config_.maxHits > 0 && hits_.size() == config_.maxHits ? std::min(hits_.back().t, config_.tFar)
                                                                   : config_.tFar;
  }

  void insert(ConeHit hit) {
    if (hit.t < config_.tNear || hit.t > config_.tFar) return;
    if (config_.maxHits == 0) {
      hits_.push_back(hit);
      return;
    }
    if (hits_.size() == config_.maxHits && !coneHitBefore(hit, hits_.back())) return;
    hits_.insert(std::upper_bound(hits_.begin(), hits_.end(), hit, coneHitBefore), hit);
    if (hits_.size() > config_.maxHits) hits_.pop_back();
  }

  void finish() {
    if (config_.maxHits == 0) std::sort(hits_.begin(), hits_.end(), coneHitBefore);
  }

 private:
  std::vector<ConeHit>& hits_;
  const ConeQueryConfig& config_;
};

// Each triangle is tested once per query (kd leaves share triangles): a
// stamp per triangle, one scratch per thread.
struct ConeScratch {
  std::vector<uint32_t> stamp;
  uint32_t query = 0;
  // Starts a query; true for a triangle the first time it is seen.
  void begin(size_t triangles) {
    if (stamp.size() != triangles || ++query == 0) {
      stamp.assign(triangles, 0);
      query = 1;
    }
  }
  bool firstVisit(uint32_t id) {
    if (stamp[id] == query) return false;
    stamp[id] = query;
    return true;
  }
};

}  // namespace passtrace
