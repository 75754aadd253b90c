#pragma once
// tinygltf as passtrace compiles it: images are never decoded (textures are
// not rendered), so no stb_image, and its warnings, which are tinygltf's own,
// are silenced. scenes/tinygltf_implementation.cpp defines TINYGLTF_IMPLEMENTATION
// before including this; every other user gets the declarations only.

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-variable"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <tiny_gltf.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
