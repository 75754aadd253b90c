#include "accel/bih/bih_texels.h"

#include <span>

#include "accel/reference_lists.h"
#include "stream/texel_address.h"

namespace passtrace {

BihTexels flattenBih(const Bih& bih, size_t triangleCount) {
  BihTexels out;
  out.nodes.reserve(bih.nodes.size());
  ReferenceLists lists;
  for (const BihNode& n : bih.nodes) {
    if (n.isLeaf()) {
      float list = -1.0f;
      if (n.refCount > 0) list = packIndex(lists.append(std::span(bih.references.data() + n.firstRef, n.refCount)));
      out.nodes.emplace_back(0.0f, 0.0f, 0.0f, list);
    } else {
      out.nodes.emplace_back(packIndex(n.rightChild), n.clip[0], n.clip[1], -(float(n.axis) + 2.0f));
    }
  }
  out.lists = lists.texels();
  out.listEntries = lists.entries().size();
  out.floatsPerTriangle =
      triangleCount == 0 ? 0.0 : (4.0 * double(bih.nodes.size()) + double(out.listEntries)) / double(triangleCount);
  return out;
}

}  // namespace passtrace
