// Uses the installed passtrace: the generated version header, a header-only
// layer, a compile definition the package exports and a function from its
// libraries. check_install.sh compares the line it prints.
#include <cstdio>

#include "accel/geometry/geometry.h"
#include "passtrace_version.h"
#include "scenes/scene_registry.h"

int main() {
  const passtrace::Scene scene = passtrace::loadScene("cornell");
  passtrace::Aabb bounds;
  for (const passtrace::Triangle& t : scene.triangles) bounds.extend(t.bounds());
  std::printf("passtrace %s: %s has %zu triangles, %s bounds, embree %d\n", passtrace::kVersion, scene.name.c_str(),
              scene.triangles.size(), bounds.empty() ? "empty" : "finite", PASSTRACE_HAVE_EMBREE);
  return 0;
}
