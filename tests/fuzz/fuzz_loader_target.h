#pragma once
// The body every loader fuzz target shares: load the file; a SceneError with
// a proper one-line message is an accepted outcome, and so is a scene that
// keeps Scene's promises. Anything else aborts, which libFuzzer reports as a
// crash with the input saved: a sanitizer report, an exception of another
// type (it escapes), a broken scene or a malformed message.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "scenes/scene_error.h"
#include "tests/fuzz/scene_invariants.h"

namespace passtrace::fuzz {

template <class Load>
void requireCleanOutcome(const std::filesystem::path& path, Load&& load) {
  std::string problem;
  try {
    problem = sceneProblem(load(path));
  } catch (const SceneError& e) {
    problem = errorProblem(e.what(), path.string());
    if (!problem.empty()) problem += ": " + std::string(e.what());
  }
  if (!problem.empty()) {
    std::fprintf(stderr, "passtrace fuzz: %s\n", problem.c_str());
    std::abort();
  }
}

}  // namespace passtrace::fuzz
