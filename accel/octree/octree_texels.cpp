#include "accel/octree/octree_texels.h"

#include <span>

#include "accel/reference_lists.h"
#include "stream/texel_address.h"

namespace passtrace {

OctreeTexels flattenOctree(const Octree& octree, size_t triangleCount) {
  OctreeTexels out;
  out.nodes.reserve(kOctreeNodeStride * octree.nodes.size());
  ReferenceLists lists;
  for (const OctreeNode& n : octree.nodes) {
    glm::vec4 children[2] = {glm::vec4(-1.0f), glm::vec4(-1.0f)};
    float tag = -2.0f;
    if (n.isLeaf()) {
      tag = n.refCount == 0 ? -1.0f
                            : packIndex(lists.append(std::span(octree.references.data() + n.firstRef, n.refCount)));
    } else {
      // buildOctree stores the non-empty octants in order; a child's octant
      // is where its box starts: bit k set when above the parent's minimum.
      for (uint32_t c = n.firstChild; c < n.firstChild + n.childCount; ++c) {
        const Aabb& box = octree.nodes[c].box;
        int octant = 0;
        for (int k = 0; k < 3; ++k)
          if (box.min[k] > n.box.min[k]) octant |= 1 << k;
        children[octant >> 2][octant & 3] = packIndex(c);
      }
    }
    out.nodes.emplace_back(tag, 0.0f, 0.0f, 0.0f);
    out.nodes.push_back(children[0]);
    out.nodes.push_back(children[1]);
  }
  out.lists = lists.texels();
  out.listEntries = lists.entries().size();
  out.floatsPerTriangle = triangleCount == 0 ? 0.0
                                             : (4.0 * kOctreeNodeStride * double(octree.nodes.size()) +
                                                double(out.listEntries)) / double(triangleCount);
  return out;
}

}  // namespace passtrace
