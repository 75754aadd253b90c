#pragma once
// Writes a Scene's triangles as passtrace built them (--export), so they can be
// checked in another tool or fed to another ray tracer: the same order, so a
// triangle's index in the file is its id in --hits, one vertex per corner (no
// welding, which could reorder nothing but would change what a reader sees
// as shared), vertex normals when the scene has them, and the materials as far
// as the format holds them. Coordinates are written in the file's own units
// (the power-of-two rescaling of scenes/scene_scale.h undone exactly), as
// shortest round-trip decimals, so loading the export gives the same floats.
//
//   .obj   + FILE.mtl beside it: Kd = diffuse; a mirror is illum 3 with Ks =
//          its reflectance (what scenes/obj_loader.cpp reads back)
//   .gltf  one file, the buffer inline as a base64 data URI; normals made unit
//          length as glTF requires (a zero one becomes the face normal)
//   .glb   binary glTF
// glTF materials: baseColorFactor = diffuse; a mirror is metallic 1, roughness
// 0 (what scenes/gltf_loader.cpp reads back as a mirror of the base colour,
// so a mirror's own reflectance, when it differs from its diffuse colour, is
// lost). The point light and the view are not written (loading the export
// frames it as any file without them).
//
// The files are returned, not written: the run's OutputFiles
// (render/output_files.h) writes them with its other outputs. Errors (an
// unknown extension) throw std::runtime_error with a one-line message naming
// the file.

#include <filesystem>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace passtrace {

// True for the extensions exportFiles writes: .obj, .gltf, .glb (any case).
bool isExportFormat(const std::filesystem::path& file);

struct ExportedFile {
  std::filesystem::path path;
  std::string bytes;
};

// `file` and, for .obj, the FILE.mtl beside it.
std::vector<ExportedFile> exportFiles(const Scene& scene, const std::filesystem::path& file);

}  // namespace passtrace
