// libFuzzer target: Wavefront OBJ through loadScene (loadObj, framing,
// rescaling: the command line's path).
#include <cstddef>
#include <cstdint>

#include "scenes/scene_registry.h"
#include "tests/fuzz/fuzz_input_file.h"
#include "tests/fuzz/fuzz_loader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace passtrace;
  // A material library beside the input, so `mtllib materials.mtl` reaches the MTL parser.
  static const bool once = [] {
    const char mtl[] = "newmtl red\nKd 1 0 0\nnewmtl mirror\nKs 0.9 0.9 0.9\nillum 3\n";
    fuzz::writeInputFile("materials.mtl", mtl, sizeof mtl - 1);
    return true;
  }();
  (void)once;
  fuzz::requireCleanOutcome(fuzz::writeInputFile("input.obj", data, size), [](const auto& p) { return loadScene(p.string()); });
  return 0;
}
