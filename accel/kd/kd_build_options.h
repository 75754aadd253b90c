#pragma once
// The two choices a kd-tree build makes besides -e and -d (--kd-builder,
// --kd-termination), as AccelBuildConfig holds them. buildKdTreeFor
// (kd_structures.h) turns them into a builder and its limits.

#include <array>
#include <optional>
#include <string_view>

namespace passtrace {

// How a node's split plane is chosen.
enum class KdBuilderKind {
  Exact,   // every clipped triangle bound is a candidate (kd_tree_builder.h)
  Binned,  // min-max binning: bin boundaries are the candidates (kd_binned_builder.h)
};

// When a node becomes a leaf (kd_termination.h).
enum class KdTermination {
  Thesis,  // -e and -d (default 8 + 1.3 log2 N), as thesis section 8.4 and pbrt
  Papay,   // seed 003 section 9.2: d_max = ceil(2 + 1.2 log2 N), leaf below n_max(N)
};

inline constexpr std::array<std::string_view, 2> kKdBuilderNames = {"exact", "binned"};
inline constexpr std::array<std::string_view, 2> kKdTerminationNames = {"thesis", "papay"};

inline std::optional<KdBuilderKind> kdBuilderByName(std::string_view name) {
  for (size_t i = 0; i < kKdBuilderNames.size(); ++i)
    if (kKdBuilderNames[i] == name) return KdBuilderKind(i);
  return std::nullopt;
}

inline std::optional<KdTermination> kdTerminationByName(std::string_view name) {
  for (size_t i = 0; i < kKdTerminationNames.size(); ++i)
    if (kKdTerminationNames[i] == name) return KdTermination(i);
  return std::nullopt;
}

}  // namespace passtrace
