#pragma once
// Two --cone-hits buffers of the same scene and cone (kd-tree vs BVH, or a
// structure vs itself elsewhere): the same count on every pixel, and the
// same nearest id except at ties (another triangle at the very same t).

#include <string>

#include <gtest/gtest.h>

#include "render/image_output.h"

namespace passtrace::test {

inline void expectConeBuffersAgree(const std::string& a, const std::string& b, int size) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  const std::vector<ConeHitRecord> ra = readConeHitBuffer(a, wa, ha), rb = readConeHitBuffer(b, wb, hb);
  ASSERT_EQ(wa, size);
  ASSERT_EQ(ha, size);
  ASSERT_EQ(wb, size);
  ASSERT_EQ(hb, size);
  size_t met = 0, ties = 0;
  for (size_t i = 0; i < ra.size(); ++i) {
    ASSERT_EQ(ra[i].count, rb[i].count) << "pixel " << i;
    met += ra[i].count > 0;
    if (ra[i].count == 0) {
      EXPECT_EQ(ra[i].id, 0xFFFFFFFFu);
      EXPECT_EQ(rb[i].id, 0xFFFFFFFFu);
      continue;
    }
    EXPECT_EQ(ra[i].t, rb[i].t) << "pixel " << i;
    ties += ra[i].id != rb[i].id;
  }
  EXPECT_GT(met, ra.size() / 10) << "the scene should fill part of the image";
  EXPECT_LT(ties, ra.size() / 100 + 1) << "ties should be rare";
}

// Two renderers' buffers of the same structure's tree (-r 1 and -r 2):
// identical count, id and t on every pixel.
inline void expectConeBuffersEqual(const std::string& a, const std::string& b, int size) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  const std::vector<ConeHitRecord> ra = readConeHitBuffer(a, wa, ha), rb = readConeHitBuffer(b, wb, hb);
  ASSERT_EQ(wa, size);
  ASSERT_EQ(ha, size);
  ASSERT_EQ(wb, size);
  ASSERT_EQ(hb, size);
  size_t met = 0;
  for (size_t i = 0; i < ra.size(); ++i) {
    ASSERT_EQ(ra[i].count, rb[i].count) << "pixel " << i;
    ASSERT_EQ(ra[i].id, rb[i].id) << "pixel " << i;
    ASSERT_EQ(ra[i].t, rb[i].t) << "pixel " << i;
    met += ra[i].count > 0;
  }
  EXPECT_GT(met, ra.size() / 10) << "the scene should fill part of the image";
}

}  // namespace passtrace::test
