#pragma once
// The binary tree bvh8 and bvh8-packet are collapsed from (--bvh8-builder),
// as AccelBuildConfig holds it.

#include <array>
#include <optional>
#include <string_view>

namespace passtrace {

enum class Bvh8BuilderKind {
  Binned,  // binned SAH on all cores (binary_bvh.h)
  Sbvh,    // Stich et al. 2009's spatial splits, one thread (sbvh_binary_bvh.h)
};

inline constexpr std::array<std::string_view, 2> kBvh8BuilderNames = {"binned", "sbvh"};

inline std::optional<Bvh8BuilderKind> bvh8BuilderByName(std::string_view name) {
  for (size_t i = 0; i < kBvh8BuilderNames.size(); ++i)
    if (kBvh8BuilderNames[i] == name) return Bvh8BuilderKind(i);
  return std::nullopt;
}

}  // namespace passtrace
