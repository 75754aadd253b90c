// The compute stage's tile-order slots (stream/element_slots.h): every
// element of a stream has its own slot inside the surface's whole tiles, and
// an 8x8 tile's lanes run as the compute variant's invocations do (each run
// of 8 a 4x2 block, each run of 32 an 8x4 block).

#include <gtest/gtest.h>

#include <vector>

#include "stream/element_slots.h"

namespace passtrace {
namespace {

TEST(ElementSlots, EveryElementHasItsOwnSlotInsideTheSurface) {
  for (const auto [w, h] : {std::pair{1u, 1u}, {8u, 8u}, {37u, 23u}, {29u, 64u}, {512u, 3u}}) {
    const uint64_t slots = surfaceSlots(w, h);
    EXPECT_EQ(slots % kSlotsPerTile, 0u);
    EXPECT_GE(slots, uint64_t(w) * h);
    std::vector<int> taken(slots, 0);
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        const uint64_t slot = elementSlot(x, y, w);
        ASSERT_LT(slot, slots) << w << "x" << h << " element " << x << "," << y;
        ASSERT_EQ(taken[slot]++, 0) << w << "x" << h << " element " << x << "," << y;
      }
  }
}

TEST(ElementSlots, ATilesLanesRunInBlocksOfFourByTwoThenEightByFour) {
  // Lane -> (x, y) as compute_variant.cpp maps gl_LocalInvocationIndex.
  for (uint32_t lane = 0; lane < kSlotsPerTile; ++lane) {
    const uint32_t x = (lane & 3u) | ((lane >> 1u) & 4u), y = ((lane >> 2u) & 1u) | ((lane >> 3u) & 6u);
    EXPECT_EQ(tileLane(x, y), lane);
    EXPECT_EQ(elementSlot(8 + x, 16 + y, 40), (2 * 5 + 1) * kSlotsPerTile + lane);  // tile (1, 2) of 5 a row
  }
  // Lanes 0-7 cover x 0-3, y 0-1; lanes 0-31 cover x 0-7, y 0-3.
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 4; ++x) EXPECT_LT(tileLane(x, y), 8u);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 8; ++x) EXPECT_LT(tileLane(x, y), 32u);
}

}  // namespace
}  // namespace passtrace
