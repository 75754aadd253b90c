#pragma once
// The seed's termination rules (seed 003 section 9.2, after Vinkler et al.
// 2016) as limits of the SAH builders' KdBuildConfig. A node becomes a leaf
// when (a) d_max splits lie above it, (b) it holds fewer than n_max
// references, or (c) a leaf costs no more than its best split (both builders
// always apply (c)). --kd-termination thesis keeps -e and -d instead.
//
// d_max = ceil(2 + 1.2 log2 N) for N triangles (2 for N <= 1), in
// KdBuildConfig::maxDepth's sense: splits on a root-to-leaf path.
// n_max: the seed gives 2 below 700K primitives, 8 "around a million" and
// 12 above 3M; we read that as 2 for N < 700,000, 8 for 700,000 <= N <=
// 3,000,000 and 12 for N > 3,000,000. "Fewer than n_max" is
// KdBuildConfig::minElements = n_max - 1. Papay's rules replace -e and -d.

#include <cstddef>

#include "accel/kd/kd_build_options.h"
#include "accel/kd/kd_tree_builder.h"

namespace passtrace {

int kdPapayMaxDepth(size_t triangleCount);
size_t kdPapayLeafBelow(size_t triangleCount);  // n_max

// `config` with the limits of `rule` for N triangles (Thesis: unchanged).
KdBuildConfig kdWithTermination(KdBuildConfig config, KdTermination rule, size_t triangleCount);

}  // namespace passtrace
