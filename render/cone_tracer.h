#pragma once
// One cone per pixel (--cone): the axis is the camera contract's primary ray
// through the pixel centre (render/camera.h), the apex the eye. Traces a
// frame through a structure's cone query on all cores.

#include <vector>

#include "accel/cone/cone_traversal.h"
#include "render/camera.h"
#include "render/image_output.h"

namespace passtrace {

struct ConeFrame {
  int width = 0, height = 0;
  std::vector<ConeHitRecord> hits;   // per pixel, row 0 the top
  std::vector<uint32_t> nodes;       // nodes visited per pixel
  std::vector<uint32_t> triangles;   // triangle references met in leaves per pixel
  double ms = 0;                     // steady clock around the traversal
};

// halfAngle in radians.
ConeFrame traceCones(const ConeTraversal& traversal, const CameraBasis& camera, float halfAngle,
                     const ConeQueryConfig& config, unsigned threads);

}  // namespace passtrace
