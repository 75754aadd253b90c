// passtrace --export through the command line: the file it writes renders
// hits at the same triangle ids as the scene it came from (ids are the
// export's face order), it needs no GL context, and bad requests are one-line
// errors that write nothing.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scenes/scene_registry.h"
#include "tests/cli_support.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using Cli = test::CliTest;

TEST_F(Cli, ExportThenRenderGivesTheSameHitIds) {
  for (const char* ext : {".obj", ".glb"}) {
    SCOPED_TRACE(ext);
    const std::string file = path(std::string("cows") + ext);
    // No GL context: an EGL that cannot start does not matter.
    const test::RunResult r = run("-s cows --export " + file, "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("cows: 30791 triangles written to " + file), std::string::npos) << r.out;
    // The exported file renders hits that brute force over the original
    // scene's triangles confirms, with the original's ids.
    const Scene original = loadScene("cows");
    const Scene exported = loadScene(file);
    Scene view = original;
    view.camera = exported.camera;  // the export holds no view: the file's framing
    ASSERT_EQ(run("-s " + file + " -r 1 -b 1 -w 32 --hits " + path("h.exr")).status, 0);
    test::expectHitsMatchBruteForce(path("h.exr"), view, 32);
  }
}

TEST_F(Cli, ExportErrorsWriteNothing) {
  expectOneLineError(run("-s cornell --export " + path("x.ply")), "x.ply: unknown format");
  expectOneLineError(run("-s cornell --export " + path("x.obj") + " -o " + path("x.png")), "--export");
  expectOneLineError(run("-s cornell --export " + path("nowhere/x.obj")), "x.obj: directory");
  expectOneLineError(run("-s " + path("missing.obj") + " --export " + path("x.obj")), "missing.obj");
}

}  // namespace
}  // namespace passtrace
