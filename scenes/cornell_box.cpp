#include "scenes/cornell_box.h"

namespace passtrace {
namespace {

enum CornellMaterial : uint32_t { kWhite, kRed, kGreen, kLight };

// Splits the quad a-b-c-d (in order around its edge) into (a,b,c), (a,c,d).
void addQuad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, CornellMaterial material) {
  scene.triangles.push_back({a, b, c});
  scene.triangles.push_back({a, c, d});
  scene.materialIds.insert(scene.materialIds.end(), 2, material);
}

}  // namespace

// Coordinates are the Cornell University measurements
// (graphics.cornell.edu/online/box/data.html), in millimetres. Every quad is
// wound so its geometric normal faces into the room (walls, light) or away
// from its block.
Scene makeCornellBox() {
  Scene scene;
  scene.name = "cornell";
  scene.materials = {
      Material{glm::vec3(0.75f)},
      Material{glm::vec3(0.63f, 0.065f, 0.05f)},
      Material{glm::vec3(0.14f, 0.45f, 0.091f)},
      Material{glm::vec3(0.78f)},
  };

  // Walls.
  addQuad(scene, {552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}, kWhite);                   // floor
  addQuad(scene, {556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}, kWhite);     // ceiling
  addQuad(scene, {549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}, kWhite);  // back
  addQuad(scene, {552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}, kRed);       // left
  addQuad(scene, {0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}, kGreen);                   // right

  // Short block: top, then the four sides.
  addQuad(scene, {130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}, kWhite);
  addQuad(scene, {290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}, kWhite);
  addQuad(scene, {130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}, kWhite);
  addQuad(scene, {82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}, kWhite);
  addQuad(scene, {240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}, kWhite);

  // Tall block: top, then the four sides.
  addQuad(scene, {423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}, kWhite);
  addQuad(scene, {423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}, kWhite);
  addQuad(scene, {472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}, kWhite);
  addQuad(scene, {314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}, kWhite);
  addQuad(scene, {265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}, kWhite);

  // The light square hangs 0.5 below the ceiling so the two never coincide.
  const float lightY = 548.8f - 0.5f;
  addQuad(scene, {343, lightY, 227}, {343, lightY, 332}, {213, lightY, 332}, {213, lightY, 227}, kLight);

  // A point light just under the square's centre lights the room.
  scene.light = PointLight{{278.0f, 540.0f, 279.5f}, glm::vec3(1.0f)};
  scene.background = glm::vec3(0.0f);
  scene.ambient = 0.1f;
  // The measured camera: 35 mm focal length, 25 mm film, so 2*atan(12.5/35).
  scene.camera = CameraSpec{{278.0f, 273.0f, -800.0f}, {278.0f, 273.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 39.3f};
  return scene;
}

}  // namespace passtrace
