// libFuzzer target: 3DS through loadScene (Assimp, uninstrumented, with the
// index watch of assimp_index_watch.h, then the node walk, framing and
// rescaling: the command line's path).
#include <cstddef>
#include <cstdint>

#include "scenes/scene_registry.h"
#include "tests/fuzz/fuzz_input_file.h"
#include "tests/fuzz/fuzz_loader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace passtrace;
  fuzz::requireCleanOutcome(fuzz::writeInputFile("input.3ds", data, size), [](const auto& p) { return loadScene(p.string()); });
  return 0;
}
