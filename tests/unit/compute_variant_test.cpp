// The compute variant of a fragment kernel (stream/compute_variant.h), as
// text: what it turns discards, outputs and the fragment built-ins into, and
// which kernels it refuses. The GL tests run the variants.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "stream/compute_variant.h"

namespace passtrace {
namespace {

const char* const kKernel = R"(#version 450 core
#line 1 1
#extension GL_ARB_shader_group_vote : require
uniform sampler2D uState;
layout(early_fragment_tests) in;
layout(location = 0) out vec4 outState;
layout(location = 2) out vec4 outHit;
float helper(float x) { return x + gl_FragCoord.x; }
void main() {
  if (texelFetch(uState, ivec2(gl_FragCoord.xy), 0).w == 0.0) discard;
  if (gl_HelperInvocation) return;
  outState = vec4(helper(1.0));
  outHit = vec4(2.0);
  gl_FragDepth = 0.0;
}
)";

TEST(ComputeVariant, DiscardEndsTheElementAndOutputsBecomeMaskedSlotStores) {
  const std::string v = computeVariant(kKernel);
  EXPECT_EQ(v.find("discard;"), std::string::npos);
  EXPECT_NE(v.find("{ discarded_ = true; return; }"), std::string::npos);
  EXPECT_NE(v.find("void fragmentMain_()"), std::string::npos);
  // Output N goes to the element's slot past its surface's first, or to imageBuffer unit N.
  EXPECT_NE(v.find("if ((uWriteMask_ & 4u) != 0u) surfaceSlots_[uOutputSlot2_ + elementSlot_] = outHit;"),
            std::string::npos);
  EXPECT_NE(v.find("layout(rgba32f, binding = 0) uniform writeonly imageBuffer outStateImage_;"), std::string::npos);
  EXPECT_NE(v.find("layout(rgba32f, binding = 2) uniform writeonly imageBuffer outHitImage_;"), std::string::npos);
  EXPECT_NE(v.find("if ((uWriteMask_ & 4u) != 0u) imageStore(outHitImage_, int(elementSlot_), outHit);"),
            std::string::npos);
  // A stream surface is read as a buffer texture.
  EXPECT_NE(v.find("uniform samplerBuffer uState;"), std::string::npos);
  EXPECT_EQ(v.find("sampler2D"), std::string::npos);
  for (const char* gone : {"gl_FragCoord", "gl_HelperInvocation", "gl_FragDepth", "early_fragment_tests", "out vec4"})
    EXPECT_EQ(v.find(gone), std::string::npos) << gone;
  // #extension lines move above the variant's globals; the #line after them keeps log lines true.
  const size_t extension = v.find("#extension GL_ARB_shader_group_vote");
  EXPECT_LT(extension, v.find("vec4 fragCoord_;"));
  EXPECT_LT(v.find("vec4 fragCoord_;"), v.find("#line 1 1"));
}

TEST(ComputeVariant, RefusesADiscardOutsideMain) {
  const std::string kernel = "#version 450 core\nvoid f() { discard; }\nvoid main() { f(); }\n";
  EXPECT_THROW(computeVariant(kernel), std::invalid_argument);
  EXPECT_THROW(computeVariant("#version 450 core\nvoid notMain() {}\n"), std::invalid_argument);
}

}  // namespace
}  // namespace passtrace
