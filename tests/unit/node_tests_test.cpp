// --stats/--json's node (box) tests per ray: how each kind of row's steps read
// (render/run_report.h nodeTestsPerRay, accel/registry.h Structure).

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "accel/registry.h"
#include "render/run_report.h"

namespace passtrace {
namespace {

RunReport report(RendererId renderer, double steps, double tests) {
  RunReport r;
  r.rendererId = int(renderer);
  r.stepsPerRay = steps;
  r.triangleTestsPerRay = tests;
  return r;
}

TEST(NodeTests, StepsAreNodeOrTriangleTestsByDefault) {
  EXPECT_DOUBLE_EQ(*nodeTestsPerRay(report(RendererId::Gpu, 20.0, 2.0)), 18.0);
  RunReport visits = report(RendererId::Cpu, 20.0, 6.0);
  visits.stepsVisitNodes = true;  // kd-tree: triangles tested inside a leaf's step
  EXPECT_DOUBLE_EQ(*nodeTestsPerRay(visits), 20.0);
}

TEST(NodeTests, EmbreeAndThePreviewCountNothing) {
  EXPECT_FALSE(nodeTestsPerRay(report(RendererId::Embree, 0.0, 0.0)).has_value());
  EXPECT_FALSE(nodeTestsPerRay(report(RendererId::OpenGl, 0.0, 0.0)).has_value());
  EXPECT_TRUE(toJson(report(RendererId::Embree, 0.0, 0.0))["node_tests_per_ray"].is_null());
}

TEST(NodeTests, RowsWhoseCpuStepsVisitNodesAreTheNodeVisitingTraversals) {
  for (const char* name : {"kd-tree", "kd-pbrt", "grid", "octree-descent"}) {
    ASSERT_NE(findStructure(name), nullptr) << name;
    EXPECT_TRUE(findStructure(name)->cpuStepsVisitNodes) << name;
  }
  for (const char* name : {"kk-bvh", "kd-restart", "grid-stream", "dacrt"})
    EXPECT_FALSE(findStructure(name)->cpuStepsVisitNodes) << name;
}

}  // namespace
}  // namespace passtrace
