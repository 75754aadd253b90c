// libFuzzer target: PLY through loadScene (the header check, Assimp, the
// node walk, framing, rescaling: the command line's path). Assimp itself is
// Debian's uninstrumented library: ASan still catches what it does to
// memory the loader owns, and a crash inside it still stops the run.
#include <cstddef>
#include <cstdint>

#include "scenes/scene_registry.h"
#include "tests/fuzz/fuzz_input_file.h"
#include "tests/fuzz/fuzz_loader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace passtrace;
  fuzz::requireCleanOutcome(fuzz::writeInputFile("input.ply", data, size), [](const auto& p) { return loadScene(p.string()); });
  return 0;
}
