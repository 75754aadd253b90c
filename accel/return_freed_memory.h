#pragma once
// Hands the heap's free pages back to the system. glibc keeps what a build
// frees for the next allocations, and with its mmap threshold grown past the
// builder's mid-sized vectors (it grows to whatever was last freed, up to
// 32 MiB) that is most of the builder's temporaries: measured on bvh-octant's
// stream path, spheres 1M -> 2M triangles, 50 bytes per triangle of peak
// resident memory that the next step (writing the texture) never reused.
// Call it where a build's temporaries are gone and the big allocations of
// the next step are about to start.

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace passtrace {

inline void returnFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace passtrace
