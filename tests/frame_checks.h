#pragma once
// Two renderings that must agree bit for bit (the same rays traced another
// way: compacted, fused): image, per-pixel steps, the frame's counts and the
// primary hits (--hits) where they were captured.

#include <gtest/gtest.h>

#include "render/frame_result.h"

namespace passtrace::test {

inline void expectSameFrame(const FrameResult& got, const FrameResult& want) {
  EXPECT_EQ(got.rgb, want.rgb);
  EXPECT_EQ(got.steps, want.steps);
  EXPECT_EQ(got.stats.rays, want.stats.rays);
  EXPECT_EQ(got.stats.passes, want.stats.passes);
  EXPECT_EQ(got.stats.steps, want.stats.steps);
  EXPECT_EQ(got.stats.triangleTests, want.stats.triangleTests);
  EXPECT_EQ(got.stats.maxStepsPerRay, want.stats.maxStepsPerRay);
  ASSERT_EQ(got.primaryHits.size(), want.primaryHits.size());
  for (size_t i = 0; i < got.primaryHits.size(); ++i) {
    const HitRecord a = got.primaryHits[i], b = want.primaryHits[i];
    ASSERT_TRUE(a.t == b.t && a.u == b.u && a.v == b.v && a.id == b.id) << "pixel " << i;
  }
}

}  // namespace passtrace::test
