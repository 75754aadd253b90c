#pragma once
// A PLY header read and checked before Assimp sees the file. Assimp sizes its
// arrays from the header's element counts, so "element vertex 4000000000" in
// a 300-byte file makes it allocate gigabytes (or fail with a bare
// std::bad_alloc), and it reads a property of an unknown type as garbage
// without complaint. This check rejects both with "FILE:LINE: reason":
// unknown formats and types, a second format line, control characters,
// names that are not words, malformed lines, a header without end_header
// in its first 1 MiB, and element counts the rest of the file is too short to
// hold. The body is walked too: in a binary file every instance's bytes,
// lists included, so that a truncated file is named as such; in an ASCII
// file every instance's line, which must hold exactly its values (Assimp
// sizes a list from its length before reading it). After it, what Assimp
// allocates is bounded by a small multiple of the file size.

#include <cstdint>
#include <filesystem>

namespace passtrace {

struct PlyHeaderSummary {
  bool binary = false;
  uint64_t vertices = 0;  // instances of element "vertex"
  uint64_t faces = 0;     // instances of elements "face" and "tristrips"
};

// Throws SceneError for a header Assimp should not be given.
PlyHeaderSummary checkPlyHeader(const std::filesystem::path& file);

}  // namespace passtrace
