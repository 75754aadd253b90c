// libFuzzer target: glTF through loadScene (loadGltf, framing, rescaling: the
// command line's path); input that
// starts with the binary magic "glTF" is loaded as .glb, anything else as
// .gltf (JSON).
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "scenes/scene_registry.h"
#include "tests/fuzz/fuzz_input_file.h"
#include "tests/fuzz/fuzz_loader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace passtrace;
  // An external buffer beside the input (one triangle, then indices 0 1 2),
  // so `"uri": "buffer.bin"` reaches the external-file code.
  static const bool once = [] {
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint16_t indices[4] = {0, 1, 2, 0};
    unsigned char bytes[sizeof triangle + sizeof indices];
    std::memcpy(bytes, triangle, sizeof triangle);
    std::memcpy(bytes + sizeof triangle, indices, sizeof indices);
    fuzz::writeInputFile("buffer.bin", bytes, sizeof bytes);
    return true;
  }();
  (void)once;
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const auto path = fuzz::writeInputFile(binary ? "input.glb" : "input.gltf", data, size);
  fuzz::requireCleanOutcome(path, [](const auto& p) { return loadScene(p.string()); });
  return 0;
}
