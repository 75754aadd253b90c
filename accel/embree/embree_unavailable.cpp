// Compiled instead of embree_accelerator.cpp when passtrace is built without
// Embree (accel/CMakeLists.txt; PASSTRACE_HAVE_EMBREE=0), so that callers
// still link and asking for the baseline is a one-line error.
#include <stdexcept>

#include "accel/embree/embree_accelerator.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeEmbreeAccelerator(std::span<const Triangle>) {
  throw std::runtime_error("the Embree baseline (-r 3) is not available: passtrace was built without Embree");
}

}  // namespace passtrace
