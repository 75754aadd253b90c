#pragma once
// The stack BVH's builders (--bvh-builder), as AccelBuildConfig holds them.

#include <array>
#include <optional>
#include <string_view>

namespace passtrace {

enum class BvhBuilderKind {
  Sah,     // binned SAH over the centroids (sah_builder.h)
  Sbvh,    // Stich et al. 2009: object or spatial splits, reference unsplitting (sbvh_builder.h)
  Middle,  // the middle of the centroid box's largest axis (middle_builder.h)
};

inline constexpr std::array<std::string_view, 3> kBvhBuilderNames = {"sah", "sbvh", "middle"};

inline std::optional<BvhBuilderKind> bvhBuilderByName(std::string_view name) {
  for (size_t i = 0; i < kBvhBuilderNames.size(); ++i)
    if (kBvhBuilderNames[i] == name) return BvhBuilderKind(i);
  return std::nullopt;
}

}  // namespace passtrace
