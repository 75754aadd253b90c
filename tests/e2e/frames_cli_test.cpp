// --frames through the command line: a sequence over a glTF node animation
// and over morph targets renders N distinct images named NAME_0000.png ...,
// and --json reports each frame's time, build and trace times; bad requests
// are one-line errors that leave no frame behind.

#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using test::slurp;

const std::string kGltf = std::string(PASSTRACE_TEST_DATA) + "/gltf/";

class Frames : public test::CliTest {
 protected:
  void expectDistinctFrames(const std::string& scene, const std::string& renderer, float end);
};

// Runs a 30-frame sequence of `scene`; expects 30 distinct images and the
// JSON's sequence over the scene's animation range [0, end].
void Frames::expectDistinctFrames(const std::string& scene, const std::string& renderer, float end) {
  Frames& cli = *this;
  const auto r = cli.run("-s " + scene + " -r " + renderer + " -w 32 -b 1 --frames 30 -o " + cli.path("f.png") +
                         " --json " + cli.path("f.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  std::set<std::string> images;
  for (int k = 0; k < 30; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "f_%04d.png", k);
    ASSERT_TRUE(fs::exists(cli.path(name))) << name;
    images.insert(slurp(cli.path(name)));
  }
  EXPECT_EQ(images.size(), 30u) << "frames repeat";
  const nlohmann::json j = nlohmann::json::parse(slurp(cli.path("f.json")));
  ASSERT_EQ(j["sequence"].size(), 30u);
  EXPECT_EQ(j["sequence"][0]["time"], 0.0);
  EXPECT_FLOAT_EQ(j["sequence"][29]["time"].get<float>(), end);
  for (const auto& f : j["sequence"]) {
    EXPECT_GE(f["build_ms"].get<double>(), 0.0);
    EXPECT_GT(f["frame_ms"].get<double>(), 0.0);
    EXPECT_GT(f["moving_triangles"].get<int>(), 0);
  }
}

TEST_F(Frames, OverAGltfNodeAnimationAndMorphTargets) {
  // A camera that sees every frame of the moving triangles.
  expectDistinctFrames(kGltf + "animated.gltf --eye 2,1,12 --look-at 2,1,0", "1", 2.0f);
  expectDistinctFrames(kGltf + "morph.gltf --eye 3,-3,3 --look-at 0.5,0.5,0.5", "2", 1.0f);
}

TEST_F(Frames, ErrorsLeaveNothing) {
  expectOneLineError(run("-s cornell --frames 3 -r 1 -w 8 -o " + path("f.png")), "no animation");
  expectOneLineError(run("-s " + kGltf + "animated.gltf --frames 3 -r 1 -w 8 --heatmap " + path("h.png")), "--frames");
  expectOneLineError(run("-s " + kGltf + "animated.gltf --time-start 1 -r 1 -w 8 -o " + path("f.png")), "--frames");
  expectOneLineError(run("-s " + kGltf + "animated.gltf --frames 3 --time-start 2 --time-end 1 -r 1 -w 8 -o " +
                         path("f.png")), "start time");
  expectOneLineError(run("-s " + kGltf + "animated.gltf --frames 0 -r 1 -w 8"), "--frames");
  expectOneLineError(run("-s " + kGltf + "animated.gltf --frames 3 --time-end inf -r 1 -w 8 -o " + path("f.png")),
                     "--time");
}

}  // namespace
}  // namespace passtrace
