#pragma once
// bvh8's spatial-split build (--bvh8-builder sbvh): the stack BVH's SBVH
// builder (accel/bvh_stack/sbvh_builder.h, Stich et al. 2009) with the wide
// BVH's leaf sizes, converted into the binary tree the collapse takes
// (binary_bvh.h). Its leaves may repeat a triangle (a reference per clipped
// part) and their boxes bound the clipped parts only, so a triangle may stick
// out of a leaf's box; the collapse keeps each leaf's triangles once.

#include <span>

#include "accel/bvh_stack/binary_bvh.h"
#include "accel/wide_bvh/binary_bvh.h"

namespace passtrace {

// The SBVH constants for the wide BVH: SahBuildConfig's leaf sizes (leaves of
// at most `leafSize` references always, up to `maxLeafSize` where the SAH
// prefers them: the collapse packs them by 4), its K_T and K_I, and the stack
// BVH's spatial-split settings (alpha 1e-5, references at most 2x triangles).
BvhStackConfig wideSbvhConfig(const SahBuildConfig& sah = {});

// The same tree in SahBinaryBvh's layout (the two children of a node side by
// side, after their parent). Leaves above maxLeafSize references (only where
// the SBVH stopped at its depth limit) are cut into halves under the same box,
// so no leaf exceeds what one wide leaf can hold.
SahBinaryBvh toSahBinaryBvh(const BinaryBvh& sbvh, uint32_t maxLeafSize);

// buildSbvh with wideSbvhConfig(sah), converted. Triangles with a non-finite
// vertex are left out (they can never be hit); one thread.
SahBinaryBvh buildSbvhBinaryBvh(std::span<const Triangle> tris, const SahBuildConfig& sah = {});

}  // namespace passtrace
