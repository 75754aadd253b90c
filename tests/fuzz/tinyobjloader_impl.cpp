// tinyobjloader compiled from its header with the fuzzing instrumentation, in
// place of Debian's prebuilt libtinyobjloader, so that libFuzzer sees its
// branches and the sanitizers check its memory accesses. The same version
// and options as the library the main build links.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
