#pragma once
// The Cornell box of thesis figure 26, built in code: the classic measured
// room with its short and tall block and the ceiling light.

#include "scenes/scene.h"

namespace passtrace {

// 32 diffuse triangles: 5 walls, 2 blocks of 5 faces, the light square (all
// two triangles per quad). Red wall at x = 556, green at x = 0.
Scene makeCornellBox();

}  // namespace passtrace
