#pragma once
// The rays the CPU renderer traces, grouped into the packets it would form:
// primary rays in 8x4 tiles; from their hits (found with bvh8's single-ray
// traversal) shadow rays to the light and AO rays (the renderer's directions
// and length), each in packets of one 8x8 tile, one packet per AO sample.
// Shared by the measurement tools that time traversal alone on them.

#include <optional>
#include <string>
#include <vector>

#include "accel/ray_packet.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "scenes/scene.h"

namespace passtrace {

struct PacketSet {
  std::string kind;  // "primary", "shadow" or "ao"
  bool anyHit = false;
  std::vector<RayPacket> packets;
  size_t rays = 0;
};

// Needs AVX2 (wideBvhAvx2Available()): the primary hits come from traverseWideBvhAvx2.
std::vector<PacketSet> rendererRays(const Scene& scene, const WideBvh& bvh, int width, int aoSamples);

// The tools' arguments: SCENE [WIDTH=512] [REPEATS=defaultRepeats] [AO_SAMPLES=4].
struct RayToolArgs {
  std::string scene;
  int width = 512, repeats = 0, aoSamples = 4;
};
// Prints the usage line and returns nullopt without SCENE; throws
// std::invalid_argument naming an argument that is not a positive integer.
std::optional<RayToolArgs> parseRayToolArgs(int argc, char** argv, int defaultRepeats);

// `text` as a positive int; throws std::invalid_argument "NAME: 'text' is not a positive integer".
int parsePositiveInt(const char* name, const char* text);

}  // namespace passtrace
