// The registry of structures (accel/registry.h): rows, thesis numbering per
// renderer, name resolution and its errors, unused-parameter reporting.
// Runs without a GL context.
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "accel/registry.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

TEST(Registry, NamesAreUniqueAndEachRowHasItsFactories) {
  std::set<std::string_view> names;
  for (const Structure& s : structures()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name;
    EXPECT_FALSE(s.family.empty()) << s.name;
    EXPECT_FALSE(s.description.empty()) << s.name;
    EXPECT_EQ(s.description.find('\n'), std::string_view::npos) << s.name;
    // A renderer is listed exactly when the row can build for it.
    EXPECT_EQ(s.runsOn(RendererId::Cpu) || s.runsOn(RendererId::Embree), s.cpu != nullptr) << s.name;
    EXPECT_EQ(s.runsOn(RendererId::Gpu), s.stream != nullptr) << s.name;
    EXPECT_FALSE(s.runsOn(RendererId::OpenGl)) << s.name;
    if (s.stream) { EXPECT_NE(s.mirror, nullptr) << s.name << ": a stream structure needs its kernel's CPU mirror"; }
    EXPECT_EQ(s.number.has_value(), s.numberedOn.bits != 0) << s.name;
  }
}

// The reports that run a chosen few rows read them from the registry: each
// names a renderer the row runs on, once, and each report has what its
// tables compare (the scaling report: a CPU row, a stream row and, where
// Embree is built, the baseline; the stage table: stream rows).
TEST(Registry, FeaturedRowsRunWhereTheyAreFeatured) {
  std::set<std::pair<Report, RendererId>> found;
  bool embree = false;
  for (const Structure& s : structures()) {
    embree = embree || s.runsOn(RendererId::Embree);
    std::set<std::pair<Report, RendererId>> own;
    for (const Featured& f : s.featured) {
      EXPECT_TRUE(s.runsOn(f.renderer)) << s.name << " featured in " << reportName(f.report) << " on "
                                        << rendererName(f.renderer);
      EXPECT_TRUE(own.insert({f.report, f.renderer}).second) << s.name << ": featured twice alike";
      EXPECT_TRUE(f.report != Report::Stages || f.renderer == RendererId::Gpu) << s.name;
      found.insert({f.report, f.renderer});
    }
  }
  EXPECT_TRUE(found.count({Report::Scale, RendererId::Cpu}));
  EXPECT_TRUE(found.count({Report::Scale, RendererId::Gpu}));
  EXPECT_EQ(found.count({Report::Scale, RendererId::Embree}), embree ? 1u : 0u);
  EXPECT_TRUE(found.count({Report::Stages, RendererId::Gpu}));
  EXPECT_EQ(reportName(Report::Scale), "scale");
  EXPECT_EQ(reportName(Report::Stages), "stages");
}

// Thesis Table 4: the CPU and GPU columns number different structures.
TEST(Registry, ThesisNumbersPerRendererColumn) {
  const char* cpu[] = {"kk-bvh", "gs-bvh", "kd-tree", "kd-pbrt", "grid", "kk-bvh-recursive", "gs-bvh-recursive",
                       "octree-descent"};
  const char* gpu[] = {"kk-bvh", "gs-bvh", "kd-restart", "kd-backtrack", "grid"};
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(resolveStructure(std::to_string(i), RendererId::Cpu).name, cpu[i]);
    EXPECT_EQ(resolveStructure(cpu[i], RendererId::Cpu).name, cpu[i]);
  }
  for (int i = 0; i < 5; ++i) { EXPECT_EQ(resolveStructure(std::to_string(i), RendererId::Gpu).name, gpu[i]); }
  EXPECT_THROW(resolveStructure("5", RendererId::Gpu), std::invalid_argument);
  EXPECT_THROW(resolveStructure("8", RendererId::Cpu), std::invalid_argument);
  EXPECT_THROW(resolveStructure("-1", RendererId::Cpu), std::invalid_argument);
  EXPECT_THROW(resolveStructure("", RendererId::Cpu), std::invalid_argument);
  // The kernels' CPU mirrors run on the CPU by name only.
  EXPECT_EQ(resolveStructure("kd-restart", RendererId::Cpu).name, "kd-restart");
  EXPECT_EQ(resolveStructure("grid-stream", RendererId::Cpu).name, "grid-stream");
}

TEST(Registry, UnknownOrMisplacedNamesGiveOneLineListingTheValidOnes) {
  try {
    resolveStructure("bogus", RendererId::Cpu);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown accelerator 'bogus'"), std::string::npos) << what;
    EXPECT_NE(what.find("5 kk-bvh-recursive"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  try {
    resolveStructure("kd-tree", RendererId::Gpu);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("does not run on the GPU stream renderer"), std::string::npos) << what;
    EXPECT_NE(what.find("2 kd-restart"), std::string::npos) << what;
  }
  EXPECT_THROW(resolveStructure("0", RendererId::OpenGl), std::invalid_argument);
}

TEST(Registry, BuildingForARendererWithoutAnImplementationThrows) {
  const auto tris = testmesh::singleTriangle();
  EXPECT_THROW(makeStreamStructure(*findStructure("octree-descent"), tris), std::invalid_argument);
  EXPECT_THROW(makeMirrorStructure(*findStructure("kd-tree"), tris), std::invalid_argument);
  GpuTraversalConfig negativeLoop;
  negativeLoop.loopLimit = -1;  // 0 is "one pass per bounce"
  EXPECT_THROW(makeStreamStructure(*findStructure("kk-bvh"), tris, negativeLoop), std::invalid_argument);
}

TEST(Registry, UnusedParametersAreThoseTheRowDoesNotRead) {
  const Structure& kd = *findStructure("kd-tree");
  using P = BuildParam;
  const std::vector<P> given = {P::GridMultiplier, P::KdMaxDepth, P::LoopLimit, P::TriangleTest};
  EXPECT_EQ(unusedParams(kd, RendererId::Cpu, given), (std::vector<P>{P::GridMultiplier, P::LoopLimit}));
  const Structure& grid = *findStructure("grid");
  EXPECT_EQ(unusedParams(grid, RendererId::Gpu, {P::GridKernels, P::LoopLimit, P::PageTexels}), std::vector<P>{});
  EXPECT_EQ(unusedParams(grid, RendererId::Cpu, {P::GridKernels, P::GridMultiplier}), std::vector<P>{P::GridKernels});
  if (const Structure* embree = findStructure("embree")) {
    EXPECT_EQ(unusedParams(*embree, RendererId::Embree, {P::TriangleTest}), std::vector<P>{P::TriangleTest});
  }
}

// Every row's CPU structure reports the row's name (the JSON's "accelerator").
TEST(Registry, BuiltStructuresCarryTheRowName) {
  const auto tris = testmesh::uvSphere(6, 8);
  for (const Structure& s : structures()) {
    if (s.cpu) { EXPECT_EQ(makeCpuStructure(s, tris)->stats().name, s.name); }
    if (s.mirror) { EXPECT_EQ(makeMirrorStructure(s, tris)->stats().name.substr(0, 4), s.name.substr(0, 4)) << s.name; }
  }
}

TEST(Registry, MemoryModelMeasuredForEveryRendererOfEveryRow) {
  for (const Structure& s : structures()) {
    if (s.runsOn(RendererId::Cpu) || s.runsOn(RendererId::Embree)) { EXPECT_GT(s.memory.cpu.bytesPerTriangle, 0) << s.name; }
    if (s.runsOn(RendererId::Gpu)) { EXPECT_GT(s.memory.gpu.bytesPerTriangle, 0) << s.name; }
    for (const MemoryCost& cost : {s.memory.cpu, s.memory.gpu}) {
      EXPECT_GE(cost.growth, 1.0) << s.name;  // never extrapolated downwards
      EXPECT_LT(cost.growth, 1.5) << s.name;  // a fit gone wrong
    }
  }
}

}  // namespace
}  // namespace passtrace
