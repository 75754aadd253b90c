#include "scenes/scene.h"

namespace passtrace {

Aabb Scene::bounds() const {
  Aabb box;
  for (const Triangle& t : triangles) box.extend(t.bounds());
  return box;
}

}  // namespace passtrace
