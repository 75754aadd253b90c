// The compute stage's indirect dispatch over an active list
// (stream/active_elements.h): after the cull kernel has appended the elements
// still active, sizes the work-group grid that runs one invocation per entry,
// 64 per group. A grid side may hold at most 65,535 groups (the GL's
// guaranteed minimum), so a longer list takes a second dimension.
layout(local_size_x = 1) in;
layout(std430, binding = 6) buffer NextList_ { uint header[4]; };  // groups x, y, z; count

void main() {
  uint groups = (header[3] + 63u) / 64u;
  uint x = min(groups, 65535u);
  header[0] = x;
  header[1] = x == 0u ? 1u : (groups + x - 1u) / x;
  header[2] = 1u;
}
