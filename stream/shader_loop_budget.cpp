#include "stream/shader_loop_budget.h"

#include <algorithm>
#include <regex>

#include "stream/gl.h"

namespace passtrace {

uint32_t shaderLoopBudget(const std::string& glRenderer) {
  if (glRenderer.find("llvmpipe") == std::string::npos) return uint32_t(1) << 30;
  constexpr uint32_t kLlvmpipeLoopCap = 65535;
  constexpr uint32_t kMargin = 256;  // loops a kernel does not count (unrolled ones, mostly)
  uint32_t bits = 512;               // the widest SIMD llvmpipe uses, when the string does not say
  std::smatch m;
  if (std::regex_search(glRenderer, m, std::regex("([0-9]+) bits")) && std::stoul(m[1]) >= 128)
    bits = uint32_t(std::stoul(m[1]));
  return kLlvmpipeLoopCap / (bits / 32) - kMargin;
}

uint32_t currentShaderLoopBudget() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return shaderLoopBudget(renderer ? renderer : "");
}

int passStepLimit(int loopLimit, uint32_t budget) {
  const int cap = int(std::max<uint32_t>(1, budget / kLoopIterationsPerStep));
  return loopLimit <= 0 ? cap : std::min(loopLimit, cap);
}

int passStepLimit(int loopLimit) { return passStepLimit(loopLimit, currentShaderLoopBudget()); }

}  // namespace passtrace
