#include "accel/bvh_stack/bvh_stack_texels.h"

#include "stream/texel_address.h"

namespace passtrace {

BvhStackTexels flattenBvhStack(const BinaryBvh& bvh, size_t triangleCount) {
  BvhStackTexels out;
  out.nodes.reserve(kBvhStackNodeTexels * bvh.nodes.size());
  for (const BvhStackNode& node : bvh.nodes)
    for (const BvhChild& c : node.child) {
      if (!c.present) {
        out.nodes.emplace_back(0.0f, 0.0f, 0.0f, kBvhStackAbsent);
        out.nodes.emplace_back(0.0f);
        continue;
      }
      out.nodes.emplace_back(c.box.min, packIndex(c.index));
      out.nodes.emplace_back(c.box.max, float(c.count));
    }
  out.references.assign((bvh.references.size() + 3) / 4, glm::vec4(-1.0f));
  for (size_t j = 0; j < bvh.references.size(); ++j) out.references[j / 4][int(j % 4)] = packIndex(bvh.references[j]);
  if (triangleCount > 0)
    out.floatsPerTriangle = double(4 * out.nodes.size() + bvh.references.size()) / double(triangleCount);
  return out;
}

}  // namespace passtrace
