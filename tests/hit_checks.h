#pragma once
// Hit comparisons shared by the tests that hold a structure against brute
// force: a structure may differ from it only in which of several triangles
// hit at the same t wins.

#include <algorithm>
#include <cmath>

#include "accel/geometry/geometry.h"

namespace passtrace::test {

inline bool sameHit(const Hit& a, const Hit& b) { return a.id == b.id && a.t == b.t && a.u == b.u && a.v == b.v; }

// Equal within `relative` (1e-6 by default): two triangles met at the same t.
inline bool tiedT(float a, float b, float relative = 1e-6f) {
  return std::fabs(a - b) <= relative * std::max(std::fabs(a), std::fabs(b));
}

}  // namespace passtrace::test
