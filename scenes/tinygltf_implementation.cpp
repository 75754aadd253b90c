// tinygltf's implementation (its JSON is nlohmann's, which the project
// already links), compiled here once and always as a translation unit of its
// own: inside the library's unity unit, a file including tinygltf_include.h
// before it would leave the implementation out (the header is included once).
#define TINYGLTF_IMPLEMENTATION
#include "scenes/tinygltf_include.h"
