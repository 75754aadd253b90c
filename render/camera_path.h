#pragma once
// The benchmark camera path of thesis figure 27: the eye follows
// f(t) = (cos t, sin t, sin 3t) around the scene's centre, looking at it.
// passtrace's scenes are y-up, so (cos t, sin t) runs in the horizontal x-z
// plane and sin 3t is the height; angle k of n uses t = 2 pi k / n.

#include "scenes/scene.h"

namespace passtrace {

// The distance scales with the scene's bounding sphere so that the whole
// scene fits the scene's default field of view from the path's nearest point.
CameraSpec cameraPathView(const Scene& scene, int angle, int angles);

}  // namespace passtrace
