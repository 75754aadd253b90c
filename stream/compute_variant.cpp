#include "stream/compute_variant.h"

#include <regex>
#include <stdexcept>
#include <utility>
#include <vector>

namespace passtrace {
namespace {

// Globals the kernel's own code may use (texel_address.glsl's readElement),
// so they go before it: the element's slot in the stream's surfaces and how
// to find another's (stream/element_slots.h, whose twin slotOf_ is).
const char* const kVariantGlobals = R"(#define COMPUTE_STAGE 1
vec4 fragCoord_;
float fragDepth_;
bool discarded_;
uint elementSlot_;
uint slotOf_(uvec2 p, uint width) {
  uint tile = (p.y >> 3u) * ((width + 7u) >> 3u) + (p.x >> 3u);
  return tile * 64u + ((p.x & 3u) | ((p.y & 1u) << 2u) | ((p.x & 4u) << 1u) | ((p.y & 6u) << 3u));
}
)";

// The variant's main: which element this invocation is, the kernel's main as
// a function, then what the fragment stage's fixed function would do. A
// subgroup's appends and counts are gathered by a ballot first
// (GL_ARB_shader_ballot), so it touches the global counters once, not once
// per element.
const char* const kComputeMain = R"(
layout(local_size_x = 64) in;
uniform uvec2 uStreamSize_;  // the stream's width and the rows the dispatch covers
uniform uint uRowsRun_;      // the rows whose elements run (the row limit)
uniform uint uElementList_;  // 0: every element of those rows, 1: the active list
uniform uint uWriteMask_;    // bit N: output N is stored
uniform uint uCull_;         // 1: build the next active list from the elements that discard
uniform uint uCountPassed_;  // 1: count the elements that do not discard
uniform uint uStoreImages_;  // 1: outputs go to image units, not the storage block (inout_stream.h)
layout(std430, binding = 4) writeonly buffer StreamSurfaces_ { vec4 surfaceSlots_[]; };
layout(std430, binding = 7) readonly buffer ActiveList_ { uint activeHeader_[4]; uint activeIndex_[]; };
layout(std430, binding = 6) buffer NextList_ { uint nextHeader_[4]; uint nextIndex_[]; };
layout(std430, binding = 5) buffer PassedCount_ { uint passedCount_; };
uint laneCount_(uint64_t lanes) { uvec2 v = unpackUint2x32(lanes); return uint(bitCount(v.x) + bitCount(v.y)); }
uint lowestLane_(uint64_t lanes) {
  uvec2 v = unpackUint2x32(lanes);
  return uint(v.x != 0u ? findLSB(v.x) : 32 + findLSB(v.y));
}

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint element = 0u;
  uvec2 pixel = uvec2(0u);
  bool live;
  if (uElementList_ != 0u) {
    uint entry = group * 64u + gl_LocalInvocationIndex;
    live = entry < activeHeader_[3];
    if (live) {
      element = activeIndex_[entry];
      pixel = uvec2(element % uStreamSize_.x, element / uStreamSize_.x);
      elementSlot_ = slotOf_(pixel, uStreamSize_.x);
    }
  } else {
    uint tilesPerRow = (uStreamSize_.x + 7u) / 8u;
    uint tiles = tilesPerRow * ((uStreamSize_.y + 7u) / 8u);
    // Group g runs tile g, so consecutive groups store to consecutive slots
    // (element_slots.h). It used to run tile bitreverse(g), to spread each of
    // llvmpipe's threads over the image; with the slots in tile order that
    // made kk-bvh's compute frames 1.2-1.5x longer (docs/bench-speed/NOTES.md).
    uint tile = group;
    // Each run of 8 invocations (one SIMD vector of llvmpipe's AVX2 code) is
    // a 4x2 block, as its fragment shaders' two quads are, not a row of 8:
    // rays of a squarer block part later in the walk (bvh-octant-fused's bunny
    // frame 1.72-1.91x -> 1.39-1.59x the fragment stage's, docs/bench-speed/NOTES.md).
    // Runs of 32 (a warp) are 8x4 blocks.
    uint i_ = gl_LocalInvocationIndex;
    pixel = uvec2((tile % tilesPerRow) * 8u + ((i_ & 3u) | ((i_ >> 1u) & 4u)),
                  (tile / tilesPerRow) * 8u + (((i_ >> 2u) & 1u) | ((i_ >> 3u) & 6u)));
    live = tile < tiles && all(lessThan(pixel, uStreamSize_));
    element = pixel.y * uStreamSize_.x + pixel.x;
    elementSlot_ = tile * 64u + i_;  // = slotOf_(pixel, uStreamSize_.x)
  }
  bool kept = false, passed = false;
  if (live && pixel.y >= uRowsRun_) {
    kept = uCull_ != 0u;  // past the row limit an element stays as it is, active
  } else if (live) {
    fragCoord_ = vec4(vec2(pixel) + 0.5, 0.5, 1.0);
    discarded_ = false;
    fragmentMain_();
    passed = !discarded_;
    kept = uCull_ != 0u && discarded_;
    if (passed && uCull_ == 0u && uStoreImages_ != 0u) {
%IMAGE_STORES%    } else if (passed && uCull_ == 0u) {
%STORES%    }
  }
  // The subgroup's first lane reserves the slots of every lane that keeps its element.
  uint64_t keptLanes = ballotARB(kept);
  bool first = gl_SubGroupInvocationARB == lowestLane_(ballotARB(true));
  uint base = 0u;
  if (first && keptLanes != 0ul) base = atomicAdd(nextHeader_[3], laneCount_(keptLanes));
  base = readFirstInvocationARB(base);
  if (kept) nextIndex_[base + laneCount_(keptLanes & gl_SubGroupLtMaskARB)] = element;
  uint passedLanes = laneCount_(ballotARB(passed && uCountPassed_ != 0u));
  if (first && passedLanes != 0u) atomicAdd(passedCount_, passedLanes);
}
)";

}  // namespace

std::string computeVariant(std::string source) {
  const std::regex mainSignature(R"(\bvoid\s+main\s*\(\s*\))");
  std::smatch mainAt;
  if (!std::regex_search(source, mainAt, mainSignature)) throw std::invalid_argument("the kernel has no main()");
  const std::regex discard(R"(\bdiscard\s*;)");
  std::smatch firstDiscard;
  if (std::regex_search(source, firstDiscard, discard) && firstDiscard.position() < mainAt.position())
    throw std::invalid_argument("the kernel discards outside main(), which its compute variant cannot express");
  source = std::regex_replace(source, discard, "{ discarded_ = true; return; }");
  source = std::regex_replace(source, std::regex(R"(\bgl_FragDepth\b)"), "fragDepth_");
  source = std::regex_replace(source, std::regex(R"(\bgl_FragCoord\b)"), "fragCoord_");
  source = std::regex_replace(source, std::regex(R"(\bgl_HelperInvocation\b)"), "false");
  source = std::regex_replace(source, std::regex(R"(layout\s*\(\s*early_fragment_tests\s*\)\s*in\s*;)"), "");
  // The variant's globals go after "#version", before any code that uses
  // them; #extension lines must precede them, so they move up too, each
  // leaving an empty line. The next line is an assembled file's #line, so
  // driver logs still name the kernel's own files and lines.
  std::string head;
  const std::regex extension(R"((^|\n)(#extension[^\n]*))");
  for (std::sregex_iterator it(source.begin(), source.end(), extension), end; it != end; ++it)
    head += (*it)[2].str() + "\n";
  source = std::regex_replace(source, extension, "$1");
  head += "#extension GL_ARB_shader_ballot : require\n#extension GL_ARB_gpu_shader_int64 : require\n";
  source.insert(source.find('\n') + 1, head + kVariantGlobals);
  // Stream surfaces are buffer textures here (InOutStream); kernels read them
  // through texel_address.glsl's functions, which COMPUTE_STAGE switches.
  source = std::regex_replace(source, std::regex(R"(\buniform\s+sampler2D\b)"), "uniform samplerBuffer");

  std::vector<std::pair<std::string, std::string>> outputs;  // image unit, name
  const std::regex output(R"(layout\s*\(\s*location\s*=\s*(\d+)\s*\)\s*out\s+vec4\s+(\w+)\s*;)");
  for (std::sregex_iterator it(source.begin(), source.end(), output), end; it != end; ++it)
    outputs.emplace_back((*it)[1], (*it)[2]);
  source = std::regex_replace(source, output, "vec4 $2;");
  source = std::regex_replace(source, mainSignature, "void fragmentMain_()");

  std::string stores, imageStores;
  for (const auto& [unit, name] : outputs) {
    source += "layout(rgba32f, binding = " + unit + ") uniform writeonly imageBuffer " + name + "Image_;\n";
    source += "uniform uint uOutputSlot" + unit + "_;  // the first slot of the surface output " + unit + " goes to\n";
    const std::string written = "      if ((uWriteMask_ & " + std::to_string(1u << std::stoi(unit)) + "u) != 0u) ";
    stores += written + "surfaceSlots_[uOutputSlot" + unit + "_ + elementSlot_] = " + name + ";\n";
    imageStores += written + "imageStore(" + name + "Image_, int(elementSlot_), " + name + ");\n";
  }
  std::string main = kComputeMain;
  main.replace(main.find("%STORES%"), 8, stores);
  main.replace(main.find("%IMAGE_STORES%"), 14, imageStores);
  static_assert(kComputeGroupSize == 64 && kComputeTileSide == 8 && kActiveListBinding == 7 &&
                    kNextListBinding == 6 && kPassedCountBinding == 5 && kStreamSurfacesBinding == 4,
                "kComputeMain spells these numbers out");
  return source + main;
}

}  // namespace passtrace
