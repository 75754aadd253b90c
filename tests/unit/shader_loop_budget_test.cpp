// The per-element loop budget of a pass (stream/shader_loop_budget.h):
// llvmpipe's 65,535-iteration cap shared by the lanes its renderer string
// names, less the margin; no cap elsewhere.
#include <gtest/gtest.h>

#include "stream/shader_loop_budget.h"

namespace passtrace {
namespace {

TEST(ShaderLoopBudget, LlvmpipeSharesItsCapAmongTheLanes) {
  EXPECT_EQ(shaderLoopBudget("llvmpipe (LLVM 15.0.6, 256 bits)"), 65535u / 8 - 256);
  EXPECT_EQ(shaderLoopBudget("llvmpipe (LLVM 15.0.6, 128 bits)"), 65535u / 4 - 256);
  EXPECT_EQ(shaderLoopBudget("llvmpipe (LLVM 17.0.6, 512 bits)"), 65535u / 16 - 256);
  // A string without the width: the widest llvmpipe uses.
  EXPECT_EQ(shaderLoopBudget("llvmpipe"), 65535u / 16 - 256);
}

TEST(ShaderLoopBudget, OtherDriversHaveNoCap) {
  EXPECT_EQ(shaderLoopBudget("NVIDIA H200/PCIe/SSE2"), 1u << 30);
  EXPECT_EQ(shaderLoopBudget(""), 1u << 30);
}

TEST(ShaderLoopBudget, PassStepLimitResolvesZeroAndBoundsEveryLimit) {
  const uint32_t budget = shaderLoopBudget("llvmpipe (LLVM 15.0.6, 256 bits)");
  const int cap = int(budget / kLoopIterationsPerStep);
  EXPECT_EQ(passStepLimit(0, budget), cap);           // one pass per bounce, within the cap
  EXPECT_EQ(passStepLimit(20, budget), 20);           // the thesis's -l runs as given
  EXPECT_EQ(passStepLimit(100000, budget), cap);      // more than the cap would be cut without a sign
  EXPECT_EQ(passStepLimit(0, 1u << 30), int((1u << 30) / kLoopIterationsPerStep));
  EXPECT_EQ(passStepLimit(0, 1), 1);                  // a pass always makes progress
}

}  // namespace
}  // namespace passtrace
