#pragma once
// passtrace's own OFF reader (Geomview's Object File Format). Assimp 5.2's
// OFF reader clamps a face's out-of-range vertex index to the last vertex
// and says nothing unless its logger is on, so a corrupt file rendered. A
// check in front of Assimp would have to split lines and skip comments
// exactly as Assimp does; reading the format here (it is small) makes the
// check and the geometry come from the same parse.
//
// Read: an optional keyword [ST][C][N][n]OFF ("nOFF" with dimension 3 only;
// "4OFF", homogeneous coordinates, is refused), the counts (vertices, faces,
// and edges, ignored), one vertex per line (x y z, then nx ny nz with N; the
// rest of the line, colours or texture coordinates, is skipped), one face per
// line ("n i0 .. in-1", then an optional colour, skipped). '#' starts a
// comment. Errors are "FILE:LINE: reason": a face naming a vertex out of
// range ("face K names vertex V of N"), counts the file is too short for,
// text after the last face. The scene follows indexed_mesh.h.

#include <filesystem>

#include "scenes/scene.h"

namespace passtrace {

Scene loadOff(const std::filesystem::path& path);

}  // namespace passtrace
