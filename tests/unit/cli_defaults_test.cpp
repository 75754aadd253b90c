// The command line's defaults are the registry's: each build parameter's
// default in apps/cli_options.h (what -t, -e, ... are when not given) equals
// buildParamDefault(), which `passtrace --list` prints and which comes from the
// default-constructed AccelBuildConfig / GpuTraversalConfig the tests build with.

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "accel/registry.h"
#include "apps/cli_options.h"
#include "render/shading_config.h"

namespace passtrace {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The leading number of "0 = 8 + 1.3 log2 N", or the whole text.
std::string value(BuildParam p) {
  const std::string d = buildParamDefault(p);
  return d.substr(0, d.find(" = "));
}

TEST(CliDefaults, EqualTheRegistrysBuildParameterDefaults) {
  const Options o;
  EXPECT_EQ(number(o.swapChildren), value(BuildParam::SwapChildren));
  EXPECT_EQ(number(o.gsTries), value(BuildParam::GsTries));
  EXPECT_EQ(number(o.gridMultiplier), value(BuildParam::GridMultiplier));
  EXPECT_EQ(number(o.kdMinElements), value(BuildParam::KdMinElements));
  EXPECT_EQ(number(o.kdMaxDepth), value(BuildParam::KdMaxDepth));
  EXPECT_EQ(o.gridKernels, value(BuildParam::GridKernels));
  EXPECT_EQ(number(o.loopLimit), value(BuildParam::LoopLimit));
  EXPECT_EQ(number(double(o.pageTexels)), value(BuildParam::PageTexels));
  EXPECT_EQ(o.triangleTest, value(BuildParam::TriangleTest));
  EXPECT_EQ(number(o.stackSize), value(BuildParam::KdStackSize));
  EXPECT_EQ(o.kdBuilder, value(BuildParam::KdBuilder));
  EXPECT_EQ(o.kdTermination, value(BuildParam::KdTermination));
  EXPECT_EQ(o.dynamic, value(BuildParam::Dynamic));
  EXPECT_EQ(number(o.dacrtRLimit), value(BuildParam::DacrtRLimit));
  EXPECT_EQ(number(o.dacrtPLimit), value(BuildParam::DacrtPLimit));
  EXPECT_EQ(o.dacrtCones ? "on" : "off", value(BuildParam::DacrtCones));
  EXPECT_EQ(o.dacrtSplit, value(BuildParam::DacrtSplit));
  EXPECT_EQ(o.bvhBuilder, value(BuildParam::BvhBuilder));
  EXPECT_EQ(o.bvh8Builder, value(BuildParam::Bvh8Builder));
}

TEST(CliDefaults, EveryBuildParameterHasAFlagAndADefault) {
  for (BuildParam p : kBuildParams) {
    EXPECT_EQ(buildParamFlag(p).substr(0, 1), "-");
    EXPECT_FALSE(buildParamDefault(p).empty());
    EXPECT_NE(buildParamDefault(p), "?");
  }
}

TEST(CliDefaults, ShadingDefaultsEqualShadingConfigs) {
  const Options o;
  const ShadingConfig config;
  EXPECT_EQ(shadingModeByName(o.shading), config.mode);
  EXPECT_EQ(config.mode, ShadingMode::Thesis);  // today's images by default
  EXPECT_EQ(o.aoSamples, config.aoSamples);
  EXPECT_EQ(o.aoDistance, config.aoDistance);
  for (ShadingMode m : {ShadingMode::Thesis, ShadingMode::Whitted, ShadingMode::Ao})
    EXPECT_EQ(shadingModeByName(shadingModeName(m)), m);
  EXPECT_EQ(shadingModeByName("phong"), std::nullopt);
}

}  // namespace
}  // namespace passtrace
