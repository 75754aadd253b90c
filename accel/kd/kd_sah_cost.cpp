#include "accel/kd/kd_sah_cost.h"

namespace passtrace {

double kdSahCost(const KdTree& tree, double traversalCost, double intersectionCost) {
  if (tree.empty()) return 0.0;
  const double rootArea = tree.nodes[0].box.surfaceArea();
  double cost = 0.0;
  for (const KdNode& node : tree.nodes) {
    const double weight = rootArea > 0.0 ? node.box.surfaceArea() / rootArea : 1.0;
    cost += weight * (node.isLeaf() ? intersectionCost * node.refCount : traversalCost);
  }
  return cost;
}

}  // namespace passtrace
