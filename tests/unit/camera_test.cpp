// The camera's two forms of one formula: cameraDirections (eight pixels of a
// row at once, the CPU renderer's packet tiles) must give, bit for bit, the
// direction primaryRay gives pixel by pixel (the per-ray paths, raygen.frag's
// mirror). A difference would make packet rows trace other rays than the rest.
#include <cstring>

#include <gtest/gtest.h>

#include "render/camera.h"

namespace passtrace {
namespace {

void expectRowsAgree(const CameraSpec& spec, int width, int height) {
  const CameraBasis basis = makeCameraBasis(spec, width, height);
  constexpr int kLanes = 8;
  for (int py = 0; py < height; ++py) {
    const float sy = cameraScreenY(basis, py);
    for (int px0 = 0; px0 < width; px0 += kLanes) {
      float sx[kLanes], x[kLanes], y[kLanes], z[kLanes];
      for (int k = 0; k < kLanes; ++k) sx[k] = cameraScreenX(basis, px0 + k);
      cameraDirections<kLanes>(basis, sx, sy, x, y, z);
      for (int k = 0; k < kLanes && px0 + k < width; ++k) {
        const Ray want = primaryRay(basis, px0 + k, py);
        const float got[3] = {x[k], y[k], z[k]};
        const float expected[3] = {want.direction.x, want.direction.y, want.direction.z};
        ASSERT_EQ(std::memcmp(got, expected, sizeof got), 0)
            << "pixel (" << px0 + k << ", " << py << "): (" << got[0] << ", " << got[1] << ", " << got[2]
            << ") against (" << expected[0] << ", " << expected[1] << ", " << expected[2] << ")";
      }
    }
  }
}

TEST(Camera, RowDirectionsEqualPrimaryRaysBitForBit) {
  expectRowsAgree(CameraSpec{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.0f}, 64, 48);
  // An oblique camera, odd sizes (a partial last group of lanes) and a wide field of view.
  expectRowsAgree(CameraSpec{{1.0f, 2.0f, 3.0f}, {0.5f, -1.0f, 0.25f}, {0, 1, 0}, 52.0f}, 77, 45);
  expectRowsAgree(CameraSpec{{-3.0f, 0.2f, -7.5f}, {4.0f, 1.0f, 2.0f}, {0.1f, 1, 0.3f}, 120.0f}, 13, 101);
}

}  // namespace
}  // namespace passtrace
