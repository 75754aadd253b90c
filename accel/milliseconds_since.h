#pragma once
// Wall-clock milliseconds since a steady-clock instant: what every build and
// frame time in passtrace is measured with (a steady clock, never the
// system clock, which can jump).
#include <chrono>

namespace passtrace {

inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace passtrace
