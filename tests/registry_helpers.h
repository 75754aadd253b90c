#pragma once
// Tests name structures as the command line does: by the thesis number in a
// renderer's column, or by name (accel/registry.h).

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <memory>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "accel/registry.h"

namespace passtrace::testing_registry {

// A row's name as a gtest case name ("kd-stack" -> "kd_stack").
inline std::string caseName(std::string_view name) {
  std::string s(name);
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

// For INSTANTIATE_TEST_SUITE_P over row names.
struct CaseNameOfRow {
  template <class Info>
  std::string operator()(const Info& info) const { return caseName(info.param); }
};

// The names of the rows that run on `renderer` (every row for nullopt).
inline std::vector<std::string> rowNames(std::optional<RendererId> renderer = std::nullopt) {
  std::vector<std::string> names;
  for (const Structure& s : structures())
    if (!renderer || s.runsOn(*renderer)) names.emplace_back(s.name);
  return names;
}

inline const Structure& cpuRow(int number) { return resolveStructure(std::to_string(number), RendererId::Cpu); }
inline std::string cpuName(int number) { return std::string(cpuRow(number).name); }
inline std::unique_ptr<CpuAccelerator> cpuStructure(int number, std::span<const Triangle> tris,
                                                    const AccelBuildConfig& config = {}) {
  return makeCpuStructure(cpuRow(number), tris, config);
}

}  // namespace passtrace::testing_registry

namespace passtrace::testing_registry {

// Every structure on every ray tracer, as (renderer id, "-a" argument and its
// variant flags): the GPU rows that read --grid-kernels once per kernel set,
// the rows that read --stack-size also with 1 and 8 entries (4 is the default).
inline std::vector<std::pair<int, std::string>> everyStructureRun() {
  std::vector<std::pair<int, std::string>> runs;
  for (RendererId r : {RendererId::Gpu, RendererId::Cpu, RendererId::Embree})
    for (const Structure& s : structures()) {
      if (!s.runsOn(r)) continue;
      runs.emplace_back(int(r), std::string(s.name));
      const auto reads = s.readsOn(r);
      if (std::find(reads.begin(), reads.end(), BuildParam::GridKernels) != reads.end())
        runs.emplace_back(int(r), std::string(s.name) + " --grid-kernels split");
      if (std::find(reads.begin(), reads.end(), BuildParam::KdStackSize) != reads.end())
        for (const char* k : {"1", "8"}) runs.emplace_back(int(r), std::string(s.name) + " --stack-size " + k);
      // DACRT: its conic packets, and its recursion at rLimit = pLimit = 1.
      if (std::find(reads.begin(), reads.end(), BuildParam::DacrtCones) != reads.end())
        runs.emplace_back(int(r), std::string(s.name) + " --dacrt-cones");
      if (std::find(reads.begin(), reads.end(), BuildParam::DacrtRLimit) != reads.end()) {
        runs.emplace_back(int(r), std::string(s.name) + " --dacrt-rlimit 1 --dacrt-plimit 1");
        runs.emplace_back(int(r), std::string(s.name) + " --dacrt-cones --dacrt-rlimit 1 --dacrt-plimit 1");
      }
      // The stack BVH's non-default builders (sah is the default run above).
      if (std::find(reads.begin(), reads.end(), BuildParam::BvhBuilder) != reads.end())
        for (const char* b : {"sbvh", "middle"}) runs.emplace_back(int(r), std::string(s.name) + " --bvh-builder " + b);
      // bvh8's spatial-split build (binned is the default run above).
      if (std::find(reads.begin(), reads.end(), BuildParam::Bvh8Builder) != reads.end())
        runs.emplace_back(int(r), std::string(s.name) + " --bvh8-builder sbvh");
    }
  return runs;
}

// Whether an everyStructureRun entry stands for its family on its renderer in
// the long BART matrix: the family's first row there, without variant flags.
// The rest of the family shares its builder, its texel layout and most of its
// traversal, and runs on the Cornell box and the bunny anyway; the whole
// matrix runs with PASSTRACE_FULL_MATRIX=1 (docs/testing.md).
inline bool representsItsFamily(const std::pair<int, std::string>& run) {
  if (run.second.find(' ') != std::string::npos) return false;
  const RendererId renderer = RendererId(run.first);
  for (const Structure& s : structures()) {
    if (!s.runsOn(renderer)) continue;
    if (s.family == resolveStructure(run.second, renderer).family) return s.name == run.second;
  }
  return false;
}

// The runs of `runs` whose structure (the name before any flags) is the first
// one listed for their renderer, with all of that structure's variants.
inline std::vector<std::pair<int, std::string>> firstStructurePerRenderer(
    const std::vector<std::pair<int, std::string>>& runs) {
  const auto structureOf = [](const std::string& run) { return run.substr(0, run.find(' ')); };
  std::map<int, std::string> first;
  std::vector<std::pair<int, std::string>> kept;
  for (const auto& [renderer, run] : runs) {
    const std::string& structure = first.try_emplace(renderer, structureOf(run)).first->second;
    if (structureOf(run) == structure) kept.emplace_back(renderer, run);
  }
  return kept;
}

inline bool fullMatrix() {
  const char* full = std::getenv("PASSTRACE_FULL_MATRIX");
  return full && std::string_view(full) == "1";
}

// A test name for an everyStructureRun entry: "r2_kd_shortstack_stack_size_1"
// for (2, "kd-shortstack --stack-size 1").
inline std::string runName(const std::pair<int, std::string>& run) {
  std::string name = "r" + std::to_string(run.first) + "_";
  for (const char c : run.second)
    if (std::isalnum(static_cast<unsigned char>(c)))
      name += c;
    else if (name.back() != '_')
      name += '_';
  return name;
}

// The loop limits (-l) a command-line test runs `run` (an everyStructureRun
// entry) with: 3 and 64 for every GPU row, whose state (stacks included) must
// survive a pass ending anywhere; on the CPU only the default (empty flag).
inline std::vector<std::string> loopLimitFlags(const std::pair<int, std::string>& run) {
  if (run.first == int(RendererId::Gpu))
    return {" -l 3", " -l 64"};
  return {""};
}

}  // namespace passtrace::testing_registry

namespace passtrace::testing_registry {

// The rows that read --kd-builder on the CPU and GPU ray tracers, as
// (renderer id, "-a" argument with "--kd-builder binned" and the termination).
inline std::vector<std::pair<int, std::string>> kdBinnedRuns() {
  std::vector<std::pair<int, std::string>> runs;
  for (RendererId r : {RendererId::Gpu, RendererId::Cpu})
    for (const Structure& s : structures()) {
      const auto reads = s.readsOn(r);
      if (std::find(reads.begin(), reads.end(), BuildParam::KdBuilder) == reads.end()) continue;
      for (const char* rule : {"thesis", "papay"})
        runs.emplace_back(int(r), std::string(s.name) + " --kd-builder binned --kd-termination " + rule);
    }
  return runs;
}

}  // namespace passtrace::testing_registry
