#pragma once
// The OpenGL rasterized preview (-r 0, thesis Appendix A): the scene drawn as
// triangles with the same camera, for checking a view before tracing it.

#include "render/frame_result.h"
#include "scenes/scene.h"

namespace passtrace {

// Needs a current GL context. Mirrors are drawn with their diffuse colour.
FrameResult renderPreview(const Scene& scene, const CameraSpec& camera, int width, int height);

}  // namespace passtrace
