// libFuzzer target: AFF and NFF through loadScene, the command line's path
// (loadAff, then framing and the power-of-two rescaling that make a scene
// near FLT_MAX renderable; loadAff alone may leave its framed view infinite). One
// parser reads both and ignores the extension, so every input is an .aff.
// The animation time follows the input's length (0 to 4 in quarters), so
// keyframes are evaluated inside and past their range without spending
// input bytes on it.
#include <cstddef>
#include <cstdint>

#include "scenes/scene_registry.h"
#include "tests/fuzz/fuzz_input_file.h"
#include "tests/fuzz/fuzz_loader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace passtrace;
  // A file beside the input, so `i 0 part.aff` reaches the include code.
  static const bool once = [] {
    const char part[] = "fm 0 0 0 1 0 0 0 0 0 1 0 1\np 3 0 0 0 1 0 0 0 1 0\n";
    fuzz::writeInputFile("part.aff", part, sizeof part - 1);
    return true;
  }();
  (void)once;
  const float time = static_cast<float>(size % 17) * 0.25f;
  const auto path = fuzz::writeInputFile("input.aff", data, size);
  fuzz::requireCleanOutcome(path, [&](const auto& p) { SceneOptions options;
    options.time = time;
    return loadScene(p.string(), options);
  });
  return 0;
}
