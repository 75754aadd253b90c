#pragma once
// Shared by the degenerate-geometry and extreme-coordinate tests: scenes
// written as exact OBJ text, height fields, transforms, and a command-line
// fixture whose inputs live apart from the outputs that must not appear.

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "accel/geometry/geometry.h"
#include "tests/cli_support.h"

namespace passtrace::test {

// An OBJ of separate triangles, every coordinate written exactly (%.17g of a
// float is its exact value, so the file reads back bit for bit).
std::string objOf(const std::vector<Triangle>& tris);

// An n x n height field over [-1, 1]^2 in the plane z = 0 when bumpy is
// false (a flat square of 2n^2 triangles), with hills otherwise.
std::vector<Triangle> heightField(int n, bool bumpy);

std::vector<Triangle> transformed(std::vector<Triangle> tris, const std::function<glm::vec3(glm::vec3)>& f);

std::vector<Triangle> scaledByPowerOfTwo(std::vector<Triangle> tris, int k);

class DegenerateCli : public CliTest {
 protected:
  // Inputs go to a subdirectory, apart from the outputs that must not appear.
  std::string write(const std::string& name, const std::string& text) {
    std::filesystem::create_directories(dir_ / "in");
    const std::filesystem::path file = dir_ / "in" / name;
    std::ofstream(file) << text;
    return file.string();
  }
};

}  // namespace passtrace::test
