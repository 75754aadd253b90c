#include "scenes/tessellate.h"

#include <cmath>

#include <glm/gtc/constants.hpp>

namespace passtrace {

glm::vec3 faceNormal(const Triangle& t, const glm::vec3& fallback) {
  // In double: in float the cross product of huge edges overflows and that of
  // tiny ones underflows, which would give such triangles the fallback.
  const glm::dvec3 v0(t.v0);
  const glm::dvec3 n = glm::cross(glm::dvec3(t.v1) - v0, glm::dvec3(t.v2) - v0);
  const double len = glm::length(n);
  return (len > 0.0 && std::isfinite(len)) ? glm::vec3(n / len) : fallback;
}

void tessellateSphere(const glm::vec3& centre, float radius, TriangleList& out, int slices, int stacks) {
  const auto unit = [&](int stack, int slice) {
    const float theta = glm::pi<float>() * static_cast<float>(stack) / static_cast<float>(stacks);
    const float phi = glm::two_pi<float>() * static_cast<float>(slice % slices) / static_cast<float>(slices);
    return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  const float r = std::fabs(radius);
  for (int stack = 0; stack < stacks; ++stack) {
    for (int slice = 0; slice < slices; ++slice) {
      const glm::vec3 a = unit(stack, slice), b = unit(stack, slice + 1);
      const glm::vec3 c = unit(stack + 1, slice), d = unit(stack + 1, slice + 1);
      // Counter-clockwise seen from outside.
      if (stack != 0) {
        out.triangles.push_back({centre + r * a, centre + r * b, centre + r * d});
        out.normals.push_back({a, b, d});
      }
      if (stack != stacks - 1) {
        out.triangles.push_back({centre + r * a, centre + r * d, centre + r * c});
        out.normals.push_back({a, d, c});
      }
    }
  }
}

void tessellateCone(const glm::vec3& base, float baseRadius, const glm::vec3& apex, float apexRadius,
                    TriangleList& out, int slices) {
  glm::vec3 axis = apex - base;
  const float height = glm::length(axis);
  axis = height > 0.0f ? axis / height : glm::vec3(0.0f, 1.0f, 0.0f);
  // Two unit vectors perpendicular to the axis.
  const glm::vec3 helper = std::fabs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(axis, helper));
  const glm::vec3 v = glm::cross(axis, u);
  const float r0 = std::fabs(baseRadius), r1 = std::fabs(apexRadius);
  // The side's normal tilts towards the narrow end by atan((r0 - r1) / h).
  const float slope = height > 0.0f ? (r0 - r1) / height : 0.0f;
  const auto dir = [&](int slice) {
    const float phi = glm::two_pi<float>() * static_cast<float>(slice % slices) / static_cast<float>(slices);
    return std::cos(phi) * u + std::sin(phi) * v;
  };
  const auto normal = [&](const glm::vec3& radial) { return glm::normalize(radial + slope * axis); };
  for (int slice = 0; slice < slices; ++slice) {
    const glm::vec3 d0 = dir(slice), d1 = dir(slice + 1);
    const glm::vec3 b0 = base + r0 * d0, b1 = base + r0 * d1;
    const glm::vec3 a0 = apex + r1 * d0, a1 = apex + r1 * d1;
    const glm::vec3 n0 = normal(d0), n1 = normal(d1);
    if (r0 > 0.0f && r1 > 0.0f) {
      out.triangles.push_back({b0, a1, b1});
      out.normals.push_back({n0, n1, n1});
      out.triangles.push_back({b0, a0, a1});
      out.normals.push_back({n0, n0, n1});
    } else if (r1 == 0.0f) {  // a0 == a1 == apex
      out.triangles.push_back({b0, a0, b1});
      out.normals.push_back({n0, normal(glm::normalize(d0 + d1)), n1});
    } else {  // b0 == b1 == base
      out.triangles.push_back({b0, a0, a1});
      out.normals.push_back({normal(glm::normalize(d0 + d1)), n0, n1});
    }
  }
}

namespace {

// Appends the triangles `corners` picks out of the polygon (see appendPolygon).
void appendTriangles(const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                     const std::vector<std::array<uint32_t, 3>>& corners, TriangleList& out) {
  glm::vec3 geometric(0.0f, 0.0f, 1.0f);
  if (normals.empty()) {
    for (const auto& [a, b, c] : corners) {
      const glm::vec3 n = faceNormal({vertices[a], vertices[b], vertices[c]}, glm::vec3(0.0f));
      if (n != glm::vec3(0.0f)) {
        geometric = n;
        break;
      }
    }
  }
  for (const auto& [a, b, c] : corners) {
    out.triangles.push_back({vertices[a], vertices[b], vertices[c]});
    if (normals.empty())
      out.normals.push_back({geometric, geometric, geometric});
    else
      out.normals.push_back({normals[a], normals[b], normals[c]});
  }
}

}  // namespace

PolygonShape appendPolygon(const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                           TriangleList& out) {
  const PolygonTriangles polygon = triangulatePolygon(vertices);
  appendTriangles(vertices, normals, polygon.triangles, out);
  return polygon.shape;
}

void triangulateFan(const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                    TriangleList& out) {
  appendTriangles(vertices, normals, fanTriangles(vertices.size()), out);
}

}  // namespace passtrace
