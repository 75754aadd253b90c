// libFuzzer target: PLY through loadScene (passtrace's own reader: the
// header check of ply_header.h and the body of ply_reader.h, then framing and
// rescaling: the command line's path).
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
